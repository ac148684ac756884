//! The Omron shims (`stljit_rt_omron_*`): the JIT's way into [`crate::omron_image`], under the
//! module conventions of [`super`]. The timer and counter shims are lean (pointers to the object's bytes, computed from the layout at compile time) and return
//! the condition-flag writes for compiled code to apply; kinds travel as their position in
//! core's `ALL` lists, set values and operand values as `u32` (Omron value order).

use super::status_of;
use crate::omron_image;
use crate::rules::Gate;
use std::panic::{AssertUnwindSafe, catch_unwind};
use stljit_core::ir::{OmronCounterKind, OmronTimerKind};
use stljit_core::layout::{COUNTER_STATE_SIZE, Layout, TIMER_STATE_SIZE};

/// `ctl` of the fast Omron shims: bits 0–2 the logic-stack levels 0–2, bit 8 the gate open
/// ([`super::CTL_GATE`]); other bits are ignored.
const CTL_LEVELS: u32 = 0b111;

/// The packed condition-flag writes a fast Omron shim returns: the mask in bits 16–31, the
/// values in bits 0–15 (both in the `Flags` area's little-endian bit order).
pub fn pack_flag_writes(w: crate::omron::FlagWrites) -> u32 {
    u32::from(w.mask) << 16 | u32::from(w.value & w.mask)
}

/// The levels and the gate of a fast shim's `ctl`.
fn ctl_parts(ctl: u32) -> (u16, Gate) {
    let gate = Gate::with(
        ctl & super::CTL_GATE != 0,
        stljit_core::GatePolicy::OmronInterlock,
    );
    ((ctl & CTL_LEVELS) as u16, gate)
}

/// [`omron_image::timer_step`] for `kind` on one timer's bytes.
///
/// **Why no `catch_unwind`:** between entry and return
/// this does fixed-size array accesses with constant in-bounds indices and runs
/// `OmronTimer::step`, whose arithmetic saturates, whose divisions are by a timer unit (never
/// 0, and `max(1)` where it is not a constant) and whose BCD conversions are total; so it cannot
/// panic and nothing unwinds across `extern "C"`. Keep it that way when editing `step`.
///
/// # Safety
/// Each pointer must be valid for reads and writes of its size (`now`: reads), the ranges must
/// not overlap, and nothing else may access them during the call. The JIT derives them from
/// the program's layout for a timer the profile has, inside the image it runs on.
#[inline(always)]
unsafe fn timer_fast(
    kind: OmronTimerKind,
    value: *mut u8,
    flag: *mut u8,
    state: *mut u8,
    now: *const u8,
    ctl: u32,
    sv: u32,
) -> u32 {
    let (stack, gate) = ctl_parts(ctl);
    // SAFETY: the caller's contract: valid, disjoint, exclusively ours for the call.
    let (value, flag, state, now) = unsafe {
        (
            &mut *value.cast::<[u8; 2]>(),
            &mut *flag,
            &mut *state.cast::<[u8; TIMER_STATE_SIZE as usize]>(),
            u64::from_ne_bytes(*now.cast::<[u8; 8]>()),
        )
    };
    let w = omron_image::timer_step((value, flag, state), now, kind, stack, gate, sv as u16);
    pack_flag_writes(w)
}

/// [`omron_image::counter_step`] for `kind` on one counter's bytes; as [`timer_fast`] (no
/// `now`), and no `catch_unwind` for the same reason: `OmronCounter::step` counts only where
/// the result stays in range (`pv + 1` below the set value, `pv - 1` above 0).
///
/// # Safety
/// As [`timer_fast`].
#[inline(always)]
unsafe fn counter_fast(
    kind: OmronCounterKind,
    value: *mut u8,
    flag: *mut u8,
    state: *mut u8,
    ctl: u32,
    sv: u32,
) -> u32 {
    let (stack, gate) = ctl_parts(ctl);
    // SAFETY: the caller's contract: valid, disjoint, exclusively ours for the call.
    let (value, flag, state) = unsafe {
        (
            &mut *value.cast::<[u8; 2]>(),
            &mut *flag,
            &mut *state.cast::<[u8; COUNTER_STATE_SIZE as usize]>(),
        )
    };
    let w = omron_image::counter_step((value, flag, state), kind, stack, gate, sv as u16);
    pack_flag_writes(w)
}

/// Defines one `extern "C"` shim per Omron timer or counter kind, each the inner function
/// specialised to its kind (no dispatch, constant units and number formats), and the table
/// from kind to shim.
macro_rules! omron_fast_shims {
    (@one $name:ident, $kind:expr, $inner:ident ($($arg:ident: $ty:ty),*)) => {
        #[doc = concat!("`", stringify!($kind), "` on one object's bytes ([`", stringify!($inner), "`]).")]
        ///
        /// # Safety
        #[doc = concat!("As [`", stringify!($inner), "`].")]
        pub unsafe extern "C" fn $name($($arg: $ty),*) -> u32 {
            // SAFETY: forwarded caller contract.
            unsafe { $inner($kind, $($arg),*) }
        }
    };
    (timers: $($name:ident => $kind:ident;)+) => {
        $(omron_fast_shims!(@one $name, OmronTimerKind::$kind, timer_fast(
            value: *mut u8, flag: *mut u8, state: *mut u8, now: *const u8, ctl: u32, sv: u32));)+

        /// The fast shim of an Omron timer kind.
        pub fn omron_timer_fast_fn(kind: OmronTimerKind) -> OmronTimerFn {
            match kind {
                $(OmronTimerKind::$kind => $name,)+
            }
        }
    };
    (counters: $($name:ident => $kind:ident;)+) => {
        $(omron_fast_shims!(@one $name, OmronCounterKind::$kind, counter_fast(
            value: *mut u8, flag: *mut u8, state: *mut u8, ctl: u32, sv: u32));)+

        /// The fast shim of an Omron counter kind.
        pub fn omron_counter_fast_fn(kind: OmronCounterKind) -> OmronCounterFn {
            match kind {
                $(OmronCounterKind::$kind => $name,)+
            }
        }
    };
}

/// The type of every fast Omron timer shim: `(value, flag, state, now, ctl, sv)`.
pub type OmronTimerFn = unsafe extern "C" fn(*mut u8, *mut u8, *mut u8, *const u8, u32, u32) -> u32;
/// The type of every fast Omron counter shim: `(value, flag, state, ctl, sv)`.
pub type OmronCounterFn = unsafe extern "C" fn(*mut u8, *mut u8, *mut u8, u32, u32) -> u32;

omron_fast_shims!(timers:
    stljit_rt_omron_tim_fast => Tim;
    stljit_rt_omron_timx_fast => TimX;
    stljit_rt_omron_timh_fast => TimH;
    stljit_rt_omron_timhx_fast => TimHX;
    stljit_rt_omron_tmhh_fast => Tmhh;
    stljit_rt_omron_tmhhx_fast => TmhhX;
    stljit_rt_omron_ttim_fast => Ttim;
    stljit_rt_omron_ttimx_fast => TtimX;
);
omron_fast_shims!(counters:
    stljit_rt_omron_cnt_fast => Cnt;
    stljit_rt_omron_cntx_fast => CntX;
    stljit_rt_omron_cntr_fast => Cntr;
    stljit_rt_omron_cntrx_fast => CntrX;
);

/// Bit of [`stljit_rt_omron_arith`]'s result: a result is to be written (no ER).
pub const OMRON_ARITH_HAS_RESULT: u64 = 1 << 63;

/// [`crate::omron::arith::execute`] of `op` (its position in `OmronArith::ALL`) for the
/// instructions with at most two result words, as a pure value for compiled code: bits 0–31
/// the result (word 0 = bits 0–15, written to R; word 1 to R+1), bits 32–47 the flag values,
/// bits 48–62 the flag mask (the condition flags fill twelve bits), bit 63
/// [`OMRON_ARITH_HAS_RESULT`]. An impossible `op` (or a four-word one) returns 0: nothing
/// written, no flag changed.
pub extern "C" fn stljit_rt_omron_arith(op: u32, a: u32, b: u32, cy: u32) -> u64 {
    use stljit_core::ir::OmronArith;
    let Some(&op) = OmronArith::ALL.get(op as usize) else {
        return 0;
    };
    if op.result_words() > 2 {
        return 0;
    }
    let run = AssertUnwindSafe(|| {
        let out = crate::omron::arith::execute(op, a, b, cy != 0);
        let w = out.flags;
        let flags = u64::from(w.value & w.mask) << 32 | u64::from(w.mask) << 48;
        match out.result {
            Some(r) => (r & 0xFFFF_FFFF) | flags | OMRON_ARITH_HAS_RESULT,
            None => flags,
        }
    });
    catch_unwind(run).unwrap_or(0)
}

/// [`omron_image::run_box`]: box `code` ([`omron_image::box_code`]) on `a`, `b`, result at
/// image offset `dst`.
///
/// # Safety
/// See the module conventions of [`super`]; `dst` plus the result's bytes lies inside the
/// image (the JIT passes a verified direct location).
pub unsafe extern "C" fn stljit_rt_omron_box(
    image: *mut u8,
    layout: *const Layout,
    code: u32,
    a: u32,
    b: u32,
    dst: u32,
) -> u32 {
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |img, l| {
            if omron_image::run_box(img, l, code, a, b, dst) {
                Ok(())
            } else {
                Err(stljit_core::ErrorCode::OperandRange)
            }
        })
    }
}

/// The `*_ref` argument of [`stljit_rt_omron_box_refs`] for an absent operand.
pub const OMRON_NO_OPERAND: u32 = u32::MAX;

fn box_operand(packed: u32, value: u32) -> omron_image::BoxOperand {
    match (packed, omron_image::unpack_ref(packed)) {
        (OMRON_NO_OPERAND, _) => omron_image::BoxOperand::Absent,
        (_, Some(r)) => omron_image::BoxOperand::Ref(r),
        (_, None) => omron_image::BoxOperand::Direct(value),
    }
}

/// [`omron_image::run_box_refs`]: box `code` whose operands are each a value (`*_ref` 0, the
/// value or the destination's image offset in `*_val`), an indirect operand
/// ([`omron_image::pack_ref`]) or absent ([`OMRON_NO_OPERAND`]); `words` = source words | result
/// words << 8.
///
/// # Safety
/// See the module conventions of [`super`].
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn stljit_rt_omron_box_refs(
    image: *mut u8,
    layout: *const Layout,
    code: u32,
    lhs_ref: u32,
    lhs_val: u32,
    rhs_ref: u32,
    rhs_val: u32,
    dst_ref: u32,
    dst_off: u32,
    words: u32,
) -> u32 {
    let ops = (
        box_operand(lhs_ref, lhs_val),
        box_operand(rhs_ref, rhs_val),
        box_operand(dst_ref, dst_off),
    );
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |img, l| {
            let sizes = (words & 0xFF, (words >> 8) & 0xFF);
            if omron_image::run_box_refs(img, l, code, ops, sizes) {
                Ok(())
            } else {
                Err(stljit_core::ErrorCode::OperandRange)
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic byte stream for the random states.
    fn bytes(seed: u64) -> impl FnMut() -> u8 {
        let mut x = seed | 1;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x as u8
        }
    }

    #[test]
    fn every_kind_shim_is_the_image_step_of_its_kind() {
        // The per-kind shims must be `timer_step`/`counter_step` of exactly their kind, on any
        // bytes, levels, gate and set value.
        let mut next = bytes(0x5EED);
        for _ in 0..2000 {
            let ctl = u32::from(next()) & 0b111 | (u32::from(next() & 1) << 8);
            let sv = u32::from(next()) << 8 | u32::from(next());
            let (stack, gate) = ctl_parts(ctl);
            for &kind in OmronTimerKind::ALL {
                let mut t: omron_image::TimerBytes = (
                    [next(), next()],
                    next() & 1,
                    std::array::from_fn(|_| next() % 4),
                );
                let now = u64::from(next()) * 37;
                let mut want = t;
                let w = omron_image::timer_step(
                    (&mut want.0, &mut want.1, &mut want.2),
                    now,
                    kind,
                    stack,
                    gate,
                    sv as u16,
                );
                let now_bytes = now.to_ne_bytes();
                // SAFETY: four distinct local arrays of the sizes the shim reads and writes.
                let got = unsafe {
                    omron_timer_fast_fn(kind)(
                        t.0.as_mut_ptr(),
                        &mut t.1,
                        t.2.as_mut_ptr(),
                        now_bytes.as_ptr(),
                        ctl,
                        sv,
                    )
                };
                assert_eq!((got, t), (pack_flag_writes(w), want), "{kind:?}");
            }
            for &kind in OmronCounterKind::ALL {
                let mut c: omron_image::CounterBytes = (
                    [next(), next()],
                    next() & 1,
                    std::array::from_fn(|_| next() & 1),
                );
                let mut want = c;
                let w = omron_image::counter_step(
                    (&mut want.0, &mut want.1, &mut want.2),
                    kind,
                    stack,
                    gate,
                    sv as u16,
                );
                // SAFETY: three distinct local arrays of the sizes the shim reads and writes.
                let got = unsafe {
                    omron_counter_fast_fn(kind)(
                        c.0.as_mut_ptr(),
                        &mut c.1,
                        c.2.as_mut_ptr(),
                        ctl,
                        sv,
                    )
                };
                assert_eq!((got, c), (pack_flag_writes(w), want), "{kind:?}");
            }
        }
    }
}
