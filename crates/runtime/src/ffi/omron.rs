//! The Omron shims (`stljit_rt_omron_*`): the JIT's way into [`crate::omron_image`], under the
//! module conventions of [`super`]. The timer and counter shims are lean like the S7 fast
//! shims (pointers to the object's bytes, computed from the layout at compile time) and return
//! the condition-flag writes for compiled code to apply; kinds travel as their position in
//! core's `ALL` lists, set values and operand values as `u32` (Omron value order).

use super::status_of;
use crate::omron_image;
use crate::rules::Gate;
use std::panic::{AssertUnwindSafe, catch_unwind};
use stljit_core::ir::{OmronCounterKind, OmronTimerKind};
use stljit_core::layout::{COUNTER_STATE_SIZE, Layout, TIMER_STATE_SIZE};

/// `ctl` of the fast Omron shims: bits 0–2 the logic-stack levels 0–2, bit 8 the gate open
/// ([`super::CTL_GATE`]), bits 16–23 the kind's position in its `ALL` list.
pub const OMRON_CTL_KIND_SHIFT: u32 = 16;

/// The packed condition-flag writes a fast Omron shim returns: the mask in bits 16–31, the
/// values in bits 0–15 (both in the `Flags` area's little-endian bit order).
pub fn pack_flag_writes(w: crate::omron::FlagWrites) -> u32 {
    u32::from(w.mask) << 16 | u32::from(w.value & w.mask)
}

fn ctl_parts(ctl: u32) -> (u16, Gate, usize) {
    let gate = Gate::with(
        ctl & super::CTL_GATE != 0,
        stljit_core::GatePolicy::OmronInterlock,
    );
    (
        (ctl & 0b111) as u16,
        gate,
        ((ctl >> OMRON_CTL_KIND_SHIFT) & 0xFF) as usize,
    )
}

/// [`omron_image::timer_step`] on one timer's bytes, for compiled code that knows the layout:
/// `value` (2 bytes), `flag` (1), `state` (`TIMER_STATE_SIZE`), `now` (the scheduler's
/// native-endian `u64` `T_NOW`), `ctl` as [`OMRON_CTL_KIND_SHIFT`] says, `sv` the set value.
/// Returns the flag writes ([`pack_flag_writes`]) for compiled code to apply; an impossible
/// kind writes nothing and returns 0.
///
/// # Safety
/// Each pointer must be valid for reads and writes of its size (`now`: reads), the ranges must
/// not overlap, and nothing else may access them during the call. The JIT derives them from
/// the program's layout for a timer the profile has, inside the image it runs on.
pub unsafe extern "C" fn stljit_rt_omron_timer_fast(
    value: *mut u8,
    flag: *mut u8,
    state: *mut u8,
    now: *const u8,
    ctl: u32,
    sv: u32,
) -> u32 {
    let (stack, gate, kind) = ctl_parts(ctl);
    let Some(&kind) = OmronTimerKind::ALL.get(kind) else {
        return 0;
    };
    // SAFETY: the caller's contract: valid, disjoint, exclusively ours for the call.
    let (value, flag, state, now) = unsafe {
        (
            &mut *value.cast::<[u8; 2]>(),
            &mut *flag,
            &mut *state.cast::<[u8; TIMER_STATE_SIZE as usize]>(),
            u64::from_ne_bytes(*now.cast::<[u8; 8]>()),
        )
    };
    let run = AssertUnwindSafe(|| {
        let w = omron_image::timer_step((value, flag, state), now, kind, stack, gate, sv as u16);
        pack_flag_writes(w)
    });
    catch_unwind(run).unwrap_or(0)
}

/// [`omron_image::counter_step`] on one counter's bytes: `value`, `flag`, `state`
/// (`COUNTER_STATE_SIZE`), `ctl`, `sv`, as [`stljit_rt_omron_timer_fast`].
///
/// # Safety
/// As [`stljit_rt_omron_timer_fast`] (no `now`).
pub unsafe extern "C" fn stljit_rt_omron_counter_fast(
    value: *mut u8,
    flag: *mut u8,
    state: *mut u8,
    ctl: u32,
    sv: u32,
) -> u32 {
    let (stack, gate, kind) = ctl_parts(ctl);
    let Some(&kind) = OmronCounterKind::ALL.get(kind) else {
        return 0;
    };
    // SAFETY: the caller's contract: valid, disjoint, exclusively ours for the call.
    let (value, flag, state) = unsafe {
        (
            &mut *value.cast::<[u8; 2]>(),
            &mut *flag,
            &mut *state.cast::<[u8; COUNTER_STATE_SIZE as usize]>(),
        )
    };
    let run = AssertUnwindSafe(|| {
        let w = omron_image::counter_step((value, flag, state), kind, stack, gate, sv as u16);
        pack_flag_writes(w)
    });
    catch_unwind(run).unwrap_or(0)
}

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
