//! The user-memory check of seed §1-1-11 (omron-cp.md §5, OMR-E035): every instruction of the
//! project takes its steps (`mnemonics::TABLE`'s `steps` column, [uncertain]) plus one for each
//! constant operand of a double-length instruction, all tasks together, against the profile's
//! capacity (`OmronAreas::program_steps`).

use crate::lexer::Line;
use crate::lower::Lowerer;
use crate::mnemonics;
use stljit_core::ir::{OmronBox, Op, Operand};
use stljit_source::{Code, Diagnostic, Span};

/// The running step count of the project.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Capacity {
    /// Steps so far.
    steps: u32,
    /// The first instruction that did not fit, if any.
    full_at: Option<Span>,
}

impl Lowerer<'_> {
    /// Counts the steps of a recognised instruction line (lowered or not: code after END takes
    /// user memory too).
    pub(crate) fn count_steps(&mut self, l: &Line) {
        if let Some(steps) = mnemonics::steps(&l.mnemonic) {
            self.add_steps(u32::from(steps), l);
        }
    }

    /// One more step for each constant operand of a double-length instruction among the ops
    /// this line lowered to.
    pub(crate) fn count_constant_steps(&mut self, ops: &[Op], l: &Line) {
        let extra: u32 = ops.iter().map(double_constants).sum();
        if extra > 0 {
            self.add_steps(extra, l);
        }
    }

    fn add_steps(&mut self, n: u32, l: &Line) {
        let cap = &mut self.capacity;
        cap.steps = cap.steps.saturating_add(n);
        if cap.steps > self.cx.profile.omron.program_steps && cap.full_at.is_none() {
            cap.full_at = Some(self.cx.span(&l.head));
        }
    }

    /// E035 at the first instruction that did not fit.
    pub(crate) fn check_capacity(&mut self) {
        let Some(at) = self.capacity.full_at else {
            return;
        };
        let (need, model) = (self.capacity.steps, self.cx.profile.model);
        let max = self.cx.profile.omron.program_steps;
        let msg = format!(
            "line {}: program needs {need} steps, {model} allows {max}; the user memory is full from this instruction on",
            at.line
        );
        self.cx
            .diags
            .push(Diagnostic::new(Code::OmrCapacity, at, "", msg));
    }
}

/// Constant operands of a double-length data instruction (MOVL, CMPL, CPSL, the `L`
/// arithmetic and comparison contacts).
fn double_constants(op: &Op) -> u32 {
    let Op::Omron(b @ (OmronBox::Move { .. } | OmronBox::Compare { .. } | OmronBox::Arith { .. })) =
        op
    else {
        return 0;
    };
    let o = b.operands();
    if o.src_words < 2 {
        return 0;
    }
    o.sources
        .iter()
        .filter(|s| matches!(s, Some(Operand::Const(_))))
        .count() as u32
}
