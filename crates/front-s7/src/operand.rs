//! Operand syntax (spec §1.2): addresses, constants, `&` address-of and `*` pointers, parsed into
//! a width-free [`Syn`] before the instruction decides what the operand means.

use stljit_core::{Area, Width};

/// A constant as written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Const {
    /// A decimal integer with optional sign.
    Int(i64),
    /// A raw bit pattern: `16#..`, `2#..` or an ASCII constant.
    Bits(u64),
    /// A real literal (`1.5`, `-2.0E+3`).
    Real(f32),
}

/// An operand as written, before the instruction fixes its width and meaning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Syn {
    /// `I0.3`, `V10.2`, `SM0.1`: a bit of a byte-addressable area.
    Bit {
        /// The area.
        area: Area,
        /// Byte number.
        byte: u32,
        /// Bit number 0..=7.
        bit: u8,
    },
    /// `VB100`, `IW2`, `SMD4`, `AIW0`: a value of a byte-addressable area.
    Mem {
        /// The area.
        area: Area,
        /// Width from the prefix letter.
        width: Width,
        /// First byte.
        offset: u32,
    },
    /// `T37`: bit or current value, depending on the instruction.
    Timer(u32),
    /// `C5`.
    Counter(u32),
    /// `AC1`.
    Acc(u32),
    /// `HC0`.
    Hc(u32),
    /// A constant.
    Const(Const),
    /// `*VD4`, `*LD8`, `*AC1`: the pointer's own location.
    Indirect {
        /// `V`, `L` or `AC`.
        area: Area,
        /// Byte offset (`VD`/`LD`) or accumulator number (`AC`).
        n: u32,
    },
    /// `&VB100`, `&AIW0`, `&T37`: the pointed-to location.
    AddressOf {
        /// Target area (`TimerValue`/`CounterValue` for `&T`/`&C`).
        area: Area,
        /// Byte offset, or the timer/counter number.
        n: u32,
    },
}

/// Spells an operand as STL writes it (`I0.3`, `VW10`, `SMB34`, `T37`), for messages.
pub(crate) fn show(syn: Syn) -> String {
    use crate::spelling::{area_prefix, width_letter};
    match syn {
        Syn::Bit { area, byte, bit } => format!("{}{byte}.{bit}", area_prefix(area)),
        Syn::Mem {
            area: area @ (Area::AI | Area::AQ),
            offset,
            ..
        } => format!("{}W{offset}", area_prefix(area)),
        Syn::Mem {
            area,
            width,
            offset,
        } => format!("{}{}{offset}", area_prefix(area), width_letter(width)),
        Syn::Timer(n) => format!("T{n}"),
        Syn::Counter(n) => format!("C{n}"),
        Syn::Acc(n) => format!("AC{n}"),
        Syn::Hc(n) => format!("HC{n}"),
        Syn::Const(Const::Int(i)) => i.to_string(),
        Syn::Const(Const::Bits(b)) => format!("16#{b:X}"),
        Syn::Const(Const::Real(f)) => format!("{f:?}"),
        Syn::Indirect { area: Area::AC, n } => format!("*AC{n}"),
        Syn::Indirect { area, n } => format!("*{}D{n}", area_prefix(area)),
        Syn::AddressOf {
            area: Area::TimerValue,
            n,
        } => format!("&T{n}"),
        Syn::AddressOf {
            area: Area::CounterValue,
            n,
        } => format!("&C{n}"),
        Syn::AddressOf { area, n } => format!("&{}B{n}", area_prefix(area)),
    }
}

impl Syn {
    /// A short description for messages ("a byte address", "a constant", ...).
    pub(crate) fn describe(&self) -> &'static str {
        match self {
            Syn::Bit { .. } => "a bit address",
            Syn::Mem {
                width: Width::Byte, ..
            } => "a byte address",
            Syn::Mem {
                width: Width::Word, ..
            } => "a word address",
            Syn::Mem {
                width: Width::DWord,
                ..
            } => "a dword address",
            Syn::Timer(_) => "a timer",
            Syn::Counter(_) => "a counter",
            Syn::Acc(_) => "an accumulator",
            Syn::Hc(_) => "a high-speed counter",
            Syn::Const(Const::Real(_)) => "a real constant",
            Syn::Const(_) => "a constant",
            Syn::Indirect { .. } => "a pointer (*)",
            Syn::AddressOf { .. } => "an address-of (&)",
        }
    }
}

/// Why an operand text could not be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum SynError {
    /// Not address syntax at all: maybe a symbol.
    NotAddress,
    /// Address or constant syntax, but malformed; the text says how.
    Malformed(&'static str),
}

#[derive(Clone, Copy)]
enum Kind {
    Bit(Area),
    Mem(Area, Width),
    Timer,
    Counter,
    Acc,
    Hc,
}

/// Prefixes, longest first where one is a prefix of another (`SMB` before `SM` before `S`).
const PREFIXES: &[(&str, Kind)] = &[
    ("SMB", Kind::Mem(Area::SM, Width::Byte)),
    ("SMW", Kind::Mem(Area::SM, Width::Word)),
    ("SMD", Kind::Mem(Area::SM, Width::DWord)),
    ("SM", Kind::Bit(Area::SM)),
    ("AIW", Kind::Mem(Area::AI, Width::Word)),
    ("AQW", Kind::Mem(Area::AQ, Width::Word)),
    ("AC", Kind::Acc),
    ("HC", Kind::Hc),
    ("IB", Kind::Mem(Area::I, Width::Byte)),
    ("IW", Kind::Mem(Area::I, Width::Word)),
    ("ID", Kind::Mem(Area::I, Width::DWord)),
    ("I", Kind::Bit(Area::I)),
    ("QB", Kind::Mem(Area::Q, Width::Byte)),
    ("QW", Kind::Mem(Area::Q, Width::Word)),
    ("QD", Kind::Mem(Area::Q, Width::DWord)),
    ("Q", Kind::Bit(Area::Q)),
    ("MB", Kind::Mem(Area::M, Width::Byte)),
    ("MW", Kind::Mem(Area::M, Width::Word)),
    ("MD", Kind::Mem(Area::M, Width::DWord)),
    ("M", Kind::Bit(Area::M)),
    ("VB", Kind::Mem(Area::V, Width::Byte)),
    ("VW", Kind::Mem(Area::V, Width::Word)),
    ("VD", Kind::Mem(Area::V, Width::DWord)),
    ("V", Kind::Bit(Area::V)),
    ("SB", Kind::Mem(Area::S, Width::Byte)),
    ("SW", Kind::Mem(Area::S, Width::Word)),
    ("SD", Kind::Mem(Area::S, Width::DWord)),
    ("S", Kind::Bit(Area::S)),
    ("LB", Kind::Mem(Area::L, Width::Byte)),
    ("LW", Kind::Mem(Area::L, Width::Word)),
    ("LD", Kind::Mem(Area::L, Width::DWord)),
    ("L", Kind::Bit(Area::L)),
    ("T", Kind::Timer),
    ("C", Kind::Counter),
];

/// Reads a run of decimal digits, saturating (an absurd number is then simply out of range).
fn digits(b: &[u8]) -> (u32, usize) {
    let mut v: u32 = 0;
    let mut n = 0;
    while n < b.len() && b[n].is_ascii_digit() {
        v = v.saturating_mul(10).saturating_add(u32::from(b[n] - b'0'));
        n += 1;
    }
    (v, n)
}

/// Parses a direct address (`VW100`, `I0.3`, `T37`, `AC0`).
fn parse_address(t: &str) -> Result<Syn, SynError> {
    let b = t.as_bytes();
    let first = b.first().map_or(0, u8::to_ascii_uppercase);
    for &(p, kind) in PREFIXES {
        let pb = p.as_bytes();
        // Cheap first-letter filter: most operands are rejected by all but two or three entries.
        if pb[0] != first {
            continue;
        }
        if b.len() <= pb.len() || !b[..pb.len()].eq_ignore_ascii_case(pb) {
            continue;
        }
        let rest = &b[pb.len()..];
        if !rest[0].is_ascii_digit() {
            continue;
        }
        let (n, used) = digits(rest);
        let rest = &rest[used..];
        return match kind {
            Kind::Bit(area) => match rest {
                [b'.', d] if d.is_ascii_digit() => {
                    if *d > b'7' {
                        Err(SynError::Malformed("bit numbers run from 0 to 7"))
                    } else {
                        Ok(Syn::Bit {
                            area,
                            byte: n,
                            bit: d - b'0',
                        })
                    }
                }
                [] => Err(SynError::Malformed(
                    "a bit address needs a bit number (byte.bit, e.g. I0.3)",
                )),
                _ => Err(SynError::Malformed("expected byte.bit (e.g. V10.2)")),
            },
            _ if !rest.is_empty() => Err(SynError::Malformed("unexpected text after the address")),
            Kind::Mem(area, width) => Ok(Syn::Mem {
                area,
                width,
                offset: n,
            }),
            Kind::Timer => Ok(Syn::Timer(n)),
            Kind::Counter => Ok(Syn::Counter(n)),
            Kind::Acc => Ok(Syn::Acc(n)),
            Kind::Hc => Ok(Syn::Hc(n)),
        };
    }
    Err(SynError::NotAddress)
}

/// Parses a constant (`+50`, `-3`, `16#FF`, `2#1010`, `1.5`, `-2.0E+3`, `'AB'`).
pub(crate) fn parse_const(t: &str) -> Result<Const, SynError> {
    let b = t.as_bytes();
    if let Some(hash) = t.find('#') {
        let (radix, digits) = match &t[..hash] {
            "16" => (16, &t[hash + 1..]),
            "2" => (2, &t[hash + 1..]),
            _ => return Err(SynError::Malformed("only 16# and 2# radix prefixes exist")),
        };
        if digits.is_empty() || digits.len() > 32 || digits.starts_with(['+', '-']) {
            return Err(SynError::Malformed("bad digits after the radix prefix"));
        }
        return u64::from_str_radix(digits, radix)
            .map(Const::Bits)
            .map_err(|_| SynError::Malformed("bad digits after the radix prefix"));
    }
    if b.first() == Some(&b'\'') {
        let inner = t
            .strip_prefix('\'')
            .and_then(|s| s.strip_suffix('\''))
            .filter(|s| (1..=4).contains(&s.len()) && s.is_ascii())
            .ok_or(SynError::Malformed(
                "an ASCII constant holds 1 to 4 characters in single quotes",
            ))?;
        let v = inner.bytes().fold(0u64, |a, c| (a << 8) | u64::from(c));
        return Ok(Const::Bits(v));
    }
    let body = t.strip_prefix(['+', '-']).unwrap_or(t);
    if !body.as_bytes().first().is_some_and(u8::is_ascii_digit) {
        return Err(SynError::Malformed("a number must start with a digit"));
    }
    if body.bytes().all(|c| c.is_ascii_digit()) {
        if body.len() > 18 {
            return Err(SynError::Malformed("the number is too large"));
        }
        return t
            .parse::<i64>()
            .map(Const::Int)
            .map_err(|_| SynError::Malformed("bad integer constant"));
    }
    let real_chars = body
        .bytes()
        .all(|c| c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'E' | b'+' | b'-'));
    match t.parse::<f32>() {
        Ok(v) if real_chars && v.is_finite() => Ok(Const::Real(v)),
        Ok(_) if real_chars => Err(SynError::Malformed("the real constant is out of range")),
        _ => Err(SynError::Malformed("bad number")),
    }
}

/// Parses operand text without symbols: `Ok` for an address or constant, `NotAddress` for text
/// that can only be a symbol name.
pub(crate) fn parse_syn(t: &str) -> Result<Syn, SynError> {
    match t.as_bytes().first() {
        None => Err(SynError::Malformed("the operand is empty")),
        Some(b'+' | b'-' | b'\'' | b'0'..=b'9') => parse_const(t).map(Syn::Const),
        Some(b'&') => address_of(parse_syn(t[1..].trim_start())?),
        Some(b'*') => indirect(parse_syn(t[1..].trim_start())?),
        Some(c) if c.is_ascii_alphabetic() => parse_address(t),
        Some(_) => Err(SynError::NotAddress),
    }
}

/// `&x`: the pointed-to location of a byte address, an analog word or a timer/counter.
pub(crate) fn address_of(inner: Syn) -> Result<Syn, SynError> {
    match inner {
        Syn::Mem {
            area: area @ (Area::I | Area::Q | Area::M | Area::S | Area::SM | Area::V),
            width: Width::Byte,
            offset,
        }
        | Syn::Mem {
            area: area @ (Area::AI | Area::AQ),
            offset,
            ..
        } => Ok(Syn::AddressOf { area, n: offset }),
        Syn::Timer(n) => Ok(Syn::AddressOf {
            area: Area::TimerValue,
            n,
        }),
        Syn::Counter(n) => Ok(Syn::AddressOf {
            area: Area::CounterValue,
            n,
        }),
        _ => Err(SynError::Malformed(
            "& takes VB, IB, QB, MB, SB, SMB, AIW, AQW, T or C",
        )),
    }
}

/// `*x`: a pointer held in `VDn`, `LDn` or `ACn`.
pub(crate) fn indirect(inner: Syn) -> Result<Syn, SynError> {
    match inner {
        Syn::Mem {
            area: area @ (Area::V | Area::L),
            width: Width::DWord,
            offset,
        } => Ok(Syn::Indirect { area, n: offset }),
        Syn::Acc(n) => Ok(Syn::Indirect { area: Area::AC, n }),
        _ => Err(SynError::Malformed("* takes VD, LD or AC")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn syn(t: &str) -> Syn {
        parse_syn(t).unwrap_or_else(|e| panic!("{t}: {e:?}"))
    }

    #[test]
    fn longest_prefix_wins() {
        assert_eq!(
            syn("SMB28"),
            Syn::Mem {
                area: Area::SM,
                width: Width::Byte,
                offset: 28
            }
        );
        assert_eq!(
            syn("SM0.1"),
            Syn::Bit {
                area: Area::SM,
                byte: 0,
                bit: 1
            }
        );
        assert_eq!(
            syn("S0.1"),
            Syn::Bit {
                area: Area::S,
                byte: 0,
                bit: 1
            }
        );
        assert_eq!(
            syn("SB2"),
            Syn::Mem {
                area: Area::S,
                width: Width::Byte,
                offset: 2
            }
        );
        assert_eq!(
            syn("AIW4"),
            Syn::Mem {
                area: Area::AI,
                width: Width::Word,
                offset: 4
            }
        );
        assert_eq!(
            syn("ld12"),
            Syn::Mem {
                area: Area::L,
                width: Width::DWord,
                offset: 12
            }
        );
        assert_eq!(syn("T37"), Syn::Timer(37));
        assert_eq!(syn("C5"), Syn::Counter(5));
        assert_eq!(syn("AC0"), Syn::Acc(0));
        assert_eq!(syn("HC1"), Syn::Hc(1));
    }

    #[test]
    fn constants() {
        assert_eq!(syn("+50"), Syn::Const(Const::Int(50)));
        assert_eq!(syn("-3"), Syn::Const(Const::Int(-3)));
        assert_eq!(syn("16#FF"), Syn::Const(Const::Bits(0xFF)));
        assert_eq!(syn("16#abcd"), Syn::Const(Const::Bits(0xABCD)));
        assert_eq!(syn("2#1010"), Syn::Const(Const::Bits(10)));
        assert_eq!(syn("1.5"), Syn::Const(Const::Real(1.5)));
        assert_eq!(syn("-2.0E+3"), Syn::Const(Const::Real(-2000.0)));
        assert_eq!(syn("1e-7"), Syn::Const(Const::Real(1e-7)));
        assert_eq!(syn("'AB'"), Syn::Const(Const::Bits(0x4142)));
        assert!(matches!(parse_syn("8#17"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("16#"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("1.5.2"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("1e40"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("+inf"), Err(SynError::Malformed(_))));
    }

    #[test]
    fn pointers() {
        assert_eq!(
            syn("&VB100"),
            Syn::AddressOf {
                area: Area::V,
                n: 100
            }
        );
        assert_eq!(
            syn("&T37"),
            Syn::AddressOf {
                area: Area::TimerValue,
                n: 37
            }
        );
        assert_eq!(
            syn("*VD4"),
            Syn::Indirect {
                area: Area::V,
                n: 4
            }
        );
        assert_eq!(
            syn("*AC1"),
            Syn::Indirect {
                area: Area::AC,
                n: 1
            }
        );
        assert!(matches!(parse_syn("&VW100"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("*VW4"), Err(SynError::Malformed(_))));
    }

    #[test]
    fn malformed_and_symbols() {
        assert!(matches!(parse_syn("V10.8"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("I3"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("VB10X"), Err(SynError::Malformed(_))));
        assert_eq!(parse_syn("Motor"), Err(SynError::NotAddress));
        assert_eq!(parse_syn("启动"), Err(SynError::NotAddress));
    }
}
