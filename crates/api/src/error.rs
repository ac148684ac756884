//! [`Error`]: everything that can go wrong in the embedding API, one variant per cause, each
//! naming the place (file, address, value) and the reason. Nothing in this crate panics on bad
//! input; every public operation that can fail returns `Result<_, Error>`.

use std::fmt;
use std::path::PathBuf;
use stljit_sim::SimError;

/// Why an operation of the embedding API failed.
#[derive(Debug)]
pub enum Error {
    /// A program or symbol file could not be read.
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// No program file was given.
    NoSources,
    /// `dialect` does not name a dialect (`s7`, `omron`).
    UnknownDialect {
        /// The name as given.
        name: String,
    },
    /// `cpu` does not name a profile of the dialect.
    UnknownCpu {
        /// The name as given.
        name: String,
        /// The dialect's profiles, for the message.
        known: Vec<&'static str>,
    },
    /// The dialect of a file could not be told from its content, or two files disagree.
    Dialect {
        /// What went wrong, naming the file.
        message: String,
    },
    /// The program has errors; `rendered` is every diagnostic as `stljit check` prints it.
    Compile {
        /// Number of error diagnostics.
        errors: usize,
        /// The diagnostics rendered rustc-style (file:line:col, code, source line, caret).
        rendered: String,
    },
    /// The engine could not be built (the JIT rejected the host or the program).
    Engine {
        /// The engine's reason.
        message: String,
    },
    /// The scan time is 0 ms.
    ZeroScanTime,
    /// A duration (scan time, run length) that is not one (`10ms`, `1.5s`, `2m`, `24h`).
    Duration {
        /// The parser's message, naming the text.
        message: String,
    },
    /// A name is neither an address of the program's dialect and profile nor a symbol.
    Address {
        /// The name as written.
        name: String,
        /// The dialect's reason.
        reason: String,
    },
    /// The address may not be written or forced from outside (SMB0, HC, L, ...).
    NotWritable {
        /// The name as written.
        name: String,
        /// Why.
        reason: &'static str,
    },
    /// A value does not fit the address (a 2 for a bit, 70000 for a word, a real for a word).
    Value {
        /// The name as written.
        name: String,
        /// Why.
        reason: String,
    },
    /// A handle or a snapshot belongs to another program or profile.
    Foreign {
        /// What was passed (`handle VW10`, `snapshot`).
        what: String,
    },
    /// A serialized snapshot is truncated or not a snapshot at all.
    Snapshot {
        /// Why it was rejected.
        reason: &'static str,
    },
    /// A high-speed counter the program's CPU does not have ([`crate::Plc::set_hsc_steps`]).
    NoCounter {
        /// The counter's number as given.
        counter: u8,
        /// The CPU's model (`A5`).
        cpu: &'static str,
        /// The counters it has (`HSC0, HSC1`), or `none`.
        have: String,
    },
    /// A serial port the program's CPU does not have ([`crate::Plc::queue_rx`]).
    NoPort {
        /// The port's number as given.
        port: u8,
        /// The CPU's model (`CP1H`).
        cpu: &'static str,
        /// The ports it has (`PORT0, PORT1`), or `none`.
        have: String,
    },
    /// The simulation could not run (a trace writer failed, a stimulus does not fit).
    Sim(SimError),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io { path, source } => write!(f, "cannot read {}: {source}", path.display()),
            Error::NoSources => f.write_str("no program files"),
            Error::UnknownDialect { name } => {
                write!(f, "unknown dialect `{name}` (known: s7, omron)")
            }
            Error::UnknownCpu { name, known } => {
                write!(f, "unknown cpu `{name}` (known: {})", known.join(", "))
            }
            Error::Dialect { message } => f.write_str(message),
            Error::Compile { errors, rendered } => {
                write!(f, "{rendered}{errors} error(s); nothing was compiled")
            }
            Error::Engine { message } => f.write_str(message),
            Error::ZeroScanTime => f.write_str("scan time must be at least 1 ms"),
            Error::Duration { message } => f.write_str(message),
            Error::Address { name, reason } => write!(f, "`{name}`: {reason}"),
            Error::NotWritable { name, reason } => write!(f, "`{name}` is not writable: {reason}"),
            Error::Value { name, reason } => write!(f, "`{name}`: {reason}"),
            Error::Foreign { what } => {
                write!(f, "{what} belongs to another program or CPU profile")
            }
            Error::Snapshot { reason } => write!(f, "not a stljit snapshot: {reason}"),
            Error::NoCounter { counter, cpu, have } => write!(
                f,
                "the {cpu} has no high-speed counter {counter} (it has: {have})"
            ),
            Error::NoPort { port, cpu, have } => {
                write!(f, "the {cpu} has no serial port {port} (it has: {have})")
            }
            Error::Sim(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        // The messages of `Io` and `Sim` already contain their causes' text; only a simulation
        // error's own cause (a trace writer's I/O error) is passed on, as `SimError` does.
        match self {
            Error::Sim(e) => e.source(),
            _ => None,
        }
    }
}

impl From<SimError> for Error {
    fn from(e: SimError) -> Error {
        Error::Sim(e)
    }
}
