//! The S7 mnemonics: [`TABLE`], every supported instruction with the lowering routine it goes
//! to (`Lowerer::instr` dispatches on it and "did you mean" suggestions iterate it, so the two
//! cannot drift), and [`FAMILIES`], the optional instruction families with their mnemonics: one
//! the CPU lacks gets "not available on this CPU", one not in [`TABLE`] "not supported yet",
//! instead of "unknown".

use stljit_core::InstrSet;
use stljit_core::ir::{CounterKind, RealFn, TimerKind};

/// The lowering routine of a mnemonic (`Lowerer::instr`); a routine that serves several
/// mnemonics tells them apart by the mnemonic's text, or by the kind carried here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Group {
    /// `LD`, `A`, `O` with their negated (`N`) and immediate (`I`) forms.
    Contact,
    /// `=`, `=I`.
    Coil,
    /// `S`, `R`, `SI`, `RI`.
    SetReset,
    /// The logic-stack ops without operands: `NOT`, `ALD`, `OLD`, `LPS`, `LRD`, `LPP`, `AENO`.
    StackOp,
    /// `EU`, `ED`.
    Edge,
    /// `LDS n`.
    Pick,
    /// `TON`, `TONR`, `TOF` (also spelled `TOFF`).
    Timer(TimerKind),
    /// `CTU`, `CTD`, `CTUD`.
    Counter(CounterKind),
    /// The compare contacts `LDB=` … `OR<` (form, type and relation are parsed from the text).
    Compare,
    /// `MOVB`, `MOVW`, `MOVD`, `MOVR`.
    Move,
    /// `SWAP`.
    Swap,
    /// `BMB`, `BMW`, `BMD`, `FILL`.
    BlockMove,
    /// `+I` … `/R`: integer and real arithmetic.
    Arith,
    /// `MUL`, `DIV`: 16 × 16 → 32 bit.
    MulDiv,
    /// `SQRT`, `LN`, `EXP`, `SIN`, `COS`, `TAN`.
    RealFunc(RealFn),
    /// `INCB` … `DECD`.
    Step,
    /// `ANDB` … `XORD`.
    WordLogic,
    /// `INVB`, `INVW`, `INVD`.
    Invert,
    /// `SLB` … `RRD`.
    ShiftRotate,
    /// `SHRB`.
    ShiftRegister,
    /// `BTI`, `ITB`, `ITD`, `DTI`, `DTR`, `ROUND`, `TRUNC`, `DECO`, `ENCO`, `SEG`.
    Convert,
    /// `BCDI`, `IBCD`.
    Bcd,
    /// `BIR`, `BIW`.
    ImmediateByte,
    /// `NOP`.
    Nop,
    /// Program control (spec §4.13), lowered by `Lowerer::control`.
    Control(Flow),
    /// `ATCH`, `DTCH`, `ENI`, `DISI`, `CEVNT` (s7-200-more §3.4), lowered by
    /// `Lowerer::interrupt`.
    Interrupt,
    /// The boxes of s7-200-more §4–§7 (tables, ASCII and number text, strings, the clock,
    /// PID), lowered by `Lowerer::ext`.
    Ext,
    /// The string compare contacts `LDS=` … `OS<>` (s7-200-more §5.6).
    StrCompare,
    /// `HDEF`, `HSC` (s7-200-more §8), lowered by `Lowerer::hsc`.
    Hsc,
    /// `PLS` (s7-200-more §9), lowered by `Lowerer::pls`.
    Pls,
    /// `XMT`, `RCV`, `NETR`, `NETW`, `GET`, `PUT`, `GPA`, `SPA` (s7-200-more §10), lowered by
    /// `Lowerer::comm`.
    Comm,
}

/// The program-control routines (spec §4.13).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Flow {
    /// `END` (conditional), `MEND`.
    End,
    /// `STOP`.
    Stop,
    /// `WDR`.
    WatchdogReset,
    /// `RET`, `CRET` (conditional).
    Return,
    /// `RETI`, `CRETI` (conditional).
    ReturnFromInterrupt,
    /// `JMP n`.
    Jump,
    /// `LBL n`.
    Label,
    /// `CALL`.
    Call,
    /// `FOR`.
    For,
    /// `NEXT`.
    Next,
    /// `LSCR`.
    ScrBegin,
    /// `SCRT`.
    ScrTransition,
    /// `CSCRE`.
    ScrCondEnd,
    /// `SCRE`.
    ScrEnd,
}

/// Every supported mnemonic (upper case) and its lowering routine; compare contacts are listed
/// with each relation. On a tie, suggestions prefer the earlier entry, so the order is part of
/// the behaviour.
pub(crate) const TABLE: &[(&str, Group)] = &[
    ("LD", Group::Contact),
    ("LDN", Group::Contact),
    ("A", Group::Contact),
    ("AN", Group::Contact),
    ("O", Group::Contact),
    ("ON", Group::Contact),
    ("=", Group::Coil),
    ("NOT", Group::StackOp),
    ("S", Group::SetReset),
    ("R", Group::SetReset),
    ("EU", Group::Edge),
    ("ED", Group::Edge),
    ("LDI", Group::Contact),
    ("LDNI", Group::Contact),
    ("AI", Group::Contact),
    ("ANI", Group::Contact),
    ("OI", Group::Contact),
    ("ONI", Group::Contact),
    ("=I", Group::Coil),
    ("SI", Group::SetReset),
    ("RI", Group::SetReset),
    ("BIR", Group::ImmediateByte),
    ("BIW", Group::ImmediateByte),
    ("NOP", Group::Nop),
    ("ALD", Group::StackOp),
    ("OLD", Group::StackOp),
    ("LPS", Group::StackOp),
    ("LRD", Group::StackOp),
    ("LPP", Group::StackOp),
    ("LDS", Group::Pick),
    ("AENO", Group::StackOp),
    ("TON", Group::Timer(TimerKind::On)),
    ("TONR", Group::Timer(TimerKind::Retentive)),
    ("TOF", Group::Timer(TimerKind::Off)),
    ("TOFF", Group::Timer(TimerKind::Off)),
    ("CTU", Group::Counter(CounterKind::Up)),
    ("CTD", Group::Counter(CounterKind::Down)),
    ("CTUD", Group::Counter(CounterKind::UpDown)),
    ("LDB=", Group::Compare),
    ("LDB<>", Group::Compare),
    ("LDB>=", Group::Compare),
    ("LDB<=", Group::Compare),
    ("LDB>", Group::Compare),
    ("LDB<", Group::Compare),
    ("AB=", Group::Compare),
    ("AB<>", Group::Compare),
    ("AB>=", Group::Compare),
    ("AB<=", Group::Compare),
    ("AB>", Group::Compare),
    ("AB<", Group::Compare),
    ("OB=", Group::Compare),
    ("OB<>", Group::Compare),
    ("OB>=", Group::Compare),
    ("OB<=", Group::Compare),
    ("OB>", Group::Compare),
    ("OB<", Group::Compare),
    ("LDW=", Group::Compare),
    ("LDW<>", Group::Compare),
    ("LDW>=", Group::Compare),
    ("LDW<=", Group::Compare),
    ("LDW>", Group::Compare),
    ("LDW<", Group::Compare),
    ("AW=", Group::Compare),
    ("AW<>", Group::Compare),
    ("AW>=", Group::Compare),
    ("AW<=", Group::Compare),
    ("AW>", Group::Compare),
    ("AW<", Group::Compare),
    ("OW=", Group::Compare),
    ("OW<>", Group::Compare),
    ("OW>=", Group::Compare),
    ("OW<=", Group::Compare),
    ("OW>", Group::Compare),
    ("OW<", Group::Compare),
    ("LDD=", Group::Compare),
    ("LDD<>", Group::Compare),
    ("LDD>=", Group::Compare),
    ("LDD<=", Group::Compare),
    ("LDD>", Group::Compare),
    ("LDD<", Group::Compare),
    ("AD=", Group::Compare),
    ("AD<>", Group::Compare),
    ("AD>=", Group::Compare),
    ("AD<=", Group::Compare),
    ("AD>", Group::Compare),
    ("AD<", Group::Compare),
    ("OD=", Group::Compare),
    ("OD<>", Group::Compare),
    ("OD>=", Group::Compare),
    ("OD<=", Group::Compare),
    ("OD>", Group::Compare),
    ("OD<", Group::Compare),
    ("LDR=", Group::Compare),
    ("LDR<>", Group::Compare),
    ("LDR>=", Group::Compare),
    ("LDR<=", Group::Compare),
    ("LDR>", Group::Compare),
    ("LDR<", Group::Compare),
    ("AR=", Group::Compare),
    ("AR<>", Group::Compare),
    ("AR>=", Group::Compare),
    ("AR<=", Group::Compare),
    ("AR>", Group::Compare),
    ("AR<", Group::Compare),
    ("OR=", Group::Compare),
    ("OR<>", Group::Compare),
    ("OR>=", Group::Compare),
    ("OR<=", Group::Compare),
    ("OR>", Group::Compare),
    ("OR<", Group::Compare),
    ("MOVB", Group::Move),
    ("MOVW", Group::Move),
    ("MOVD", Group::Move),
    ("MOVR", Group::Move),
    ("SWAP", Group::Swap),
    ("BMB", Group::BlockMove),
    ("BMW", Group::BlockMove),
    ("BMD", Group::BlockMove),
    ("FILL", Group::BlockMove),
    ("+I", Group::Arith),
    ("-I", Group::Arith),
    ("*I", Group::Arith),
    ("/I", Group::Arith),
    ("+D", Group::Arith),
    ("-D", Group::Arith),
    ("*D", Group::Arith),
    ("/D", Group::Arith),
    ("MUL", Group::MulDiv),
    ("DIV", Group::MulDiv),
    ("+R", Group::Arith),
    ("-R", Group::Arith),
    ("*R", Group::Arith),
    ("/R", Group::Arith),
    ("SQRT", Group::RealFunc(RealFn::Sqrt)),
    ("LN", Group::RealFunc(RealFn::Ln)),
    ("EXP", Group::RealFunc(RealFn::Exp)),
    ("SIN", Group::RealFunc(RealFn::Sin)),
    ("COS", Group::RealFunc(RealFn::Cos)),
    ("TAN", Group::RealFunc(RealFn::Tan)),
    ("INCB", Group::Step),
    ("DECB", Group::Step),
    ("INCW", Group::Step),
    ("DECW", Group::Step),
    ("INCD", Group::Step),
    ("DECD", Group::Step),
    ("ANDB", Group::WordLogic),
    ("ANDW", Group::WordLogic),
    ("ANDD", Group::WordLogic),
    ("ORB", Group::WordLogic),
    ("ORW", Group::WordLogic),
    ("ORD", Group::WordLogic),
    ("XORB", Group::WordLogic),
    ("XORW", Group::WordLogic),
    ("XORD", Group::WordLogic),
    ("INVB", Group::Invert),
    ("INVW", Group::Invert),
    ("INVD", Group::Invert),
    ("SLB", Group::ShiftRotate),
    ("SLW", Group::ShiftRotate),
    ("SLD", Group::ShiftRotate),
    ("SRB", Group::ShiftRotate),
    ("SRW", Group::ShiftRotate),
    ("SRD", Group::ShiftRotate),
    ("RLB", Group::ShiftRotate),
    ("RLW", Group::ShiftRotate),
    ("RLD", Group::ShiftRotate),
    ("RRB", Group::ShiftRotate),
    ("RRW", Group::ShiftRotate),
    ("RRD", Group::ShiftRotate),
    ("SHRB", Group::ShiftRegister),
    ("BTI", Group::Convert),
    ("ITB", Group::Convert),
    ("ITD", Group::Convert),
    ("DTI", Group::Convert),
    ("DTR", Group::Convert),
    ("ROUND", Group::Convert),
    ("TRUNC", Group::Convert),
    ("BCDI", Group::Bcd),
    ("IBCD", Group::Bcd),
    ("DECO", Group::Convert),
    ("ENCO", Group::Convert),
    ("SEG", Group::Convert),
    ("END", Group::Control(Flow::End)),
    ("MEND", Group::Control(Flow::End)),
    ("STOP", Group::Control(Flow::Stop)),
    ("WDR", Group::Control(Flow::WatchdogReset)),
    ("JMP", Group::Control(Flow::Jump)),
    ("LBL", Group::Control(Flow::Label)),
    ("CALL", Group::Control(Flow::Call)),
    ("CRET", Group::Control(Flow::Return)),
    ("RET", Group::Control(Flow::Return)),
    ("RETI", Group::Control(Flow::ReturnFromInterrupt)),
    ("CRETI", Group::Control(Flow::ReturnFromInterrupt)),
    ("FOR", Group::Control(Flow::For)),
    ("NEXT", Group::Control(Flow::Next)),
    ("LSCR", Group::Control(Flow::ScrBegin)),
    ("SCRT", Group::Control(Flow::ScrTransition)),
    ("CSCRE", Group::Control(Flow::ScrCondEnd)),
    ("SCRE", Group::Control(Flow::ScrEnd)),
    ("ATCH", Group::Interrupt),
    ("DTCH", Group::Interrupt),
    ("ENI", Group::Interrupt),
    ("DISI", Group::Interrupt),
    ("CEVNT", Group::Interrupt),
    ("ATT", Group::Ext),
    ("FIFO", Group::Ext),
    ("LIFO", Group::Ext),
    ("FND=", Group::Ext),
    ("FND<>", Group::Ext),
    ("FND<", Group::Ext),
    ("FND>", Group::Ext),
    ("ATH", Group::Ext),
    ("HTA", Group::Ext),
    ("ITA", Group::Ext),
    ("DTA", Group::Ext),
    ("RTA", Group::Ext),
    ("ITS", Group::Ext),
    ("DTS", Group::Ext),
    ("RTS", Group::Ext),
    ("STI", Group::Ext),
    ("STD", Group::Ext),
    ("STR", Group::Ext),
    ("SLEN", Group::Ext),
    ("SCPY", Group::Ext),
    ("SSCPY", Group::Ext),
    ("SCAT", Group::Ext),
    ("SFND", Group::Ext),
    ("CFND", Group::Ext),
    ("TODR", Group::Ext),
    ("TODW", Group::Ext),
    ("TODRX", Group::Ext),
    ("TODWX", Group::Ext),
    ("PID", Group::Ext),
    ("HDEF", Group::Hsc),
    ("HSC", Group::Hsc),
    ("PLS", Group::Pls),
    ("XMT", Group::Comm),
    ("RCV", Group::Comm),
    ("NETR", Group::Comm),
    ("NETW", Group::Comm),
    ("GET", Group::Comm),
    ("PUT", Group::Comm),
    ("GPA", Group::Comm),
    ("SPA", Group::Comm),
    ("LDS=", Group::StrCompare),
    ("LDS<>", Group::StrCompare),
    ("AS=", Group::StrCompare),
    ("AS<>", Group::StrCompare),
    ("OS=", Group::StrCompare),
    ("OS<>", Group::StrCompare),
];

/// The optional instruction families (s7-200-more Appendix A) and their mnemonics: whether the
/// selected CPU lacks a family is profile data (`CpuProfile::lacks`). A mnemonic listed
/// here and not in [`TABLE`] is known but not supported yet; the string compare contacts
/// (`LDS=`, …) belong to [`InstrSet::Strings`] through [`is_string_compare`] and the table find
/// (`FND=`, …) to [`InstrSet::Tables`]. (There is no instruction `TBL`: `TBL_FIND` is the LAD
/// name of `FND`.)
pub(crate) const FAMILIES: &[(InstrSet, &[&str])] = &[
    (
        InstrSet::Interrupts,
        &["ATCH", "DTCH", "ENI", "DISI", "CRETI", "CEVNT"],
    ),
    (
        InstrSet::Tables,
        &["ATT", "FIFO", "LIFO", "FND=", "FND<>", "FND<", "FND>"],
    ),
    (InstrSet::Ascii, &["ATH", "HTA", "ITA", "DTA", "RTA"]),
    (
        InstrSet::Strings,
        &[
            "ITS", "DTS", "RTS", "STI", "STD", "STR", "SLEN", "SCPY", "SSCPY", "SCAT", "SFND",
            "CFND",
        ],
    ),
    (InstrSet::Clock, &["TODR", "TODW", "TODRX", "TODWX"]),
    (InstrSet::Pid, &["PID"]),
    (InstrSet::HighSpeedCounters, &["HDEF", "HSC"]),
    (InstrSet::PulseOutputs, &["PLS"]),
    (InstrSet::Freeport, &["XMT", "RCV"]),
    (InstrSet::PortAddress, &["GPA", "SPA"]),
    (InstrSet::NetReadWrite, &["NETR", "NETW"]),
    (InstrSet::GetPut, &["GET", "PUT"]),
    (InstrSet::IpAddress, &["GIP", "SIP"]),
    (InstrSet::IntervalTimers, &["BITIM", "CITIM"]),
    (InstrSet::DiagnosticLed, &["DIAG_LED"]),
];

/// The family of mnemonic `m` (upper case), if it belongs to one.
pub(crate) fn family(m: &str) -> Option<InstrSet> {
    if is_string_compare(m) {
        return Some(InstrSet::Strings);
    }
    FAMILIES
        .iter()
        .find(|(_, ms)| ms.contains(&m))
        .map(|&(set, _)| set)
}

/// Why a family's instructions are not supported yet (the help of E027), and what to do
/// meanwhile. Issue 13 of the project tracks each family.
pub(crate) fn not_yet(set: InstrSet) -> &'static str {
    match set {
        InstrSet::Interrupts => {
            "interrupts are simulated (s7-200-more §3), but not this instruction yet"
        }
        // Every mnemonic of these families is in `TABLE` (a test checks it).
        InstrSet::Tables
        | InstrSet::Ascii
        | InstrSet::Strings
        | InstrSet::Clock
        | InstrSet::Pid
        | InstrSet::HighSpeedCounters
        | InstrSet::PulseOutputs
        | InstrSet::Freeport
        | InstrSet::PortAddress
        | InstrSet::NetReadWrite
        | InstrSet::GetPut => "this instruction is not implemented yet",
        InstrSet::IpAddress => {
            "the IP address instructions GIP/SIP are out of scope (s7-200-more §10.6)"
        }
        InstrSet::IntervalTimers | InstrSet::DiagnosticLed => {
            "this instruction is not implemented yet"
        }
    }
}

/// What to use instead of a family the CPU does not have (the help of E037).
pub(crate) fn instead(set: InstrSet) -> &'static str {
    match set {
        InstrSet::NetReadWrite => {
            "the S7-200 SMART has no PPI network read/write; use GET/PUT (Ethernet S7 communication)"
        }
        InstrSet::GetPut => {
            "GET/PUT are the S7-200 SMART's Ethernet instructions; the classic CPUs use NETR/NETW"
        }
        InstrSet::IpAddress => "only the S7-200 SMART has an Ethernet port",
        InstrSet::PulseOutputs => {
            "no A5 document describes pulse outputs; choose --cpu s7-200 or --cpu smart"
        }
        _ => "choose the --cpu that has it",
    }
}

/// `LDS=`, `AS<>`, ...: string compares (not the LDS stack instruction).
pub(crate) fn is_string_compare(m: &str) -> bool {
    let rest = m
        .strip_prefix("LDS")
        .or_else(|| m.strip_prefix("AS"))
        .or_else(|| m.strip_prefix("OS"));
    rest.is_some_and(|r| !r.is_empty() && r.bytes().all(|c| matches!(c, b'=' | b'<' | b'>')))
}

/// The lowering routine of the supported mnemonic `m` (upper case); `None` for an unknown or
/// out-of-scope one. A compare contact may spell its `=` as `==` (`LDW==`); only `=` is
/// suggested.
pub(crate) fn group(m: &str) -> Option<Group> {
    listed(m).or_else(|| {
        m.strip_suffix('=')
            .filter(|stem| stem.ends_with('='))
            .and_then(listed)
            .filter(|&g| g == Group::Compare)
    })
}

fn listed(m: &str) -> Option<Group> {
    TABLE.iter().find(|&&(k, _)| k == m).map(|&(_, g)| g)
}

fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The supported mnemonic closest to `m` (upper case), if one is close enough to be a likely typo.
pub(crate) fn closest(m: &str) -> Option<&'static str> {
    if m.is_empty() || m.len() > 12 {
        return None;
    }
    let (best, d) = TABLE
        .iter()
        .map(|&(k, _)| (k, distance(m, k)))
        .min_by_key(|&(_, d)| d)?;
    let limit = if m.len() <= 3 { 1 } else { 2 };
    (d <= limit).then_some(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lower::compare;
    use crate::{compile_str, print_op};
    use stljit_core::ProfileId;
    use stljit_core::ir::Program;
    use stljit_source::Code;

    /// Where a line may stand: text before and after it (loops, segments, jump targets,
    /// subroutines and interrupt routines for the instructions that need them).
    const CONTEXTS: &[(&str, &str)] = &[
        ("LD I0.0\n", ""),
        ("LD I0.0\nFOR VW100, 1, 2\n", ""),
        ("LD I0.0\n", "NEXT\n"),
        ("LD I0.0\n", "SCRE\n"),
        ("LSCR S0.1\n", "SCRE\n"),
        ("LSCR S0.1\n", ""),
        ("LD I0.0\n", "LBL 1\n"),
        ("LD I0.0\n", "MEND\nSBR 0\nLD I0.0\n"),
        ("MEND\nSBR 0\nLD I0.0\n", ""),
        ("MEND\nINT 0\nLD I0.0\n", ""),
    ];

    /// Plausible operand lists, one of which fits every supported instruction.
    const OPERANDS: &[&str] = &[
        "",
        "I0.0",
        "Q0.0",
        "S0.2",
        "1",
        "Q0.0, 1",
        "T37, 100",
        "T1, 100",
        "C1, 5",
        "VB0, VB1",
        "VW0, VW2",
        "VD0, VD4",
        "VW0, VD4",
        "VB0, VW2",
        "VW0, VB2",
        "VD0, VW4",
        "VB0",
        "VW0",
        "VD0",
        "VB0, 1",
        "VW0, 1",
        "VD0, 1",
        "VB0, VB10, 3",
        "VW0, VB10, 3",
        "VD0, VB10, 3",
        "VB0, 1, VW10",
        "VB0, 1, VD10",
        "VB0, 1, 4, VB20",
        "VB0, VB10, VB20",
        "VW0, VW2, VW4",
        "VB0, 0",
        "VW0, VW10, 3",
        "VD0, VD20, 3",
        "I0.0, V0.0, 4",
        "IB0, VB1",
        "VB1, QB0",
        "VW100, 1, 2",
        "SBR0",
        "INT0, 10",
        "10",
        "0",
        "1, 0",
    ];

    /// Mnemonics that lower to the same IR as another one, which the printer uses.
    const SAME_IR: &[(&str, &str)] = &[("TOFF", "TOF"), ("MOVR", "MOVD")];

    /// The mnemonic the S7 printer gives the last op lowered from source line `line`.
    fn printed_at(program: &Program, line: usize) -> Option<String> {
        program.pous.iter().find_map(|pou| {
            let at = pou.locs.iter().rposition(|l| l.line as usize == line)?;
            let text = print_op(program, pou, &pou.ops[at]);
            text.split_whitespace().next().map(str::to_owned)
        })
    }

    /// Every table entry reaches its lowering routine (no "unknown"/"not supported" with any
    /// operands) and lowers cleanly with some plausible operands to an op the printer spells
    /// with the entry's own mnemonic, so the table and the lowering cannot drift apart.
    #[test]
    fn every_entry_lowers() {
        for &(m, group) in TABLE {
            let mut clean = false;
            // The A5 first; PLS exists on the Siemens CPUs only, GET/PUT on the SMART only
            // (E033 elsewhere).
            'search: for (before, after, cpu) in CONTEXTS.iter().flat_map(|&(b, a)| {
                [ProfileId::A5, ProfileId::S7_200, ProfileId::Smart].map(|cpu| (b, a, cpu))
            }) {
                for ops in OPERANDS {
                    let text = format!("{before}{m} {ops}\n{after}");
                    let c = compile_str("t.stl", &text, cpu);
                    for d in &c.diagnostics {
                        assert!(
                            !matches!(d.code, Code::UnknownMnemonic | Code::Unsupported),
                            "{m} ({group:?}) is not lowered:\n{text}{d:?}"
                        );
                    }
                    if let Some(program) = &c.program {
                        let line = before.lines().count() + 1;
                        let same_ir = SAME_IR.iter().find(|&&(a, _)| a == m).map(|&(_, b)| b);
                        assert_eq!(
                            printed_at(program, line).as_deref(),
                            Some(same_ir.unwrap_or(m)),
                            "{m} ({group:?}) lowers to another instruction:\n{text}"
                        );
                        clean = true;
                        break 'search;
                    }
                }
            }
            assert!(clean, "{m} ({group:?}) never lowers without an error");
        }
    }

    #[test]
    fn entries_are_unique_and_not_out_of_scope() {
        for (i, &(m, group)) in TABLE.iter().enumerate() {
            assert!(
                TABLE[..i].iter().all(|&(k, _)| k != m),
                "{m} is listed twice"
            );
            assert_eq!(
                is_string_compare(m),
                group == Group::StrCompare,
                "{m}: string compares are the StrCompare entries"
            );
        }
        for (i, (set, ms)) in FAMILIES.iter().enumerate() {
            for m in *ms {
                assert_eq!(family(m), Some(*set), "{m} is listed in two families");
                assert!(
                    FAMILIES[..i].iter().all(|(_, o)| !o.contains(m)),
                    "{m} is listed twice"
                );
            }
        }
    }

    /// The compare entries are exactly the form × type × relation combinations `compare`
    /// reads, so suggestions include every compare contact.
    #[test]
    fn compare_entries_are_what_compare_reads() {
        for &(m, group) in TABLE {
            assert_eq!(compare(m).is_some(), group == Group::Compare, "{m}");
        }
        for ty in ["B", "W", "D", "R"] {
            for form in ["LD", "A", "O"] {
                for rel in ["=", "<>", ">=", "<=", ">", "<"] {
                    let m = format!("{form}{ty}{rel}");
                    assert_eq!(group(&m), Some(Group::Compare), "{m}");
                }
            }
        }
        assert_eq!(group("LDW=="), Some(Group::Compare));
        assert!(compare("LDW==").is_some());
        assert_eq!(group("LDS=="), None);
        assert_eq!(group("S=="), None);
        assert_eq!(group("NOPE"), None);
    }

    /// Every mnemonic of the families issue 13 parts C and D, pulse outputs (§9) and
    /// communication (§10) implement is lowered, so none of them reaches "not supported yet".
    #[test]
    fn implemented_families_are_complete() {
        for (set, ms) in FAMILIES {
            if matches!(
                set,
                InstrSet::Tables
                    | InstrSet::Ascii
                    | InstrSet::Strings
                    | InstrSet::Clock
                    | InstrSet::Pid
                    | InstrSet::HighSpeedCounters
                    | InstrSet::PulseOutputs
                    | InstrSet::Freeport
                    | InstrSet::PortAddress
                    | InstrSet::NetReadWrite
                    | InstrSet::GetPut
            ) {
                for m in *ms {
                    assert!(group(m).is_some(), "{m} is not lowered");
                }
            }
        }
        for m in ["LDS=", "LDS<>", "AS=", "AS<>", "OS=", "OS<>"] {
            assert_eq!(group(m), Some(Group::StrCompare));
            assert_eq!(family(m), Some(InstrSet::Strings));
        }
    }

    #[test]
    fn suggestions() {
        assert!(closest("MOVV").is_some_and(|s| s.starts_with("MOV")));
        assert_eq!(closest("MOVWW"), Some("MOVW"));
        assert_eq!(closest("TONN"), Some("TON"));
        assert_eq!(closest("XYZZYQ"), None);
    }

    #[test]
    fn string_compares() {
        assert!(is_string_compare("LDS="));
        assert!(is_string_compare("AS<>"));
        assert!(!is_string_compare("LDS"));
        assert!(!is_string_compare("AN"));
    }
}
