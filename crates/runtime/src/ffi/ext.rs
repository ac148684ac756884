//! Shims over the s7-200-more instructions ([`crate::ext`]): compiled code passes a pointer to
//! the op itself, which the JIT keeps alive beside the code, so the runtime resolves the
//! operands exactly as for the interpreter. Part of [`crate::ffi`]; its conventions and table
//! apply.

use super::{RT_BAD_ARGUMENT, pack, with_image};
use crate::ext;
use stljit_core::ir::{ExtBox, StrCompare};
use stljit_core::layout::Layout;

/// [`ext::execute`] of the box at `op` in L frame `frame` with power flow `pf`: u64 result,
/// ENO (0/1) on success, else the error code to record.
///
/// # Safety
/// See [`crate::ffi`]; `op` is null or points to a live [`ExtBox`].
pub unsafe extern "C" fn stljit_rt_ext(
    image: *mut u8,
    layout: *const Layout,
    op: *const ExtBox,
    frame: u32,
    pf: u32,
) -> u64 {
    // SAFETY: the caller's contract: `op` is null or live, and only read.
    let Some(op) = (unsafe { op.as_ref() }) else {
        return pack(Err(RT_BAD_ARGUMENT));
    };
    // SAFETY: forwarded caller contract.
    unsafe {
        with_image(image, layout, |b, l| {
            pack(
                ext::execute(b, l, op, frame, pf != 0)
                    .map(u32::from)
                    .map_err(|e| u32::from(e as u16)),
            )
        })
        .unwrap_or_else(|e| pack(Err(e)))
    }
}

/// [`ext::str_compare`] of the contact at `c` in L frame `frame`: u64 result, the contact's
/// value (0/1) on success, else the fatal code.
///
/// # Safety
/// See [`crate::ffi`]; `c` is null or points to a live [`StrCompare`].
pub unsafe extern "C" fn stljit_rt_str_compare(
    image: *mut u8,
    layout: *const Layout,
    c: *const StrCompare,
    frame: u32,
) -> u64 {
    // SAFETY: the caller's contract: `c` is null or live, and only read.
    let Some(c) = (unsafe { c.as_ref() }) else {
        return pack(Err(RT_BAD_ARGUMENT));
    };
    // SAFETY: forwarded caller contract.
    unsafe {
        with_image(image, layout, |b, l| {
            pack(
                ext::str_compare(b, l, c, frame)
                    .map(u32::from)
                    .map_err(|f| u32::from(f as u16)),
            )
        })
        .unwrap_or_else(|e| pack(Err(e)))
    }
}
