//! Operand access for the interpreter: every operand is first resolved to an [`Addr`] (checking
//! bounds, pointers and writability), then read or written. Resolving a destination before
//! computing is what guarantees spec §4.0 rule 3: an operand error writes nothing.

use crate::exec::Machine;
use stljit_core::ir::{BitLoc, Operand};
use stljit_core::{Area, ErrorCode, Width};
use stljit_runtime::block::Span;
use stljit_runtime::image::bit_addr;
use stljit_runtime::{mem, operand};

/// A resolved operand (the runtime's, so that the interpreter and the runtime's own
/// instructions resolve alike).
pub(crate) use stljit_runtime::operand::Addr;

impl Machine<'_> {
    /// Resolves `op` for a `width` access; `write` rejects constants and read-only pointer
    /// targets ([`operand::resolve`]).
    pub(crate) fn resolve(
        &self,
        op: &Operand,
        width: Width,
        frame: u32,
        write: bool,
    ) -> Result<Addr, ErrorCode> {
        operand::resolve(self.img, self.layout, op, width, frame, write)
    }

    pub(crate) fn load(&self, a: Addr, width: Width) -> u32 {
        operand::load(self.img, a, width)
    }

    pub(crate) fn store(&mut self, a: Addr, width: Width, v: u32) {
        operand::store(self.img, a, width, v);
    }

    /// Reads an input operand.
    pub(crate) fn read(&self, op: &Operand, width: Width, frame: u32) -> Result<u32, ErrorCode> {
        operand::read(self.img, self.layout, op, width, frame)
    }

    /// Resolves the start of a run for the block instructions ([`operand::span`]).
    pub(crate) fn span(
        &self,
        op: &Operand,
        width: Width,
        frame: u32,
        write: bool,
    ) -> Result<Span, ErrorCode> {
        operand::span(self.img, self.layout, op, width, frame, write)
    }

    /// Reads a bit (0 when the IR names one outside its area, which a checked program never does).
    pub(crate) fn bit(&self, b: BitLoc, frame: u32) -> bool {
        bit_addr(self.layout, b, frame).is_some_and(|at| mem::get_bit(self.img, at, b.bit))
    }

    /// Writes a bit.
    pub(crate) fn set_bit(&mut self, b: BitLoc, frame: u32, v: bool) {
        if let Some(at) = bit_addr(self.layout, b, frame) {
            mem::set_bit(self.img, at, b.bit, v);
        }
    }

    /// Reads a bit of the physical input copy (`LDI`).
    pub(crate) fn phys_in_bit(&self, b: BitLoc) -> bool {
        b.area == Area::I
            && b.byte < self.layout.area_size(Area::I)
            && mem::get_bit(self.img, self.layout.phys_in + b.byte, b.bit)
    }

    /// Writes a Q bit's physical output copy (`=I`).
    pub(crate) fn set_phys_out_bit(&mut self, b: BitLoc, v: bool) {
        if b.area == Area::Q && b.byte < self.layout.area_size(Area::Q) {
            mem::set_bit(self.img, self.layout.phys_out + b.byte, b.bit, v);
        }
    }
}
