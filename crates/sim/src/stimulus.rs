//! The stimulus CSV: which values are driven into the PLC before which scan.
//!
//! ```text
//! scan,I0.0,IB1,AIW0,VW100      or      t_ms,I0.0,...
//! 0,1,,100,
//! 5,0,16#0F,,-7
//! ```
//! The first header cell picks the time base: `scan` numbers or `t_ms` (virtual milliseconds; a
//! row applies to the first scan starting at or after that time). A row's values are written
//! before that scan runs and hold until a later row changes them (inputs stay in the physical
//! input copy; other areas are written once, like an HMI write, and the program may overwrite
//! them). An empty cell leaves the value alone. Blank lines and lines starting with `#` are
//! ignored. Every error names the line and column (1-based) of the offending cell; a stimulus
//! with any error is rejected whole, so nothing runs on half a stimulus.

use crate::Resolver;
use crate::value::{ValueError, ValueKind, parse_value, writable};
use std::fmt;
use stljit_core::CpuProfile;
use stljit_core::ir::Address;

/// How a row's time is counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeBase {
    /// Scan numbers (0 is the first scan).
    Scan,
    /// Virtual milliseconds.
    Millis,
}

/// One driven address.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Column {
    /// The name as written in the header.
    pub name: String,
    /// What it resolved to.
    pub address: Address,
}

/// One row: when, and the raw value per column (`None` = leave alone).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    /// Scan number or ms, per [`TimeBase`].
    pub at: u64,
    /// Source line (1-based) for messages.
    pub line: u32,
    /// One cell per column.
    pub cells: Vec<Option<u32>>,
}

/// A checked stimulus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stimulus {
    time_base: TimeBase,
    columns: Vec<Column>,
    rows: Vec<Row>,
    read_only_sm: u32,
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
    /// The same name appears twice in the header.
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

impl Stimulus {
    /// An empty stimulus (nothing driven): every input stays 0.
    pub fn empty(time_base: TimeBase, profile: &CpuProfile) -> Stimulus {
        Stimulus {
            time_base,
            columns: Vec::new(),
            rows: Vec::new(),
            read_only_sm: profile.special_memory_read_only,
        }
    }

    /// Parses and checks a stimulus CSV for `profile` (which fixes the read-only SM range).
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
                let kind = ValueKind::of(&column.address);
                let v = parse_value(cell, kind).map_err(|error| {
                    let kind = StimulusErrorKind::BadValue {
                        column: column.name.clone(),
                        text: cell.to_string(),
                        error,
                    };
                    err(line, col, kind)
                })?;
                values.push(Some(v));
            }
            stim.push_row_at(line, tcol, at, values)?;
        }
        Ok(stim)
    }

    /// Adds a column (programmatic construction). Fails like a bad header cell.
    pub fn add_column(
        &mut self,
        name: &str,
        resolve: Resolver<'_>,
    ) -> Result<usize, StimulusErrorKind> {
        let address = resolve(name).map_err(|reason| StimulusErrorKind::UnknownAddress {
            name: name.to_string(),
            reason,
        })?;
        if let Some(reason) = writable(&address, self.read_only_sm) {
            return Err(StimulusErrorKind::NotWritable {
                name: name.to_string(),
                reason,
            });
        }
        if self
            .columns
            .iter()
            .any(|c| c.name == name || c.address == address)
        {
            return Err(StimulusErrorKind::DuplicateColumn(name.to_string()));
        }
        self.columns.push(Column {
            name: name.to_string(),
            address,
        });
        Ok(self.columns.len() - 1)
    }

    /// Appends a row of raw values (programmatic construction). Errors report the row as line
    /// `rows + 2` (as if a header were line 1) and the 1-based cell as column.
    pub fn push_row(&mut self, at: u64, cells: Vec<Option<u32>>) -> Result<(), StimulusError> {
        let line = self.rows.len() as u32 + 2;
        if cells.len() != self.columns.len() {
            let kind = StimulusErrorKind::CellCount {
                expected: self.columns.len() + 1,
                found: cells.len() + 1,
            };
            return Err(err(line, 1, kind));
        }
        for (i, (cell, column)) in cells.iter().zip(&self.columns).enumerate() {
            let kind = ValueKind::of(&column.address);
            let limit = match kind {
                ValueKind::Bit => 1,
                ValueKind::Value(w) => w.mask(),
            };
            if let Some(v) = *cell
                && v > limit
            {
                let kind = StimulusErrorKind::BadValue {
                    column: column.name.clone(),
                    text: v.to_string(),
                    error: ValueError::OutOfRange { kind },
                };
                return Err(err(line, i as u32 + 2, kind));
            }
        }
        self.push_row_at(line, 1, at, cells)
    }

    fn push_row_at(
        &mut self,
        line: u32,
        tcol: u32,
        at: u64,
        cells: Vec<Option<u32>>,
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

    /// The driven addresses.
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
