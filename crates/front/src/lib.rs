//! The front ends side by side (as naga's `front/{wgsl,glsl,spv}`): one [`Dialect`] switch that
//! compiles a project of any dialect to the dialect-neutral IR ([`Dialect::compile`]), reads
//! the addresses that stimulus files and watch lists name ([`Dialect::parse_address`]) and prints
//! a program in the dialect's own text ([`Dialect::print_program`]).
//!
//! Everything dialect-neutral about sources and diagnostics lives in `stljit-source` and is
//! re-exported here; each dialect is its own crate (`stljit-front-s7`, `stljit-front-omron`).
//! [`Dialect::detect`] guesses a text's dialect from the marks only one of them writes. Adding a dialect adds a
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
    /// Omron CP-series mnemonics (CX-Programmer instruction lists), omron-cp.md.
    Omron,
}

/// A dialect's symbol table, as the compilation read it.
#[derive(Clone, Debug)]
pub enum Symbols {
    /// A MicroWIN symbol table.
    S7(stljit_front_s7::SymbolTable),
    /// A CX-Programmer symbol table.
    Omron(stljit_front_omron::SymbolTable),
}

impl Symbols {
    /// Every symbol name, in no particular order.
    pub fn names(&self) -> Box<dyn Iterator<Item = &str> + '_> {
        match self {
            Symbols::S7(t) => Box::new(t.names()),
            Symbols::Omron(t) => Box::new(t.names()),
        }
    }
}

/// What compiling a project produced: the program (when there is no error), every diagnostic,
/// the decoded sources for rendering, and the symbol table.
pub type Compilation = stljit_source::Compilation<Symbols>;

/// Why an address named outside a program (stimulus, watch list) was rejected.
pub use stljit_source::AddressError;

/// The front ends' options; the default is each spec's default behaviour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// The Omron front end's (`tc_mode`, `allow_backward_jumps`); the S7 front end has none.
    pub omron: stljit_front_omron::Options,
}

pub use stljit_front_omron::TcMode;

/// The dialects' profiles (Omron's models are the CP ones).
const OMRON_PROFILES: [ProfileId; 2] = [ProfileId::Cp1h, ProfileId::Cp1e];
const S7_PROFILES: [ProfileId; 3] = [ProfileId::A5, ProfileId::S7_200, ProfileId::Smart];

impl Dialect {
    /// Every dialect.
    pub const ALL: &'static [Dialect] = &[Dialect::S7, Dialect::Omron];

    /// The name on the command line (`--dialect s7`).
    pub fn name(self) -> &'static str {
        match self {
            Dialect::S7 => "s7",
            Dialect::Omron => "omron",
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
            Dialect::Omron => ProfileId::Cp1h,
        }
    }

    /// The CPU profiles of this dialect.
    pub fn profiles(self) -> &'static [ProfileId] {
        match self {
            Dialect::S7 => &S7_PROFILES,
            Dialect::Omron => &OMRON_PROFILES,
        }
    }

    /// The dialect `text` is written in, when the heuristics can tell (`None` when neither or
    /// both dialects' marks dominate).
    pub fn detect(text: &str) -> Option<Dialect> {
        match (
            stljit_front_omron::looks_like_omron(text),
            stljit_front_omron::looks_like_s7(text),
        ) {
            (true, false) => Some(Dialect::Omron),
            (false, true) => Some(Dialect::S7),
            _ => None,
        }
    }

    /// Compiles a project: every file in `files` (together one program) and the optional symbol
    /// table, against `profile`, with the default [`Options`]. Never panics; every diagnostic of
    /// every file is reported.
    pub fn compile(
        self,
        files: &[SourceFile],
        symbols: Option<&SourceFile>,
        profile: ProfileId,
    ) -> Compilation {
        self.compile_with(files, symbols, profile, Options::default())
    }

    /// [`Dialect::compile`] with the front ends' `options` (each dialect reads its own).
    pub fn compile_with(
        self,
        files: &[SourceFile],
        symbols: Option<&SourceFile>,
        profile: ProfileId,
        options: Options,
    ) -> Compilation {
        match self {
            Dialect::S7 => {
                stljit_front_s7::compile(files, symbols, profile).map_symbols(Symbols::S7)
            }
            Dialect::Omron => {
                stljit_front_omron::compile_with(files, symbols, profile, options.omron)
                    .map_symbols(Symbols::Omron)
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
                let table = symbols.and_then(|s| match s {
                    Symbols::S7(t) => Some(t),
                    Symbols::Omron(_) => None,
                });
                stljit_front_s7::parse_address(text, profile.profile(), table)
            }
            Dialect::Omron => {
                let table = symbols.and_then(|s| match s {
                    Symbols::Omron(t) => Some(t),
                    Symbols::S7(_) => None,
                });
                stljit_front_omron::parse_address(text, profile, table)
                    .map_err(|e| AddressError { message: e.message })
            }
        }
    }

    /// An address in this dialect's spelling (the inverse of [`Dialect::parse_address`]).
    pub fn print_address(self, address: &Address) -> String {
        match self {
            Dialect::S7 => stljit_front_s7::print_address(address),
            Dialect::Omron => stljit_front_omron::print_address(address),
        }
    }

    /// The program as text of this dialect that compiles back to the same IR; `None` when the
    /// program is not one this dialect's front end produces (the Omron printer refuses op
    /// sequences no text lowers to; `stljit_front_omron::print_program` says why).
    pub fn print_program(self, program: &Program) -> Option<String> {
        match self {
            Dialect::S7 => Some(stljit_front_s7::print_program(program)),
            Dialect::Omron => stljit_front_omron::print_program(program).ok(),
        }
    }

    /// The options the text of [`Dialect::print_program`] compiles back with (an Omron
    /// program with backward jumps needs `allow_backward_jumps`).
    pub fn printed_options(self, program: &Program) -> Options {
        match self {
            Dialect::S7 => Options::default(),
            Dialect::Omron => Options {
                omron: stljit_front_omron::printed_options(program),
            },
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
        assert_eq!(Dialect::from_name("omron"), Some(Dialect::Omron));
        assert_eq!(Dialect::Omron.default_profile(), ProfileId::Cp1h);
        assert_eq!(
            Dialect::Omron.profiles(),
            [ProfileId::Cp1h, ProfileId::Cp1e]
        );
        assert!(!Dialect::S7.profiles().contains(&ProfileId::Cp1h));
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
        assert!(
            Dialect::S7
                .print_program(&p)
                .is_some_and(|t| t.contains("Q0.1"))
        );
        assert!(
            Dialect::S7
                .parse_address("Q99.0", ProfileId::A5, None)
                .is_err()
        );
    }

    #[test]
    fn omron_compiles_and_spells_its_addresses() {
        let file = SourceFile {
            name: "t.omr".into(),
            bytes: b"LD Start\nOUT 100.01\nEND(001)\n".to_vec(),
        };
        let syms = SourceFile {
            name: "s.txt".into(),
            bytes: b"Start\tBOOL\t0.00\n".to_vec(),
        };
        let c = Dialect::Omron.compile(&[file], Some(&syms), ProfileId::Cp1h);
        assert_eq!(c.error_count(), 0, "{:?}", c.diagnostics);
        let p = c.program.expect("compiles");
        assert_eq!(p.op_count(), 3);
        assert_eq!(c.symbols.as_ref().map(|s| s.names().count()), Some(1));
        let a = Dialect::Omron
            .parse_address("Start", ProfileId::Cp1h, c.symbols.as_ref())
            .expect("a symbol");
        assert_eq!(Dialect::Omron.print_address(&a), "0.00");
        assert!(
            Dialect::Omron
                .parse_address("W600", ProfileId::Cp1h, None)
                .is_err()
        );
        let text = Dialect::Omron.print_program(&p).expect("printable");
        assert!(text.contains("LD         0.00"), "{text}");
        assert_eq!(
            Dialect::Omron.print_program(&Program {
                profile: ProfileId::A5,
                ..p
            }),
            None
        );
    }

    #[test]
    fn detect_tells_the_dialects_apart() {
        let omron = "LD 0.00\nAND LD\nOUT 100.00\nMOV(021) #0001 D0\nEND(001)\n";
        let s7 = "NETWORK 1\nLD I0.0\n= Q0.0\n";
        assert_eq!(Dialect::detect(omron), Some(Dialect::Omron));
        assert_eq!(Dialect::detect(s7), Some(Dialect::S7));
        assert_eq!(Dialect::detect(""), None);
        assert_eq!(Dialect::detect("NOP\n"), None);
    }
}
