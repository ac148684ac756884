//! The text rules of s7-200-more §5.2–§5.4 as pure functions on bytes: ASCII ↔ hex digits
//! (`ATH`, `HTA`), numbers → text (`ITA`, `DTA`, `RTA` and the string forms `ITS`, `DTS`,
//! `RTS`) and text → numbers (`STI`, `STD`, `STR`). Integer-exact throughout: a REAL is
//! formatted from the exact decimal value of its f32 (rounded half away from zero) and parsed
//! with correct rounding to nearest even, so both engines, and any host, give the same bytes.

/// What a number-to-text conversion produces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum NumText {
    /// The text, right-justified to the output size: ENO 1.
    Text(Vec<u8>),
    /// The output size filled with spaces: ENO 0 (more than 5 fraction digits, a REAL that is
    /// NaN, infinite or too wide for its field).
    Spaces(usize),
    /// An illegal format: nothing is written, ENO 0.
    Illegal,
}

/// The output size of ITA/ITS (8) and DTA/DTS (12) (§5.3).
pub const INT_SIZE: usize = 8;
/// The output size of DTA/DTS.
pub const DINT_SIZE: usize = 12;

/// The separator and fraction digits of a format byte's low nibble: bit 3 comma, bits 2–0
/// digits.
fn separator(fmt: u8) -> (u8, usize) {
    (
        if fmt & 0x08 != 0 { b',' } else { b'.' },
        usize::from(fmt & 0x07),
    )
}

/// `magnitude` in decimal with `frac` digits after `sep` (zero-padded to at least `frac + 1`
/// digits) and a '-' when `negative`, right-justified in `size` bytes, or
/// [`NumText::Spaces`] when that text is wider. Written from the right into the one buffer it
/// returns: these conversions run every scan in some programs.
fn fixed_point_text(magnitude: u128, frac: usize, sep: u8, negative: bool, size: usize) -> NumText {
    let mut out = vec![b' '; size];
    match write_from_right(&mut out, magnitude, frac, sep, negative) {
        Some(()) => NumText::Text(out),
        None => NumText::Spaces(size),
    }
}

/// Writes [`fixed_point_text`]'s text at the end of `out`; `None` when it does not fit.
fn write_from_right(
    out: &mut [u8],
    magnitude: u128,
    frac: usize,
    sep: u8,
    neg: bool,
) -> Option<()> {
    let mut free = out.len();
    let mut put = |b: u8| {
        free = free.checked_sub(1)?;
        out[free] = b;
        Some(())
    };
    let (mut m, mut n) = (magnitude, 0);
    while n <= frac || m != 0 {
        if n == frac && frac > 0 {
            put(sep)?;
        }
        // A u64 division where the value fits: a u128 one is a library call.
        let digit = match u64::try_from(m) {
            Ok(small) => {
                m = u128::from(small / 10);
                small % 10
            }
            Err(_) => {
                let d = (m % 10) as u64;
                m /= 10;
                d
            }
        };
        put(b'0' + digit as u8)?;
        n += 1;
    }
    if neg {
        put(b'-')?;
    }
    Some(())
}

/// ITA/DTA/ITS/DTS (§5.3 `int_text`): `v` with `nnn` digits after the separator, right-justified
/// in `size` bytes ([`INT_SIZE`] or [`DINT_SIZE`]). A format with bits 7–4 set is illegal; more
/// than 5 digits gives spaces.
pub fn int_text(v: i32, fmt: u8, size: usize) -> NumText {
    if fmt & 0xF0 != 0 {
        return NumText::Illegal;
    }
    let (sep, frac) = separator(fmt);
    if frac > 5 {
        return NumText::Spaces(size);
    }
    fixed_point_text(u128::from(v.unsigned_abs()), frac, sep, v < 0, size)
}

/// The magnitude of the f32 `x` (finite, below 1e16) times 10^`frac`, rounded half away from
/// zero: exact integer arithmetic on the float's significand and exponent.
fn scaled_magnitude(x: f32, frac: usize) -> u128 {
    let bits = x.to_bits();
    let exp = ((bits >> 23) & 0xFF) as i32;
    let mant = bits & 0x7F_FFFF;
    // x = m · 2^e exactly.
    let (m, e) = if exp == 0 {
        (u128::from(mant), -149)
    } else {
        (u128::from(mant | 0x80_0000), exp - 150)
    };
    let scaled = m * 10u128.pow(frac as u32);
    if e >= 0 {
        return scaled << e;
    }
    let k = e.unsigned_abs();
    if k >= 100 {
        // scaled < 2^41, far below half of 2^k: rounds to 0.
        return 0;
    }
    let q = scaled >> k;
    let rem = scaled & ((1u128 << k) - 1);
    if rem >= 1u128 << (k - 1) { q + 1 } else { q }
}

/// RTA/RTS (§5.3 `real_text`): the f32 with bits `bits`, `nnn` fraction digits, right-justified
/// in `ssss` bytes (the format's bits 7–4, 3..=15, else illegal). More than 5 digits, NaN, ±Inf
/// or a text longer than `ssss` give spaces. `-0.0004` with one digit is `"0.0"` (no sign when
/// the rounded value is 0).
pub fn real_text(bits: u32, fmt: u8) -> NumText {
    let size = usize::from(fmt >> 4);
    if !(3..=15).contains(&size) {
        return NumText::Illegal;
    }
    let (sep, frac) = separator(fmt);
    let x = f32::from_bits(bits);
    if frac > 5 || !x.is_finite() {
        return NumText::Spaces(size);
    }
    // 1e16 has 17 digits: wider than any field.
    if x.abs() >= 1e16 {
        return NumText::Spaces(size);
    }
    let q = scaled_magnitude(x, frac);
    let negative = x.is_sign_negative() && q != 0;
    fixed_point_text(q, frac, sep, negative, size)
}

/// ATH (§5.2): the hex digit of an ASCII character (`0`–`9`, upper-case `A`–`F` only).
pub fn hex_digit(c: u8) -> Option<u8> {
    match c {
        b'0'..=b'9' => Some(c - b'0'),
        b'A'..=b'F' => Some(c - b'A' + 10),
        _ => None,
    }
}

/// ATH: converts the characters `src` into hex digits packed two per byte into `out` (its old
/// contents, at least `(src.len() + 1) / 2` bytes), first character in the high nibble; a
/// nibble no character reaches keeps its value. Stops at the first character that is no hex
/// digit; returns whether every character was one.
pub fn ascii_to_hex(src: &[u8], out: &mut [u8]) -> bool {
    for (i, &c) in src.iter().enumerate() {
        let Some(d) = hex_digit(c) else {
            return false;
        };
        let b = &mut out[i / 2];
        *b = if i % 2 == 0 {
            (*b & 0x0F) | d << 4
        } else {
            (*b & 0xF0) | d
        };
    }
    true
}

/// HTA (§5.2): the first `len` hex digits of `src` (high nibble of each byte first) as upper-case
/// ASCII characters.
pub fn hex_to_ascii(src: &[u8], len: usize) -> Vec<u8> {
    (0..len)
        .map(|i| {
            let b = src[i / 2];
            let d = if i % 2 == 0 { b >> 4 } else { b & 0x0F };
            b"0123456789ABCDEF"[usize::from(d)]
        })
        .collect()
}

/// Why a string holds no number for STI/STD/STR (SM1.1 := 1, OUT unchanged, ENO 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParseFail {
    /// No digit where the number should start.
    NoNumber,
    /// The value does not fit the result type.
    Overflow,
}

/// The number text from 1-based position `start` of the string characters `s` (§5.4): spaces
/// skipped, one optional sign, the digits, and with `fraction` one optional `.` or `,` and
/// more digits; it ends at the end of the string or the first other character. Returns the
/// sign, the integer digits and the fraction digits.
fn scan_number(s: &[u8], start: usize, fraction: bool) -> Result<(bool, &[u8], &[u8]), ParseFail> {
    let mut p = start.saturating_sub(1);
    while s.get(p) == Some(&b' ') {
        p += 1;
    }
    let negative = s.get(p) == Some(&b'-');
    if matches!(s.get(p), Some(b'+' | b'-')) {
        p += 1;
    }
    let digits = |from: usize| {
        let n = s[from.min(s.len())..]
            .iter()
            .take_while(|c| c.is_ascii_digit())
            .count();
        &s[from.min(s.len())..from.min(s.len()) + n]
    };
    let int = digits(p);
    if int.is_empty() {
        return Err(ParseFail::NoNumber);
    }
    p += int.len();
    let frac = if fraction && matches!(s.get(p), Some(b'.' | b',')) {
        digits(p + 1)
    } else {
        &[]
    };
    Ok((negative, int, frac))
}

/// STI/STD: the integer at 1-based position `start` of `s`, within `min..=max`.
pub fn parse_int(s: &[u8], start: usize, min: i64, max: i64) -> Result<i64, ParseFail> {
    let (negative, int, _) = scan_number(s, start, false)?;
    let mut v: i64 = 0;
    for &c in int {
        v = v
            .checked_mul(10)
            .and_then(|v| v.checked_add(i64::from(c - b'0')))
            .ok_or(ParseFail::Overflow)?;
    }
    let v = if negative { -v } else { v };
    if (min..=max).contains(&v) {
        Ok(v)
    } else {
        Err(ParseFail::Overflow)
    }
}

/// STR: the real at 1-based position `start` of `s` (no exponent: `1.234E6` is 1.234), the
/// exact decimal rounded to the nearest f32 (ties to even); a value that rounds to infinity
/// overflows.
pub fn parse_real(s: &[u8], start: usize) -> Result<f32, ParseFail> {
    let (negative, int, frac) = scan_number(s, start, true)?;
    let mut text = String::with_capacity(int.len() + frac.len() + 2);
    if negative {
        text.push('-');
    }
    text.extend(int.iter().map(|&c| char::from(c)));
    if !frac.is_empty() {
        text.push('.');
        text.extend(frac.iter().map(|&c| char::from(c)));
    }
    // Rust's float parsing is correctly rounded (round to nearest, ties to even).
    let v: f32 = text.parse().map_err(|_| ParseFail::NoNumber)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ParseFail::Overflow)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(t: NumText) -> String {
        match t {
            NumText::Text(b) => String::from_utf8(b).unwrap(),
            other => format!("{other:?}"),
        }
    }

    /// §5.3 reference values (ITA: the manual's figure; DTA and RTA: its examples).
    #[test]
    fn reference_values() {
        let ita = |v| text(int_text(v, 0x03, INT_SIZE));
        assert_eq!(ita(12), "   0.012");
        assert_eq!(ita(-123), "  -0.123");
        assert_eq!(ita(1234), "   1.234");
        assert_eq!(ita(-12345), " -12.345");
        let dta = |v| text(int_text(v, 0x04, DINT_SIZE));
        assert_eq!(dta(-12), "     -0.0012");
        assert_eq!(dta(1234567), "    123.4567");
        let rta = |x: f32| text(real_text(x.to_bits(), 0x61));
        assert_eq!(rta(1234.5), "1234.5");
        assert_eq!(rta(-0.0004), "   0.0");
        assert_eq!(rta(-3.67526), "  -3.7");
        assert_eq!(rta(1.95), "   2.0");
        assert_eq!(real_text(12345.67f32.to_bits(), 0x61), NumText::Spaces(6));
        assert_eq!(text(int_text(1234, 0x0B, INT_SIZE)), "   1,234");
    }

    /// The widest values still fit (§5.3 [derived]); illegal formats and too many digits.
    #[test]
    fn widths_and_formats() {
        assert_eq!(text(int_text(-32768, 0x05, INT_SIZE)), "-0.32768");
        assert_eq!(text(int_text(i32::MIN, 0x05, DINT_SIZE)), "-21474.83648");
        assert_eq!(text(int_text(0, 0x00, INT_SIZE)), "       0");
        assert_eq!(text(int_text(-7, 0x00, INT_SIZE)), "      -7");
        assert_eq!(int_text(5, 0x06, INT_SIZE), NumText::Spaces(INT_SIZE));
        assert_eq!(int_text(5, 0x13, INT_SIZE), NumText::Illegal);
        assert_eq!(
            real_text(1.0f32.to_bits(), 0x21),
            NumText::Illegal,
            "ssss 2"
        );
        assert_eq!(
            real_text(1.0f32.to_bits(), 0x0B),
            NumText::Illegal,
            "ssss 0"
        );
        assert_eq!(real_text(1.0f32.to_bits(), 0x66), NumText::Spaces(6));
        assert_eq!(real_text(f32::NAN.to_bits(), 0x61), NumText::Spaces(6));
        assert_eq!(
            real_text(f32::INFINITY.to_bits(), 0xF2),
            NumText::Spaces(15)
        );
        assert_eq!(
            text(real_text(0.5f32.to_bits(), 0x30)),
            "  1",
            "half away from zero"
        );
        assert_eq!(text(real_text((-2.5f32).to_bits(), 0x40)), "  -3");
        assert_eq!(text(real_text(1e15f32.to_bits(), 0xF0)), "999999986991104");
        assert_eq!(real_text(1e16f32.to_bits(), 0xF0), NumText::Spaces(15));
        // 0.125 is exact in binary: a true tie at 2 digits rounds away from zero.
        assert_eq!(text(real_text(0.125f32.to_bits(), 0x52)), " 0.13");
        // 1.005 is 1.00499999523… as an f32: rounds down.
        assert_eq!(text(real_text(1.005f32.to_bits(), 0x52)), " 1.00");
        assert_eq!(
            text(real_text(f32::from_bits(1).to_bits(), 0x75)),
            "0.00000"
        );
        assert_eq!(
            real_text(f32::from_bits(1).to_bits(), 0x55),
            NumText::Spaces(5)
        );
        assert_eq!(text(real_text((-1.25f32).to_bits(), 0x6A)), " -1,25");
    }

    /// §12 M8: ATH with an odd count keeps the low nibble; it stops at `G`.
    #[test]
    fn ascii_hex() {
        let mut out = [0x00, 0xFF];
        assert!(ascii_to_hex(b"3EA", &mut out));
        assert_eq!(out, [0x3E, 0xAF]);
        let mut out = [0x00, 0x00];
        assert!(!ascii_to_hex(b"EAG", &mut out));
        assert_eq!(out, [0xEA, 0x00]);
        let mut out = [0x55];
        assert!(!ascii_to_hex(b"a1", &mut out), "lower case is no hex digit");
        assert_eq!(out, [0x55]);
        assert_eq!(hex_to_ascii(&[0xE3, 0x1A], 3), b"E31");
        assert_eq!(hex_to_ascii(&[0xE3, 0x1A], 4), b"E31A");
    }

    /// §5.4: the manual's valid and invalid strings.
    #[test]
    fn string_to_number() {
        let int = |s: &str| parse_int(s.as_bytes(), 1, -32768, 32767);
        assert_eq!(int("123"), Ok(123));
        assert_eq!(int("-00456"), Ok(-456));
        assert_eq!(int("123.45"), Ok(123));
        assert_eq!(int("+2345"), Ok(2345));
        assert_eq!(int("000000123ABCD"), Ok(123));
        assert_eq!(int("   -32768"), Ok(-32768));
        for bad in ["A123", "", "++123", "+-123", "+ 123", "   "] {
            assert_eq!(int(bad), Err(ParseFail::NoNumber), "{bad:?}");
        }
        assert_eq!(int("32768"), Err(ParseFail::Overflow));
        assert_eq!(int("99999999999999999999999"), Err(ParseFail::Overflow));
        assert_eq!(
            parse_int(b"2147483647", 1, i64::from(i32::MIN), i64::from(i32::MAX)),
            Ok(2_147_483_647)
        );
        let real = |s: &str, p| parse_real(s.as_bytes(), p);
        assert_eq!(real("123.45", 1), Ok(123.45));
        assert_eq!(real("1.234E6", 1), Ok(1.234));
        assert_eq!(real("-3,5", 1), Ok(-3.5));
        assert_eq!(real("7.", 1), Ok(7.0));
        assert_eq!(real(".5", 1), Err(ParseFail::NoNumber));
        // §12 M9: position 6 of "Temp: -77.8C" is the blank before "-77.8".
        assert_eq!(real("Temp: -77.8C", 6).map(f32::to_bits), Ok(0xC29B_999A));
        assert_eq!(
            parse_int(b"Temp: -77.8C", 7, -32768, 32767),
            Ok(-77),
            "from position 7"
        );
        assert_eq!(real(&"9".repeat(40), 1), Err(ParseFail::Overflow));
        assert_eq!(real("5", 2), Err(ParseFail::NoNumber), "past the end");
    }
}
