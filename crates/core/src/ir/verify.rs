//! The IR verifier: the structural rules every engine relies on, stated once. A front end's
//! checked program always passes; both engines call [`verify`] before they run or compile a
//! program, so a malformed one (hand-built, fuzzed, or from a front-end bug) is an error, never
//! a failing lookup or a miscompilation.
//!
//! The rules: there is a main POU; the logic stack has 1 to [`MAX_STACK_DEPTH`] levels; every
//! POU has one source location per op and fewer than 2^31 ops; every label position holds its
//! `LBL`; jumps name known labels and never enter a FOR body from outside; calls name a
//! subroutine (never the main program or an interrupt routine) and a call's formal parameters
//! lie in L memory; interrupt routines have distinct numbers up to [`MAX_ROUTINE`] on a profile
//! with interrupts, ATCH names one of them, and every event an interrupt op names is one of the
//! profile's; FOR and NEXT name each other and nest properly; CSCRE
//! names a SCRE; edge slots exist, and the program has no more of them than its profile allows;
//! every direct location an op names ([`Op::operand_uses`], [`Op::bit_uses`]) lies inside its
//! area of the profile's layout, no op writes a constant, and every timer and counter an op runs
//! is declared with that kind; timers and counters are declared once each, within the profile. Pointers are the only run-time-checked accesses.

use super::facts::loop_entered_by;
use super::uses::Access;
use super::{BoxOp, IndexOffset, IntOp, OmronRef, Op, Operand, Pou, PouKind, Program};
use crate::area::{Area, Width};
use crate::interrupt::MAX_ROUTINE;
use crate::layout::Layout;
use crate::profile::Family;
use std::fmt;

/// The deepest logic stack an engine supports (the interpreter keeps it in a `u16`).
pub const MAX_STACK_DEPTH: u8 = 16;

/// Why a program is malformed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum VerifyError {
    /// The program has no POU (the main program is missing).
    NoMain,
    /// `logic_stack_depth` is 0 or above [`MAX_STACK_DEPTH`].
    StackDepth(u8),
    /// More edge slots than the profile's `max_edges`.
    TooManyEdges(usize),
    /// A timer or counter declaration names an object the profile does not have, or one
    /// declared twice.
    BadDeclaration {
        /// `TimerBit` for a timer, `CounterBit` for a counter.
        area: Area,
        /// Its number.
        number: u16,
    },
    /// Initial V values (`Program::data`) run past the end of V.
    DataOutOfArea {
        /// The first V byte.
        offset: u32,
        /// Bytes.
        len: u32,
    },
    /// A POU breaks a rule.
    Pou {
        /// POU index.
        pou: usize,
        /// The rule.
        rule: PouRule,
    },
    /// An op breaks a rule.
    Op {
        /// POU index.
        pou: usize,
        /// Op index.
        op: usize,
        /// The rule.
        rule: OpRule,
    },
}

/// A rule of a whole POU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PouRule {
    /// `locs` and `ops` differ in length.
    LocsLength,
    /// 2^31 ops or more.
    TooLong,
    /// An interrupt routine whose number is above [`MAX_ROUTINE`] or used twice, or on a
    /// profile without interrupts.
    InterruptNumber,
}

/// A rule of one op.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpRule {
    /// A label's recorded position does not hold its `LBL`.
    LabelPosition,
    /// A jump names a label the POU does not have.
    UnknownLabel,
    /// A jump enters the body of the FOR loop at `head` from outside it.
    JumpIntoLoop {
        /// The loop's FOR.
        head: usize,
    },
    /// A call names no POU, the main program or an interrupt routine.
    BadCall,
    /// A call's formal parameter is not a location of area `L`.
    FormalNotLocal,
    /// ATCH names a POU that is not an interrupt routine.
    BadRoutine,
    /// An interrupt op names an event the profile does not have.
    UnknownEvent(u8),
    /// FOR does not name a NEXT that names it back, after it.
    ForWithoutNext,
    /// NEXT does not name a FOR that names it back, before it.
    NextWithoutFor,
    /// Two loops overlap without nesting.
    LoopsOverlap,
    /// CSCRE does not name a SCRE.
    CondEndWithoutEnd,
    /// An edge slot beyond `Program::edges`.
    UnknownEdge,
    /// A direct location (or a pointer's own dword) runs past the end of its area.
    OutOfArea {
        /// The area.
        area: Area,
        /// The first byte.
        offset: u32,
        /// Bytes accessed.
        len: u32,
    },
    /// `&` of an area pointers cannot address.
    PointerToArea(Area),
    /// An op writes a constant or an address constant.
    WriteToConstant,
    /// A timer or counter op whose object is not declared with that kind.
    UndeclaredObject,
    /// An op writes the Omron condition flags or system bits (`Area::Flags`), which only the
    /// scan cycle and the Omron boxes' own flag rules may change.
    WriteToSystemBits,
    /// An op of one PLC family's execution model (Omron interlocks, timers, counters and
    /// flag boxes; S7 SCR segments) in a program for a profile of the other.
    WrongFamily,
    /// A PID loop number above 7.
    PidLoop,
    /// HDEF/HSC of a counter the profile does not have.
    HscNumber,
    /// HDEF with a mode the counter does not accept.
    HscMode,
    /// PLS of a pulse channel the profile does not have.
    PulseChannel,
    /// A constant string longer than [`super::MAX_STRING`] bytes.
    StringTooLong,
}

impl fmt::Display for VerifyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VerifyError::NoMain => f.write_str("program has no main POU"),
            VerifyError::StackDepth(d) => {
                write!(f, "logic stack depth {d} not in 1..={MAX_STACK_DEPTH}")
            }
            VerifyError::TooManyEdges(n) => write!(f, "{n} edge slots exceed the profile's limit"),
            VerifyError::BadDeclaration { area, number } => {
                write!(
                    f,
                    "{area:?} {number} is declared twice or not in the profile"
                )
            }
            VerifyError::DataOutOfArea { offset, len } => {
                write!(f, "{len} initial byte(s) at V {offset} run past the area")
            }
            VerifyError::Pou { pou, rule } => {
                let what = match rule {
                    PouRule::LocsLength => "one source location per op",
                    PouRule::TooLong => "fewer than 2^31 ops",
                    PouRule::InterruptNumber => {
                        "a distinct interrupt number on a profile with interrupts"
                    }
                };
                write!(f, "pou{pou} must have {what}")
            }
            VerifyError::Op { pou, op, rule } => {
                write!(f, "pou{pou} op{op}: ")?;
                match rule {
                    OpRule::LabelPosition => f.write_str("label position does not hold its LBL"),
                    OpRule::UnknownLabel => f.write_str("unknown label"),
                    OpRule::JumpIntoLoop { head } => {
                        write!(f, "jump into the body of the FOR loop at op{head}")
                    }
                    OpRule::BadCall => {
                        f.write_str("call of an unknown POU, of main or of an interrupt routine")
                    }
                    OpRule::FormalNotLocal => {
                        f.write_str("a call's formal parameter is not in L memory")
                    }
                    OpRule::BadRoutine => {
                        f.write_str("ATCH of a POU that is not an interrupt routine")
                    }
                    OpRule::UnknownEvent(e) => write!(f, "event {e} is not one of the profile's"),
                    OpRule::ForWithoutNext => f.write_str("FOR without its NEXT"),
                    OpRule::NextWithoutFor => f.write_str("NEXT without its FOR"),
                    OpRule::LoopsOverlap => f.write_str("FOR loops overlap without nesting"),
                    OpRule::CondEndWithoutEnd => f.write_str("CSCRE without its SCRE"),
                    OpRule::UnknownEdge => f.write_str("edge slot not declared"),
                    OpRule::OutOfArea { area, offset, len } => {
                        write!(f, "{len} byte(s) at {area:?} {offset} run past the area")
                    }
                    OpRule::PointerToArea(a) => write!(f, "no pointer can address area {a:?}"),
                    OpRule::WriteToConstant => f.write_str("writes a constant"),
                    OpRule::UndeclaredObject => {
                        f.write_str("timer or counter not declared with this kind")
                    }
                    OpRule::WriteToSystemBits => {
                        f.write_str("writes the Omron condition flags or system bits")
                    }
                    OpRule::WrongFamily => {
                        f.write_str("op of another PLC family than the program's profile")
                    }
                    OpRule::PidLoop => f.write_str("PID loop number above 7"),
                    OpRule::HscNumber => f.write_str("no such high-speed counter on the CPU"),
                    OpRule::HscMode => f.write_str("a mode the high-speed counter does not accept"),
                    OpRule::PulseChannel => f.write_str("no such pulse output on the CPU"),
                    OpRule::StringTooLong => f.write_str("constant string longer than 254 bytes"),
                }
            }
        }
    }
}

impl std::error::Error for VerifyError {}

/// Checks every structural rule of `program` (see the module documentation).
pub fn verify(program: &Program) -> Result<(), VerifyError> {
    if program.pous.is_empty() {
        return Err(VerifyError::NoMain);
    }
    if !(1..=MAX_STACK_DEPTH).contains(&program.logic_stack_depth) {
        return Err(VerifyError::StackDepth(program.logic_stack_depth));
    }
    if program.edges.len() > usize::from(program.profile.profile().max_edges) {
        return Err(VerifyError::TooManyEdges(program.edges.len()));
    }
    let layout = Layout::of(program.profile);
    declarations(program, &layout)?;
    let interrupts = program.profile.profile().interrupts;
    let mut numbers = std::collections::HashSet::new();
    for d in &program.data {
        let len = u32::try_from(d.bytes.len()).unwrap_or(u32::MAX);
        if d.offset
            .checked_add(len)
            .is_none_or(|end| end > layout.area_size(Area::V))
        {
            return Err(VerifyError::DataOutOfArea {
                offset: d.offset,
                len,
            });
        }
    }
    for (p, pou) in program.pous.iter().enumerate() {
        if let Some(n) = pou.kind.interrupt()
            && (n > MAX_ROUTINE || !numbers.insert(n) || !interrupts.any())
        {
            return Err(VerifyError::Pou {
                pou: p,
                rule: PouRule::InterruptNumber,
            });
        }
        verify_pou(program, &layout, pou).map_err(|e| match e {
            Err(rule) => VerifyError::Pou { pou: p, rule },
            Ok((op, rule)) => VerifyError::Op { pou: p, op, rule },
        })?;
    }
    Ok(())
}

/// One POU's rules; the error is a POU rule, or an op index and its rule.
fn verify_pou(
    program: &Program,
    layout: &Layout,
    pou: &Pou,
) -> Result<(), Result<(usize, OpRule), PouRule>> {
    let n = pou.ops.len();
    if pou.locs.len() != n {
        return Err(Err(PouRule::LocsLength));
    }
    if n >= 1 << 31 {
        return Err(Err(PouRule::TooLong));
    }
    for (label, at) in pou.labels.iter().enumerate() {
        if !matches!(pou.ops.get(at.index()), Some(Op::Label(l)) if l.index() == label) {
            return Err(Ok((at.index().min(n), OpRule::LabelPosition)));
        }
    }
    // Open loops, innermost last: a NEXT must close the innermost one.
    let mut open: Vec<usize> = Vec::new();
    for (i, op) in pou.ops.iter().enumerate() {
        let bad = |rule| Err(Ok((i, rule)));
        match op {
            Op::Jump(l) if l.index() >= pou.labels.len() => return bad(OpRule::UnknownLabel),
            _ if op.callee().is_some_and(|c| {
                !matches!(
                    program.pous.get(c.index()).map(|p| p.kind),
                    Some(PouKind::Subroutine(_))
                )
            }) =>
            {
                return bad(OpRule::BadCall);
            }
            Op::CallArgs(c) if !c.args.iter().all(super::Arg::formal_is_local) => {
                return bad(OpRule::FormalNotLocal);
            }
            Op::Interrupt(IntOp::Attach { routine, .. })
                if !matches!(
                    program.pous.get(routine.index()).map(|p| p.kind),
                    Some(PouKind::Interrupt(_))
                ) =>
            {
                return bad(OpRule::BadRoutine);
            }
            Op::For { next, .. } => {
                let paired = matches!(pou.ops.get(next.index()), Some(Op::Next { head }) if head.index() == i);
                if !paired || next.index() <= i {
                    return bad(OpRule::ForWithoutNext);
                }
                open.push(i);
            }
            Op::Next { head } => {
                let paired = matches!(pou.ops.get(head.index()), Some(Op::For { next, .. }) if next.index() == i);
                if !paired || head.index() >= i {
                    return bad(OpRule::NextWithoutFor);
                }
                if open.pop() != Some(head.index()) {
                    return bad(OpRule::LoopsOverlap);
                }
            }
            Op::ScrCondEnd { end } if !matches!(pou.ops.get(end.index()), Some(Op::ScrEnd)) => {
                return bad(OpRule::CondEndWithoutEnd);
            }
            Op::Edge { slot, .. } if slot.index() >= program.edges.len() => {
                return bad(OpRule::UnknownEdge);
            }
            _ => {}
        }
        locations(program, layout, op).map_err(|rule| Ok((i, rule)))?;
    }
    // Loops nest properly now, so the loop a jump enters is well defined.
    for (i, op) in pou.ops.iter().enumerate() {
        if let Op::Jump(l) = op {
            let target = pou.label_target(*l).index();
            if let Some((head, _)) = loop_entered_by(pou, i, target) {
                return Err(Ok((i, OpRule::JumpIntoLoop { head })));
            }
        }
    }
    Ok(())
}

/// Every declared timer and counter exists in the profile, once (the engines index their state
/// blocks by the number).
fn declarations(program: &Program, layout: &Layout) -> Result<(), VerifyError> {
    let timers = program.timers.iter().map(|t| (Area::TimerBit, t.id.0));
    let counters = program.counters.iter().map(|c| (Area::CounterBit, c.id.0));
    let mut seen = std::collections::HashSet::new();
    for (area, number) in timers.chain(counters) {
        if u32::from(number) >= layout.area_size(area) || !seen.insert((area, number)) {
            return Err(VerifyError::BadDeclaration { area, number });
        }
    }
    Ok(())
}

/// The location rules of one op: direct operands and bits inside their areas, no write to a
/// constant, timers and counters declared with the kind the op runs.
fn locations(program: &Program, layout: &Layout, op: &Op) -> Result<(), OpRule> {
    let inside = |area: Area, offset: u32, len: u32| {
        let fits = offset
            .checked_add(len)
            .is_some_and(|end| end <= layout.area_size(area));
        if fits {
            Ok(())
        } else {
            Err(OpRule::OutOfArea { area, offset, len })
        }
    };
    let params = match op {
        Op::CallArgs(c) => c.args.as_slice(),
        _ => &[],
    };
    let param_uses = params
        .iter()
        .flat_map(|a| a.actual_use().into_iter().chain(a.formal_use()));
    for u in op.operand_uses().iter().chain(param_uses) {
        match u.operand {
            Operand::Mem(l) => inside(l.area, l.offset, u.width.bytes())?,
            Operand::Indirect(l) => inside(l.area, l.offset, Width::DWord.bytes())?,
            Operand::AddressOf(l) => {
                if l.area.pointer_code().is_none() {
                    return Err(OpRule::PointerToArea(l.area));
                }
                inside(l.area, l.offset, 1)?;
            }
            Operand::Const(_) => {}
            Operand::Omron(r) => {
                if !matches!(op, Op::Omron(_)) {
                    return Err(OpRule::WrongFamily);
                }
                match r {
                    OmronRef::DmBinary(n) | OmronRef::DmBcd(n) => {
                        inside(Area::Dm, 2 * u32::from(n), 2)?;
                    }
                    OmronRef::Index { ir, offset, .. } => {
                        inside(Area::IndexReg, 4 * u32::from(ir), 4)?;
                        if let IndexOffset::Dr(m) = offset {
                            inside(Area::DataReg, 2 * u32::from(m), 2)?;
                        }
                    }
                }
            }
        }
        if u.access != Access::Read && matches!(u.operand, Operand::Mem(l) if l.area == Area::Flags)
        {
            return Err(OpRule::WriteToSystemBits);
        }
        let constant = matches!(u.operand, Operand::Const(_) | Operand::AddressOf(_));
        if constant && u.access != Access::Read {
            return Err(OpRule::WriteToConstant);
        }
    }
    for (b, access) in op.bit_uses() {
        if access != Access::Read && b.area == Area::Flags {
            return Err(OpRule::WriteToSystemBits);
        }
        if b.bit > 7 {
            return Err(OpRule::OutOfArea {
                area: b.area,
                offset: b.byte,
                len: 1,
            });
        }
        inside(b.area, b.byte, 1)?;
    }
    let family = layout.profile.profile().family;
    let op_family = match op {
        // The immediate I/O copies are the S7 `BIR`/`BIW` and Omron's `!` word refresh.
        Op::Box(BoxOp::ImmediateRead { .. } | BoxOp::ImmediateWrite { .. }) => None,
        Op::Interlock
        | Op::InterlockEnd
        | Op::TaskStart
        | Op::OmronTimer { .. }
        | Op::OmronCounter { .. }
        | Op::Omron(_) => Some(Family::Omron),
        Op::ScrBegin { .. }
        | Op::ScrTransition { .. }
        | Op::ScrCondEnd { .. }
        | Op::ScrEnd
        | Op::Timer { .. }
        | Op::Counter { .. }
        | Op::Interrupt(_)
        | Op::Box(_)
        | Op::Ext(_)
        | Op::StrCompare(_) => Some(Family::S7),
        _ => None,
    };
    if op_family.is_some_and(|f| f != family) {
        return Err(OpRule::WrongFamily);
    }
    if let Op::Interrupt(i) = op
        && let Some(e) = i.event()
        && !layout.profile.profile().interrupts.has(e)
    {
        return Err(OpRule::UnknownEvent(e));
    }
    let declared = match op {
        Op::OmronTimer { timer, .. } => {
            inside(Area::TimerBit, u32::from(timer.0), 1)?;
            true
        }
        Op::OmronCounter { counter, .. } => {
            inside(Area::CounterBit, u32::from(counter.0), 1)?;
            true
        }
        Op::Timer { kind, timer, .. } => program
            .timers
            .iter()
            .any(|t| t.id == *timer && t.kind == *kind),
        Op::Counter { kind, counter, .. } => program
            .counters
            .iter()
            .any(|c| c.id == *counter && c.kind == *kind),
        Op::Box(super::BoxOp::ImmediateRead { input, .. }) => {
            inside(Area::I, *input, 1)?;
            true
        }
        Op::Box(super::BoxOp::ImmediateWrite { output, .. }) => {
            inside(Area::Q, *output, 1)?;
            true
        }
        Op::ResetTimers { first, .. } => {
            inside(Area::TimerBit, u32::from(first.0), 1)?;
            true
        }
        Op::ResetCounters { first, .. } => {
            inside(Area::CounterBit, u32::from(first.0), 1)?;
            true
        }
        Op::Ext(b) => {
            if matches!(**b, super::ExtBox::Pid { lp, .. } if lp > 7) {
                return Err(OpRule::PidLoop);
            }
            hsc_operands(b, layout.profile.profile())?;
            constant_strings(b.strings())?;
            true
        }
        Op::StrCompare(c) => {
            constant_strings(vec![&c.lhs, &c.rhs])?;
            true
        }
        _ => true,
    };
    if declared {
        Ok(())
    } else {
        Err(OpRule::UndeclaredObject)
    }
}

/// HDEF and HSC name a counter of the profile's table, HDEF a mode that counter accepts, PLS
/// a pulse channel of it (the runtime indexes their state by the number).
fn hsc_operands(b: &super::ExtBox, profile: &crate::CpuProfile) -> Result<(), OpRule> {
    let (counter, mode) = match *b {
        super::ExtBox::HscDefine { counter, mode } => (counter, Some(mode)),
        super::ExtBox::Hsc { counter } => (counter, None),
        super::ExtBox::Pls { channel } => {
            return match profile.pulse.get(channel) {
                Some(_) => Ok(()),
                None => Err(OpRule::PulseChannel),
            };
        }
        _ => return Ok(()),
    };
    let info = profile.hsc.get(counter).ok_or(OpRule::HscNumber)?;
    match mode {
        Some(m) if !info.has_mode(m) => Err(OpRule::HscMode),
        _ => Ok(()),
    }
}

/// Constant strings hold at most [`super::MAX_STRING`] bytes (their length byte is 0..=254).
fn constant_strings(strings: Vec<&super::StrArg>) -> Result<(), OpRule> {
    let too_long = strings
        .iter()
        .any(|s| matches!(s, super::StrArg::Const(b) if b.len() > super::MAX_STRING));
    if too_long {
        Err(OpRule::StringTooLong)
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::test_ops::{for_, jmp, lbl, next, program, vw};
    use crate::ir::{BoxOp, Loc};

    fn op_rule(p: &Program) -> Option<(usize, OpRule)> {
        match verify(p) {
            Err(VerifyError::Op { op, rule, .. }) => Some((op, rule)),
            Ok(()) => None,
            Err(e) => panic!("unexpected {e}"),
        }
    }

    #[test]
    fn well_formed_loops_and_jumps_pass() {
        let ok = program(
            vec![for_(3), jmp(0), lbl(0), next(0), jmp(1), lbl(1)],
            vec![2, 5],
        );
        assert_eq!(verify(&ok), Ok(()));
    }

    #[test]
    fn a_jump_into_a_loop_is_rejected() {
        let p = program(vec![jmp(0), for_(3), lbl(0), next(1)], vec![2]);
        assert_eq!(op_rule(&p), Some((0, OpRule::JumpIntoLoop { head: 1 })));
    }

    #[test]
    fn pairing_and_nesting_are_checked() {
        let nested = program(vec![for_(3), for_(2), next(1), next(0)], vec![]);
        assert_eq!(op_rule(&nested), None);
        let mut bad = nested.clone();
        bad.pous[0].ops = vec![for_(2), for_(3), next(0), next(1)];
        assert_eq!(op_rule(&bad), Some((2, OpRule::LoopsOverlap)));
        bad.pous[0].ops = vec![next(1), for_(0)];
        bad.pous[0].locs.truncate(2);
        assert_eq!(op_rule(&bad), Some((0, OpRule::NextWithoutFor)));
        bad.pous[0].locs.pop();
        assert_eq!(
            verify(&bad),
            Err(VerifyError::Pou {
                pou: 0,
                rule: PouRule::LocsLength
            })
        );
    }

    /// A call's parameters: formals in L and inside the frame, no constant as an OUT actual.
    #[test]
    fn call_parameters_are_checked() {
        use crate::ir::{Arg, ArgDir, ArgValue, CallArgs};
        let call = |dir, formal: Loc, actual| {
            let mut p = program(
                vec![Op::CallArgs(Box::new(CallArgs {
                    callee: crate::PouId::new(1),
                    args: vec![Arg {
                        dir,
                        value: ArgValue::Value {
                            width: Width::Word,
                            formal,
                            actual,
                        },
                    }],
                }))],
                vec![],
            );
            let mut sub = p.pous[0].clone();
            sub.kind = crate::ir::PouKind::Subroutine(0);
            sub.ops.clear();
            sub.locs.clear();
            p.pous.push(sub);
            op_rule(&p)
        };
        let l = |offset| Loc {
            area: Area::L,
            offset,
        };
        assert_eq!(call(ArgDir::In, l(0), Operand::Const(5)), None);
        assert_eq!(call(ArgDir::Out, l(62), vw(0)), None);
        assert_eq!(
            call(ArgDir::Out, l(0), Operand::Const(5)),
            Some((0, OpRule::WriteToConstant))
        );
        assert_eq!(
            call(ArgDir::In, l(63), vw(0)),
            Some((
                0,
                OpRule::OutOfArea {
                    area: Area::L,
                    offset: 63,
                    len: 2
                }
            ))
        );
        let v = Loc {
            area: Area::V,
            offset: 0,
        };
        assert_eq!(
            call(ArgDir::In, v, vw(0)),
            Some((0, OpRule::FormalNotLocal))
        );
    }

    #[test]
    fn references_are_checked() {
        let p = program(vec![jmp(3)], vec![]);
        assert_eq!(op_rule(&p), Some((0, OpRule::UnknownLabel)));
        let p = program(vec![Op::Call(crate::PouId::new(0))], vec![]);
        assert_eq!(op_rule(&p), Some((0, OpRule::BadCall)));
        let p = program(vec![Op::Nop], vec![0]);
        assert_eq!(op_rule(&p), Some((0, OpRule::LabelPosition)));
        let attach = |routine, event| Op::Interrupt(IntOp::Attach { routine, event });
        let mut p = program(vec![attach(crate::PouId(1), 10)], vec![]);
        let mut int = p.pous[0].clone();
        int.kind = PouKind::Interrupt(3);
        int.ops = vec![Op::Nop];
        int.locs.truncate(1);
        p.pous.push(int);
        assert_eq!(op_rule(&p), None);
        p.pous[0].ops[0] = attach(crate::PouId(1), 21); // A5: no T32 event
        assert_eq!(op_rule(&p), Some((0, OpRule::UnknownEvent(21))));
        p.pous[0].ops[0] = Op::Call(crate::PouId(1));
        assert_eq!(op_rule(&p), Some((0, OpRule::BadCall)));
        p.pous[0].ops[0] = attach(crate::PouId(0), 10);
        assert_eq!(op_rule(&p), Some((0, OpRule::BadRoutine)));
        p.pous[0].ops[0] = Op::Nop;
        p.pous.push(p.pous[1].clone());
        assert_eq!(
            verify(&p),
            Err(VerifyError::Pou {
                pou: 2,
                rule: PouRule::InterruptNumber
            })
        );
        let mut p = program(vec![], vec![]);
        p.logic_stack_depth = 17;
        assert_eq!(verify(&p), Err(VerifyError::StackDepth(17)));
        p.pous.clear();
        assert_eq!(verify(&p), Err(VerifyError::NoMain));
    }

    #[test]
    fn direct_locations_must_lie_inside_their_areas() {
        let mov = |src, dst| {
            Op::Box(BoxOp::Move {
                width: crate::Width::Word,
                src,
                dst,
            })
        };
        // A5: V has 2500 bytes, so VW2498 is the last word.
        assert_eq!(op_rule(&program(vec![mov(vw(0), vw(2498))], vec![])), None);
        assert_eq!(
            op_rule(&program(vec![mov(vw(0), vw(2499))], vec![])),
            Some((
                0,
                OpRule::OutOfArea {
                    area: Area::V,
                    offset: 2499,
                    len: 2
                }
            ))
        );
        let pointer = Operand::Indirect(Loc {
            area: Area::V,
            offset: 2497,
        });
        assert!(matches!(
            op_rule(&program(vec![mov(pointer, vw(0))], vec![])),
            Some((0, OpRule::OutOfArea { len: 4, .. }))
        ));
        assert_eq!(
            op_rule(&program(vec![mov(vw(0), Operand::Const(1))], vec![])),
            Some((0, OpRule::WriteToConstant))
        );
        let timer = Op::Timer {
            kind: crate::ir::TimerKind::On,
            timer: crate::TimerId(37),
            preset: Operand::Const(10),
        };
        assert_eq!(
            op_rule(&program(vec![timer], vec![])),
            Some((0, OpRule::UndeclaredObject))
        );
    }

    #[test]
    fn declarations_lie_within_the_profile() {
        let mut p = program(vec![], vec![]);
        p.timers.push(crate::ir::TimerDecl {
            id: crate::TimerId(64),
            kind: crate::ir::TimerKind::On,
            resolution: crate::profile::Resolution::Ms100,
        });
        assert_eq!(
            verify(&p),
            Err(VerifyError::BadDeclaration {
                area: Area::TimerBit,
                number: 64
            })
        );
        p.timers[0].id = crate::TimerId(63);
        assert_eq!(verify(&p), Ok(()));
        p.timers.push(p.timers[0]);
        assert!(matches!(
            verify(&p),
            Err(VerifyError::BadDeclaration { number: 63, .. })
        ));
    }
}
