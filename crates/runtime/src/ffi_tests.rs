//! The shims behave like their Rust counterparts and reject bad arguments without panicking.

use super::*;
use crate::image::Image;
use stljit_core::ProfileId;

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
