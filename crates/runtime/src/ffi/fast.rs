//! Lean timer and counter shims for compiled code. Part of [`crate::ffi`]; its table applies.
//!
//! The JIT knows the image layout at compile time, so instead of `(image, layout, n)` it passes
//! pointers to exactly the bytes one execution touches: the object's value, its bit, its private
//! state block and one scheduler field. The shim decodes them into the runtime's typed view,
//! runs the same rule function the interpreter runs ([`Timer::step`], [`Counter::step`]) and
//! encodes the result back: no layout lookup, no slice bounds check, no `catch_unwind`.
//!
//! **Why no `catch_unwind`:** between entry and return these shims only do fixed-size array
//! accesses with constant in-bounds indices, `from_be_bytes`/`to_be_bytes`, and the step
//! functions, which contain no indexing, no division, no `unwrap`, and only arithmetic that
//! cannot overflow (`i64` sums of an `i16` and a `u32`, guarded `+= 1`/`-= 1`, wrapping ops).
//! So they cannot panic, in release or debug builds, and nothing can unwind across
//! `extern "C"`. Keep it that way when editing `step`.
//!
//! `ctl` packs the small arguments so that every argument travels in a register on x86-64 and
//! AArch64: bits 0–7 the input(s) (timer: `S0` 0/1; counter: logic-stack levels 0–2,
//! `bit i = S_i`), bit 8 the SCR gate ([`CTL_GATE`]), bits 16–23 the kind's `code()`
//! ([`CTL_KIND_SHIFT`]).

use super::{RT_BAD_ARGUMENT, RT_OK, counter_kind, timer_kind};
use crate::counter::Counter;
use crate::edge;
use crate::timer::{STATE_BYTES, Timer};
use stljit_core::layout::COUNTER_STATE_SIZE;

/// `ctl` bit: the SCR gate is open.
pub const CTL_GATE: u32 = 1 << 8;
/// `ctl` shift of the kind's `code()`.
pub const CTL_KIND_SHIFT: u32 = 16;

/// [`Timer::step`] on one timer's bytes: `value` (2 bytes, big-endian CV), `bit` (1),
/// `state` ([`STATE_BYTES`]), `d100` (the scan's native-endian `u32` 100-ms delta). Returns
/// [`RT_OK`], or [`RT_BAD_ARGUMENT`] (nothing touched) for an unknown kind.
///
/// # Safety
/// Each pointer must be valid for reads and writes of its size (`d100`: reads), the four ranges
/// must not overlap, and nothing else may access them during the call. Alignment does not
/// matter (byte arrays). The JIT derives them from the program's layout for a timer the profile
/// has, inside the image it runs on.
pub unsafe extern "C" fn stljit_rt_timer_fast(
    value: *mut u8,
    bit: *mut u8,
    state: *mut u8,
    d100: *const u8,
    ctl: u32,
    preset: i32,
) -> u32 {
    let Some(kind) = timer_kind(ctl >> CTL_KIND_SHIFT) else {
        return RT_BAD_ARGUMENT;
    };
    // SAFETY: the caller guarantees each range is valid, disjoint from the others and not
    // accessed elsewhere during the call; `[u8; N]` has alignment 1, so any address is aligned.
    let (value, bit, state, d100) = unsafe {
        (
            &mut *value.cast::<[u8; 2]>(),
            &mut *bit,
            &mut *state.cast::<[u8; STATE_BYTES]>(),
            d100.cast::<[u8; 4]>().read(),
        )
    };
    let mut t = Timer::decode(value, *bit, state);
    t.step(
        kind,
        ctl & 1 != 0,
        ctl & CTL_GATE != 0,
        preset as i16,
        u32::from_ne_bytes(d100),
    );
    t.encode(value, bit, state);
    RT_OK
}

/// [`Counter::step`] on one counter's bytes: `value` (2 bytes, big-endian CV), `bit` (1),
/// `state` ([`COUNTER_STATE_SIZE`]), `first_scan` (the scan's first-scan flag byte, for
/// [`edge::suppressed`]). Returns [`RT_OK`], or [`RT_BAD_ARGUMENT`] (nothing touched) for an
/// unknown kind.
///
/// # Safety
/// As [`stljit_rt_timer_fast`]: valid, disjoint ranges of the stated sizes, exclusively borrowed
/// for the call (`first_scan` is only read).
pub unsafe extern "C" fn stljit_rt_counter_fast(
    value: *mut u8,
    bit: *mut u8,
    state: *mut u8,
    first_scan: *const u8,
    ctl: u32,
    preset: i32,
) -> u32 {
    let Some(kind) = counter_kind(ctl >> CTL_KIND_SHIFT) else {
        return RT_BAD_ARGUMENT;
    };
    // SAFETY: as in `stljit_rt_timer_fast`: valid, disjoint, exclusive, alignment 1.
    let (value, bit, state, first_scan) = unsafe {
        (
            &mut *value.cast::<[u8; 2]>(),
            &mut *bit,
            &mut *state.cast::<[u8; COUNTER_STATE_SIZE as usize]>(),
            first_scan.read(),
        )
    };
    let mut c = Counter::decode(*value, state);
    let on = c.step(
        kind,
        (ctl & 0xFF) as u16,
        ctl & CTL_GATE != 0,
        preset as i16,
        edge::suppressed(first_scan),
    );
    c.encode(value, state);
    *bit = u8::from(on);
    RT_OK
}

#[cfg(test)]
#[path = "fast_tests.rs"]
mod tests;
