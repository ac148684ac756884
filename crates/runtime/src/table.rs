//! The table instructions (s7-200-more §4): `ATT`, `FIFO`, `LIFO` and `FND=`/`<>`/`<`/`>`.
//!
//! A table is a run of big-endian words: TL (the maximum number of entries, 1–100), EC (the
//! entry count), then the entries. Each function takes the table as a [`Span`] (its first word
//! and the end of its area) and checks every word it touches against it: a table that runs
//! past its area, or a TL or EC above 100, is 0x0091 and writes nothing. Every input is read
//! before anything is written; the writes go in the order of the spec's pseudo-code (DATA,
//! then the entries, then EC), which decides only where DATA overlaps the table.

use crate::block::Span;
use crate::flags::{SmFlags, TABLE_EMPTY, TABLE_FULL, apply_flags};
use crate::mem;
use crate::operand::{self, Addr};
use stljit_core::ir::FindRel;
use stljit_core::layout::Layout;
use stljit_core::{ErrorCode, Width};

/// The most entries a table holds (s7-200-more §4.1).
pub const MAX_ENTRIES: u32 = 100;

fn word(img: &[u8], at: usize) -> u16 {
    mem::get_be(img, at as u32, Width::Word) as u16
}

fn set_word(img: &mut [u8], at: usize, v: u16) {
    mem::set_be(img, at as u32, Width::Word, u32::from(v));
}

/// `count` (at most [`MAX_ENTRIES`], else 0x0091) entries after `header` bytes of `table`:
/// the image range of header and entries.
fn run(
    img: &[u8],
    table: Span,
    header: u32,
    count: u32,
) -> Result<std::ops::Range<usize>, ErrorCode> {
    if count > MAX_ENTRIES {
        return Err(ErrorCode::OperandRange);
    }
    table.bytes(header + 2 * count, img.len())
}

/// `ATT DATA, TBL`: appends `data` when EC < TL (SM1.4 := 0, ENO 1); a full table (EC ≥ TL)
/// is left alone with SM1.4 := 1 and ENO 0. Returns ENO.
pub fn add(img: &mut [u8], layout: &Layout, table: Span, data: u16) -> Result<bool, ErrorCode> {
    let head = table.bytes(4, img.len())?;
    let (tl, ec) = (word(img, head.start), word(img, head.start + 2));
    let r = run(img, table, 4, u32::from(tl))?;
    if ec >= tl {
        apply_flags(img, layout, SmFlags::assign(TABLE_FULL, TABLE_FULL));
        return Ok(false);
    }
    set_word(img, r.start + 4 + 2 * usize::from(ec), data);
    set_word(img, r.start + 2, ec + 1);
    apply_flags(img, layout, SmFlags::assign(TABLE_FULL, 0));
    Ok(true)
}

/// `FIFO TBL, DATA` (`lifo` false: the oldest entry, the rest move down one place; the vacated
/// last word keeps its value) or `LIFO TBL, DATA` (the newest entry): DATA := the entry,
/// EC −= 1, SM1.5 := 0, ENO 1. An empty table gives SM1.5 := 1, ENO 0, DATA unchanged. TL is
/// not read. `data` is resolved (for a write) by the caller.
pub fn take(
    img: &mut [u8],
    layout: &Layout,
    table: Span,
    data: Addr,
    lifo: bool,
) -> Result<bool, ErrorCode> {
    let head = table.bytes(4, img.len())?;
    let ec = word(img, head.start + 2);
    let r = run(img, table, 4, u32::from(ec))?;
    if ec == 0 {
        apply_flags(img, layout, SmFlags::assign(TABLE_EMPTY, TABLE_EMPTY));
        return Ok(false);
    }
    let entries: Vec<u16> = (0..usize::from(ec))
        .map(|i| word(img, r.start + 4 + 2 * i))
        .collect();
    let value = if lifo {
        entries[entries.len() - 1]
    } else {
        entries[0]
    };
    operand::store(img, data, Width::Word, u32::from(value));
    if !lifo {
        for (i, &v) in entries.iter().skip(1).enumerate() {
            set_word(img, r.start + 4 + 2 * i, v);
        }
    }
    set_word(img, r.start + 2, ec - 1);
    apply_flags(img, layout, SmFlags::assign(TABLE_EMPTY, 0));
    Ok(true)
}

/// Whether entry `d` stands in relation `rel` to the pattern `p` (signed INT compare, §13 T1).
pub fn matches(rel: FindRel, d: i16, p: i16) -> bool {
    match rel {
        FindRel::Eq => d == p,
        FindRel::Ne => d != p,
        FindRel::Lt => d < p,
        FindRel::Gt => d > p,
    }
}

/// `FND= TBL, PTN, INDX`: `ec` is the table's **EC** word (the entries follow it); the search
/// runs from entry `start` (INDX at entry; negative counts as 0) to EC − 1. Returns the new
/// INDX: the first matching entry, or EC when none matches.
pub fn find(
    img: &[u8],
    ec: Span,
    pattern: i16,
    start: i16,
    rel: FindRel,
) -> Result<u16, ErrorCode> {
    let head = ec.bytes(2, img.len())?;
    let n = word(img, head.start);
    let r = run(img, ec, 2, u32::from(n))?;
    let first = u16::try_from(start).unwrap_or(0);
    Ok((first..n)
        .find(|&i| {
            matches(
                rel,
                word(img, r.start + 2 + 2 * usize::from(i)) as i16,
                pattern,
            )
        })
        .unwrap_or(n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::Image;
    use stljit_core::{Area, ProfileId};

    fn setup(words: &[(u32, u16)]) -> Image {
        let mut img = Image::blank(ProfileId::A5);
        let v = img.layout().base(Area::V);
        for &(off, w) in words {
            set_word(img.bytes_mut(), (v + off) as usize, w);
        }
        img
    }

    fn vw(img: &Image, off: u32) -> u16 {
        word(img.bytes(), (img.layout().base(Area::V) + off) as usize)
    }

    fn span(img: &Image, off: u32) -> Span {
        Span::of(img.layout(), Area::V, off, 0).unwrap()
    }

    fn smb1(img: &Image) -> u8 {
        img.bytes()[img.layout().base(Area::SM) as usize + 1]
    }

    /// s7-200-more §12 M7: TL 4; ATT 10, 20, 30; FND= 20 from 0 finds entry 1; FIFO takes 10,
    /// LIFO takes 30; ATT 40, 50, 60 fill the table and ATT 70 finds it full.
    #[test]
    fn m7_att_fnd_fifo_lifo() {
        let mut img = setup(&[(200, 4), (202, 0)]);
        let t = span(&img, 200);
        for d in [10, 20, 30] {
            let (b, l) = img.split_mut();
            assert_eq!(add(b, l, t, d), Ok(true));
        }
        assert_eq!(vw(&img, 202), 3);
        // FND's TBL is the EC word (VW202).
        assert_eq!(
            find(img.bytes(), span(&img, 202), 20, 0, FindRel::Eq),
            Ok(1)
        );
        let v = img.layout().base(Area::V);
        let (b, l) = img.split_mut();
        assert_eq!(take(b, l, t, Addr::Image(v + 302), false), Ok(true));
        let (b, l) = img.split_mut();
        assert_eq!(take(b, l, t, Addr::Image(v + 304), true), Ok(true));
        assert_eq!((vw(&img, 302), vw(&img, 304)), (10, 30));
        // FIFO moved 20 and 30 down; LIFO took 30, so EC = 1 and d0 = 20.
        assert_eq!((vw(&img, 202), vw(&img, 204)), (1, 20));
        for d in [40, 50, 60] {
            let (b, l) = img.split_mut();
            assert_eq!(add(b, l, t, d), Ok(true));
        }
        let (b, l) = img.split_mut();
        assert_eq!(add(b, l, t, 70), Ok(false), "full");
        assert_eq!(smb1(&img) & TABLE_FULL, TABLE_FULL);
        let words: Vec<u16> = (0..6).map(|i| vw(&img, 200 + 2 * i)).collect();
        assert_eq!(words, [4, 4, 20, 40, 50, 60]);
        assert_eq!(smb1(&img) & TABLE_EMPTY, 0);
    }

    /// The manual's LIFO example: TL 6, EC 3, entries 5431, 8942, 1234 → DATA 1234, EC 2.
    #[test]
    fn lifo_manual_example_and_empty_table() {
        let mut img = setup(&[(0, 6), (2, 3), (4, 5431), (6, 8942), (8, 1234)]);
        let t = span(&img, 0);
        let v = img.layout().base(Area::V);
        let (b, l) = img.split_mut();
        assert_eq!(take(b, l, t, Addr::Image(v + 100), true), Ok(true));
        assert_eq!((vw(&img, 100), vw(&img, 2), vw(&img, 8)), (1234, 2, 1234));
        let mut img = setup(&[(0, 6), (100, 77)]);
        let (b, l) = img.split_mut();
        assert_eq!(take(b, l, t, Addr::Image(v + 100), false), Ok(false));
        assert_eq!((vw(&img, 100), smb1(&img) & TABLE_EMPTY), (77, TABLE_EMPTY));
    }

    /// FIFO leaves the vacated last word as it was (§4.2 [design], §13 T2).
    #[test]
    fn fifo_keeps_the_vacated_word() {
        let mut img = setup(&[(0, 3), (2, 3), (4, 1), (6, 2), (8, 3)]);
        let t = span(&img, 0);
        let v = img.layout().base(Area::V);
        let (b, l) = img.split_mut();
        assert_eq!(take(b, l, t, Addr::Image(v + 100), false), Ok(true));
        let words: Vec<u16> = (0..5).map(|i| vw(&img, 2 * i)).collect();
        assert_eq!(words, [3, 2, 2, 3, 3]);
    }

    /// TL above 100, EC above 100 and tables past the end of V are 0x0091, nothing written.
    #[test]
    fn range_errors_write_nothing() {
        let mut img = setup(&[(0, 101)]);
        let before = img.clone();
        let t = span(&img, 0);
        let (b, l) = img.split_mut();
        assert_eq!(add(b, l, t, 1), Err(ErrorCode::OperandRange));
        assert_eq!(img, before);
        // TL 10 at VW2490: the entries would end at VB2513, past VB2499.
        let mut img = setup(&[(2490, 10)]);
        let t = span(&img, 2490);
        let (b, l) = img.split_mut();
        assert_eq!(add(b, l, t, 1), Err(ErrorCode::OperandRange));
        let mut img = setup(&[(2, 101)]);
        let v = img.layout().base(Area::V);
        let t = span(&img, 0);
        let (b, l) = img.split_mut();
        assert_eq!(
            take(b, l, t, Addr::Image(v + 100), false),
            Err(ErrorCode::OperandRange)
        );
        assert_eq!(
            find(img.bytes(), span(&img, 2), 0, 0, FindRel::Eq),
            Err(ErrorCode::OperandRange)
        );
    }

    /// FND compares signed, starts at INDX (negative: 0), and gives EC when nothing matches.
    #[test]
    fn find_relations() {
        // EC 4 at VW10: -5, 7, 3, 7.
        let img = setup(&[(10, 4), (12, (-5i16) as u16), (14, 7), (16, 3), (18, 7)]);
        let ec = span(&img, 10);
        let f = |p, s, r| find(img.bytes(), ec, p, s, r);
        assert_eq!(f(7, 0, FindRel::Eq), Ok(1));
        assert_eq!(f(7, 2, FindRel::Eq), Ok(3));
        assert_eq!(f(7, 4, FindRel::Eq), Ok(4), "INDX = EC: not found");
        assert_eq!(f(7, 9, FindRel::Eq), Ok(4), "INDX past EC: EC");
        assert_eq!(f(0, 0, FindRel::Lt), Ok(0), "-5 < 0 signed");
        assert_eq!(f(7, 0, FindRel::Ne), Ok(0));
        assert_eq!(f(3, 0, FindRel::Gt), Ok(1));
        assert_eq!(f(7, -3, FindRel::Eq), Ok(1), "negative INDX counts as 0");
        assert_eq!(f(100, 0, FindRel::Gt), Ok(4));
    }
}
