//! Operand syntax of the Omron dialect (omron-cp.md §1.2), before it meets a profile: word and
//! bit addresses of the CIO/W/H/A/D areas, timer and counter numbers, TR bits, the `P_…`
//! symbols ([`FLAGS`], the one list of their names), constants, and the forms that are
//! recognised but not supported yet (indirect and index-register addressing, TK, strings).

use stljit_core::ir::{IndexOffset, IndexStep, OmronRef};
use stljit_core::omron::{SystemBit, WordArea};

/// The `P_…` symbols of the condition flags, constants and clock pulses (§1.8), as
/// CX-Programmer spells them. `P_First_Cycle` is an A-area bit ([`FIRST_CYCLE_NAME`]).
pub(crate) const FLAGS: [(&str, SystemBit); 19] = [
    ("P_ER", SystemBit::Er),
    ("P_CY", SystemBit::Cy),
    ("P_GT", SystemBit::Gt),
    ("P_EQ", SystemBit::Eq),
    ("P_LT", SystemBit::Lt),
    ("P_N", SystemBit::N),
    ("P_OF", SystemBit::Of),
    ("P_UF", SystemBit::Uf),
    ("P_GE", SystemBit::Ge),
    ("P_NE", SystemBit::Ne),
    ("P_LE", SystemBit::Le),
    ("P_AER", SystemBit::Aer),
    ("P_On", SystemBit::On),
    ("P_Off", SystemBit::Off),
    ("P_0_02s", SystemBit::Pulse20ms),
    ("P_0_1s", SystemBit::Pulse100ms),
    ("P_0_2s", SystemBit::Pulse200ms),
    ("P_1s", SystemBit::Pulse1s),
    ("P_1min", SystemBit::Pulse1min),
];

/// The symbol of A200.11 (`core::omron::FIRST_CYCLE`).
pub(crate) const FIRST_CYCLE_NAME: &str = "P_First_Cycle";

/// The prefix letter of a word area (`""` for CIO).
pub(crate) fn area_prefix(area: WordArea) -> &'static str {
    match area {
        WordArea::Cio => "",
        WordArea::Work => "W",
        WordArea::Holding => "H",
        WordArea::Aux => "A",
        WordArea::Dm => "D",
    }
}

/// The area's name in messages.
pub(crate) fn area_name(area: WordArea) -> &'static str {
    match area {
        WordArea::Cio => "CIO",
        WordArea::Work => "W",
        WordArea::Holding => "H",
        WordArea::Aux => "A",
        WordArea::Dm => "D",
    }
}

/// How a constant was written; the form decides its range (§1.6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ConstForm {
    /// `#hex`, with its number of digits.
    Hex(usize),
    /// `&dec`.
    Unsigned,
    /// `+dec` / `-dec`.
    Signed,
}

/// One operand's syntax.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Syn {
    /// A word: `100`, `CIO 10`, `W3`, `D200`.
    Word {
        /// The area.
        area: WordArea,
        /// Word number.
        word: u32,
    },
    /// A bit: `0.00`, `W3.15`, `A200.11`.
    Bit {
        /// The area.
        area: WordArea,
        /// Word number.
        word: u32,
        /// Bit number as written (valid: 0..=15).
        bit: u32,
    },
    /// `T0005`, `TIM0005`: completion flag or PV by context.
    Timer(u32),
    /// `C0002`, `CNT0002`.
    Counter(u32),
    /// `TR0` … `TR15`.
    Tr(u32),
    /// A `P_…` system bit.
    Flag(SystemBit),
    /// `P_First_Cycle` (A200.11).
    FirstCycle,
    /// A constant: its value (negative only for the signed form) and form.
    Const(i64, ConstForm),
    /// An indirect word operand: `@Dn`, `*Dn`, `c,IRn`, `DRm,IRn`, `,IRn+`, `,--IRn` (§1.7).
    Indirect(OmronRef),
    /// `IRn`: an index register (MOVR's destination).
    IndexReg(u32),
    /// `DRn`: a data register, a signed word.
    DataReg(u32),
    /// A form recognised but not supported yet: what it is.
    Unsupported(&'static str),
}

/// Why a text is not an operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SynError {
    /// It looks like an address or constant but is malformed (the reason).
    Malformed(&'static str),
    /// It is not address syntax at all (perhaps a symbol).
    NotAddress,
}

fn digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

/// A decimal number; numbers too large for `u32` saturate (they are out of every range).
fn dec(s: &str) -> u32 {
    s.parse().unwrap_or(u32::MAX)
}

/// `word` or `word.bb` of `area`.
fn word_or_bit(area: WordArea, s: &str) -> Result<Syn, SynError> {
    match s.split_once('.') {
        None if digits(s) => Ok(Syn::Word { area, word: dec(s) }),
        Some((w, b)) if digits(w) && digits(b) => {
            if b.len() != 2 {
                return Err(SynError::Malformed("a bit number is two digits, 00 to 15"));
            }
            Ok(Syn::Bit {
                area,
                word: dec(w),
                bit: dec(b),
            })
        }
        _ => Err(SynError::Malformed("expected a word number or word.bit")),
    }
}

/// A constant's value: `#hex`, `&dec`, `+dec`, `-dec`.
fn constant(t: &str) -> Option<Result<Syn, SynError>> {
    let bad = |m| Some(Err(SynError::Malformed(m)));
    if let Some(h) = t.strip_prefix('#') {
        if h.is_empty() || h.len() > 8 || !h.bytes().all(|b| b.is_ascii_hexdigit()) {
            return bad("`#` takes 1 to 8 hexadecimal digits");
        }
        let v = i64::from_str_radix(h, 16).unwrap_or(0);
        return Some(Ok(Syn::Const(v, ConstForm::Hex(h.len()))));
    }
    let (body, form, neg) = if let Some(d) = t.strip_prefix('&') {
        (d, ConstForm::Unsigned, false)
    } else if let Some(d) = t.strip_prefix('+') {
        (d, ConstForm::Signed, false)
    } else if let Some(d) = t.strip_prefix('-') {
        (d, ConstForm::Signed, true)
    } else {
        return None;
    };
    if !digits(body) || body.len() > 11 {
        return bad("expected decimal digits after `&`, `+` or `-`");
    }
    let v: i64 = body.parse().unwrap_or(i64::MAX);
    Some(Ok(Syn::Const(if neg { -v } else { v }, form)))
}

/// A DM word number of an indirect operand (the range is checked against the profile later).
fn small(n: &str) -> Result<u16, SynError> {
    u16::try_from(dec(n)).map_err(|_| SynError::Malformed("no such DM word"))
}

/// The register number of `IRn` / `DRn`: 0 to 15.
fn register(n: &str) -> Result<u8, SynError> {
    match n.parse::<u8>() {
        Ok(r) if r <= 15 && digits(n) => Ok(r),
        _ => Err(SynError::Malformed(
            "index and data registers are numbered 0 to 15",
        )),
    }
}

/// `offset,register` (upper case): the index-register forms of §1.7.
fn indexed(offset: &str, reg: &str) -> Result<Syn, SynError> {
    let (step_pre, rest) = if let Some(r) = reg.strip_prefix("--") {
        (Some(IndexStep::PreDec2), r)
    } else if let Some(r) = reg.strip_prefix('-') {
        (Some(IndexStep::PreDec1), r)
    } else {
        (None, reg)
    };
    let rest = rest.strip_prefix("IR").ok_or(SynError::Malformed(
        "expected `,IRn` (an index register) after the comma",
    ))?;
    let (n, step_post) = if let Some(n) = rest.strip_suffix("++") {
        (n, Some(IndexStep::PostInc2))
    } else if let Some(n) = rest.strip_suffix('+') {
        (n, Some(IndexStep::PostInc1))
    } else {
        (rest, None)
    };
    let step = match (step_pre, step_post) {
        (Some(_), Some(_)) => {
            return Err(SynError::Malformed(
                "an index register is either incremented after or decremented before, not both",
            ));
        }
        (Some(s), None) | (None, Some(s)) => s,
        (None, None) => IndexStep::None,
    };
    let ir = register(n)?;
    let offset = if offset.is_empty() {
        IndexOffset::Const(0)
    } else if let Some(m) = offset.strip_prefix("DR") {
        if step != IndexStep::None {
            return Err(SynError::Malformed(
                "a DR offset takes no increment or decrement",
            ));
        }
        IndexOffset::Dr(register(m)?)
    } else {
        let body = offset.strip_prefix(['+', '-']).unwrap_or(offset);
        if !digits(body) || step != IndexStep::None {
            return Err(SynError::Malformed(
                "an IR offset is a decimal constant −2048…+2047 (no increment or decrement)",
            ));
        }
        match offset.parse::<i16>() {
            Ok(c) if (-2048..=2047).contains(&c) => IndexOffset::Const(c),
            _ => {
                return Err(SynError::Malformed(
                    "an IR offset is a decimal constant −2048…+2047",
                ));
            }
        }
    };
    Ok(Syn::Indirect(OmronRef::Index { ir, offset, step }))
}

/// Parses an operand's text (case-insensitive).
pub(crate) fn parse_syn(text: &str) -> Result<Syn, SynError> {
    let t = text.trim();
    let up = t.to_ascii_uppercase();
    if t.starts_with('\'') {
        return Ok(Syn::Unsupported("string constants"));
    }
    if let Some((offset, reg)) = up.rsplit_once(',') {
        return indexed(offset, reg);
    }
    if let Some(c) = constant(t) {
        return c;
    }
    if let Some(n) = up.strip_prefix("@D").filter(|n| digits(n)) {
        return Ok(Syn::Indirect(OmronRef::DmBinary(small(n)?)));
    }
    if let Some(n) = up.strip_prefix("*D").filter(|n| digits(n)) {
        return Ok(Syn::Indirect(OmronRef::DmBcd(small(n)?)));
    }
    if let Some(n) = up.strip_prefix("IR").filter(|n| digits(n)) {
        return Ok(Syn::IndexReg(dec(n)));
    }
    if let Some(n) = up.strip_prefix("DR").filter(|n| digits(n)) {
        return Ok(Syn::DataReg(dec(n)));
    }
    if up.strip_prefix("TK").is_some_and(digits) {
        return Ok(Syn::Unsupported("task flags (TKn)"));
    }
    if let Some(n) = up.strip_prefix("TR").filter(|n| digits(n)) {
        return Ok(Syn::Tr(dec(n)));
    }
    if up.starts_with("P_") {
        if up == FIRST_CYCLE_NAME.to_ascii_uppercase() {
            return Ok(Syn::FirstCycle);
        }
        return FLAGS
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(t))
            .map(|&(_, f)| Syn::Flag(f))
            .ok_or(SynError::NotAddress);
    }
    if let Some(rest) = up.strip_prefix("CIO") {
        return word_or_bit(WordArea::Cio, rest).map_err(|_| {
            SynError::Malformed("`CIO` must be followed by a CIO word or bit address")
        });
    }
    for (prefix, make) in [
        ("TIM", Syn::Timer as fn(u32) -> Syn),
        ("CNT", Syn::Counter),
        ("T", Syn::Timer),
        ("C", Syn::Counter),
    ] {
        if let Some(n) = up.strip_prefix(prefix).filter(|n| digits(n)) {
            return Ok(make(dec(n)));
        }
    }
    for (prefix, area) in [
        ('W', WordArea::Work),
        ('H', WordArea::Holding),
        ('A', WordArea::Aux),
        ('D', WordArea::Dm),
    ] {
        if let Some(rest) = up.strip_prefix(prefix)
            && rest.starts_with(|c: char| c.is_ascii_digit())
        {
            return word_or_bit(area, rest);
        }
    }
    if up
        .strip_prefix('E')
        .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
    {
        return Err(SynError::Malformed("the CP series has no EM area"));
    }
    if up.starts_with(|c: char| c.is_ascii_digit()) {
        return word_or_bit(WordArea::Cio, &up);
    }
    Err(SynError::NotAddress)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_of_every_area() {
        let bit = |area, word, bit| Ok(Syn::Bit { area, word, bit });
        assert_eq!(parse_syn("0.00"), bit(WordArea::Cio, 0, 0));
        assert_eq!(parse_syn("CIO0100.01"), bit(WordArea::Cio, 100, 1));
        assert_eq!(parse_syn("w3.15"), bit(WordArea::Work, 3, 15));
        assert_eq!(parse_syn("A200.11"), bit(WordArea::Aux, 200, 11));
        assert_eq!(
            parse_syn("D200"),
            Ok(Syn::Word {
                area: WordArea::Dm,
                word: 200
            })
        );
        assert_eq!(
            parse_syn("10"),
            Ok(Syn::Word {
                area: WordArea::Cio,
                word: 10
            })
        );
        assert_eq!(parse_syn("T0005"), Ok(Syn::Timer(5)));
        assert_eq!(parse_syn("CNT0002"), Ok(Syn::Counter(2)));
        assert_eq!(parse_syn("TR3"), Ok(Syn::Tr(3)));
        assert_eq!(parse_syn("p_eq"), Ok(Syn::Flag(SystemBit::Eq)));
        assert_eq!(parse_syn("P_First_Cycle"), Ok(Syn::FirstCycle));
        assert!(matches!(parse_syn("0.1"), Err(SynError::Malformed(_))));
        assert!(matches!(parse_syn("CIOD0"), Err(SynError::Malformed(_))));
        // The CP series has no EM (§1.1): `E…` operands are an error, not a symbol.
        assert!(matches!(parse_syn("E0_100"), Err(SynError::Malformed(_))));
        assert_eq!(parse_syn("Start_PB"), Err(SynError::NotAddress));
    }

    #[test]
    fn constants_and_unsupported_forms() {
        assert_eq!(
            parse_syn("#12A4"),
            Ok(Syn::Const(0x12A4, ConstForm::Hex(4)))
        );
        assert_eq!(
            parse_syn("&70000"),
            Ok(Syn::Const(70000, ConstForm::Unsigned))
        );
        assert_eq!(parse_syn("-5"), Ok(Syn::Const(-5, ConstForm::Signed)));
        assert!(matches!(parse_syn("#"), Err(SynError::Malformed(_))));
        for t in ["TK0", "'AB'"] {
            assert!(matches!(parse_syn(t), Ok(Syn::Unsupported(_))), "{t}");
        }
    }

    #[test]
    fn indirect_and_index_register_forms() {
        use IndexStep::*;
        let ix = |ir, offset, step| Ok(Syn::Indirect(OmronRef::Index { ir, offset, step }));
        // Spec §1.7 and the seed's examples.
        assert_eq!(parse_syn("@D20"), Ok(Syn::Indirect(OmronRef::DmBinary(20))));
        assert_eq!(parse_syn("*D21"), Ok(Syn::Indirect(OmronRef::DmBcd(21))));
        assert_eq!(parse_syn(",IR0"), ix(0, IndexOffset::Const(0), None));
        assert_eq!(parse_syn("+5,IR0"), ix(0, IndexOffset::Const(5), None));
        assert_eq!(
            parse_syn("-2048,IR15"),
            ix(15, IndexOffset::Const(-2048), None)
        );
        assert_eq!(parse_syn("DR0,IR0"), ix(0, IndexOffset::Dr(0), None));
        assert_eq!(parse_syn(",IR0++"), ix(0, IndexOffset::Const(0), PostInc2));
        assert_eq!(parse_syn(",ir1+"), ix(1, IndexOffset::Const(0), PostInc1));
        assert_eq!(parse_syn(",--IR0"), ix(0, IndexOffset::Const(0), PreDec2));
        assert_eq!(parse_syn(",-IR3"), ix(3, IndexOffset::Const(0), PreDec1));
        assert_eq!(parse_syn("IR2"), Ok(Syn::IndexReg(2)));
        assert_eq!(parse_syn("DR1"), Ok(Syn::DataReg(1)));
        for bad in ["+2048,IR0", ",IR16", ",--IR0+", "5,D0", "DR0,IR0+"] {
            assert!(
                matches!(parse_syn(bad), Err(SynError::Malformed(_))),
                "{bad}"
            );
        }
    }
}
