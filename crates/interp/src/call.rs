//! `CALL` with parameters (s7-200-more §1.5; the rule in words is `stljit_core::ir::CallArgs`'s
//! doc): resolve every actual in the caller's frame, copy IN and IN_OUT into the next frame, run
//! the callee, copy IN_OUT and OUT back to the places resolved before the call, ENO = 1.

use crate::exec::{Exit, Machine};
use crate::operand::Addr;
use stljit_core::ErrorCode;
use stljit_core::ir::{Arg, ArgValue, BitLoc, CallArgs};

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
                match (a.value, place) {
                    (ArgValue::Bit { formal, .. }, Place::Bit(actual)) => {
                        let v = self.bit(actual, depth);
                        self.set_bit(formal, callee_frame, v);
                    }
                    (ArgValue::Value { width, formal, .. }, Place::Value(at)) => {
                        let v = self.load(at, width);
                        if let Ok(f) = self.resolve(
                            &stljit_core::ir::Operand::Mem(formal),
                            width,
                            callee_frame,
                            true,
                        ) {
                            self.store(f, width, v);
                        }
                    }
                    _ => {}
                }
            }
        }
        if self.run_pou(call.callee.index(), callee_frame, 1) == Exit::Fatal {
            return Err(());
        }
        for (a, &place) in call.args.iter().zip(&places) {
            if a.dir.copies_out() {
                match (a.value, place) {
                    (ArgValue::Bit { formal, .. }, Place::Bit(actual)) => {
                        let v = self.bit(formal, callee_frame);
                        self.set_bit(actual, depth, v);
                    }
                    (ArgValue::Value { width, formal, .. }, Place::Value(at)) => {
                        let f = self.resolve(
                            &stljit_core::ir::Operand::Mem(formal),
                            width,
                            callee_frame,
                            false,
                        );
                        if let Ok(f) = f {
                            let v = self.load(f, width);
                            self.store(at, width, v);
                        }
                    }
                    _ => {}
                }
            }
        }
        self.set_eno(true);
        Ok(())
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
