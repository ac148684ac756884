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
}

const fn m(name: &'static str, code: Option<u16>, group: Group, allowed: Allowed) -> Mnemonic {
    Mnemonic {
        name,
        code,
        group,
        allowed,
    }
}

use Group as G;
use OmronCounterKind as Ck;
use OmronTimerKind as Tk;

/// Every supported mnemonic except the arithmetic (named by [`OmronArith`]) and the comparison
/// contacts ([`compare`]).
pub const TABLE: &[Mnemonic] = &[
    m("LD", None, G::Contact(Join::Load, false), ALL),
    m("AND", None, G::Contact(Join::And, false), ALL),
    m("OR", None, G::Contact(Join::Or, false), ALL),
    m("LD NOT", None, G::Contact(Join::Load, true), IMM),
    m("AND NOT", None, G::Contact(Join::And, true), IMM),
    m("OR NOT", None, G::Contact(Join::Or, true), IMM),
    m("AND LD", None, G::Block(Join::And), NONE),
    m("OR LD", None, G::Block(Join::Or), NONE),
    m("NOT", Some(520), G::Not, NONE),
    m("UP", Some(521), G::Edge(false), NONE),
    m("DOWN", Some(522), G::Edge(true), NONE),
    m("OUT", None, G::Out(false), IMM),
    m("OUT NOT", None, G::Out(true), IMM),
    m("SET", None, G::SetReset(true), ALL),
    m("RSET", None, G::SetReset(false), ALL),
    m("KEEP", Some(11), G::Keep, IMM),
    m("DIFU", Some(13), G::Differentiate(false), NONE),
    m("DIFD", Some(14), G::Differentiate(true), NONE),
    m("TIM", None, G::Timer(Tk::Tim), NONE),
    m("TIMX", Some(550), G::Timer(Tk::TimX), NONE),
    m("TIMH", Some(15), G::Timer(Tk::TimH), NONE),
    m("TIMHX", Some(551), G::Timer(Tk::TimHX), NONE),
    m("TMHH", Some(540), G::Timer(Tk::Tmhh), NONE),
    m("TMHHX", Some(552), G::Timer(Tk::TmhhX), NONE),
    m("TTIM", Some(87), G::Timer(Tk::Ttim), NONE),
    m("TTIMX", Some(555), G::Timer(Tk::TtimX), NONE),
    m("CNT", None, G::Counter(Ck::Cnt), NONE),
    m("CNTX", Some(546), G::Counter(Ck::CntX), NONE),
    m("CNTR", Some(12), G::Counter(Ck::Cntr), NONE),
    m("CNTRX", Some(548), G::Counter(Ck::CntrX), NONE),
    m("MOV", Some(21), G::Move(false), UP_IMM),
    m("MOVL", Some(498), G::Move(true), UP_IMM),
    m("MOVR", Some(560), G::MoveAddress, UP),
    m("CCS", Some(282), G::SaveFlags(true), UP),
    m("CCL", Some(283), G::SaveFlags(false), UP),
    m("IORF", Some(97), G::Iorf, UP),
    m("CMP", Some(20), G::Compare(false, false), IMM),
    m("CMPL", Some(60), G::Compare(true, false), IMM),
    m("CPS", Some(114), G::Compare(false, true), IMM),
    m("CPSL", Some(115), G::Compare(true, true), IMM),
    m("IL", Some(2), G::Control(Flow::Il), NONE),
    m("ILC", Some(3), G::Control(Flow::Ilc), NONE),
    m("JMP", Some(4), G::Control(Flow::Jmp), NONE),
    m("JME", Some(5), G::Control(Flow::Jme), NONE),
    m("CJP", Some(510), G::Control(Flow::Cjp), NONE),
    m("CJPN", Some(511), G::Control(Flow::Cjpn), NONE),
    m("JMP0", Some(515), G::Control(Flow::Jmp0), NONE),
    m("JME0", Some(516), G::Control(Flow::Jme0), NONE),
    m("END", Some(1), G::Control(Flow::End), NONE),
    m("SBS", Some(91), G::Control(Flow::Sbs), UP),
    m("SBN", Some(92), G::Control(Flow::Sbn), NONE),
    m("RET", Some(93), G::Control(Flow::Ret), NONE),
    m("FOR", Some(503), G::Control(Flow::For), NONE),
    m("NEXT", Some(504), G::Control(Flow::Next), NONE),
    m("BREAK", Some(514), G::Control(Flow::Break), NONE),
];

/// Instructions of the CP series this front end recognises but does not lower yet (E011 with
/// "not supported yet"), with their function codes.
pub const NOT_YET: &[(&str, u16)] = &[("STEP", 8), ("SNXT", 9), ("BPRG", 96), ("BEND", 801)];

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

/// The arithmetic instruction named `mnemonic`.
pub fn arith(mnemonic: &str) -> Option<OmronArith> {
    OmronArith::ALL
        .iter()
        .copied()
        .find(|a| a.mnemonic() == mnemonic)
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
        assert!(lookup("STEP").is_none());
    }
}
