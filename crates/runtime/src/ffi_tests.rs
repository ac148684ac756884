//! The shims behave like their Rust counterparts and reject bad arguments without panicking.

use super::*;
use crate::image::Image;
use stljit_core::ProfileId;

fn img() -> Image {
    Image::blank(ProfileId::A5)
}

#[test]
fn scan_and_timer_through_the_shims() {
    let mut im = img();
    let plan = scan::ScanPlan::every_timer(im.layout());
    let (b, l) = im.split_mut();
    let (p, lp) = (b.as_mut_ptr(), l as *const Layout);
    // SAFETY: p/lp come from a live image borrowed for the whole block.
    unsafe {
        assert_eq!(stljit_rt_scan_begin(p, lp, &plan, std::ptr::null(), 0), 1);
        assert_eq!(stljit_rt_timer(p, lp, 37, 1, 1, 1, -5), RT_OK);
        assert_eq!(stljit_rt_timer(p, lp, 64, 1, 1, 1, 5), 0x0091);
        assert_eq!(stljit_rt_timer(p, lp, 1, 9, 1, 1, 5), RT_BAD_ARGUMENT);
        assert_eq!(stljit_rt_counter(p, lp, 0, 4, 0, 1, 5), RT_BAD_ARGUMENT);
        assert_eq!(stljit_rt_counter_reset(p, lp, 31, 2), 0x0091);
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
    }
    assert!(im.timer_bit(37), "negative PT: on at once (TC11)");
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
        let plan = scan::ScanPlan::every_timer(&l);
        assert_eq!(
            stljit_rt_scan_begin(std::ptr::null_mut(), &l, &plan, std::ptr::null(), 0),
            0
        );
        assert_eq!(
            stljit_rt_scan_begin(
                std::ptr::null_mut(),
                &l,
                std::ptr::null(),
                std::ptr::null(),
                0
            ),
            0
        );
        assert_eq!(
            stljit_rt_pointer_end(std::ptr::null_mut(), std::ptr::null(), 0x0600_0000),
            0
        );
        let fatal = scan::Begin::Fatal as u32;
        for phase in [0, 1] {
            assert_eq!(
                stljit_rt_scan_steps(std::ptr::null_mut(), &l, &plan, std::ptr::null(), phase),
                fatal
            );
            assert_eq!(
                stljit_rt_scan_steps(
                    std::ptr::null_mut(),
                    &l,
                    std::ptr::null(),
                    std::ptr::null(),
                    phase
                ),
                fatal
            );
        }
    }
}

#[test]
fn event_phases_of_a_program_without_events_go_on() {
    let mut im = img();
    let plan = scan::ScanPlan::every_timer(im.layout());
    let before = im.bytes().to_vec();
    let (b, l) = im.split_mut();
    let (p, lp) = (b.as_mut_ptr(), l as *const Layout);
    // SAFETY: p/lp come from a live image borrowed for the whole block.
    unsafe {
        for phase in [0, 1] {
            assert_eq!(
                stljit_rt_scan_steps(p, lp, &plan, std::ptr::null(), phase),
                scan::Begin::Run as u32
            );
        }
    }
    assert_eq!(im.bytes(), &before[..], "no phase, no byte written");
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

#[test]
fn the_watch_shim_reports_a_change_once_and_rejects_null_pointers() {
    let mut im = img();
    let mut w = crate::engine::ChangeWatch::new(&im, std::iter::once(3..5));
    let (b, l) = im.split_mut();
    b[4] = 9;
    let (p, lp) = (b.as_mut_ptr(), l as *const Layout);
    // SAFETY: p/lp come from a live image borrowed for the whole block; `w` is live and not
    // otherwise borrowed during the calls.
    unsafe {
        assert_eq!(stljit_rt_watch_changed(p, lp, &mut w), 1);
        assert_eq!(stljit_rt_watch_changed(p, lp, &mut w), 0);
        assert_eq!(stljit_rt_watch_changed(p, lp, std::ptr::null_mut()), 0);
        assert_eq!(stljit_rt_watch_changed(std::ptr::null_mut(), lp, &mut w), 0);
        assert_eq!(stljit_rt_watch_changed(p, std::ptr::null(), &mut w), 0);
    }
}
