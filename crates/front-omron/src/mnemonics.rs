//! The Omron mnemonics: [`TABLE`], every supported instruction with its function code, its
//! lowering routine and the options it accepts (omron-cp.md §3; `Lowerer::instr` dispatches on
//! it, so the table and the lowering cannot drift), the comparison contacts (§3.1, parsed from
//! their text by [`compare`]) and the instructions that are recognised but not supported yet.

use stljit_core::ir::{CmpOp, OmronArith, OmronCounterKind, OmronTimerKind};
use stljit_core::omron::SystemBit;

/// The lowering routine of a mnemonic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// `LD`, `AND`, `OR` and their `NOT` forms: (class, negated).
    Contact(Join, bool),
    /// `AND LD`, `OR LD`.
    Block(Join),
    /// `NOT(520)`.
    Not,
    /// `UP(521)` (false), `DOWN(522)` (true).
    Edge(bool),
    /// `OUT`, `OUT NOT` (true).
    Out(bool),
    /// `SET` (true), `RSET` (false).
    SetReset(bool),
    /// `KEEP(011)`.
    Keep,
    /// `DIFU(013)` (false), `DIFD(014)` (true).
    Differentiate(bool),
    /// The timers.
    Timer(OmronTimerKind),
    /// The counters.
    Counter(OmronCounterKind),
    /// `MOV(021)` (false), `MOVL(498)` (true).
    Move(bool),
    /// `MOVR(560)`: an effective address into an index register.
    MoveAddress,
    /// `CCS(282)` (true: save) / `CCL(283)` (load) the condition flags.
    SaveFlags(bool),
    /// `IORF(097) St E`: refresh of expansion I/O words.
    Iorf,
    /// `CMP`/`CMPL`/`CPS`/`CPSL`: (double, signed).
    Compare(bool, bool),
    /// The arithmetic of §3.6.
    Arith(OmronArith),
    /// Program control.
    Control(Flow),
}

/// How a contact or block combines with the execution condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Join {
    /// `LD`: starts a block.
    Load,
    /// `AND`.
    And,
    /// `OR`.
    Or,
}

/// The program-control instructions (§3.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// `IL(002)`.
    Il,
    /// `ILC(003)`.
    Ilc,
    /// `JMP(004)`: jump when OFF.
    Jmp,
    /// `CJP(510)`: jump when ON.
    Cjp,
    /// `CJPN(511)`: jump when OFF.
    Cjpn,
    /// `JME(005)`.
    Jme,
    /// `JMP0(515)`.
    Jmp0,
    /// `JME0(516)`.
    Jme0,
    /// `END(001)`.
    End,
    /// `SBS(091)`.
    Sbs,
    /// `SBN(092)`.
    Sbn,
    /// `RET(093)`.
    Ret,
    /// `FOR(503) N`.
    For,
    /// `NEXT(504)`.
    Next,
    /// `BREAK(514)`.
    Break,
    /// `STEP(008) B` (start of step B) or `STEP(008)` (end of the step area).
    Step,
    /// `SNXT(009) B`.
    Snxt,
    /// `BPRG(096) N`.
    Bprg,
    /// `BEND(801)`.
    Bend,
}

/// The options an instruction accepts (spec §2.5; anything else is E012).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Allowed {
    /// `@`.
    pub up: bool,
    /// `%`.
    pub down: bool,
    /// `!`.
    pub immediate: bool,
}

const NONE: Allowed = Allowed {
    up: false,
    down: false,
    immediate: false,
};
const ALL: Allowed = Allowed {
    up: true,
    down: true,
    immediate: true,
};
const IMM: Allowed = Allowed {
    up: false,
    down: false,
    immediate: true,
};
const UP_IMM: Allowed = Allowed {
    up: true,
    down: false,
    immediate: true,
};
const UP: Allowed = Allowed {
    up: true,
    down: false,
    immediate: false,
};

/// The options of the comparison contacts (`!` [uncertain]; `@`/`%` are E012, U10).
pub const COMPARE_OPTIONS: Allowed = IMM;

/// The steps of a comparison contact (`LD>=` …) [uncertain].
pub(crate) const COMPARE_STEPS: u8 = 4;

/// The steps of an arithmetic instruction of §3.6 (`+` … `/BL`) [uncertain].
const ARITH_STEPS: u8 = 4;

/// One supported mnemonic.
#[derive(Clone, Copy, Debug)]
pub struct Mnemonic {
    /// As written (upper case).
    pub name: &'static str,
    /// Its function code, if it has one.
    pub code: Option<u16>,
    /// Its lowering routine.
    pub group: Group,
    /// The options it accepts.
    pub allowed: Allowed,
    /// The user-memory steps it takes (the "number of steps" column of the CP1H instruction
    /// list; [uncertain], docs/omron.md "Program capacity"), before the extra step of each
    /// constant operand of a double-length instruction.
    pub(crate) steps: u8,
}

const fn m(
    name: &'static str,
    code: Option<u16>,
    group: Group,
    allowed: Allowed,
    steps: u8,
) -> Mnemonic {
    Mnemonic {
        name,
        code,
        group,
        allowed,
        steps,
    }
}

use Group as G;
use OmronCounterKind as Ck;
use OmronTimerKind as Tk;

/// Every supported mnemonic except the arithmetic (named by [`OmronArith`]) and the comparison
/// contacts ([`compare`]).
pub const TABLE: &[Mnemonic] = &[
    m("LD", None, G::Contact(Join::Load, false), ALL, 1),
    m("AND", None, G::Contact(Join::And, false), ALL, 1),
    m("OR", None, G::Contact(Join::Or, false), ALL, 1),
    m("LD NOT", None, G::Contact(Join::Load, true), IMM, 1),
    m("AND NOT", None, G::Contact(Join::And, true), IMM, 1),
    m("OR NOT", None, G::Contact(Join::Or, true), IMM, 1),
    m("AND LD", None, G::Block(Join::And), NONE, 1),
    m("OR LD", None, G::Block(Join::Or), NONE, 1),
    m("NOT", Some(520), G::Not, NONE, 1),
    m("UP", Some(521), G::Edge(false), NONE, 3),
    m("DOWN", Some(522), G::Edge(true), NONE, 4),
    m("OUT", None, G::Out(false), IMM, 1),
    m("OUT NOT", None, G::Out(true), IMM, 1),
    m("SET", None, G::SetReset(true), ALL, 2),
    m("RSET", None, G::SetReset(false), ALL, 2),
    m("KEEP", Some(11), G::Keep, IMM, 1),
    m("DIFU", Some(13), G::Differentiate(false), NONE, 2),
    m("DIFD", Some(14), G::Differentiate(true), NONE, 2),
    m("TIM", None, G::Timer(Tk::Tim), NONE, 3),
    m("TIMX", Some(550), G::Timer(Tk::TimX), NONE, 3),
    m("TIMH", Some(15), G::Timer(Tk::TimH), NONE, 3),
    m("TIMHX", Some(551), G::Timer(Tk::TimHX), NONE, 3),
    m("TMHH", Some(540), G::Timer(Tk::Tmhh), NONE, 3),
    m("TMHHX", Some(552), G::Timer(Tk::TmhhX), NONE, 3),
    m("TTIM", Some(87), G::Timer(Tk::Ttim), NONE, 3),
    m("TTIMX", Some(555), G::Timer(Tk::TtimX), NONE, 3),
    m("CNT", None, G::Counter(Ck::Cnt), NONE, 3),
    m("CNTX", Some(546), G::Counter(Ck::CntX), NONE, 3),
    m("CNTR", Some(12), G::Counter(Ck::Cntr), NONE, 3),
    m("CNTRX", Some(548), G::Counter(Ck::CntrX), NONE, 3),
    m("MOV", Some(21), G::Move(false), UP_IMM, 3),
    m("MOVL", Some(498), G::Move(true), UP_IMM, 3),
    m("MOVR", Some(560), G::MoveAddress, UP, 3),
    m("CCS", Some(282), G::SaveFlags(true), UP, 1),
    m("CCL", Some(283), G::SaveFlags(false), UP, 1),
    m("IORF", Some(97), G::Iorf, UP, 3),
    m("CMP", Some(20), G::Compare(false, false), IMM, 3),
    m("CMPL", Some(60), G::Compare(true, false), IMM, 3),
    m("CPS", Some(114), G::Compare(false, true), IMM, 3),
    m("CPSL", Some(115), G::Compare(true, true), IMM, 3),
    m("IL", Some(2), G::Control(Flow::Il), NONE, 1),
    m("ILC", Some(3), G::Control(Flow::Ilc), NONE, 1),
    m("JMP", Some(4), G::Control(Flow::Jmp), NONE, 2),
    m("JME", Some(5), G::Control(Flow::Jme), NONE, 2),
    m("CJP", Some(510), G::Control(Flow::Cjp), NONE, 2),
    m("CJPN", Some(511), G::Control(Flow::Cjpn), NONE, 2),
    m("JMP0", Some(515), G::Control(Flow::Jmp0), NONE, 1),
    m("JME0", Some(516), G::Control(Flow::Jme0), NONE, 1),
    m("END", Some(1), G::Control(Flow::End), NONE, 1),
    m("SBS", Some(91), G::Control(Flow::Sbs), UP, 2),
    m("SBN", Some(92), G::Control(Flow::Sbn), NONE, 2),
    m("RET", Some(93), G::Control(Flow::Ret), NONE, 1),
    m("FOR", Some(503), G::Control(Flow::For), NONE, 2),
    m("NEXT", Some(504), G::Control(Flow::Next), NONE, 1),
    m("BREAK", Some(514), G::Control(Flow::Break), NONE, 1),
    m("STEP", Some(8), G::Control(Flow::Step), NONE, 2),
    m("SNXT", Some(9), G::Control(Flow::Snxt), NONE, 2),
    m("BPRG", Some(96), G::Control(Flow::Bprg), NONE, 2),
    m("BEND", Some(801), G::Control(Flow::Bend), NONE, 1),
];

/// The instructions only a block program (BPRG–BEND) may use, with their function codes
/// (CS/CJ instruction list, [uncertain] for the CP1H): outside a block program OMR-E027, inside
/// one OMR-E011 "not supported yet".
pub(crate) const BLOCK_ONLY: &[(&str, u16)] = &[
    ("IF", 802),
    ("IF NOT", 802),
    ("ELSE", 803),
    ("IEND", 804),
    ("WAIT", 805),
    ("WAIT NOT", 805),
    ("EXIT", 806),
    ("EXIT NOT", 806),
    ("LOOP", 809),
    ("LEND", 810),
    ("LEND NOT", 810),
    ("BPPS", 811),
    ("BPRS", 812),
    ("TIMW", 813),
    ("CNTW", 814),
    ("TMHW", 815),
    ("TIMWX", 816),
    ("TMHWX", 817),
    ("CNTWX", 818),
];

/// The instructions a step area (the first `STEP B` to `STEP` without operand) may not use
/// (omron-cp.md §2.9, seed §1-2-2); SBN is OMR-E029, the rest OMR-E026.
pub(crate) const NOT_IN_STEPS: &[&str] = &[
    "FOR", "NEXT", "BREAK", "END", "IL", "ILC", "JMP", "JME", "CJP", "CJPN", "JMP0", "JME0", "SBN",
    "RET", "IF", "IF NOT", "ELSE", "IEND", "BPRS", "BPPS",
];

/// The instructions a block program (BPRG–BEND) may not use (omron-cp.md §2.9, seed §1-2-2),
/// besides the timer family and every `@`/`%` instruction; SBN is OMR-E029, the rest OMR-E026.
/// A step area or another block program inside a block program is not allowed either [design].
pub(crate) const NOT_IN_BLOCKS: &[&str] = &[
    "FOR", "NEXT", "BREAK", "IL", "ILC", "JMP0", "JME0", "END", "UP", "DOWN", "DIFU", "DIFD",
    "KEEP", "OUT", "OUT NOT", "SBN", "BPRG", "STEP",
];

/// The instructions a function-block body may not use (omron-cp.md §2.9, seed §1-4), besides
/// every instruction with the `!` option.
pub(crate) const NOT_IN_FUNCTION_BLOCKS: &[&str] = &[
    "BPRG", "BEND", "SBS", "GSBS", "RET", "MCRO", "SBN", "JMP", "CJP", "CJPN", "STEP", "SNXT",
    "IORF", "TMHH",
];

/// The comparison relations with their function-code offsets (§3.1: `=`(300) … `>=`(325)),
/// longest first (the order [`compare`] tries them in).
pub const RELATIONS: [(&str, CmpOp, u16); 6] = [
    ("<>", CmpOp::Ne, 305),
    ("<=", CmpOp::Le, 315),
    (">=", CmpOp::Ge, 325),
    ("=", CmpOp::Eq, 300),
    ("<", CmpOp::Lt, 310),
    (">", CmpOp::Gt, 320),
];

/// The condition flag a comparison contact reads (U2's default: its relation's own flag); the
/// lowering emits it and the printer reads it back.
pub fn relation_flag(op: CmpOp) -> SystemBit {
    match op {
        CmpOp::Eq => SystemBit::Eq,
        CmpOp::Ne => SystemBit::Ne,
        CmpOp::Lt => SystemBit::Lt,
        CmpOp::Le => SystemBit::Le,
        CmpOp::Gt => SystemBit::Gt,
        CmpOp::Ge => SystemBit::Ge,
    }
}

/// How a comparison contact joins the execution condition, by its prefix.
pub const COMPARE_JOINS: [(&str, Join); 3] =
    [("LD", Join::Load), ("AND", Join::And), ("OR", Join::Or)];

/// The comparison suffixes (§3.1): none (unsigned 16), `L` (unsigned 32), `S` (signed 16),
/// `SL` (signed 32), as (suffix, double, signed, function-code offset).
pub const COMPARE_SUFFIXES: [(&str, bool, bool, u16); 4] = [
    ("", false, false, 0),
    ("L", true, false, 1),
    ("S", false, true, 2),
    ("SL", true, true, 3),
];

/// A parsed comparison contact (`LD>=S`, `AND<L`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CompareContact {
    /// How it joins the execution condition.
    pub join: Join,
    /// The relation.
    pub op: CmpOp,
    /// `L`: 32-bit operands.
    pub double: bool,
    /// `S`: signed.
    pub signed: bool,
    /// Its function code.
    pub code: u16,
}

/// Reads a comparison-contact mnemonic: `LD|AND|OR` + relation + suffix none/`L`/`S`/`SL`.
pub fn compare(mnemonic: &str) -> Option<CompareContact> {
    let (join, rest) = COMPARE_JOINS
        .into_iter()
        .find_map(|(p, j)| mnemonic.strip_prefix(p).map(|r| (j, r)))?;
    let (op, base, suffix) = RELATIONS
        .into_iter()
        .find_map(|(t, op, code)| rest.strip_prefix(t).map(|s| (op, code, s)))?;
    let (_, double, signed, plus) = COMPARE_SUFFIXES.into_iter().find(|s| s.0 == suffix)?;
    Some(CompareContact {
        join,
        op,
        double,
        signed,
        code: base + plus,
    })
}

/// `mnemonic` with its function code as messages write it (`CJP(510)`), or as it is if it has
/// none.
pub(crate) fn with_code(mnemonic: &str) -> String {
    match lookup(mnemonic).and_then(|m| m.code) {
        Some(c) => format!("{mnemonic}({c:03})"),
        None => mnemonic.to_owned(),
    }
}

/// The arithmetic instruction named `mnemonic`.
pub fn arith(mnemonic: &str) -> Option<OmronArith> {
    OmronArith::ALL
        .iter()
        .copied()
        .find(|a| a.mnemonic() == mnemonic)
}

/// The user-memory steps of the instruction named `mnemonic` (comparison contacts and
/// arithmetic included), `None` for an unknown one.
pub(crate) fn steps(mnemonic: &str) -> Option<u8> {
    lookup(mnemonic)
        .map(|m| m.steps)
        .or_else(|| compare(mnemonic).map(|_| COMPARE_STEPS))
}

/// The supported instruction named `mnemonic` (arithmetic included).
pub fn lookup(mnemonic: &str) -> Option<Mnemonic> {
    if let Some(found) = TABLE.iter().find(|m| m.name == mnemonic) {
        return Some(*found);
    }
    arith(mnemonic).map(|a| Mnemonic {
        name: a.mnemonic(),
        code: Some(a.function_code()),
        group: Group::Arith(a),
        allowed: UP_IMM,
        steps: ARITH_STEPS,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comparison_contacts_and_their_codes() {
        // §3.1: `>=` is 325, `S` adds 2; `<` is 310, `L` adds 1; `<>` is 305.
        let c = compare("LD>=S").unwrap();
        assert_eq!(
            (c.join, c.op, c.double, c.signed, c.code),
            (Join::Load, CmpOp::Ge, false, true, 327)
        );
        let c = compare("AND<L").unwrap();
        assert_eq!(
            (c.op, c.double, c.signed, c.code),
            (CmpOp::Lt, true, false, 311)
        );
        assert_eq!(compare("OR<>SL").unwrap().code, 308);
        assert_eq!(compare("OR=").unwrap().code, 300);
        assert!(compare("LD").is_none());
        assert!(compare("LD=X").is_none());
    }

    #[test]
    fn names_are_unique_and_arith_is_found() {
        let mut seen = std::collections::HashSet::new();
        for m in TABLE {
            assert!(seen.insert(m.name), "{}", m.name);
        }
        assert_eq!(lookup("+BL").map(|m| m.code), Some(Some(405)));
        assert_eq!(lookup("KEEP").map(|m| m.code), Some(Some(11)));
        assert_eq!(lookup("FOR").map(|m| m.code), Some(Some(503)));
        // An instruction takes 1 to 7 steps (seed §1-1-11).
        assert!(TABLE.iter().all(|m| (1..=7).contains(&m.steps)));
        assert_eq!(steps("+L"), Some(4));
        assert_eq!(steps("LD>=SL"), Some(COMPARE_STEPS));
        assert_eq!(steps("XYZ"), None);
        assert_eq!(lookup("STEP").map(|m| m.code), Some(Some(8)));
        assert!(lookup("IF").is_none());
    }
}
