//! FMI 2.0 co-simulation FMUs of stljit programs.
//!
//! An FMU made by `stljit fmu` is a zip archive holding
//!
//! * `modelDescription.xml` ([`model_description`]): the variables, their value references,
//!   causality (inputs from the program's I/AI, Omron CIO 0–1; outputs from Q/AQ, Omron CIO
//!   100–101; chosen internal variables as locals), variability, types and start values;
//! * `binaries/<platform>/<modelIdentifier>.<so|dylib|dll>`: the FMI runtime
//!   (`stljit-fmu-runtime`), one generic library with the stljit front ends, runtime and JIT;
//! * `resources/`: the program's files, its symbol table and [`manifest`]'s `stljit.txt`, from
//!   which the runtime compiles the program at `fmi2Instantiate`.
//!
//! [`variables`] decides the variable list once; the manifest carries it to the runtime, so the
//! description and the runtime cannot disagree on a value reference. [`package`] writes the
//! archive.

pub mod manifest;
pub mod model_description;
pub mod package;
pub mod variables;

pub use manifest::{Manifest, ManifestError};
pub use package::{ExportError, ExportOptions, export};
pub use variables::{Causality, FmiType, Variable, variables};
