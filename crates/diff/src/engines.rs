//! The engines under test, built fresh for every program: the reference interpreter and the
//! Cranelift JIT at either optimisation level.

use std::fmt;
use stljit_core::ir::Program;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};
use stljit_runtime::Engine;

/// Which engine.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EngineKind {
    /// `stljit_interp::Interpreter`.
    Interp,
    /// `stljit_jit::JitProgram` at an optimisation level.
    Jit(OptLevel),
}

impl EngineKind {
    /// Name for reports.
    pub fn name(self) -> &'static str {
        match self {
            EngineKind::Interp => "interp",
            EngineKind::Jit(OptLevel::None) => "jit(none)",
            EngineKind::Jit(OptLevel::Speed) => "jit(speed)",
        }
    }

    /// Builds the engine for `program`.
    pub fn build(self, program: &Program) -> Result<Box<dyn Engine>, BuildError> {
        match self {
            EngineKind::Interp => Interpreter::new(program)
                .map(|i| Box::new(i) as Box<dyn Engine>)
                .map_err(|e| BuildError {
                    engine: self.name(),
                    message: e.to_string(),
                }),
            EngineKind::Jit(opt) => JitProgram::compile(program, &JitOptions { opt })
                .map(|j| Box::new(j) as Box<dyn Engine>)
                .map_err(|e| BuildError {
                    engine: self.name(),
                    message: e.to_string(),
                }),
        }
    }
}

impl fmt::Display for EngineKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An engine refused a program.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BuildError {
    /// The engine.
    pub engine: &'static str,
    /// Its error, displayed.
    pub message: String,
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} could not be built: {}", self.engine, self.message)
    }
}

impl std::error::Error for BuildError {}
