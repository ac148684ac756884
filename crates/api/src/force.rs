//! Forcing: an address held at a value whatever the program or a write does, as PLC engineers
//! force I/O from a programming tool.
//!
//! **Where in the scan.** A scan is `begin` (time, input refresh from the physical input copy,
//! system bits), the program, `end` (output copy to the physical outputs, STOP handling). Forces
//! act at two points, identically for every engine because they are applied around
//! [`Engine::scan`] and not inside an engine:
//!
//! 1. *Before the program sees its inputs*: a forced input is written into the physical input
//!    copy just before the scan, so the input refresh puts it in the I image and immediate reads
//!    (`LDI`, `!LD`) see it too; every other forced address is written into the image, so the
//!    program starts from the forced value even if something wrote the address in between.
//! 2. *After the program, before the output copy*: every forced address is written into the
//!    image again, overriding what the program wrote, and a forced output also into the physical
//!    output copy. `end` only copies Q to the physical outputs and updates the scan bookkeeping,
//!    so writing after `end` leaves exactly the bytes that writing before the copy would. The
//!    exceptions follow the copy: after a fatal error (no output copy) and while the PLC is in
//!    STOP (outputs held at 0), the physical outputs are left alone.
//!
//! After the scan the physical input copy is given back the values written from outside, so an
//! input's own value comes back the scan after it is unforced.

use crate::handle::Handle;
use stljit_core::{Area, ScanStatus};
use stljit_runtime::engine::scan_by_scan;
use stljit_runtime::{ChangeWatch, Engine, Image};

/// One forced address.
#[derive(Clone, Debug)]
pub(crate) struct Force {
    pub(crate) handle: Handle,
    pub(crate) raw: u32,
    /// The outside value of a forced input, kept while the scan runs.
    saved: u32,
}

/// The forced addresses of one PLC.
#[derive(Clone, Debug, Default)]
pub(crate) struct Forces {
    list: Vec<Force>,
}

impl Forces {
    /// Forces `handle` to `raw` (replacing an earlier force of the same address) and writes it
    /// into the image at once.
    pub(crate) fn set(&mut self, image: &mut Image, handle: Handle, raw: u32) {
        let force = Force {
            handle,
            raw,
            saved: 0,
        };
        force
            .handle
            .store(image.bytes_mut(), force.handle.read_offset(), raw);
        match self
            .list
            .iter_mut()
            .find(|f| f.handle.address() == force.handle.address())
        {
            Some(f) => *f = force,
            None => self.list.push(force),
        }
    }

    /// Releases the force of `handle`'s address; `false` when it was not forced.
    pub(crate) fn remove(&mut self, handle: &Handle) -> bool {
        let before = self.list.len();
        self.list.retain(|f| f.handle.address() != handle.address());
        self.list.len() != before
    }

    /// Releases every force.
    pub(crate) fn clear(&mut self) {
        self.list.clear();
    }

    /// The forced addresses in the order they were forced.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &Force> {
        self.list.iter()
    }

    fn before(&mut self, image: &mut Image) {
        let bytes = image.bytes_mut();
        for f in &mut self.list {
            let h = &f.handle;
            if h.is_input() {
                f.saved = h.load(bytes, h.write_offset());
                h.store(bytes, h.write_offset(), f.raw);
            } else {
                h.store(bytes, h.read_offset(), f.raw);
            }
        }
    }

    fn after(&self, image: &mut Image, outputs_copied: bool) {
        let (bytes, layout) = image.split_mut();
        for f in &self.list {
            let h = &f.handle;
            h.store(bytes, h.read_offset(), f.raw);
            if h.is_input() {
                h.store(bytes, h.write_offset(), f.saved);
            } else if h.area() == Area::Q && outputs_copied {
                let phys = h.read_offset() - layout.base(Area::Q) + layout.phys_out;
                h.store(bytes, phys, f.raw);
            }
        }
    }
}

/// An engine with forces applied around each of its scans (see the module doc).
pub(crate) struct Forced<'a> {
    pub(crate) engine: &'a mut dyn Engine,
    pub(crate) forces: &'a mut Forces,
}

impl Engine for Forced<'_> {
    fn name(&self) -> &'static str {
        self.engine.name()
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        if self.forces.list.is_empty() {
            return self.engine.scan(image, t_ms);
        }
        let was_stopped = image.is_stopped();
        self.forces.before(image);
        let status = self.engine.scan(image, t_ms);
        self.forces
            .after(image, !was_stopped && status != ScanStatus::Fatal);
        status
    }

    /// Without forces, the engine's own stretch (the JIT's native loop); with forces, scan by
    /// scan, so that every scan is forced.
    fn run_scans(&mut self, image: &mut Image, t0: u64, dt: u64, n: u64) -> (u64, ScanStatus) {
        if self.forces.list.is_empty() {
            return self.engine.run_scans(image, t0, dt, n);
        }
        scan_by_scan(self, image, t0, dt, n, None)
    }

    /// As [`Forced::run_scans`], ending early where `watch` sees a change.
    fn run_scans_watching(
        &mut self,
        image: &mut Image,
        t0: u64,
        dt: u64,
        n: u64,
        watch: &mut ChangeWatch,
    ) -> (u64, ScanStatus) {
        if self.forces.list.is_empty() {
            return self.engine.run_scans_watching(image, t0, dt, n, watch);
        }
        scan_by_scan(self, image, t0, dt, n, Some(watch))
    }
}
