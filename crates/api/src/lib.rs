//! The stljit embedding API: compile a PLC program of either dialect (S7-200/A5 STL, Omron CP
//! mnemonics) with its CPU profile and symbol table into a [`Plc`], on the JIT or the reference
//! interpreter, and drive it from another simulation tool — a plant model, a co-simulation
//! master, a test — scan by scan on deterministic virtual time.
//!
//! * [`Project`] — files, symbols, dialect (named or detected), CPU; [`Project::compile`].
//! * [`Plc`] — read and write any address or symbol by name ([`Plc::read`], [`Plc::write`]) or
//!   through a pre-resolved [`Handle`] ([`Plc::get`], [`Plc::set`]); run one scan, `n` scans or a
//!   span of virtual time ([`Plc::scan`], [`Plc::run`], [`Plc::run_for`], [`Plc::run_until`]);
//!   the time and scan number ([`Plc::time_ms`], [`Plc::scan_no`]); the simulated hardware's
//!   stimulus (high-speed counter steps [`Plc::set_hsc_steps`], bytes received on a serial port
//!   [`Plc::queue_rx`]); [`Plc::snapshot`] and
//!   [`Plc::restore`] of the whole state; forcing ([`Plc::force`], [`Plc::unforce`]; where in
//!   the scan: [`force`]); an observer per scan ([`Plc::set_observer`], [`Plc::run_observed`]);
//!   stimulus files, cancel flags and progress ([`Plc::simulate`]).
//! * [`Recorder`] — an observer that records handles into preallocated columns (traces).
//! * [`used`] — the process I/O a program uses (an FMU's inputs and outputs) and names for
//!   addresses.
//!
//! Every error is an [`Error`] naming the place and the cause; nothing here panics on bad input,
//! reads a clock or the environment. The `stljit` CLI's `run`, the Python package and the FMU
//! are built on this crate.
//!
//! # Example
//!
//! A start button that must be held for 5 s (a TON with 100 ms resolution) before the motor
//! runs:
//!
//! ```
//! use stljit_api::{Options, Plc, Project, Value};
//!
//! let project = Project::new().text(
//!     "motor.stl",
//!     "NETWORK 1\nLD I0.0\nTON T37, 50\nNETWORK 2\nLD T37\n= Q0.0\n",
//! );
//! let mut plc = Plc::compile(&project, &Options::default())?;
//! let (start, motor) = (plc.handle("I0.0")?, plc.handle("Q0.0")?);
//!
//! plc.set(&start, true)?;
//! plc.run_for(4_990)?; // scans at 0, 10, …, 4980 ms
//! assert_eq!(plc.get(&motor)?, Value::Bool(false));
//! plc.scan()?; // the scan at 4990 ms: T37 has counted 4.99 s, not yet 5 s
//! plc.scan()?; // 5000 ms
//! assert_eq!(plc.get(&motor)?, Value::Bool(true));
//! assert_eq!(plc.time_ms(), 5_010);
//!
//! // What if the button is released now? Branch the run from a snapshot.
//! let saved = plc.snapshot();
//! plc.set(&start, false)?;
//! plc.scan()?;
//! assert_eq!(plc.get(&motor)?, Value::Bool(false));
//! plc.restore(&saved)?;
//! plc.scan()?;
//! assert_eq!(plc.get(&motor)?, Value::Bool(true));
//!
//! // Force the motor off whatever the program writes.
//! plc.force(&motor, false)?;
//! plc.run_for(1_000)?;
//! assert_eq!(plc.get(&motor)?, Value::Bool(false));
//! # Ok::<(), stljit_api::Error>(())
//! ```

pub mod duration;
mod error;
pub mod force;
mod handle;
mod plc;
mod project;
mod recorder;
mod snapshot;
pub mod used;

pub use error::Error;
pub use handle::{Handle, Type, Value};
pub use plc::{EngineKind, Options, Plc, Run, build_engine};
pub use project::{
    Compiled, DetectError, Project, detect_dialect, dialect_named, read_source, resolve_cpu,
};
pub use recorder::Recorder;
pub use snapshot::{Snapshot, fnv1a as fingerprint};

pub use stljit_core::ScanStatus;
pub use stljit_front::{Dialect, SourceFile};
pub use stljit_jit::OptLevel;
pub use stljit_runtime::rtc::DateTime;
pub use stljit_sim::{
    FnObserver, Observer, Outcome, Progress, RunReport, ScanEvent, Stimulus, Until,
};

impl From<bool> for Value {
    fn from(b: bool) -> Value {
        Value::Bool(b)
    }
}

impl From<i64> for Value {
    fn from(v: i64) -> Value {
        Value::Int(v)
    }
}

impl From<i32> for Value {
    fn from(v: i32) -> Value {
        Value::Int(i64::from(v))
    }
}

impl From<f64> for Value {
    fn from(v: f64) -> Value {
        Value::Real(v)
    }
}
