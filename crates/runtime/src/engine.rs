//! The [`Engine`] trait: what the interpreter and the JIT both offer, and what the differential
//! oracle, the conformance harness and the CLI drive.
//!
//! An engine owns only its compiled form of the program; all state lives in the [`Image`] it is
//! handed, so a wrapper (fault injection, tracing, the differential oracle) can sit between caller
//! and engine without knowing anything about either: it forwards [`Engine::scan`] and may inspect
//! or alter the image before and after.

use crate::image::Image;
use std::ops::Range;
use stljit_core::ScanStatus;

/// An execution engine for one compiled program.
pub trait Engine {
    /// Short name for reports (`interp`, `jit`).
    fn name(&self) -> &'static str;

    /// Runs one full scan at virtual time `t_ms`: [`crate::scan::begin`], the program,
    /// [`crate::scan::end`]. The harness writes inputs into the image's physical input copy
    /// before the call and reads outputs and memory after it.
    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus;

    /// Runs up to `n` scans at times `t0_ms + i · scan_ms`, stopping after the first scan that
    /// does not return [`ScanStatus::Ok`]. Returns the number of scans run (that last one
    /// included) and the last status (`Ok` when all ran or `n` is 0). Exactly `scan` in a
    /// loop (times wrap past 2^64 ms, as the native loop's do); an engine overrides it where it
    /// can run the stretch faster (the JIT's native loop).
    fn run_scans(
        &mut self,
        image: &mut Image,
        t0_ms: u64,
        scan_ms: u64,
        n: u64,
    ) -> (u64, ScanStatus) {
        scan_by_scan(self, image, t0_ms, scan_ms, n, None)
    }

    /// [`Engine::run_scans`], also stopping after the first scan that returns Ok and leaves a
    /// byte `watch` watches different from the value `watch` last saw (which then holds the new
    /// bytes; a scan that does not return Ok ends the stretch without a look): the stretch an
    /// observer that only needs changed values (a VCD trace) can wait through.
    /// Exactly `scan` and [`ChangeWatch::changed`] in a loop; the JIT's native loop compares
    /// after each scan of its own.
    fn run_scans_watching(
        &mut self,
        image: &mut Image,
        t0_ms: u64,
        scan_ms: u64,
        n: u64,
        watch: &mut ChangeWatch,
    ) -> (u64, ScanStatus) {
        scan_by_scan(self, image, t0_ms, scan_ms, n, Some(watch))
    }
}

/// [`Engine::run_scans`] (with `watch`: [`Engine::run_scans_watching`]) as their definition
/// states it, one [`Engine::scan`] at a time: the trait's default, and what a wrapper that
/// must see every scan (forces) runs.
pub fn scan_by_scan<E: Engine + ?Sized>(
    engine: &mut E,
    image: &mut Image,
    t0_ms: u64,
    scan_ms: u64,
    n: u64,
    mut watch: Option<&mut ChangeWatch>,
) -> (u64, ScanStatus) {
    for i in 0..n {
        let t = t0_ms.wrapping_add(i.wrapping_mul(scan_ms));
        let status = engine.scan(image, t);
        if status != ScanStatus::Ok || watch.as_mut().is_some_and(|w| w.changed(image.bytes())) {
            return (i + 1, status);
        }
    }
    (n, ScanStatus::Ok)
}

/// Image bytes whose change ends a stretch of [`Engine::run_scans_watching`], with the values
/// they had when last compared.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ChangeWatch {
    /// The watched runs of bytes, sorted and merged, inside the image.
    ranges: Vec<Range<usize>>,
    /// Their bytes as last seen, run after run.
    seen: Vec<u8>,
}

impl ChangeWatch {
    /// Watches `ranges` of `image` (bytes outside it are dropped), as they are now.
    pub fn new(image: &Image, ranges: impl IntoIterator<Item = Range<usize>>) -> ChangeWatch {
        let size = image.bytes().len();
        let mut all: Vec<Range<usize>> = ranges
            .into_iter()
            .map(|r| r.start.min(size)..r.end.min(size))
            .filter(|r| r.start < r.end)
            .collect();
        all.sort_by_key(|r| r.start);
        let mut merged: Vec<Range<usize>> = Vec::with_capacity(all.len());
        for r in all {
            match merged.last_mut() {
                Some(last) if r.start <= last.end => last.end = last.end.max(r.end),
                _ => merged.push(r),
            }
        }
        let seen = merged
            .iter()
            .flat_map(|r| &image.bytes()[r.clone()])
            .copied()
            .collect();
        ChangeWatch {
            ranges: merged,
            seen,
        }
    }

    /// Whether a watched byte of `bytes` (an image's) differs from its value last seen; the
    /// values of `bytes` become the ones seen. A watch of another image's size sees a change.
    pub fn changed(&mut self, bytes: &[u8]) -> bool {
        let mut at = 0;
        let mut changed = false;
        for r in &self.ranges {
            let (Some(now), Some(seen)) =
                (bytes.get(r.clone()), self.seen.get_mut(at..at + r.len()))
            else {
                return true;
            };
            if now != seen {
                seen.copy_from_slice(now);
                changed = true;
            }
            at += r.len();
        }
        changed
    }
}

/// Implements [`Engine`] for pointers to an engine (a box, a borrow), forwarding every method.
macro_rules! forward_engine {
    ($($pointer:ty),*) => {$(
        impl<E: Engine + ?Sized> Engine for $pointer {
            fn name(&self) -> &'static str {
                (**self).name()
            }

            fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
                (**self).scan(image, t_ms)
            }

            fn run_scans(&mut self, image: &mut Image, t0: u64, dt: u64, n: u64) -> (u64, ScanStatus) {
                (**self).run_scans(image, t0, dt, n)
            }

            fn run_scans_watching(
                &mut self,
                image: &mut Image,
                t0: u64,
                dt: u64,
                n: u64,
                watch: &mut ChangeWatch,
            ) -> (u64, ScanStatus) {
                (**self).run_scans_watching(image, t0, dt, n, watch)
            }
        }
    )*};
}

forward_engine!(Box<E>, &mut E);

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ProfileId;

    #[test]
    fn a_watch_merges_its_ranges_drops_bytes_outside_and_sees_each_change_once() {
        let mut img = Image::blank(ProfileId::A5);
        let size = img.bytes().len();
        img.bytes_mut()[10] = 7;
        let mut w = ChangeWatch::new(&img, [12..14, 8..11, 10..12, size - 1..size + 5, 40..40]);
        assert_eq!(w.ranges, vec![8..14, size - 1..size]);
        assert_eq!(w.seen, vec![0, 0, 7, 0, 0, 0, 0]);
        assert!(!w.changed(img.bytes()));
        img.bytes_mut()[13] = 1;
        assert!(w.changed(img.bytes()));
        assert!(!w.changed(img.bytes()), "the new bytes are the ones seen");
        img.bytes_mut()[14] = 1;
        assert!(!w.changed(img.bytes()), "byte 14 is not watched");
        assert!(
            w.changed(&img.bytes()[..size - 1]),
            "a shorter image is a change"
        );
        assert!(ChangeWatch::new(&img, []).ranges.is_empty());
    }

    /// Counts its scans; a scan writes the count into byte 0 every third scan, and the fifth
    /// scan stops.
    struct Every3(u8);

    impl Engine for Every3 {
        fn name(&self) -> &'static str {
            "every3"
        }

        fn scan(&mut self, image: &mut Image, _t_ms: u64) -> ScanStatus {
            self.0 += 1;
            if self.0.is_multiple_of(3) {
                image.bytes_mut()[0] = self.0;
            }
            if self.0 == 5 {
                ScanStatus::Stopped
            } else {
                ScanStatus::Ok
            }
        }
    }

    #[test]
    fn a_stretch_ends_after_the_scan_that_changed_a_watched_byte_or_did_not_return_ok() {
        let mut img = Image::blank(ProfileId::A5);
        let mut e = Every3(0);
        let mut w = ChangeWatch::new(&img, std::iter::once(0..1));
        assert_eq!(
            e.run_scans_watching(&mut img, 0, 10, 10, &mut w),
            (3, ScanStatus::Ok)
        );
        assert_eq!(w.seen, vec![3]);
        assert_eq!(
            e.run_scans_watching(&mut img, 30, 10, 10, &mut w),
            (2, ScanStatus::Stopped)
        );
        let mut unwatched = ChangeWatch::default();
        assert_eq!(
            e.run_scans_watching(&mut img, 50, 10, 4, &mut unwatched),
            (4, ScanStatus::Ok)
        );
    }
}
