//! The deterministic simulation tooling of stljit: stimulus in, scans at virtual time, traces out.
//!
//! It drives any engine through the runtime's [`Engine`] trait and reads and writes the runtime's
//! [`Image`]; it needs neither the interpreter nor the JIT, and the runtime does not know it.
//! Nothing here reads a clock or touches the file system: time is `k · scan_ms`, inputs come from
//! a parsed [`Stimulus`], traces go to any `impl Write`. Address names are resolved by a closure
//! the caller supplies (normally `stljit_front_s7::parse_address` for the program's profile), so
//! the simulation does not depend on the front end.
//!
//! * [`stimulus`] — the stimulus CSV (`scan,I0.0,VW100,HSC0,PORT0` or `t_ms,...`).
//! * [`watch`] — watch specs (`VD50:real`) and how values print.
//! * [`trace_csv`], [`trace_vcd`] — trace writers, both [`Observer`]s.
//! * [`driver`] — [`Simulation`]: runs an [`Engine`] scan by scan.
//! * [`value`] — value literals and reading/writing an [`Address`] in an image.
//!
//! [`Engine`]: stljit_runtime::Engine
//! [`Image`]: stljit_runtime::Image

pub mod driver;
pub mod stimulus;
pub mod trace_csv;
pub mod trace_vcd;
pub mod value;
pub mod watch;

#[cfg(test)]
mod test_resolver;

pub use driver::{
    FnObserver, Observer, Outcome, Progress, RunReport, ScanEvent, SimError, Simulation, Until,
};
pub use stimulus::{
    Cell, CellError, Column, Stimulus, StimulusError, StimulusErrorKind, Target, TimeBase,
};
pub use trace_csv::CsvTrace;
pub use trace_vcd::VcdTrace;
pub use value::{
    ValueError, ValueKind, parse_value, read_address, writable, write_address, write_offset,
};
pub use watch::{Format, WatchError, WatchSpec};

use stljit_core::ir::Address;

/// Resolves an address name (`I0.3`, `VW100`, `T37`, a symbol) to an [`Address`]; the error is a
/// human-readable reason. The simulation never parses address syntax itself.
pub type Resolver<'a> = &'a dyn Fn(&str) -> Result<Address, String>;
