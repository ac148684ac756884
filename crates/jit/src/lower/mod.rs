//! Lowering of one POU to one Cranelift function.
//!
//! Every POU becomes `fn(image: i64, depth: i32) -> i32`: `image` is the image's first byte,
//! `depth` the call depth (0 for the main program, which also selects the L frame), and the
//! result 0 to continue or [`ScanStatus::Fatal`] when a fatal error aborted the scan (the error
//! is already recorded in the image). Subroutines are separate functions so that a POU called
//! from many places is compiled once.
//!
//! Straight-line code between two block leaders (see [`crate::analysis`]) is lowered with the
//! logic stack as compile-time booleans ([`value::Stack`]), packed into the stack register (its
//! live levels only) where a block ends, and with recently read or written image bytes reused
//! from SSA values ([`cache::Cache`]); writes are stored at once. Both are the block's
//! [`BlockState`], which a block entered by a jump starts afresh and the cuts of long straight
//! runs, entered only by falling through, keep ([`state`] groups the lowering's state by
//! lifetime). The submodules lower the instruction groups: bit logic, boxes, control flow,
//! memory operands and the stateful instructions that call the runtime.

pub(crate) mod bits;
pub(crate) mod boxes;
pub(crate) mod cache;
pub(crate) mod call;
pub(crate) mod control;
pub(crate) mod ext;
pub(crate) mod flow;
pub(crate) mod mem;
pub(crate) mod omron;
pub(crate) mod rules;
pub(crate) mod state;
pub(crate) mod stateful;
pub(crate) mod value;

use crate::analysis::{ChunkPlan, PouInfo};
use crate::helpers::{Helper, HelperIds};
use cache::Addr;
use cranelift_codegen::ir::{
    Block, FuncRef, InstBuilder, MemFlagsData, SourceLoc, Type, Value,
    types::{I16, I32, I64},
};
use cranelift_frontend::FunctionBuilder;
use cranelift_jit::JITModule;
use cranelift_module::{FuncId, Module};
use state::{BlockState, BoxState, FnState};
use stljit_core::ir::{Op, Program};
use stljit_core::layout::{Layout, Sched};
use stljit_core::{Area, ErrorCode, FatalCode, ScanStatus};
use stljit_runtime::ffi::ValueOp;
use stljit_runtime::rules::Rules;
use value::B;

/// The host addresses compiled code uses as constants. They must stay valid while the code
/// lives: the engine boxes what they point to and keeps it beside the code.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Baked {
    /// The program's boxed [`Layout`], passed to every runtime shim.
    pub(crate) layout: i64,
    /// The program's boxed `runtime::scan::ScanPlan`, passed to the scan prologue shim.
    pub(crate) scan_plan: i64,
    /// The program's boxed `runtime::ffi::NativeRoutines` (its compiled interrupt routines),
    /// passed to the scan prologue shim; 0 for a program without interrupt routines.
    pub(crate) routines: i64,
    /// A `u64` that counts executed ops (the instrumented build for `bench`).
    pub(crate) op_counter: Option<i64>,
}

/// What all POU functions of one program share.
pub(crate) struct Env<'a> {
    pub(crate) prog: &'a Program,
    pub(crate) layout: &'a Layout,
    /// Host addresses baked into the code (the layout passed to every runtime shim, …).
    pub(crate) baked: Baked,
    pub(crate) pou_funcs: Vec<FuncId>,
    pub(crate) helpers: &'a HelperIds,
    pub(crate) info: Vec<PouInfo>,
    /// Per POU, how it is split into chunk functions (`None`: one function).
    pub(crate) plans: Vec<Option<ChunkPlan>>,
    /// [`crate::JitOptions::hot_ops`].
    pub(crate) hot_ops: usize,
    /// Each timer number's resolution (`stljit_runtime::timer::declared_resolutions`).
    pub(crate) timer_res: Vec<Option<u8>>,
    /// [`crate::JitOptions::opt`] (the module's ISA is always at `none`: [`crate::midend`]).
    pub(crate) opt: crate::OptLevel,
    /// The semantic switches the inlined code follows (`Rules::IN_FORCE` but in tests).
    pub(crate) rules: Rules,
    /// The payloads of the s7-200-more ops, passed to the runtime by address.
    pub(crate) ext: &'a ext::ExtKeep,
    /// The image bytes kept one byte per bit in the shadow, in the image's scratch.
    pub(crate) resident: &'a crate::resident::Resident,
}

/// Memory flags for every image access: the image is never null and every direct offset is in
/// range, but words may be unaligned.
pub(crate) fn mf() -> MemFlagsData {
    MemFlagsData::new().with_notrap()
}

/// The state of lowering one function (a POU, or one chunk of a split POU), one field per
/// lifetime: the program's [`Env`] and module, the function's builder and [`FnState`], the
/// current [`BlockState`], op and [`BoxState`].
pub(crate) struct Lower<'e, 'f> {
    pub(crate) env: &'e Env<'e>,
    pub(crate) module: &'e mut JITModule,
    pub(crate) b: FunctionBuilder<'f>,
    /// The function being built.
    pub(crate) func: FnState,
    /// The basic block being lowered.
    pub(crate) block: BlockState,
    /// The op being lowered (recorded as the error site).
    pub(crate) op: usize,
    /// The box instruction being lowered.
    pub(crate) in_box: BoxState,
}

impl<'e, 'f> Lower<'e, 'f> {
    /// The number of logic-stack levels (the program's `logic_stack_depth`).
    pub(crate) fn stack_depth(&self) -> u8 {
        self.env.prog.logic_stack_depth
    }

    /// `PF = S0 AND gate`.
    pub(crate) fn pf(&mut self) -> B {
        self.block.pf(&mut self.b)
    }

    // ---- raw memory --------------------------------------------------------------------------

    /// The base pointer of an address.
    pub(crate) fn base(&self, a: Addr) -> Value {
        if a.local {
            self.func.lbase
        } else {
            self.func.image
        }
    }

    fn off32(a: Addr) -> i32 {
        // Image offsets are far below 2^31 (images are a few kB); checked at compile time.
        a.off as i32
    }

    /// A byte through the cache.
    pub(crate) fn byte(&mut self, a: Addr) -> Value {
        if let Some(v) = self.block.cache.get(a) {
            return v;
        }
        let base = self.base(a);
        let v = self.b.ins().uload8(I32, mf(), base, Self::off32(a));
        self.block.cache.put_clean(a, v);
        v
    }

    /// A byte for a bit test, as a value and the bit where the byte's bit 0 sits in it: the
    /// cached byte (at 0), or else a plain 32-bit load of four bytes around it that were not
    /// stored recently (see [`StoreLog`](cache::StoreLog)), which x86 folds into the consuming `and`/`or`/`andn`
    /// (little-endian: the byte `k` bytes into the load is at bit `8 * k`; the other bytes
    /// are garbage to a [`B`]). The aligned word comes first, so that tests of neighbouring
    /// bytes share one load. Loads are not cached: the cache holds clean bytes.
    pub(crate) fn test_byte(&mut self, a: Addr) -> (Value, u8) {
        if self.block.cache.get(a).is_none() {
            let aligned = a.off & !3;
            let starts = std::iter::once(aligned)
                .chain((a.off.saturating_sub(3)..=a.off).filter(|&s| s != aligned));
            for start in starts {
                let w = Addr {
                    local: a.local,
                    off: start,
                };
                if self.cold_window(w) {
                    return (self.load_window(w), (8 * (a.off - start)) as u8);
                }
            }
        }
        (self.byte(a), 0)
    }

    /// Whether a 32-bit load of the four bytes from `w` stays inside the image (or L frame),
    /// does not cross a 16-byte boundary of the image and overlaps no recent store (see
    /// [`StoreLog`](cache::StoreLog)). The system allocator aligns the image buffer to 16 bytes on the hosts we
    /// run on, so such a load never splits across cache lines; elsewhere it is only slower.
    pub(crate) fn cold_window(&self, w: Addr) -> bool {
        let room = if w.local {
            self.env.layout.area_size(Area::L)
        } else {
            self.env.layout.size
        };
        w.off % 16 <= 12
            && w.off + 4 <= room
            && self.func.stores.is_cold(w, 4, self.block.cache.now)
    }

    /// A plain 32-bit load of the four bytes from `w` (foldable into the instruction that
    /// consumes it; see [`Lower::test_byte`]).
    pub(crate) fn load_window(&mut self, w: Addr) -> Value {
        let base = self.base(w);
        self.b.ins().load(I32, mf(), base, Self::off32(w))
    }

    /// Stores the low byte of `v` (whose upper bits may be garbage, so it is not cached).
    pub(crate) fn store_low_byte(&mut self, a: Addr, v: Value) {
        self.func.stores.stored(a, 1, self.block.cache.now);
        self.block.cache.forget(a, 1);
        let base = self.base(a);
        self.b.ins().istore8(mf(), v, base, Self::off32(a));
    }

    /// Writes a byte (`v` must have its upper 24 bits zero). The store is immediate and the
    /// value stays cached: keeping writes in registers until the block ends made every value
    /// of the block live to its end, which the register allocator paid for with spills.
    pub(crate) fn set_byte(&mut self, a: Addr, v: Value) {
        self.func.stores.stored(a, 1, self.block.cache.now);
        let base = self.base(a);
        self.b.ins().istore8(mf(), v, base, Self::off32(a));
        self.block.cache.put_clean(a, v);
    }

    /// Writes a byte through the cache, keeping the old value where the current box predicate
    /// is zero.
    pub(crate) fn set_byte_pred(&mut self, a: Addr, v: Value) {
        let v = match self.in_box.pf() {
            Some(p) => {
                let old = self.byte(a);
                self.b.ins().select(p, v, old)
            }
            None => v,
        };
        self.set_byte(a, v);
    }

    /// Forgets every cached byte and counts every byte as just stored (before code that may
    /// write anywhere).
    pub(crate) fn forget_all(&mut self) {
        self.block.cache.clear();
        self.func.stores.stored_anywhere(self.block.cache.now);
    }

    /// Loads `ty` in native byte order at a static address (scheduler fields).
    pub(crate) fn load_ne(&mut self, a: Addr, ty: Type) -> Value {
        let base = self.base(a);
        self.b.ins().load(ty, mf(), base, Self::off32(a))
    }

    /// Stores `v` (of type `ty`) in native byte order at a static address.
    pub(crate) fn store_ne(&mut self, a: Addr, v: Value) {
        let ty = self.b.func.dfg.value_type(v);
        self.block.cache.forget(a, ty.bytes());
        self.func.stores.stored(a, ty.bytes(), self.block.cache.now);
        let base = self.base(a);
        self.b.ins().store(mf(), v, base, Self::off32(a));
    }

    /// Image address of a scheduler field.
    pub(crate) fn sched(&self, field: u32) -> Addr {
        Addr::img(self.env.layout.sched(field))
    }

    /// Image address of a byte of an area (L: relative to the current frame).
    pub(crate) fn area_addr(&self, area: Area, off: u32) -> Addr {
        if area == Area::L {
            Addr { local: true, off }
        } else {
            Addr::img(self.env.layout.addr(area, off, 0))
        }
    }

    // ---- helpers and errors ------------------------------------------------------------------

    pub(crate) fn iconst(&mut self, ty: Type, v: i64) -> Value {
        self.b.ins().iconst(ty, v)
    }

    /// Calls a runtime shim after forgetting the cache (it may touch any byte).
    pub(crate) fn call_helper(&mut self, h: Helper, args: &[Value]) -> Value {
        self.forget_all();
        self.call_pure(h, args)
    }

    /// Calls a runtime shim that reads and writes only the image bytes in `ranges`: only they
    /// are forgotten after it, so the rest of the cache stays valid across the call.
    pub(crate) fn call_touching(
        &mut self,
        h: Helper,
        args: &[Value],
        ranges: &[(Addr, u32)],
    ) -> Value {
        let r = self.call_pure(h, args);
        for &(a, n) in ranges {
            self.block.cache.forget(a, n);
            self.func.stores.stored(a, n, self.block.cache.now);
        }
        r
    }

    /// The function `id` of the module as seen from this function (declared at its first use).
    fn func_ref(&mut self, id: FuncId) -> FuncRef {
        if let Some(f) = self.func.fnrefs.get(&id) {
            return *f;
        }
        let f = self.module.declare_func_in_func(id, self.b.func);
        self.func.fnrefs.insert(id, f);
        f
    }

    /// Calls the value shim of `op` (pure: no image, no memory) on `out` and `in1`; returns
    /// the packed outcome.
    pub(crate) fn call_value(&mut self, op: ValueOp, out: Value, in1: Value) -> Value {
        let fref = self.func_ref(self.env.helpers.value(op));
        let call = self.b.ins().call(fref, &[out, in1]);
        self.b.inst_results(call)[0]
    }

    /// Calls a runtime shim that never touches the image.
    pub(crate) fn call_pure(&mut self, h: Helper, args: &[Value]) -> Value {
        let fref = self.func_ref(self.env.helpers.id(h));
        let mut all = Vec::with_capacity(args.len() + 2);
        if h.takes_image() {
            all.push(self.func.image);
            let layout = self.iconst(I64, self.env.baked.layout);
            all.push(layout);
        }
        all.extend_from_slice(args);
        let call = self.b.ins().call(fref, &all);
        self.b.inst_results(call)[0]
    }

    /// Records a non-fatal error for the current op (`code` an `i32` value).
    pub(crate) fn record_error(&mut self, code: Value) {
        let c16 = self.b.ins().ireduce(I16, code);
        let a = self.sched(Sched::LAST_ERR);
        self.store_ne(a, c16);
        self.record_site();
        // SM4.3 (`RUN_Err`), as the runtime's `scan::record_error` sets it.
        if let Some((at, bit)) = stljit_runtime::scan::run_err_bit(self.env.layout) {
            let a = Addr::img(at);
            let v = self.byte(a);
            let v = self.b.ins().bor_imm_s(v, 1 << bit);
            self.set_byte(a, v);
        }
        // Every non-fatal error clears ENO, boxes or not (the interpreter's `error`).
        self.set_eno(B::K(false));
    }

    fn record_site(&mut self) {
        let pou = self.iconst(I16, i64::from(self.func.pou.0 as u16));
        let a = self.sched(Sched::ERR_POU);
        self.store_ne(a, pou);
        let op = self.iconst(I32, self.op as i64);
        let a = self.sched(Sched::ERR_OP);
        self.store_ne(a, op);
    }

    /// Records a statically known non-fatal error.
    pub(crate) fn record_error_k(&mut self, code: ErrorCode) {
        let c = self.iconst(I32, i64::from(code as u16));
        self.record_error(c);
    }

    /// Sets ENO.
    pub(crate) fn set_eno(&mut self, v: B) {
        let v01 = v.to01(&mut self.b);
        let a = self.sched(Sched::ENO);
        self.set_byte(a, v01);
    }

    /// Emits the fatal exit of the current op in the current block: record, return.
    pub(crate) fn fatal_here(&mut self, code: FatalCode) {
        let c = self.iconst(I16, i64::from(code as u16));
        let a = self.sched(Sched::FATAL);
        self.store_ne(a, c);
        self.record_site();
        let st = self.iconst(I32, ScanStatus::Fatal as i64);
        self.return_status(st);
    }

    /// Leaves the POU with `status` (an `i32`: 0 = continue, else the scan's status). A chunk
    /// function returns it as an `i64` whose upper half 0 means "the POU returns".
    pub(crate) fn return_status(&mut self, status: Value) {
        if self.func.chunk.is_some() {
            let r = self.b.ins().uextend(I64, status);
            self.b.ins().return_(&[r]);
        } else {
            self.b.ins().return_(&[status]);
        }
    }

    /// Branches to a (cold) fatal exit when `cond` (non-zero) holds.
    pub(crate) fn fatal_if(&mut self, cond: Value, code: FatalCode) {
        self.side_exit(cond, true, |s| s.fatal_here(code));
    }

    // ---- blocks ------------------------------------------------------------------------------

    /// Writes the stack register back (end of a block that continues at op `target`), with
    /// the levels live at `target` ([`crate::analysis::PouInfo`]'s `stack_live`).
    pub(crate) fn spill_state(&mut self, target: usize) {
        let live = self.env.info[self.func.pou.index()]
            .stack_live
            .get(target)
            .copied()
            .unwrap_or(u32::MAX);
        if let Some(r) = self.block.pack(live, &mut self.b) {
            self.b.def_var(self.func.st, r);
        }
    }

    /// Starts lowering in `blk`, a block reached by a jump (or an unreachable one), with a
    /// fresh [`BlockState`]: the stack from the stack register, the gate from the analysis or
    /// the image.
    pub(crate) fn enter(&mut self, blk: Block, at_op: usize) {
        // Reached by a jump or as a function entry: earlier stores are not in the log.
        self.func.stores.stored_anywhere(at_op);
        self.b.switch_to_block(blk);
        let st = self.b.use_var(self.func.st);
        self.block = BlockState::unpack(st, self.stack_depth(), self.block.cache.now);
        self.block.gate = self.gate_at(at_op);
    }

    /// The gate at the start of op `at` of this POU: 1 where the analysis proves it, else read.
    pub(crate) fn gate_at(&mut self, at: usize) -> B {
        let known = self.env.info[self.func.pou.index()]
            .gate_one
            .get(at)
            .copied()
            .unwrap_or(false);
        if known {
            B::K(true)
        } else {
            let a = self.sched(Sched::SCR_ENABLE);
            let v = self.byte(a);
            B::Bit { v, pos: 0 }
        }
    }

    /// Ends the current block with a jump to the leader at op `target`.
    pub(crate) fn jump_to_op(&mut self, target: usize) {
        if let Some(&blk) = self.func.leaders.get(&target) {
            self.spill_state(target);
            self.b.ins().jump(blk, &[]);
        } else if let Some(k) = self.func.chunk {
            self.exit_chunk_to(k, target);
        } else {
            // The analysis makes every target a leader; returning keeps codegen total anyway.
            self.ret_ok();
        }
    }

    /// Leaves chunk `k` to continue at op `target` of another chunk: returns
    /// `(target + 1) << 32 | stack register` to the POU's dispatcher.
    fn exit_chunk_to(&mut self, k: usize, target: usize) {
        let plan = self.env.plans[self.func.pou.index()].as_ref();
        let planned = plan.is_some_and(|p| p.entries[p.chunk_of(target)].contains(&target));
        if !planned && self.func.unsupported.is_none() {
            // The plan lists every cross-chunk target; anything else is a bug in this crate.
            self.func.unsupported = Some(format!("chunk {k}: unplanned exit to op {target}"));
        }
        self.spill_state(target);
        let st = self.b.use_var(self.func.st);
        let st = self.b.ins().uextend(I64, st);
        let r = self.b.ins().bor_imm_s(st, ((target as i64) + 1) << 32);
        self.b.ins().return_(&[r]);
    }

    /// Returns 0 (continue).
    pub(crate) fn ret_ok(&mut self) {
        let z = self.iconst(I32, 0);
        self.return_status(z);
    }

    /// Lowers the whole POU as one function.
    pub(crate) fn lower_pou(&mut self) {
        let pou = self.env.prog.pou(self.func.pou);
        let info = &self.env.info[self.func.pou.index()];
        // Op 0 needs a block only when a jump targets it (a loop to the top of the POU).
        let top_targeted = pou.ops.iter().any(|op| {
            matches!(op, Op::Jump(l) if pou.labels.get(l.index()).is_some_and(|t| t.index() == 0))
        });
        for (i, &lead) in info.leader.iter().enumerate() {
            if lead && (i != 0 || top_targeted) {
                let blk = self.b.create_block();
                self.func.leaders.insert(i, blk);
            }
        }
        // The end of the op list is a leader too, for jumps past the last op.
        let end = pou.ops.len();
        let end_blk = self.b.create_block();
        self.func.leaders.insert(end, end_blk);
        self.lower_ops(0..end);
        self.lower_end(end);
    }

    /// Lowers chunk `k` of a split POU. The function's parameters `st_in` (the stack register)
    /// and `at` (the op to start at, one of the chunk's planned entries) come from the
    /// dispatcher; leaving the chunk's range returns to it (see [`Lower::exit_chunk_to`]).
    pub(crate) fn lower_chunk(&mut self, k: usize, st_in: Value, at: Value) {
        let pou = self.env.prog.pou(self.func.pou);
        let n = pou.ops.len();
        let Some(plan) = self.env.plans[self.func.pou.index()].as_ref() else {
            self.func.unsupported = Some("chunk of an unsplit POU".into());
            return;
        };
        let range = plan.range(k, n);
        let last = k + 1 == plan.starts.len();
        let info = &self.env.info[self.func.pou.index()];
        for i in range.clone() {
            if info.leader[i] || i == range.start {
                let blk = self.b.create_block();
                self.func.leaders.insert(i, blk);
            }
        }
        if last {
            let end_blk = self.b.create_block();
            self.func.leaders.insert(n, end_blk);
        }
        self.b.def_var(self.func.st, st_in);
        let start = self.func.leaders[&range.start];
        match plan.entries[k].as_slice() {
            [_] => {
                self.b.ins().jump(start, &[]);
            }
            entries => {
                let mut sw = cranelift_frontend::Switch::new();
                for e in entries {
                    sw.set_entry(*e as u128, self.func.leaders[e]);
                }
                sw.emit(&mut self.b, at, start);
            }
        }
        self.block.open = false;
        self.lower_ops(range.clone());
        if last {
            self.lower_end(n);
        } else if self.block.open {
            self.exit_chunk_to(k, range.end);
            self.block.open = false;
        }
    }

    /// The end of the POU: falls into (or is jumped to as) the final leader and returns 0.
    fn lower_end(&mut self, end: usize) {
        let Some(&end_blk) = self.func.leaders.get(&end) else {
            return;
        };
        if self.block.open {
            self.spill_state(end);
            self.b.ins().jump(end_blk, &[]);
        }
        self.enter(end_blk, end);
        self.b.set_srcloc(SourceLoc::default());
        self.ret_ok();
        self.block.open = false;
    }

    /// Lowers the ops in `range`, starting a new block at every leader.
    fn lower_ops(&mut self, range: std::ops::Range<usize>) {
        let pou = self.env.prog.pou(self.func.pou);
        for i in range {
            let op = &pou.ops[i];
            if let Some(&blk) = self.func.leaders.get(&i) {
                let cut = self.env.info[self.func.pou.index()].cut[i];
                if self.block.open && cut {
                    // Only this block falls into a cut: the block state (logic stack, gate,
                    // cached bytes) carries over as it is.
                    self.b.ins().jump(blk, &[]);
                    self.b.switch_to_block(blk);
                } else {
                    if self.block.open {
                        // (At op 0 this writes the initial stack into the register.)
                        self.spill_state(i);
                        self.b.ins().jump(blk, &[]);
                    }
                    self.enter(blk, i);
                }
            }
            if !self.block.open {
                // Unreachable ops after an unconditional transfer: lower them into a block
                // without predecessors so that every op still has CLIF (and a srcloc).
                let blk = self.b.create_block();
                self.enter(blk, i);
            }
            self.op = i;
            self.block.cache.now = i;
            self.b.set_srcloc(SourceLoc::new(i as u32 + 1));
            if let Some(addr) = self.env.baked.op_counter {
                let a = self.iconst(I64, addr);
                let n = self.b.ins().load(I64, mf(), a, 0);
                let n = self.b.ins().iadd_imm_s(n, 1);
                self.b.ins().store(mf(), n, a, 0);
            }
            self.lower_op(op);
        }
    }

    /// Lowers one op: the one match over [`Op`], so a new op is a compile error here and
    /// nowhere else in the lowering.
    fn lower_op(&mut self, op: &Op) {
        match *op {
            Op::Load(ref c) => self.load(c),
            Op::And(ref c) => self.combine(c, true),
            Op::Or(ref c) => self.combine(c, false),
            Op::Not => self.not(),
            Op::AndBlock => self.combine_block(true),
            Op::OrBlock => self.combine_block(false),
            Op::Dup => self.dup(),
            Op::ReadSecond => self.read_second(),
            Op::Pop => {
                self.block.stack.pop();
            }
            Op::Pick(n) => self.pick(n),
            Op::AndEno => self.and_eno(),
            Op::Edge { slot, falling } => self.edge(slot.0, falling),
            Op::Assign { bit, immediate } => self.assign(bit, immediate),
            Op::SetRange {
                start,
                ref count,
                value,
                immediate,
            } => self.set_range(start, count, value, immediate),
            Op::ResetTimers { first, ref count } => {
                self.reset_range(Helper::TimerReset, u32::from(first.0), count)
            }
            Op::ResetCounters { first, ref count } => {
                self.reset_range(Helper::CounterReset, u32::from(first.0), count)
            }
            Op::Timer {
                kind,
                timer,
                ref preset,
            } => self.timer(kind, timer.0, preset),
            Op::Counter {
                kind,
                counter,
                ref preset,
            } => self.counter(kind, counter.0, preset),
            Op::Box(ref bx) => self.lower_box(bx),
            Op::Jump(l) => self.jump(l),
            Op::Label(_) | Op::Nop => {}
            Op::Call(callee) => self.call(callee),
            Op::CallArgs(ref c) => self.call_args(c),
            Op::Return { conditional } | Op::End { conditional } => self.ret(conditional),
            Op::Stop => self.stop(),
            Op::Wdr => self.wdr(),
            Op::Interrupt(i) => self.interrupt(i),
            Op::For {
                ref index,
                ref init,
                ref limit,
                next,
            } => self.for_loop(index, init, limit, next.index()),
            Op::Next { head } => self.next(head.index()),
            Op::ScrBegin { bit } => self.scr_begin(bit),
            Op::ScrTransition { to, from } => self.scr_transition(to, from),
            Op::ScrCondEnd { end } => self.scr_cond_end(end.index()),
            Op::ScrEnd | Op::InterlockEnd => self.scr_end(),
            Op::Interlock => self.interlock(),
            Op::TaskStart => self.task_start(),
            Op::OmronTimer {
                kind,
                timer,
                ref set_value,
            } => self.omron_timer(kind, timer.0, set_value),
            Op::OmronCounter {
                kind,
                counter,
                ref set_value,
            } => self.omron_counter(kind, counter.0, set_value),
            Op::Omron(ref bx) => self.omron_box(bx),
            Op::Ext(ref bx) => self.ext_box(bx),
            Op::StrCompare(ref c) => self.str_compare(c),
        }
    }
}
