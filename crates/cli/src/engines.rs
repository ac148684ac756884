//! Choosing an engine from command-line options (`stljit_api` builds it).

use stljit_jit::OptLevel;

/// `--engine`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum EngineKind {
    /// Cranelift native code.
    Jit,
    /// The reference interpreter.
    Interp,
}

impl EngineKind {
    pub(crate) fn name(self) -> &'static str {
        match self {
            EngineKind::Jit => "jit",
            EngineKind::Interp => "interp",
        }
    }
}

/// `--opt`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum OptArg {
    /// Fastest compile.
    None,
    /// Fastest code.
    Speed,
}

impl From<OptArg> for OptLevel {
    fn from(o: OptArg) -> OptLevel {
        match o {
            OptArg::None => OptLevel::None,
            OptArg::Speed => OptLevel::Speed,
        }
    }
}

impl From<EngineKind> for stljit_api::EngineKind {
    fn from(k: EngineKind) -> stljit_api::EngineKind {
        match k {
            EngineKind::Jit => stljit_api::EngineKind::Jit,
            EngineKind::Interp => stljit_api::EngineKind::Interp,
        }
    }
}
