//! The engines under test, built fresh for every program: the reference interpreter and the
//! Cranelift JIT at either optimisation level, whole or split into one function per basic block.

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
    /// The JIT with every basic block of every POU in a chunk function of its own
    /// ([`JitOptions::chunk_ops`] = 1) and 32-bit bit tests wherever they are valid
    /// ([`JitOptions::hot_ops`] = 0): generated programs are far shorter than the default
    /// chunk size and store too often for the default heuristic, so this is what puts the
    /// chunk dispatcher and the wide loads under test.
    JitSplit(OptLevel),
}

impl EngineKind {
    /// Name for reports.
    pub fn name(self) -> &'static str {
        match self {
            EngineKind::Interp => "interp",
            EngineKind::Jit(OptLevel::None) => "jit(none)",
            EngineKind::Jit(OptLevel::Speed) => "jit(speed)",
            EngineKind::JitSplit(OptLevel::None) => "jit-split(none)",
            EngineKind::JitSplit(OptLevel::Speed) => "jit-split(speed)",
        }
    }

    /// The same engine with split compilation (the interpreter is unchanged).
    pub fn split(self) -> Self {
        match self {
            EngineKind::Jit(opt) => EngineKind::JitSplit(opt),
            other => other,
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
            EngineKind::Jit(opt) | EngineKind::JitSplit(opt) => {
                let opts = match self {
                    EngineKind::JitSplit(_) => JitOptions {
                        opt,
                        chunk_ops: 1,
                        hot_ops: 0,
                    },
                    _ => JitOptions::at(opt),
                };
                JitProgram::compile(program, &opts)
                    .map(|j| Box::new(j) as Box<dyn Engine>)
                    .map_err(|e| BuildError {
                        engine: self.name(),
                        message: e.to_string(),
                    })
            }
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
