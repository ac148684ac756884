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
use stljit_core::layout::{
    COUNTER_STATE_SIZE, CounterState, Layout, Sched, TIMER_STATE_SIZE, TimerState,
};
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

/// One Omron timer's bytes: PV (big-endian), completion flag, private state.
pub type TimerBytes = ([u8; 2], u8, [u8; TIMER_STATE_SIZE as usize]);

/// One Omron counter's bytes: PV, completion flag, private state.
pub type CounterBytes = ([u8; 2], u8, [u8; COUNTER_STATE_SIZE as usize]);

/// Executes Omron timer instruction `kind` on one timer's bytes `t` at virtual time `t_ms` with
/// the logic stack `stack` (bit i = `S_i`: the TIM family's execution condition is `S0`; TTIM's
/// timer input `S1`, reset `S0`) under `gate`, with set value `sv` (the raw word); returns the
/// condition-flag writes. Both engines' timer paths end here.
pub fn timer_step(
    t: &mut TimerBytes,
    t_ms: u64,
    kind: OmronTimerKind,
    stack: u16,
    gate: Gate,
    sv: u16,
) -> FlagWrites {
    let (value, flag, state) = t;
    let last = |s: &[u8; TIMER_STATE_SIZE as usize]| {
        let at = TimerState::LAST as usize;
        let mut b = [0; 8];
        b.copy_from_slice(&s[at..at + 8]);
        u64::from_ne_bytes(b)
    };
    let mut timer = OmronTimer {
        pv: u16::from_be_bytes(*value),
        flag: *flag != 0,
        running: state[TimerState::RUN as usize] != 0,
        last_ms: last(state),
        rem_ms: u32::from(state[TimerState::TOF as usize]),
    };
    let (ec, reset) = if kind.totalizing() {
        (stack & 0b10 != 0, stack & 1 != 0)
    } else {
        (stack & 1 != 0, false)
    };
    let writes = timer.step(kind, ec, reset, sv, t_ms, gate);
    *value = timer.pv.to_be_bytes();
    *flag = u8::from(timer.flag);
    state[TimerState::RUN as usize] = u8::from(timer.running);
    // The remainder is below the unit (at most 99 ms), so it fits its byte.
    state[TimerState::TOF as usize] = timer.rem_ms.min(255) as u8;
    let at = TimerState::LAST as usize;
    state[at..at + 8].copy_from_slice(&timer.last_ms.to_ne_bytes());
    writes
}

/// Executes Omron counter instruction `kind` on one counter's bytes `c` with the logic stack
/// `stack` (CNT: count `S1`, reset `S0`; CNTR: increment `S2`, decrement `S1`, reset `S0`)
/// under `gate`, set value `sv`; returns the condition-flag writes.
pub fn counter_step(
    c: &mut CounterBytes,
    kind: OmronCounterKind,
    stack: u16,
    gate: Gate,
    sv: u16,
) -> FlagWrites {
    let (value, flag, state) = c;
    let mut counter = OmronCounter {
        pv: u16::from_be_bytes(*value),
        flag: *flag != 0,
        prev_count: state[CounterState::PREV_UP as usize] != 0,
        prev_dec: state[CounterState::PREV_DOWN as usize] != 0,
    };
    let s = |i: u16| stack & (1 << i) != 0;
    let inputs = if kind.ring() {
        [s(2), s(1), s(0)]
    } else {
        [s(1), false, s(0)]
    };
    let writes = counter.step(kind, inputs, sv, gate);
    *value = counter.pv.to_be_bytes();
    *flag = u8::from(counter.flag);
    state[CounterState::PREV_UP as usize] = u8::from(counter.prev_count);
    state[CounterState::PREV_DOWN as usize] = u8::from(counter.prev_dec);
    writes
}

/// Copies `N` image bytes from `at` (zeros past the end, which the callers' range checks rule
/// out).
fn take<const N: usize>(img: &[u8], at: u32) -> [u8; N] {
    let mut b = [0; N];
    for (i, v) in b.iter_mut().enumerate() {
        *v = mem::get_u8(img, at + i as u32);
    }
    b
}

fn put(img: &mut [u8], at: u32, bytes: &[u8]) {
    for (i, &v) in bytes.iter().enumerate() {
        mem::set_u8(img, at + i as u32, v);
    }
}

/// [`timer_step`] on timer `n` of the image (a number outside the profile does nothing; the
/// verifier rejects such a program), the flags applied.
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
    let mut t = (take(img, value), mem::get_u8(img, bit), take(img, state));
    let writes = timer_step(&mut t, t_ms, kind, stack, gate, sv);
    put(img, value, &t.0);
    mem::set_u8(img, bit, t.1);
    put(img, state, &t.2);
    apply_flags(img, layout, writes);
}

/// [`counter_step`] on counter `n` of the image, the flags applied.
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
    let mut c = (take(img, value), mem::get_u8(img, bit), take(img, state));
    let writes = counter_step(&mut c, kind, stack, gate, sv);
    put(img, value, &c.0);
    mem::set_u8(img, bit, c.1);
    put(img, state, &c.2);
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
