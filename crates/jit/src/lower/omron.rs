//! The Omron CP timers, counters and data boxes: calls into the runtime's `omron_image`
//! (through the `stljit_rt_omron_*` shims), which both engines share.

use super::Lower;
use super::mem::OnFail;
use super::value::{B, Stack};
use crate::helpers::Helper;
use cranelift_codegen::ir::{InstBuilder, Value, types::I32};
use stljit_core::ir::{OmronBox, OmronCounterKind, OmronTimerKind, Operand};
use stljit_core::{FatalCode, Width};
use stljit_runtime::omron_image;

impl Lower<'_, '_> {
    /// The Omron value of a direct operand: a word, or a double word with its low 16 bits in
    /// the lower-numbered word (a location's big-endian dword with its halves swapped;
    /// constants are Omron values already).
    fn omron_value(&mut self, o: &Operand, double: bool) -> Value {
        let width = if double { Width::DWord } else { Width::Word };
        // Omron operands are direct: no pointer can fail.
        let v = self.read_operand(o, width, OnFail::Fatal(FatalCode::CompareIndirect));
        if double && matches!(o, Operand::Mem(_)) {
            // The halves swapped as two shifts and an `or` (x86 folds them into one rotate).
            let hi = self.b.ins().ishl_imm_s(v, 16);
            let lo = self.b.ins().ushr_imm_s(v, 16);
            self.b.ins().bor(hi, lo)
        } else {
            v
        }
    }

    /// Logic-stack levels 0..=2 packed (bit i = S_i): the conditions the Omron timers and
    /// counters read.
    fn omron_conditions(&mut self) -> Value {
        let levels = Stack {
            lv: (0..3).map(|i| self.block.stack.level(i)).collect(),
        };
        levels.to_reg(&mut self.b)
    }

    /// `TIM`…`TTIMX n sv`.
    pub(crate) fn omron_timer(&mut self, kind: OmronTimerKind, n: u16, sv: &Operand) {
        let sv = self.omron_value(sv, false);
        let stack = self.omron_conditions();
        let gate = self.gate_word();
        let nv = self.iconst(I32, i64::from(n));
        let k = self.iconst(I32, i64::from(omron_kind_code(OmronTimerKind::ALL, kind)));
        self.call_helper(Helper::OmronTimer, &[nv, k, stack, gate, sv]);
    }

    /// `CNT`…`CNTRX n sv`.
    pub(crate) fn omron_counter(&mut self, kind: OmronCounterKind, n: u16, sv: &Operand) {
        let sv = self.omron_value(sv, false);
        let stack = self.omron_conditions();
        let gate = self.gate_word();
        let nv = self.iconst(I32, i64::from(n));
        let k = self.iconst(I32, i64::from(omron_kind_code(OmronCounterKind::ALL, kind)));
        self.call_helper(Helper::OmronCounter, &[nv, k, stack, gate, sv]);
    }

    /// `MOV`, `CMP`, arithmetic: when PF, the runtime's box on the operand values.
    pub(crate) fn omron_box(&mut self, bx: &OmronBox) {
        let pf = self.pf();
        if pf == B::K(false) {
            return;
        }
        let bx = *bx;
        self.guarded(pf, move |s| {
            let code = s.iconst(I32, i64::from(omron_image::box_code(&bx)));
            let zero = s.iconst(I32, 0);
            let (a, b, dst) = match bx {
                OmronBox::Move { double, src, dst } => {
                    (s.omron_value(&src, double), zero, Some(dst))
                }
                OmronBox::Compare {
                    double, lhs, rhs, ..
                } => (
                    s.omron_value(&lhs, double),
                    s.omron_value(&rhs, double),
                    None,
                ),
                OmronBox::Arith { op, lhs, rhs, dst } => {
                    let double = op.operand_words() == 2;
                    (
                        s.omron_value(&lhs, double),
                        s.omron_value(&rhs, double),
                        Some(dst),
                    )
                }
            };
            let at = match dst {
                Some(Operand::Mem(loc)) => s.loc_addr(loc).off,
                // The verifier keeps destinations direct and writable.
                _ => 0,
            };
            let at = s.iconst(I32, i64::from(at));
            s.call_helper(Helper::OmronBox, &[code, a, b, at]);
        });
    }
}

/// The position of `kind` in `all` (its `FfiCode`).
fn omron_kind_code<T: PartialEq>(all: &[T], kind: T) -> u32 {
    all.iter().position(|k| *k == kind).unwrap_or(0) as u32
}
