//! Bit logic: contacts, compares, logic-stack instructions, edges and coils.
//!
//! All of it works on [`B`] booleans and cached bytes, so a run of contacts and coils becomes a
//! handful of ALU instructions with no memory traffic until the block ends.

use super::cache::Addr;
use super::mem::OnFail;
use super::value::B;
use super::{Lower, mf};
use cranelift_codegen::ir::{
    InstBuilder, Value,
    condcodes::{FloatCC, IntCC},
    types::{F32, I16, I32},
};
use stljit_core::ir::{BitLoc, CmpOp, CmpType, Contact, Operand};
use stljit_core::layout::Sched;
use stljit_core::{Area, FatalCode, Width};
use stljit_runtime::block::set_range_run;
use stljit_runtime::rules::GatePolicy;

/// The longest `S`/`R` range written inline; a longer one (or one whose count is read from
/// memory) is the runtime's `set_range`, which writes the image bytes itself.
pub(crate) const MAX_INLINE_RANGE: u32 = 64;

impl Lower<'_, '_> {
    /// The cached byte and bit of a bit location.
    pub(crate) fn bit_byte(&self, bit: BitLoc) -> Addr {
        self.area_addr(bit.area, bit.byte)
    }

    /// Reads a bit as a lazy boolean.
    pub(crate) fn read_bit(&mut self, bit: BitLoc) -> B {
        // `P_On`/`P_Off` are constants of the scan (no program writes them).
        if let Some(k) = stljit_core::omron::SystemBit::constant_at(bit) {
            return B::K(k);
        }
        if let Some(off) = self.env.resident.slot(bit) {
            // A 32-bit load where no recent store overlaps its four bytes (the three after
            // the shadow byte are garbage to a boolean at bit 0): `and`/`or`/`andn` take it as
            // their memory operand, one instruction for the contact.
            let a = Addr::img(off as u32);
            let v = if a.off % 16 <= 12 && self.func.stores.is_cold(a, 4, self.block.cache.now) {
                self.load_window(a)
            } else {
                self.b.ins().uload8(I32, mf(), self.func.image, off)
            };
            return B::Bit { v, pos: 0 };
        }
        let a = self.bit_byte(bit);
        let (v, at) = self.test_byte(a);
        B::Bit {
            v,
            pos: at + bit.bit,
        }
    }

    /// Writes a boolean into a resident bit's shadow byte at `off` (`crate::resident`): bit 0
    /// is the value, the other bits are garbage, so a boolean at bit 0 is stored as it is.
    fn write_resident(&mut self, off: i32, val: B) {
        let v = match val {
            B::K(k) => self.b.ins().iconst(I32, i64::from(k)),
            B::Bit { v, pos } => super::value::align(&mut self.b, v, pos, 0),
            B::Not { v, pos } => {
                let s = super::value::align(&mut self.b, v, pos, 0);
                self.b.ins().bnot(s)
            }
        };
        self.func
            .stores
            .stored(Addr::img(off as u32), 1, self.block.cache.now);
        self.b.ins().istore8(mf(), v, self.func.image, off);
    }

    /// Writes a boolean into bit `pos` of the byte at `a`.
    pub(crate) fn write_bit_at(&mut self, a: Addr, pos: u8, val: B) {
        if let B::Bit { v, pos: from } = val
            && self.write_bit_folded(a, pos, v, from)
        {
            return;
        }
        let old = self.byte(a);
        let mask = 1i64 << pos;
        let new = match val {
            B::K(true) => self.b.ins().bor_imm_s(old, mask),
            B::K(false) => self.b.ins().band_imm_s(old, !mask & 0xFF),
            B::Bit { v, pos: from } => {
                let s = super::value::align(&mut self.b, v, from, pos);
                let bitv = self.b.ins().band_imm_s(s, mask);
                let cleared = self.b.ins().band_imm_s(old, !mask & 0xFF);
                self.b.ins().bor(cleared, bitv)
            }
            B::Not { v, pos: from } => {
                // (old AND NOT m) OR (NOT v AND m) = (old OR m) XOR (v AND m): no `not`.
                let s = super::value::align(&mut self.b, v, from, pos);
                let bitv = self.b.ins().band_imm_s(s, mask);
                let set = self.b.ins().bor_imm_s(old, mask);
                self.b.ins().bxor(set, bitv)
            }
        };
        self.set_byte(a, new);
    }

    /// Writes bit `from` of `v` into bit `pos` of the byte at `a` as `old XOR ((old XOR v) AND
    /// m)`, both `old`s being 32-bit loads from `a` that x86 folds into the two `xor`s: five
    /// instructions where loading the byte, clearing, masking and merging take six. Only where
    /// the byte is not cached and the four bytes from `a` are cold (see [`StoreLog`]); false
    /// (nothing emitted) otherwise. The second load goes through an opaque copy of the image
    /// pointer so that Cranelift does not merge the two loads into one register operand.
    ///
    /// [`StoreLog`]: super::cache::StoreLog
    fn write_bit_folded(&mut self, a: Addr, pos: u8, v: Value, from: u8) -> bool {
        if a.local || self.block.cache.get(a).is_some() || !self.cold_window(a) {
            return false;
        }
        let s = super::value::align(&mut self.b, v, from, pos);
        let first = self.load_window(a);
        let diff = self.b.ins().bxor(s, first);
        let diff = self.b.ins().band_imm_s(diff, 1i64 << pos);
        // `crate::rebase` recognises exactly this form (to give the load a short
        // displacement): a change here is a change there.
        let pair = self.b.ins().iconcat(self.func.image, self.func.image);
        let (image, _) = self.b.ins().isplit(pair);
        let second = self.b.ins().load(I32, super::mf(), image, Self::off32(a));
        let new = self.b.ins().bxor(diff, second);
        self.store_low_byte(a, new);
        true
    }

    /// Evaluates a contact (compares may take a fatal exit).
    fn contact(&mut self, c: &Contact) -> (B, bool) {
        match *c {
            Contact::Bit { bit, negated } => (self.read_bit(bit), negated),
            Contact::ImmediateInput { bit, negated }
                if bit.area != Area::I || bit.byte >= self.env.layout.area_size(Area::I) =>
            {
                (B::K(false), negated)
            }
            Contact::ImmediateInput { bit, negated } => {
                let a = Addr::img(self.env.layout.phys_in + bit.byte);
                let v = self.byte(a);
                (B::Bit { v, pos: bit.bit }, negated)
            }
            Contact::Compare {
                ty,
                op,
                ref lhs,
                ref rhs,
            } => (self.compare(ty, op, lhs, rhs), false),
        }
    }

    fn compare(&mut self, ty: CmpType, op: CmpOp, lhs: &Operand, rhs: &Operand) -> B {
        let w = ty.width();
        let fail = OnFail::Fatal(FatalCode::CompareIndirect);
        let a = self.read_operand(lhs, w, fail);
        let b = self.read_operand(rhs, w, fail);
        let r = match ty {
            CmpType::Byte => self.b.ins().icmp(int_cc(op, false), a, b),
            CmpType::Int => {
                let a = self.b.ins().ireduce(I16, a);
                let b = self.b.ins().ireduce(I16, b);
                self.b.ins().icmp(int_cc(op, true), a, b)
            }
            CmpType::DInt => self.b.ins().icmp(int_cc(op, true), a, b),
            CmpType::Real => {
                let fa = self
                    .b
                    .ins()
                    .bitcast(F32, cranelift_codegen::ir::MemFlagsData::new(), a);
                let fb = self
                    .b
                    .ins()
                    .bitcast(F32, cranelift_codegen::ir::MemFlagsData::new(), b);
                let nan = self.b.ins().fcmp(FloatCC::Unordered, fa, fb);
                self.fatal_if(nan, FatalCode::CompareNaN);
                self.b.ins().fcmp(float_cc(op), fa, fb)
            }
        };
        let v = self.b.ins().uextend(I32, r);
        B::Bit { v, pos: 0 }
    }

    /// `LD`/`LDN` (and the contact forms): pushes the contact.
    pub(crate) fn load(&mut self, c: &Contact) {
        let (v, neg) = self.contact(c);
        let v = if neg { v.not(&mut self.b) } else { v };
        self.block.stack.push(v);
    }

    /// `A`/`AN`/`O`/`ON` (and the contact forms): combines the contact into S0.
    pub(crate) fn combine(&mut self, c: &Contact, and: bool) {
        let (v, neg) = self.contact(c);
        let v = if neg { v.not(&mut self.b) } else { v };
        let top = self.block.stack.top();
        let want = self.bit_target();
        let r = if and {
            top.and_toward(&mut self.b, v, want)
        } else {
            top.or_toward(&mut self.b, v, want)
        };
        let r = self.anchor(r);
        self.block.stack.set_top(r);
    }

    /// Where the value this op leaves in S0 is wanted ([`PouInfo::bit_target`]).
    ///
    /// [`PouInfo::bit_target`]: crate::analysis::PouInfo
    fn bit_target(&self) -> Option<u8> {
        self.env.info[self.func.pou.index()]
            .bit_target
            .get(self.op)
            .copied()
            .flatten()
    }

    /// `NOT`.
    pub(crate) fn not(&mut self) {
        let t = self.block.stack.top().not(&mut self.b);
        self.block.stack.set_top(t);
    }

    /// `ALD`/`OLD`: pops S0 and combines it into the new S0.
    pub(crate) fn combine_block(&mut self, and: bool) {
        let s0 = self.block.stack.pop();
        let s1 = self.block.stack.top();
        let want = self.bit_target();
        let r = if and {
            s0.and_toward(&mut self.b, s1, want)
        } else {
            s0.or_toward(&mut self.b, s1, want)
        };
        let r = self.anchor(r);
        self.block.stack.set_top(r);
    }

    /// `LPS`.
    pub(crate) fn dup(&mut self) {
        let t = self.block.stack.top();
        self.block.stack.push(t);
    }

    /// `LRD`.
    pub(crate) fn read_second(&mut self) {
        let s1 = self.block.stack.level(1);
        self.block.stack.set_top(s1);
    }

    /// `LDS n`.
    pub(crate) fn pick(&mut self, n: u8) {
        let v = self.block.stack.level(usize::from(n));
        self.block.stack.push(v);
    }

    /// `AENO`.
    pub(crate) fn and_eno(&mut self) {
        let a = self.sched(Sched::ENO);
        let top = self.block.stack.top();
        let v = self.byte(a);
        let eno = match self.block.cache.eno {
            // The byte is still what the box stored, and the box's ENO implies this top.
            Some(f) if f.byte == v && f.top == top => {
                self.block.stack.set_top(f.value);
                return;
            }
            Some(f) if f.byte == v => f.value,
            _ => B::Bit { v, pos: 0 },
        };
        let t = top.and(&mut self.b, eno);
        self.block.stack.set_top(t);
    }

    /// `=`/`=I`: the coil writes PF.
    pub(crate) fn assign(&mut self, bit: BitLoc, immediate: bool) {
        let pf = self.pf();
        if let Some(off) = self.env.resident.slot(bit) {
            self.write_resident(off, pf);
        } else {
            let a = self.bit_byte(bit);
            self.write_bit_at(a, bit.bit, pf);
        }
        if immediate && bit.area == Area::Q && bit.byte < self.env.layout.area_size(Area::Q) {
            let a = Addr::img(self.env.layout.phys_out + bit.byte);
            self.write_bit_at(a, bit.bit, pf);
        }
    }

    /// Pins a computed boolean to the op that computed it (at `--opt speed` only).
    ///
    /// With the e-graph on, every pure instruction is placed just before its first use by a
    /// side-effecting one (a coil's store), so a whole rung's ALU code landed after all of its
    /// loads and every loaded byte stayed live across the rung: the allocator spilled ~560
    /// values per 10k ops. Passing the value through `isplit(iconcat(v, image))`, a two-result
    /// instruction that the e-graph keeps in place, keeps the ALU code at its op (spills drop
    /// to ~10). It costs no machine instruction: the 32-bit ALU result is already
    /// zero-extended and the halves are just registers. It also hides the value from the
    /// e-graph's `NOT (a AND NOT b)` rewrite (see `value::is_andn`) and, being a lowering
    /// root, stops a later double use from marking the whole rung as used twice.
    pub(crate) fn anchor(&mut self, x: B) -> B {
        use cranelift_codegen::ir::{Opcode, types::I64};
        let (v, pos, neg) = match x {
            B::Bit { v, pos } => (v, pos, false),
            B::Not { v, pos } => (v, pos, true),
            B::K(_) => return x,
        };
        if self.env.opt == crate::OptLevel::None {
            return x;
        }
        let dfg = &self.b.func.dfg;
        // Only 32-bit ALU results zero their upper half for free (a load would need a mov).
        let alu = dfg.value_def(v).inst().is_some_and(|i| {
            matches!(
                dfg.insts[i].opcode(),
                Opcode::Band | Opcode::Bor | Opcode::Bxor | Opcode::Ishl | Opcode::Ushr
            )
        });
        if !alu {
            return x;
        }
        let wide = self.b.ins().uextend(I64, v);
        let pair = self.b.ins().iconcat(wide, self.func.image);
        let (lo, _) = self.b.ins().isplit(pair);
        let v = self.b.ins().ireduce(I32, lo);
        if neg {
            B::Not { v, pos }
        } else {
            B::Bit { v, pos }
        }
    }

    /// `EU`/`ED` inline with the runtime's rules (`edge::execute`): the gate policy of
    /// the program family's gate policy and the first-scan switch of [`Rules`](stljit_runtime::rules::Rules).
    pub(crate) fn edge(&mut self, slot: u16, falling: bool) {
        if slot >= self.env.layout.profile.profile().max_edges {
            self.block.stack.set_top(B::K(false));
            return;
        }
        let (v, frozen_unless) = match self.gate_policy() {
            // A closed gate is an input of 0: `v = S0 AND gate`, the memory takes it.
            GatePolicy::S7Scr => (self.pf(), None),
            // A closed gate freezes the memory and outputs 0.
            GatePolicy::OmronInterlock => match self.block.gate {
                B::K(false) => {
                    self.block.stack.set_top(B::K(false));
                    return;
                }
                B::K(true) => (self.block.stack.top(), None),
                g => (self.block.stack.top(), Some(g)),
            },
        };
        // The input as a clean 0/1 first: the edge byte stores it, and at bit 0, where the
        // edge byte and the first-scan flag are, it needs no further alignment.
        let v01 = v.to01(&mut self.b);
        let v = match v {
            B::K(_) => v,
            _ => B::Bit { v: v01, pos: 0 },
        };
        let at = Addr::img(self.env.layout.edges + u32::from(slot));
        let mem = self.byte(at);
        let memb = B::Bit { v: mem, pos: 0 };
        let mut out = if falling {
            memb.and_not(&mut self.b, v)
        } else {
            v.and_not(&mut self.b, memb)
        };
        let suppress = self.env.rules.first_scan_suppresses();
        let mask = self.env.resident.first_scan_mask().filter(|_| suppress);
        if suppress && mask.is_none() {
            let first = self.byte(self.sched(Sched::FIRST_SCAN));
            out = out.and_not(&mut self.b, B::Bit { v: first, pos: 0 });
        }
        let new_mem = match frozen_unless {
            None => v01,
            Some(g) => {
                out = out.and(&mut self.b, g);
                let open = g.cond(&mut self.b);
                self.b.ins().select(open, v01, mem)
            }
        };
        self.set_byte(at, new_mem);
        if let Some(at) = mask.filter(|_| out != B::K(false)) {
            // Loaded after the edge byte's store, so that x86 folds the load into the `and`
            // (a load does not move past a store). All its bits are alike: it applies at
            // whatever bit `out` is.
            let mask = self.b.ins().load(I32, super::mf(), self.func.image, at);
            let pos = match out {
                B::Bit { pos, .. } | B::Not { pos, .. } => pos,
                B::K(_) => 0,
            };
            out = out.and(&mut self.b, B::Bit { v: mask, pos });
        }
        self.block.stack.set_top(out);
    }

    /// `S`/`R`/`SI`/`RI`: inline when the count is a constant; otherwise the runtime does it.
    pub(crate) fn set_range(
        &mut self,
        start: BitLoc,
        count: &Operand,
        value: bool,
        immediate: bool,
    ) {
        let pf = self.pf();
        if pf == B::K(false) {
            return;
        }
        if let Operand::Const(k) = *count {
            let run = match set_range_run(self.env.layout, start, k & Width::Byte.mask()) {
                Ok(None) => return,
                Ok(Some(run)) => run,
                Err(e) => {
                    self.guarded(pf, |s| s.record_error_k(e));
                    return;
                }
            };
            if run.count <= MAX_INLINE_RANGE {
                // Resident bits one by one in the shadow (`old OR PF`, `old AND NOT PF`), the
                // others by masks on their bytes.
                let mut bits: Vec<(Addr, u8)> = Vec::new();
                for (byte, bit) in run.bits() {
                    let loc = BitLoc {
                        area: start.area,
                        byte,
                        bit,
                    };
                    match self.env.resident.slot(loc) {
                        Some(off) => {
                            let old = self.b.ins().uload8(I32, mf(), self.func.image, off);
                            let new = self.set_or_reset(B::Bit { v: old, pos: 0 }, pf, value);
                            self.write_resident(off, new);
                            if immediate && start.area == Area::Q {
                                // The physical bit takes the same conditional write.
                                let pa = Addr::img(self.env.layout.phys_out + byte);
                                let (v, at) = self.test_byte(pa);
                                let old = B::Bit { v, pos: at + bit };
                                let new = self.set_or_reset(old, pf, value);
                                self.write_bit_at(pa, bit, new);
                            }
                        }
                        None => bits.push((self.area_addr(start.area, byte), bit)),
                    }
                }
                if bits.is_empty() {
                    return;
                }
                let phys = immediate && start.area == Area::Q;
                let out = self.env.layout.phys_out;
                let base_q = self.env.layout.base(Area::Q);
                // Conditional write without branching: new = pf ? value : old, one
                // read-modify-write per byte (the bits of a range are consecutive).
                let mut masks: Vec<(Addr, i64)> = Vec::new();
                for (a, pos) in bits {
                    match masks.last_mut() {
                        Some((la, m)) if *la == a => *m |= 1 << pos,
                        _ => masks.push((a, 1 << pos)),
                    }
                }
                if let [(a, m)] = masks[..]
                    && m.count_ones() == 1
                    && !matches!(pf, B::K(_))
                {
                    // One bit: PF aligned to it and isolated, no spread.
                    let t = pf.at_bit(&mut self.b, m.trailing_zeros() as u8);
                    self.merge_mask(a, t, value);
                    if phys {
                        let pa = Addr::img(out + (a.off - base_q));
                        self.merge_mask(pa, t, value);
                    }
                    return;
                }
                // All ones where PF holds, zero elsewhere.
                let spread = match pf {
                    B::K(_) => None,
                    B::Bit { v, pos } => {
                        // PF's bit to the sign, then spread by an arithmetic shift: two
                        // instructions where isolating the bit and negating takes three.
                        let top = self.b.ins().ishl_imm_s(v, 31 - i64::from(pos));
                        Some(self.b.ins().sshr_imm_s(top, 31))
                    }
                    B::Not { .. } => {
                        let p01 = pf.to01(&mut self.b);
                        Some(self.b.ins().ineg(p01))
                    }
                };
                for (a, m) in masks {
                    self.cond_write_mask(a, m, spread, value);
                    if phys {
                        let pa = Addr::img(out + (a.off - base_q));
                        self.cond_write_mask(pa, m, spread, value);
                    }
                }
                return;
            }
        }
        self.set_range_helper(pf, start, count, value, immediate);
    }

    /// One bit of `S` (`value`) or `R` under power flow `pf`: `old OR PF`, `old AND NOT PF`.
    fn set_or_reset(&mut self, old: B, pf: B, value: bool) -> B {
        if value {
            old.or(&mut self.b, pf)
        } else {
            old.and_not(&mut self.b, pf)
        }
    }

    /// Sets (or clears) the bits of `mask` where `spread` (PF as all ones or zero; `None` for
    /// PF = 1) holds, leaves them elsewhere.
    fn cond_write_mask(&mut self, a: Addr, mask: i64, spread: Option<Value>, value: bool) {
        let Some(sp) = spread else {
            let old = self.byte(a);
            let new = if value {
                self.b.ins().bor_imm_s(old, mask)
            } else {
                self.b.ins().band_imm_s(old, !mask & 0xFF)
            };
            self.set_byte(a, new);
            return;
        };
        let m = self.b.ins().band_imm_s(sp, mask);
        self.merge_mask(a, m, value);
    }

    /// Sets (`value`) or clears the bits set in `m` (an `i32` that is zero outside the byte's
    /// bits) in the byte at `a`. The old byte is a folded 32-bit load where the four bytes
    /// from `a` are cold and uncached (the `or`/`andn` takes it as its memory operand).
    fn merge_mask(&mut self, a: Addr, m: Value, value: bool) {
        let folded = self.block.cache.get(a).is_none() && self.cold_window(a);
        let old = if folded {
            self.load_window(a)
        } else {
            self.byte(a)
        };
        let new = if value {
            self.b.ins().bor(old, m)
        } else {
            self.b.ins().band_not(old, m)
        };
        if folded {
            self.store_low_byte(a, new);
        } else {
            self.set_byte(a, new);
        }
    }

    /// Runs `f` only where `pf` holds (a branch unless `pf` is constant); the cache survives.
    pub(crate) fn guarded(&mut self, pf: B, f: impl FnOnce(&mut Self)) {
        match pf {
            B::K(false) => {}
            B::K(true) => f(self),
            _ => {
                let c = pf.cond(&mut self.b);
                self.diamond(c, f, |_| {});
            }
        }
    }

    /// Reads a byte operand used as a count (S/R/timer resets).
    pub(crate) fn count_value(&mut self, count: &Operand, fail: OnFail) -> Value {
        self.read_operand(count, Width::Byte, fail)
    }
}

fn int_cc(op: CmpOp, signed: bool) -> IntCC {
    match (op, signed) {
        (CmpOp::Eq, _) => IntCC::Equal,
        (CmpOp::Ne, _) => IntCC::NotEqual,
        (CmpOp::Ge, true) => IntCC::SignedGreaterThanOrEqual,
        (CmpOp::Le, true) => IntCC::SignedLessThanOrEqual,
        (CmpOp::Gt, true) => IntCC::SignedGreaterThan,
        (CmpOp::Lt, true) => IntCC::SignedLessThan,
        (CmpOp::Ge, false) => IntCC::UnsignedGreaterThanOrEqual,
        (CmpOp::Le, false) => IntCC::UnsignedLessThanOrEqual,
        (CmpOp::Gt, false) => IntCC::UnsignedGreaterThan,
        (CmpOp::Lt, false) => IntCC::UnsignedLessThan,
    }
}

fn float_cc(op: CmpOp) -> FloatCC {
    match op {
        CmpOp::Eq => FloatCC::Equal,
        CmpOp::Ne => FloatCC::NotEqual,
        CmpOp::Ge => FloatCC::GreaterThanOrEqual,
        CmpOp::Le => FloatCC::LessThanOrEqual,
        CmpOp::Gt => FloatCC::GreaterThan,
        CmpOp::Lt => FloatCC::LessThan,
    }
}
