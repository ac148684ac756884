//! The Omron shims (`stljit_rt_omron_*`): the JIT's way into [`crate::omron_image`], under the
//! module conventions of [`super`]. Kinds travel as their [`FfiCode`](super::FfiCode), the gate
//! as a gate word, set values and operand values as `u32` (Omron value order).

use super::{RT_BAD_ARGUMENT, decode_gate_word, status_of};
use crate::omron_image;
use stljit_core::ir::{OmronCounterKind, OmronTimerKind};
use stljit_core::layout::Layout;

/// [`omron_image::timer`]; `stack` is the logic stack (bit i = S_i).
///
/// # Safety
/// See the module conventions of [`super`].
pub unsafe extern "C" fn stljit_rt_omron_timer(
    image: *mut u8,
    layout: *const Layout,
    n: u32,
    kind: u32,
    stack: u32,
    gate: u32,
    sv: u32,
) -> u32 {
    let (Some(&kind), Ok(n)) = (OmronTimerKind::ALL.get(kind as usize), u16::try_from(n)) else {
        return RT_BAD_ARGUMENT;
    };
    let (gate, _) = decode_gate_word(gate);
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |b, l| {
            omron_image::timer(b, l, kind, n, stack as u16, gate, sv as u16);
            Ok(())
        })
    }
}

/// [`omron_image::counter`]; `stack` is the logic stack.
///
/// # Safety
/// See the module conventions of [`super`].
pub unsafe extern "C" fn stljit_rt_omron_counter(
    image: *mut u8,
    layout: *const Layout,
    n: u32,
    kind: u32,
    stack: u32,
    gate: u32,
    sv: u32,
) -> u32 {
    let (Some(&kind), Ok(n)) = (OmronCounterKind::ALL.get(kind as usize), u16::try_from(n)) else {
        return RT_BAD_ARGUMENT;
    };
    let (gate, _) = decode_gate_word(gate);
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |b, l| {
            omron_image::counter(b, l, kind, n, stack as u16, gate, sv as u16);
            Ok(())
        })
    }
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
