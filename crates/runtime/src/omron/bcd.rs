//! Packed BCD (spec §1.6): one decimal digit per nibble, `#0000`–`#9999` in a word,
//! `#00000000`–`#99999999` in a double word (16 digits for the `*BL` product).
//!
//! One pair of digit loops (`decode`, `encode`) serves every width; the public functions
//! only fix the digit count.

/// The value of the `digits` low nibbles of `v` as decimal digits, or `None` if a nibble is
/// above 9 or `v` has bits above the digits.
fn decode(v: u64, digits: u32) -> Option<u64> {
    if digits < 16 && v >> (4 * digits) != 0 {
        return None;
    }
    let mut out = 0u64;
    for i in (0..digits).rev() {
        let d = (v >> (4 * i)) & 0xF;
        if d > 9 {
            return None;
        }
        out = out * 10 + d;
    }
    Some(out)
}

/// `v` as `digits` BCD digits, or `None` if it needs more digits. The loop stops at the last
/// non-zero digit (most values are small; the remaining digits are 0).
fn encode(mut v: u64, digits: u32) -> Option<u64> {
    let mut out = 0u64;
    let mut i = 0;
    while v != 0 && i < digits {
        out |= (v % 10) << (4 * i);
        v /= 10;
        i += 1;
    }
    (v == 0).then_some(out)
}

/// Whether every nibble of `v` is a decimal digit.
pub fn is_bcd16(v: u16) -> bool {
    bcd16_to_bin(v).is_some()
}

/// Whether every nibble of `v` is a decimal digit.
pub fn is_bcd32(v: u32) -> bool {
    bcd32_to_bin(v).is_some()
}

/// The value of a 4-digit BCD word (`#1234` → 1234), or `None` if it is not BCD.
pub fn bcd16_to_bin(v: u16) -> Option<u16> {
    decode(u64::from(v), 4).map(|b| b as u16) // at most 9999
}

/// 0–9999 as a 4-digit BCD word, or `None` above 9999.
pub fn bin_to_bcd16(v: u16) -> Option<u16> {
    encode(u64::from(v), 4).map(|b| b as u16) // 4 nibbles
}

/// The value of an 8-digit BCD double word, or `None` if it is not BCD.
pub fn bcd32_to_bin(v: u32) -> Option<u32> {
    decode(u64::from(v), 8).map(|b| b as u32) // at most 99 999 999
}

/// 0–99 999 999 as an 8-digit BCD double word, or `None` above.
pub fn bin_to_bcd32(v: u32) -> Option<u32> {
    encode(u64::from(v), 8).map(|b| b as u32) // 8 nibbles
}

/// 0–9 999 999 999 999 999 as 16 BCD digits (the `*BL` product), or `None` above.
pub fn bin_to_bcd64(v: u64) -> Option<u64> {
    encode(v, 16)
}

/// The value of 16 BCD digits, or `None` if a nibble is above 9.
pub fn bcd64_to_bin(v: u64) -> Option<u64> {
    decode(v, 16)
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
