//! Shims over the instructions that touch a run of memory (`S/R` with a run-time count, block
//! moves, `FILL`, `SHRB`) and the end of a pointer's area. Part of [`crate::ffi`]; its
//! conventions and table apply.

use super::{FfiCode, RT_BAD_ARGUMENT, status_of, width_of};
use crate::block::{self, Span};
use crate::pointer;
use stljit_core::Area;
use stljit_core::ir::BitLoc;
use stljit_core::layout::Layout;

/// The bit `area` (its [`FfiCode`]), `byte`, `bit` of a bit-run shim; a bit number above 7
/// stays out of range (8) for the runtime to reject.
fn bit_loc(area: u32, byte: u32, bit: u32) -> Option<BitLoc> {
    Some(BitLoc {
        area: Area::from_ffi(area)?,
        byte,
        bit: bit.min(8) as u8,
    })
}

/// [`block::set_range_imm`] (`S/R/SI/RI`); the bit is `area` (its [`FfiCode`]), `byte`, `bit`.
///
/// # Safety
/// See [`crate::ffi`].
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn stljit_rt_set_range(
    image: *mut u8,
    layout: *const Layout,
    area: u32,
    byte: u32,
    bit: u32,
    frame: u32,
    count: u32,
    value: u32,
    immediate: u32,
) -> u32 {
    let Some(start) = bit_loc(area, byte, bit) else {
        return RT_BAD_ARGUMENT;
    };
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |b, l| {
            block::set_range_imm(b, l, start, frame, count, value != 0, immediate != 0)
        })
    }
}

/// [`block::block_move`]: spans as image offsets (start, area end).
///
/// # Safety
/// See [`crate::ffi`].
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn stljit_rt_block_move(
    image: *mut u8,
    layout: *const Layout,
    src: u32,
    src_end: u32,
    dst: u32,
    dst_end: u32,
    width: u32,
    count: u32,
) -> u32 {
    let Some(width) = width_of(width) else {
        return RT_BAD_ARGUMENT;
    };
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |b, l| {
            // Ends beyond the image would let a bad span through the per-area check.
            let (s, d) = (
                Span {
                    start: src,
                    end: src_end.min(l.size),
                },
                Span {
                    start: dst,
                    end: dst_end.min(l.size),
                },
            );
            block::block_move(b, s, d, width, count)
        })
    }
}

/// [`block::fill`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_fill(
    image: *mut u8,
    layout: *const Layout,
    value: u32,
    dst: u32,
    dst_end: u32,
    count: u32,
) -> u32 {
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |b, l| {
            let d = Span {
                start: dst,
                end: dst_end.min(l.size),
            };
            block::fill(b, value as u16, d, count)
        })
    }
}

/// [`block::shift_register`] (`SHRB`); `len` is the signed count.
///
/// # Safety
/// See [`crate::ffi`].
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn stljit_rt_shift_register(
    image: *mut u8,
    layout: *const Layout,
    data: u32,
    area: u32,
    byte: u32,
    bit: u32,
    frame: u32,
    len: i32,
) -> u32 {
    let Some(start) = bit_loc(area, byte, bit) else {
        return RT_BAD_ARGUMENT;
    };
    // SAFETY: forwarded caller contract.
    unsafe {
        status_of(image, layout, |b, l| {
            block::shift_register(b, l, data != 0, start, frame, len as i8)
        })
    }
}

/// The image offset one past the end of the area a pointer designates (0 for a bad area code),
/// the `end` of a pointer [`Span`].
///
/// # Safety
/// See [`crate::ffi`] (the image is not touched).
pub unsafe extern "C" fn stljit_rt_pointer_end(
    _image: *mut u8,
    layout: *const Layout,
    ptr: u32,
) -> u32 {
    if layout.is_null() {
        return 0;
    }
    // SAFETY: non-null; the caller guarantees a live Layout.
    let l = unsafe { &*layout };
    pointer::decode(ptr).map_or(0, |(area, _)| l.base(area) + l.area_size(area))
}
