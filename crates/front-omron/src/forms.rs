//! The instruction and operand forms of Omron text, as the fuzzer's coverage counts them:
//! [`forms`] reads a text with the front end's own lexer and operand syntax and names, per
//! instruction, the mnemonic as written with its options (`!@LD`, `LD>=S`, `TIMX`) and the form
//! of each operand (`W bit`, `T PV`, `#hex`, `,IR+` …); [`program_forms`] names the forms of
//! a whole program (its units, regions inside regions, backward jumps, the options it is
//! compiled with). [`mnemonic_forms`], [`OPERAND_FORMS`] and [`PROGRAM_FORMS`] list every form
//! the front end accepts, so a coverage report can say what was never generated.

use crate::lexer::{Line, lex_line};
use crate::mnemonics::{
    self, COMPARE_JOINS, COMPARE_SUFFIXES, Flow, Group, Mnemonic, RELATIONS, TABLE,
};
use crate::operand::{ConstForm, Syn, parse_syn};
use crate::{Options, TcMode};
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

/// Every form of a whole program [`program_forms`] names.
pub const PROGRAM_FORMS: &[&str] = &[
    "$TASK CYCLIC",
    "$TASK CYCLIC STANDBY",
    "$TASK UNASSIGNED",
    "$FB",
    "several tasks",
    "STEP in IL",
    "BPRG in a step area",
    "backward jump",
    "tc_mode binary",
    "allow_backward_jumps",
];

/// The forms of every instruction line of `text` (lines the front end would not lower, after
/// END, count too: they are lexed all the same); directives are not instructions.
pub fn forms(text: &str) -> Vec<Form> {
    text.split('\n')
        .filter_map(|raw| lex_line(raw, 1))
        .filter(|l| !l.mnemonic.starts_with('$'))
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
                        Flow::Jmp
                            | Flow::Cjp
                            | Flow::Cjpn
                            | Flow::Jme
                            | Flow::Sbs
                            | Flow::Sbn
                            | Flow::Bprg
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

/// The forms of a whole program (names from [`PROGRAM_FORMS`]), each once: its directives,
/// whether several tasks run, a step area inside IL–ILC, a block program inside a step area, a
/// jump back to a JME before it, and the `options` it is compiled with.
pub fn program_forms(text: &str, options: Options) -> Vec<&'static str> {
    let mut out = Vec::new();
    let mut add = |f: &'static str| {
        if !out.contains(&f) {
            out.push(f);
        }
    };
    let (mut tasks, mut instructions_before) = (0, false);
    let (mut il, mut step) = (false, false);
    let mut jmes: Vec<u32> = Vec::new();
    for l in text.split('\n').filter_map(|raw| lex_line(raw, 1)) {
        if l.mnemonic.starts_with('$') {
            jmes.clear();
            (il, step) = (false, false);
            if let Some(f) = directive_form(&l) {
                tasks += usize::from(f == "$TASK CYCLIC");
                add(f);
            }
            continue;
        }
        if tasks == 0 && !instructions_before {
            // The text before the first directive is task 0.
            instructions_before = true;
            tasks += 1;
        }
        let number = l.operands.first().and_then(|t| number(&t.text));
        match (l.mnemonic.as_str(), l.operands.is_empty()) {
            ("IL", _) => il = true,
            ("ILC", _) => il = false,
            ("STEP", false) => {
                step = true;
                if il {
                    add("STEP in IL");
                }
            }
            ("STEP", true) => step = false,
            ("BPRG", _) if step => add("BPRG in a step area"),
            ("JME", _) => jmes.extend(number),
            ("JMP" | "CJP" | "CJPN", _) if number.is_some_and(|n| jmes.contains(&n)) => {
                add("backward jump");
            }
            ("SBN" | "RET" | "END", _) => jmes.clear(),
            _ => {}
        }
    }
    if tasks > 1 {
        add("several tasks");
    }
    if options.tc_mode == TcMode::Binary {
        add("tc_mode binary");
    }
    if options.allow_backward_jumps {
        add("allow_backward_jumps");
    }
    out
}

/// The form of a directive line.
fn directive_form(l: &Line) -> Option<&'static str> {
    let words: Vec<String> = l
        .operands
        .iter()
        .map(|t| t.text.to_ascii_uppercase())
        .collect();
    let words: Vec<&str> = words.iter().map(String::as_str).collect();
    match (l.mnemonic.as_str(), words.as_slice()) {
        ("$TASK", ["CYCLIC", _]) => Some("$TASK CYCLIC"),
        ("$TASK", ["CYCLIC", _, "STANDBY"]) => Some("$TASK CYCLIC STANDBY"),
        ("$TASK", ["UNASSIGNED"]) => Some("$TASK UNASSIGNED"),
        ("$FB", [_]) => Some("$FB"),
        _ => None,
    }
}

/// A jump number as written (`5`, `&5`, `#0005`).
fn number(text: &str) -> Option<u32> {
    match parse_syn(text).ok()? {
        Syn::Const(v, _) => u32::try_from(v).ok(),
        Syn::Word { word, .. } => Some(word),
        _ => None,
    }
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
    fn program_forms_name_units_regions_and_options() {
        let text = "LD 0.00\nOUT W0.00\nEND(001)\n$task cyclic 3\nLD 0.01\nIL(002)\nLD P_On\nSNXT W1.00\nSTEP W1.00\nLD 0.02\nBPRG(096) 1\nBEND(801)\nSTEP\nILC(003)\nJME(005) &2\nLD 0.03\nCJP(510) #0002\nEND(001)\n$TASK CYCLIC 4 STANDBY\nEND(001)\n$FB f\n";
        let binary = Options {
            tc_mode: TcMode::Binary,
            ..Options::default()
        };
        let mut got = program_forms(text, binary);
        got.sort_unstable();
        let mut want = vec![
            "$TASK CYCLIC",
            "$TASK CYCLIC STANDBY",
            "$FB",
            "several tasks",
            "STEP in IL",
            "BPRG in a step area",
            "backward jump",
            "tc_mode binary",
        ];
        want.sort_unstable();
        assert_eq!(got, want);
        assert!(got.iter().all(|f| PROGRAM_FORMS.contains(f)));
        // One task, a forward jump: nothing.
        let plain = program_forms(
            "LD 0.00\nJMP(004) 1\nJME(005) 1\nEND(001)\n",
            Options::default(),
        );
        assert!(plain.is_empty(), "{plain:?}");
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
