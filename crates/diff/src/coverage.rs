//! Coverage counters: how often each mnemonic and each operand kind was generated, so that a
//! campaign shows what it exercised (and what it never reached). S7 programs are counted from
//! their IR (per STL mnemonic); Omron programs from their generated text, per instruction form
//! as written (`!@LD`, `LD>=S`, `TIMX`), per operand form (`W bit`, `T PV`, `,IR+` …) and per
//! program form (`$TASK CYCLIC`, `STEP in IL`, `backward jump`, `tc_mode binary` …), which the
//! Omron front end names and lists (`stljit_front_omron::forms`).

use std::collections::BTreeMap;
use stljit_core::ir::{
    BoxOp, ClockOp, CmpType, Contact, Conversion, ExtBox, FindRel, IntOp, NumType, Op, Operand,
    Program, StackForm, StrArg,
};
use stljit_core::{Area, Width};
use stljit_front_s7::spelling::{area_prefix, counter_mnemonic, timer_mnemonic};

/// Counts per mnemonic (`LD`, `LDW>=`, `MOVD`, `TONR`, ...) and per operand kind (`V`, `*VD`, `&`,
/// `const`, `"str"` for a constant string, ...).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Coverage {
    /// Generated instructions per mnemonic.
    pub mnemonics: BTreeMap<&'static str, u64>,
    /// Generated operands per kind.
    pub operands: BTreeMap<String, u64>,
    /// Generated Omron instructions per form (mnemonic with its options as written).
    pub omron_mnemonics: BTreeMap<String, u64>,
    /// Generated Omron operands per form.
    pub omron_operands: BTreeMap<&'static str, u64>,
    /// Generated Omron programs per program form (units, regions, options).
    pub omron_programs: BTreeMap<&'static str, u64>,
}

impl Coverage {
    /// Counts every op of `program`.
    pub fn add_program(&mut self, program: &Program) {
        for pou in &program.pous {
            for op in &pou.ops {
                *self.mnemonics.entry(mnemonic(op)).or_default() += 1;
                for_each_operand(op, |o| {
                    *self.operands.entry(operand_kind(o)).or_default() += 1;
                });
                // A constant string is no operand (its bytes are in the op), so it is counted
                // here, as kind `"str"`.
                let strings = match op {
                    Op::Ext(b) => b.strings(),
                    Op::StrCompare(c) => vec![&c.lhs, &c.rhs],
                    _ => vec![],
                };
                for s in strings {
                    if let StrArg::Const(_) = s {
                        *self.operands.entry("\"str\"".into()).or_default() += 1;
                    }
                }
            }
        }
    }

    /// Counts every instruction and operand of an Omron program's text, and its program forms
    /// with the front-end `options` it is compiled with.
    pub fn add_omron_source(&mut self, text: &str, options: stljit_front_omron::Options) {
        for f in stljit_front_omron::forms::program_forms(text, options) {
            *self.omron_programs.entry(f).or_default() += 1;
        }
        for f in stljit_front_omron::forms::forms(text) {
            for o in &f.operands {
                *self.omron_operands.entry(o).or_default() += 1;
            }
            *self.omron_mnemonics.entry(f.mnemonic).or_default() += 1;
        }
    }

    /// Adds another coverage (from a worker thread).
    pub fn merge(&mut self, other: &Coverage) {
        for (k, v) in &other.mnemonics {
            *self.mnemonics.entry(k).or_default() += v;
        }
        for (k, v) in &other.operands {
            *self.operands.entry(k.clone()).or_default() += v;
        }
        for (k, v) in &other.omron_mnemonics {
            *self.omron_mnemonics.entry(k.clone()).or_default() += v;
        }
        for (k, v) in &other.omron_operands {
            *self.omron_operands.entry(k).or_default() += v;
        }
        for (k, v) in &other.omron_programs {
            *self.omron_programs.entry(k).or_default() += v;
        }
    }

    /// Omron instruction forms (`stljit_front_omron::forms::mnemonic_forms`), operand forms
    /// (`forms::OPERAND_FORMS`) and program forms (`forms::PROGRAM_FORMS`) never generated.
    pub fn missing_omron(&self) -> Vec<String> {
        let forms = stljit_front_omron::forms::mnemonic_forms()
            .into_iter()
            .filter(|m| !self.omron_mnemonics.contains_key(m));
        let operands = stljit_front_omron::forms::OPERAND_FORMS
            .iter()
            .filter(|o| !self.omron_operands.contains_key(*o))
            .map(|o| format!("operand {o}"));
        let programs = stljit_front_omron::forms::PROGRAM_FORMS
            .iter()
            .filter(|f| !self.omron_programs.contains_key(*f))
            .map(|f| format!("program {f}"));
        forms.chain(operands).chain(programs).collect()
    }

    /// Mnemonics of [`ALL_MNEMONICS`] never generated.
    pub fn missing(&self) -> Vec<&'static str> {
        ALL_MNEMONICS
            .iter()
            .copied()
            .filter(|m| !self.mnemonics.contains_key(m))
            .collect()
    }
}

/// Every mnemonic [`mnemonic`] can return (compare contacts count per type, not per relation).
pub const ALL_MNEMONICS: &[&str] = &[
    "LD", "LDN", "A", "AN", "O", "ON", "LDI", "LDNI", "AI", "ANI", "OI", "ONI", "LDB", "LDW",
    "LDD", "LDR", "AB", "AW", "AD", "AR", "OB", "OW", "OD", "OR", "NOT", "ALD", "OLD", "LPS",
    "LRD", "LPP", "LDS", "AENO", "EU", "ED", "=", "=I", "S", "R", "SI", "RI", "R T", "R C", "TON",
    "TONR", "TOF", "CTU", "CTD", "CTUD", "MOVB", "MOVW", "MOVD", "SWAP", "BMB", "BMW", "BMD",
    "FILL", "+I", "-I", "*I", "/I", "+D", "-D", "*D", "/D", "MUL", "DIV", "+R", "-R", "*R", "/R",
    "SQRT", "LN", "EXP", "SIN", "COS", "TAN", "INCB", "DECB", "INCW", "DECW", "INCD", "DECD",
    "ANDB", "ORB", "XORB", "ANDW", "ORW", "XORW", "ANDD", "ORD", "XORD", "INVB", "INVW", "INVD",
    "SLB", "SLW", "SLD", "SRB", "SRW", "SRD", "RLB", "RLW", "RLD", "RRB", "RRW", "RRD", "SHRB",
    "BTI", "ITB", "ITD", "DTI", "DTR", "ROUND", "TRUNC", "BCDI", "IBCD", "DECO", "ENCO", "SEG",
    "BIR", "BIW", "JMP", "LBL", "CALL", "CRET", "RET", "END", "MEND", "STOP", "WDR", "NOP", "FOR",
    "NEXT", "LSCR", "SCRT", "CSCRE", "SCRE", "ATCH", "DTCH", "ENI", "DISI", "CEVNT", "ATT", "FIFO",
    "LIFO", "FND=", "FND<>", "FND<", "FND>", "ATH", "HTA", "ITA", "DTA", "RTA", "ITS", "DTS",
    "RTS", "STI", "STD", "STR", "SLEN", "SCPY", "SCAT", "SSCPY", "SFND", "CFND", "TODR", "TODW",
    "TODRX", "TODWX", "PID", "LDS=", "LDS<>", "AS=", "AS<>", "OS=", "OS<>", "HDEF", "HSC", "PLS",
];

fn contact_mnemonic(prefix: usize, c: &Contact) -> &'static str {
    // prefix: 0 = LD, 1 = A, 2 = O.
    match c {
        Contact::Bit { negated, .. } => {
            ["LD", "LDN", "A", "AN", "O", "ON"][prefix * 2 + usize::from(*negated)]
        }
        Contact::ImmediateInput { negated, .. } => {
            ["LDI", "LDNI", "AI", "ANI", "OI", "ONI"][prefix * 2 + usize::from(*negated)]
        }
        Contact::Compare { ty, .. } => {
            let t = match ty {
                CmpType::Byte => 0,
                CmpType::Int => 1,
                CmpType::DInt => 2,
                CmpType::Real => 3,
            };
            [
                "LDB", "LDW", "LDD", "LDR", "AB", "AW", "AD", "AR", "OB", "OW", "OD", "OR",
            ][prefix * 4 + t]
        }
    }
}

fn by_width(w: Width, names: [&'static str; 3]) -> &'static str {
    match w {
        Width::Byte => names[0],
        Width::Word => names[1],
        Width::DWord => names[2],
    }
}

/// The STL mnemonic of an op (compare relations folded into the type, e.g. `LDW`).
pub fn mnemonic(op: &Op) -> &'static str {
    match op {
        Op::Load(c) => contact_mnemonic(0, c),
        Op::And(c) => contact_mnemonic(1, c),
        Op::Or(c) => contact_mnemonic(2, c),
        Op::Not => "NOT",
        Op::AndBlock => "ALD",
        Op::OrBlock => "OLD",
        Op::Dup => "LPS",
        Op::ReadSecond => "LRD",
        Op::Pop => "LPP",
        Op::Pick(_) => "LDS",
        Op::AndEno => "AENO",
        Op::Edge { falling, .. } => {
            if *falling {
                "ED"
            } else {
                "EU"
            }
        }
        Op::Assign { immediate, .. } => {
            if *immediate {
                "=I"
            } else {
                "="
            }
        }
        Op::SetRange {
            value, immediate, ..
        } => match (value, immediate) {
            (true, false) => "S",
            (false, false) => "R",
            (true, true) => "SI",
            (false, true) => "RI",
        },
        Op::ResetTimers { .. } => "R T",
        Op::ResetCounters { .. } => "R C",
        Op::Timer { kind, .. } => timer_mnemonic(*kind),
        Op::Counter { kind, .. } => counter_mnemonic(*kind),
        Op::Box(b) => box_mnemonic(b),
        Op::Jump(_) => "JMP",
        Op::Label(_) => "LBL",
        Op::Call(_) => "CALL",
        Op::CallArgs(_) => "CALL (parameters)",
        Op::Return { conditional } => {
            if *conditional {
                "CRET"
            } else {
                "RET"
            }
        }
        Op::End { conditional } => {
            if *conditional {
                "END"
            } else {
                "MEND"
            }
        }
        Op::Stop => "STOP",
        Op::Wdr => "WDR",
        Op::Interrupt(i) => match i {
            IntOp::Attach { .. } => "ATCH",
            IntOp::Detach { .. } => "DTCH",
            IntOp::Enable => "ENI",
            IntOp::Disable => "DISI",
            IntOp::ClearEvent { .. } => "CEVNT",
        },
        Op::Nop => "NOP",
        Op::For { .. } => "FOR",
        Op::Next { .. } => "NEXT",
        Op::ScrBegin { .. } => "LSCR",
        Op::ScrTransition { .. } => "SCRT",
        Op::ScrCondEnd { .. } => "CSCRE",
        Op::ScrEnd => "SCRE",
        // The Omron ops by their Omron mnemonic families (their own coverage: issue 12).
        Op::Interlock => "IL",
        Op::InterlockEnd => "ILC",
        Op::TaskStart => "$TASK",
        Op::OmronTimer { .. } => "TIM",
        Op::OmronCounter { .. } => "CNT",
        Op::Omron(_) => "MOV/CMP/+",
        Op::Ext(b) => ext_mnemonic(b),
        Op::StrCompare(c) => {
            let form = match c.form {
                StackForm::Load => 0,
                StackForm::And => 1,
                StackForm::Or => 2,
            };
            ["LDS=", "LDS<>", "AS=", "AS<>", "OS=", "OS<>"][form * 2 + usize::from(c.ne)]
        }
    }
}

fn ext_mnemonic(b: &ExtBox) -> &'static str {
    match b {
        ExtBox::TableAdd { .. } => "ATT",
        ExtBox::TableTake { lifo, .. } => ["FIFO", "LIFO"][usize::from(*lifo)],
        ExtBox::TableFind { rel, .. } => match rel {
            FindRel::Eq => "FND=",
            FindRel::Ne => "FND<>",
            FindRel::Lt => "FND<",
            FindRel::Gt => "FND>",
        },
        ExtBox::AsciiToHex { .. } => "ATH",
        ExtBox::HexToAscii { .. } => "HTA",
        ExtBox::NumToText { ty, string, .. } => {
            let t = match ty {
                NumType::Int => 0,
                NumType::DInt => 1,
                NumType::Real => 2,
            };
            ["ITA", "DTA", "RTA", "ITS", "DTS", "RTS"][t + 3 * usize::from(*string)]
        }
        ExtBox::TextToNum { ty, .. } => match ty {
            NumType::Int => "STI",
            NumType::DInt => "STD",
            NumType::Real => "STR",
        },
        ExtBox::StrLen { .. } => "SLEN",
        ExtBox::StrCopy { .. } => "SCPY",
        ExtBox::StrCat { .. } => "SCAT",
        ExtBox::SubStr { .. } => "SSCPY",
        ExtBox::StrFind { chars, .. } => ["SFND", "CFND"][usize::from(*chars)],
        ExtBox::Clock { op, .. } => match op {
            ClockOp::Read => "TODR",
            ClockOp::Write => "TODW",
            ClockOp::ReadExt => "TODRX",
            ClockOp::WriteExt => "TODWX",
        },
        ExtBox::Pid { .. } => "PID",
        ExtBox::HscDefine { .. } => "HDEF",
        ExtBox::Hsc { .. } => "HSC",
        ExtBox::Pls { .. } => "PLS",
        ExtBox::Comm { op, .. } => op.mnemonic(),
    }
}

fn box_mnemonic(b: &BoxOp) -> &'static str {
    use stljit_core::ir::{ArithOp as A, LogicOp as L, RealFn as F};
    match b {
        BoxOp::Move { width, .. } => by_width(*width, ["MOVB", "MOVW", "MOVD"]),
        BoxOp::Swap { .. } => "SWAP",
        BoxOp::BlockMove { width, .. } => by_width(*width, ["BMB", "BMW", "BMD"]),
        BoxOp::Fill { .. } => "FILL",
        BoxOp::IntArith { op, width, .. } => {
            let i = match op {
                A::Add => 0,
                A::Sub => 1,
                A::Mul => 2,
                A::Div => 3,
            };
            if *width == Width::DWord {
                ["+D", "-D", "*D", "/D"][i]
            } else {
                ["+I", "-I", "*I", "/I"][i]
            }
        }
        BoxOp::MulWide { .. } => "MUL",
        BoxOp::DivWide { .. } => "DIV",
        BoxOp::RealArith { op, .. } => match op {
            A::Add => "+R",
            A::Sub => "-R",
            A::Mul => "*R",
            A::Div => "/R",
        },
        BoxOp::RealFunc { func, .. } => match func {
            F::Sqrt => "SQRT",
            F::Ln => "LN",
            F::Exp => "EXP",
            F::Sin => "SIN",
            F::Cos => "COS",
            F::Tan => "TAN",
        },
        BoxOp::Step { width, up, .. } => {
            if *up {
                by_width(*width, ["INCB", "INCW", "INCD"])
            } else {
                by_width(*width, ["DECB", "DECW", "DECD"])
            }
        }
        BoxOp::Logic { op, width, .. } => match op {
            L::And => by_width(*width, ["ANDB", "ANDW", "ANDD"]),
            L::Or => by_width(*width, ["ORB", "ORW", "ORD"]),
            L::Xor => by_width(*width, ["XORB", "XORW", "XORD"]),
        },
        BoxOp::Invert { width, .. } => by_width(*width, ["INVB", "INVW", "INVD"]),
        BoxOp::Shift { left, width, .. } => {
            if *left {
                by_width(*width, ["SLB", "SLW", "SLD"])
            } else {
                by_width(*width, ["SRB", "SRW", "SRD"])
            }
        }
        BoxOp::Rotate { left, width, .. } => {
            if *left {
                by_width(*width, ["RLB", "RLW", "RLD"])
            } else {
                by_width(*width, ["RRB", "RRW", "RRD"])
            }
        }
        BoxOp::ShiftRegister { .. } => "SHRB",
        BoxOp::Convert { conv, .. } => match conv {
            Conversion::ByteToInt => "BTI",
            Conversion::IntToByte => "ITB",
            Conversion::IntToDInt => "ITD",
            Conversion::DIntToInt => "DTI",
            Conversion::DIntToReal => "DTR",
            Conversion::Round => "ROUND",
            Conversion::Trunc => "TRUNC",
            Conversion::BcdToInt => "BCDI",
            Conversion::IntToBcd => "IBCD",
            Conversion::Decode => "DECO",
            Conversion::Encode => "ENCO",
            Conversion::Segment => "SEG",
        },
        BoxOp::ImmediateRead { .. } => "BIR",
        BoxOp::ImmediateWrite { .. } => "BIW",
    }
}

/// Calls `f` on every value operand of `op`.
pub fn for_each_operand(op: &Op, mut f: impl FnMut(&Operand)) {
    let contact = |c: &Contact, f: &mut dyn FnMut(&Operand)| {
        if let Contact::Compare { lhs, rhs, .. } = c {
            f(lhs);
            f(rhs);
        }
    };
    match op {
        Op::Load(c) | Op::And(c) | Op::Or(c) => contact(c, &mut f),
        Op::SetRange { count, .. }
        | Op::ResetTimers { count, .. }
        | Op::ResetCounters { count, .. } => f(count),
        Op::Timer { preset, .. } | Op::Counter { preset, .. } => f(preset),
        Op::For {
            index, init, limit, ..
        } => {
            f(index);
            f(init);
            f(limit);
        }
        Op::Box(b) => match b {
            BoxOp::Move { src, dst, .. }
            | BoxOp::IntArith { src, dst, .. }
            | BoxOp::MulWide { src, dst }
            | BoxOp::DivWide { src, dst }
            | BoxOp::RealArith { src, dst, .. }
            | BoxOp::RealFunc { src, dst, .. }
            | BoxOp::Logic { src, dst, .. }
            | BoxOp::Convert { src, dst, .. } => {
                f(src);
                f(dst);
            }
            BoxOp::Swap { dst } | BoxOp::Step { dst, .. } | BoxOp::Invert { dst, .. } => f(dst),
            BoxOp::BlockMove {
                src, dst, count, ..
            }
            | BoxOp::Fill { src, dst, count } => {
                f(src);
                f(dst);
                f(count);
            }
            BoxOp::Shift { dst, count, .. } | BoxOp::Rotate { dst, count, .. } => {
                f(dst);
                f(count);
            }
            BoxOp::ShiftRegister { len, .. } => f(len),
            BoxOp::ImmediateRead { dst, .. } => f(dst),
            BoxOp::ImmediateWrite { src, .. } => f(src),
        },
        Op::Ext(b) => b.operand_uses().iter().for_each(|u| f(&u.operand)),
        Op::StrCompare(c) => c.operand_uses().iter().for_each(|u| f(&u.operand)),
        _ => {}
    }
}

/// A short name for an operand's kind: the area (`V`, `AC`, `T`), `*VD`/`*LD`/`*AC`, `&V`, `const`.
pub fn operand_kind(o: &Operand) -> String {
    match o {
        Operand::Mem(l) => area_name(l.area).to_string(),
        Operand::Const(_) => "const".into(),
        Operand::Indirect(l) => format!("*{}", area_name(l.area)),
        Operand::AddressOf(l) => format!("&{}", area_name(l.area)),
        Operand::Omron(r) => match r {
            stljit_core::ir::OmronRef::DmBinary(_) => "@D".into(),
            stljit_core::ir::OmronRef::DmBcd(_) => "*D".into(),
            stljit_core::ir::OmronRef::Index { .. } => ",IR".into(),
        },
    }
}

fn area_name(a: Area) -> &'static str {
    match a {
        Area::TimerValue => "T",
        Area::CounterValue => "C",
        Area::TimerBit => "T-bit",
        Area::CounterBit => "C-bit",
        other => area_prefix(other),
    }
}
