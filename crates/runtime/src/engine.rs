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
}

impl<E: Engine + ?Sized> Engine for Box<E> {
    fn name(&self) -> &'static str {
        (**self).name()
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        (**self).scan(image, t_ms)
    }
}

impl<E: Engine + ?Sized> Engine for &mut E {
    fn name(&self) -> &'static str {
        (**self).name()
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        (**self).scan(image, t_ms)
    }
}
