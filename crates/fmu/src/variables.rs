//! The FMU's variables: which addresses become inputs, outputs and locals, their names, FMI
//! types and value references.
//!
//! * **Inputs**: every I bit and every I/AI value (Omron: CIO 0–1 bits and words) the program
//!   reads, from its instructions' operands ([`stljit_api::used::process_io`]).
//! * **Outputs**: every Q bit and Q/AQ value (Omron: CIO 100–101) the program writes.
//! * **Locals**: the names chosen with `stljit fmu --local` (any address or symbol, with a type
//!   suffix such as `VD100:real`).
//!
//! A variable is named by its symbol where the table has one, else by its address in the
//! dialect's spelling (`Q0.0`, `AIW0`, `100.01`); a local by the name as given. Bits are
//! `Boolean`, integers `Integer` (a 32-bit `fmi2Integer`; an unsigned dword is passed as its
//! two's-complement bits), `:real` dwords `Real`. Value references are 1, 2, 3, ... in the order
//! inputs, outputs, locals, each in address order.

use stljit_api::{Compiled, Error, Handle, Plc, Type};

/// An FMI causality.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Causality {
    /// Set by the master before a step.
    Input,
    /// Computed by the PLC.
    Output,
    /// Internal, observable.
    Local,
}

impl Causality {
    /// The modelDescription spelling.
    pub fn name(self) -> &'static str {
        match self {
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Local => "local",
        }
    }

    /// The causality called `name`.
    pub fn from_name(name: &str) -> Option<Causality> {
        [Causality::Input, Causality::Output, Causality::Local]
            .into_iter()
            .find(|c| c.name() == name)
    }
}

/// An FMI variable type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FmiType {
    /// `fmi2Real` (a `:real` dword).
    Real,
    /// `fmi2Integer` (bytes, words, dwords).
    Integer,
    /// `fmi2Boolean` (bits).
    Boolean,
}

impl FmiType {
    /// The modelDescription element name.
    pub fn name(self) -> &'static str {
        match self {
            FmiType::Real => "Real",
            FmiType::Integer => "Integer",
            FmiType::Boolean => "Boolean",
        }
    }

    /// The type called `name`.
    pub fn from_name(name: &str) -> Option<FmiType> {
        [FmiType::Real, FmiType::Integer, FmiType::Boolean]
            .into_iter()
            .find(|t| t.name() == name)
    }

    /// The FMI type of a handle's values.
    pub fn of(ty: Type) -> FmiType {
        match ty {
            Type::Bool => FmiType::Boolean,
            Type::Real => FmiType::Real,
            _ => FmiType::Integer,
        }
    }
}

/// One variable of the FMU.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Variable {
    /// The value reference.
    pub vr: u32,
    /// The FMI name.
    pub name: String,
    /// What the runtime resolves (`Q0.0`, `AIW0`, `VD100:real`): an address or symbol with
    /// its type suffix.
    pub spec: String,
    /// Input, output or local.
    pub causality: Causality,
    /// Real, Integer or Boolean.
    pub ty: FmiType,
    /// The address, and the symbol's address for a symbol (`Q0.0`, `Car_Red (Q0.0)`).
    pub description: String,
    /// The integer range the handle holds (`(0, 1)` for a bit).
    pub range: (i64, i64),
}

/// The variables of `compiled`'s program with `locals` (names as `--local` takes them).
pub fn variables(
    compiled: &std::sync::Arc<Compiled>,
    locals: &[String],
) -> Result<Vec<Variable>, Error> {
    // A throwaway interpreter-backed PLC resolves names exactly as the runtime will.
    let options = stljit_api::Options {
        engine: stljit_api::EngineKind::Interp,
        ..stljit_api::Options::default()
    };
    let plc = Plc::new(compiled.clone(), &options)?;
    let io = stljit_api::used::process_io(plc.program());
    let names = compiled.names();
    let mut out: Vec<Variable> = Vec::new();
    let mut push = |name: String, spec: String, causality, h: &Handle, description: String| {
        if out.iter().any(|v| v.name == name) {
            return;
        }
        out.push(Variable {
            vr: out.len() as u32 + 1,
            name,
            spec,
            causality,
            ty: FmiType::of(h.ty()),
            description,
            range: h.ty().read_range(),
        });
    };
    for (list, causality) in [
        (&io.inputs, Causality::Input),
        (&io.outputs, Causality::Output),
    ] {
        for a in list {
            let plain = names.plain(a);
            let h = plc.handle(&plain)?;
            let name = names.watch_name(a);
            push(name, plain, causality, &h, names.name(a));
        }
    }
    for spec in locals {
        let spec = spec.trim();
        let h = plc.handle(spec)?;
        let description = names.name(h.address());
        push(
            spec.to_string(),
            spec.to_string(),
            Causality::Local,
            &h,
            description,
        );
    }
    Ok(out)
}
