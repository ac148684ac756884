//! Pointers (`&VB100`, `*AC1`): the encoding of spec §1.6 and the run-time dereference check.
//!
//! A pointer is `area code << 24 | byte offset` ([`Area::pointer_code`]). Dereferencing checks
//! that the code names a pointer area, that the access fits the area, that T/C current values are
//! addressed at even offsets, and (for writes) that the target is writable: SMB0–SMB29, AI and HC
//! are read-only (spec A8). Any failure is the non-fatal error 0x0006.

use crate::image::area_span;
use stljit_core::layout::Layout;
use stljit_core::{Area, ErrorCode, Width};

/// The pointer `&area offset` (what `MOVD &VB100, AC1` stores), or `None` for an area a pointer
/// cannot address or an offset above 24 bits.
pub fn make(area: Area, offset: u32) -> Option<u32> {
    let code = area.pointer_code()?;
    (offset < 1 << 24).then_some(u32::from(code) << 24 | offset)
}

/// Splits a pointer into its area and offset, if the area code is known.
pub fn decode(ptr: u32) -> Option<(Area, u32)> {
    let area = Area::from_pointer_code((ptr >> 24) as u8)?;
    Some((area, ptr & 0x00FF_FFFF))
}

/// Image offset of a `width` access through `ptr` (spec §1.6, A8).
pub fn resolve(layout: &Layout, ptr: u32, width: Width, write: bool) -> Result<u32, ErrorCode> {
    let (area, offset) = decode(ptr).ok_or(ErrorCode::IndirectAddress)?;
    let value_area = matches!(area, Area::TimerValue | Area::CounterValue);
    if value_area && offset % 2 != 0 {
        return Err(ErrorCode::IndirectAddress);
    }
    if write {
        let read_only = match area {
            Area::SM => offset < layout.profile.profile().special_memory_read_only,
            Area::AI | Area::HC => true,
            _ => false,
        };
        if read_only {
            return Err(ErrorCode::IndirectAddress);
        }
    }
    area_span(layout, area, offset, width.bytes(), 0).ok_or(ErrorCode::IndirectAddress)
}

/// Image offset and end (exclusive) of `count` consecutive `width` elements through `ptr`, for
/// block moves and FILL: the first element is checked like [`resolve`], the span's end is the
/// caller's to check against the returned area end.
pub fn resolve_area_end(
    layout: &Layout,
    ptr: u32,
    width: Width,
    write: bool,
) -> Result<(u32, u32), ErrorCode> {
    let at = resolve(layout, ptr, width, write)?;
    let (area, _) = decode(ptr).ok_or(ErrorCode::IndirectAddress)?;
    Ok((at, layout.base(area) + layout.area_size(area)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ProfileId;

    #[test]
    fn encoding_matches_spec_1_6() {
        assert_eq!(make(Area::V, 200), Some(0x0600_00C8));
        assert_eq!(make(Area::TimerValue, 74), Some(0x0900_004A));
        assert_eq!(make(Area::L, 0), None, "L is not pointer-addressable");
        assert_eq!(make(Area::AC, 0), None);
        assert_eq!(decode(0x0300_0010), Some((Area::M, 16)));
        assert_eq!(decode(0x0B00_0000), None);
    }

    #[test]
    fn dereference_checks() {
        let l = Layout::of(ProfileId::A5);
        let v = |o| make(Area::V, o).unwrap();
        assert_eq!(
            resolve(&l, v(200), Width::Word, true),
            Ok(l.base(Area::V) + 200)
        );
        assert_eq!(
            resolve(&l, v(2496), Width::DWord, false),
            Ok(l.base(Area::V) + 2496)
        );
        let bad = Err(ErrorCode::IndirectAddress);
        assert_eq!(resolve(&l, v(2497), Width::DWord, false), bad);
        assert_eq!(resolve(&l, 0, Width::Byte, false), bad, "area code 0");
        // A8: SMB0–29 and AI are read-only through pointers, SMB30 is writable.
        let sm = |o| make(Area::SM, o).unwrap();
        assert_eq!(resolve(&l, sm(29), Width::Byte, true), bad);
        assert!(resolve(&l, sm(29), Width::Byte, false).is_ok());
        assert!(resolve(&l, sm(30), Width::Byte, true).is_ok());
        let ai = make(Area::AI, 0).unwrap();
        assert_eq!(resolve(&l, ai, Width::Word, true), bad);
        assert!(resolve(&l, ai, Width::Word, false).is_ok());
        // T/C current values: even offsets inside 2 × count.
        let t = |o| make(Area::TimerValue, o).unwrap();
        assert!(resolve(&l, t(126), Width::Word, true).is_ok());
        assert_eq!(resolve(&l, t(127), Width::Word, false), bad);
        assert_eq!(resolve(&l, t(128), Width::Word, false), bad);
        let c = make(Area::CounterValue, 62).unwrap();
        assert_eq!(
            resolve(&l, c, Width::Word, false),
            Ok(l.base(Area::CounterValue) + 62)
        );
    }
}
