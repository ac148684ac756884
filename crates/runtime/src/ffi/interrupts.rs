//! The interrupt side of the shims: [`stljit_rt_interrupt`] (ATCH, DTCH, ENI, DISI, CEVNT)
//! and [`NativeRoutines`], the JIT's compiled interrupt routines as the begin shim runs them.
//! Part of [`crate::ffi`]; its conventions and table apply.

use super::{RT_BAD_ARGUMENT, status_of};
use crate::interrupt::{self, Action, Isr};
use std::sync::OnceLock;
use stljit_core::layout::{ISR_FRAME, Layout};
use stljit_core::{PouId, ScanStatus};

/// [`interrupt::execute`] of the action `(kind, event, routine)` ([`Action::encode`]).
///
/// # Safety
/// See [`crate::ffi`].
pub unsafe extern "C" fn stljit_rt_interrupt(
    image: *mut u8,
    layout: *const Layout,
    kind: u32,
    event: u32,
    routine: u32,
) -> u32 {
    let Some(action) = Action::decode(kind, event, routine) else {
        return RT_BAD_ARGUMENT;
    };
    // SAFETY: forwarded caller contract.
    unsafe { status_of(image, layout, |b, l| interrupt::execute(b, l, action)) }
}

/// A compiled POU as the JIT builds it: `(image, depth) -> status` (0 continue, else a
/// `ScanStatus`).
pub type PouFn = unsafe extern "C" fn(*mut u8, u32) -> u32;

/// The JIT's compiled interrupt routines by POU: what the begin shim runs a routine body
/// with (`&NativeRoutines` is an [`Isr`]), so the body is native code while everything around
/// it is the runtime's. The JIT bakes the table's address into its scan loop before the code
/// exists and installs the functions once after finalizing, through a shared reference.
#[derive(Debug, Default)]
pub struct NativeRoutines {
    fns: OnceLock<Box<[Option<PouFn>]>>,
}

impl NativeRoutines {
    /// An empty table (every run returns at once until [`NativeRoutines::install`]).
    pub fn new() -> NativeRoutines {
        NativeRoutines::default()
    }

    /// Installs the compiled bodies, indexed by POU (`None` for POUs that are not interrupt
    /// routines); only the first call has an effect.
    ///
    /// # Safety
    /// Every function must have the [`PouFn`] ABI, be compiled for the image layout of the
    /// program this table serves, and stay valid for as long as the table is used.
    pub unsafe fn install(&self, fns: Vec<Option<PouFn>>) {
        let _ = self.fns.set(fns.into());
    }
}

impl Isr for &NativeRoutines {
    fn run(&mut self, img: &mut [u8], _: &Layout, pou: PouId) -> ScanStatus {
        let f = self
            .fns
            .get()
            .and_then(|fns| fns.get(pou.index()).copied().flatten());
        let Some(f) = f else {
            return ScanStatus::Ok;
        };
        // SAFETY: `install`'s contract makes `f` the program's compiled POU for this image's
        // layout; `img` is the whole image (the begin shim's slice), exclusively borrowed for
        // the call, and the compiled code addresses only the image within its layout.
        let status = unsafe { f(img.as_mut_ptr(), ISR_FRAME) };
        ScanStatus::try_from(status as u8).unwrap_or(ScanStatus::Fatal)
    }
}
