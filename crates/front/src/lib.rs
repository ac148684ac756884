//! The front ends side by side (as naga's `front/{wgsl,glsl,spv}`): one [`Dialect`] switch that
//! compiles a project of any dialect to the dialect-neutral IR ([`Dialect::compile`]), reads
//! the addresses that stimulus files and watch lists name ([`Dialect::parse_address`]) and prints
//! a program in the dialect's own text ([`Dialect::print_program`]).
//!
//! Everything dialect-neutral about sources and diagnostics lives in `stljit-source` and is
//! re-exported here; each dialect is its own crate (`stljit-front-s7`). Adding a dialect adds a
//! variant to [`Dialect`] and to [`Symbols`], and one arm in each `match` of this file.

use stljit_core::ProfileId;
use stljit_core::ir::{Address, Program};

pub use stljit_source::{
    Code, Diagnostic, Encoding, Severity, SourceFile, SourceText, Sources, render_human,
    render_json,
};

/// A program-text dialect stljit reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Dialect {
    /// S7-200-style STL as used by the A5 series: plain text and MicroWIN `.awl` exports.
    S7,
}

/// A dialect's symbol table, as the compilation read it.
#[derive(Clone, Debug)]
pub enum Symbols {
    /// A MicroWIN symbol table.
    S7(stljit_front_s7::SymbolTable),
}

impl Symbols {
    /// Every symbol name, in no particular order.
    pub fn names(&self) -> Box<dyn Iterator<Item = &str> + '_> {
        match self {
            Symbols::S7(t) => Box::new(t.names()),
        }
    }
}

/// What compiling a project produced: the program (when there is no error), every diagnostic,
/// the decoded sources for rendering, and the symbol table.
pub type Compilation = stljit_source::Compilation<Symbols>;

/// Why an address named outside a program (stimulus, watch list) was rejected.
pub use stljit_front_s7::AddressError;

impl Dialect {
    /// Every dialect.
    pub const ALL: &'static [Dialect] = &[Dialect::S7];

    /// The name on the command line (`--dialect s7`).
    pub fn name(self) -> &'static str {
        match self {
            Dialect::S7 => "s7",
        }
    }

    /// The dialect called `name`.
    pub fn from_name(name: &str) -> Option<Dialect> {
        Dialect::ALL.iter().copied().find(|d| d.name() == name)
    }

    /// The CPU profile a program of this dialect is checked against unless one is chosen.
    pub fn default_profile(self) -> ProfileId {
        match self {
            Dialect::S7 => ProfileId::A5,
        }
    }

    /// The CPU profiles of this dialect.
    pub fn profiles(self) -> &'static [ProfileId] {
        match self {
            Dialect::S7 => &ProfileId::ALL,
        }
    }

    /// Compiles a project: every file in `files` (together one program) and the optional symbol
    /// table, against `profile`. Never panics; every diagnostic of every file is reported.
    pub fn compile(
        self,
        files: &[SourceFile],
        symbols: Option<&SourceFile>,
        profile: ProfileId,
    ) -> Compilation {
        match self {
            Dialect::S7 => {
                stljit_front_s7::compile(files, symbols, profile).map_symbols(Symbols::S7)
            }
        }
    }

    /// Parses one address (or a symbol of `symbols`) as this dialect writes it.
    pub fn parse_address(
        self,
        text: &str,
        profile: ProfileId,
        symbols: Option<&Symbols>,
    ) -> Result<Address, AddressError> {
        match self {
            Dialect::S7 => {
                let table = symbols.map(|Symbols::S7(t)| t);
                stljit_front_s7::parse_address(text, profile.profile(), table)
            }
        }
    }

    /// An address in this dialect's spelling (the inverse of [`Dialect::parse_address`]).
    pub fn print_address(self, address: &Address) -> String {
        match self {
            Dialect::S7 => stljit_front_s7::print_address(address),
        }
    }

    /// The program as text of this dialect that compiles back to the same IR.
    pub fn print_program(self, program: &Program) -> String {
        match self {
            Dialect::S7 => stljit_front_s7::print_program(program),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_s7_is_one_of_them() {
        for &d in Dialect::ALL {
            assert_eq!(Dialect::from_name(d.name()), Some(d));
            assert!(d.profiles().contains(&d.default_profile()));
        }
        assert_eq!(Dialect::from_name("s7"), Some(Dialect::S7));
        assert_eq!(Dialect::from_name("omron"), None);
    }

    #[test]
    fn compile_and_addresses_dispatch_to_the_dialect() {
        let file = SourceFile {
            name: "t.stl".into(),
            bytes: b"LD I0.0\n= Q0.1\n".to_vec(),
        };
        let c = Dialect::S7.compile(&[file], None, ProfileId::A5);
        assert_eq!(c.error_count(), 0);
        let p = c.program.expect("compiles");
        assert_eq!(p.op_count(), 2);
        let a = Dialect::S7
            .parse_address("Q0.1", ProfileId::A5, c.symbols.as_ref())
            .expect("an address");
        assert_eq!(Dialect::S7.print_address(&a), "Q0.1");
        assert!(Dialect::S7.print_program(&p).contains("Q0.1"));
        assert!(
            Dialect::S7
                .parse_address("Q99.0", ProfileId::A5, None)
                .is_err()
        );
    }
}
