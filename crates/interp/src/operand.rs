//! Operand access for the interpreter: every operand is first resolved to an [`Addr`] (checking
//! bounds, pointers and writability), then read or written. Resolving a destination before
//! computing is what guarantees spec §4.0 rule 3: an operand error writes nothing.

use crate::exec::Machine;
use stljit_core::ir::{BitLoc, Operand};
use stljit_core::{Area, ErrorCode, Width};
use stljit_runtime::block::Span;
use stljit_runtime::image::{bit_addr, loc_addr};
use stljit_runtime::{mem, pointer};

/// A resolved operand.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Addr {
    /// Image offset of the value's first byte.
    Image(u32),
    /// A constant (or an `&x` pointer value).
    Value(u32),
}

impl Machine<'_> {
    /// Resolves `op` for a `width` access; `write` rejects constants and read-only pointer
    /// targets.
    pub(crate) fn resolve(
        &self,
        op: &Operand,
        width: Width,
        frame: u32,
        write: bool,
    ) -> Result<Addr, ErrorCode> {
        match *op {
            Operand::Mem(loc) => loc_addr(self.layout, loc, width, frame)
                .map(Addr::Image)
                .ok_or(ErrorCode::OperandRange),
            Operand::Const(c) if !write => Ok(Addr::Value(c & width.mask())),
            Operand::AddressOf(loc) if !write => pointer::make(loc.area, loc.offset)
                .map(|p| Addr::Value(p & width.mask()))
                .ok_or(ErrorCode::IndirectAddress),
            // Omron indirect operands are resolved by the runtime (`omron_image`), only in
            // Omron boxes (the verifier rejects them elsewhere).
            Operand::Const(_) | Operand::AddressOf(_) | Operand::Omron(_) => {
                Err(ErrorCode::OperandRange)
            }
            Operand::Indirect(loc) => {
                let at = loc_addr(self.layout, loc, Width::DWord, frame)
                    .ok_or(ErrorCode::IndirectAddress)?;
                let ptr = mem::get_be(self.img, at, Width::DWord);
                pointer::resolve(self.layout, ptr, width, write).map(Addr::Image)
            }
        }
    }

    pub(crate) fn load(&self, a: Addr, width: Width) -> u32 {
        match a {
            Addr::Image(at) => mem::get_be(self.img, at, width),
            Addr::Value(v) => v,
        }
    }

    pub(crate) fn store(&mut self, a: Addr, width: Width, v: u32) {
        if let Addr::Image(at) = a {
            mem::set_be(self.img, at, width, v);
        }
    }

    /// Reads an input operand.
    pub(crate) fn read(&self, op: &Operand, width: Width, frame: u32) -> Result<u32, ErrorCode> {
        let a = self.resolve(op, width, frame, false)?;
        Ok(self.load(a, width))
    }

    /// Resolves the start of a run for the block instructions.
    pub(crate) fn span(
        &self,
        op: &Operand,
        width: Width,
        frame: u32,
        write: bool,
    ) -> Result<Span, ErrorCode> {
        match *op {
            Operand::Mem(loc) => {
                Span::of(self.layout, loc.area, loc.offset, frame).ok_or(ErrorCode::OperandRange)
            }
            Operand::Indirect(loc) => {
                let at = loc_addr(self.layout, loc, Width::DWord, frame)
                    .ok_or(ErrorCode::IndirectAddress)?;
                let ptr = mem::get_be(self.img, at, Width::DWord);
                Span::of_pointer(self.layout, ptr, width, write)
            }
            Operand::Const(_) | Operand::AddressOf(_) | Operand::Omron(_) => {
                Err(ErrorCode::OperandRange)
            }
        }
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
