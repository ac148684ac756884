//! Counters `CTU`/`CTD`/`CTUD` (spec §5.3), as functions on the image bytes.
//!
//! Inputs come from logic-stack levels (spec §4.5); the caller passes the whole stack as a bit
//! vector (`bit i = S_i`) so that the level assignment lives here and nowhere else.
//!
//! The rules of an execution live in [`Counter::step`], over a decoded [`Counter`]. The
//! interpreter reaches them through [`execute`] (layout lookups, range check), the JIT through
//! [`crate::ffi::stljit_rt_counter_fast`] (offsets fixed at compile time).

use crate::rules::{Gate, GatePolicy, Rules};
use crate::{block, mem};
use std::hint::select_unpredictable;
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

/// Rising edge of `input` against the memory `prev`, which takes the new input; no edge while
/// `quiet` (first scan, [`Rules::edges_suppressed`]).
#[inline]
fn edge_of(prev: &mut u8, input: bool, quiet: bool) -> bool {
    let was = *prev != 0;
    *prev = u8::from(input);
    input && !was && !quiet
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
    /// or `None` when the bit keeps its value. `stack` holds the logic stack (`bit i = S_i`);
    /// each input is `S_k`, or 0 under a gate closed by [`GatePolicy::S7Scr`]; a gate closed
    /// by [`GatePolicy::OmronInterlock`] does not execute the counter (value, bit and edge
    /// memories kept). `quiet` suppresses edges (the first-scan rule); the edge memories are
    /// updated even while R/LD is on (TC10). Cannot panic: no indexing or division, increments
    /// are guarded or wrapping.
    #[inline]
    pub fn step(
        &mut self,
        kind: CounterKind,
        stack: u16,
        gate: Gate,
        preset: i16,
        quiet: bool,
    ) -> Option<bool> {
        let stack = match gate {
            Gate::Open => stack,
            Gate::Closed(GatePolicy::S7Scr) => 0,
            Gate::Closed(GatePolicy::OmronInterlock) => return None,
        };
        let s = |k: u16| (stack >> k) & 1 != 0;
        let c = self;
        // `S0` (R, or LD for CTD) wins over counting; otherwise an edge counts once. Written
        // as selects, not branches, for the reason given in `Timer::step`.
        let reset = s(0);
        let (counted, reset_cv, bit) = match kind {
            CounterKind::Up => {
                let up = edge_of(&mut c.prev_up, s(1), quiet);
                let counted = c.cv + i16::from(up & (c.cv < i16::MAX));
                (counted, 0, counted >= preset)
            }
            CounterKind::Down => {
                let down = edge_of(&mut c.prev_down, s(1), quiet);
                let counted = c.cv - i16::from(down & (c.cv > 0));
                (counted, preset, counted == 0)
            }
            CounterKind::UpDown => {
                let up = edge_of(&mut c.prev_up, s(2), quiet);
                let down = edge_of(&mut c.prev_down, s(1), quiet);
                let counted =
                    c.cv.wrapping_add(i16::from(up))
                        .wrapping_sub(i16::from(down));
                (counted, 0, counted >= preset)
            }
        };
        c.cv = select_unpredictable(reset, reset_cv, counted);
        Some(!reset & bit)
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
