//! Control flow inside one op: side exits, two-armed diamonds and the frame every box
//! instruction runs in.
//!
//! All keep the byte cache across the op: a side exit (a conditional jump, return or fatal
//! exit) runs on a copy of the cache and the fall-through continues with the original; the
//! arms of a diamond or box start from a copy of the cache at the branch, and the join keeps
//! only the entries no arm replaced ([`Cache::meet`]). The logic stack and the gate are
//! untouched by these ops, so their compile-time values stay valid after the join.

use super::Lower;
use super::cache::{Cache, EnoFact};
use super::mem::OnFail;
use super::state::Pred;
use super::value::B;
use cranelift_codegen::ir::{Block, InstBuilder, Value, types::I32};
use stljit_core::layout::Sched;

/// The arms of one branching op on their way to `join`: the cache at the branch, which every
/// arm starts from, and the cache each finished arm left.
pub(crate) struct Arms {
    start: Cache,
    ends: Vec<Cache>,
    join: Block,
}

impl Lower<'_, '_> {
    /// Starts the "clone the cache, build the arms, meet" protocol of an op that branches and
    /// joins again at `join`: every arm starts from the cache as it is now
    /// ([`Lower::start_arm`]), ends with a jump to `join` ([`Lower::end_arm`]), and
    /// [`Lower::join_arms`] continues at `join` with the entries no arm changed.
    pub(crate) fn fork(&self, join: Block) -> Arms {
        Arms {
            start: self.block.cache.clone(),
            ends: Vec::with_capacity(3),
            join,
        }
    }

    /// Continues in `block`, an arm, with the cache of the branch.
    pub(crate) fn start_arm(&mut self, arms: &Arms, block: Block) {
        self.b.switch_to_block(block);
        self.block.cache = arms.start.clone();
    }

    /// Ends the current arm: remembers its cache and jumps to the join.
    pub(crate) fn end_arm(&mut self, arms: &mut Arms) {
        arms.ends.push(std::mem::take(&mut self.block.cache));
        self.b.ins().jump(arms.join, &[]);
    }

    /// Continues at the join with the entries every arm left untouched.
    pub(crate) fn join_arms(&mut self, arms: Arms) {
        self.b.seal_block(arms.join);
        self.b.switch_to_block(arms.join);
        self.block.cache = Cache::meet(&arms.ends);
    }

    /// `if cond { exit }`, where `exit` leaves for good (a jump to another block, a return, a
    /// fatal exit) and `cold` marks it rarely taken. Code continues in a fresh block whose
    /// only predecessor is the branch, so the block state carries on as it was before the
    /// exit: the exit starts from a copy of the cache and whatever it forgets stays forgotten
    /// only there.
    pub(crate) fn side_exit(&mut self, cond: Value, cold: bool, exit: impl FnOnce(&mut Self)) {
        let (out, cont) = (self.b.create_block(), self.b.create_block());
        if cold {
            self.b.set_cold_block(out);
        }
        self.b.ins().brif(cond, out, &[], cont, &[]);
        self.b.seal_block(out);
        self.b.seal_block(cont);
        self.b.switch_to_block(out);
        let kept = self.block.cache.clone();
        exit(self);
        self.block.cache = kept;
        self.b.switch_to_block(cont);
    }

    /// `if cond { then } else { other }` with the cache kept across.
    pub(crate) fn diamond(
        &mut self,
        cond: Value,
        then: impl FnOnce(&mut Self),
        other: impl FnOnce(&mut Self),
    ) {
        let (t, e, j) = (
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
        );
        let mut arms = self.fork(j);
        self.b.ins().brif(cond, t, &[], e, &[]);
        self.b.seal_block(t);
        self.b.seal_block(e);
        self.start_arm(&arms, t);
        then(self);
        self.end_arm(&mut arms);
        self.start_arm(&arms, e);
        other(self);
        self.end_arm(&mut arms);
        self.join_arms(arms);
    }

    /// Runs a box instruction (spec §4.0): nothing but `ENO = 0` when PF is 0; otherwise `run`
    /// reads its inputs, computes and writes, returning ENO (1, or 0 for a flag-rule failure). A
    /// pointer that fails to resolve (or an explicit branch to the failure block with a code)
    /// records the error and clears ENO, writing nothing.
    pub(crate) fn boxed(&mut self, run: impl FnOnce(&mut Self, OnFail) -> B) {
        let pf = self.pf();
        if pf == B::K(false) {
            self.set_eno(B::K(false));
            return;
        }
        if self.in_box.free {
            self.boxed_free(pf, run);
            return;
        }
        self.run_failing(pf, true, |s, fail| {
            let eno = run(s, fail);
            s.set_eno(eno);
        });
    }

    /// Runs `run` where `pf` (not constant 0) holds, with a failure block for pointer operands
    /// (and explicit failures) that records the error; with `eno` (boxes) the failure and skip
    /// paths also clear ENO. The arms (run, error, and skip unless PF is 1) join with the cache
    /// kept across.
    pub(crate) fn run_failing(&mut self, pf: B, eno: bool, run: impl FnOnce(&mut Self, OnFail)) {
        let (r, err, j) = (
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
        );
        let code = self.b.append_block_param(err, I32);
        let mut arms = self.fork(j);
        let skip = if pf == B::K(true) {
            self.b.ins().jump(r, &[]);
            None
        } else {
            let s = self.b.create_block();
            let c = pf.cond(&mut self.b);
            self.b.ins().brif(c, r, &[], s, &[]);
            self.b.seal_block(s);
            Some(s)
        };
        self.b.seal_block(r);
        self.start_arm(&arms, r);
        run(self, OnFail::Branch(err));
        self.end_arm(&mut arms);

        self.b.seal_block(err);
        self.start_arm(&arms, err);
        self.record_error(code);
        if eno {
            self.set_eno(B::K(false));
        }
        self.end_arm(&mut arms);

        if let Some(s) = skip {
            self.start_arm(&arms, s);
            if eno {
                self.set_eno(B::K(false));
            }
            self.end_arm(&mut arms);
        }
        self.join_arms(arms);
    }

    /// A box that cannot fail (no pointer operand, no static error) runs on every path; its
    /// writes of OUT and SMB1 select the old value where PF is 0, and `ENO = PF AND ok`. This
    /// leaves exactly the bytes of the branching form without splitting the block, so the byte
    /// cache stays valid across the box.
    fn boxed_free(&mut self, pf: B, run: impl FnOnce(&mut Self, OnFail) -> B) {
        self.in_box.pred = match pf {
            B::K(_) => None,
            B::Bit { .. } | B::Not { .. } => Some(Pred::new(pf, &mut self.b)),
        };
        // No operand is a pointer, so nothing takes this failure path; a compare's fatal code
        // is only a placeholder.
        let ok = run(self, OnFail::Fatal(stljit_core::FatalCode::CompareIndirect));
        self.in_box.pred = None;
        let eno = pf.and(&mut self.b, ok);
        self.set_eno(eno);
        // PF is the top AND the gate, so ENO implies the top (see `and_eno`).
        let byte = self.block.cache.get(self.sched(Sched::ENO));
        self.block.cache.eno = byte.map(|byte| EnoFact {
            byte,
            value: eno,
            top: self.block.stack.top(),
        });
    }

    /// Branches to the failure block with a static error code when `cond` holds.
    pub(crate) fn fail_if(&mut self, cond: Value, fail: OnFail, code: u16) {
        if let OnFail::Branch(err) = fail {
            let cont = self.b.create_block();
            let c = self.iconst(I32, i64::from(code));
            self.b.ins().brif(
                cond,
                err,
                &[cranelift_codegen::ir::BlockArg::Value(c)],
                cont,
                &[],
            );
            self.b.seal_block(cont);
            self.b.switch_to_block(cont);
        }
    }

    /// Jumps to the failure block unconditionally (a statically known error) and continues in an
    /// unreachable block so the caller's code stays well-formed.
    pub(crate) fn fail_now(&mut self, fail: OnFail, code: u16) {
        let one = self.iconst(I32, 1);
        self.fail_if(one, fail, code);
    }
}
