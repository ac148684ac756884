//! Program control: JMP/LBL, CALL/RET/CRET, END/MEND, STOP, WDR, FOR/NEXT and SCR segments.
//!
//! The loop budget is counted exactly at the interpreter's events (a taken backward JMP, a NEXT
//! that loops back) with the runtime's rule (`scan::loop_tick`, inlined: saturating increment,
//! fatal when the count exceeds `LOOP_LIMIT`).

use super::Lower;
use super::mem::OnFail;
use super::value::B;
use crate::helpers::Helper;
use cranelift_codegen::ir::{
    Block, InstBuilder,
    condcodes::IntCC,
    types::{I16, I32},
};
use cranelift_module::Module;
use stljit_core::ir::{BitLoc, Op, Operand};
use stljit_core::layout::Sched;
use stljit_core::{ErrorCode, FatalCode, LabelId, PouId, Width};

impl Lower<'_, '_> {
    /// One loop-budget event; takes the Watchdog fatal exit when the budget is exhausted.
    fn loop_tick(&mut self) {
        let ca = self.sched(Sched::LOOP_COUNT);
        let n = self.load_ne(ca, I32);
        let n1 = self.b.ins().iadd_imm_s(n, 1);
        let wrapped = self.b.ins().icmp_imm_s(IntCC::Equal, n1, 0);
        let n1 = self.b.ins().select(wrapped, n, n1);
        self.store_ne(ca, n1);
        let la = self.sched(Sched::LOOP_LIMIT);
        let limit = self.load_ne(la, I32);
        let over = self.b.ins().icmp(IntCC::UnsignedGreaterThan, n1, limit);
        self.fatal_if(over, FatalCode::Watchdog);
    }

    /// If `pf`: (count a loop event if `backward`, then) go to the leader at `target`; else
    /// fall through with the state kept.
    fn branch_if(&mut self, pf: B, target: usize, backward: bool) {
        match pf {
            B::K(false) => {}
            B::K(true) => {
                if backward {
                    self.loop_tick();
                }
                self.jump_to_op(target);
                self.block.open = false;
            }
            _ => {
                let c = pf.cond(&mut self.b);
                self.side_exit(c, false, |s| {
                    if backward {
                        s.loop_tick();
                    }
                    s.jump_to_op(target);
                });
            }
        }
    }

    /// Returns 0 from the POU if `pf` (RET/CRET/END/MEND).
    fn return_if(&mut self, pf: B) {
        match pf {
            B::K(false) => {}
            B::K(true) => {
                self.ret_ok();
                self.block.open = false;
            }
            _ => {
                let c = pf.cond(&mut self.b);
                self.side_exit(c, false, Self::ret_ok);
            }
        }
    }

    /// A failure block for FOR/NEXT operands: records the error and continues at `past`.
    /// The block starts from an empty cache (it is entered from several points of the
    /// checks, each with its own cache).
    fn loop_fail_block(&mut self, past: usize) -> Block {
        let err = self.b.create_block();
        let code = self.b.append_block_param(err, I32);
        // cranelift-frontend only switches away from a filled block: end this one first.
        let cont = self.b.create_block();
        self.b.ins().jump(cont, &[]);
        self.b.seal_block(cont);
        let saved = std::mem::take(&mut self.block.cache);
        self.b.switch_to_block(err);
        self.record_error(code);
        self.jump_to_op(past);
        self.block.cache = saved;
        self.b.switch_to_block(cont);
        err
    }

    /// `FOR` (interpreter `exec_for`): skipped without PF; INDX and INIT resolved, INIT stored
    /// into INDX, then FINAL resolved and read (an error skips the loop); `INIT > FINAL` sets S0
    /// and skips.
    fn lower_for(&mut self, index: &Operand, init: &Operand, limit: &Operand, past: usize) {
        let pf = self.pf();
        let not_pf = pf.not(&mut self.b);
        self.branch_if(not_pf, past, false);
        if !self.block.open {
            return;
        }
        let err = self.loop_fail_block(past);
        let fail = OnFail::Branch(err);
        // Spec §4.14 order (as the interpreter's `exec_for`): INDX := INIT, then FINAL is read.
        let dst = self.place(index, Width::Word, true, fail);
        let first = self.read_operand(init, Width::Word, fail);
        if let Some(p) = dst {
            self.write_place(p, Width::Word, first);
        }
        let last = self.read_operand(limit, Width::Word, fail);
        let f16 = self.b.ins().ireduce(I16, first);
        let l16 = self.b.ins().ireduce(I16, last);
        let over = self.b.ins().icmp(IntCC::SignedGreaterThan, f16, l16);
        let over = self.b.ins().uextend(I32, over);
        let top = self.block.stack.top();
        self.block.stack.set_top(B::K(true));
        self.branch_if(B::Bit { v: over, pos: 0 }, past, false);
        self.block.stack.set_top(top);
    }

    /// `NEXT` (interpreter `exec_next`): S0 = 1; INDX += 1 (wrapping); loop back (counting the
    /// budget) while INDX <= FINAL; an operand error records it and leaves the loop.
    fn lower_next(&mut self, index: &Operand, limit: &Operand, body: usize) {
        self.block.stack.set_top(B::K(true));
        let past = self.op + 1;
        let err = self.loop_fail_block(past);
        let fail = OnFail::Branch(err);
        let Some(p) = self.place(index, Width::Word, true, fail) else {
            return;
        };
        let i = self.read_place(p, Width::Word);
        let i1 = self.b.ins().iadd_imm_s(i, 1);
        let i1 = self.b.ins().band_imm_s(i1, 0xFFFF);
        self.write_place(p, Width::Word, i1);
        let last = self.read_operand(limit, Width::Word, fail);
        let a16 = self.b.ins().ireduce(I16, i1);
        let l16 = self.b.ins().ireduce(I16, last);
        let again = self.b.ins().icmp(IntCC::SignedLessThanOrEqual, a16, l16);
        let again = self.b.ins().uextend(I32, again);
        self.branch_if(B::Bit { v: again, pos: 0 }, body, true);
    }

    /// `JMP n`: to the label's op if PF (a backward jump counts a loop event).
    pub(crate) fn jump(&mut self, l: LabelId) {
        let target = self.env.prog.pou(self.func.pou).label_target(l).index();
        let pf = self.pf();
        self.branch_if(pf, target, target <= self.op);
    }

    /// `RET`/`CRET`/`END`/`MEND`.
    pub(crate) fn ret(&mut self, conditional: bool) {
        let pf = if conditional { self.pf() } else { B::K(true) };
        self.return_if(pf);
    }

    /// `STOP`: requests STOP if PF.
    pub(crate) fn stop(&mut self) {
        let pf = self.pf();
        if pf != B::K(false) {
            let a = self.sched(Sched::STOP_REQ);
            let old = self.byte(a);
            let p = pf.to01(&mut self.b);
            let new = self.b.ins().bor(old, p);
            self.set_byte(a, new);
        }
    }

    /// `WDR`: restarts the loop budget if PF.
    pub(crate) fn wdr(&mut self) {
        let pf = self.pf();
        self.guarded(pf, |s| {
            let z = s.iconst(I32, 0);
            let a = s.sched(Sched::LOOP_COUNT);
            s.store_ne(a, z);
        });
    }

    /// `FOR`, whose `NEXT` is op `next`.
    pub(crate) fn for_loop(
        &mut self,
        index: &Operand,
        init: &Operand,
        limit: &Operand,
        next: usize,
    ) {
        self.lower_for(index, init, limit, next + 1);
    }

    /// `NEXT` of the `FOR` at op `head`.
    pub(crate) fn next(&mut self, head: usize) {
        let pou = self.env.prog.pou(self.func.pou);
        if let Some(Op::For { index, limit, .. }) = pou.ops.get(head) {
            self.lower_next(index, limit, head + 1)
        }
    }

    /// `LSCR`: the segment's bit becomes the gate and is pushed.
    pub(crate) fn scr_begin(&mut self, bit: BitLoc) {
        let v = self.read_bit(bit);
        let a = self.sched(Sched::SCR_ENABLE);
        let v01 = v.to01(&mut self.b);
        self.set_byte(a, v01);
        self.block.gate = v;
        self.block.stack.push(v);
    }

    /// `SCRT`: if PF, sets `to` and resets `from`.
    pub(crate) fn scr_transition(&mut self, to: BitLoc, from: BitLoc) {
        let pf = self.pf();
        let (ta, fa) = (self.bit_byte(to), self.bit_byte(from));
        // Conditional set then reset, as straight-line read-modify-writes.
        let old = self.byte(ta);
        let m = pf.at_bit(&mut self.b, to.bit);
        let new = self.b.ins().bor(old, m);
        self.set_byte(ta, new);
        let old = self.byte(fa);
        let m = pf.at_bit(&mut self.b, from.bit);
        let new = self.b.ins().band_not(old, m);
        self.set_byte(fa, new);
    }

    /// `CSCRE`: to the segment end if PF.
    pub(crate) fn scr_cond_end(&mut self, end: usize) {
        let pf = self.pf();
        self.branch_if(pf, end, false);
    }

    /// `SCRE`: the gate opens again.
    pub(crate) fn scr_end(&mut self) {
        let a = self.sched(Sched::SCR_ENABLE);
        let one = self.iconst(I32, 1);
        self.set_byte(a, one);
        self.block.gate = B::K(true);
    }

    /// `IL(002)`: gate := PF (an interlock cannot be lifted by a later IL, omron-cp.md §2.7).
    pub(crate) fn interlock(&mut self) {
        let pf = self.pf();
        let a = self.sched(Sched::SCR_ENABLE);
        let v01 = pf.to01(&mut self.b);
        self.set_byte(a, v01);
        self.block.gate = pf;
    }

    /// The start of an Omron cyclic task: the runtime's `scan::task_start` (flags cleared, gate
    /// open), once per task and scan, so a call rather than an inlined copy of the rule.
    pub(crate) fn task_start(&mut self) {
        self.call_helper(Helper::TaskStart, &[]);
        self.block.gate = B::K(true);
    }

    /// `CALL`: if PF, the callee runs one frame deeper with a fresh stack (its own function);
    /// nesting beyond the profile's limit is error 0x0008 and the call is skipped.
    pub(crate) fn call(&mut self, callee: PouId) {
        let pf = self.pf();
        if pf == B::K(false) {
            return;
        }
        let max = i64::from(self.env.layout.profile.profile().max_call_depth);
        let gate_before = self.block.gate;
        self.guarded(pf, |s| {
            let too_deep =
                s.b.ins()
                    .icmp_imm_s(IntCC::SignedGreaterThanOrEqual, s.func.call_depth, max);
            s.diamond(
                too_deep,
                |s| s.record_error_k(ErrorCode::CallNesting),
                |s| s.run_callee(callee),
            );
        });
        self.block.gate = self.gate_after_call(callee, gate_before);
    }

    /// Calls `callee` one frame deeper with a fresh stack, after forgetting the cache (the callee
    /// may write anything); a fatal status ends this POU too.
    pub(crate) fn run_callee(&mut self, callee: PouId) {
        let fref = match self.func.pou_refs.get(&callee) {
            Some(f) => *f,
            None => {
                let id = self.env.pou_funcs[callee.index()];
                let f = self.module.declare_func_in_func(id, self.b.func);
                self.func.pou_refs.insert(callee, f);
                f
            }
        };
        self.forget_all();
        let d1 = self.b.ins().iadd_imm_s(self.func.call_depth, 1);
        let call = self.b.ins().call(fref, &[self.func.image, d1]);
        let status = self.b.inst_results(call)[0];
        self.side_exit(status, true, |s| s.return_status(status));
    }

    /// The gate after a call of `callee`: unchanged when every exit of the callee leaves it
    /// open (`analysis`), else reloaded from the image.
    pub(crate) fn gate_after_call(&mut self, callee: PouId, gate_before: B) -> B {
        let exits_one = self
            .env
            .info
            .get(callee.index())
            .is_some_and(|i| i.exits_one);
        if exits_one {
            gate_before
        } else {
            self.gate_reload()
        }
    }

    fn gate_reload(&mut self) -> B {
        let a = self.sched(Sched::SCR_ENABLE);
        let v = self.byte(a);
        B::Bit { v, pos: 0 }
    }
}
