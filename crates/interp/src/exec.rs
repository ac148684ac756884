//! The op loop: one POU at a time, the logic stack in a local `u16` (spec §3.1), every other piece
//! of state in the image.

use crate::Interpreter;
use stljit_core::ir::{Contact, Op, Operand, Program, StackForm};
use stljit_core::layout::{ISR_FRAME, Layout, Sched};
use stljit_core::{ErrorCode, FatalCode, PouId, ScanStatus, Width};
use stljit_runtime::interrupt::{self, Action, Isr};
use stljit_runtime::rules::{Gate, Rules};
use stljit_runtime::{block, compare, counter, edge, ext, mem, scan, timer};

/// What the loop does after an op.
enum Step {
    /// Continue with the next op.
    Next,
    /// Continue at this op index.
    Goto(usize),
    /// Leave the POU (RET, CRET, or the end of main for END/MEND).
    Return,
    /// A STOP in an interrupt routine's chain: end the routine at once (s7-200-more §3.4).
    Stop,
    /// Abort the scan: a fatal error has been recorded.
    Fatal,
}

/// How a POU ended.
#[derive(PartialEq, Eq)]
pub(crate) enum Exit {
    Normal,
    EndScan,
    /// A STOP ended an interrupt routine's chain.
    Stopped,
    Fatal,
}

/// The interpreter as the interrupt machinery's [`Isr`]: runs a routine's POU.
pub(crate) struct Routines<'a>(pub(crate) &'a Interpreter);

impl Isr for Routines<'_> {
    fn run(&mut self, img: &mut [u8], layout: &Layout, pou: PouId) -> ScanStatus {
        let mut m = Machine::new(self.0, img, layout);
        match m.run_pou(pou.index(), ISR_FRAME, 0) {
            Exit::Normal | Exit::EndScan => ScanStatus::Ok,
            Exit::Stopped => ScanStatus::Stopped,
            Exit::Fatal => ScanStatus::Fatal,
        }
    }
}

/// The interpreter bound to one image for one scan.
pub(crate) struct Machine<'a> {
    prog: &'a Program,
    timer_res: &'a [Option<u8>],
    mask: u16,
    rules: Rules,
    pub(crate) img: &'a mut [u8],
    pub(crate) layout: &'a Layout,
}

impl<'a> Machine<'a> {
    pub(crate) fn new(
        interp: &'a Interpreter,
        img: &'a mut [u8],
        layout: &'a Layout,
    ) -> Machine<'a> {
        Machine {
            prog: &interp.program,
            timer_res: &interp.timer_res,
            mask: interp.stack_mask,
            rules: interp.rules,
            img,
            layout,
        }
    }

    /// Executes the main program (spec §2.1 step 5).
    pub(crate) fn run_main(&mut self) -> ScanStatus {
        match self.run_pou(0, 0, 0) {
            Exit::Fatal => ScanStatus::Fatal,
            Exit::Normal | Exit::EndScan | Exit::Stopped => ScanStatus::Ok,
        }
    }

    fn gate(&self) -> bool {
        mem::sched_u8(self.img, self.layout, Sched::SCR_ENABLE) != 0
    }

    /// The gate timers, counters and edges run under: the gate byte (SCR enable or Omron
    /// interlock), with the policy of the program's family.
    pub(crate) fn stateful_gate(&self) -> Gate {
        Gate::with(
            self.gate(),
            self.layout.profile.profile().family.gate_policy(),
        )
    }

    fn set_gate(&mut self, v: bool) {
        mem::set_sched_u8(self.img, self.layout, Sched::SCR_ENABLE, u8::from(v));
    }

    pub(crate) fn set_eno(&mut self, v: bool) {
        mem::set_sched_u8(self.img, self.layout, Sched::ENO, u8::from(v));
    }

    /// Whether a CALL made at call depth `depth` would nest deeper than the profile allows
    /// (`CpuProfile::deepest_frame`: the main program's chain, or an interrupt routine's).
    pub(crate) fn call_too_deep(&self, depth: u32) -> bool {
        depth + 1 > self.layout.profile.profile().deepest_frame(depth)
    }

    /// A non-fatal error: recorded, ENO = 0 (spec §2.5, §3.5).
    pub(crate) fn error(&mut self, code: ErrorCode, pou: usize, pc: usize) {
        scan::record_error(self.img, self.layout, code, pou as u32, pc as u32);
        self.set_eno(false);
    }

    fn fatal(&mut self, code: FatalCode, pou: usize, pc: usize) -> Step {
        scan::record_fatal(self.img, self.layout, code, pou as u32, pc as u32);
        Step::Fatal
    }

    fn push(&self, st: u16, v: bool) -> u16 {
        ((st << 1) | u16::from(v)) & self.mask
    }

    /// Runs POU `pou` at call depth `depth` (its L frame: 0 for the main program, `ISR_FRAME`
    /// for an interrupt routine) with initial stack `st`.
    pub(crate) fn run_pou(&mut self, pou: usize, depth: u32, mut st: u16) -> Exit {
        let prog = self.prog;
        let Some(ops) = prog.pous.get(pou).map(|p| &p.ops) else {
            return Exit::Normal;
        };
        let mut pc = 0;
        while let Some(op) = ops.get(pc) {
            match self.step(op, pou, pc, depth, &mut st) {
                Step::Next => pc += 1,
                Step::Goto(to) => pc = to,
                Step::Return => {
                    // END/MEND in main end the scan; RET/CRET in a subroutine return.
                    return if depth == 0 {
                        Exit::EndScan
                    } else {
                        Exit::Normal
                    };
                }
                Step::Stop => return Exit::Stopped,
                Step::Fatal => return Exit::Fatal,
            }
        }
        Exit::Normal
    }

    fn contact(&mut self, c: &Contact, frame: u32, pou: usize, pc: usize) -> Result<bool, Step> {
        match *c {
            Contact::Bit { bit, negated } => Ok(self.bit(bit, frame) != negated),
            Contact::ImmediateInput { bit, negated } => Ok(self.phys_in_bit(bit) != negated),
            Contact::Compare { ty, op, lhs, rhs } => {
                let w = ty.width();
                let (a, b) = match (self.read(&lhs, w, frame), self.read(&rhs, w, frame)) {
                    (Ok(a), Ok(b)) => (a, b),
                    _ => return Err(self.fatal(FatalCode::CompareIndirect, pou, pc)),
                };
                compare::compare(ty, op, a, b).map_err(|f| self.fatal(f, pou, pc))
            }
        }
    }

    fn step(&mut self, op: &Op, pou: usize, pc: usize, depth: u32, st: &mut u16) -> Step {
        let frame = depth;
        let pf = *st & 1 != 0 && self.gate();
        match op {
            Op::Load(c) => match self.contact(c, frame, pou, pc) {
                Ok(v) => *st = self.push(*st, v),
                Err(s) => return s,
            },
            Op::And(c) => match self.contact(c, frame, pou, pc) {
                Ok(v) => *st &= !1 | u16::from(v),
                Err(s) => return s,
            },
            Op::Or(c) => match self.contact(c, frame, pou, pc) {
                Ok(v) => *st |= u16::from(v),
                Err(s) => return s,
            },
            Op::Not => *st ^= 1,
            Op::AndBlock => *st = ((*st >> 1) & !1) | (*st & (*st >> 1) & 1),
            Op::OrBlock => *st = ((*st >> 1) & !1) | ((*st | (*st >> 1)) & 1),
            Op::Dup => *st = self.push(*st, *st & 1 != 0),
            Op::ReadSecond => *st = (*st & !1) | ((*st >> 1) & 1),
            Op::Pop => *st >>= 1,
            Op::Pick(n) => {
                let v = st.checked_shr(u32::from(*n)).unwrap_or(0) & 1 != 0;
                *st = self.push(*st, v);
            }
            Op::AndEno => {
                let eno = mem::sched_u8(self.img, self.layout, Sched::ENO) != 0;
                *st &= !1 | u16::from(eno);
            }
            Op::Edge { slot, falling } => {
                let (gate, rules) = (self.stateful_gate(), self.rules);
                let s0 = *st & 1 != 0;
                let v = edge::execute(self.img, self.layout, slot.0, s0, gate, *falling, rules);
                *st = (*st & !1) | u16::from(v);
            }
            Op::Assign { bit, immediate } => {
                self.set_bit(*bit, frame, pf);
                if *immediate {
                    self.set_phys_out_bit(*bit, pf);
                }
            }
            Op::SetRange {
                start,
                count,
                value,
                immediate,
            } if pf => {
                let r = self.read(count, Width::Byte, frame).and_then(|n| {
                    block::set_range_imm(
                        self.img,
                        self.layout,
                        *start,
                        frame,
                        n,
                        *value,
                        *immediate,
                    )
                });
                if let Err(e) = r {
                    self.error(e, pou, pc);
                }
            }
            Op::ResetTimers { first, count } if pf => {
                let r = self
                    .read(count, Width::Byte, frame)
                    .and_then(|n| timer::reset_range(self.img, self.layout, first.0, n));
                if let Err(e) = r {
                    self.error(e, pou, pc);
                }
            }
            Op::ResetCounters { first, count } if pf => {
                let r = self
                    .read(count, Width::Byte, frame)
                    .and_then(|n| counter::reset_range(self.img, self.layout, first.0, n));
                if let Err(e) = r {
                    self.error(e, pou, pc);
                }
            }
            Op::SetRange { .. } | Op::ResetTimers { .. } | Op::ResetCounters { .. } => {}
            Op::Timer {
                kind,
                timer,
                preset,
            } => {
                let gate = self.stateful_gate();
                let r = self.read(preset, Width::Word, frame).and_then(|pt| {
                    timer::execute(
                        self.img,
                        self.layout,
                        timer.0,
                        *kind,
                        *st & 1 != 0,
                        gate,
                        pt as u16 as i16,
                        self.timer_res.get(usize::from(timer.0)).copied().flatten(),
                    )
                });
                if let Err(e) = r {
                    self.error(e, pou, pc);
                }
            }
            Op::Counter {
                kind,
                counter,
                preset,
            } => {
                let gate = self.stateful_gate();
                let r = self.read(preset, Width::Word, frame).and_then(|pv| {
                    counter::execute(
                        self.img,
                        self.layout,
                        counter.0,
                        *kind,
                        *st,
                        gate,
                        pv as u16 as i16,
                        self.rules,
                    )
                });
                if let Err(e) = r {
                    self.error(e, pou, pc);
                }
            }
            Op::Box(b) => {
                if !pf {
                    self.set_eno(false);
                } else {
                    match self.exec_box(b, frame) {
                        Ok(eno) => self.set_eno(eno),
                        Err(e) => self.error(e, pou, pc),
                    }
                }
            }
            Op::Jump(label) if pf => {
                let Some(to) = self
                    .prog
                    .pous
                    .get(pou)
                    .and_then(|p| p.labels.get(label.index()))
                else {
                    return Step::Return;
                };
                let to = to.index();
                if to <= pc && !scan::loop_tick(self.img, self.layout) {
                    return self.fatal(FatalCode::Watchdog, pou, pc);
                }
                return Step::Goto(to);
            }
            Op::Jump(_) | Op::Label(_) | Op::Nop => {}
            Op::Call(callee) if pf => {
                if self.call_too_deep(depth) {
                    self.error(ErrorCode::CallNesting, pou, pc);
                } else {
                    match self.run_pou(callee.index(), depth + 1, 1) {
                        Exit::Fatal => return Step::Fatal,
                        Exit::Stopped => return Step::Stop,
                        Exit::Normal | Exit::EndScan => {}
                    }
                }
                // The caller's stack is `*st`, untouched by the callee (spec §3.2 CALL).
            }
            Op::Call(_) => {}
            // The caller's stack is untouched here too; ENO follows s7-200-more §1.5.
            Op::CallArgs(call) => match self.call_args(call, pf, depth, (pou, pc)) {
                Exit::Fatal => return Step::Fatal,
                Exit::Stopped => return Step::Stop,
                Exit::Normal | Exit::EndScan => {}
            },
            Op::Return { conditional } | Op::End { conditional } => {
                if !*conditional || pf {
                    return Step::Return;
                }
            }
            Op::Stop if pf => {
                mem::set_sched_u8(self.img, self.layout, Sched::STOP_REQ, 1);
                // In an interrupt routine's chain STOP ends the routine at once (§3.4).
                if depth >= ISR_FRAME {
                    return Step::Stop;
                }
            }
            Op::Wdr if pf => scan::watchdog_reset(self.img, self.layout),
            Op::Interrupt(i) if pf => {
                if let Some(a) = Action::of(*i, self.prog)
                    && let Err(e) = interrupt::execute(self.img, self.layout, a)
                {
                    self.error(e, pou, pc);
                }
            }
            Op::Stop | Op::Wdr | Op::Interrupt(_) => {}
            Op::For {
                index,
                init,
                limit,
                next,
            } => {
                let ops = (index, init, limit);
                return self.exec_for(pf, ops, next.index(), frame, pou, pc, st);
            }
            Op::Next { head } => return self.exec_next(head.index(), frame, pou, pc, st),
            Op::ScrBegin { bit } => {
                let v = self.bit(*bit, frame);
                self.set_gate(v);
                *st = self.push(*st, v);
            }
            Op::ScrTransition { to, from } if pf => {
                self.set_bit(*to, frame, true);
                self.set_bit(*from, frame, false);
            }
            Op::ScrTransition { .. } => {}
            Op::ScrCondEnd { end } if pf => return Step::Goto(end.index()),
            Op::ScrCondEnd { .. } => {}
            Op::ScrEnd | Op::InterlockEnd => self.set_gate(true),
            Op::Interlock => self.set_gate(pf),
            Op::TaskStart => scan::task_start(self.img, self.layout),
            Op::OmronTimer { .. } | Op::OmronCounter { .. } | Op::Omron(_) => {
                self.omron(op, frame, *st, pf);
            }
            // PID runs without power flow too (its history bit); the others skip then.
            Op::Ext(b) => match ext::execute(self.img, self.layout, b, frame, pf) {
                Ok(eno) => self.set_eno(eno),
                Err(e) => self.error(e, pou, pc),
            },
            Op::StrCompare(c) => match ext::str_compare(self.img, self.layout, c, frame) {
                Ok(v) => {
                    *st = match c.form {
                        StackForm::Load => self.push(*st, v),
                        StackForm::And => *st & (!1 | u16::from(v)),
                        StackForm::Or => *st | u16::from(v),
                    }
                }
                Err(f) => return self.fatal(f, pou, pc),
            },
        }
        Step::Next
    }

    /// `FOR INDX, INIT, FINAL` (spec §4.14): disabled or empty loops continue after NEXT.
    #[allow(clippy::too_many_arguments)]
    fn exec_for(
        &mut self,
        pf: bool,
        (index, init, limit): (&Operand, &Operand, &Operand),
        next: usize,
        frame: u32,
        pou: usize,
        pc: usize,
        st: &mut u16,
    ) -> Step {
        if !pf {
            return Step::Goto(next + 1);
        }
        let r = (|| {
            // Spec §4.14 order: INDX := INIT, then FINAL is read, so a FINAL that overlaps
            // INDX sees the new index (docs/semantics.md, "FOR operands").
            let dst = self.resolve(index, Width::Word, frame, true)?;
            let first = self.read(init, Width::Word, frame)?;
            self.store(dst, Width::Word, first);
            let last = self.read(limit, Width::Word, frame)?;
            Ok((first as u16 as i16) <= (last as u16 as i16))
        })();
        match r {
            Ok(true) => Step::Next,
            Ok(false) => {
                *st |= 1;
                Step::Goto(next + 1)
            }
            Err(e) => {
                self.error(e, pou, pc);
                Step::Goto(next + 1)
            }
        }
    }

    /// `NEXT`: INDX += 1, S0 = 1, loop back while INDX <= FINAL (both re-read).
    fn exec_next(&mut self, head: usize, frame: u32, pou: usize, pc: usize, st: &mut u16) -> Step {
        *st |= 1;
        let Some(Op::For { index, limit, .. }) =
            self.prog.pous.get(pou).and_then(|p| p.ops.get(head))
        else {
            return Step::Next;
        };
        let r = (|| {
            let dst = self.resolve(index, Width::Word, frame, true)?;
            let i = (self.load(dst, Width::Word) as u16 as i16).wrapping_add(1);
            self.store(dst, Width::Word, i as u16 as u32);
            let last = self.read(limit, Width::Word, frame)? as u16 as i16;
            Ok(i <= last)
        })();
        match r {
            Ok(true) => {
                if !scan::loop_tick(self.img, self.layout) {
                    return self.fatal(FatalCode::Watchdog, pou, pc);
                }
                Step::Goto(head + 1)
            }
            Ok(false) => Step::Next,
            Err(e) => {
                self.error(e, pou, pc);
                Step::Next
            }
        }
    }
}
