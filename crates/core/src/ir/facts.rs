//! The structural facts of every op, stated once: where control goes next ([`Op::successors`]),
//! what it does to the logic stack ([`Op::stack_effect`]) and to the gate ([`Op::gate_effect`]),
//! which FOR loop a jump would enter ([`loop_entered_by`]) and which subroutine it calls
//! ([`Op::callee`]). The verifier, the JIT's analyses and the front ends' stack checks read
//! these instead of matching on ops themselves, so a new op states its facts here and nowhere else.

use super::{CounterKind, Op, Pou};
use crate::index::PouId;

/// Where control can go after an op: the next op, and one branch target (an op index, where
/// `ops.len()` is the POU's end).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Successors {
    /// Control may continue with the next op (for the last op: the POU's end).
    pub falls_through: bool,
    /// The op control may branch to instead.
    pub branch: Option<usize>,
}

impl Successors {
    /// The successor op indices of op `i`, the fall-through first.
    pub fn indices(self, i: usize) -> impl Iterator<Item = usize> {
        self.falls_through
            .then_some(i + 1)
            .into_iter()
            .chain(self.branch)
    }

    /// Whether control only ever falls through to the next op.
    pub fn is_straight(self) -> bool {
        self.falls_through && self.branch.is_none()
    }
}

/// What an op does to the logic stack, as a transfer of levels. On entry `S0` is the top; the op
/// reads some levels, removes `pops` levels from the top, then pushes `pushes` levels (whose
/// values are computed from the levels in `feeds`, its operands and memory). Levels below the
/// popped ones move by `pushes - pops`; a pop fills the bottom with 0, a push loses the bottom.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StackEffect {
    /// Levels (bit `k` = `S_k` on entry) the pushed values are computed from.
    pub feeds: u16,
    /// Levels read for the op's own effect (power flow, counter inputs, an edge's memory
    /// update), whether or not a later op reads the result.
    pub uses: u16,
    /// Levels removed from the top.
    pub pops: u8,
    /// Levels then pushed.
    pub pushes: u8,
}

impl StackEffect {
    /// Reads the power flow (`S0`) and leaves the stack as it is: outputs, boxes, jumps.
    const CONSUMER: StackEffect = StackEffect::uses(0b1);
    /// Replaces the top with a value computed from it (`A`, `O`, `NOT`, `EU`, `AENO`).
    const REPLACE_TOP: StackEffect = StackEffect {
        feeds: 0b1,
        uses: 0,
        pops: 1,
        pushes: 1,
    };
    /// Touches nothing.
    const NONE: StackEffect = StackEffect::uses(0);

    const fn uses(levels: u16) -> StackEffect {
        StackEffect {
            feeds: 0,
            uses: levels,
            pops: 0,
            pushes: 0,
        }
    }

    const fn push(feeds: u16) -> StackEffect {
        StackEffect {
            feeds,
            uses: 0,
            pops: 0,
            pushes: 1,
        }
    }

    /// How many levels from the top the op reads (0 when it reads none).
    pub fn levels_read(self) -> u8 {
        (16 - (self.feeds | self.uses).leading_zeros()) as u8
    }

    /// Whether the op pushes a value that does not depend on the stack (a fresh load).
    pub fn pushes_fresh(self) -> bool {
        self.pushes > 0 && self.feeds == 0 && self.pops == 0
    }

    /// Backward liveness through the op: given which levels may be read after it (`live_out`,
    /// bit `k` = `S_k`), which levels may be read on entry, within a stack of `mask` levels.
    pub fn live_in(self, live_out: u32, mask: u32) -> u32 {
        let pushed = (1u32 << self.pushes) - 1;
        let fed = if live_out & pushed != 0 {
            u32::from(self.feeds)
        } else {
            0
        };
        let moved = (live_out >> self.pushes) << self.pops;
        mask & (u32::from(self.uses) | fed | moved)
    }
}

/// What an op does to the gate (the SCR enable / Omron interlock byte that power flow is ANDed
/// with).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GateEffect {
    /// Leaves it as it is.
    Keeps,
    /// Sets it to 1 (`SCRE`, `ILC`, a task start).
    Opens,
    /// Sets it to a value known only at run time (`LSCR`, `IL`).
    Sets,
    /// Whatever the callee leaves it at (`CALL`; the JIT's analysis follows the callee).
    Callee,
}

impl Op {
    /// Where control may go after this op of `pou`. A target outside the POU (only in a program
    /// the verifier rejects) is clamped to its end.
    pub fn successors(&self, pou: &Pou) -> Successors {
        let end = pou.ops.len();
        let to = |t: usize| Some(t.min(end));
        let (falls_through, branch) = match self {
            Op::Jump(l) => (
                true,
                to(pou.labels.get(l.index()).map_or(end, |t| t.index())),
            ),
            Op::Return { conditional } | Op::End { conditional } => (*conditional, None),
            Op::For { next, .. } => (true, to(next.index() + 1)),
            Op::Next { head } => (true, to(head.index() + 1)),
            Op::ScrCondEnd { end: scre } => (true, to(scre.index())),
            _ => (true, None),
        };
        Successors {
            falls_through,
            branch,
        }
    }

    /// Whether the op may leave its POU (`RET`, `CRET`, `END`, `MEND`).
    pub fn may_exit(&self) -> bool {
        matches!(self, Op::Return { .. } | Op::End { .. })
    }

    /// The subroutine the op calls (`CALL`, with or without parameters).
    pub fn callee(&self) -> Option<PouId> {
        match self {
            Op::Call(p) => Some(*p),
            Op::CallArgs(c) => Some(c.callee),
            _ => None,
        }
    }

    /// The op's effect on the gate.
    pub fn gate_effect(&self) -> GateEffect {
        match self {
            Op::ScrBegin { .. } | Op::Interlock => GateEffect::Sets,
            Op::ScrEnd | Op::InterlockEnd | Op::TaskStart => GateEffect::Opens,
            Op::Call(_) | Op::CallArgs(_) => GateEffect::Callee,
            _ => GateEffect::Keeps,
        }
    }

    /// The op's effect on the logic stack.
    pub fn stack_effect(&self) -> StackEffect {
        match self {
            Op::Load(_) | Op::ScrBegin { .. } => StackEffect::push(0),
            Op::And(_) | Op::Or(_) | Op::Not | Op::AndEno => StackEffect::REPLACE_TOP,
            Op::Edge { .. } => StackEffect {
                uses: 0b1,
                ..StackEffect::REPLACE_TOP
            },
            Op::AndBlock | Op::OrBlock => StackEffect {
                feeds: 0b11,
                uses: 0,
                pops: 2,
                pushes: 1,
            },
            Op::Dup => StackEffect::push(0b1),
            Op::ReadSecond => StackEffect {
                feeds: 0b10,
                ..StackEffect::REPLACE_TOP
            },
            Op::Pop => StackEffect {
                feeds: 0,
                uses: 0,
                pops: 1,
                pushes: 0,
            },
            Op::Pick(k) => StackEffect::push(1u16.checked_shl(u32::from(*k)).unwrap_or(0)),
            // NEXT leaves S0 = 1 whichever way it goes.
            Op::Next { .. } => StackEffect {
                feeds: 0,
                ..StackEffect::REPLACE_TOP
            },
            Op::Counter { kind, .. } => StackEffect::uses(match kind {
                CounterKind::Up | CounterKind::Down => 0b11,
                CounterKind::UpDown => 0b111,
            }),
            Op::OmronTimer { kind, .. } => StackEffect::uses((1 << kind.conditions()) - 1),
            Op::OmronCounter { kind, .. } => StackEffect::uses((1 << kind.conditions()) - 1),
            // FOR sets S0 = 1 only when it skips the loop; S0 is its power flow anyway.
            Op::Assign { .. }
            | Op::SetRange { .. }
            | Op::ResetTimers { .. }
            | Op::ResetCounters { .. }
            | Op::Timer { .. }
            | Op::Box(_)
            | Op::Jump(_)
            | Op::Call(_)
            | Op::CallArgs(_)
            | Op::Stop
            | Op::Wdr
            | Op::For { .. }
            | Op::ScrTransition { .. }
            | Op::ScrCondEnd { .. }
            | Op::Interlock
            | Op::Omron(_) => StackEffect::CONSUMER,
            Op::Return { conditional } | Op::End { conditional } => {
                if *conditional {
                    StackEffect::CONSUMER
                } else {
                    StackEffect::NONE
                }
            }
            Op::Label(_) | Op::Nop | Op::ScrEnd | Op::InterlockEnd | Op::TaskStart => {
                StackEffect::NONE
            }
        }
    }
}

/// The innermost FOR loop whose body contains op `i`, as `(head, next)` op indices.
pub fn enclosing_loop(pou: &Pou, i: usize) -> Option<(usize, usize)> {
    enclosing_loops(pou, i).next()
}

/// Every FOR loop whose body (the ops strictly between FOR and NEXT) contains op `i`, innermost
/// first.
fn enclosing_loops(pou: &Pou, i: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
    // Loops are properly nested (the verifier checks FOR/NEXT pairing), so the enclosing ones
    // are the FORs before `i` whose NEXT lies after it.
    pou.ops[..i.min(pou.ops.len())]
        .iter()
        .enumerate()
        .rev()
        .filter_map(move |(h, op)| match op {
            Op::For { next, .. } if next.index() > i => Some((h, next.index())),
            _ => None,
        })
}

/// The FOR loop that a jump at op `from` to op `to` would enter from outside, as `(head, next)`:
/// the outermost loop whose body contains `to` but not `from`. NEXT would then run with no active
/// FOR (spec a5-stl §2.5), so such a jump is rejected at compile time.
pub fn loop_entered_by(pou: &Pou, from: usize, to: usize) -> Option<(usize, usize)> {
    enclosing_loops(pou, to)
        .filter(|&(head, next)| !(head < from && from < next))
        .last()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::test_ops::{for_, jmp, lbl, next, pou};

    #[test]
    fn live_in_matches_the_stack_rules() {
        let full = 0x1FF;
        // LD pushes: level k after is level k-1 before; the bottom falls off.
        assert_eq!(StackEffect::push(0).live_in(0b110, full), 0b11);
        // ALD: a live result needs both operands; the rest moves up.
        let ald = Op::AndBlock.stack_effect();
        assert_eq!(ald.live_in(0b1, full), 0b11);
        assert_eq!(ald.live_in(0b10, full), 0b100);
        // LRD reads level 1 only if its result is read.
        assert_eq!(Op::ReadSecond.stack_effect().live_in(0, full), 0);
        assert_eq!(Op::ReadSecond.stack_effect().live_in(1, full), 0b10);
        // LPP: level 0 dies.
        assert_eq!(Op::Pop.stack_effect().live_in(0b1, full), 0b10);
        // LDS 3 copies level 3.
        assert_eq!(Op::Pick(3).stack_effect().live_in(0b1, full), 0b1000);
        // A coil reads the power flow even if nothing reads the stack later.
        let coil = StackEffect::CONSUMER;
        assert_eq!(coil.live_in(0, full), 1);
        assert_eq!(Op::Pick(3).stack_effect().levels_read(), 4);
    }

    #[test]
    fn successors_follow_jumps_loops_and_exits() {
        let p = pou(
            vec![
                jmp(0),
                for_(3),
                lbl(0),
                next(1),
                Op::End { conditional: false },
            ],
            vec![2],
        );
        let s = |i: usize| p.ops[i].successors(&p).indices(i).collect::<Vec<_>>();
        assert_eq!(s(0), [1, 2]);
        assert_eq!(s(1), [2, 4]);
        assert_eq!(s(3), [4, 2]);
        assert_eq!(s(4), Vec::<usize>::new());
        assert!(p.ops[2].successors(&p).is_straight());
    }

    #[test]
    fn a_jump_into_a_loop_body_enters_the_outermost_loop_it_is_not_in() {
        // 0 JMP, 1 FOR, 2 JMP, 3 FOR, 4 LBL, 5 NEXT, 6 NEXT, 7 JMP
        let p = pou(
            vec![
                jmp(0),
                for_(6),
                jmp(0),
                for_(5),
                lbl(0),
                next(3),
                next(1),
                jmp(0),
            ],
            vec![4],
        );
        assert_eq!(loop_entered_by(&p, 0, 4), Some((1, 6)));
        assert_eq!(loop_entered_by(&p, 7, 4), Some((1, 6)));
        // From the outer body into the inner one.
        assert_eq!(loop_entered_by(&p, 2, 4), Some((3, 5)));
        assert_eq!(enclosing_loop(&p, 4), Some((3, 5)));
        assert_eq!(enclosing_loop(&p, 2), Some((1, 6)));
        assert_eq!(loop_entered_by(&p, 0, 7), None);
    }
}
