//! The high-speed counter stimulus of a case (s7-200-more §8.4, §11.2 `hsc_steps`):
//! `hsc = { 0 = 10 }` in a `[[scan]]` is HSC0's counting activity in the interval before that
//! scan. Like the inputs of an S7 scan it is whole: a counter the scan does not list has no
//! activity. [`Feed`] writes it into the image before each scan, around any engine.
//!
//! The serial receive stimulus (s7-200-more §10.4, §11.2 `rx`) rides along: `rx = { 0 = [79,
//! 75, 13] }` is the bytes that arrive on port 0 during the interval before that scan.

use stljit_core::ScanStatus;
use stljit_runtime::{Engine, Image};
use toml::{Table, Value};

/// Reads a scan's `hsc` table: `(counter, steps)`.
pub(crate) fn parse(t: &Table) -> Result<Vec<(u8, i32)>, String> {
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
pub(crate) fn parse_rx(t: &Table) -> Result<Vec<(u8, Vec<u8>)>, String> {
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
    /// Per scan, the listed `(counter, steps)`.
    pub(crate) scans: Vec<Vec<(u8, i32)>>,
    /// Per scan, the bytes arriving on each listed port.
    pub(crate) rx: Vec<Vec<(u8, Vec<u8>)>>,
    pub(crate) k: usize,
}

impl Engine for Feed<'_> {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        let listed = self.scans.get(self.k).cloned().unwrap_or_default();
        let counters: Vec<u8> = image
            .layout()
            .profile
            .profile()
            .hsc
            .iter()
            .map(|c| c.number)
            .collect();
        for n in counters {
            let steps = listed.iter().find(|(c, _)| *c == n).map_or(0, |&(_, s)| s);
            image.set_hsc_rate(n, steps);
        }
        for (port, bytes) in self.rx.get(self.k).cloned().unwrap_or_default() {
            image.queue_rx(port, &bytes);
        }
        self.k += 1;
        self.inner.scan(image, t_ms)
    }
}
