//! The per-block cache of image bytes held in SSA values.
//!
//! Bit logic reads and writes single bits, which on a byte-addressed image means a load, a
//! shift, a mask and a read-modify-write store per instruction. A byte read or written within
//! the last few ops is reused from its SSA value instead of loaded again; every write is stored
//! at once (keeping writes in registers to the block's end cost spills), so the cache holds
//! only values equal to memory and nothing ever needs to be written back: helper calls, exits
//! and pointer accesses at most forget entries. The cache maps a static address
//! (image-relative, or relative to the current POU's L frame) to its value. [`StoreLog`]
//! remembers where stores happened, for the wide loads of bit tests.
//!
//! Inside one op that branches (a box that may fail, a conditional call) the arms start from a
//! copy of the cache and [`Cache::meet`] keeps only the entries no arm changed.

use super::value::B;
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
    pub(crate) at: usize,
    /// Set where the byte was written as part of a wider value.
    pub(crate) part: Option<Part>,
}

/// A cached byte written as bits `shift..shift + 8` of a wider `i32` value (a word or double
/// word store), so that a wide read of the same bytes can take the value instead of assembling
/// the bytes one by one (`MOVW IN1, OUT` then `+I IN2, OUT`, how LAD's ADD_I reads in STL).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Part {
    /// The wide value stored.
    pub(crate) wide: Value,
    /// Where the byte sits in it.
    pub(crate) shift: u32,
}

/// How many ops a cached byte stays usable. Reusing a value much later keeps it live across
/// everything in between, and the register allocator then spills it (a store and a reload),
/// which costs more than loading the byte again.
const WINDOW: usize = 12;

/// The cache itself; a `BTreeMap` so that [`Cache::meet`] visits entries in address order
/// (deterministic CLIF).
#[derive(Clone, Debug, Default)]
pub(crate) struct Cache {
    pub(crate) map: BTreeMap<Addr, Entry>,
    /// The op being lowered (set by the lowering loop).
    pub(crate) now: usize,
    /// The boolean behind the ENO byte's cached value, while that value is still cached.
    pub(crate) eno: Option<EnoFact>,
    /// What the last integer `+`/`-` box left in SMB1, while SMB1's cached value is still
    /// the one it stored.
    pub(crate) flags: Option<FlagsChain>,
}

/// What a branch-free box knew when it set ENO: `AENO` right after it can use the boolean
/// instead of the byte (`top AND (top AND gate AND ok)` is the box's ENO itself), which saves
/// the byte's alignment and a second `and`.
///
/// The fact holds only while the ENO byte's cached value is `byte`: any other write of the
/// byte puts another value there (or forgets it), so a stale fact is never used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct EnoFact {
    /// The value the box stored in the ENO byte (0/1).
    pub(crate) byte: Value,
    /// The same boolean as a [`B`] (no alignment or masking paid for).
    pub(crate) value: B,
    /// The logic stack's top when the box ran; `value` implies it.
    pub(crate) top: B,
}

/// SMB1 as left by a run of integer `+`/`-` boxes (`+I`, `-D`, `INCW`, ...), kept as the
/// operands of its rule rather than as the byte: SM1.0–SM1.2 of such a box depend only on its
/// result and overflow, so a box that follows selects its own result and overflow over the
/// chain's and derives the byte once, from where the chain started. Every box still stores
/// the byte it computes; the dead-store pass drops all but the last store of a block, and
/// with it the flag computations nobody reads (about ten instructions a box).
///
/// The fact holds only while SMB1's cached value is `smb1`, like [`EnoFact`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct FlagsChain {
    /// The SMB1 value the chain's last box stored.
    pub(crate) smb1: Value,
    /// SMB1 before the chain's first box.
    pub(crate) base: Value,
    /// The result (sign-extended to `i32`) of the chain's last box that ran.
    pub(crate) r: Value,
    /// That box's signed-overflow flag (an `i8` 0/1).
    pub(crate) ovf: Value,
    /// Whether any box of the chain ran.
    pub(crate) ran: B,
}

impl Cache {
    /// An empty cache whose op clock is at `now`.
    pub(crate) fn at(now: usize) -> Cache {
        Cache {
            map: BTreeMap::new(),
            now,
            eno: None,
            flags: None,
        }
    }

    /// The cached value of a byte, if recent enough.
    pub(crate) fn get(&self, a: Addr) -> Option<Value> {
        self.entry(a).map(|e| e.v)
    }

    /// The wide value a cached byte was written as part of, if recent enough.
    pub(crate) fn part(&self, a: Addr) -> Option<Part> {
        self.entry(a).and_then(|e| e.part)
    }

    /// A byte's entry, if recent enough.
    fn entry(&self, a: Addr) -> Option<&Entry> {
        self.map
            .get(&a)
            .filter(|e| self.now.saturating_sub(e.at) <= WINDOW)
    }

    /// Records a value just loaded from memory (or just stored to it).
    pub(crate) fn put_clean(&mut self, a: Addr, v: Value) {
        self.put(a, v, None);
    }

    /// Records a byte value just stored, which is `part` of a wider value when that is given.
    pub(crate) fn put(&mut self, a: Addr, v: Value, part: Option<Part>) {
        let at = self.now;
        self.map.insert(a, Entry { v, at, part });
    }

    /// Forgets everything (memory may have changed anywhere); keeps the op counter.
    pub(crate) fn clear(&mut self) {
        self.map.clear();
        self.eno = None;
        self.flags = None;
    }
    /// Forgets `len` bytes from `a` (they are about to be overwritten in memory).
    pub(crate) fn forget(&mut self, a: Addr, len: u32) {
        for i in 0..len {
            self.map.remove(&a.plus(i));
        }
    }

    /// The entries every arm left untouched.
    pub(crate) fn meet(arms: &[Cache]) -> Cache {
        let Some((first, rest)) = arms.split_first() else {
            return Cache::default();
        };
        let map = first
            .map
            .iter()
            .filter(|(a, e)| rest.iter().all(|c| c.map.get(a) == Some(e)))
            .map(|(a, e)| (*a, *e))
            .collect();
        let eno = first.eno.filter(|f| rest.iter().all(|c| c.eno == Some(*f)));
        let flags = first
            .flags
            .filter(|f| rest.iter().all(|c| c.flags == Some(*f)));
        Cache {
            map,
            now: first.now,
            eno,
            flags,
        }
    }
}

/// Which image bytes were stored recently, so that a bit test reads four bytes at once only
/// where that load cannot overlap a store still in flight.
///
/// x86 folds a 32-bit load into the `and`/`or`/`andn` that consumes it, which saves both the
/// `movzx` of a byte contact and its alignment shift; Cranelift folds no narrower load. But a
/// wide load over a byte stored shortly before stalls until the store has left the store
/// buffer (a store-to-load interlock), which made 32-bit contacts everywhere 1.8x slower than
/// byte contacts. The log holds the op of the last store to each byte, and an op from which
/// every byte counts as stored: a helper call, a pointer write, or the entry of a block that
/// is reached by a jump or starts a function, where earlier stores are not visible. A store
/// counts for [`JitOptions::hot_ops`](crate::JitOptions::hot_ops) ops.
#[derive(Clone, Debug)]
pub(crate) struct StoreLog {
    /// Op of the last store, per image byte and per byte of the L frame.
    image: Vec<usize>,
    local: Vec<usize>,
    all: usize,
    hot_ops: usize,
}

impl StoreLog {
    /// A log for an image of `image_size` bytes and an L frame of `local_size`, whose stores
    /// count for `hot_ops` ops.
    pub(crate) fn new(image_size: u32, local_size: u32, hot_ops: usize) -> StoreLog {
        StoreLog {
            image: vec![0; image_size as usize],
            local: vec![0; local_size as usize],
            all: 0,
            hot_ops,
        }
    }

    fn slot(&mut self, a: Addr) -> Option<&mut usize> {
        let area = if a.local {
            &mut self.local
        } else {
            &mut self.image
        };
        area.get_mut(a.off as usize)
    }

    /// Records a store of `len` bytes from `a` at op `now`.
    pub(crate) fn stored(&mut self, a: Addr, len: u32, now: usize) {
        for i in 0..len {
            if let Some(at) = self.slot(a.plus(i)) {
                *at = now;
            }
        }
    }

    /// Records that any byte may have been stored at op `now` (older per-byte entries then
    /// no longer matter: they are older than this one).
    pub(crate) fn stored_anywhere(&mut self, now: usize) {
        self.all = now;
    }

    /// No byte of the `len` from `a` was stored within the last `hot_ops` ops before `now`
    /// (bytes outside the image or frame count as just stored).
    pub(crate) fn is_cold(&self, a: Addr, len: u32, now: usize) -> bool {
        let long_ago = |at: usize| now.saturating_sub(at) > self.hot_ops;
        let area = if a.local { &self.local } else { &self.image };
        long_ago(self.all)
            && (0..len).all(|i| {
                area.get(a.plus(i).off as usize)
                    .is_some_and(|&at| long_ago(at))
            })
    }
}
