//! Counters `CTU`/`CTD`/`CTUD` (spec §5.3), as functions on the image bytes.
//!
//! Inputs come from logic-stack levels (spec §4.5); the caller passes the whole stack as a bit
//! vector (`bit i = S_i`) so that the level assignment lives here and nowhere else.

use crate::{edge, mem};
use stljit_core::ir::CounterKind;
use stljit_core::layout::{CounterState, Layout};
use stljit_core::{Area, ErrorCode};

fn value_at(layout: &Layout, n: u16) -> u32 {
    layout.base(Area::CounterValue) + 2 * u32::from(n)
}

fn bit_at(layout: &Layout, n: u16) -> u32 {
    layout.base(Area::CounterBit) + u32::from(n)
}

/// Executes a counter instruction on counter `n` (spec §5.3). `stack` holds the logic stack
/// (`bit i = S_i`); each input is `S_k AND gate`. Edges are suppressed in the first scan
/// ([`edge::edges_suppressed`]); the edge memories are updated even while R/LD is on (TC10).
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    n: u16,
    kind: CounterKind,
    stack: u16,
    gate: bool,
    preset: i16,
) -> Result<(), ErrorCode> {
    if u32::from(n) >= layout.area_size(Area::CounterBit) {
        return Err(ErrorCode::OperandRange);
    }
    let s = |k: u16| gate && (stack >> k) & 1 != 0;
    let st = layout.counter_state(n);
    let quiet = edge::edges_suppressed(img, layout);
    let edge_of = |img: &mut [u8], field: u32, input: bool| {
        let prev = mem::get_u8(img, st + field) != 0;
        mem::set_u8(img, st + field, u8::from(input));
        input && !prev && !quiet
    };
    let mut cv = mem::get_i16_be(img, value_at(layout, n));
    let bit = match kind {
        CounterKind::Up => {
            let up = edge_of(img, CounterState::PREV_UP, s(1));
            if s(0) {
                cv = 0;
                false
            } else {
                if up && cv < i16::MAX {
                    cv += 1;
                }
                cv >= preset
            }
        }
        CounterKind::Down => {
            let down = edge_of(img, CounterState::PREV_DOWN, s(1));
            if s(0) {
                cv = preset;
                false
            } else {
                if down && cv > 0 {
                    cv -= 1;
                }
                cv == 0
            }
        }
        CounterKind::UpDown => {
            let up = edge_of(img, CounterState::PREV_UP, s(2));
            let down = edge_of(img, CounterState::PREV_DOWN, s(1));
            if s(0) {
                cv = 0;
                false
            } else {
                if up {
                    cv = cv.wrapping_add(1);
                }
                if down {
                    cv = cv.wrapping_sub(1);
                }
                cv >= preset
            }
        }
    };
    mem::set_i16_be(img, value_at(layout, n), cv);
    mem::set_u8(img, bit_at(layout, n), u8::from(bit));
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
    if u32::from(first) + count > layout.area_size(Area::CounterBit) {
        return Err(ErrorCode::OperandRange);
    }
    for n in u32::from(first)..u32::from(first) + count {
        mem::set_i16_be(img, value_at(layout, n as u16), 0);
        mem::set_u8(img, bit_at(layout, n as u16), 0);
    }
    Ok(())
}

/// Resets one counter.
pub fn reset(img: &mut [u8], layout: &Layout, n: u16) -> Result<(), ErrorCode> {
    reset_range(img, layout, n, 1)
}

#[cfg(test)]
#[path = "counter_tests.rs"]
mod tests;
