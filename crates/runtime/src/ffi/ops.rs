//! Shims over the instruction helpers (arithmetic, logic, shifts, conversions, compares, block
//! instructions). Part of [`crate::ffi`]; its conventions and table apply.

use super::{FfiCode, RT_BAD_ARGUMENT, pack, status, width_of, with_image};
use crate::block::{self, Span};
use crate::flags::{Outcome, apply_flags};
use crate::{arith, bitops, compare, convert, pointer};
use stljit_core::ir::{ArithOp, BitLoc, CmpOp, CmpType, Conversion, LogicOp, RealFn};
use stljit_core::layout::Layout;
use stljit_core::{Area, Width};

/// Applies the outcome's flags and packs its value (bit 32 = written / ENO).
fn outcome(img: &mut [u8], l: &Layout, o: Outcome) -> u64 {
    apply_flags(img, l, o.flags);
    match o.value {
        Some(v) => pack(Ok(v)),
        None => 0,
    }
}

/// Runs a value helper: decodes nothing itself, applies flags, packs the result.
///
/// # Safety
/// The module conventions of [`crate::ffi`].
unsafe fn value_shim(
    image: *mut u8,
    layout: *const Layout,
    f: impl FnOnce() -> Option<Outcome>,
) -> u64 {
    let Some(o) = f() else {
        return pack(Err(RT_BAD_ARGUMENT));
    };
    // SAFETY: forwarded caller contract.
    unsafe { with_image(image, layout, |b, l| outcome(b, l, o)) }.unwrap_or_else(|e| pack(Err(e)))
}

/// [`arith::int_arith`]: `OUT op IN1`; u64 result, SMB1 updated.
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_int_arith(
    image: *mut u8,
    layout: *const Layout,
    op: u32,
    width: u32,
    out: u32,
    in1: u32,
) -> u64 {
    let f = || {
        Some(arith::int_arith(
            ArithOp::from_ffi(op)?,
            width_of(width)?,
            out,
            in1,
        ))
    };
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`arith::mul_wide`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_mul_wide(
    image: *mut u8,
    layout: *const Layout,
    out: u32,
    in1: u32,
) -> u64 {
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, || Some(arith::mul_wide(out, in1))) }
}

/// [`arith::div_wide`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_div_wide(
    image: *mut u8,
    layout: *const Layout,
    out: u32,
    in1: u32,
) -> u64 {
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, || Some(arith::div_wide(out, in1))) }
}

/// [`arith::step`] (INC/DEC).
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_step(
    image: *mut u8,
    layout: *const Layout,
    width: u32,
    up: u32,
    x: u32,
) -> u64 {
    let f = || Some(arith::step(width_of(width)?, up != 0, x));
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`arith::real_arith`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_real_arith(
    image: *mut u8,
    layout: *const Layout,
    op: u32,
    out: u32,
    in1: u32,
) -> u64 {
    let f = || Some(arith::real_arith(ArithOp::from_ffi(op)?, out, in1));
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`arith::real_func`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_real_func(
    image: *mut u8,
    layout: *const Layout,
    func: u32,
    x: u32,
) -> u64 {
    let f = || Some(arith::real_func(RealFn::from_ffi(func)?, x));
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`bitops::logic`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_logic(
    image: *mut u8,
    layout: *const Layout,
    op: u32,
    width: u32,
    out: u32,
    in1: u32,
) -> u64 {
    let f = || {
        Some(bitops::logic(
            LogicOp::from_ffi(op)?,
            width_of(width)?,
            out,
            in1,
        ))
    };
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`bitops::invert`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_invert(
    image: *mut u8,
    layout: *const Layout,
    width: u32,
    x: u32,
) -> u64 {
    let f = || Some(bitops::invert(width_of(width)?, x));
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`bitops::shift`]; `n` is the count byte.
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_shift(
    image: *mut u8,
    layout: *const Layout,
    left: u32,
    width: u32,
    x: u32,
    n: u32,
) -> u64 {
    let f = || Some(bitops::shift(left != 0, width_of(width)?, x, n as u8));
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`bitops::rotate`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_rotate(
    image: *mut u8,
    layout: *const Layout,
    left: u32,
    width: u32,
    x: u32,
    n: u32,
) -> u64 {
    let f = || Some(bitops::rotate(left != 0, width_of(width)?, x, n as u8));
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`convert::convert`]; operand widths from [`convert::widths`].
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_convert(
    image: *mut u8,
    layout: *const Layout,
    conv: u32,
    x: u32,
) -> u64 {
    let f = || Some(convert::convert(Conversion::from_ffi(conv)?, x));
    // SAFETY: forwarded caller contract.
    unsafe { value_shim(image, layout, f) }
}

/// [`compare::compare`]: u64 result with payload 0/1, or on failure the `FatalCode` (not yet
/// recorded: call `stljit_rt_fatal` with the site).
///
/// # Safety
/// See [`crate::ffi`] (the image is not touched).
pub unsafe extern "C" fn stljit_rt_compare(
    _image: *mut u8,
    _layout: *const Layout,
    ty: u32,
    op: u32,
    lhs: u32,
    rhs: u32,
) -> u64 {
    let (Some(ty), Some(op)) = (CmpType::from_ffi(ty), CmpOp::from_ffi(op)) else {
        return pack(Err(RT_BAD_ARGUMENT));
    };
    pack(
        compare::compare(ty, op, lhs, rhs)
            .map(u32::from)
            .map_err(|f| u32::from(f as u16)),
    )
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
    let Some(area) = Area::from_ffi(area) else {
        return RT_BAD_ARGUMENT;
    };
    let start = BitLoc {
        area,
        byte,
        bit: bit.min(8) as u8,
    };
    // SAFETY: forwarded caller contract.
    unsafe {
        with_image(image, layout, |b, l| {
            status(block::set_range_imm(
                b,
                l,
                start,
                frame,
                count,
                value != 0,
                immediate != 0,
            ))
        })
    }
    .unwrap_or_else(|e| e)
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
        with_image(image, layout, |b, l| {
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
            status(block::block_move(b, s, d, width, count))
        })
    }
    .unwrap_or_else(|e| e)
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
        with_image(image, layout, |b, l| {
            let d = Span {
                start: dst,
                end: dst_end.min(l.size),
            };
            status(block::fill(b, value as u16, d, count))
        })
    }
    .unwrap_or_else(|e| e)
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
    let Some(area) = Area::from_ffi(area) else {
        return RT_BAD_ARGUMENT;
    };
    let start = BitLoc {
        area,
        byte,
        bit: bit.min(8) as u8,
    };
    // SAFETY: forwarded caller contract.
    unsafe {
        with_image(image, layout, |b, l| {
            status(block::shift_register(
                b,
                l,
                data != 0,
                start,
                frame,
                len as i8,
            ))
        })
    }
    .unwrap_or_else(|e| e)
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

/// The FFI code of a width (its byte count), for symmetry with [`FfiCode`].
pub fn width_code(w: Width) -> u32 {
    w.bytes()
}
