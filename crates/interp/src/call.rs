//! `CALL` with parameters (s7-200-more §1.5; the rule in words is `stljit_core::ir::CallArgs`'s
//! doc): resolve every actual in the caller's frame, copy IN and IN_OUT into the next frame, run
//! the callee, copy IN_OUT and OUT back to the places resolved before the call, ENO = 1.

use crate::exec::{Exit, Machine};
use crate::operand::Addr;
use stljit_core::ErrorCode;
use stljit_core::ir::{Arg, ArgValue, BitLoc, CallArgs, Operand};

/// Where an actual lives once resolved.
#[derive(Clone, Copy)]
enum Place {
    /// A bit of the caller's context.
    Bit(BitLoc),
    /// A value: image offset, or a constant.
    Value(Addr),
}

impl Machine<'_> {
    /// Runs `CALL callee, args…` at call depth `depth` with power flow `pf`; `Err` when the
    /// callee aborted the scan with a fatal error.
    pub(crate) fn call_args(
        &mut self,
        call: &CallArgs,
        pf: bool,
        depth: u32,
        (pou, pc): (usize, usize),
    ) -> Result<(), ()> {
        if !pf {
            self.set_eno(false);
            return Ok(());
        }
        if depth + 1 > self.max_depth() {
            self.error(ErrorCode::CallNesting, pou, pc);
            return Ok(());
        }
        let places: Result<Vec<Place>, ErrorCode> = call
            .args
            .iter()
            .map(|a| self.resolve_actual(a, depth))
            .collect();
        let places = match places {
            Ok(p) => p,
            Err(e) => {
                self.error(e, pou, pc);
                return Ok(());
            }
        };
        let callee_frame = depth + 1;
        for (a, &place) in call.args.iter().zip(&places) {
            if a.dir.copies_in() {
                self.copy(a.value, place, (depth, callee_frame), true);
            }
        }
        if self.run_pou(call.callee.index(), callee_frame, 1) == Exit::Fatal {
            return Err(());
        }
        for (a, &place) in call.args.iter().zip(&places) {
            if a.dir.copies_out() {
                self.copy(a.value, place, (depth, callee_frame), false);
            }
        }
        self.set_eno(true);
        Ok(())
    }

    /// Copies one parameter between the actual's `place` (in the caller's frame) and the formal
    /// (in the callee's): into the callee (copy-in) or back (copy-back).
    fn copy(&mut self, value: ArgValue, place: Place, (caller, callee): (u32, u32), into: bool) {
        match (value, place) {
            (ArgValue::Bit { formal, .. }, Place::Bit(actual)) => {
                let ((from, from_frame), (to, to_frame)) = if into {
                    ((actual, caller), (formal, callee))
                } else {
                    ((formal, callee), (actual, caller))
                };
                let v = self.bit(from, from_frame);
                self.set_bit(to, to_frame, v);
            }
            (ArgValue::Value { width, formal, .. }, Place::Value(at)) => {
                let Ok(f) = self.resolve(&Operand::Mem(formal), width, callee, into) else {
                    return;
                };
                let (from, to) = if into { (at, f) } else { (f, at) };
                let v = self.load(from, width);
                self.store(to, width, v);
            }
            // The verifier pairs bit formals with bit actuals and values with values.
            _ => {}
        }
    }

    /// Resolves one actual in the caller's frame `frame` (writes for IN_OUT and OUT).
    fn resolve_actual(&self, a: &Arg, frame: u32) -> Result<Place, ErrorCode> {
        match a.value {
            ArgValue::Bit { actual, .. } => Ok(Place::Bit(actual)),
            ArgValue::Value { width, actual, .. } => self
                .resolve(&actual, width, frame, a.dir.copies_out())
                .map(Place::Value),
        }
    }
}
