//! Value operands: constants, direct locations and pointers.
//!
//! Direct locations are range-checked by the IR verifier against the same profile, so they become
//! loads and stores at constant offsets (big-endian words through `bswap`). A pointer operand is
//! read as a dword, resolved by the runtime's `pointer::resolve` (through its shim, so the rule
//! exists once) and accessed at the resulting image offset; a failed resolution branches to the
//! caller's failure path. Because a pointer may alias any cached byte, the cache is forgotten
//! before a pointer write (the cache holds only values equal to memory, so a pointer read needs
//! nothing).

use super::cache::{Addr, Part};
use super::{Lower, mf};
use crate::helpers::Helper;
use cranelift_codegen::ir::{
    Block, BlockArg, InstBuilder, Value,
    condcodes::IntCC,
    types::{I16, I32, I64},
};
use stljit_core::ir::{Loc, Operand};
use stljit_core::{FatalCode, Width};

/// Where a value operand lives once resolved.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Place {
    /// A static address (through the cache).
    Static(Addr),
    /// An absolute address computed at run time (image pointer plus resolved offset).
    Dyn(Value),
}

/// What a failed pointer resolution does.
#[derive(Clone, Copy, Debug)]
pub(crate) enum OnFail {
    /// Branch to this block, passing the error code (`i32`).
    Branch(Block),
    /// Abort the scan with this fatal code (compares).
    Fatal(FatalCode),
}

impl Lower<'_, '_> {
    /// The static address of a location.
    pub(crate) fn loc_addr(&self, loc: Loc) -> Addr {
        self.area_addr(loc.area, loc.offset)
    }

    /// Reads `width` big-endian bytes at a static address, zero-extended to `i32`.
    pub(crate) fn read_static(&mut self, a: Addr, width: Width) -> Value {
        if width == Width::Byte {
            return self.byte(a);
        }
        let n = width.bytes();
        if let Some(v) = self.reread_wide(a, width) {
            return v;
        }
        let cached = (0..n)
            .filter(|&i| self.block.cache.get(a.plus(i)).is_some())
            .count() as u32;
        let now = self.block.cache.now;
        if cached == n || (cached > 0 && !self.func.stores.is_cold(a, n, now)) {
            // All bytes are in registers (typically just written): assemble them. So too where
            // some are and the range was stored recently (`MOVB` into the word, then `+I` on
            // it): a word load over a byte store still in flight waits until the store
            // commits, byte loads of the others do not.
            let mut acc = self.byte(a);
            for i in 1..n {
                let hi = self.b.ins().ishl_imm_s(acc, 8);
                let lo = self.byte(a.plus(i));
                acc = self.b.ins().bor(hi, lo);
            }
            return acc;
        }
        if let Some(pred) = &self.in_box.pred
            && let Some(&(_, _, v)) = pred.reads.iter().find(|r| r.0 == a && r.1 == width)
        {
            return v;
        }
        let base = self.base(a);
        let v = self.load_be(base, a.off as i32, width);
        if let Some(pred) = &mut self.in_box.pred {
            pred.reads.push((a, width, v));
        }
        v
    }

    /// A word or double word read whose bytes are all cached as consecutive parts of one wide
    /// value just stored ([`Part`]): that value shifted (and byte-swapped where it was stored
    /// in memory order, by a raw move), instead of the bytes assembled one by one.
    fn reread_wide(&mut self, a: Addr, width: Width) -> Option<Value> {
        let n = width.bytes();
        let parts: Vec<Part> = (0..n)
            .map(|i| self.block.cache.part(a.plus(i)))
            .collect::<Option<_>>()?;
        let wide = parts[0].wide;
        let low = parts[n as usize - 1].shift;
        let at = |i: u32| parts[i as usize].shift;
        if parts.iter().all(|p| p.wide == wide) {
            // Big-endian inside the value: byte i is 8(n-1-i) bits above the last one.
            if (0..n).all(|i| at(i) == low + 8 * (n - 1 - i)) {
                let v = match low {
                    0 => wide,
                    s => self.b.ins().ushr_imm_s(wide, i64::from(s)),
                };
                return Some(match width {
                    Width::DWord => v,
                    _ => self.b.ins().band_imm_s(v, i64::from(width.mask())),
                });
            }
            // Memory order inside the value (a raw move's little-endian load of the bytes).
            let first = at(0);
            if (0..n).all(|i| at(i) == first + 8 * i) {
                let v = match first {
                    0 => wide,
                    s => self.b.ins().ushr_imm_s(wide, i64::from(s)),
                };
                return Some(match width {
                    Width::DWord => self.b.ins().bswap(v),
                    _ => {
                        let h = self.b.ins().ireduce(I16, v);
                        let h = self.b.ins().bswap(h);
                        self.b.ins().uextend(I32, h)
                    }
                });
            }
        }
        None
    }

    pub(crate) fn load_be(&mut self, base: Value, off: i32, width: Width) -> Value {
        match width {
            Width::Byte => self.b.ins().uload8(I32, mf(), base, off),
            Width::Word => {
                let v = self.b.ins().load(I16, mf(), base, off);
                let s = self.b.ins().bswap(v);
                self.b.ins().uextend(I32, s)
            }
            Width::DWord => {
                let v = self.b.ins().load(I32, mf(), base, off);
                self.b.ins().bswap(v)
            }
        }
    }

    pub(crate) fn store_be(&mut self, base: Value, off: i32, width: Width, v: Value) {
        match width {
            Width::Byte => {
                self.b.ins().istore8(mf(), v, base, off);
            }
            Width::Word => {
                let w = self.b.ins().ireduce(I16, v);
                let s = self.b.ins().bswap(w);
                self.b.ins().store(mf(), s, base, off);
            }
            Width::DWord => {
                let s = self.b.ins().bswap(v);
                self.b.ins().store(mf(), s, base, off);
            }
        }
    }

    /// Writes the low `width` bytes of `v` (an `i32`) big-endian at a static address.
    /// Inside a branch-free box the write keeps the old value where PF is 0.
    pub(crate) fn write_static(&mut self, a: Addr, width: Width, v: Value) {
        let v = match self.in_box.pf() {
            Some(p) => {
                let old = self.read_static(a, width);
                self.b.ins().select(p, v, old)
            }
            None => v,
        };
        match width {
            Width::Byte => {
                let m = self.b.ins().band_imm_s(v, 0xFF);
                self.set_byte(a, m);
            }
            _ => {
                let n = width.bytes();
                self.note_wide_write(a, n, v, |i| 8 * (n - 1 - i));
                let base = self.base(a);
                self.store_be(base, a.off as i32, width, v);
            }
        }
        // A later read inside the same box must see this write, not a recorded old value.
        if let Some(pred) = &mut self.in_box.pred {
            pred.reads.clear();
        }
    }

    /// Records a store of `n` bytes from `a` whose byte `i` is bits `shift(i)` to
    /// `shift(i) + 7` of `v` (an `i32`): the bytes stay in registers, so that a later bit or
    /// byte read of them (flags, coils on the same word) needs no load, and the store log
    /// counts them as just stored. The caller emits the store itself.
    pub(crate) fn note_wide_write(
        &mut self,
        a: Addr,
        n: u32,
        v: Value,
        shift: impl Fn(u32) -> u32,
    ) {
        for i in 0..n {
            let s = match shift(i) {
                0 => v,
                sh => self.b.ins().ushr_imm_s(v, i64::from(sh)),
            };
            let m = self.b.ins().band_imm_s(s, 0xFF);
            let part = Part {
                wide: v,
                shift: shift(i),
            };
            self.block.cache.put(a.plus(i), m, Some(part));
        }
        self.func.stores.stored(a, n, self.block.cache.now);
    }

    /// Resolves a pointer held at `loc` for a `width` access; on failure takes `fail`.
    fn resolve(&mut self, loc: Loc, width: Width, write: bool, fail: OnFail) -> Value {
        let (off, _) = self.resolve_off(loc, width, write, fail);
        let off = self.b.ins().uextend(I64, off);
        self.b.ins().iadd(self.func.image, off)
    }

    /// Resolves a pointer held at `loc`: its image offset (`i32`) and the raw pointer.
    pub(crate) fn resolve_off(
        &mut self,
        loc: Loc,
        width: Width,
        write: bool,
        fail: OnFail,
    ) -> (Value, Value) {
        let pa = self.loc_addr(loc);
        let ptr = self.read_static(pa, Width::DWord);
        let w = self.iconst(I32, i64::from(width.bytes()));
        let wr = self.iconst(I32, i64::from(write));
        // The shim packs its result: bit 32 set = success with the image offset in bits 0-31,
        // else the error code in bits 0-31.
        let r = self.call_pure(Helper::Pointer, &[ptr, w, wr]);
        let okbit = self.b.ins().ushr_imm_s(r, 32);
        let okbit = self.b.ins().band_imm_s(okbit, 1);
        let bad = self.b.ins().icmp_imm_s(IntCC::Equal, okbit, 0);
        let payload = self.b.ins().ireduce(I32, r);
        match fail {
            OnFail::Fatal(code) => self.fatal_if(bad, code),
            OnFail::Branch(err) => {
                let cont = self.b.create_block();
                self.b
                    .ins()
                    .brif(bad, err, &[BlockArg::Value(payload)], cont, &[]);
                self.b.seal_block(cont);
                self.b.switch_to_block(cont);
            }
        }
        (payload, ptr)
    }

    /// Resolves an operand to a place (constants and `&` have none: the caller handles them).
    pub(crate) fn place(
        &mut self,
        o: &Operand,
        width: Width,
        write: bool,
        fail: OnFail,
    ) -> Option<Place> {
        match *o {
            Operand::Mem(loc) => Some(Place::Static(self.loc_addr(loc))),
            Operand::Indirect(loc) => Some(Place::Dyn(self.resolve(loc, width, write, fail))),
            // Omron indirect operands only occur in Omron boxes, which resolve them in the
            // runtime (`lower::omron`).
            Operand::Const(_) | Operand::AddressOf(_) | Operand::Omron(_) => None,
        }
    }

    /// Reads a resolved place.
    pub(crate) fn read_place(&mut self, p: Place, width: Width) -> Value {
        match p {
            Place::Static(a) => self.read_static(a, width),
            Place::Dyn(addr) => self.load_be(addr, 0, width),
        }
    }

    /// Writes a resolved place.
    pub(crate) fn write_place(&mut self, p: Place, width: Width, v: Value) {
        match p {
            Place::Static(a) => self.write_static(a, width, v),
            Place::Dyn(addr) => {
                self.forget_all();
                self.store_be(addr, 0, width, v);
            }
        }
    }

    /// Writes a resolved place inside a branch-free box without the box's predicate: `v`
    /// already is the old value wherever the box does not run.
    pub(crate) fn write_place_unpredicated(&mut self, p: Place, width: Width, v: Value) {
        let pred = self.in_box.pred.take();
        self.write_place(p, width, v);
        // Like every write in the box: a later read must see it, not a recorded old value.
        self.in_box.pred = pred.map(|mut pred| {
            pred.reads.clear();
            pred
        });
    }

    /// Reads an operand's value (zero-extended `i32`), resolving pointers.
    pub(crate) fn read_operand(&mut self, o: &Operand, width: Width, fail: OnFail) -> Value {
        match *o {
            Operand::Const(k) => self.iconst(I32, i64::from(k & width.mask())),
            Operand::AddressOf(loc) => {
                let code = loc.area.pointer_code().unwrap_or(0);
                let p = (u32::from(code) << 24) | (loc.offset & 0x00FF_FFFF);
                self.iconst(I32, i64::from(p & width.mask()))
            }
            _ => match self.place(o, width, false, fail) {
                Some(p) => self.read_place(p, width),
                None => self.iconst(I32, 0),
            },
        }
    }

    /// Sign-extends the low `width` bits of an `i32` to `i32`.
    pub(crate) fn sext(&mut self, v: Value, width: Width) -> Value {
        match width {
            Width::Byte => {
                let s = self.b.ins().ishl_imm_s(v, 24);
                self.b.ins().sshr_imm_s(s, 24)
            }
            Width::Word => {
                let s = self.b.ins().ishl_imm_s(v, 16);
                self.b.ins().sshr_imm_s(s, 16)
            }
            Width::DWord => v,
        }
    }

    /// Whether an operand is a pointer (needs run-time resolution).
    pub(crate) fn is_indirect(o: &Operand) -> bool {
        matches!(o, Operand::Indirect(_))
    }
}
