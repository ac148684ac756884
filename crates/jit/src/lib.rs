//! The Cranelift JIT engine of stljit.
//!
//! [`JitProgram::compile`] turns a checked [`stljit_core::ir::Program`] into native code: one
//! function per POU (`fn(image, depth) -> status`, see [`lower`]) plus an entry that runs many
//! scans in one call. [`JitProgram`] implements [`stljit_runtime::Engine`], so it is driven
//! exactly like the interpreter, and must leave the same image bytes after every scan.
//! [`clif_text`] prints the annotated Cranelift IR for `stljit dump-clif`.
//!
//! Semantics with intricate rules (timers, counters, pointer resolution, multiplication and
//! division, reals, shifts, conversions) are the runtime's code, called through its `extern "C"`
//! shims or the value shim in [`helpers`]; bit logic, moves, compares, integer add/sub and word
//! logic are inlined. The only `unsafe` is in [`engine`], which enters the compiled code.

mod analysis;
mod build;
mod clif;
mod dse;
mod engine;
mod helpers;
mod lower;
mod midend;
mod rebase;
mod resident;
mod scan_loop;
#[cfg(test)]
mod test_fn;

pub use clif::{asm_text, clif_text, optimized_clif_text};
pub use engine::JitProgram;

use std::fmt;

/// Code-generation effort.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum OptLevel {
    /// No optimisation passes: fastest compile.
    #[default]
    None,
    /// Cranelift's `speed` level (e-graph rewrites, better register allocation).
    Speed,
}

impl OptLevel {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            OptLevel::None => "none",
            OptLevel::Speed => "speed",
        }
    }

    /// Parses a command-line name (`none`, `speed`).
    pub fn from_name(s: &str) -> Option<OptLevel> {
        match s {
            "none" => Some(OptLevel::None),
            "speed" => Some(OptLevel::Speed),
            _ => None,
        }
    }
}

/// Options of [`JitProgram::compile`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct JitOptions {
    /// Cranelift optimisation level.
    pub opt: OptLevel,
    /// A POU longer than this many ops is compiled as several chunk functions (0: never split).
    /// The result is the same either way; the split only bounds the size of each Cranelift
    /// function, whose compile time grows faster than linearly.
    pub chunk_ops: usize,
    /// How many ops after a store a bit test keeps reading single bytes instead of a 32-bit
    /// load that covers the stored byte (see `docs/performance.md`, "wide loads"). Only speed
    /// depends on it; 0 makes almost every bit test and bit write take the wide path, which
    /// the differential tests use to cover it with short programs.
    pub hot_ops: usize,
}

/// The default [`JitOptions::chunk_ops`].
pub const DEFAULT_CHUNK_OPS: usize = 2048;

/// The default [`JitOptions::hot_ops`]: on the Zen 3 development machine 64 ops (about 200
/// instructions) left no more store-to-load interlocks than byte-only code; 32 left ~930 per
/// `bitlogic_10k` scan, 16 ~1,700.
pub const DEFAULT_HOT_OPS: usize = 64;

impl Default for JitOptions {
    fn default() -> Self {
        JitOptions {
            opt: OptLevel::None,
            chunk_ops: DEFAULT_CHUNK_OPS,
            hot_ops: DEFAULT_HOT_OPS,
        }
    }
}

impl JitOptions {
    /// The default options at optimisation level `opt`.
    pub fn at(opt: OptLevel) -> Self {
        JitOptions {
            opt,
            ..Self::default()
        }
    }
}

/// Why a program could not be compiled.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum JitError {
    /// The host CPU is not supported by Cranelift.
    UnsupportedHost(String),
    /// Cranelift rejected a setting or the generated code (a bug in this crate).
    Codegen(String),
    /// The program breaks a rule of the IR verifier; a front end never produces such a program.
    Malformed(stljit_core::ir::VerifyError),
    /// The program uses an instruction this engine does not compile yet.
    Unsupported(String),
}

impl fmt::Display for JitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            JitError::UnsupportedHost(m) => write!(f, "host not supported by the JIT: {m}"),
            JitError::Codegen(m) => write!(f, "JIT code generation failed: {m}"),
            JitError::Malformed(m) => write!(f, "malformed program: {m}"),
            JitError::Unsupported(m) => write!(f, "not supported by the JIT yet: {m}"),
        }
    }
}

impl std::error::Error for JitError {}
