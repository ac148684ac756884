//! The shims behave like their Rust counterparts and reject bad arguments without panicking.

use super::*;
use crate::image::Image;
use stljit_core::ProfileId;
use stljit_core::ir::{CmpOp, CmpType};

fn img() -> Image {
    Image::blank(ProfileId::A5)
}

#[test]
fn symbols_are_unique_and_named_like_the_table() {
    let syms = symbols();
    let mut names: Vec<_> = syms.iter().map(|s| s.0).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), syms.len());
    let doc = include_str!("ffi.rs");
    for (name, ptr) in syms {
        assert!(name.starts_with("stljit_rt_"));
        assert!(!ptr.is_null());
        assert!(
            doc.contains(&format!("`{name}(")),
            "{name} missing from the doc table"
        );
    }
}

#[test]
fn scan_and_timer_through_the_shims() {
    let mut im = img();
    let (b, l) = im.split_mut();
    let (p, lp) = (b.as_mut_ptr(), l as *const Layout);
    // SAFETY: p/lp come from a live image borrowed for the whole block.
    unsafe {
        assert_eq!(stljit_rt_scan_begin(p, lp, 0), 1);
        assert_eq!(stljit_rt_timer(p, lp, 37, 1, 1, 1, -5), RT_OK);
        assert_eq!(stljit_rt_timer(p, lp, 64, 1, 1, 1, 5), 0x0091);
        assert_eq!(stljit_rt_timer(p, lp, 1, 9, 1, 1, 5), RT_BAD_ARGUMENT);
        assert_eq!(stljit_rt_counter(p, lp, 0, 4, 0, 1, 5), RT_BAD_ARGUMENT);
        assert_eq!(stljit_rt_counter_reset(p, lp, 31, 2), 0x0091);
        assert_eq!(
            stljit_rt_edge(p, lp, 0, 1, 1, 0),
            0,
            "first scan: suppressed"
        );
        assert_eq!(stljit_rt_scan_end(p, lp, 0), 0);
        assert_eq!(
            stljit_rt_pointer(p, lp, 0x0600_0000, 2, 1),
            1 << 32 | u64::from(l.base(stljit_core::Area::V))
        );
        assert_eq!(stljit_rt_pointer(p, lp, 0x0700_0000, 2, 1), 0x0006);
        assert_eq!(
            stljit_rt_pointer(p, lp, 0x0600_0000, 3, 1),
            u64::from(RT_BAD_ARGUMENT)
        );
        assert_eq!(stljit_rt_error(p, lp, 0x91, 2, 5), 0x91);
        assert_eq!(stljit_rt_error(p, lp, 0x55, 2, 5), RT_BAD_ARGUMENT);
        assert_eq!(stljit_rt_fatal(p, lp, 0x0103, 1, 4), 2);
        stljit_rt_wdr(p, lp);
        assert_eq!(stljit_rt_loop_tick(p, lp), 1);
    }
    assert!(im.timer_bit(37), "negative PT: on at once (TC11)");
    assert_eq!(im.last_error(), 0x91);
    assert_eq!(im.fatal(), 0x0103);
    assert_eq!(im.error_site(), (1, 4));
    assert_eq!(im.scan_no(), 1);
}

#[test]
fn null_pointers_are_rejected() {
    let l = Layout::of(ProfileId::A5);
    // SAFETY: null pointers are checked before any dereference.
    unsafe {
        assert_eq!(
            stljit_rt_timer(std::ptr::null_mut(), &l, 1, 1, 1, 1, 1),
            RT_BAD_ARGUMENT
        );
        assert_eq!(stljit_rt_scan_begin(std::ptr::null_mut(), &l, 0), 0);
        assert_eq!(
            stljit_rt_loop_tick(std::ptr::null_mut(), std::ptr::null()),
            0
        );
    }
}

#[test]
fn value_shims_match_the_helpers_and_apply_flags() {
    use crate::{arith, bitops, convert};
    use stljit_core::ir::{ArithOp, Conversion, LogicOp};
    let mut im = img();
    let smb1 = |im: &Image| im.bytes()[im.layout().base(stljit_core::Area::SM) as usize + 1];
    let (b, l) = im.split_mut();
    let (p, lp) = (b.as_mut_ptr(), l as *const Layout);
    let add = ArithOp::Add.ffi_code();
    // SAFETY: p/lp come from a live image borrowed for the whole block.
    unsafe {
        // T15: 32767 + 1 overflows → not written, SM1.1.
        assert_eq!(stljit_rt_int_arith(p, lp, add, 2, 32767, 1), 0);
        assert_eq!(
            stljit_rt_int_arith(p, lp, add, 3, 1, 1),
            u64::from(RT_BAD_ARGUMENT)
        );
        assert_eq!(
            stljit_rt_int_arith(p, lp, 9, 2, 1, 1),
            u64::from(RT_BAD_ARGUMENT)
        );
    }
    assert_eq!(smb1(&im), crate::flags::OVERFLOW);
    let (b, l) = im.split_mut();
    let (p, lp) = (b.as_mut_ptr(), l as *const Layout);
    let packed = |o: crate::flags::Outcome| o.value.map_or(0, |v| 1 << 32 | u64::from(v));
    // SAFETY: as above.
    unsafe {
        for (x, y) in [(5u32, 7u32), (0xFFFF, 1), (0x8000, 0xFFFF), (100, 0)] {
            for op in ArithOp::ALL {
                let want = packed(arith::int_arith(*op, Width::Word, x, y));
                assert_eq!(stljit_rt_int_arith(p, lp, op.ffi_code(), 2, x, y), want);
                let want = packed(arith::real_arith(*op, x << 16, y << 16));
                assert_eq!(
                    stljit_rt_real_arith(p, lp, op.ffi_code(), x << 16, y << 16),
                    want
                );
            }
            assert_eq!(
                stljit_rt_mul_wide(p, lp, x, y),
                packed(arith::mul_wide(x, y))
            );
            assert_eq!(
                stljit_rt_div_wide(p, lp, x, y),
                packed(arith::div_wide(x, y))
            );
            assert_eq!(
                stljit_rt_step(p, lp, 1, 1, x),
                packed(arith::step(Width::Byte, true, x))
            );
            let want = packed(bitops::logic(LogicOp::Xor, Width::DWord, x, y));
            assert_eq!(
                stljit_rt_logic(p, lp, LogicOp::Xor.ffi_code(), 4, x, y),
                want
            );
            assert_eq!(
                stljit_rt_invert(p, lp, 1, x),
                packed(bitops::invert(Width::Byte, x))
            );
            assert_eq!(
                stljit_rt_shift(p, lp, 1, 2, x, y),
                packed(bitops::shift(true, Width::Word, x, y as u8))
            );
            assert_eq!(
                stljit_rt_rotate(p, lp, 0, 4, x, y),
                packed(bitops::rotate(false, Width::DWord, x, y as u8))
            );
            for c in Conversion::ALL {
                assert_eq!(
                    stljit_rt_convert(p, lp, c.ffi_code(), x),
                    packed(convert::convert(*c, x))
                );
            }
        }
        let nan = f32::NAN.to_bits();
        let real = CmpType::Real.ffi_code();
        assert_eq!(
            stljit_rt_compare(p, lp, real, CmpOp::Eq.ffi_code(), nan, 0),
            0x0103
        );
        assert_eq!(
            stljit_rt_compare(
                p,
                lp,
                CmpType::Byte.ffi_code(),
                CmpOp::Gt.ffi_code(),
                200,
                100
            ),
            1 << 32 | 1
        );
    }
}

#[test]
fn block_shims() {
    use stljit_core::Area;
    let mut im = img();
    let (b, l) = im.split_mut();
    let (p, lp) = (b.as_mut_ptr(), l as *const Layout);
    let v = l.base(Area::V);
    let v_end = v + l.area_size(Area::V);
    let q = Area::Q.ffi_code();
    let vptr = crate::pointer::make(Area::V, 0).unwrap();
    // SAFETY: p/lp come from a live image borrowed for the whole block.
    unsafe {
        assert_eq!(stljit_rt_set_range(p, lp, q, 0, 6, 0, 3, 1, 1), RT_OK);
        assert_eq!(stljit_rt_set_range(p, lp, q, 15, 6, 0, 3, 1, 0), 0x0091);
        assert_eq!(
            stljit_rt_set_range(p, lp, 99, 0, 0, 0, 1, 1, 0),
            RT_BAD_ARGUMENT
        );
        assert_eq!(stljit_rt_fill(p, lp, 0xBEEF, v, v_end, 2), RT_OK);
        assert_eq!(
            stljit_rt_block_move(p, lp, v, v_end, v + 10, v_end, 2, 2),
            RT_OK
        );
        assert_eq!(
            stljit_rt_block_move(p, lp, v, v_end, v_end - 2, v_end, 2, 2),
            0x0091
        );
        assert_eq!(
            stljit_rt_block_move(p, lp, v, u32::MAX, v, u32::MAX, 4, 255),
            RT_OK
        );
        assert_eq!(stljit_rt_pointer_end(p, lp, vptr), v_end);
        assert_eq!(stljit_rt_pointer_end(p, lp, 0), 0);
        let m = Area::M.ffi_code();
        assert_eq!(stljit_rt_shift_register(p, lp, 1, m, 0, 0, 0, 4), RT_OK);
        assert_eq!(stljit_rt_shift_register(p, lp, 1, m, 0, 0, 0, 0), 0x0092);
    }
    assert_eq!(im.phys_out()[..2], [0xC0, 0x01]);
    let rd = |im: &Image, o| {
        im.read(
            stljit_core::ir::Loc {
                area: Area::V,
                offset: o,
            },
            Width::DWord,
            0,
        )
    };
    assert_eq!(rd(&im, 10), Ok(0xBEEF_BEEF));
    assert_eq!(
        im.read(
            stljit_core::ir::Loc {
                area: Area::M,
                offset: 0
            },
            Width::Byte,
            0
        ),
        Ok(1)
    );
}
