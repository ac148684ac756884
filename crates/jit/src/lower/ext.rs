//! The s7-200-more ops (tables, ASCII and number text, strings, the clock, PID, the string
//! compare contacts): each is one call of the runtime's own implementation (`runtime::ext`),
//! which resolves the operands itself, given the address of the op. [`ExtKeep`] holds a copy of
//! every such op for as long as the code lives.

use super::Lower;
use super::mem::OnFail;
use super::state::BoxState;
use super::value::B;
use crate::helpers::Helper;
use cranelift_codegen::ir::{
    InstBuilder, Value,
    condcodes::IntCC,
    types::{I16, I32, I64},
};
use std::collections::HashMap;
use stljit_core::ScanStatus;
use stljit_core::ir::{ExtBox, Op, Program, StackForm, StrCompare};
use stljit_core::layout::Sched;

/// The payloads of a program's [`Op::Ext`] and [`Op::StrCompare`] ops, copied once into
/// slices that are never resized, so their addresses, baked into the code, never move; the
/// engine keeps this beside the code.
#[derive(Debug, Default)]
pub(crate) struct ExtKeep {
    /// Only kept alive (the code holds their addresses).
    _boxes: Box<[ExtBox]>,
    /// Only kept alive, as `_boxes`.
    _compares: Box<[StrCompare]>,
    /// `(pou, op)` → the address of its payload.
    addr: HashMap<(usize, usize), i64>,
}

impl ExtKeep {
    /// Copies every payload of `prog`.
    pub(crate) fn of(prog: &Program) -> ExtKeep {
        let (mut boxes, mut compares, mut at) = (Vec::new(), Vec::new(), Vec::new());
        for (p, pou) in prog.pous.iter().enumerate() {
            for (i, op) in pou.ops.iter().enumerate() {
                match op {
                    Op::Ext(b) => {
                        at.push(((p, i), Ok(boxes.len())));
                        boxes.push((**b).clone());
                    }
                    Op::StrCompare(c) => {
                        at.push(((p, i), Err(compares.len())));
                        compares.push((**c).clone());
                    }
                    _ => {}
                }
            }
        }
        let (boxes, compares) = (boxes.into_boxed_slice(), compares.into_boxed_slice());
        let addr = at
            .into_iter()
            .map(|(key, n)| {
                let a = match n {
                    Ok(n) => &boxes[n] as *const ExtBox as i64,
                    Err(n) => &compares[n] as *const StrCompare as i64,
                };
                (key, a)
            })
            .collect();
        ExtKeep {
            _boxes: boxes,
            _compares: compares,
            addr,
        }
    }

    /// The address of the payload of op `op` of POU `pou` (0, which the shims reject, for an
    /// op that has none).
    fn of_op(&self, pou: usize, op: usize) -> i64 {
        self.addr.get(&(pou, op)).copied().unwrap_or(0)
    }
}

impl Lower<'_, '_> {
    /// The shim's `u64` result split: (success, payload).
    fn unpack(&mut self, r: Value) -> (Value, Value) {
        let ok = self.b.ins().ushr_imm_s(r, 32);
        let ok = self.b.ins().ireduce(I32, ok);
        let ok = self.b.ins().band_imm_s(ok, 1);
        let low = self.b.ins().ireduce(I32, r);
        (ok, low)
    }

    /// Calls `stljit_rt_ext` for the current op with power flow `pf` (an `i32` 0/1).
    fn call_ext(&mut self, pf: Value) -> (Value, Value) {
        let at = self.env.ext.of_op(self.func.pou.index(), self.op);
        let p = self.iconst(I64, at);
        let r = self.call_helper(Helper::Ext, &[p, self.func.call_depth, pf]);
        self.unpack(r)
    }

    /// An [`Op::Ext`] box: the runtime runs it; ENO or the error comes back. PID is called
    /// whatever the power flow (its history bit); the others only with power flow.
    pub(crate) fn ext_box(&mut self, b: &ExtBox) {
        if matches!(b, ExtBox::Pid { .. }) {
            let pf = self.pf().to01(&mut self.b);
            let (ok, low) = self.call_ext(pf);
            let bad = self.b.ins().icmp_imm_s(IntCC::Equal, ok, 0);
            self.diamond(
                bad,
                |s| s.record_error(low),
                |s| {
                    let eno = s.b.ins().band_imm_s(low, 1);
                    s.set_eno(B::Bit { v: eno, pos: 0 });
                },
            );
            return;
        }
        self.in_box = BoxState::new(false);
        self.boxed(|s, fail| {
            let one = s.iconst(I32, 1);
            let (ok, low) = s.call_ext(one);
            let zero = s.iconst(I32, 0);
            let st = s.b.ins().select(ok, zero, low);
            debug_assert!(matches!(fail, OnFail::Branch(_)));
            s.fail_on_status(st, fail);
            let eno = s.b.ins().band_imm_s(low, 1);
            B::Bit { v: eno, pos: 0 }
        });
        self.in_box = BoxState::default();
    }

    /// A string compare contact: the runtime compares; a failure is the fatal error it names.
    pub(crate) fn str_compare(&mut self, c: &StrCompare) {
        let at = self.env.ext.of_op(self.func.pou.index(), self.op);
        let p = self.iconst(I64, at);
        let r = self.call_helper(Helper::StrCompare, &[p, self.func.call_depth]);
        let (ok, low) = self.unpack(r);
        let bad = self.b.ins().icmp_imm_s(IntCC::Equal, ok, 0);
        self.side_exit(bad, true, |s| {
            let code = s.b.ins().ireduce(I16, low);
            let a = s.sched(Sched::FATAL);
            s.store_ne(a, code);
            s.record_site();
            let st = s.iconst(I32, ScanStatus::Fatal as i64);
            s.return_status(st);
        });
        let v = B::Bit { v: low, pos: 0 };
        match c.form {
            StackForm::Load => self.block.stack.push(v),
            StackForm::And | StackForm::Or => {
                let top = self.block.stack.top();
                let r = if c.form == StackForm::And {
                    top.and(&mut self.b, v)
                } else {
                    top.or(&mut self.b, v)
                };
                let r = self.anchor(r);
                self.block.stack.set_top(r);
            }
        }
    }
}
