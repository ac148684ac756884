//! Differential fuzzing for stljit: the JIT must equal the reference interpreter, and no input may
//! crash anything.
//!
//! - [`generate`] builds valid random programs ([`generate::Case`]: a [`stljit_core::ir::Program`] and a
//!   [`generate::Stimulus`]) from a seed or from fuzzer bytes ([`rng::Choices`]).
//! - [`oracle`] runs two engines side by side and compares status and the whole image after every
//!   scan; [`locate`] names the differing bytes; [`inject`] breaks an engine on purpose to prove
//!   the oracle sees it.
//! - [`coverage`] counts what was generated.
//! - [`canon`] puts generated IR in the front end's canonical form.

pub mod campaign;
pub mod canon;
pub mod coverage;
pub mod engines;
pub mod generate;
pub mod inject;
pub mod locate;
pub mod oracle;
pub mod repro;
pub mod rng;
pub mod roundtrip;
pub mod shrink;
