//! The Omron CP timers, counters and data boxes: calls into the runtime's `omron_image`
//! (through the `stljit_rt_omron_*` shims), which both engines share.

use super::Lower;
use super::cache::Addr;
use super::mem::OnFail;
use super::state::{BoxState, Pred};
use super::value::{B, Stack};
use crate::helpers::Helper;
use cranelift_codegen::ir::{
    InstBuilder, Value,
    condcodes::IntCC,
    types::{I16, I32, I64},
};
use std::cmp::Ordering;
use stljit_core::ir::{
    BoxOperands, OmronArith, OmronBox, OmronCounterKind, OmronTimerKind, Operand,
};
use stljit_core::layout::{CounterState, Sched, TimerState};
use stljit_core::{Area, FatalCode, Width};
use stljit_runtime::ffi::{OMRON_ARITH_HAS_RESULT, OMRON_NO_OPERAND};
use stljit_runtime::omron::arith::{self, BinarySum};
use stljit_runtime::omron::data;
use stljit_runtime::omron::flags::compare_writes;
use stljit_runtime::omron::{Flag, FlagWrites};
use stljit_runtime::omron_image::{self, CounterFixed, CounterLevels};

impl Lower<'_, '_> {
    /// The Omron value of a direct operand: a word, or a double word with its low 16 bits in
    /// the lower-numbered word (a location's big-endian dword with its halves swapped;
    /// constants are Omron values already).
    fn omron_value(&mut self, o: &Operand, double: bool) -> Value {
        let width = if double { Width::DWord } else { Width::Word };
        // Omron operands are direct: no pointer can fail.
        let v = self.read_operand(o, width, OnFail::Fatal(FatalCode::CompareIndirect));
        if double && matches!(o, Operand::Mem(_)) {
            self.swap_halves(v)
        } else {
            v
        }
    }

    /// Logic-stack levels 0..=2 packed (bit i = S_i): the conditions the Omron timers and
    /// counters read.
    fn omron_conditions(&mut self) -> Value {
        let levels = Stack {
            lv: (0..3).map(|i| self.block.stack.level(i)).collect(),
        };
        levels.to_reg(&mut self.b)
    }

    /// `TIM`…`TTIMX n sv`: the fast shim on the timer's own bytes and the scan time, its flag
    /// writes applied here. With a constant set value under an open gate, a reset (EC OFF) and
    /// a start (EC ON, not running) are the runtime's outcomes computed now
    /// (`omron_image::timer_reset_outcome`, `timer_start_outcome`), stored inline: only a
    /// running timer calls.
    pub(crate) fn omron_timer(&mut self, kind: OmronTimerKind, n: u16, sv: &Operand) {
        let l = self.env.layout;
        if u32::from(n) >= l.area_size(Area::TimerBit) {
            return; // the verifier keeps timer numbers inside the profile
        }
        let [v, b, s] = l.timer_bytes(n).map(|(off, len)| (Addr::img(off), len));
        let ranges = [v, b, s, (self.sched(Sched::T_NOW), 8)];
        let (reset, start) = match (*sv, self.block.gate) {
            (Operand::Const(k), B::K(true)) => (
                omron_image::timer_reset_outcome(kind, k as u16),
                omron_image::timer_start_outcome(kind, k as u16),
            ),
            _ => (None, None),
        };
        let sv = self.omron_value(sv, false);
        let h = Helper::omron_timer_fast(kind);
        let call = move |s: &mut Self| s.omron_fast(h, &ranges, sv);
        let on = move |s: &mut Self| match start {
            Some(outcome) => {
                let running = s.byte(ranges[2].0.plus(TimerState::RUN));
                s.diamond(running, call, move |s| s.store_timer_start(n, outcome));
            }
            None => call(s),
        };
        match (reset, self.block.stack.top()) {
            (Some(r), B::K(false)) => self.store_timer_reset(n, r),
            (_, B::K(true)) => on(self),
            (Some(r), ec) => {
                let c = ec.cond(&mut self.b);
                self.diamond(c, on, move |s| s.store_timer_reset(n, r));
            }
            (None, _) => call(self),
        }
    }

    /// Stores a timer start computed at compile time: PV, flag, the flag writes, `running`
    /// ON, no unconverted milliseconds and the scan's time as the last execution.
    fn store_timer_start(&mut self, n: u16, (pv, flag, w): ([u8; 2], u8, FlagWrites)) {
        let [(v, _), (b, _), (s, _)] = self.env.layout.timer_bytes(n);
        for (at, byte) in [
            (v, pv[0]),
            (v + 1, pv[1]),
            (b, flag),
            (s + TimerState::RUN, 1),
            (s + TimerState::TOF, 0),
        ] {
            let k = self.iconst(I32, i64::from(byte));
            self.set_byte(Addr::img(at), k);
        }
        // `LAST := T_NOW`: both native-endian u64, copied as two 4-byte halves (any byte order
        // copies the same bytes).
        let (now, last) = (self.sched(Sched::T_NOW), Addr::img(s + TimerState::LAST));
        for half in [0, 4] {
            let word = self.read_static(now.plus(half), Width::DWord);
            self.write_static(last.plus(half), Width::DWord, word);
        }
        self.put_constant_flags(w);
    }

    /// Stores a timer reset computed at compile time: PV, flag, `running` and the flag writes.
    fn store_timer_reset(&mut self, n: u16, (pv, flag, run, w): ([u8; 2], u8, u8, FlagWrites)) {
        let l = self.env.layout;
        let [(v, _), (b, _), (s, _)] = l.timer_bytes(n);
        for (at, byte) in [
            (v, pv[0]),
            (v + 1, pv[1]),
            (b, flag),
            (s + TimerState::RUN, run),
        ] {
            let k = self.iconst(I32, i64::from(byte));
            self.set_byte(Addr::img(at), k);
        }
        self.put_constant_flags(w);
    }

    /// `CNT`…`CNTRX n sv`: as [`Lower::omron_timer`]. With a constant set value under an open
    /// gate, the runtime's outcomes of a reset and of a quiet execution (no count edge,
    /// `omron_image::counter_fixed`, computed now) are stored inline; only a count calls.
    pub(crate) fn omron_counter(&mut self, kind: OmronCounterKind, n: u16, sv: &Operand) {
        let l = self.env.layout;
        if u32::from(n) >= l.area_size(Area::CounterBit) {
            return;
        }
        let ranges = l.counter_bytes(n).map(|(off, len)| (Addr::img(off), len));
        let fixed = match (*sv, self.block.gate) {
            (Operand::Const(k), B::K(true)) => omron_image::counter_fixed(kind, k as u16),
            _ => CounterFixed {
                reset: None,
                quiet: None,
            },
        };
        let sv = self.omron_value(sv, false);
        let h = Helper::omron_counter_fast(kind);
        let call = move |s: &mut Self| s.omron_fast(h, &ranges, sv);
        let levels = CounterLevels::of(kind);
        let count = self.block.stack.level(levels.count);
        let reset = self.block.stack.level(levels.reset);
        let dec = levels.dec.map(|l| self.block.stack.level(l));
        let state = ranges[2].0;
        let inputs = [
            (Some(count), CounterState::PREV_UP),
            (dec, CounterState::PREV_DOWN),
        ];
        // The count edges: an input ON whose memory is OFF.
        let mut edge = B::K(false);
        if fixed.quiet.is_some() {
            for (input, at) in inputs {
                if let Some(input) = input {
                    let memory = self.byte(state.plus(at));
                    let rising = input.and_not(&mut self.b, B::Bit { v: memory, pos: 0 });
                    edge = edge.or(&mut self.b, rising);
                }
            }
        }
        let record = move |s: &mut Self| {
            for (input, at) in inputs {
                if let Some(input) = input {
                    let v = input.to01(&mut s.b);
                    s.set_byte(state.plus(at), v);
                }
            }
        };
        let on_reset = move |s: &mut Self| match fixed.reset {
            Some((pv, flag, w)) => {
                let (value, bit) = (ranges[0].0, ranges[1].0);
                for (at, byte) in [(value, pv[0]), (value.plus(1), pv[1]), (bit, flag)] {
                    let k = s.iconst(I32, i64::from(byte));
                    s.set_byte(at, k);
                }
                record(s);
                s.put_constant_flags(w);
            }
            None => call(s),
        };
        let otherwise = move |s: &mut Self| match fixed.quiet {
            Some(w) if edge == B::K(false) => {
                record(s);
                s.put_constant_flags(w);
            }
            Some(w) if edge != B::K(true) => {
                let c = edge.cond(&mut s.b);
                s.diamond(c, call, move |s| {
                    record(s);
                    s.put_constant_flags(w);
                });
            }
            _ => call(s),
        };
        match reset {
            B::K(true) => on_reset(self),
            B::K(false) => otherwise(self),
            _ if fixed.reset.is_none() && fixed.quiet.is_none() => call(self),
            _ => {
                let c = reset.cond(&mut self.b);
                self.diamond(c, on_reset, otherwise);
            }
        }
    }

    /// The condition flags := the constant writes `w`.
    fn put_constant_flags(&mut self, w: FlagWrites) {
        for byte in 0..2u32 {
            let m = (w.mask >> (8 * byte)) & 0xFF;
            if m == 0 {
                continue;
            }
            let val = (w.value >> (8 * byte)) & m;
            let a = self.area_addr(Area::Flags, byte);
            let old = self.byte(a);
            let kept = self.b.ins().band_imm_s(old, i64::from(!m & 0xFF));
            let new = self.b.ins().bor_imm_s(kept, i64::from(val));
            self.set_byte(a, new);
        }
    }

    /// Calls a fast Omron shim on the image ranges `ranges` (pointers, in order) with `ctl`
    /// (stack levels 0–2, the gate) and `sv`, then applies the flag writes it returns.
    fn omron_fast(&mut self, h: Helper, ranges: &[(Addr, u32)], sv: Value) {
        let stack = self.omron_conditions();
        let ctl = self.fast_ctl(stack);
        let image = self.func.image;
        let mut args: Vec<Value> = ranges
            .iter()
            .map(|(a, _)| self.b.ins().iadd_imm_s(image, i64::from(a.off)))
            .collect();
        args.extend([ctl, sv]);
        let packed = self.call_touching(h, &args, ranges);
        self.apply_packed_flags(packed);
    }

    /// The condition flags := the packed writes of a fast shim (`ffi::pack_flag_writes`: mask
    /// in bits 16–31, values in bits 0–15).
    fn apply_packed_flags(&mut self, packed: Value) {
        for byte in 0..2u32 {
            let a = self.area_addr(Area::Flags, byte);
            let old = self.byte(a);
            let m = self.b.ins().ushr_imm_s(packed, i64::from(16 + 8 * byte));
            let m = self.b.ins().band_imm_s(m, 0xFF);
            let v = self.b.ins().ushr_imm_s(packed, i64::from(8 * byte));
            let v = self.b.ins().band_imm_s(v, 0xFF);
            let kept = self.b.ins().band_not(old, m);
            let new = self.b.ins().bor(kept, v);
            self.set_byte(a, new);
        }
    }

    /// `MOV`, `CMP`, arithmetic: when PF. MOV/MOVL and the compares are inlined branch-free
    /// (their writes keep the old bytes where PF is 0); the arithmetic calls the runtime's box.
    pub(crate) fn omron_box(&mut self, bx: &OmronBox) {
        let pf = self.pf();
        if pf == B::K(false) {
            return;
        }
        if Self::has_refs(bx) {
            let bx = *bx;
            self.guarded(pf, move |s| s.omron_box_refs(&bx));
            return;
        }
        match *bx {
            OmronBox::Move { double, src, dst } => {
                self.omron_free(pf, |s| s.omron_move(double, &src, &dst));
                return;
            }
            OmronBox::Compare {
                double,
                signed,
                lhs,
                rhs,
            } => {
                self.omron_free(pf, |s| s.omron_compare(double, signed, &lhs, &rhs));
                return;
            }
            OmronBox::Arith { op, lhs, rhs, dst } if BinarySum::of(op).is_some() => {
                self.omron_free(pf, |s| s.omron_binary_sum(op, &lhs, &rhs, &dst));
                return;
            }
            OmronBox::Arith { op, lhs, rhs, dst } if op.result_words() <= 2 => {
                // A branch, not branch-free: the call is skipped where PF is 0.
                self.guarded(pf, |s| s.omron_arith(op, &lhs, &rhs, &dst));
                return;
            }
            OmronBox::Arith { .. } | OmronBox::SetIndex { .. } | OmronBox::Flags { .. } => {}
        }
        let bx = *bx;
        self.guarded(pf, move |s| {
            let code = s.iconst(I32, i64::from(omron_image::box_code(&bx)));
            let zero = s.iconst(I32, 0);
            let (a, b, dst) = match bx {
                OmronBox::Move { double, src, dst } => {
                    (s.omron_value(&src, double), zero, Some(dst))
                }
                OmronBox::Compare {
                    double, lhs, rhs, ..
                } => (
                    s.omron_value(&lhs, double),
                    s.omron_value(&rhs, double),
                    None,
                ),
                OmronBox::Arith { op, lhs, rhs, dst } => {
                    let double = op.operand_words() == 2;
                    (
                        s.omron_value(&lhs, double),
                        s.omron_value(&rhs, double),
                        Some(dst),
                    )
                }
                OmronBox::SetIndex { ea, ir } => {
                    let dst = Operand::Mem(stljit_core::ir::Loc {
                        area: Area::IndexReg,
                        offset: 4 * u32::from(ir),
                    });
                    (s.iconst(I32, i64::from(ea)), zero, Some(dst))
                }
                OmronBox::Flags { .. } => (zero, zero, None),
            };
            let at = match dst {
                Some(Operand::Mem(loc)) => s.loc_addr(loc).off,
                // The verifier keeps destinations direct and writable.
                _ => 0,
            };
            let at = s.iconst(I32, i64::from(at));
            s.call_helper(Helper::OmronBox, &[code, a, b, at]);
        });
    }
}

impl Lower<'_, '_> {
    /// Whether a box has an Omron indirect operand (resolved in the runtime).
    fn has_refs(bx: &OmronBox) -> bool {
        let is_ref = |o: &Operand| matches!(o, Operand::Omron(_));
        match bx {
            OmronBox::Move { src, dst, .. } => is_ref(src) || is_ref(dst),
            OmronBox::Compare { lhs, rhs, .. } => is_ref(lhs) || is_ref(rhs),
            OmronBox::Arith { lhs, rhs, dst, .. } => is_ref(lhs) || is_ref(rhs) || is_ref(dst),
            OmronBox::SetIndex { .. } | OmronBox::Flags { .. } => false,
        }
    }

    /// A box with indirect operands: the direct ones read here, everything else (resolution
    /// in operand order, the step of an index register, AER, the box) in the runtime
    /// (`stljit_rt_omron_box_refs`), which may touch any byte.
    fn omron_box_refs(&mut self, bx: &OmronBox) {
        let code = omron_image::box_code(bx);
        let BoxOperands {
            sources: [lhs, rhs],
            dst,
            src_words,
            dst_words,
        } = bx.operands();
        let mut args = vec![self.iconst(I32, i64::from(code))];
        for (o, is_dst) in [(lhs, false), (rhs, false), (dst, true)] {
            let (r, v) = match o {
                None => (OMRON_NO_OPERAND, None),
                Some(Operand::Omron(r)) => (omron_image::pack_ref(r), None),
                Some(Operand::Mem(loc)) if is_dst => (
                    0,
                    Some(self.iconst(I32, i64::from(self.area_addr(loc.area, loc.offset).off))),
                ),
                Some(o) => (0, Some(self.omron_value(&o, src_words == 2))),
            };
            let v = v.unwrap_or_else(|| self.iconst(I32, 0));
            let r = self.iconst(I32, i64::from(r));
            args.extend([r, v]);
        }
        args.push(self.iconst(I32, i64::from(src_words | dst_words << 8)));
        self.call_helper(Helper::OmronBoxRefs, &args);
    }

    /// Runs `f` as a branch-free box under `pf`: every write through the cache keeps the old
    /// value where `pf` is 0 (no ENO: Omron boxes have none).
    fn omron_free(&mut self, pf: B, f: impl FnOnce(&mut Self)) {
        self.in_box = BoxState::new(true);
        self.in_box.pred = match pf {
            B::K(_) => None,
            _ => Some(Pred::new(pf, &mut self.b)),
        };
        f(self);
        self.in_box = BoxState::default();
    }

    /// Condition-flag byte `byte` (0 or 1) of the `Flags` area := its bits outside `mask` kept,
    /// the bits of `bits` (within `mask`) set.
    fn put_omron_flags(&mut self, byte: u32, mask: u16, bits: Value) {
        let m = i64::from((mask >> (8 * byte)) & 0xFF);
        if m == 0 {
            return;
        }
        let a = self.area_addr(Area::Flags, byte);
        let old = self.byte(a);
        let kept = self.b.ins().band_imm_s(old, !m & 0xFF);
        let new = self.b.ins().bor(kept, bits);
        self.set_byte_pred(a, new);
    }

    /// `flag` (a 0/1 value) moved to its bit inside its flag byte.
    fn flag_at(&mut self, flag: Flag, v: Value) -> Value {
        let bit = flag.system_bit().bit_loc().bit;
        let v = self.b.ins().uextend(I32, v);
        self.b.ins().ishl_imm_s(v, i64::from(bit))
    }

    /// The condition flags := `values` (0/1 values) for the flags in `mask` (the rule's
    /// `FlagWrites::mask`); a flag of `mask` not in `values` is written OFF.
    fn put_flag_values(&mut self, mask: u16, values: &[(Flag, Value)]) {
        let mut bytes = [None, None];
        for &(flag, v) in values {
            let at = self.flag_at(flag, v);
            let byte = flag.system_bit().bit_loc().byte as usize;
            bytes[byte] = Some(match bytes[byte] {
                Some(acc) => self.b.ins().bor(acc, at),
                None => at,
            });
        }
        for (byte, bits) in bytes.into_iter().enumerate() {
            let bits = bits.unwrap_or_else(|| self.iconst(I32, 0));
            self.put_omron_flags(byte as u32, mask, bits);
        }
    }

    /// `MOV`/`MOVL` inline with `data::mov`'s flags: ER OFF, `=` when the value is 0, `N` its
    /// top bit.
    fn omron_move(&mut self, double: bool, src: &Operand, dst: &Operand) {
        let v = self.omron_value(src, double);
        if let Operand::Mem(loc) = *dst {
            let a = self.area_addr(loc.area, loc.offset);
            let stored = if double { self.swap_halves(v) } else { v };
            let width = if double { Width::DWord } else { Width::Word };
            self.write_static(a, width, stored);
        }
        let (_, writes) = data::mov(double, 0);
        let top = if double { 31 } else { 15 };
        let zero = self.b.ins().icmp_imm_s(IntCC::Equal, v, 0);
        let n = self.b.ins().ushr_imm_s(v, top);
        let n = self.b.ins().band_imm_s(n, 1);
        let n = self.b.ins().ireduce(cranelift_codegen::ir::types::I8, n);
        self.put_flag_values(writes.mask, &[(Flag::Eq, zero), (Flag::N, n)]);
    }

    /// `CMP`/`CMPL`/`CPS`/`CPSL` inline: the order of the operands as an index (0 less, 1
    /// equal, 2 greater) selects each flag byte's bits from a table of the runtime's own
    /// writes for the three orders (`flags::compare_writes`), so no flag formula is restated.
    fn omron_compare(&mut self, double: bool, signed: bool, lhs: &Operand, rhs: &Operand) {
        let a = self.omron_value(lhs, double);
        let b = self.omron_value(rhs, double);
        let (a, b) = if double || !signed {
            (a, b)
        } else {
            (self.sext(a, Width::Word), self.sext(b, Width::Word))
        };
        let (lt_cc, gt_cc) = if signed {
            (IntCC::SignedLessThan, IntCC::SignedGreaterThan)
        } else {
            (IntCC::UnsignedLessThan, IntCC::UnsignedGreaterThan)
        };
        let lt = self.b.ins().icmp(lt_cc, a, b);
        let gt = self.b.ins().icmp(gt_cc, a, b);
        let lt = self.b.ins().uextend(I32, lt);
        let gt = self.b.ins().uextend(I32, gt);
        // (gt − lt + 1) · 8: the bit offset of the order's entry in a byte table.
        let order = self.b.ins().isub(gt, lt);
        let shift = self.b.ins().ishl_imm_s(order, 3);
        let shift = self.b.ins().iadd_imm_s(shift, 8);
        let table = [Ordering::Less, Ordering::Equal, Ordering::Greater].map(compare_writes);
        let mask = table[0].mask;
        for byte in 0..2u32 {
            let bits_of = |w: FlagWrites| u32::from((w.value & mask) >> (8 * byte)) & 0xFF;
            let packed = table
                .iter()
                .enumerate()
                .fold(0u32, |acc, (i, w)| acc | bits_of(*w) << (8 * i));
            if (mask >> (8 * byte)) & 0xFF == 0 {
                continue;
            }
            let packed = self.iconst(I32, i64::from(packed));
            let bits = self.b.ins().ushr(packed, shift);
            let bits = self.b.ins().band_imm_s(bits, 0xFF);
            self.put_omron_flags(byte, mask, bits);
        }
    }

    /// An arithmetic instruction with at most two result words: the runtime's pure arithmetic
    /// (`stljit_rt_omron_arith`, no image), its result and flags applied here (nothing written
    /// on ER).
    fn omron_arith(&mut self, op: OmronArith, lhs: &Operand, rhs: &Operand, dst: &Operand) {
        let double = op.operand_words() == 2;
        let a = self.omron_value(lhs, double);
        let b = self.omron_value(rhs, double);
        let cy = self.flag_bit(Flag::Cy);
        let code = self.iconst(I32, i64::from(omron_kind_code(OmronArith::ALL, op)));
        let out = self.call_pure(Helper::OmronArith, &[code, a, b, cy]);
        // The flag writes, repacked as a fast shim's (mask 16–31, values 0–15).
        let flags = self.b.ins().ushr_imm_s(out, 32);
        let flags = self.b.ins().ireduce(I32, flags);
        let vals = self.b.ins().band_imm_s(flags, 0xFFFF);
        // Bit 31 here is OMRON_ARITH_HAS_RESULT, not a flag.
        let mask = self.b.ins().band_imm_s(flags, 0x7FFF_0000);
        let packed = self.b.ins().bor(vals, mask);
        let has = self.b.ins().band_imm_s(out, OMRON_ARITH_HAS_RESULT as i64);
        let has = self.b.ins().icmp_imm_s(IntCC::NotEqual, has, 0);
        if let Operand::Mem(loc) = *dst {
            let r = self.b.ins().ireduce(I32, out);
            let a = self.area_addr(loc.area, loc.offset);
            let (width, stored) = if op.result_words() == 2 {
                (Width::DWord, self.swap_halves(r))
            } else {
                (Width::Word, r)
            };
            // Written only with a result: fold `has` into the box's predicate.
            let old = self.read_static(a, width);
            let v = self.b.ins().select(has, stored, old);
            self.write_static(a, width, v);
        }
        self.apply_packed_flags(packed);
    }

    /// The binary sums and differences inline (`runtime::omron::arith`'s `add`/`sub`): the
    /// exact result one size wider gives CY (the unsigned result does not fit, or the borrow),
    /// OF/UF (the signed result above / below the range), `=` and N from the stored result.
    fn omron_binary_sum(&mut self, op: OmronArith, lhs: &Operand, rhs: &Operand, dst: &Operand) {
        let Some(shape) = BinarySum::of(op) else {
            return;
        };
        let double = op.operand_words() == 2;
        let bits = if double { 32 } else { 16 };
        let mask = (1i64 << bits) - 1;
        let a = self.omron_value(lhs, double);
        let b = self.omron_value(rhs, double);
        let (ua, sa) = self.widened(a, double);
        let (ub, sb) = self.widened(b, double);
        let cin = if shape.carry_in {
            let cy = self.flag_bit(Flag::Cy);
            Some(self.b.ins().uextend(I64, cy))
        } else {
            None
        };
        let (r, cy, exact) = if shape.add {
            let sum = self.b.ins().iadd(ua, ub);
            let exact = self.b.ins().iadd(sa, sb);
            let (sum, exact) = match cin {
                Some(c) => (self.b.ins().iadd(sum, c), self.b.ins().iadd(exact, c)),
                None => (sum, exact),
            };
            let r = self.b.ins().band_imm_s(sum, mask);
            let cy = self
                .b
                .ins()
                .icmp_imm_s(IntCC::UnsignedGreaterThan, sum, mask);
            (r, cy, exact)
        } else {
            let (y, exact) = match cin {
                Some(c) => {
                    let e = self.b.ins().isub(sa, sb);
                    (self.b.ins().iadd(ub, c), self.b.ins().isub(e, c))
                }
                None => (ub, self.b.ins().isub(sa, sb)),
            };
            let diff = self.b.ins().isub(ua, y);
            let r = self.b.ins().band_imm_s(diff, mask);
            let cy = self.b.ins().icmp(IntCC::UnsignedLessThan, ua, y);
            (r, cy, exact)
        };
        let of = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedGreaterThan, exact, mask >> 1);
        let uf = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedLessThan, exact, -(mask >> 1) - 1);
        let eq = self.b.ins().icmp_imm_s(IntCC::Equal, r, 0);
        let n = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedGreaterThan, r, mask >> 1);
        if let Operand::Mem(loc) = *dst {
            let r = self.b.ins().ireduce(I32, r);
            let at = self.area_addr(loc.area, loc.offset);
            let (width, stored) = if double {
                (Width::DWord, self.swap_halves(r))
            } else {
                (Width::Word, r)
            };
            self.write_static(at, width, stored);
        }
        let writes = arith::execute(op, 0, 0, false).flags;
        self.put_flag_values(
            writes.mask,
            &[
                (Flag::Cy, cy),
                (Flag::Eq, eq),
                (Flag::N, n),
                (Flag::Of, of),
                (Flag::Uf, uf),
            ],
        );
    }

    /// An Omron value as i64, zero-extended and sign-extended from its 16 or 32 bits.
    fn widened(&mut self, v: Value, double: bool) -> (Value, Value) {
        let narrow = if double {
            v
        } else {
            self.b.ins().ireduce(I16, v)
        };
        (
            self.b.ins().uextend(I64, narrow),
            self.b.ins().sextend(I64, narrow),
        )
    }

    /// Condition flag `flag` as a 0/1 `i32`.
    fn flag_bit(&mut self, flag: Flag) -> Value {
        let at = flag.system_bit().bit_loc();
        let byte = self.area_addr(Area::Flags, at.byte);
        let v = self.byte(byte);
        let v = self.b.ins().ushr_imm_s(v, i64::from(at.bit));
        self.b.ins().band_imm_s(v, 1)
    }

    /// `v` with its 16-bit halves swapped: an Omron double word to the IR's big-endian dword
    /// and back.
    fn swap_halves(&mut self, v: Value) -> Value {
        let hi = self.b.ins().ishl_imm_s(v, 16);
        let lo = self.b.ins().ushr_imm_s(v, 16);
        self.b.ins().bor(hi, lo)
    }
}

/// The position of `kind` in `all` (its `FfiCode`).
fn omron_kind_code<T: PartialEq>(all: &[T], kind: T) -> u32 {
    all.iter().position(|k| *k == kind).unwrap_or(0) as u32
}
