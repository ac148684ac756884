//! The Omron CP ops for the interpreter: operands read as Omron values, then the runtime's
//! `omron_image` functions, which both engines share.

use crate::exec::Machine;
use crate::operand::Addr;
use stljit_core::Width;
use stljit_core::ir::{BoxOperands, Op, Operand};
use stljit_runtime::omron_image::{self, BoxOperand};

/// Words of an Omron operand as the IR width it is read at.
fn width_of(double: bool) -> Width {
    if double { Width::DWord } else { Width::Word }
}

impl Machine<'_> {
    /// The Omron value of `op`: a word, or a double word with its low 16 bits in the
    /// lower-numbered word (a location's big-endian dword swapped; constants are Omron values
    /// already). Omron operands are direct (the front end has no pointers yet), so an
    /// unresolvable one reads 0, as an illegal access does (omron-cp.md U14).
    fn omron_value(&self, op: &Operand, double: bool, frame: u32) -> u32 {
        let width = width_of(double);
        match self.resolve(op, width, frame, false) {
            Ok(a @ Addr::Image(_)) if double => omron_image::double_of_be(self.load(a, width)),
            Ok(a) => self.load(a, width),
            Err(_) => 0,
        }
    }

    /// Executes one Omron timer, counter or box op; `st` is the logic stack, `pf` the power
    /// flow.
    pub(crate) fn omron(&mut self, op: &Op, frame: u32, st: u16, pf: bool) {
        match op {
            Op::OmronTimer {
                kind,
                timer,
                set_value,
            } => {
                let gate = self.stateful_gate();
                let sv = self.omron_value(set_value, false, frame) as u16;
                omron_image::timer(self.img, self.layout, *kind, timer.0, st, gate, sv);
            }
            Op::OmronCounter {
                kind,
                counter,
                set_value,
            } => {
                let gate = self.stateful_gate();
                let sv = self.omron_value(set_value, false, frame) as u16;
                omron_image::counter(self.img, self.layout, *kind, counter.0, st, gate, sv);
            }
            Op::Omron(b) if pf => {
                let code = omron_image::box_code(b);
                let BoxOperands {
                    sources: [lhs, rhs],
                    dst,
                    src_words,
                    dst_words,
                } = b.operands();
                let source = |o: Option<Operand>| match o {
                    None => BoxOperand::Absent,
                    Some(Operand::Omron(r)) => BoxOperand::Ref(r),
                    Some(o) => BoxOperand::Direct(self.omron_value(&o, src_words == 2, frame)),
                };
                let (a, b2) = (source(lhs), source(rhs));
                let d = match dst {
                    None => BoxOperand::Absent,
                    Some(Operand::Omron(r)) => BoxOperand::Ref(r),
                    Some(d) => match self.resolve(&d, width_of(dst_words >= 2), frame, true) {
                        Ok(Addr::Image(at)) => BoxOperand::Direct(at),
                        // The verifier keeps every direct destination inside its area.
                        _ => return,
                    },
                };
                if [a, b2, d].iter().any(|o| matches!(o, BoxOperand::Ref(_))) {
                    let sizes = (src_words, dst_words);
                    omron_image::run_box_refs(self.img, self.layout, code, (a, b2, d), sizes);
                } else {
                    let val = |o: BoxOperand| match o {
                        BoxOperand::Direct(v) => v,
                        _ => 0,
                    };
                    omron_image::run_box(self.img, self.layout, code, val(a), val(b2), val(d));
                }
            }
            _ => {}
        }
    }
}
