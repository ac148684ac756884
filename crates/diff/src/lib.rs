//! Differential fuzzing for stljit: the JIT must equal the reference interpreter, and no input may
//! crash anything.
//!
//! - [`generate`] builds valid random programs ([`generate::Case`]: a [`stljit_core::ir::Program`] and a
//!   [`generate::Stimulus`]) from a seed or from fuzzer bytes ([`rng::Choices`]).
//! - [`coverage`] counts what was generated.
//! - [`canon`] puts generated IR in the front end's canonical form.

pub mod canon;
pub mod coverage;
pub mod generate;
pub mod rng;
