//! Lean timer shims for compiled code. Part of [`crate::ffi`]; its table applies.
//!
//! The JIT knows the image layout at compile time, so instead of `(image, layout, n)` it passes
//! pointers to exactly the bytes one execution touches: the timer's value, its bit, its private
//! state block and the scan's 100-ms delta. The shim decodes them into the runtime's typed view,
//! runs the same rule the interpreter runs ([`Timer::step`], [`crate::timer::timer_rule`]) and
//! encodes the result back: no layout lookup, no slice bounds check, no `catch_unwind`.
//!
//! **Why timers call a shim and counters do not:** the JIT emits both rules inline from the same
//! rule text ([`crate::rule_ops`]); counters run that way (callgrind on mixed_10k: 39 Ir per
//! CTU inline against 56 through a shim), but LLVM compiles the timer rule tighter than
//! Cranelift does (memory-operand compares, fewer registers), so a TON costs 44 Ir through this
//! shim and 55 inline (docs/performance.md). Compiled code under rules these shims are not
//! specialised to emits the timer rule inline instead.
//!
//! **Why no `catch_unwind`:** between entry and return these shims only do fixed-size array
//! accesses with constant in-bounds indices, `from_be_bytes`/`to_be_bytes`, and the step
//! function, which contains no indexing, no division, no `unwrap`, and only arithmetic that
//! cannot overflow (wrapping `i64` ops on values decoded from bytes). So they cannot panic, in
//! release or debug builds, and nothing can unwind across `extern "C"`. Keep it that way when
//! editing `timer_rule`.
//!
//! There is one shim per kind (`ton`, `tonr`, `tof`): the kind is known
//! at compile time, so each shim is the step function specialised to it, with no dispatch.
//! `ctl` packs the small arguments so that every argument travels in a register on x86-64 and
//! AArch64: bit 0 the input (`S0`), bit 8 the gate ([`CTL_GATE`]); other bits are ignored.
//!
//! The shims are also specialised to the gate policy of the SCR enable
//! ([`crate::rules::SCR_POLICY`]) and to [`Rules::IN_FORCE`], so that both fold away: compiled
//! code that follows other rules (tests) emits the rule inline. See [`fast_shims_apply`].

use super::{CTL_GATE, RT_OK, gate_word_fixed};
use crate::rules::{Gate, Rules, SCR_POLICY};
use crate::timer::{STATE_BYTES, Timer};
use stljit_core::ir::TimerKind;
use stljit_core::layout::TimerState;

/// Offset of the PT cache in a timer's state block.
const PT_CACHE: usize = TimerState::PT_CACHE as usize;
const _: () = assert!(PT_CACHE + 2 <= STATE_BYTES);

/// Whether the fast shims implement `rules` with the SCR gate policy (else compiled code emits
/// the timer rule inline).
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
    // The PT cache is read with a volatile load, so that it is loaded whatever IN is: LLVM
    // otherwise compiles `timer_rule`'s select of the old PT cache as a branch around its load,
    // which the inputs (following the plant) mispredict about half the time (docs/performance.md,
    // "Timer and counter rules written once").
    // SAFETY: the caller guarantees the state block is valid for reads of its size, and
    // `PT_CACHE + 2 <= STATE_BYTES`; it is read before any reference to the block exists.
    let pt_cache = unsafe { state.add(PT_CACHE).cast::<[u8; 2]>().read_volatile() };
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
    let mut seen = *state;
    [seen[PT_CACHE], seen[PT_CACHE + 1]] = pt_cache;
    let mut t = Timer::decode(value, *bit, &seen);
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

/// Defines the per-kind `extern "C"` shims over [`timer_fast`].
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

/// The fast timer shim for `kind`, as a function pointer (for tests and symbol tables).
pub fn timer_fast_fn(kind: TimerKind) -> FastFn {
    match kind {
        TimerKind::On => stljit_rt_ton_fast,
        TimerKind::Retentive => stljit_rt_tonr_fast,
        TimerKind::Off => stljit_rt_tof_fast,
    }
}

/// The type of every fast shim.
pub type FastFn = unsafe extern "C" fn(*mut u8, *mut u8, *mut u8, *const u8, u32, i32) -> u32;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rule_ops::spec_rows::{TIMER_ROWS, timer_bytes};

    #[test]
    fn timer_fast_shims_follow_spec_5_2() {
        // The JIT's path for timers: the kind's fast shim on the same bytes.
        for (i, &(kind, res, before, input, gate, pt, d100, after)) in TIMER_ROWS.iter().enumerate()
        {
            let mut b = timer_bytes(kind, res, before);
            let d = d100.to_ne_bytes();
            let ctl = u32::from(input) | if gate { CTL_GATE } else { 0 };
            // SAFETY: four distinct live locals of the documented sizes.
            let st = unsafe {
                timer_fast_fn(kind)(
                    b.value.as_mut_ptr(),
                    &mut b.bit,
                    b.state.as_mut_ptr(),
                    d.as_ptr(),
                    ctl | 0xFFFF_0000, // bits above the gate are ignored
                    i32::from(pt),
                )
            };
            assert_eq!(st, RT_OK, "row {i}");
            assert_eq!(b, timer_bytes(kind, res, after), "row {i}");
        }
    }
}
