//! Choosing and building an engine from command-line options.

use stljit_core::ir::Program;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};
use stljit_runtime::Engine;

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

/// Builds the chosen engine for `program`.
pub(crate) fn build_engine(
    kind: EngineKind,
    opt: OptArg,
    program: &Program,
) -> anyhow::Result<Box<dyn Engine>> {
    Ok(match kind {
        EngineKind::Interp => Box::new(Interpreter::new(program)?),
        EngineKind::Jit => Box::new(JitProgram::compile(program, &JitOptions::at(opt.into()))?),
    })
}
