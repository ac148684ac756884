//! Operand resolution (spec §4.0): an IR operand becomes an [`Addr`] (checking bounds, pointers
//! and writability) before anything is read or written, which is what makes "an operand error
//! writes nothing" hold. The interpreter resolves every operand through here, and so do the
//! instructions that run wholly in the runtime (`ext`), so both engines resolve alike.

use crate::block::Span;
use crate::image::loc_addr;
use crate::{mem, pointer};
use stljit_core::ir::Operand;
use stljit_core::layout::Layout;
use stljit_core::{ErrorCode, Width};

/// A resolved operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Addr {
    /// Image offset of the value's first byte.
    Image(u32),
    /// A constant (or an `&x` pointer value).
    Value(u32),
}

/// Resolves `op` for a `width` access in L frame `frame`; `write` rejects constants and
/// read-only pointer targets. A direct location outside its area is 0x0091 (the verifier rules
/// it out), a bad pointer 0x0006.
pub fn resolve(
    img: &[u8],
    layout: &Layout,
    op: &Operand,
    width: Width,
    frame: u32,
    write: bool,
) -> Result<Addr, ErrorCode> {
    match *op {
        Operand::Mem(loc) => loc_addr(layout, loc, width, frame)
            .map(Addr::Image)
            .ok_or(ErrorCode::OperandRange),
        Operand::Const(c) if !write => Ok(Addr::Value(c & width.mask())),
        Operand::AddressOf(loc) if !write => pointer::make(loc.area, loc.offset)
            .map(|p| Addr::Value(p & width.mask()))
            .ok_or(ErrorCode::IndirectAddress),
        // Omron indirect operands are resolved by `omron_image`, only in Omron boxes (the
        // verifier rejects them elsewhere).
        Operand::Const(_) | Operand::AddressOf(_) | Operand::Omron(_) => {
            Err(ErrorCode::OperandRange)
        }
        Operand::Indirect(loc) => {
            let ptr = pointer_value(img, layout, loc, frame)?;
            pointer::resolve(layout, ptr, width, write).map(Addr::Image)
        }
    }
}

/// The pointer stored in the dword at `loc` (0x0006 when that dword is outside its area).
fn pointer_value(
    img: &[u8],
    layout: &Layout,
    loc: stljit_core::ir::Loc,
    frame: u32,
) -> Result<u32, ErrorCode> {
    let at = loc_addr(layout, loc, Width::DWord, frame).ok_or(ErrorCode::IndirectAddress)?;
    Ok(mem::get_be(img, at, Width::DWord))
}

/// The value at a resolved address.
pub fn load(img: &[u8], a: Addr, width: Width) -> u32 {
    match a {
        Addr::Image(at) => mem::get_be(img, at, width),
        Addr::Value(v) => v,
    }
}

/// Writes a value to a resolved address (nothing for a constant, which `resolve` never gives
/// for a write).
pub fn store(img: &mut [u8], a: Addr, width: Width, v: u32) {
    if let Addr::Image(at) = a {
        mem::set_be(img, at, width, v);
    }
}

/// Resolves and reads an input operand.
pub fn read(
    img: &[u8],
    layout: &Layout,
    op: &Operand,
    width: Width,
    frame: u32,
) -> Result<u32, ErrorCode> {
    resolve(img, layout, op, width, frame, false).map(|a| load(img, a, width))
}

/// The run an operand starts (block moves, FILL, tables, buffers, strings): its first byte and
/// the end of its area, the first element checked like a `width` access. Constants start no
/// run (0x0091).
pub fn span(
    img: &[u8],
    layout: &Layout,
    op: &Operand,
    width: Width,
    frame: u32,
    write: bool,
) -> Result<Span, ErrorCode> {
    match *op {
        Operand::Mem(loc) => {
            Span::of(layout, loc.area, loc.offset, frame).ok_or(ErrorCode::OperandRange)
        }
        Operand::Indirect(loc) => {
            let ptr = pointer_value(img, layout, loc, frame)?;
            Span::of_pointer(layout, ptr, width, write)
        }
        Operand::Const(_) | Operand::AddressOf(_) | Operand::Omron(_) => {
            Err(ErrorCode::OperandRange)
        }
    }
}
