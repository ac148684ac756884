//! The instruction and operand forms of Omron text, as the fuzzer's coverage counts them:
//! [`forms`] reads a text with the front end's own lexer and operand syntax and names, per
//! instruction, the mnemonic as written with its options (`!@LD`, `LD>=S`, `TIMX`) and the form
//! of each operand (`W bit`, `T PV`, `#hex`, `,IR+` …). [`mnemonic_forms`] and
//! [`OPERAND_FORMS`] list every form the front end accepts, so a coverage report can say what
//! was never generated.

use crate::lexer::lex_line;
use crate::mnemonics::{
    self, COMPARE_JOINS, COMPARE_SUFFIXES, Flow, Group, Mnemonic, RELATIONS, TABLE,
};
use crate::operand::{ConstForm, Syn, parse_syn};
use stljit_core::ir::{IndexOffset, IndexStep, OmronArith, OmronRef};
use stljit_core::omron::{SystemBit, WordArea, word_loc};
use stljit_core::{Area, ProfileId};

/// One instruction of a text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Form {
    /// The mnemonic with its options as written, upper case, without the function code.
    pub mnemonic: String,
    /// The form of each operand (names from [`OPERAND_FORMS`]); spelling variants such as a
    /// `CIO` prefix add a second entry.
    pub operands: Vec<&'static str>,
}

/// Every operand form [`forms`] names.
pub const OPERAND_FORMS: &[&str] = &[
    "CIO in bit",
    "CIO out bit",
    "CIO bit",
    "W bit",
    "H bit",
    "A bit",
    "D bit",
    "T flag",
    "C flag",
    "TR",
    "condition flag",
    "P_On/P_Off",
    "clock pulse",
    "P_First_Cycle",
    "CIO in word",
    "CIO out word",
    "CIO word",
    "W word",
    "H word",
    "A word",
    "D word",
    "T PV",
    "C PV",
    "DR",
    "IR",
    "#hex",
    "&dec",
    "+-dec",
    "@D",
    "*D",
    ",IR",
    "c,IR",
    "DR,IR",
    ",IR+",
    ",IR++",
    ",-IR",
    ",--IR",
    "number",
    "CIO prefix",
    "TIM/CNT prefix",
];

/// The forms of every instruction line of `text` (lines the front end would not lower, after
/// END, count too: they are lexed all the same).
pub fn forms(text: &str) -> Vec<Form> {
    text.split('\n')
        .filter_map(|raw| lex_line(raw, 1))
        .map(|l| {
            let group = mnemonics::lookup(&l.mnemonic).map(|m| m.group);
            let operands = l
                .operands
                .iter()
                .enumerate()
                .flat_map(|(i, t)| operand_forms(&t.text, group, i))
                .collect();
            Form {
                mnemonic: format!("{}{}", l.options.text(), l.mnemonic),
                operands,
            }
        })
        .collect()
}

/// Whether operand `i` of an instruction of `group` is a number (timer, counter, jump or
/// subroutine number) rather than an address.
fn is_number(group: Option<Group>, i: usize) -> bool {
    i == 0
        && matches!(
            group,
            Some(
                Group::Timer(_)
                    | Group::Counter(_)
                    | Group::Control(
                        Flow::Jmp | Flow::Cjp | Flow::Cjpn | Flow::Jme | Flow::Sbs | Flow::Sbn
                    )
            )
        )
}

/// Whether a timer or counter operand of `group` names the completion flag (else the PV).
fn bit_context(group: Option<Group>) -> bool {
    matches!(
        group,
        Some(
            Group::Contact(..)
                | Group::Out(_)
                | Group::SetReset(_)
                | Group::Keep
                | Group::Differentiate(_)
        ) | None
    )
}

fn operand_forms(text: &str, group: Option<Group>, i: usize) -> Vec<&'static str> {
    let up = text.to_ascii_uppercase();
    let mut out = Vec::new();
    if up.starts_with("CIO") {
        out.push("CIO prefix");
    }
    if up.starts_with("TIM") || up.starts_with("CNT") {
        out.push("TIM/CNT prefix");
    }
    if is_number(group, i) {
        out.push("number");
        return out;
    }
    let Ok(syn) = parse_syn(text) else {
        return out;
    };
    let cp1h = ProfileId::Cp1h.profile();
    let routed = |area: WordArea, word: u32| word_loc(cp1h, area, word).map(|l| l.area);
    let form = match syn {
        Syn::Bit { area, word, .. } => match (area, routed(area, word)) {
            (WordArea::Cio, Some(Area::I)) => "CIO in bit",
            (WordArea::Cio, Some(Area::Q)) => "CIO out bit",
            (WordArea::Cio, _) => "CIO bit",
            (WordArea::Work, _) => "W bit",
            (WordArea::Holding, _) => "H bit",
            (WordArea::Aux, _) => "A bit",
            (WordArea::Dm, _) => "D bit",
        },
        Syn::Word { area, word } => match (area, routed(area, word)) {
            (WordArea::Cio, Some(Area::I)) => "CIO in word",
            (WordArea::Cio, Some(Area::Q)) => "CIO out word",
            (WordArea::Cio, _) => "CIO word",
            (WordArea::Work, _) => "W word",
            (WordArea::Holding, _) => "H word",
            (WordArea::Aux, _) => "A word",
            (WordArea::Dm, _) => "D word",
        },
        Syn::Timer(_) if bit_context(group) => "T flag",
        Syn::Timer(_) => "T PV",
        Syn::Counter(_) if bit_context(group) => "C flag",
        Syn::Counter(_) => "C PV",
        Syn::Tr(_) => "TR",
        Syn::Flag(SystemBit::On | SystemBit::Off) => "P_On/P_Off",
        Syn::Flag(f) if f.index() < SystemBit::CONDITION_FLAGS.count_ones() => "condition flag",
        Syn::Flag(_) => "clock pulse",
        Syn::FirstCycle => "P_First_Cycle",
        Syn::Const(_, ConstForm::Hex(_)) => "#hex",
        Syn::Const(_, ConstForm::Unsigned) => "&dec",
        Syn::Const(_, ConstForm::Signed) => "+-dec",
        Syn::Indirect(OmronRef::DmBinary(_)) => "@D",
        Syn::Indirect(OmronRef::DmBcd(_)) => "*D",
        Syn::Indirect(OmronRef::Index { offset, step, .. }) => match (offset, step) {
            (IndexOffset::Const(0), IndexStep::None) => ",IR",
            (IndexOffset::Const(_), IndexStep::None) => "c,IR",
            (IndexOffset::Dr(_), _) => "DR,IR",
            (_, IndexStep::PostInc1) => ",IR+",
            (_, IndexStep::PostInc2) => ",IR++",
            (_, IndexStep::PreDec1) => ",-IR",
            (_, IndexStep::PreDec2) => ",--IR",
        },
        Syn::IndexReg(_) => "IR",
        Syn::DataReg(_) => "DR",
        Syn::Unsupported(_) => return out,
    };
    out.push(form);
    out
}

/// The options an instruction may be written with, one at a time: none, `@`, `%`, `!`.
fn option_forms(m: &Mnemonic) -> impl Iterator<Item = String> + '_ {
    [
        ("", true),
        ("@", m.allowed.up),
        ("%", m.allowed.down),
        ("!", m.allowed.immediate),
    ]
    .into_iter()
    .filter(|o| o.1)
    .map(move |(o, _)| format!("{o}{}", m.name))
}

/// Every instruction form the front end lowers, as [`Form::mnemonic`] spells it: each
/// [`TABLE`] entry and arithmetic instruction alone and with each option it accepts, and every
/// comparison contact (join × relation × suffix) alone and with `!`.
pub fn mnemonic_forms() -> Vec<String> {
    let mut out: Vec<String> = TABLE.iter().flat_map(option_forms).collect();
    for a in OmronArith::ALL {
        if let Some(m) = mnemonics::lookup(a.mnemonic()) {
            out.extend(option_forms(&m).collect::<Vec<_>>());
        }
    }
    for (join, _) in COMPARE_JOINS {
        for (rel, ..) in RELATIONS {
            for (suffix, ..) in COMPARE_SUFFIXES {
                let name = format!("{join}{rel}{suffix}");
                if mnemonics::COMPARE_OPTIONS.immediate {
                    out.push(format!("!{name}"));
                }
                out.push(name);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms_name_mnemonics_options_and_operands() {
        let f = forms(
            "!@LD CIO 0.01 ; c\nTIMX(550) T0003 &10\nLD>=S(327) D0 -5\nMOV(021) #0001 ,IR0++\n\nLD TIM0003\n",
        );
        let got: Vec<(&str, Vec<&str>)> = f
            .iter()
            .map(|f| (f.mnemonic.as_str(), f.operands.clone()))
            .collect();
        assert_eq!(
            got,
            [
                ("!@LD", vec!["CIO prefix", "CIO in bit"]),
                ("TIMX", vec!["number", "&dec"]),
                ("LD>=S", vec!["D word", "+-dec"]),
                ("MOV", vec!["#hex", ",IR++"]),
                ("LD", vec!["TIM/CNT prefix", "T flag"]),
            ]
        );
    }

    #[test]
    fn every_listed_form_is_one_the_front_end_accepts() {
        let all = mnemonic_forms();
        assert!(all.contains(&"%LD".to_owned()) && all.contains(&"!OUT NOT".to_owned()));
        assert!(all.contains(&"@+BCL".to_owned()) && all.contains(&"!OR<>SL".to_owned()));
        assert!(!all.contains(&"@OUT".to_owned()) && !all.contains(&"%MOV".to_owned()));
        // 28 arithmetic instructions with none/@/!, 72 comparison contacts with none/!.
        assert!(all.len() > 28 * 3 + 72 * 2, "{}", all.len());
        let unique: std::collections::HashSet<_> = all.iter().collect();
        assert_eq!(unique.len(), all.len());
    }
}
