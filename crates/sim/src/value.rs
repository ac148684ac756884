//! Value literals of stimulus cells and expectations, and reading or writing an [`Address`] in an
//! image the way a harness or an HMI does.
//!
//! Literals: bits `0`/`1`; integers in decimal (optionally signed), `16#` or `#` (Omron) hex or `2#` binary;
//! reals with a decimal point (`1.5`, `-2.0E+3`) for dwords only. Words and dwords accept both the
//! signed and the unsigned range (`-1` and `65535` are the same word), bytes only 0…255.
//! Every result is the raw bit pattern, zero-extended to `u32`.

use std::fmt;
use stljit_core::ir::{Address, BitLoc, Loc};
use stljit_core::layout::Layout;
use stljit_core::{Area, Width};
use stljit_runtime::image::{Image, bit_addr, loc_addr};

/// What a literal is parsed as: a bit or a value of a width.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ValueKind {
    /// `0` or `1`.
    Bit,
    /// A byte, word or dword.
    Value(Width),
}

impl ValueKind {
    /// The kind an address holds.
    pub fn of(address: &Address) -> ValueKind {
        match address {
            Address::Bit(_) => ValueKind::Bit,
            Address::Value { width, .. } => ValueKind::Value(*width),
        }
    }

    fn name(self) -> &'static str {
        match self {
            ValueKind::Bit => "a bit",
            ValueKind::Value(Width::Byte) => "a byte",
            ValueKind::Value(Width::Word) => "a word",
            ValueKind::Value(Width::DWord) => "a dword",
        }
    }
}

/// Why a literal was rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ValueError {
    /// Nothing but blanks.
    Empty,
    /// Not a number in any accepted notation.
    Syntax,
    /// A number that does not fit the kind (the text is kept for the message).
    OutOfRange {
        /// The kind it was parsed for.
        kind: ValueKind,
    },
    /// A real literal for something that is not a dword.
    RealNotAllowed {
        /// The kind it was parsed for.
        kind: ValueKind,
    },
}

impl fmt::Display for ValueError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ValueError::Empty => f.write_str("empty value"),
            ValueError::Syntax => f.write_str(
                "not a number (expected decimal, 16#hex, 2#binary or a real with a point)",
            ),
            ValueError::OutOfRange { kind } => match kind {
                ValueKind::Bit => f.write_str("a bit must be 0 or 1"),
                ValueKind::Value(Width::Byte) => f.write_str("out of range for a byte (0…255)"),
                ValueKind::Value(Width::Word) => {
                    f.write_str("out of range for a word (-32768…65535)")
                }
                ValueKind::Value(Width::DWord) => {
                    f.write_str("out of range for a dword (-2147483648…4294967295)")
                }
            },
            ValueError::RealNotAllowed { kind } => {
                write!(f, "a real literal needs a dword, this is {}", kind.name())
            }
        }
    }
}

impl std::error::Error for ValueError {}

/// Parses a literal for `kind` into its raw bit pattern.
pub fn parse_value(text: &str, kind: ValueKind) -> Result<u32, ValueError> {
    let t = text.trim();
    if t.is_empty() {
        return Err(ValueError::Empty);
    }
    let range = ValueError::OutOfRange { kind };
    if kind == ValueKind::Bit {
        return match t {
            "0" => Ok(0),
            "1" => Ok(1),
            _ if t.parse::<i64>().is_ok() => Err(range),
            _ => Err(ValueError::Syntax),
        };
    }
    let ValueKind::Value(width) = kind else {
        return Err(ValueError::Syntax);
    };
    let mask = u64::from(width.mask());
    // `16#` is S7's hex notation, `#` Omron's (`#00AA`, omron-cp.md §1.6).
    if let Some(digits) = t.strip_prefix("16#").or_else(|| t.strip_prefix('#')) {
        return radix(digits, 16, mask, range);
    }
    if let Some(digits) = t.strip_prefix("2#") {
        return radix(digits, 2, mask, range);
    }
    if t.contains('.') {
        let v: f32 = t.parse().map_err(|_| ValueError::Syntax)?;
        return match width {
            Width::DWord => Ok(v.to_bits()),
            _ => Err(ValueError::RealNotAllowed { kind }),
        };
    }
    let digits = t.strip_prefix('+').unwrap_or(t);
    if digits.starts_with(['+', '-']) && t.starts_with('+') {
        return Err(ValueError::Syntax);
    }
    let v: i64 = digits.parse().map_err(|e: std::num::ParseIntError| {
        if matches!(
            e.kind(),
            std::num::IntErrorKind::PosOverflow | std::num::IntErrorKind::NegOverflow
        ) {
            range.clone()
        } else {
            ValueError::Syntax
        }
    })?;
    let min = match width {
        Width::Byte => 0,
        Width::Word => i64::from(i16::MIN),
        Width::DWord => i64::from(i32::MIN),
    };
    if v < min || v > mask as i64 {
        return Err(range);
    }
    Ok((v as u64 & mask) as u32)
}

fn radix(digits: &str, radix: u32, mask: u64, range: ValueError) -> Result<u32, ValueError> {
    if digits.is_empty() || digits.starts_with(['+', '-']) {
        return Err(ValueError::Syntax);
    }
    match u64::from_str_radix(digits, radix) {
        Ok(v) if v <= mask => Ok(v as u32),
        Ok(_) => Err(range),
        Err(e) if *e.kind() == std::num::IntErrorKind::PosOverflow => Err(range),
        Err(_) => Err(ValueError::Syntax),
    }
}

/// Reads an address from the image (inputs from the I image, not the physical copy; `L` from the
/// main program's frame). `None` when the address does not fit the image's areas.
pub fn read_address(image: &Image, address: &Address) -> Option<u32> {
    match *address {
        Address::Bit(bit) => image.bit(bit, 0).ok().map(u32::from),
        Address::Value { loc, width } => image.read(loc, width, 0).ok(),
    }
}

/// The image bytes [`read_address`] reads for `address`, or `None` when it does not fit.
pub fn read_range(layout: &Layout, address: &Address) -> Option<std::ops::Range<usize>> {
    let (at, len) = match *address {
        Address::Bit(bit) => (bit_addr(layout, bit, 0)?, 1),
        Address::Value { loc, width } => (loc_addr(layout, loc, width, 0)?, width.bytes()),
    };
    Some(at as usize..(at + len) as usize)
}

/// Writes `raw` to an address the way the harness does before a scan: inputs (`I`) go to the
/// physical input copy, which the scan start copies into the I image; everything else is written
/// into the image directly, like an HMI write. Returns `false` (and writes nothing) when the
/// address does not fit its area. Writability is the caller's check ([`writable`]).
pub fn write_address(image: &mut Image, address: &Address, raw: u32) -> bool {
    let (bytes, layout) = image.split_mut();
    match *address {
        Address::Bit(bit) => {
            let Some(at) = target_bit(layout, bit) else {
                return false;
            };
            stljit_runtime::mem::set_bit(bytes, at, bit.bit, raw & 1 != 0);
        }
        Address::Value { loc, width } => {
            let Some(at) = target_value(layout, loc, width) else {
                return false;
            };
            stljit_runtime::mem::set_be(bytes, at, width, raw);
        }
    }
    true
}

/// The image offset [`write_address`] writes `address` at (the byte holding a bit; an input's
/// byte in the physical input copy), or `None` when the address does not fit its area.
pub fn write_offset(layout: &Layout, address: &Address) -> Option<u32> {
    match *address {
        Address::Bit(bit) => target_bit(layout, bit),
        Address::Value { loc, width } => target_value(layout, loc, width),
    }
}

fn target_bit(layout: &Layout, bit: BitLoc) -> Option<u32> {
    let at = bit_addr(layout, bit, 0)?;
    Some(rebase_input(layout, bit.area, at))
}

fn target_value(layout: &Layout, loc: Loc, width: Width) -> Option<u32> {
    let at = loc_addr(layout, loc, width, 0)?;
    Some(rebase_input(layout, loc.area, at))
}

/// Inputs are driven through the physical copy so that `LDI`/`BIR` see them too.
fn rebase_input(layout: &Layout, area: Area, at: u32) -> u32 {
    if area == Area::I {
        at - layout.base(Area::I) + layout.phys_in
    } else {
        at
    }
}

/// Why an address may not be driven from outside, or `None` when it may. Read-only for a
/// stimulus: SMB0 up to the profile's read-only limit (written by the CPU every scan), the
/// high-speed counters, and `L` (local to a POU frame, not addressable from outside).
pub fn writable(address: &Address, read_only_sm: u32) -> Option<&'static str> {
    let (area, first) = match *address {
        Address::Bit(b) => (b.area, b.byte),
        Address::Value { loc, .. } => (loc.area, loc.offset),
    };
    match area {
        Area::SM if first < read_only_sm => Some("SMB0–SMB29 are read-only (written by the CPU)"),
        Area::HC => Some(
            "a high-speed counter's current value is read-only (its counting is driven by steps: \
             an `HSCn` stimulus column)",
        ),
        Area::L => Some("L memory is local to a POU and cannot be driven from outside"),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ProfileId;

    const B: ValueKind = ValueKind::Value(Width::Byte);
    const W: ValueKind = ValueKind::Value(Width::Word);
    const D: ValueKind = ValueKind::Value(Width::DWord);

    #[test]
    fn literals() {
        assert_eq!(parse_value("1", ValueKind::Bit), Ok(1));
        assert_eq!(parse_value(" 0 ", ValueKind::Bit), Ok(0));
        assert_eq!(
            parse_value("2", ValueKind::Bit),
            Err(ValueError::OutOfRange {
                kind: ValueKind::Bit
            })
        );
        assert_eq!(parse_value("x", ValueKind::Bit), Err(ValueError::Syntax));
        assert_eq!(parse_value("255", B), Ok(255));
        assert_eq!(parse_value("16#FF", B), Ok(255));
        assert_eq!(parse_value("#00FF", B), Ok(255));
        assert_eq!(parse_value("2#1010", B), Ok(10));
        assert_eq!(
            parse_value("256", B),
            Err(ValueError::OutOfRange { kind: B })
        );
        assert_eq!(
            parse_value("-1", B),
            Err(ValueError::OutOfRange { kind: B })
        );
        assert_eq!(parse_value("-1", W), Ok(0xFFFF));
        assert_eq!(parse_value("+7", W), Ok(7));
        assert_eq!(parse_value("65535", W), Ok(0xFFFF));
        assert_eq!(parse_value("-32768", W), Ok(0x8000));
        assert_eq!(
            parse_value("-32769", W),
            Err(ValueError::OutOfRange { kind: W })
        );
        assert_eq!(
            parse_value("16#10000", W),
            Err(ValueError::OutOfRange { kind: W })
        );
        assert_eq!(parse_value("-2147483648", D), Ok(0x8000_0000));
        assert_eq!(parse_value("4294967295", D), Ok(u32::MAX));
        assert_eq!(
            parse_value("4294967296", D),
            Err(ValueError::OutOfRange { kind: D })
        );
        assert_eq!(parse_value("1.5", D), Ok(1.5f32.to_bits()));
        assert_eq!(parse_value("-2.0E+3", D), Ok((-2000.0f32).to_bits()));
        assert_eq!(
            parse_value("1.5", W),
            Err(ValueError::RealNotAllowed { kind: W })
        );
        assert_eq!(parse_value("", W), Err(ValueError::Empty));
        assert_eq!(parse_value("16#", W), Err(ValueError::Syntax));
        assert_eq!(parse_value("16#-1", W), Err(ValueError::Syntax));
        assert_eq!(parse_value("+-1", W), Err(ValueError::Syntax));
        assert_eq!(
            parse_value("99999999999999999999999", D),
            Err(ValueError::OutOfRange { kind: D })
        );
    }

    #[test]
    fn inputs_go_to_the_physical_copy_others_to_the_image() {
        let mut img = Image::blank(ProfileId::A5);
        let l = img.layout().clone();
        let i03 = Address::Bit(BitLoc {
            area: Area::I,
            byte: 0,
            bit: 3,
        });
        assert!(write_address(&mut img, &i03, 1));
        assert_eq!(img.bytes()[l.phys_in as usize], 0x08);
        assert_eq!(
            img.bytes()[l.base(Area::I) as usize],
            0,
            "image waits for the scan start"
        );
        let vw = Address::Value {
            loc: Loc {
                area: Area::V,
                offset: 100,
            },
            width: Width::Word,
        };
        assert!(write_address(&mut img, &vw, 0x1234));
        assert_eq!(read_address(&img, &vw), Some(0x1234));
        let past = Address::Value {
            loc: Loc {
                area: Area::V,
                offset: 2499,
            },
            width: Width::Word,
        };
        assert!(!write_address(&mut img, &past, 1));
        assert_eq!(read_address(&img, &past), None);
        let sm = Address::Bit(BitLoc {
            area: Area::SM,
            byte: 0,
            bit: 1,
        });
        assert!(writable(&sm, 30).is_some());
        let smb30 = Address::Value {
            loc: Loc {
                area: Area::SM,
                offset: 30,
            },
            width: Width::Byte,
        };
        assert_eq!(writable(&smb30, 30), None);
    }
}
