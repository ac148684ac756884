//! Spec §4.1 (T03 S with N = 3), M10–M12, §4.7 counts and §4.11 SHRB.

use super::*;
use crate::image::Image;
use stljit_core::ProfileId;
use stljit_core::ir::Loc;

fn img() -> Image {
    Image::blank(ProfileId::A5)
}

fn q(byte: u32, bit: u8) -> BitLoc {
    BitLoc {
        area: Area::Q,
        byte,
        bit,
    }
}

fn byte(im: &Image, area: Area, off: u32) -> u32 {
    im.read(Loc { area, offset: off }, Width::Byte, 0).unwrap()
}

#[test]
fn set_range_continues_into_next_byte() {
    let mut im = img();
    let (b, l) = im.split_mut();
    // §4.1: S Q0.6, 3 sets Q0.6, Q0.7, Q1.0.
    set_range_imm(b, l, q(0, 6), 0, 3, true, false).unwrap();
    assert_eq!((byte(&im, Area::Q, 0), byte(&im, Area::Q, 1)), (0xC0, 0x01));
    let (b, l) = im.split_mut();
    set_range_imm(b, l, q(0, 7), 0, 1, false, false).unwrap();
    assert_eq!(byte(&im, Area::Q, 0), 0x40);
}

#[test]
fn set_range_limits() {
    let mut im = img();
    let before = im.clone();
    let (b, l) = im.split_mut();
    assert_eq!(
        set_range_imm(b, l, q(15, 6), 0, 3, true, false),
        Err(ErrorCode::OperandRange)
    );
    assert_eq!(
        set_range_imm(b, l, q(15, 6), 0, 0, true, false),
        Ok(()),
        "N = 0: no-op (M12)"
    );
    assert_eq!(im, before, "M11: nothing written");
    let (b, l) = im.split_mut();
    assert_eq!(set_range_imm(b, l, q(15, 6), 0, 2, true, false), Ok(()));
}

#[test]
fn set_range_on_timer_bits_and_immediate() {
    let mut im = img();
    let (b, l) = im.split_mut();
    let t = BitLoc {
        area: Area::TimerBit,
        byte: 62,
        bit: 0,
    };
    set_range_imm(b, l, t, 0, 2, true, false).unwrap();
    assert_eq!(
        set_range_imm(b, l, t, 0, 3, true, false),
        Err(ErrorCode::OperandRange)
    );
    set_range_imm(b, l, q(2, 1), 0, 2, true, true).unwrap();
    assert!(im.timer_bit(62) && im.timer_bit(63) && !im.timer_bit(61));
    assert_eq!(im.phys_out()[2], 0x06);
    assert_eq!(byte(&im, Area::Q, 2), 0x06);
}

#[test]
fn block_move_ascending_overlap_and_counts() {
    let mut im = img();
    for i in 0..4 {
        im.write(
            Loc {
                area: Area::V,
                offset: i,
            },
            Width::Byte,
            0,
            i + 1,
        )
        .unwrap();
    }
    let (b, l) = im.split_mut();
    let v = |o| Span::of(l, Area::V, o, 0).unwrap();
    // Overlapping forward move: element i is read just before element i is written (M10).
    block_move(b, v(0), v(1), Width::Byte, 3).unwrap();
    let got: Vec<_> = (0..4).map(|i| byte(&im, Area::V, i)).collect();
    assert_eq!(got, [1, 1, 1, 1]);
    let (b, l) = im.split_mut();
    let v = |o| Span::of(l, Area::V, o, 0).unwrap();
    assert_eq!(
        block_move(b, v(0), v(10), Width::Word, 0),
        Err(ErrorCode::OperandRange)
    );
    assert_eq!(
        block_move(b, v(0), v(2496), Width::DWord, 2),
        Err(ErrorCode::OperandRange)
    );
    assert_eq!(block_move(b, v(0), v(2492), Width::DWord, 2), Ok(()));
    assert_eq!(Span::of(l, Area::V, 2500, 0), None);
}

#[test]
fn fill_words() {
    let mut im = img();
    let (b, l) = im.split_mut();
    let dst = Span::of(l, Area::V, 11, 0).unwrap();
    fill(b, 0xABCD, dst, 2).unwrap();
    assert_eq!(
        fill(b, 1, Span::of(l, Area::V, 2498, 0).unwrap(), 2),
        Err(ErrorCode::OperandRange)
    );
    assert_eq!(
        im.read(
            Loc {
                area: Area::V,
                offset: 11
            },
            Width::DWord,
            0
        ),
        Ok(0xABCD_ABCD)
    );
}

#[test]
fn shrb_both_directions() {
    // Register V0.6, V0.7, V1.0, V1.1 (|N| = 4), spec §4.11; bits 1,0,0,1 initially.
    let mut im = img();
    let s = BitLoc {
        area: Area::V,
        byte: 0,
        bit: 6,
    };
    im.write(
        Loc {
            area: Area::V,
            offset: 0,
        },
        Width::Byte,
        0,
        0x40,
    )
    .unwrap();
    im.write(
        Loc {
            area: Area::V,
            offset: 1,
        },
        Width::Byte,
        0,
        0x02,
    )
    .unwrap();
    let step = |im: &mut Image, data: bool, len: i8| {
        let (b, l) = im.split_mut();
        shift_register(b, l, data, s, 0, len).unwrap();
        (
            byte(im, Area::V, 0),
            byte(im, Area::V, 1),
            byte(im, Area::SM, 1),
        )
    };
    let ovf = u32::from(OVERFLOW);
    // N > 0: DATA 1 enters at V0.6, V1.1 (1) leaves to SM1.1.
    assert_eq!(step(&mut im, true, 4), (0xC0, 0x00, ovf));
    // N < 0: DATA 0 enters at V1.1, V0.6 (1) leaves.
    assert_eq!(step(&mut im, false, -4), (0x40, 0x00, ovf));
    assert_eq!(step(&mut im, false, -4), (0x00, 0x00, ovf));
    assert_eq!(
        step(&mut im, false, -4),
        (0x00, 0x00, 0),
        "a 0 shifted out clears SM1.1"
    );
    let (b, l) = im.split_mut();
    assert_eq!(
        shift_register(b, l, true, s, 0, 0),
        Err(ErrorCode::CountField)
    );
    assert_eq!(
        shift_register(b, l, true, s, 0, -65),
        Err(ErrorCode::CountField)
    );
    let top = BitLoc {
        area: Area::V,
        byte: 2499,
        bit: 0,
    };
    assert_eq!(
        shift_register(b, l, true, top, 0, 9),
        Err(ErrorCode::OperandRange)
    );
    assert_eq!(shift_register(b, l, true, top, 0, 8), Ok(()));
}
