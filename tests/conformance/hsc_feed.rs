//! The high-speed counter stimulus of a case (s7-200-more §8.4, §11.2 `hsc_steps`):
//! `hsc = { 0 = 10 }` in a `[[scan]]` is HSC0's counting activity in the interval before that
//! scan. Like the inputs of an S7 scan it is whole: a counter the scan does not list has no
//! activity. [`Feed`] writes it into the image before each scan, around any engine.

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

/// An engine that first writes the scan's counting activity (every counter: listed or 0).
pub(crate) struct Feed<'a> {
    pub(crate) inner: &'a mut dyn Engine,
    /// Per scan, the listed `(counter, steps)`.
    pub(crate) scans: Vec<Vec<(u8, i32)>>,
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
        self.k += 1;
        self.inner.scan(image, t_ms)
    }
}
