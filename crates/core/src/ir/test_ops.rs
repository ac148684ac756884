//! Builders for the IR unit tests of this module: a main POU from ops and label positions, and
//! the control ops the structural tests need.

use super::{Loc, Op, Operand, Pou, PouKind, Program, SrcLoc};
use crate::{Area, LabelId, OpIdx, ProfileId};

/// A main POU with `ops` and labels at `labels`.
pub(super) fn pou(ops: Vec<Op>, labels: Vec<usize>) -> Pou {
    Pou {
        name: "MAIN".into(),
        kind: PouKind::Main,
        locs: vec![SrcLoc::default(); ops.len()],
        ops,
        labels: labels.into_iter().map(OpIdx::new).collect(),
    }
}

/// An A5 program whose only POU is [`pou`]`(ops, labels)`.
pub(super) fn program(ops: Vec<Op>, labels: Vec<usize>) -> Program {
    Program {
        profile: ProfileId::A5,
        pous: vec![pou(ops, labels)],
        timers: vec![],
        counters: vec![],
        edges: vec![],
        logic_stack_depth: 9,
        files: vec![],
        data: Vec::new(),
    }
}

/// `FOR VW0, 0, 0`, closed by the NEXT at `next`.
pub(super) fn for_(next: usize) -> Op {
    Op::For {
        index: vw(0),
        init: Operand::Const(0),
        limit: Operand::Const(0),
        next: OpIdx::new(next),
    }
}

/// `NEXT` of the FOR at `head`.
pub(super) fn next(head: usize) -> Op {
    Op::Next {
        head: OpIdx::new(head),
    }
}

/// `JMP` to label `l`.
pub(super) fn jmp(l: usize) -> Op {
    Op::Jump(LabelId::new(l))
}

/// `LBL l`.
pub(super) fn lbl(l: usize) -> Op {
    Op::Label(LabelId::new(l))
}

/// The word `VW offset`.
pub(super) fn vw(offset: u32) -> Operand {
    Operand::Mem(Loc {
        area: Area::V,
        offset,
    })
}
