//! The per-block cache of image bytes held in SSA values.
//!
//! Bit logic reads and writes single bits, which on a byte-addressed image means a load, a
//! shift, a mask and a read-modify-write store per instruction. Instead each byte is loaded at
//! most once per basic block, every bit write produces a new SSA value for its byte, and the
//! dirty bytes are stored once: at the end of the block, before any access whose address is
//! only known at run time, before every helper call and before every exit. The cache maps a
//! static address (image-relative, or relative to the current POU's L frame) to its value.
//!
//! Inside one op that branches (a box that may fail, a conditional call) the arms start from a
//! clean copy of the cache and [`Cache::meet`] keeps only the entries no arm changed.

use cranelift_codegen::ir::Value;
use std::collections::BTreeMap;

/// A statically known byte address.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) struct Addr {
    /// Relative to the current L frame instead of the image start.
    pub(crate) local: bool,
    /// Byte offset from that base.
    pub(crate) off: u32,
}

impl Addr {
    /// An image-relative address.
    pub(crate) fn img(off: u32) -> Addr {
        Addr { local: false, off }
    }

    /// The address `n` bytes further.
    pub(crate) fn plus(self, n: u32) -> Addr {
        Addr {
            local: self.local,
            off: self.off + n,
        }
    }
}

/// One cached byte: an `i32` whose upper 24 bits are zero, and the op that produced it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Entry {
    pub(crate) v: Value,
    pub(crate) dirty: bool,
    pub(crate) at: usize,
}

/// How many ops a cached byte stays usable. Reusing a value much later keeps it live across
/// everything in between, and the register allocator then spills it (a store and a reload),
/// which costs more than loading the byte again.
const WINDOW: usize = 12;

/// The cache itself; a `BTreeMap` so that flushes store in address order (deterministic CLIF).
#[derive(Clone, Debug, Default)]
pub(crate) struct Cache {
    pub(crate) map: BTreeMap<Addr, Entry>,
    /// The op being lowered (set by the lowering loop).
    pub(crate) now: usize,
}

impl Cache {
    /// The cached value of a byte, if recent enough (dirty entries never expire).
    pub(crate) fn get(&self, a: Addr) -> Option<Value> {
        self.map
            .get(&a)
            .filter(|e| e.dirty || self.now.saturating_sub(e.at) <= WINDOW)
            .map(|e| e.v)
    }

    /// Records a value just loaded from memory (or just stored to it).
    pub(crate) fn put_clean(&mut self, a: Addr, v: Value) {
        let at = self.now;
        self.map.insert(
            a,
            Entry {
                v,
                dirty: false,
                at,
            },
        );
    }

    /// Forgets everything (memory may have changed anywhere); keeps the op counter.
    pub(crate) fn clear(&mut self) {
        self.map.clear();
    }
    /// Forgets `len` bytes from `a` (they are about to be overwritten in memory).
    pub(crate) fn forget(&mut self, a: Addr, len: u32) {
        for i in 0..len {
            self.map.remove(&a.plus(i));
        }
    }

    /// The dirty entries among `len` bytes from `a`, marking them clean (the caller stores them).
    pub(crate) fn take_dirty_in(&mut self, a: Addr, len: u32) -> Vec<(Addr, Value)> {
        let mut out = Vec::new();
        for i in 0..len {
            if let Some(e) = self.map.get_mut(&a.plus(i))
                && e.dirty
            {
                e.dirty = false;
                out.push((a.plus(i), e.v));
            }
        }
        out
    }

    /// Every dirty entry, marking them clean (the caller stores them).
    pub(crate) fn take_all_dirty(&mut self) -> Vec<(Addr, Value)> {
        let mut out = Vec::new();
        for (a, e) in self.map.iter_mut() {
            if e.dirty {
                e.dirty = false;
                out.push((*a, e.v));
            }
        }
        out
    }

    /// The entries every arm left untouched; all arms must have flushed, so they are clean.
    pub(crate) fn meet(arms: &[Cache]) -> Cache {
        let Some((first, rest)) = arms.split_first() else {
            return Cache::default();
        };
        let map = first
            .map
            .iter()
            .filter(|(a, e)| !e.dirty && rest.iter().all(|c| c.map.get(a) == Some(e)))
            .map(|(a, e)| (*a, *e))
            .collect();
        Cache {
            map,
            now: first.now,
        }
    }
}
