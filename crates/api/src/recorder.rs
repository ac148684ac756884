//! [`Recorder`]: an [`Observer`] that records the values of a set of pre-resolved handles after
//! every scan into columns allocated up front, so a run of `n` scans into a recorder made for
//! `n` allocates nothing while it runs (the Python package's traces are these columns).

use crate::handle::{Handle, Value};
use stljit_sim::{Observer, ScanEvent};

/// Columns of raw values, one per handle, plus the scan numbers and times.
#[derive(Clone, Debug)]
pub struct Recorder {
    handles: Vec<Handle>,
    scans: Vec<u64>,
    times: Vec<u64>,
    /// `columns[i]` holds handle `i`'s raw bits, one entry per scan.
    columns: Vec<Vec<u32>>,
}

impl Recorder {
    /// A recorder for `handles` with room for `capacity` scans (more scans grow the columns).
    pub fn new(handles: Vec<Handle>, capacity: usize) -> Recorder {
        Recorder {
            columns: handles
                .iter()
                .map(|_| Vec::with_capacity(capacity))
                .collect(),
            handles,
            scans: Vec::with_capacity(capacity),
            times: Vec::with_capacity(capacity),
        }
    }

    /// The handles, in column order.
    pub fn handles(&self) -> &[Handle] {
        &self.handles
    }

    /// Number of scans recorded.
    pub fn len(&self) -> usize {
        self.scans.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.scans.is_empty()
    }

    /// The scan number of each row.
    pub fn scans(&self) -> &[u64] {
        &self.scans
    }

    /// The virtual time (ms) at the start of each row's scan.
    pub fn times(&self) -> &[u64] {
        &self.times
    }

    /// Handle `i`'s raw bits, one per row.
    pub fn raw(&self, i: usize) -> &[u32] {
        self.columns.get(i).map_or(&[], Vec::as_slice)
    }

    /// Handle `i`'s values, one per row.
    pub fn values(&self, i: usize) -> Vec<Value> {
        match self.handles.get(i) {
            Some(h) => self.raw(i).iter().map(|&r| h.decode(r)).collect(),
            None => Vec::new(),
        }
    }

    /// Forgets every row (keeping the room).
    pub fn clear(&mut self) {
        self.scans.clear();
        self.times.clear();
        self.columns.iter_mut().for_each(Vec::clear);
    }
}

impl Observer for Recorder {
    fn observe(&mut self, event: &ScanEvent<'_>) -> std::io::Result<()> {
        self.scans.push(event.scan);
        self.times.push(event.t_ms);
        let bytes = event.image.bytes();
        for (h, col) in self.handles.iter().zip(&mut self.columns) {
            col.push(h.load(bytes, h.read_offset()));
        }
        Ok(())
    }
}
