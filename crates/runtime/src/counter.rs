//! Counters `CTU`/`CTD`/`CTUD` (spec §5.3), as functions on the image bytes.
//!
//! Inputs come from logic-stack levels (spec §4.5); the caller passes the whole stack as a bit
//! vector (`bit i = S_i`) so that the level assignment lives here and nowhere else.
//!
//! The rules of an execution live in [`counter_rule`], written once over [`RuleOps`]
//! ([`crate::rule_ops`]): the interpreter runs it on plain integers through [`execute`] and
//! [`Counter::step`] (layout lookups, range check), the JIT emits it inline on the counter's
//! bytes (offsets fixed at compile time).

use crate::rule_ops::{Native, RuleOps};
use crate::rules::{Gate, GatePolicy, Rules};
use crate::{block, mem};
use stljit_core::ir::CounterKind;
use stljit_core::layout::Sched;
use stljit_core::layout::{COUNTER_STATE_SIZE, CounterState, Layout};
use stljit_core::{Area, ErrorCode};

fn value_at(layout: &Layout, n: u16) -> u32 {
    layout.counter_bytes(n)[0].0
}

fn bit_at(layout: &Layout, n: u16) -> u32 {
    layout.counter_bytes(n)[1].0
}

/// The fields of one counter an execution reads: its current value and the edge memories of
/// its count inputs (the raw [`CounterState`] bytes, so a memory the kind does not use is
/// written back untouched).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Counter {
    /// Current value.
    pub cv: i16,
    /// [`CounterState::PREV_UP`] byte.
    pub prev_up: u8,
    /// [`CounterState::PREV_DOWN`] byte.
    pub prev_down: u8,
}

const UP: usize = CounterState::PREV_UP as usize;
const DOWN: usize = CounterState::PREV_DOWN as usize;

impl Counter {
    /// Decodes the fields from the value bytes (big-endian) and the private state block.
    #[inline]
    pub fn decode(value: [u8; 2], state: &[u8; COUNTER_STATE_SIZE as usize]) -> Counter {
        Counter {
            cv: i16::from_be_bytes(value),
            prev_up: state[UP],
            prev_down: state[DOWN],
        }
    }

    /// Writes the fields back; the kind byte is left as it is.
    #[inline]
    pub fn encode(&self, value: &mut [u8; 2], state: &mut [u8; COUNTER_STATE_SIZE as usize]) {
        *value = self.cv.to_be_bytes();
        state[UP] = self.prev_up;
        state[DOWN] = self.prev_down;
    }

    /// Executes a counter instruction (spec §5.3) under `gate` and returns the new counter bit,
    /// or `None` when the bit keeps its value: [`counter_rule`] on plain integers. `stack`
    /// holds the logic stack (`bit i = S_i`); `quiet` suppresses edges (the first-scan rule).
    #[inline]
    pub fn step(
        &mut self,
        kind: CounterKind,
        stack: u16,
        gate: Gate,
        preset: i16,
        quiet: bool,
    ) -> Option<bool> {
        let (open, policy) = match gate {
            // The policy only matters for a closed gate.
            Gate::Open => (true, GatePolicy::S7Scr),
            Gate::Closed(policy) => (false, policy),
        };
        let c = self;
        let fields = CounterFields {
            cv: i64::from(c.cv),
            prev_up: i64::from(c.prev_up),
            prev_down: i64::from(c.prev_down),
        };
        let inputs = CounterInputs {
            levels: [0, 1, 2].map(|k| i64::from((stack >> k) & 1)),
            gate: i64::from(open),
            preset: i64::from(preset),
            quiet: i64::from(quiet),
        };
        let (next, out) = counter_rule(&mut Native, kind, policy, fields, inputs);
        // CV stays an `i16` (guarded or wrapping steps, the preset, 0); the memories are
        // bytes (an input 0/1, or the byte as it was).
        c.cv = next.cv as i16;
        c.prev_up = next.prev_up as u8;
        c.prev_down = next.prev_down as u8;
        (out.written != 0).then_some(out.bit != 0)
    }
}

/// The fields of one counter [`counter_rule`] reads and writes, as [`RuleOps`] values: CV (as
/// `i16`) and the edge memories of its count inputs (the raw bytes; one the kind does not use
/// comes back as it was).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CounterFields<V> {
    /// Current value.
    pub cv: V,
    /// [`CounterState::PREV_UP`] byte.
    pub prev_up: V,
    /// [`CounterState::PREV_DOWN`] byte.
    pub prev_down: V,
}

/// The inputs of one counter execution: logic-stack levels 0–2 (0/1; spec §4.5), the gate (1
/// open), the preset (as `i16`) and whether edges are suppressed (the first-scan rule,
/// [`Rules::edges_suppressed`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CounterInputs<V> {
    /// `S0`, `S1`, `S2`.
    pub levels: [V; 3],
    /// The gate: 1 open.
    pub gate: V,
    /// `PV`.
    pub preset: V,
    /// 1: no edge counts in this execution.
    pub quiet: V,
}

/// What a counter execution does to its bit: `written` (0/1) says whether the bit is written
/// at all, `bit` the value written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CounterBit<V> {
    /// 1: the bit takes `bit`; 0: it keeps its value.
    pub written: V,
    /// The new counter bit (0/1).
    pub bit: V,
}

/// Rising edge of `input` against the memory `prev` (a byte; non-zero = was on), which takes
/// the new input; none while `quiet`. Returns the edge and the new memory.
fn edge_of<O: RuleOps>(o: &mut O, prev: O::V, input: O::V, quiet: O::V) -> (O::V, O::V) {
    let was = o.ne0(prev);
    let rose = o.not(was);
    let rose = o.and(input, rose);
    let loud = o.not(quiet);
    (o.and(rose, loud), input)
}

/// Executes `CTU`/`CTD`/`CTUD` (spec §5.3) on `c`: the rules of a counter execution, the one
/// text both engines run ([`crate::rule_ops`]). Each input is `S_k`, or 0 under a gate closed
/// by [`GatePolicy::S7Scr`]; a gate closed by [`GatePolicy::OmronInterlock`] does not execute
/// the counter (value, bit and edge memories kept). `S0` (R, or LD for CTD) wins over
/// counting; otherwise an edge counts once; the edge memories are updated even while R/LD is
/// on (TC10).
pub fn counter_rule<O: RuleOps>(
    o: &mut O,
    kind: CounterKind,
    policy: GatePolicy,
    c: CounterFields<O::V>,
    x: CounterInputs<O::V>,
) -> (CounterFields<O::V>, CounterBit<O::V>) {
    let [s0, s1, s2] = x.levels.map(|s| o.and(s, x.gate));
    let (zero, one) = (o.k(0), o.k(1));
    let mut next = c;
    let (counted, reset_cv, bit) = match kind {
        CounterKind::Up => {
            let (up, prev) = edge_of(o, c.prev_up, s1, x.quiet);
            next.prev_up = prev;
            let max = o.k(i64::from(i16::MAX));
            let room = o.lt(c.cv, max);
            let step = o.and(up, room);
            let counted = o.add(c.cv, step);
            (counted, zero, o.ge(counted, x.preset))
        }
        CounterKind::Down => {
            let (down, prev) = edge_of(o, c.prev_down, s1, x.quiet);
            next.prev_down = prev;
            let room = o.gt(c.cv, zero);
            let step = o.and(down, room);
            let counted = o.sub(c.cv, step);
            (counted, x.preset, o.eq(counted, zero))
        }
        CounterKind::UpDown => {
            let (up, prev_up) = edge_of(o, c.prev_up, s2, x.quiet);
            let (down, prev_down) = edge_of(o, c.prev_down, s1, x.quiet);
            next.prev_up = prev_up;
            next.prev_down = prev_down;
            let counted = o.add(c.cv, up);
            let counted = o.sub(counted, down);
            let counted = o.wrap16(counted);
            (counted, zero, o.ge(counted, x.preset))
        }
    };
    next.cv = o.select(s0, reset_cv, counted);
    let kept = o.not(s0);
    let out = CounterBit {
        written: one,
        bit: o.and(kept, bit),
    };
    match policy {
        GatePolicy::S7Scr => (next, out),
        GatePolicy::OmronInterlock => {
            let closed = o.not(x.gate);
            let fields = CounterFields {
                cv: o.select(closed, c.cv, next.cv),
                prev_up: o.select(closed, c.prev_up, next.prev_up),
                prev_down: o.select(closed, c.prev_down, next.prev_down),
            };
            (
                fields,
                CounterBit {
                    written: x.gate,
                    bit: out.bit,
                },
            )
        }
    }
}

/// Executes a counter instruction on counter `n` (spec §5.3): [`Counter::step`] on the image,
/// with edges suppressed in the first scan as `rules` say ([`Rules::edges_suppressed`]).
/// Errors only for a counter the profile lacks.
#[allow(clippy::too_many_arguments)]
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    n: u16,
    kind: CounterKind,
    stack: u16,
    gate: Gate,
    preset: i16,
    rules: Rules,
) -> Result<(), ErrorCode> {
    block::object_run(layout, Area::CounterBit, n, 1)?;
    let [(v, _), (b, _), (st, _)] = layout.counter_bytes(n);
    let (mut value, mut state) = (mem::get_array(img, v), mem::get_array(img, st));
    let mut c = Counter::decode(value, &state);
    let quiet = rules.edges_suppressed(mem::sched_u8(img, layout, Sched::FIRST_SCAN));
    let bit = c.step(kind, stack, gate, preset, quiet);
    c.encode(&mut value, &mut state);
    mem::set_array(img, st, state);
    mem::set_array(img, v, value);
    if let Some(bit) = bit {
        mem::set_u8(img, b, u8::from(bit));
    }
    Ok(())
}

/// `R Cn, N`: clears CV and bit of `count` counters from `first`; edge memories are untouched
/// (spec §5.3). Past the last counter: 0x0091, nothing reset; `count = 0` is a no-op.
pub fn reset_range(
    img: &mut [u8],
    layout: &Layout,
    first: u16,
    count: u32,
) -> Result<(), ErrorCode> {
    for n in block::object_run(layout, Area::CounterBit, first, count)? {
        mem::set_i16_be(img, value_at(layout, n), 0);
        mem::set_u8(img, bit_at(layout, n), 0);
    }
    Ok(())
}

#[cfg(test)]
#[path = "counter_tests.rs"]
mod tests;
