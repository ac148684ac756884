//! Interpreter unit tests: IR built directly with the small helpers of [`build`], expected values
//! from the spec (each test names its section).

mod build;
mod control;
mod ops;
