//! The [`Engine`] trait: what the interpreter and the JIT both offer, and what the differential
//! oracle, the conformance harness and the CLI drive.
//!
//! An engine owns only its compiled form of the program; all state lives in the [`Image`] it is
//! handed, so a wrapper (fault injection, tracing, the differential oracle) can sit between caller
//! and engine without knowing anything about either: it forwards [`Engine::scan`] and may inspect
//! or alter the image before and after.

use crate::image::Image;
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
        for i in 0..n {
            let t = t0_ms.wrapping_add(i.wrapping_mul(scan_ms));
            let status = self.scan(image, t);
            if status != ScanStatus::Ok {
                return (i + 1, status);
            }
        }
        (n, ScanStatus::Ok)
    }
}

impl<E: Engine + ?Sized> Engine for Box<E> {
    fn name(&self) -> &'static str {
        (**self).name()
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        (**self).scan(image, t_ms)
    }

    fn run_scans(&mut self, image: &mut Image, t0: u64, dt: u64, n: u64) -> (u64, ScanStatus) {
        (**self).run_scans(image, t0, dt, n)
    }
}

impl<E: Engine + ?Sized> Engine for &mut E {
    fn name(&self) -> &'static str {
        (**self).name()
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        (**self).scan(image, t_ms)
    }

    fn run_scans(&mut self, image: &mut Image, t0: u64, dt: u64, n: u64) -> (u64, ScanStatus) {
        (**self).run_scans(image, t0, dt, n)
    }
}
