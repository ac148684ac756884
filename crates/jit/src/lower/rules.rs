//! The runtime's timer and counter rules, emitted inline.
//!
//! [`stljit_runtime::timer::timer_rule`] and [`stljit_runtime::counter::counter_rule`] are
//! written over [`RuleOps`]; [`Emit`] implements it by building Cranelift instructions, so a
//! `TON` or `CTU` in compiled code is the interpreter's rule text turned into straight-line
//! code on the object's bytes, with no call and no spill of the byte cache around one. What is
//! known at compile time (a constant gate or input, the first-scan rule) is folded by
//! [`Native`], the same operations the interpreter runs, so folding cannot change a result.
//! Field bytes a rule never reads (a TON's bit, a CTU's down-edge memory) are not loaded
//! ([`Lower::drop_unread`]).

use super::cache::Addr;
use super::value::B;
use super::{Lower, mf};
use cranelift_codegen::ir::{
    Inst, InstBuilder, InstructionData, Opcode, Value, ValueDef,
    condcodes::{CondCode, IntCC},
    types::{I16, I32, I64},
};
use cranelift_frontend::FunctionBuilder;
use std::collections::HashSet;
use stljit_core::Width;
use stljit_core::ir::{CounterKind, TimerKind};
use stljit_core::layout::{CounterState, Sched, TimerState};
use stljit_runtime::counter::{CounterFields, CounterInputs, counter_rule};
use stljit_runtime::rule_ops::{Native, RuleOps};
use stljit_runtime::timer::{TimerFields, TimerInputs, timer_rule};

/// A rule value: known at compile time, or an `i64` SSA value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rv {
    /// A constant.
    K(i64),
    /// An `i64` computed at run time.
    R(Value),
}

/// [`RuleOps`] that emits Cranelift instructions into `b` (module docs).
pub(crate) struct Emit<'a, 'f> {
    pub(crate) b: &'a mut FunctionBuilder<'f>,
}

impl Emit<'_, '_> {
    /// The value as an `i64` SSA value.
    pub(crate) fn value(&mut self, v: Rv) -> Value {
        match v {
            Rv::K(k) => self.b.ins().iconst(I64, k),
            Rv::R(v) => v,
        }
    }

    /// A binary op: folded by `fold` when both sides are known, else emitted by `emit`.
    fn binary(
        &mut self,
        (a, b): (Rv, Rv),
        fold: fn(&mut Native, i64, i64) -> i64,
        emit: fn(&mut FunctionBuilder<'_>, Value, Value) -> Value,
    ) -> Rv {
        if let (Rv::K(x), Rv::K(y)) = (a, b) {
            return Rv::K(fold(&mut Native, x, y));
        }
        let (x, y) = (self.value(a), self.value(b));
        Rv::R(emit(self.b, x, y))
    }

    /// The `icmp` (an `i8`) whose zero-extension `v` is, if it is one: a select can test it
    /// directly (x86 `cmp` + `cmov`, not `setcc`, `movzx`, `test`, `cmov`), and its negation
    /// is the opposite comparison.
    fn compare_of(&self, v: Value) -> Option<(Value, IntCC, [Value; 2])> {
        let dfg = &self.b.func.dfg;
        let arg = self.uextend_arg(v)?;
        let ValueDef::Result(cmp, 0) = dfg.value_def(arg) else {
            return None;
        };
        match dfg.insts[cmp] {
            InstructionData::IntCompare {
                opcode: Opcode::Icmp,
                cond,
                args,
            } => Some((arg, cond, args)),
            _ => None,
        }
    }

    /// The value `v` is the zero-extension of, if it is one.
    fn uextend_arg(&self, v: Value) -> Option<Value> {
        let dfg = &self.b.func.dfg;
        let ValueDef::Result(ext, 0) = dfg.value_def(v) else {
            return None;
        };
        match dfg.insts[ext] {
            InstructionData::Unary {
                opcode: Opcode::Uextend,
                arg,
            } => Some(arg),
            _ => None,
        }
    }

    /// A comparison as a 0/1 `i64`.
    fn emit_compare(&mut self, cc: IntCC, x: Value, y: Value) -> Rv {
        let c = self.b.ins().icmp(cc, x, y);
        Rv::R(self.b.ins().uextend(I64, c))
    }

    /// A signed comparison as a 0/1 `i64`.
    fn compare(&mut self, cc: IntCC, a: Rv, b: Rv, fold: fn(&mut Native, i64, i64) -> i64) -> Rv {
        if let (Rv::K(x), Rv::K(y)) = (a, b) {
            return Rv::K(fold(&mut Native, x, y));
        }
        if let (Rv::R(v), Rv::K(k), IntCC::Equal | IntCC::NotEqual) = (a, b, cc)
            && let (Some(n), Ok(k)) = (self.zero_extended(v), u32::try_from(k))
        {
            // (In)equality with a constant that fits is the same on the narrow value, and
            // x86 then needs no `mov` to zero-extend it first.
            let k = self.b.ins().iconst(I32, i64::from(k));
            return self.emit_compare(cc, n, k);
        }
        let (x, y) = (self.value(a), self.value(b));
        self.emit_compare(cc, x, y)
    }

    /// The `i32` that `v` zero-extends, if it is one.
    fn zero_extended(&self, v: Value) -> Option<Value> {
        self.uextend_arg(v)
            .filter(|&a| self.b.func.dfg.value_type(a) == I32)
    }
}

impl RuleOps for Emit<'_, '_> {
    type V = Rv;

    fn k(&mut self, v: i64) -> Rv {
        Rv::K(v)
    }

    fn and(&mut self, a: Rv, b: Rv) -> Rv {
        // Booleans only (the trait's contract): 0 absorbs, 1 is the identity.
        match (a, b) {
            (Rv::K(0), _) | (_, Rv::K(0)) => Rv::K(0),
            (Rv::K(1), x) | (x, Rv::K(1)) => x,
            // `x AND (p < q)` as `select(p < q, x, 0)`: x86 `cmp` + `cmov`, without
            // materialising the comparison as 0/1 first (`setcc`, `movzx`, `and`).
            (Rv::R(c), x) | (x, Rv::R(c)) if self.compare_of(c).is_some() => {
                self.select(Rv::R(c), x, Rv::K(0))
            }
            _ => self.binary((a, b), Native::and, |b, x, y| b.ins().band(x, y)),
        }
    }

    fn or(&mut self, a: Rv, b: Rv) -> Rv {
        match (a, b) {
            (Rv::K(1), _) | (_, Rv::K(1)) => Rv::K(1),
            (Rv::K(0), x) | (x, Rv::K(0)) => x,
            _ => self.binary((a, b), Native::or, |b, x, y| b.ins().bor(x, y)),
        }
    }

    fn not(&mut self, a: Rv) -> Rv {
        match a {
            Rv::K(x) => Rv::K(Native.not(x)),
            Rv::R(v) => match self.compare_of(v) {
                Some((_, cc, [x, y])) => self.emit_compare(cc.complement(), x, y),
                None => Rv::R(self.b.ins().bxor_imm_s(v, 1)),
            },
        }
    }

    fn add(&mut self, a: Rv, b: Rv) -> Rv {
        match (a, b) {
            (Rv::K(0), x) | (x, Rv::K(0)) => x,
            _ => self.binary((a, b), Native::add, |b, x, y| b.ins().iadd(x, y)),
        }
    }

    fn sub(&mut self, a: Rv, b: Rv) -> Rv {
        match b {
            Rv::K(0) => a,
            _ => self.binary((a, b), Native::sub, |b, x, y| b.ins().isub(x, y)),
        }
    }

    fn min(&mut self, a: Rv, b: Rv) -> Rv {
        self.binary((a, b), Native::min, |b, x, y| b.ins().smin(x, y))
    }

    fn eq(&mut self, a: Rv, b: Rv) -> Rv {
        self.compare(IntCC::Equal, a, b, Native::eq)
    }

    fn ge(&mut self, a: Rv, b: Rv) -> Rv {
        self.compare(IntCC::SignedGreaterThanOrEqual, a, b, Native::ge)
    }

    fn gt(&mut self, a: Rv, b: Rv) -> Rv {
        self.compare(IntCC::SignedGreaterThan, a, b, Native::gt)
    }

    fn ne0(&mut self, a: Rv) -> Rv {
        self.compare(IntCC::NotEqual, a, Rv::K(0), |o, x, _| o.ne0(x))
    }

    fn bit0(&mut self, a: Rv) -> Rv {
        match a {
            Rv::K(x) => Rv::K(Native.bit0(x)),
            Rv::R(v) => Rv::R(self.b.ins().band_imm_s(v, 1)),
        }
    }

    fn wrap16(&mut self, a: Rv) -> Rv {
        match a {
            Rv::K(x) => Rv::K(Native.wrap16(x)),
            Rv::R(v) => {
                let low = self.b.ins().ireduce(I16, v);
                Rv::R(self.b.ins().sextend(I64, low))
            }
        }
    }

    fn select(&mut self, c: Rv, a: Rv, b: Rv) -> Rv {
        match c {
            Rv::K(c) => {
                if c != 0 {
                    a
                } else {
                    b
                }
            }
            Rv::R(_) if a == b => a,
            // x86 `cmov` takes the first arm as its source operand, and a constant there is
            // loaded from the constant pool (an 8-byte rip-relative `cmov`); as the value the
            // select starts from it is an immediate move (or a zeroing `xor`). So a constant
            // goes second, under the complemented condition.
            Rv::R(c) if matches!((a, b), (Rv::K(_), Rv::R(_))) => {
                let not_c = match self.compare_of(c) {
                    Some((_, cond, [x, y])) => self.b.ins().icmp(cond.complement(), x, y),
                    None => self.b.ins().icmp_imm_s(IntCC::Equal, c, 0),
                };
                let (x, y) = (self.value(b), self.value(a));
                Rv::R(self.b.ins().select(not_c, x, y))
            }
            Rv::R(c) => {
                let c = self.compare_of(c).map_or(c, |(flag, ..)| flag);
                let (x, y) = (self.value(a), self.value(b));
                Rv::R(self.b.ins().select(c, x, y))
            }
        }
    }
}

impl Lower<'_, '_> {
    /// A logic-stack boolean as a rule value.
    fn rule_bool(&mut self, v: B) -> Rv {
        match v {
            B::K(k) => Rv::K(i64::from(k)),
            v => {
                let x = v.to01(&mut self.b);
                Rv::R(self.b.ins().uextend(I64, x))
            }
        }
    }

    /// A byte through the cache, zero-extended.
    fn rule_byte(&mut self, a: Addr) -> Rv {
        let v = self.byte(a);
        Rv::R(self.b.ins().uextend(I64, v))
    }

    /// A field byte the rule may not read: the cached value, or else a load that
    /// [`Lower::drop_unread`] removes again if the rule did not use it (Cranelift keeps a load
    /// whose result nothing uses: a TON reads neither its bit nor its TOF byte, a CTU not its
    /// down-edge memory). The load is not cached, so nothing outside the rule can use it.
    fn rule_field_byte(&mut self, a: Addr, loads: &mut Vec<Inst>) -> Rv {
        if self.block.cache.get(a).is_some() {
            return self.rule_byte(a);
        }
        let base = self.base(a);
        let v = self.b.ins().uload8(I64, mf(), base, Self::off32(a));
        loads.extend(self.b.func.dfg.value_def(v).inst());
        Rv::R(v)
    }

    /// Removes the loads of [`Lower::rule_field_byte`] whose result nothing that matters uses,
    /// with the pure instructions computed from them alone (a decoding step like `bit0`).
    /// The rule's code follows the loads in the current block, so a backward pass from the
    /// block's end marks what stores, calls, branches and traps need; a load outside that,
    /// and every unmarked instruction using a removed value, goes. Nothing else is touched
    /// (other unused values may be cached for later ops).
    fn drop_unread(&mut self, loads: Vec<Inst>) {
        let (Some(&first), Some(block)) = (loads.first(), self.b.current_block()) else {
            return;
        };
        let func = &self.b.func;
        if func.layout.inst_block(first) != Some(block) {
            // Not straight-line code after all: keep every load (correct, one load more).
            return;
        }
        let mut live = HashSet::new();
        let mut at = func.layout.last_inst(block);
        while let Some(i) = at {
            let op = func.dfg.insts[i].opcode();
            let root = !loads.contains(&i)
                && (op.can_store()
                    || op.can_trap()
                    || op.can_load()
                    || op.is_call()
                    || op.is_branch()
                    || op.is_terminator()
                    || op.other_side_effects());
            if root || func.dfg.inst_results(i).iter().any(|r| live.contains(r)) {
                live.extend(func.dfg.inst_values(i));
            }
            if i == first {
                break;
            }
            at = func.layout.prev_inst(i);
        }
        let mut removed: HashSet<Value> = HashSet::new();
        let mut dead = Vec::new();
        let mut at = Some(first);
        while let Some(i) = at {
            let results = func.dfg.inst_results(i);
            let unused = results.iter().all(|r| !live.contains(r));
            let from_removed = func.dfg.inst_values(i).any(|a| removed.contains(&a));
            if unused && (loads.contains(&i) || from_removed) {
                removed.extend(results.iter().copied());
                dead.push(i);
            }
            at = func.layout.next_inst(i);
        }
        for i in dead {
            self.b.func.layout.remove_inst(i);
        }
    }

    /// A big-endian `i16` (a current value) through the cache, sign-extended.
    fn rule_word_be(&mut self, a: Addr) -> Rv {
        let v = self.read_static(a, Width::Word);
        let w = self.b.ins().ireduce(I16, v);
        Rv::R(self.b.ins().sextend(I64, w))
    }

    /// Writes `new` as a byte unless it is `old` itself (writing back the byte just read
    /// changes nothing).
    fn rule_set_byte(&mut self, a: Addr, old: Rv, new: Rv) {
        if new != old {
            let v = Emit { b: &mut self.b }.value(new);
            let v = self.b.ins().ireduce(I32, v);
            self.set_byte(a, v);
        }
    }

    /// Writes `new` as a big-endian word unless it is `old` itself.
    fn rule_set_word_be(&mut self, a: Addr, old: Rv, new: Rv) {
        if new != old {
            let v = Emit { b: &mut self.b }.value(new);
            let v = self.b.ins().ireduce(I32, v);
            self.write_static(a, Width::Word, v);
        }
    }

    /// `TON`/`TONR`/`TOF` on timer `n`, which exists, with preset `pv` (an `i32`, sign-extended
    /// from the word): [`timer_rule`] emitted on the timer's bytes, decoded and encoded as the
    /// runtime's `Timer::decode`/`encode` do ([`TimerFields::from_raw`]).
    pub(crate) fn timer_inline(&mut self, kind: TimerKind, n: u16, pv: Value) {
        debug_assert!(self.in_box.pf().is_none(), "a timer is not a box");
        let [(v, _), (b, _), (s, _)] = self.env.layout.timer_bytes(n);
        let (value, bit, state) = (Addr::img(v), Addr::img(b), Addr::img(s));
        let pt_at = state.plus(TimerState::PT_CACHE);
        let pt = self.load_ne(pt_at, I16);
        let mut loads = Vec::new();
        let raw = TimerFields {
            cv: self.rule_word_be(value),
            bit: self.rule_field_byte(bit, &mut loads),
            run: self.rule_byte(state.plus(TimerState::RUN)),
            tof: self.rule_field_byte(state.plus(TimerState::TOF), &mut loads),
            pt_cache: Rv::R(self.b.ins().sextend(I64, pt)),
            // The declared resolution, as the interpreter takes it (spec §5.2: compile time):
            // a 100-ms timer's delta needs no compare, a 1-ms or 10-ms timer's rule credits none.
            res: match self.env.timer_res.get(usize::from(n)).copied().flatten() {
                Some(res) => Rv::K(i64::from(res)),
                None => self.rule_byte(state.plus(TimerState::RES)),
            },
        };
        // The delta is a native-endian `u32`; loaded zero-extended in one instruction.
        let d100_at = self.sched(Sched::D100);
        let base = self.base(d100_at);
        let d100 = self.b.ins().uload32(mf(), base, Self::off32(d100_at));
        let inputs = TimerInputs {
            input: self.rule_bool(self.block.stack.top()),
            gate: self.rule_bool(self.block.gate),
            preset: Rv::R(self.b.ins().sextend(I64, pv)),
            d100: Rv::R(d100),
        };
        let policy = self.gate_policy();
        let next = {
            let o = &mut Emit { b: &mut self.b };
            let t = TimerFields::from_raw(o, raw);
            timer_rule(o, kind, policy, t, inputs)
        };
        self.rule_set_word_be(value, raw.cv, next.cv);
        self.rule_set_byte(bit, raw.bit, next.bit);
        self.rule_set_byte(state.plus(TimerState::RUN), raw.run, next.run);
        self.rule_set_byte(state.plus(TimerState::TOF), raw.tof, next.tof);
        if next.pt_cache != raw.pt_cache {
            let v = Emit { b: &mut self.b }.value(next.pt_cache);
            let v = self.b.ins().ireduce(I16, v);
            self.store_ne(pt_at, v);
        }
        self.drop_unread(loads);
    }

    /// `CTU`/`CTD`/`CTUD` on counter `n`, which exists, with preset `pv` (as in
    /// [`Lower::timer_inline`]): [`counter_rule`] emitted on the counter's bytes.
    pub(crate) fn counter_inline(&mut self, kind: CounterKind, n: u16, pv: Value) {
        debug_assert!(self.in_box.pf().is_none(), "a counter is not a box");
        let [(v, _), (b, _), (s, _)] = self.env.layout.counter_bytes(n);
        let (value, bit, state) = (Addr::img(v), Addr::img(b), Addr::img(s));
        let (up_at, down_at) = (
            state.plus(CounterState::PREV_UP),
            state.plus(CounterState::PREV_DOWN),
        );
        let mut loads = Vec::new();
        let raw = CounterFields {
            cv: self.rule_word_be(value),
            prev_up: self.rule_field_byte(up_at, &mut loads),
            prev_down: self.rule_field_byte(down_at, &mut loads),
        };
        let rules = self.env.rules;
        let first_scan = if rules.first_scan_suppresses() {
            self.rule_byte(self.sched(Sched::FIRST_SCAN))
        } else {
            Rv::K(0)
        };
        let levels = [0, 1, 2].map(|i| self.rule_bool(self.block.stack.level(i)));
        let gate = self.rule_bool(self.block.gate);
        let preset = Rv::R(self.b.ins().sextend(I64, pv));
        let policy = self.gate_policy();
        let (next, out) = {
            let o = &mut Emit { b: &mut self.b };
            let quiet = rules.edges_suppressed_in(o, first_scan);
            let inputs = CounterInputs {
                levels,
                gate,
                preset,
                quiet,
            };
            counter_rule(o, kind, policy, raw, inputs)
        };
        self.rule_set_word_be(value, raw.cv, next.cv);
        self.rule_set_byte(up_at, raw.prev_up, next.prev_up);
        self.rule_set_byte(down_at, raw.prev_down, next.prev_down);
        match out.written {
            Rv::K(0) => {}
            Rv::K(_) => self.rule_set_byte(bit, Rv::K(-1), out.bit),
            written => {
                let old = self.rule_byte(bit);
                let new = Emit { b: &mut self.b }.select(written, out.bit, old);
                self.rule_set_byte(bit, old, new);
            }
        }
        self.drop_unread(loads);
    }
}
