//! The FMI 2.0 co-simulation runtime of stljit FMUs: a C-ABI library exporting the `fmi2…`
//! functions (FMI 2.0 §2.1 and §4.2). `stljit fmu` packs it into every FMU as
//! `binaries/<platform>/<modelIdentifier>.so`; at `fmi2Instantiate` it reads the FMU's
//! `resources/stljit.txt`, compiles the program with the stljit JIT and maps the value
//! references onto the embedding API ([`instance`]).
//!
//! No panic crosses the C boundary: every exported function runs its body under
//! `catch_unwind` and reports a panic as `fmi2Fatal` through the master's logger.

#![allow(unsafe_code)] // the exported C functions, and nothing else (see `exports`)

pub mod exports;
pub mod instance;
pub mod types;

pub use instance::{FmuState, Instance, Problem, State, resource_dir};
