//! Instructions that touch a run of memory: `S/R/SI/RI` bit ranges, block moves, `FILL` and the
//! `SHRB` shift register (spec §4.1, §4.2, §4.7, §4.11, M10–M12).
//!
//! Runs are given as image offsets plus the end of the area they must stay inside (a [`Span`]),
//! so direct operands and pointers go through the same check. Every failure writes nothing.
//! Count rule (spec §4.7): a block-move or FILL count of 0, or a run leaving its area, is 0x0091.

use crate::flags::{OVERFLOW, SmFlags, apply_flags};
use crate::image::area_span;
use crate::{mem, pointer};
use stljit_core::ir::BitLoc;
use stljit_core::layout::Layout;
use stljit_core::{Area, ErrorCode, Width};

/// The start of a run in the image and the end (exclusive) of the area holding it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    /// Image offset of the first byte.
    pub start: u32,
    /// Image offset one past the area's last byte (for `L`, the frame's).
    pub end: u32,
}

impl Span {
    /// The span at byte `offset` of `area` (L: frame `frame`), or `None` if `offset` lies outside.
    pub fn of(layout: &Layout, area: Area, offset: u32, frame: u32) -> Option<Span> {
        let start = area_span(layout, area, offset, 0, frame)?;
        let end = area_span(layout, area, 0, 0, frame)? + layout.area_size(area);
        (start < end).then_some(Span { start, end })
    }

    /// The span a pointer designates (checked like a `width` access, spec §1.6).
    pub fn of_pointer(
        layout: &Layout,
        ptr: u32,
        width: Width,
        write: bool,
    ) -> Result<Span, ErrorCode> {
        let start = pointer::resolve(layout, ptr, width, write)?;
        let (area, _) = pointer::decode(ptr).ok_or(ErrorCode::IndirectAddress)?;
        let end = layout.base(area) + layout.area_size(area);
        Ok(Span { start, end })
    }

    fn fits(self, count: u32, width: Width) -> bool {
        u64::from(self.start) + u64::from(count) * u64::from(width.bytes()) <= u64::from(self.end)
    }

    /// The image range of the `len` bytes from the span's start, or 0x0091 when they run past
    /// the area's end (or the image).
    pub fn bytes(self, len: u32, img_len: usize) -> Result<std::ops::Range<usize>, ErrorCode> {
        let end = u64::from(self.start) + u64::from(len);
        if end > u64::from(self.end) || end > img_len as u64 {
            return Err(ErrorCode::OperandRange);
        }
        Ok(self.start as usize..end as usize)
    }
}

/// T/C bits: one 0/1 byte per element instead of eight bits per byte.
fn is_element_area(area: Area) -> bool {
    matches!(area, Area::TimerBit | Area::CounterBit)
}

/// The numbers of the `count` timers or counters from `first` (`R Tn, N`, `R Cn, N`, or one
/// object with `count = 1`), whose bits are `bits` ([`Area::TimerBit`] or [`Area::CounterBit`]):
/// 0x0091 when the run passes the profile's last one (spec M11), empty for `count = 0` (M12).
pub fn object_run(
    layout: &Layout,
    bits: Area,
    first: u16,
    count: u32,
) -> Result<std::ops::Range<u16>, ErrorCode> {
    let end = u32::from(first) + count;
    if end > layout.area_size(bits) {
        return Err(ErrorCode::OperandRange);
    }
    Ok(first..end as u16)
}

/// The bits `S/R start, N` writes: `count` consecutive bits from `start`, bit numbering
/// continuing into the next byte, or on T/C bits one element (a whole 0/1 byte) per step.
/// Computed by [`set_range_run`]; [`set_range_imm`] writes it, and the JIT inlines it for a
/// constant `N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitRun {
    /// The first bit (bit index within the area; on T/C bits the element index).
    pub first: u32,
    /// How many bits (or elements).
    pub count: u32,
    /// T/C bits: each step is the next timer's or counter's bit byte.
    pub per_element: bool,
}

impl BitRun {
    /// `(byte within the area, bit)` of every bit of the run, in order (elements: bit 0).
    pub fn bits(self) -> impl Iterator<Item = (u32, u8)> {
        (self.first..self.first + self.count).map(move |i| {
            if self.per_element {
                (i, 0)
            } else {
                (i / 8, (i % 8) as u8)
            }
        })
    }
}

/// The run `S/R start, count` writes in an area of `layout` (spec §4.1): `Ok(None)` for
/// `count = 0` (a no-op, M12); a run past the area end is 0x0091 and writes nothing (M11).
pub fn set_range_run(
    layout: &Layout,
    start: BitLoc,
    count: u32,
) -> Result<Option<BitRun>, ErrorCode> {
    if count == 0 {
        return Ok(None);
    }
    if start.bit > 7 {
        return Err(ErrorCode::OperandRange);
    }
    let size = u64::from(layout.area_size(start.area));
    let per_element = is_element_area(start.area);
    let (first, limit) = if per_element {
        (u64::from(start.byte), size)
    } else {
        (u64::from(start.byte) * 8 + u64::from(start.bit), size * 8)
    };
    if first + u64::from(count) > limit {
        return Err(ErrorCode::OperandRange);
    }
    Ok(Some(BitRun {
        first: first as u32,
        count,
        per_element,
    }))
}

/// `S/R bit, N` and `SI/RI`: writes `value` into the [`BitRun`] of `start` and `count`.
/// `immediate` (`SI`/`RI`) also writes the physical output copy (Q only). N = 0 is a no-op
/// (M12); a run past the area end writes nothing and is 0x0091 (M11).
pub fn set_range_imm(
    img: &mut [u8],
    layout: &Layout,
    start: BitLoc,
    frame: u32,
    count: u32,
    value: bool,
    immediate: bool,
) -> Result<(), ErrorCode> {
    if count == 0 {
        return Ok(());
    }
    let base = area_span(layout, start.area, 0, 0, frame).ok_or(ErrorCode::OperandRange)?;
    let Some(run) = set_range_run(layout, start, count)? else {
        return Ok(());
    };
    let phys = immediate && start.area == Area::Q;
    for (byte, bit) in run.bits() {
        if run.per_element {
            mem::set_u8(img, base + byte, u8::from(value));
        } else {
            mem::set_bit(img, base + byte, bit, value);
            if phys {
                mem::set_bit(img, layout.phys_out + byte, bit, value);
            }
        }
    }
    Ok(())
}

/// `BMB/BMW/BMD`: copies `count` elements of `width` from `src` to `dst`, ascending, element by
/// element (each read right before its write, which defines overlapping moves, M10).
pub fn block_move(
    img: &mut [u8],
    src: Span,
    dst: Span,
    width: Width,
    count: u32,
) -> Result<(), ErrorCode> {
    if count == 0 || count > 255 || !src.fits(count, width) || !dst.fits(count, width) {
        return Err(ErrorCode::OperandRange);
    }
    let w = width.bytes();
    for i in 0..count {
        let v = mem::get_be(img, src.start + i * w, width);
        mem::set_be(img, dst.start + i * w, width, v);
    }
    Ok(())
}

/// `FILL IN, OUT, N`: writes the word `value` into `count` words from `dst`.
pub fn fill(img: &mut [u8], value: u16, dst: Span, count: u32) -> Result<(), ErrorCode> {
    if count == 0 || count > 255 || !dst.fits(count, Width::Word) {
        return Err(ErrorCode::OperandRange);
    }
    for i in 0..count {
        mem::set_be(img, dst.start + 2 * i, Width::Word, u32::from(value));
    }
    Ok(())
}

/// `SHRB DATA, S_BIT, N` (spec §4.11): shifts the |N|-bit register starting at `start` one step
/// (N > 0 toward higher bit numbers, DATA entering at `start`; N < 0 the other way, DATA entering
/// at the top) and puts the bit shifted out in SM1.1. `data` is read by the caller before the
/// call. N = 0 or |N| > 64 is 0x0092; a register past the area end is 0x0091.
pub fn shift_register(
    img: &mut [u8],
    layout: &Layout,
    data: bool,
    start: BitLoc,
    frame: u32,
    len: i8,
) -> Result<(), ErrorCode> {
    let n = u32::from(len.unsigned_abs());
    if n == 0 || n > 64 {
        return Err(ErrorCode::CountField);
    }
    if start.bit > 7 || is_element_area(start.area) {
        return Err(ErrorCode::OperandRange);
    }
    let base = area_span(layout, start.area, 0, 0, frame).ok_or(ErrorCode::OperandRange)?;
    let first = u64::from(start.byte) * 8 + u64::from(start.bit);
    let top = first + u64::from(n) - 1;
    if top >= u64::from(layout.area_size(start.area)) * 8 {
        return Err(ErrorCode::OperandRange);
    }
    let get = |img: &[u8], i: u64| mem::get_bit(img, base + (i / 8) as u32, (i % 8) as u8);
    let set =
        |img: &mut [u8], i: u64, v| mem::set_bit(img, base + (i / 8) as u32, (i % 8) as u8, v);
    let out = if len > 0 {
        let out = get(img, top);
        for i in (first + 1..=top).rev() {
            let v = get(img, i - 1);
            set(img, i, v);
        }
        set(img, first, data);
        out
    } else {
        let out = get(img, first);
        for i in first..top {
            let v = get(img, i + 1);
            set(img, i, v);
        }
        set(img, top, data);
        out
    };
    apply_flags(
        img,
        layout,
        SmFlags::assign(OVERFLOW, if out { OVERFLOW } else { 0 }),
    );
    Ok(())
}

#[cfg(test)]
#[path = "block_tests.rs"]
mod tests;
