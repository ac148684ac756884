//! `CALL` with parameters (the rule: `stljit_core::ir::CallArgs`; the interpreter's `call.rs`).
//!
//! Inside the box frame of [`Lower::run_failing`] (PF = 0 → ENO = 0; an error → recorded, ENO =
//! 0): the nesting check and every actual's resolution branch to the failure block before
//! anything is written; the IN and IN_OUT values are read, the cache is forgotten, the values are
//! stored into the callee's frame (the caller's frame plus one frame size, never cached: no
//! static address names it), the callee runs, and the IN_OUT and OUT formals are loaded back and
//! written to the places resolved before the call, whose addresses are SSA values that survive
//! the call.

use super::Lower;
use super::mem::{OnFail, Place};
use super::value::B;
use cranelift_codegen::ir::{InstBuilder, Value, condcodes::IntCC, types::I32};
use stljit_core::ir::{ArgValue, BitLoc, CallArgs, Operand};
use stljit_core::{Area, ErrorCode};

/// An actual once resolved.
#[derive(Clone, Copy)]
enum Actual {
    /// A bit of the caller.
    Bit(BitLoc),
    /// A value place of the caller.
    Place(Place),
    /// A constant (or `&x`), already read.
    Const(Value),
}

impl Lower<'_, '_> {
    /// `CALL callee, args…`.
    pub(crate) fn call_args(&mut self, call: &CallArgs) {
        let pf = self.pf();
        if pf == B::K(false) {
            self.set_eno(B::K(false));
            return;
        }
        let gate_before = self.block.gate;
        self.run_failing(pf, true, |s, fail| {
            let max = i64::from(s.env.layout.profile.profile().max_call_depth);
            let too_deep =
                s.b.ins()
                    .icmp_imm_s(IntCC::SignedGreaterThanOrEqual, s.func.call_depth, max);
            s.fail_if(too_deep, fail, ErrorCode::CallNesting as u16);
            let actuals: Vec<Actual> = call
                .args
                .iter()
                .map(|a| s.resolve_actual(a.value, a.dir.copies_out(), fail))
                .collect();
            // Read every value copied in before anything is written.
            let ins: Vec<Option<Value>> = call
                .args
                .iter()
                .zip(&actuals)
                .map(|(a, &actual)| a.dir.copies_in().then(|| s.read_actual(a.value, actual)))
                .collect();
            s.forget_all();
            let frame = i64::from(s.env.layout.area_size(Area::L));
            let callee_frame = s.b.ins().iadd_imm_s(s.func.lbase, frame);
            for (a, v) in call.args.iter().zip(ins) {
                if let Some(v) = v {
                    s.store_formal(callee_frame, a.value, v);
                }
            }
            s.run_callee(call.callee);
            for (a, &actual) in call.args.iter().zip(&actuals) {
                if a.dir.copies_out() {
                    let v = s.load_formal(callee_frame, a.value);
                    s.write_actual(a.value, actual, v);
                }
            }
            s.set_eno(B::K(true));
        });
        self.block.gate = self.gate_after_call(call.callee, gate_before);
    }

    fn resolve_actual(&mut self, value: ArgValue, write: bool, fail: OnFail) -> Actual {
        match value {
            ArgValue::Bit { actual, .. } => Actual::Bit(actual),
            ArgValue::Value { width, actual, .. } => match actual {
                Operand::Const(_) | Operand::AddressOf(_) | Operand::Omron(_) => {
                    Actual::Const(self.read_operand(&actual, width, fail))
                }
                Operand::Mem(_) | Operand::Indirect(_) => {
                    match self.place(&actual, width, write, fail) {
                        Some(p) => Actual::Place(p),
                        None => Actual::Const(self.iconst(I32, 0)),
                    }
                }
            },
        }
    }

    /// The value of an actual: a 0/1 `i32` for a bit, the zero-extended value otherwise.
    fn read_actual(&mut self, value: ArgValue, actual: Actual) -> Value {
        match (value, actual) {
            (_, Actual::Bit(bit)) => {
                let b = self.read_bit(bit);
                b.to01(&mut self.b)
            }
            (ArgValue::Value { width, .. }, Actual::Place(p)) => self.read_place(p, width),
            (_, Actual::Const(v)) => v,
            (ArgValue::Bit { .. }, Actual::Place(_)) => self.iconst(I32, 0),
        }
    }

    fn write_actual(&mut self, value: ArgValue, actual: Actual, v: Value) {
        match (value, actual) {
            (_, Actual::Bit(bit)) => {
                let a = self.bit_byte(bit);
                self.write_bit_at(a, bit.bit, B::Bit { v, pos: 0 });
            }
            (ArgValue::Value { width, .. }, Actual::Place(p)) => self.write_place(p, width, v),
            // The verifier rejects a constant as an IN_OUT or OUT actual.
            _ => {}
        }
    }

    /// Stores `v` (0/1 for a bit) into a formal of the callee's frame at `base`.
    fn store_formal(&mut self, base: Value, value: ArgValue, v: Value) {
        match value {
            ArgValue::Bit { formal, .. } => {
                let off = formal.byte as i32;
                let old = self.b.ins().uload8(I32, super::mf(), base, off);
                let m = 1i64 << formal.bit;
                let cleared = self.b.ins().band_imm_s(old, !m & 0xFF);
                let bit = self.b.ins().ishl_imm_s(v, i64::from(formal.bit));
                let new = self.b.ins().bor(cleared, bit);
                self.b.ins().istore8(super::mf(), new, base, off);
            }
            ArgValue::Value { width, formal, .. } => {
                self.store_be(base, formal.offset as i32, width, v);
            }
        }
    }

    /// Loads a formal of the callee's frame at `base`: 0/1 for a bit.
    fn load_formal(&mut self, base: Value, value: ArgValue) -> Value {
        match value {
            ArgValue::Bit { formal, .. } => {
                let byte = self
                    .b
                    .ins()
                    .uload8(I32, super::mf(), base, formal.byte as i32);
                let s = self.b.ins().ushr_imm_s(byte, i64::from(formal.bit));
                self.b.ins().band_imm_s(s, 1)
            }
            ArgValue::Value { width, formal, .. } => {
                self.load_be(base, formal.offset as i32, width)
            }
        }
    }
}
