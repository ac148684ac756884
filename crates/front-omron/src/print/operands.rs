//! Operands in Omron spelling for the printer: bits and words of every area, constants, the
//! indirect forms of §1.7 and MOVR's effective addresses.

use crate::address::print_address;
use crate::operand::area_prefix;
use stljit_core::Area;
use stljit_core::ir::{Address, BitLoc, IndexOffset, IndexStep, OmronRef, Operand};
use stljit_core::omron::{EA_MAP, EaRegion, effective_address};
use stljit_core::{CpuProfile, Width};

type Res<T> = Result<T, String>;

pub(super) fn tr(bit: BitLoc) -> String {
    format!("TR{}", bit.byte * 8 + u32::from(bit.bit))
}

/// A bit operand in Omron spelling; an error for locations no operand names.
pub(super) fn bit_text(bit: BitLoc) -> Res<String> {
    if bit.area == Area::Tr {
        return Err("a TR bit outside OUT/LD".into());
    }
    named(print_address(&Address::Bit(bit)))
}

fn named(text: String) -> Res<String> {
    if text.starts_with('?') {
        Err(format!("{text} has no Omron operand"))
    } else {
        Ok(text)
    }
}

/// A word operand of `words` words: a location (its first word), a constant (`#` with 4 or 8
/// digits), or an indirect form.
pub(super) fn word(o: Operand, words: u32) -> Res<String> {
    match o {
        Operand::Mem(loc) if loc.area == Area::DataReg => {
            if words != 1 {
                return Err("a data register as a multi-word operand".into());
            }
            Ok(format!("DR{}", loc.offset / 2))
        }
        Operand::Mem(loc) => named(print_address(&Address::Value {
            loc,
            width: Width::Word,
        })),
        Operand::Const(v) if words == 1 => {
            if v > 0xFFFF {
                return Err(format!("constant {v:#x} does not fit one word"));
            }
            Ok(format!("#{v:04X}"))
        }
        Operand::Const(v) => Ok(format!("#{v:08X}")),
        Operand::Omron(r) => Ok(indirect(r)),
        other => Err(format!("{other:?} is not an Omron operand")),
    }
}

/// `@Dn`, `*Dn` and the index-register forms of §1.7.
fn indirect(r: OmronRef) -> String {
    match r {
        OmronRef::DmBinary(n) => format!("@D{n}"),
        OmronRef::DmBcd(n) => format!("*D{n}"),
        OmronRef::Index { ir, offset, step } => {
            let (pre, post) = match step {
                IndexStep::None => ("", ""),
                IndexStep::PostInc1 => ("", "+"),
                IndexStep::PostInc2 => ("", "++"),
                IndexStep::PreDec1 => ("-", ""),
                IndexStep::PreDec2 => ("--", ""),
            };
            let off = match offset {
                IndexOffset::Const(0) => String::new(),
                IndexOffset::Const(c) => format!("{c:+}"),
                IndexOffset::Dr(m) => format!("DR{m}"),
            };
            format!("{off},{pre}IR{ir}{post}")
        }
    }
}

/// The operand whose effective address (MOVR's source) is `ea`: a word, a timer or counter
/// PV, or a bit (`16 · word address + bit`).
pub(super) fn ea_operand(profile: &CpuProfile, ea: u32) -> Option<String> {
    let bit_base = 16 * EA_MAP.iter().map(|r| r.1).min()?;
    let (word_ea, bit) = if ea >= bit_base {
        (ea / 16, Some(ea % 16))
    } else {
        (ea, None)
    };
    let &(region, base) = EA_MAP
        .iter()
        .filter(|r| r.1 <= word_ea)
        .max_by_key(|r| r.1)?;
    let word = word_ea - base;
    if effective_address(profile, region, word) != Some(word_ea) {
        return None;
    }
    match (region, bit) {
        (EaRegion::Word(a), None) => Some(format!("{}{word}", area_prefix(a))),
        (EaRegion::Word(a), Some(b)) => Some(format!("{}{word}.{b:02}", area_prefix(a))),
        (EaRegion::TimerPv, None) => Some(format!("T{word:04}")),
        (EaRegion::CounterPv, None) => Some(format!("C{word:04}")),
        _ => None,
    }
}
