//! Packed BCD (spec §1.6): one decimal digit per nibble, `#0000`–`#9999` in a word,
//! `#00000000`–`#99999999` in a double word (16 digits for the `*BL` product).
//!
//! Every conversion is branch-free arithmetic on the whole value (no digit loop): these run
//! in every BCD timer, counter and arithmetic execution of both engines, so they are on the
//! scan's hot path. `tests` checks them against the digit-by-digit definition, exhaustively
//! for words.

/// Mask of the bits where a carry out of each nibble but the top one lands after adding 6 to
/// every nibble of a `digits`-nibble value.
const fn carry_bits(digits: u32) -> u128 {
    let mut m = 0u128;
    let mut i = 1;
    while i <= digits {
        m |= 1 << (4 * i);
        i += 1;
    }
    m
}

/// `6` in every one of `digits` nibbles.
const fn sixes(digits: u32) -> u128 {
    let mut m = 0u128;
    let mut i = 0;
    while i < digits {
        m |= 6 << (4 * i);
        i += 1;
    }
    m
}

/// Whether each of the `digits` low nibbles of `v` is 0–9 and `v` has no bits above them.
/// Adding 6 to every nibble carries out of the lowest nibble above 9 and out of no other
/// before it, so `v` is BCD exactly when that sum has no carry at a nibble boundary.
#[inline]
fn valid(v: u64, digits: u32) -> bool {
    let v = u128::from(v);
    if digits < 16 && v >> (4 * digits) != 0 {
        return false;
    }
    let carries = (v + sixes(digits)) ^ v ^ sixes(digits);
    carries & carry_bits(digits) == 0
}

/// The value of valid BCD `v` of up to 16 digits: each step turns pairs of `k`-digit decimal
/// fields held in `2k`-nibble lanes into one `2k`-digit field (`hi·16^k + lo` minus
/// `hi·(16^k − 10^k)` is `hi·10^k + lo`).
#[inline]
fn value(v: u64) -> u64 {
    let v = v - 6 * ((v >> 4) & 0x0F0F_0F0F_0F0F_0F0F); // bytes 0–99
    let v = v - 156 * ((v >> 8) & 0x00FF_00FF_00FF_00FF); // 16-bit lanes 0–9999
    let v = v - 55_536 * ((v >> 16) & 0x0000_FFFF_0000_FFFF); // 32-bit lanes 0–99 999 999
    v - 4_194_967_296 * (v >> 32)
}

/// 0–99 as two BCD digits.
#[inline]
fn two_digits(v: u64) -> u64 {
    ((v / 10) << 4) | (v % 10)
}

/// 0–9999 as four BCD digits.
#[inline]
fn four_digits(v: u64) -> u64 {
    (two_digits(v / 100) << 8) | two_digits(v % 100)
}

/// 0–99 999 999 as eight BCD digits.
#[inline]
fn eight_digits(v: u64) -> u64 {
    (four_digits(v / 10_000) << 16) | four_digits(v % 10_000)
}

/// Whether every nibble of `v` is a decimal digit.
pub fn is_bcd16(v: u16) -> bool {
    valid(u64::from(v), 4)
}

/// Whether every nibble of `v` is a decimal digit.
pub fn is_bcd32(v: u32) -> bool {
    valid(u64::from(v), 8)
}

/// The value of a 4-digit BCD word (`#1234` → 1234), or `None` if it is not BCD.
#[inline]
pub fn bcd16_to_bin(v: u16) -> Option<u16> {
    is_bcd16(v).then(|| value(u64::from(v)) as u16) // at most 9999
}

/// 0–9999 as a 4-digit BCD word, or `None` above 9999.
#[inline]
pub fn bin_to_bcd16(v: u16) -> Option<u16> {
    (v <= 9999).then(|| four_digits(u64::from(v)) as u16) // 4 nibbles
}

/// The value of an 8-digit BCD double word, or `None` if it is not BCD.
#[inline]
pub fn bcd32_to_bin(v: u32) -> Option<u32> {
    is_bcd32(v).then(|| value(u64::from(v)) as u32) // at most 99 999 999
}

/// 0–99 999 999 as an 8-digit BCD double word, or `None` above.
#[inline]
pub fn bin_to_bcd32(v: u32) -> Option<u32> {
    (v <= 99_999_999).then(|| eight_digits(u64::from(v)) as u32) // 8 nibbles
}

/// 0–9 999 999 999 999 999 as 16 BCD digits (the `*BL` product), or `None` above. Small
/// values (every sum and 16-bit result) take the short paths.
#[inline]
pub fn bin_to_bcd64(v: u64) -> Option<u64> {
    const LIMIT: u64 = 10_000_000_000_000_000;
    Some(match v {
        0..10_000 => four_digits(v),
        10_000..100_000_000 => eight_digits(v),
        100_000_000..LIMIT => (eight_digits(v / 100_000_000) << 32) | eight_digits(v % 100_000_000),
        _ => return None,
    })
}

/// The value of 16 BCD digits, or `None` if a nibble is above 9.
pub fn bcd64_to_bin(v: u64) -> Option<u64> {
    valid(v, 16).then(|| value(v))
}

/// The number format of a timer's or counter's set value and PV (spec §1.9): BCD for the plain
/// mnemonics, unsigned binary for the `X` variants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// 4-digit BCD, `#0000`–`#9999`.
    Bcd,
    /// Unsigned binary, `&0`–`&65535`.
    Binary,
}

impl Format {
    /// BCD if `bcd`, else binary (`OmronTimerKind::bcd`, `OmronCounterKind::bcd`).
    pub fn of(bcd: bool) -> Format {
        if bcd { Format::Bcd } else { Format::Binary }
    }

    /// The value of a stored word, or `None` if it is not valid in this format.
    pub fn decode(self, word: u16) -> Option<u16> {
        match self {
            Format::Bcd => bcd16_to_bin(word),
            Format::Binary => Some(word),
        }
    }

    /// The stored word of `value`. Callers store only values at most a decoded SV or PV, which
    /// always fit; a BCD value above 9999 would be stored as `#9999`.
    pub fn encode(self, value: u16) -> u16 {
        match self {
            Format::Bcd => bin_to_bcd16(value).unwrap_or(0x9999),
            Format::Binary => value,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words() {
        // §1.6: BCD (16) is `#0000`–`#9999`, each nibble 0–9.
        assert_eq!(bcd16_to_bin(0x1234), Some(1234));
        assert_eq!(bcd16_to_bin(0x9999), Some(9999));
        assert_eq!(bcd16_to_bin(0x0000), Some(0));
        // §5 E015's example: #12A4 is not BCD; neither is a high nibble above 9.
        assert_eq!(bcd16_to_bin(0x12A4), None);
        assert_eq!(bcd16_to_bin(0xA000), None);
        assert!(is_bcd16(0x0300));
        assert!(!is_bcd16(0x03A0)); // §6.10's AER extension pointer
        assert_eq!(bin_to_bcd16(256), Some(0x0256));
        assert_eq!(bin_to_bcd16(9999), Some(0x9999));
        assert_eq!(bin_to_bcd16(10000), None);
        assert_eq!(bin_to_bcd16(u16::MAX), None);
    }

    #[test]
    fn formats() {
        // §1.9: BCD PVs/SVs for TIM/CNT, unsigned binary for the X variants.
        assert_eq!(Format::Bcd.decode(0x0100), Some(100));
        assert_eq!(Format::Bcd.decode(0x12A4), None);
        assert_eq!(Format::Binary.decode(0x12A4), Some(0x12A4));
        assert_eq!(Format::Bcd.encode(100), 0x0100);
        assert_eq!(Format::Binary.encode(100), 100);
        assert_eq!(Format::of(true), Format::Bcd);
    }

    /// The digit-by-digit definition of §1.6: `digits` nibbles, each 0–9, most significant
    /// first.
    fn reference_decode(v: u64, digits: u32) -> Option<u64> {
        if digits < 16 && v >> (4 * digits) != 0 {
            return None;
        }
        (0..digits).rev().try_fold(0u64, |acc, i| {
            let d = (v >> (4 * i)) & 0xF;
            (d <= 9).then_some(acc * 10 + d)
        })
    }

    fn reference_encode(mut v: u64, digits: u32) -> Option<u64> {
        let mut out = 0;
        for i in 0..digits {
            out |= (v % 10) << (4 * i);
            v /= 10;
        }
        (v == 0).then_some(out)
    }

    #[test]
    fn every_word_matches_the_digit_definition() {
        for v in 0..=u16::MAX {
            let want = reference_decode(u64::from(v), 4);
            assert_eq!(bcd16_to_bin(v).map(u64::from), want, "{v:#06x}");
            assert_eq!(is_bcd16(v), want.is_some());
            let enc = reference_encode(u64::from(v), 4);
            assert_eq!(bin_to_bcd16(v).map(u64::from), enc, "{v}");
        }
    }

    #[test]
    fn wide_values_match_the_digit_definition() {
        // A fixed pseudo-random walk plus the edges of every digit count.
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut samples = vec![0, 9, 10, 99_999_999, 100_000_000, u64::MAX];
        for d in 0..16 {
            samples.extend([0xAu64 << (4 * d), 9u64 << (4 * d), 10u64.pow(d) - 1]);
        }
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            samples.push(x);
            samples.push(x & 0x9999_9999_9999_9999);
            samples.push(x % 10_000_000_000_000_000);
        }
        for v in samples {
            let v32 = v as u32;
            assert_eq!(
                bcd32_to_bin(v32).map(u64::from),
                reference_decode(u64::from(v32), 8),
                "{v32:#x}"
            );
            assert_eq!(
                bin_to_bcd32(v32).map(u64::from),
                reference_encode(u64::from(v32), 8),
                "{v32}"
            );
            assert_eq!(bcd64_to_bin(v), reference_decode(v, 16), "{v:#x}");
            assert_eq!(bin_to_bcd64(v), reference_encode(v, 16), "{v}");
        }
    }

    #[test]
    fn double_words_and_round_trips() {
        assert_eq!(bcd32_to_bin(0x9999_9999), Some(99_999_999));
        assert_eq!(bcd32_to_bin(0x0001_0000), Some(10_000));
        assert_eq!(bcd32_to_bin(0x0000_00F0), None);
        assert!(!is_bcd32(0xA000_0000));
        assert_eq!(bin_to_bcd32(12_345_678), Some(0x1234_5678));
        assert_eq!(bin_to_bcd32(100_000_000), None);
        assert_eq!(bin_to_bcd64(9_999_999_999_999_999), Some(u64::MAX / 15 * 9));
        assert_eq!(bin_to_bcd64(10_000_000_000_000_000), None);
        assert_eq!(
            bcd64_to_bin(0x9999_9999_9999_9999),
            Some(9_999_999_999_999_999)
        );
        assert_eq!(bcd64_to_bin(0xF000_0000_0000_0000), None);
        for v in (0..=9999u16).step_by(7) {
            assert_eq!(bin_to_bcd16(v).and_then(bcd16_to_bin), Some(v));
        }
        for v in [0u32, 1, 9, 10, 99_999_999, 50_505_050] {
            assert_eq!(bin_to_bcd32(v).and_then(bcd32_to_bin), Some(v));
        }
    }
}
