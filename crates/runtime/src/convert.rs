//! Conversions of spec §4.12, on raw operand bits.
//!
//! Flag rule fixed here: a conversion whose "Flags" column names SM1.1 (ITB, DTI, ROUND, TRUNC)
//! or SM1.6 (BCDI, IBCD) writes that bit on every execution — 1 on an invalid input (OUT
//! unchanged, ENO = 0), 0 on success — as the spec states explicitly for ITB.

use crate::flags::{BCD, OVERFLOW, Outcome, SmFlags};
use stljit_core::ir::Conversion;

/// 7-segment patterns (bit 0 = a … bit 6 = g) of 0–F (spec §4.12 SEG).
pub const SEGMENTS: [u8; 16] = [
    0x3F, 0x06, 0x5B, 0x4F, 0x66, 0x6D, 0x7D, 0x07, 0x7F, 0x6F, 0x77, 0x7C, 0x39, 0x5E, 0x79, 0x71,
];

fn checked(v: Option<u32>, flag: u8) -> Outcome {
    match v {
        Some(v) => Outcome {
            value: Some(v),
            flags: SmFlags::assign(flag, 0),
        },
        None => Outcome {
            value: None,
            flags: SmFlags::assign(flag, flag),
        },
    }
}

/// `ROUND` and `TRUNC` of a real to a dint: `None` for NaN, ±Inf or out of the i32 range.
fn real_to_dint(x: f32, round: bool) -> Option<u32> {
    let r = if round { x.round() } else { x.trunc() }; // round(): half away from zero (M6)
    // -2^31 is exact in f32; 2^31 is the first value that does not fit.
    (r.is_finite() && (-2_147_483_648.0..2_147_483_648.0).contains(&r)).then_some(r as i32 as u32)
}

fn bcd_to_int(x: u16) -> Option<u32> {
    let mut v = 0u32;
    for shift in [12, 8, 4, 0] {
        let d = u32::from(x >> shift) & 0xF;
        if d > 9 {
            return None;
        }
        v = v * 10 + d;
    }
    Some(v)
}

fn int_to_bcd(x: i16) -> Option<u32> {
    if !(0..=9999).contains(&x) {
        return None;
    }
    let x = x as u32;
    Some(((x / 1000) << 12) | ((x / 100 % 10) << 8) | ((x / 10 % 10) << 4) | (x % 10))
}

/// Executes a conversion on the input bits (for BCDI/IBCD, the current value of OUT).
pub fn convert(conv: Conversion, src: u32) -> Outcome {
    match conv {
        Conversion::ByteToInt => Outcome::plain(src & 0xFF),
        Conversion::IntToByte => {
            let v = src as u16 as i16;
            checked((0..=255).contains(&v).then_some(v as u32), OVERFLOW)
        }
        Conversion::IntToDInt => Outcome::plain(i32::from(src as u16 as i16) as u32),
        Conversion::DIntToInt => {
            let v = src as i32;
            checked(
                i16::try_from(v).is_ok().then_some(v as u32 & 0xFFFF),
                OVERFLOW,
            )
        }
        Conversion::DIntToReal => Outcome::plain((src as i32 as f32).to_bits()),
        Conversion::Round => checked(real_to_dint(f32::from_bits(src), true), OVERFLOW),
        Conversion::Trunc => checked(real_to_dint(f32::from_bits(src), false), OVERFLOW),
        Conversion::BcdToInt => checked(bcd_to_int(src as u16), BCD),
        Conversion::IntToBcd => checked(int_to_bcd(src as u16 as i16), BCD),
        Conversion::Decode => Outcome::plain(1 << (src & 0x0F)),
        Conversion::Encode => {
            let v = src as u16;
            Outcome::plain(if v == 0 { 0 } else { v.trailing_zeros() })
        }
        Conversion::Segment => Outcome::plain(u32::from(SEGMENTS[(src & 0x0F) as usize])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Conversion::*;

    fn val(c: Conversion, x: u32) -> Option<u32> {
        convert(c, x).value
    }

    #[test]
    fn table_4_12() {
        assert_eq!(val(ByteToInt, 0x1FF), Some(0xFF));
        assert_eq!(val(IntToByte, 255), Some(255));
        assert_eq!(val(IntToByte, 256), None);
        assert_eq!(val(IntToByte, 0xFFFF), None, "-1 does not fit a byte");
        assert_eq!(val(IntToDInt, 0x8000), Some(0xFFFF_8000));
        assert_eq!(val(DIntToInt, 0xFFFF_8000), Some(0x8000));
        assert_eq!(val(DIntToInt, 32768), None);
        assert_eq!(
            val(DIntToReal, 16_777_217),
            Some(16_777_216f32.to_bits()),
            "nearest even"
        );
        let r = |x: f32| x.to_bits();
        assert_eq!(val(Round, r(2.5)), Some(3));
        assert_eq!(
            val(Round, r(-2.5)),
            Some(-3i32 as u32),
            "M6: half away from zero"
        );
        assert_eq!(val(Round, r(2.4999)), Some(2));
        assert_eq!(val(Trunc, r(-2.9)), Some(-2i32 as u32));
        assert_eq!(val(Trunc, r(f32::NAN)), None);
        assert_eq!(val(Round, r(2_147_483_648.0)), None);
        assert_eq!(val(Round, r(-2_147_483_648.0)), Some(0x8000_0000));
        assert_eq!(val(BcdToInt, 0x1234), Some(1234));
        assert_eq!(val(BcdToInt, 0x12A4), None);
        assert_eq!(val(IntToBcd, 9999), Some(0x9999));
        assert_eq!(val(IntToBcd, 10000), None);
        assert_eq!(val(Decode, 0x13), Some(8));
        assert_eq!(val(Encode, 0x0140), Some(6));
        assert_eq!(val(Encode, 0), Some(0));
        assert_eq!(val(Segment, 0x0B), Some(0x7C));
        assert_eq!(val(Segment, 0x28), Some(0x7F));
    }

    #[test]
    fn flags_written_both_ways() {
        assert_eq!(convert(IntToByte, 300).flags.apply(0), OVERFLOW);
        assert_eq!(convert(IntToByte, 3).flags.apply(0xFF), !OVERFLOW);
        assert_eq!(convert(BcdToInt, 0xF).flags.apply(0), BCD);
        assert_eq!(convert(IntToBcd, 5).flags.apply(0xFF), !BCD);
        assert_eq!(convert(Segment, 5).flags, SmFlags::NONE);
    }
}
