//! The stimulus CSV: which values are driven into the PLC before which scan.
//!
//! ```text
//! scan,I0.0,IB1,AIW0,VW100,HSC0,PORT0      or      t_ms,I0.0,...
//! 0,1,,100,,10,
//! 5,0,16#0F,,-7,,16#4F4B0D
//! ```
//! The first header cell picks the time base: `scan` numbers or `t_ms` (virtual milliseconds; a
//! row applies to the first scan starting at or after that time). A row's values are written
//! before that scan runs and hold until a later row changes them (inputs stay in the physical
//! input copy; other areas are written once, like an HMI write, and the program may overwrite
//! them). An empty cell leaves the value alone. Blank lines and lines starting with `#` are
//! ignored. Every error names the line and column (1-based) of the offending cell; a stimulus
//! with any error is rejected whole, so nothing runs on half a stimulus.
//!
//! Two kinds of header names are reserved (any case; they are not looked up as addresses or
//! symbols), for the S7 CPUs' simulated hardware:
//!
//! * `HSC0` … `HSC5`: high-speed counter `n`'s counting activity per scan interval
//!   (s7-200-more §8.4, §11.2 `hsc_steps`): a signed integer (decimal, `16#` or `2#` for the
//!   32-bit pattern), the signed steps of every interval from the row's scan on, held like an
//!   input until a later row changes it. What a step does depends on the counter's mode (§8.4:
//!   modes 0–2 count in the counter's direction and ignore the sign). Only the counters of the
//!   CPU profile (`stljit_core::hsc`: HSC0/HSC1 on the `a5`, HSC0–HSC5 on the `s7-200`,
//!   HSC0–HSC3 on the `smart`).
//! * `PORT0`, `PORT1`: bytes received on serial port `n` in the interval before the row's scan
//!   (§10.4, §11.2 `rx`; they arrive back to back from the interval's start, one character time
//!   each), written in S7 hex, two digits per byte: `16#4F4B0D` is `O`, `K`, CR. Once per row,
//!   not held: an empty cell receives nothing. Only the ports of the CPU profile
//!   (`stljit_core::comm::ports`: both on every S7 profile, none on Omron). Scan 0 has no interval
//!   before it, so bytes of a row due at scan 0 arrive in the first interval, before scan 1.
//!
//! A run that starts later than scan 0 applies the held values of the rows already past (so it
//! sees the stimulus's state at its start), never their received bytes: bytes are delivered
//! once, in the interval they belong to.

use crate::Resolver;
use crate::value::{ValueError, ValueKind, parse_value, writable};
use std::fmt;
use stljit_core::comm;
use stljit_core::ir::Address;
use stljit_core::{CpuProfile, ProfileId};

/// How a row's time is counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeBase {
    /// Scan numbers (0 is the first scan).
    Scan,
    /// Virtual milliseconds.
    Millis,
}

/// What a column drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// An address: an input into the physical input copy, anything else like an HMI write.
    /// Held.
    Address(Address),
    /// `HSCn`: high-speed counter `n`'s counting steps per scan interval (s7-200-more §8.4).
    /// Held.
    HscSteps(u8),
    /// `PORTn`: the bytes received on serial port `n` before the row's scan (§10.4). Once.
    Receive(u8),
}

impl Target {
    /// Whether a cell's value holds until a later row changes it (everything but received
    /// bytes, which arrive once).
    pub fn is_held(self) -> bool {
        !matches!(self, Target::Receive(_))
    }
}

/// One driven column.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Column {
    /// The name as written in the header.
    pub name: String,
    /// What it drives.
    pub target: Target,
}

/// One cell of a row, of the kind its column's [`Target`] takes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Cell {
    /// An address's raw bits, zero-extended ([`Target::Address`]).
    Value(u32),
    /// Counting steps per scan interval ([`Target::HscSteps`]).
    Steps(i32),
    /// Received bytes, at least one ([`Target::Receive`]).
    Bytes(Vec<u8>),
}

/// One row: when, and the cell per column (`None` = leave alone, receive nothing).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    /// Scan number or ms, per [`TimeBase`].
    pub at: u64,
    /// Source line (1-based) for messages.
    pub line: u32,
    /// One cell per column.
    pub cells: Vec<Option<Cell>>,
}

/// A checked stimulus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stimulus {
    time_base: TimeBase,
    columns: Vec<Column>,
    rows: Vec<Row>,
    profile: ProfileId,
}

/// Why a cell of an `HSCn` or `PORTn` column was rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CellError {
    /// Counting steps that are not a 32-bit integer.
    Steps,
    /// Received bytes not written as `16#` and hex digits.
    BytesSyntax,
    /// `16#` with no digits after it.
    NoBytes,
    /// An odd number of hex digits (each byte is two).
    OddDigits(usize),
    /// A cell of another kind than the column takes (programmatic rows only): what it takes.
    Kind(&'static str),
}

impl fmt::Display for CellError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CellError::Steps => f.write_str(
                "counting steps are an integer (-2147483648…2147483647, or a 32-bit 16#/2# \
                 pattern)",
            ),
            CellError::BytesSyntax => f.write_str(
                "received bytes are written 16# and two hex digits per byte, e.g. 16#4F4B0D",
            ),
            CellError::NoBytes => {
                f.write_str("no bytes after 16# (leave the cell empty to receive nothing)")
            }
            CellError::OddDigits(n) => {
                write!(
                    f,
                    "{n} hex digits: every byte is two (16#4F4B0D is 3 bytes)"
                )
            }
            CellError::Kind(what) => write!(f, "this column takes {what}"),
        }
    }
}

/// A stimulus error at a line and column (1-based).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StimulusError {
    /// Line, 1-based.
    pub line: u32,
    /// Column (in characters), 1-based.
    pub col: u32,
    /// What is wrong.
    pub kind: StimulusErrorKind,
}

/// What is wrong with a stimulus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StimulusErrorKind {
    /// The text has no header line.
    MissingHeader,
    /// The first header cell is neither `scan` nor `t_ms`.
    BadTimeColumn(String),
    /// The resolver did not know the name.
    UnknownAddress {
        /// The name.
        name: String,
        /// The resolver's reason.
        reason: String,
    },
    /// The address may not be driven from outside.
    NotWritable {
        /// The name.
        name: String,
        /// Why.
        reason: &'static str,
    },
    /// An `HSCn` column for a counter the CPU does not have.
    NoCounter {
        /// The name as written.
        name: String,
        /// The CPU's model.
        cpu: &'static str,
        /// The counters it has (`HSC0, HSC1`), or `none`.
        have: String,
    },
    /// A `PORTn` column for a serial port the CPU does not have.
    NoPort {
        /// The name as written.
        name: String,
        /// The CPU's model.
        cpu: &'static str,
        /// The ports it has (`PORT0, PORT1`), or `none`.
        have: String,
    },
    /// The same name (or the same address, counter or port) appears twice in the header.
    DuplicateColumn(String),
    /// A row has more or fewer cells than the header.
    CellCount {
        /// Cells in the header.
        expected: usize,
        /// Cells in the row.
        found: usize,
    },
    /// The time cell is not a non-negative integer.
    BadTime(String),
    /// Times must increase strictly from row to row.
    Unsorted {
        /// This row's time.
        at: u64,
        /// The previous row's time.
        previous: u64,
    },
    /// A cell does not fit its column.
    BadValue {
        /// The column's name.
        column: String,
        /// The cell text.
        text: String,
        /// Why.
        error: ValueError,
    },
    /// A cell of an `HSCn` or `PORTn` column is not steps or bytes.
    BadCell {
        /// The column's name.
        column: String,
        /// The cell text.
        text: String,
        /// Why.
        error: CellError,
    },
}

impl fmt::Display for StimulusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}, column {}: ", self.line, self.col)?;
        match &self.kind {
            StimulusErrorKind::MissingHeader => {
                f.write_str("missing header line (`scan,ADDR,...` or `t_ms,ADDR,...`)")
            }
            StimulusErrorKind::BadTimeColumn(s) => {
                write!(f, "first header cell must be `scan` or `t_ms`, found `{s}`")
            }
            StimulusErrorKind::UnknownAddress { name, reason } => {
                write!(f, "unknown address `{name}`: {reason}")
            }
            StimulusErrorKind::NotWritable { name, reason } => {
                write!(f, "`{name}` cannot be driven: {reason}")
            }
            StimulusErrorKind::NoCounter { name, cpu, have } => write!(
                f,
                "`{name}`: the {cpu} has no such high-speed counter (it has: {have})"
            ),
            StimulusErrorKind::NoPort { name, cpu, have } => {
                write!(
                    f,
                    "`{name}`: the {cpu} has no such serial port (it has: {have})"
                )
            }
            StimulusErrorKind::DuplicateColumn(s) => write!(f, "column `{s}` appears twice"),
            StimulusErrorKind::CellCount { expected, found } => {
                write!(f, "row has {found} cells, the header has {expected}")
            }
            StimulusErrorKind::BadTime(s) => {
                write!(f, "`{s}` is not a time (a non-negative integer)")
            }
            StimulusErrorKind::Unsorted { at, previous } => write!(
                f,
                "time {at} does not come after the previous row's {previous} (rows must be \
                 sorted, each time once)"
            ),
            StimulusErrorKind::BadValue {
                column,
                text,
                error,
            } => write!(f, "bad value `{text}` for `{column}`: {error}"),
            StimulusErrorKind::BadCell {
                column,
                text,
                error,
            } => write!(f, "bad cell `{text}` for `{column}`: {error}"),
        }
    }
}

impl std::error::Error for StimulusError {}

fn err(line: u32, col: u32, kind: StimulusErrorKind) -> StimulusError {
    StimulusError { line, col, kind }
}

/// Splits a line into trimmed cells with the 1-based column where each starts.
fn cells(line: &str) -> Vec<(u32, &str)> {
    let mut out = Vec::new();
    let mut col = 1u32;
    for raw in line.split(',') {
        let lead = raw.len() - raw.trim_start().len();
        let start = col + raw[..lead].chars().count() as u32;
        out.push((start, raw.trim()));
        col += raw.chars().count() as u32 + 1;
    }
    out
}

/// A reserved column name: `HSCn` or `PORTn` (any case), with its number.
#[derive(Clone, Copy)]
enum Reserved {
    Hsc(u32),
    Port(u32),
}

/// The reserved name `name` is, if it is one (`HSC` or `PORT` and decimal digits; a number too
/// large for any counter or port is still reserved, and rejected as absent).
fn reserved(name: &str) -> Option<Reserved> {
    let number = |digits: &str| {
        (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
            .then(|| digits.parse::<u32>().unwrap_or(u32::MAX))
    };
    let upper = name.to_ascii_uppercase();
    if let Some(d) = upper.strip_prefix("HSC") {
        number(d).map(Reserved::Hsc)
    } else if let Some(d) = upper.strip_prefix("PORT") {
        number(d).map(Reserved::Port)
    } else {
        None
    }
}

/// The high-speed counters of `profile` as column names (`HSC0, HSC1`), or `none`.
pub fn hsc_columns(profile: &CpuProfile) -> String {
    list(profile.hsc.iter().map(|c| format!("HSC{}", c.number)))
}

/// The serial ports of `profile` as column names (`PORT0, PORT1`), or `none`.
pub fn port_columns(profile: &CpuProfile) -> String {
    list(
        comm::ports(profile)
            .iter()
            .map(|p| format!("PORT{}", p.port)),
    )
}

fn list(names: impl Iterator<Item = String>) -> String {
    let names: Vec<String> = names.collect();
    if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    }
}

/// Parses a non-empty cell of `column`.
fn parse_cell(text: &str, column: &Column) -> Result<Cell, StimulusErrorKind> {
    let bad_cell = |error| StimulusErrorKind::BadCell {
        column: column.name.clone(),
        text: text.to_string(),
        error,
    };
    match column.target {
        Target::Address(address) => parse_value(text, ValueKind::of(&address))
            .map(Cell::Value)
            .map_err(|error| StimulusErrorKind::BadValue {
                column: column.name.clone(),
                text: text.to_string(),
                error,
            }),
        Target::HscSteps(_) => parse_steps(text).map(Cell::Steps).map_err(bad_cell),
        Target::Receive(_) => parse_bytes(text).map(Cell::Bytes).map_err(bad_cell),
    }
}

/// Checks a programmatic cell against its column: the kind, an address value's range, bytes
/// not empty.
fn check_cell(cell: &Cell, column: &Column) -> Result<(), StimulusErrorKind> {
    let bad_cell = |text: String, error| StimulusErrorKind::BadCell {
        column: column.name.clone(),
        text,
        error,
    };
    match (cell, column.target) {
        (&Cell::Value(v), Target::Address(address)) => {
            let kind = ValueKind::of(&address);
            let limit = match kind {
                ValueKind::Bit => 1,
                ValueKind::Value(w) => w.mask(),
            };
            if v > limit {
                return Err(StimulusErrorKind::BadValue {
                    column: column.name.clone(),
                    text: v.to_string(),
                    error: ValueError::OutOfRange { kind },
                });
            }
            Ok(())
        }
        (Cell::Steps(_), Target::HscSteps(_)) => Ok(()),
        (Cell::Bytes(b), Target::Receive(_)) if b.is_empty() => {
            Err(bad_cell("16#".to_string(), CellError::NoBytes))
        }
        (Cell::Bytes(_), Target::Receive(_)) => Ok(()),
        (other, target) => {
            let what = match target {
                Target::Address(_) => "a value",
                Target::HscSteps(_) => "counting steps",
                Target::Receive(_) => "received bytes",
            };
            Err(bad_cell(format!("{other:?}"), CellError::Kind(what)))
        }
    }
}

/// An `HSCn` cell: a signed 32-bit count in decimal, or `16#`/`2#` digits giving its 32-bit
/// pattern (`16#FFFFFFFF` is -1, as a DINT constant).
pub fn parse_steps(text: &str) -> Result<i32, CellError> {
    let t = text.trim();
    if t.starts_with("16#") || t.starts_with("2#") {
        return parse_value(t, ValueKind::Value(stljit_core::Width::DWord))
            .map(|bits| bits as i32)
            .map_err(|_| CellError::Steps);
    }
    t.parse::<i32>().map_err(|_| CellError::Steps)
}

/// A `PORTn` cell: `16#` and an even number (at least two) of hex digits, one byte per pair.
pub fn parse_bytes(text: &str) -> Result<Vec<u8>, CellError> {
    let digits = text
        .trim()
        .strip_prefix("16#")
        .ok_or(CellError::BytesSyntax)?;
    if digits.is_empty() {
        return Err(CellError::NoBytes);
    }
    if !digits.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Err(CellError::BytesSyntax);
    }
    if digits.len() % 2 != 0 {
        return Err(CellError::OddDigits(digits.len()));
    }
    digits
        .as_bytes()
        .chunks(2)
        .map(|pair| {
            std::str::from_utf8(pair)
                .ok()
                .and_then(|p| u8::from_str_radix(p, 16).ok())
                .ok_or(CellError::BytesSyntax)
        })
        .collect()
}

impl Stimulus {
    /// An empty stimulus (nothing driven): every input stays 0.
    pub fn empty(time_base: TimeBase, profile: &CpuProfile) -> Stimulus {
        Stimulus {
            time_base,
            columns: Vec::new(),
            rows: Vec::new(),
            profile: profile.id,
        }
    }

    /// Parses and checks a stimulus CSV for `profile` (which fixes the read-only SM range, the
    /// high-speed counters and the serial ports).
    pub fn parse(
        text: &str,
        profile: &CpuProfile,
        resolve: Resolver<'_>,
    ) -> Result<Stimulus, StimulusError> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i as u32 + 1, l.trim_end_matches('\r')))
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let Some((hline, header)) = lines.next() else {
            return Err(err(1, 1, StimulusErrorKind::MissingHeader));
        };
        let head = cells(header);
        let (tcol, tname) = head[0];
        let time_base = match tname {
            "scan" => TimeBase::Scan,
            "t_ms" => TimeBase::Millis,
            other => {
                return Err(err(
                    hline,
                    tcol,
                    StimulusErrorKind::BadTimeColumn(other.to_string()),
                ));
            }
        };
        let mut stim = Stimulus::empty(time_base, profile);
        for &(col, name) in &head[1..] {
            stim.add_column(name, resolve)
                .map_err(|kind| err(hline, col, kind))?;
        }
        for (line, text) in lines {
            let row = cells(text);
            if row.len() != head.len() {
                let col = row
                    .get(head.len())
                    .map_or(text.chars().count() as u32 + 1, |c| c.0);
                let kind = StimulusErrorKind::CellCount {
                    expected: head.len(),
                    found: row.len(),
                };
                return Err(err(line, col, kind));
            }
            let (tcol, ttext) = row[0];
            let at: u64 = ttext
                .parse()
                .map_err(|_| err(line, tcol, StimulusErrorKind::BadTime(ttext.to_string())))?;
            let mut values = Vec::with_capacity(stim.columns.len());
            for (&(col, cell), column) in row[1..].iter().zip(&stim.columns) {
                if cell.is_empty() {
                    values.push(None);
                    continue;
                }
                let v = parse_cell(cell, column).map_err(|kind| err(line, col, kind))?;
                values.push(Some(v));
            }
            stim.push_row_at(line, tcol, at, values)?;
        }
        Ok(stim)
    }

    /// Adds a column (programmatic construction): an address or symbol, or a reserved name
    /// (`HSCn`, `PORTn`, module doc). Fails like a bad header cell.
    pub fn add_column(
        &mut self,
        name: &str,
        resolve: Resolver<'_>,
    ) -> Result<usize, StimulusErrorKind> {
        let target = match reserved(name) {
            Some(reserved) => self.hardware(name, reserved)?,
            None => {
                let address =
                    resolve(name).map_err(|reason| StimulusErrorKind::UnknownAddress {
                        name: name.to_string(),
                        reason,
                    })?;
                let read_only_sm = self.profile.profile().special_memory_read_only;
                if let Some(reason) = writable(&address, read_only_sm) {
                    return Err(StimulusErrorKind::NotWritable {
                        name: name.to_string(),
                        reason,
                    });
                }
                Target::Address(address)
            }
        };
        if self
            .columns
            .iter()
            .any(|c| c.name == name || c.target == target)
        {
            return Err(StimulusErrorKind::DuplicateColumn(name.to_string()));
        }
        self.columns.push(Column {
            name: name.to_string(),
            target,
        });
        Ok(self.columns.len() - 1)
    }

    /// The target of a reserved column name, if the profile has that counter or port.
    fn hardware(&self, name: &str, reserved: Reserved) -> Result<Target, StimulusErrorKind> {
        let profile = self.profile.profile();
        match reserved {
            Reserved::Hsc(n) => match u8::try_from(n) {
                Ok(n) if profile.hsc.get(n).is_some() => Ok(Target::HscSteps(n)),
                _ => Err(StimulusErrorKind::NoCounter {
                    name: name.to_string(),
                    cpu: profile.model,
                    have: hsc_columns(profile),
                }),
            },
            Reserved::Port(n) => match u8::try_from(n) {
                Ok(n) if comm::port(profile, n).is_some() => Ok(Target::Receive(n)),
                _ => Err(StimulusErrorKind::NoPort {
                    name: name.to_string(),
                    cpu: profile.model,
                    have: port_columns(profile),
                }),
            },
        }
    }

    /// Appends a row of raw values (programmatic construction): an address's raw bits, an
    /// `HSCn` column's steps as the `i32`'s bit pattern (`-1` is `u32::MAX`); a `PORTn` column
    /// takes bytes ([`Stimulus::push_cells`]), so any value there is an error. Errors report
    /// the row as line `rows + 2` (as if a header were line 1) and the 1-based cell as column.
    pub fn push_row(&mut self, at: u64, cells: Vec<Option<u32>>) -> Result<(), StimulusError> {
        let steps = |i: usize| {
            matches!(
                self.columns.get(i).map(|c| c.target),
                Some(Target::HscSteps(_))
            )
        };
        let cells = cells
            .into_iter()
            .enumerate()
            .map(|(i, v)| {
                v.map(|v| {
                    if steps(i) {
                        Cell::Steps(v as i32)
                    } else {
                        Cell::Value(v)
                    }
                })
            })
            .collect();
        self.push_cells(at, cells)
    }

    /// Appends a row of cells (programmatic construction), each of its column's kind: a
    /// [`Cell::Value`] in range for an address, [`Cell::Steps`] for `HSCn`, at least one byte
    /// of [`Cell::Bytes`] for `PORTn`. Errors as [`Stimulus::push_row`]'s.
    pub fn push_cells(&mut self, at: u64, cells: Vec<Option<Cell>>) -> Result<(), StimulusError> {
        let line = self.rows.len() as u32 + 2;
        if cells.len() != self.columns.len() {
            let kind = StimulusErrorKind::CellCount {
                expected: self.columns.len() + 1,
                found: cells.len() + 1,
            };
            return Err(err(line, 1, kind));
        }
        for (i, (cell, column)) in cells.iter().zip(&self.columns).enumerate() {
            if let Some(cell) = cell {
                check_cell(cell, column).map_err(|kind| err(line, i as u32 + 2, kind))?;
            }
        }
        self.push_row_at(line, 1, at, cells)
    }

    fn push_row_at(
        &mut self,
        line: u32,
        tcol: u32,
        at: u64,
        cells: Vec<Option<Cell>>,
    ) -> Result<(), StimulusError> {
        if let Some(prev) = self.rows.last()
            && at <= prev.at
        {
            let kind = StimulusErrorKind::Unsorted {
                at,
                previous: prev.at,
            };
            return Err(err(line, tcol, kind));
        }
        self.rows.push(Row { at, line, cells });
        Ok(())
    }

    /// The time base.
    pub fn time_base(&self) -> TimeBase {
        self.time_base
    }

    /// The driven columns.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// The rows, sorted by time.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// The scan a row applies to: its number, or the first scan starting at or after its time.
    /// `scan_ms` must not be 0.
    pub fn due_scan(&self, row: &Row, scan_ms: u64) -> u64 {
        match self.time_base {
            TimeBase::Scan => row.at,
            TimeBase::Millis => row.at.div_ceil(scan_ms.max(1)),
        }
    }
}

#[cfg(test)]
#[path = "stimulus_tests.rs"]
mod tests;
