//! The Omron instructions on the image: decode an object's bytes, run the rule of
//! [`crate::omron`] on plain values, encode the result and apply the condition-flag writes.
//! Both engines call these functions (the interpreter directly, the JIT through the
//! `stljit_rt_omron_*` shims), so the bytes an Omron timer, counter or data box leaves are the
//! same in both by construction.
//!
//! Byte layout (ARCHITECTURE.md "Omron memory"): a timer's PV is the big-endian word at
//! `TimerValue + 2n`, its completion flag the byte `TimerBit + n`, its hidden state
//! (omron-cp.md §2.12) `TimerState::RUN` (running), `TimerState::TOF` (ms not yet converted)
//! and `TimerState::LAST` (time of the last execution); a counter's PV and flag likewise, its
//! count-input memories `CounterState::PREV_UP` (count / increment) and `PREV_DOWN`
//! (decrement). The condition flags are bytes 0–1 of [`Area::Flags`], little-endian, in the
//! order of [`SystemBit`].

use crate::mem;
use crate::omron::flags::FlagWrites;
use crate::omron::{OmronCounter, OmronTimer, arith, data};
use crate::rules::Gate;
use stljit_core::Area;
use stljit_core::ir::{OmronArith, OmronBox, OmronCounterKind, OmronTimerKind};
use stljit_core::layout::{CounterState, Layout, Sched, TimerState};
use stljit_core::omron::SystemBit;

/// Applies `writes` to the condition flags.
pub fn apply_flags(img: &mut [u8], layout: &Layout, writes: FlagWrites) {
    let at = layout.base(Area::Flags);
    if layout.area_size(Area::Flags) < 2 {
        return;
    }
    let old = u16::from_le_bytes([mem::get_u8(img, at), mem::get_u8(img, at + 1)]);
    let [lo, hi] = writes.apply_bits(old).to_le_bytes();
    mem::set_u8(img, at, lo);
    mem::set_u8(img, at + 1, hi);
}

/// Executes Omron timer `n` of `kind` with the logic stack `stack` (bit i = `S_i`: the TIM
/// family's execution condition is `S0`; TTIM's timer input `S1`, reset `S0`) under `gate`,
/// with set value `sv` (the raw word). A timer number outside the profile does nothing (the
/// verifier rejects such a program).
pub fn timer(
    img: &mut [u8],
    layout: &Layout,
    kind: OmronTimerKind,
    n: u16,
    stack: u16,
    gate: Gate,
    sv: u16,
) {
    if u32::from(n) >= layout.area_size(Area::TimerBit) {
        return;
    }
    let [(value, _), (bit, _), (state, _)] = layout.timer_bytes(n);
    let t_ms = mem::get_u64_ne(img, layout.sched(Sched::T_NOW));
    let mut t = OmronTimer {
        pv: u16::from_be_bytes([mem::get_u8(img, value), mem::get_u8(img, value + 1)]),
        flag: mem::get_u8(img, bit) != 0,
        running: mem::get_u8(img, state + TimerState::RUN) != 0,
        last_ms: mem::get_u64_ne(img, state + TimerState::LAST),
        rem_ms: u32::from(mem::get_u8(img, state + TimerState::TOF)),
    };
    let (ec, reset) = if kind.totalizing() {
        (stack & 0b10 != 0, stack & 1 != 0)
    } else {
        (stack & 1 != 0, false)
    };
    let writes = t.step(kind, ec, reset, sv, t_ms, gate);
    let [hi, lo] = t.pv.to_be_bytes();
    mem::set_u8(img, value, hi);
    mem::set_u8(img, value + 1, lo);
    mem::set_u8(img, bit, u8::from(t.flag));
    mem::set_u8(img, state + TimerState::RUN, u8::from(t.running));
    // The remainder is below the unit (at most 99 ms), so it fits its byte.
    mem::set_u8(img, state + TimerState::TOF, t.rem_ms.min(255) as u8);
    mem::set_u64_ne(img, state + TimerState::LAST, t.last_ms);
    apply_flags(img, layout, writes);
}

/// Executes Omron counter `n` of `kind` with the logic stack `stack` (CNT: count `S1`, reset
/// `S0`; CNTR: increment `S2`, decrement `S1`, reset `S0`) under `gate`, set value `sv`.
pub fn counter(
    img: &mut [u8],
    layout: &Layout,
    kind: OmronCounterKind,
    n: u16,
    stack: u16,
    gate: Gate,
    sv: u16,
) {
    if u32::from(n) >= layout.area_size(Area::CounterBit) {
        return;
    }
    let [(value, _), (bit, _), (state, _)] = layout.counter_bytes(n);
    let mut c = OmronCounter {
        pv: u16::from_be_bytes([mem::get_u8(img, value), mem::get_u8(img, value + 1)]),
        flag: mem::get_u8(img, bit) != 0,
        prev_count: mem::get_u8(img, state + CounterState::PREV_UP) != 0,
        prev_dec: mem::get_u8(img, state + CounterState::PREV_DOWN) != 0,
    };
    let s = |i: u16| stack & (1 << i) != 0;
    let inputs = if kind.ring() {
        [s(2), s(1), s(0)]
    } else {
        [s(1), false, s(0)]
    };
    let writes = c.step(kind, inputs, sv, gate);
    let [hi, lo] = c.pv.to_be_bytes();
    mem::set_u8(img, value, hi);
    mem::set_u8(img, value + 1, lo);
    mem::set_u8(img, bit, u8::from(c.flag));
    mem::set_u8(img, state + CounterState::PREV_UP, u8::from(c.prev_count));
    mem::set_u8(img, state + CounterState::PREV_DOWN, u8::from(c.prev_dec));
    apply_flags(img, layout, writes);
}

/// The Omron value of a double-word operand read as the IR's big-endian dword: Omron keeps the
/// low 16 bits in the lower-numbered word (omron-cp.md §1.6), which big-endian storage puts
/// first, so the halves swap.
#[inline]
pub fn double_of_be(be: u32) -> u32 {
    be.rotate_left(16)
}

/// Writes `words` (word 0 first) as Omron words from image offset `at`.
fn write_words(img: &mut [u8], at: u32, words: &[u16]) {
    for (i, w) in words.iter().enumerate() {
        let [hi, lo] = w.to_be_bytes();
        let a = at + 2 * i as u32;
        mem::set_u8(img, a, hi);
        mem::set_u8(img, a + 1, lo);
    }
}

/// An Omron box as one integer for the JIT's shim (`stljit_rt_omron_box`): `MOV` 0, `MOVL` 1,
/// the compares 2–5 (`2 + 2·double + signed`), the arithmetic `6 + position in OmronArith::ALL`.
pub fn box_code(b: &OmronBox) -> u32 {
    match *b {
        OmronBox::Move { double, .. } => u32::from(double),
        OmronBox::Compare { double, signed, .. } => 2 + 2 * u32::from(double) + u32::from(signed),
        OmronBox::Arith { op, .. } => {
            6 + OmronArith::ALL.iter().position(|&a| a == op).unwrap_or(0) as u32
        }
    }
}

/// Runs the box of code `code` (see [`box_code`]) on the operand values `a` and `b` (Omron
/// order: a double's low word in the low 16 bits), writing a result to image offset `dst`
/// (unused by the compares) and the condition flags. `false` for an unknown code.
pub fn run_box(img: &mut [u8], layout: &Layout, code: u32, a: u32, b: u32, dst: u32) -> bool {
    match code {
        0 | 1 => {
            let double = code == 1;
            let (v, writes) = data::mov(double, a);
            if double {
                write_words(img, dst, &[v as u16, (v >> 16) as u16]);
            } else {
                write_words(img, dst, &[v as u16]);
            }
            apply_flags(img, layout, writes);
        }
        2..=5 => {
            let double = code >= 4;
            let signed = code % 2 == 1;
            apply_flags(img, layout, data::compare(double, signed, a, b));
        }
        _ => {
            let Some(&op) = OmronArith::ALL.get((code - 6) as usize) else {
                return false;
            };
            let cy = {
                let at = layout.base(Area::Flags);
                let bit = SystemBit::Cy.bit_loc();
                layout.area_size(Area::Flags) > 0
                    && mem::get_u8(img, at + bit.byte) & (1 << bit.bit) != 0
            };
            let out = arith::execute(op, a, b, cy);
            if let Some(words) = out.words() {
                let n = op.result_words() as usize;
                write_words(img, dst, &words[..n]);
            }
            apply_flags(img, layout, out.flags);
        }
    }
    true
}
