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
//! There is one shim per kind (`ton`, `tonr`, `tof`, `ctu`, `ctd`, `ctud`): the kind is known
//! at compile time, so each shim is the step function specialised to it, with no dispatch.
//! `ctl` packs the small arguments so that every argument travels in a register on x86-64 and
//! AArch64: bits 0–7 the input(s) (timer: `S0` 0/1; counter: logic-stack levels 0–2,
//! `bit i = S_i`), bit 8 the gate ([`CTL_GATE`]); other bits are ignored.
//!
//! The shims are also specialised to the gate policy of the SCR enable
//! ([`crate::rules::SCR_POLICY`]) and to [`Rules::IN_FORCE`], so that both fold away: compiled
//! code that follows other rules (tests) calls the general shims `stljit_rt_timer` /
//! `stljit_rt_counter`, which take a full gate word ([`super::decode_gate_word`]). See
//! [`fast_shims_apply`].

use super::{GATE_OPEN, RT_OK, gate_word_fixed};
use crate::counter::Counter;
use crate::rules::{Gate, Rules, SCR_POLICY};
use crate::timer::{STATE_BYTES, Timer};
use stljit_core::ir::{CounterKind, TimerKind};
use stljit_core::layout::COUNTER_STATE_SIZE;

/// `ctl` bit: the gate is open.
pub const CTL_GATE: u32 = GATE_OPEN << 8;

/// Whether the fast shims implement `rules` with the SCR gate policy (else compiled code must
/// call the general shims).
pub fn fast_shims_apply(rules: Rules) -> bool {
    gate_word_fixed(SCR_POLICY, rules) == gate_word_fixed(SCR_POLICY, Rules::IN_FORCE)
}

/// [`Timer::step`] for `kind` on one timer's bytes: `value` (2 bytes, big-endian CV), `bit` (1),
/// `state` ([`STATE_BYTES`]), `d100` (the scan's native-endian `u32` 100-ms delta).
///
/// # Safety
/// Each pointer must be valid for reads and writes of its size (`d100`: reads), the four ranges
/// must not overlap, and nothing else may access them during the call. Alignment does not
/// matter (byte arrays). The JIT derives them from the program's layout for a timer the profile
/// has, inside the image it runs on.
#[inline(always)]
unsafe fn timer_fast(
    kind: TimerKind,
    value: *mut u8,
    bit: *mut u8,
    state: *mut u8,
    d100: *const u8,
    ctl: u32,
    preset: i32,
) -> u32 {
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
    let gate = Gate::scr(ctl & CTL_GATE != 0);
    t.step(
        kind,
        ctl & 1 != 0,
        gate,
        preset as i16,
        u32::from_ne_bytes(d100),
    );
    t.encode(value, bit, state);
    RT_OK
}

/// [`Counter::step`] for `kind` on one counter's bytes: `value` (2 bytes, big-endian CV), `bit`
/// (1), `state` ([`COUNTER_STATE_SIZE`]), `first_scan` (the scan's first-scan flag byte, for
/// [`crate::rules::Rules::edges_suppressed`]).
///
/// # Safety
/// As [`timer_fast`]: valid, disjoint ranges of the stated sizes, exclusively borrowed for the
/// call (`first_scan` is only read).
#[inline(always)]
unsafe fn counter_fast(
    kind: CounterKind,
    value: *mut u8,
    bit: *mut u8,
    state: *mut u8,
    first_scan: *const u8,
    ctl: u32,
    preset: i32,
) -> u32 {
    // SAFETY: as in `timer_fast`: valid, disjoint, exclusive, alignment 1.
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
        Gate::scr(ctl & CTL_GATE != 0),
        preset as i16,
        Rules::IN_FORCE.edges_suppressed(first_scan),
    );
    c.encode(value, state);
    if let Some(on) = on {
        *bit = u8::from(on);
    }
    RT_OK
}

/// Defines the per-kind `extern "C"` shims over [`timer_fast`] / [`counter_fast`].
macro_rules! fast_shims {
    ($inner:ident, $kty:ident, $last:ident: $($name:ident => $kind:ident, $what:literal;)+) => {$(
        #[doc = concat!("`", $what, "` on one object's bytes (module docs); returns [`RT_OK`].")]
        ///
        /// # Safety
        /// Each pointer must be valid for reads and writes of its size (value 2, bit 1, the
        /// state block; the scheduler field: reads), the ranges must not overlap, and nothing
        /// else may access them during the call.
        pub unsafe extern "C" fn $name(
            value: *mut u8,
            bit: *mut u8,
            state: *mut u8,
            $last: *const u8,
            ctl: u32,
            preset: i32,
        ) -> u32 {
            // SAFETY: forwarded caller contract.
            unsafe { $inner($kty::$kind, value, bit, state, $last, ctl, preset) }
        }
    )+};
}

fast_shims!(timer_fast, TimerKind, d100:
    stljit_rt_ton_fast => On, "TON";
    stljit_rt_tonr_fast => Retentive, "TONR";
    stljit_rt_tof_fast => Off, "TOF";
);
fast_shims!(counter_fast, CounterKind, first_scan:
    stljit_rt_ctu_fast => Up, "CTU";
    stljit_rt_ctd_fast => Down, "CTD";
    stljit_rt_ctud_fast => UpDown, "CTUD";
);

/// The fast timer shim for `kind`, as a function pointer (for tests and symbol tables).
pub fn timer_fast_fn(kind: TimerKind) -> FastFn {
    match kind {
        TimerKind::On => stljit_rt_ton_fast,
        TimerKind::Retentive => stljit_rt_tonr_fast,
        TimerKind::Off => stljit_rt_tof_fast,
    }
}

/// The fast counter shim for `kind`.
pub fn counter_fast_fn(kind: CounterKind) -> FastFn {
    match kind {
        CounterKind::Up => stljit_rt_ctu_fast,
        CounterKind::Down => stljit_rt_ctd_fast,
        CounterKind::UpDown => stljit_rt_ctud_fast,
    }
}

/// The type of every fast shim.
pub type FastFn = unsafe extern "C" fn(*mut u8, *mut u8, *mut u8, *const u8, u32, i32) -> u32;

#[cfg(test)]
#[path = "fast_tests.rs"]
mod tests;
