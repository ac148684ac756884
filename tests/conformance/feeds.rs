//! The peripheral stimulus of a case, the `[[scan]]` keys beyond the inputs:
//!
//! * `hsc = { 0 = 10 }` is HSC0's counting activity in the interval before that scan
//!   (s7-200-more §8.4, §11.2 `hsc_steps`). Like the inputs of an S7 scan it is whole: a
//!   counter the scan does not list has no activity.
//! * `rx = { 0 = [79, 75, 13] }` is the bytes that arrive on serial port 0 during the interval
//!   before that scan (§10.4, §11.2 `rx`), back to back from the interval's start.
//!
//! [`Feed`] writes both into the image before each scan, around any engine.

use stljit_core::ScanStatus;
use stljit_runtime::{Engine, Image};
use toml::{Table, Value};

/// The `[[scan]]` keys this module reads.
pub(crate) const KEYS: &[&str] = &["hsc", "rx"];

/// One scan's peripheral stimulus.
#[derive(Clone, Default)]
pub(crate) struct ScanFeed {
    /// The listed `(counter, steps)`.
    hsc: Vec<(u8, i32)>,
    /// The bytes arriving on each listed port.
    rx: Vec<(u8, Vec<u8>)>,
}

impl ScanFeed {
    /// Reads the [`KEYS`] of a `[[scan]]` row (each optional).
    pub(crate) fn parse(row: &Table) -> Result<ScanFeed, String> {
        let table = |key: &str| match row.get(key) {
            None => Ok(Table::new()),
            Some(Value::Table(t)) => Ok(t.clone()),
            Some(_) => Err(format!("`{key}` must be a table")),
        };
        Ok(ScanFeed {
            hsc: parse_hsc(&table("hsc")?)?,
            rx: parse_rx(&table("rx")?)?,
        })
    }
}

/// Reads a scan's `hsc` table: `(counter, steps)`.
fn parse_hsc(t: &Table) -> Result<Vec<(u8, i32)>, String> {
    let mut out = Vec::new();
    for (k, v) in t {
        let n: u8 = k
            .parse()
            .map_err(|_| format!("hsc: `{k}` is not a counter number"))?;
        let steps = match v {
            Value::Integer(i) => i32::try_from(*i).map_err(|_| format!("hsc: {i} is too large"))?,
            _ => return Err(format!("hsc: `{k}` needs an integer")),
        };
        out.push((n, steps));
    }
    Ok(out)
}

/// Reads a scan's `rx` table: `(port, bytes)`.
fn parse_rx(t: &Table) -> Result<Vec<(u8, Vec<u8>)>, String> {
    let mut out = Vec::new();
    for (k, v) in t {
        let port: u8 = k
            .parse()
            .map_err(|_| format!("rx: `{k}` is not a port number"))?;
        let Value::Array(items) = v else {
            return Err(format!("rx: `{k}` needs an array of bytes"));
        };
        let bytes = items
            .iter()
            .map(|b| match b {
                Value::Integer(i) => u8::try_from(*i).map_err(|_| format!("rx: {i} is no byte")),
                _ => Err(format!("rx: `{k}` needs bytes")),
            })
            .collect::<Result<Vec<u8>, String>>()?;
        out.push((port, bytes));
    }
    Ok(out)
}

/// An engine that first writes the scan's counting activity (every counter: listed or 0) and
/// queues its received bytes.
pub(crate) struct Feed<'a> {
    pub(crate) inner: &'a mut dyn Engine,
    /// Per scan, its stimulus.
    pub(crate) scans: Vec<ScanFeed>,
    pub(crate) k: usize,
}

impl Engine for Feed<'_> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        let feed = self.scans.get(self.k).cloned().unwrap_or_default();
        let counters: Vec<u8> = image
            .layout()
            .profile
            .profile()
            .hsc
            .iter()
            .map(|c| c.number)
            .collect();
        for n in counters {
            let steps = feed
                .hsc
                .iter()
                .find(|(c, _)| *c == n)
                .map_or(0, |&(_, s)| s);
            image.set_hsc_rate(n, steps);
        }
        for (port, bytes) in &feed.rx {
            image.queue_rx(*port, bytes);
        }
        self.k += 1;
        self.inner.scan(image, t_ms)
    }
}
