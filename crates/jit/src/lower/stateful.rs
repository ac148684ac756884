//! Timers, counters, their resets and the run-time ranges of `S`/`R`, `BM*`, `FILL`, `SHRB`:
//! the runtime owns these semantics (spec §5). Timers and counters the profile has run the
//! runtime's rule text emitted inline ([`super::rules`]); the rest calls into the runtime.

use super::Lower;
use super::mem::OnFail;
use super::value::{B, Stack};
use crate::helpers::Helper;
use cranelift_codegen::ir::{BlockArg, InstBuilder, Value, condcodes::IntCC, types::I32};
use stljit_core::ir::{BitLoc, CounterKind, Operand, TimerKind};
use stljit_core::{Area, ErrorCode, Width};
use stljit_runtime::ffi::{CTL_GATE, FfiCode, gate_word_fixed};

impl Lower<'_, '_> {
    /// Records a non-zero runtime status as a non-fatal error (a diamond, rarely taken).
    pub(crate) fn error_if_status(&mut self, status: Value) {
        let bad = self.b.ins().icmp_imm_s(IntCC::NotEqual, status, 0);
        self.diamond(bad, |s| s.record_error(status), |_| {});
    }

    /// Executes timer or counter `n` (of kind `code`) through the general shim, for an
    /// object the profile lacks: the shim records the error (no such object).
    fn call_stateful_general(
        &mut self,
        general: Helper,
        (n, code): (u16, u8),
        inputs: Value,
        pv: Value,
    ) {
        let gate = self.gate_word();
        let nv = self.iconst(I32, i64::from(n));
        let k = self.iconst(I32, i64::from(code));
        let st = self.call_helper(general, &[nv, k, inputs, gate, pv]);
        self.error_if_status(st);
    }

    /// Reads a word preset; a failing pointer records 0x0006 and skips the instruction.
    fn with_preset(&mut self, preset: &Operand, f: impl FnOnce(&mut Self, Value)) {
        if !Self::is_indirect(preset) {
            let v = self.read_operand(
                preset,
                Width::Word,
                OnFail::Fatal(stljit_core::FatalCode::CompareIndirect),
            );
            let v = self.sext(v, Width::Word);
            f(self, v);
            return;
        }
        // A pointer preset: resolve first; the failure path records the error and skips.
        let err = self.b.create_block();
        let code = self.b.append_block_param(err, I32);
        let join = self.b.create_block();
        let mut arms = self.fork(join);
        let v = self.read_operand(preset, Width::Word, OnFail::Branch(err));
        let v = self.sext(v, Width::Word);
        f(self, v);
        self.end_arm(&mut arms);
        self.b.seal_block(err);
        self.start_arm(&arms, err);
        self.record_error(code);
        self.end_arm(&mut arms);
        self.join_arms(arms);
    }

    /// `TON`/`TONR`/`TOF Tn, PT`: the runtime's rule inline ([`Lower::timer_inline`]), or the
    /// general shim for a timer the profile lacks (it records the error).
    pub(crate) fn timer(&mut self, kind: TimerKind, n: u16, preset: &Operand) {
        self.with_preset(preset, |s, pv| {
            if u32::from(n) < s.env.layout.area_size(Area::TimerBit) {
                s.timer_inline(kind, n, pv);
            } else {
                let input = s.block.stack.top().to01(&mut s.b);
                s.call_stateful_general(Helper::Timer, (n, kind.code()), input, pv);
            }
        });
    }

    /// `CTU`/`CTD`/`CTUD Cn, PV`: the runtime's rule inline ([`Lower::counter_inline`]), or
    /// the general shim for a counter the profile lacks.
    pub(crate) fn counter(&mut self, kind: CounterKind, n: u16, preset: &Operand) {
        self.with_preset(preset, |s, pv| {
            if u32::from(n) < s.env.layout.area_size(Area::CounterBit) {
                s.counter_inline(kind, n, pv);
            } else {
                // `counter::execute` reads levels 0..=2 only; packing just those is cheaper.
                let levels = Stack {
                    lv: (0..3).map(|i| s.block.stack.level(i)).collect(),
                };
                let stack = levels.to_reg(&mut s.b);
                s.call_stateful_general(Helper::Counter, (n, kind.code()), stack, pv);
            }
        });
    }

    /// The bits of the gate word ([`stljit_runtime::ffi::decode_gate_word`]) that do not
    /// depend on the gate's state: the gate policy and the rules (0 for S7 under the rules in
    /// force).
    fn gate_word_fixed(&self) -> u32 {
        gate_word_fixed(self.gate_policy(), self.env.rules)
    }

    /// What a closed gate does in this program: its family's policy (S7 SCR or Omron IL).
    pub(crate) fn gate_policy(&self) -> stljit_runtime::rules::GatePolicy {
        self.env.layout.profile.profile().family.gate_policy()
    }

    /// The gate word of the general timer and counter shims: the gate at bit 0 and the fixed
    /// bits.
    pub(crate) fn gate_word(&mut self) -> Value {
        let open = self.block.gate.to01(&mut self.b);
        match self.gate_word_fixed() {
            0 => open,
            fixed => self.b.ins().bor_imm_s(open, i64::from(fixed)),
        }
    }

    /// The `ctl` argument of the fast Omron shims: `low` (bits 0–7: the inputs) | the gate at
    /// [`CTL_GATE`]. Outside IL/ILC the gate is a constant: one `or` or nothing.
    pub(crate) fn fast_ctl(&mut self, low: Value) -> Value {
        match self.block.gate {
            B::K(false) => low,
            B::K(true) => self.b.ins().bor_imm_s(low, i64::from(CTL_GATE)),
            g => {
                let at = g.at_bit(&mut self.b, CTL_GATE.trailing_zeros() as u8);
                self.b.ins().bor(low, at)
            }
        }
    }

    /// `R Tn, N` / `R Cn, N` through the runtime's reset (`h`).
    pub(crate) fn reset_range(&mut self, h: Helper, first: u32, count: &Operand) {
        let pf = self.pf();
        let count = *count;
        self.guarded_failing(pf, move |s, fail| {
            let c = s.count_value(&count, fail);
            let f = s.iconst(I32, i64::from(first));
            let st = s.call_helper(h, &[f, c]);
            s.error_if_status(st);
        });
    }

    /// Like [`Lower::guarded`], with a failure block for pointer operands that records the
    /// error (no ENO: these are not boxes).
    pub(crate) fn guarded_failing(&mut self, pf: B, f: impl FnOnce(&mut Self, OnFail)) {
        if pf != B::K(false) {
            self.run_failing(pf, false, f);
        }
    }

    /// `S`/`R` with a count only known at run time: the runtime's `set_range_imm`.
    pub(crate) fn set_range_helper(
        &mut self,
        pf: B,
        start: BitLoc,
        count: &Operand,
        value: bool,
        immediate: bool,
    ) {
        let count = *count;
        self.guarded_failing(pf, move |s, fail| {
            let n = s.count_value(&count, fail);
            let args = [
                s.iconst(I32, i64::from(start.area.ffi_code())),
                s.iconst(I32, i64::from(start.byte)),
                s.iconst(I32, i64::from(start.bit)),
                s.func.call_depth,
                n,
                s.iconst(I32, i64::from(value)),
                s.iconst(I32, i64::from(immediate)),
            ];
            let st = s.call_helper(Helper::SetRange, &args);
            s.error_if_status(st);
        });
    }

    /// The run an operand starts (interpreter `span`): image offset and area end, as `i32`s.
    fn span(
        &mut self,
        o: &Operand,
        width: Width,
        write: bool,
        fail: OnFail,
    ) -> Option<(Value, Value)> {
        match *o {
            Operand::Mem(loc) => {
                let size = self.env.layout.area_size(loc.area);
                if loc.offset >= size {
                    return None;
                }
                if loc.area == Area::L {
                    let fb = self.frame_off();
                    let start = self.b.ins().iadd_imm_s(fb, i64::from(loc.offset));
                    let end = self.b.ins().iadd_imm_s(fb, i64::from(size));
                    Some((start, end))
                } else {
                    let base = self.env.layout.base(loc.area);
                    Some((
                        self.iconst(I32, i64::from(base + loc.offset)),
                        self.iconst(I32, i64::from(base + size)),
                    ))
                }
            }
            Operand::Indirect(loc) => {
                let (off, ptr) = self.resolve_off(loc, width, write, fail);
                let end = self.call_pure(Helper::PointerEnd, &[ptr]);
                Some((off, end))
            }
            Operand::Const(_) | Operand::AddressOf(_) | Operand::Omron(_) => None,
        }
    }

    /// Image offset (`i32`) of the current L frame.
    fn frame_off(&mut self) -> Value {
        let size = i64::from(self.env.layout.area_size(Area::L));
        let d = self.b.ins().imul_imm_s(self.func.call_depth, size);
        self.b
            .ins()
            .iadd_imm_s(d, i64::from(self.env.layout.base(Area::L)))
    }

    /// Branches to the failure block with the (dynamic) status when it is not 0.
    pub(crate) fn fail_on_status(&mut self, st: Value, fail: OnFail) {
        if let OnFail::Branch(err) = fail {
            let cont = self.b.create_block();
            self.b
                .ins()
                .brif(st, err, &[BlockArg::Value(st)], cont, &[]);
            self.b.seal_block(cont);
            self.b.switch_to_block(cont);
        }
    }

    /// `BMB/BMW/BMD` (interpreter `exec_box` order of operand reads).
    pub(crate) fn block_move(
        &mut self,
        width: Width,
        src: &Operand,
        dst: &Operand,
        count: &Operand,
    ) {
        let range = ErrorCode::OperandRange as u16;
        self.boxed(|s, f| {
            let n = s.count_value(count, f);
            let Some((ss, se)) = s.span(src, width, false, f) else {
                s.fail_now(f, range);
                return B::K(false);
            };
            let Some((ds, de)) = s.span(dst, width, true, f) else {
                s.fail_now(f, range);
                return B::K(false);
            };
            let w = s.iconst(I32, i64::from(width.bytes()));
            let st = s.call_helper(Helper::BlockMove, &[ss, se, ds, de, w, n]);
            s.fail_on_status(st, f);
            B::K(true)
        })
    }

    /// `FILL` (interpreter `exec_box` order of operand reads).
    pub(crate) fn fill(&mut self, src: &Operand, dst: &Operand, count: &Operand) {
        let range = ErrorCode::OperandRange as u16;
        self.boxed(|s, f| {
            let v = s.read_operand(src, Width::Word, f);
            let n = s.count_value(count, f);
            let Some((ds, de)) = s.span(dst, Width::Word, true, f) else {
                s.fail_now(f, range);
                return B::K(false);
            };
            let st = s.call_helper(Helper::Fill, &[v, ds, de, n]);
            s.fail_on_status(st, f);
            B::K(true)
        })
    }

    /// `SHRB` (interpreter `exec_box` order of operand reads).
    pub(crate) fn shift_register(&mut self, data: BitLoc, start: BitLoc, len: &Operand) {
        self.boxed(|s, f| {
            let d = s.read_bit(data).to01(&mut s.b);
            let n = s.count_value(len, f);
            let n = s.sext(n, Width::Byte);
            let args = [
                d,
                s.iconst(I32, i64::from(start.area.ffi_code())),
                s.iconst(I32, i64::from(start.byte)),
                s.iconst(I32, i64::from(start.bit)),
                s.func.call_depth,
                n,
            ];
            let st = s.call_helper(Helper::ShiftRegister, &args);
            s.fail_on_status(st, f);
            B::K(true)
        })
    }
}
