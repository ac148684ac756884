//! The lowering's state, grouped by how long it lives.
//!
//! [`Lower`](super::Lower) keeps what the whole program shares ([`Env`](super::Env)), the
//! function builder, and one value per lifetime below it: [`FnState`] lives for the function
//! being built (a POU or one chunk of it), [`BlockState`] for one basic block and is replaced
//! where a block is entered by a jump (cuts of a long straight run keep it), and [`BoxState`]
//! for one box instruction.

use super::cache::{Addr, Cache, StoreLog};
use super::value::{B, Stack};
use cranelift_codegen::ir::{Block, FuncRef, Value};
use cranelift_frontend::{FunctionBuilder, Variable};
use cranelift_module::FuncId;
use std::collections::HashMap;
use stljit_core::{PouId, Width};

/// What holds for the whole function being built: which POU (or chunk) it is, its
/// parameters and the values derived from them, its blocks and declared callees, and what
/// the lowering learnt about it so far.
#[derive(Debug)]
pub(crate) struct FnState {
    /// The POU the function belongs to.
    pub(crate) pou: PouId,
    /// Lowering one chunk of a split POU: its index in the POU's
    /// [`ChunkPlan`](crate::analysis::ChunkPlan).
    pub(crate) chunk: Option<usize>,
    /// The image's first byte (the function's first parameter).
    pub(crate) image: Value,
    /// The first byte of the POU's L frame.
    pub(crate) lbase: Value,
    /// The call depth (the function's second parameter; 0 for the main program).
    pub(crate) call_depth: Value,
    /// The stack register: the logic stack where it crosses a block boundary.
    pub(crate) st: Variable,
    /// The block of every leader op lowered in this function.
    pub(crate) leaders: HashMap<usize, Block>,
    /// Runtime shims declared in this function so far.
    pub(crate) fnrefs: HashMap<FuncId, FuncRef>,
    /// Called POUs declared in this function so far.
    pub(crate) pou_refs: HashMap<PouId, FuncRef>,
    /// Recent stores, for [`Lower::test_byte`](super::Lower::test_byte). A block entered by a
    /// jump marks every byte as stored rather than starting a new log: entries older than the
    /// mark no longer matter, and the log is as large as the image.
    pub(crate) stores: StoreLog,
    /// The first instruction this engine cannot compile, if any.
    pub(crate) unsupported: Option<String>,
}

/// What the lowering knows inside one basic block: the logic stack and the gate as
/// compile-time values, and the image bytes held in SSA values.
#[derive(Debug)]
pub(crate) struct BlockState {
    /// The logic stack, level by level.
    pub(crate) stack: Stack,
    /// The block's entry value of the stack register, to recognise an unchanged stack.
    pub(crate) entry_st: Option<Value>,
    /// The SCR gate (power flow is `S0 AND gate`).
    pub(crate) gate: B,
    /// Image bytes read or written recently in this block.
    pub(crate) cache: Cache,
    /// Code still flows here: false after an unconditional transfer until the next leader.
    pub(crate) open: bool,
}

impl BlockState {
    /// The state in a function's entry block: `stack` as the POU starts with it, the gate
    /// open (a POU starts with gate 1: the main program at the start of a scan, a
    /// subroutine called with PF = 1), nothing cached.
    pub(crate) fn function_entry(stack: Stack) -> BlockState {
        BlockState {
            stack,
            entry_st: None,
            gate: B::K(true),
            cache: Cache::default(),
            open: true,
        }
    }

    /// The state where a block reached by a jump begins: the stack unpacked from the stack
    /// register's value `st` (`depth` levels) and nothing cached, with the cache's op clock
    /// still at `now`. The gate is open until the caller reads it (into this block's cache).
    pub(crate) fn unpack(st: Value, depth: u8, now: usize) -> BlockState {
        BlockState {
            stack: Stack::from_reg(st, depth),
            entry_st: Some(st),
            gate: B::K(true),
            cache: Cache::at(now),
            open: true,
        }
    }

    /// The stack register's value at the end of this block, for a successor that reads the
    /// levels set in `live`, or `None` when the register holds it already (every live level
    /// is still the bit it was unpacked from). Dead levels are packed as 0: nothing reads
    /// them, and most of a long program's stack is old rungs' results that later pushes drop
    /// off the bottom.
    pub(crate) fn pack(&self, live: u32, b: &mut FunctionBuilder<'_>) -> Option<Value> {
        let stack = self.stack.keeping(live);
        let unchanged = self.entry_st.is_some_and(|st| {
            stack.lv.iter().enumerate().all(|(i, l)| {
                live & (1 << i) == 0
                    || *l
                        == B::Bit {
                            v: st,
                            pos: i as u8,
                        }
            })
        });
        (!unchanged).then(|| stack.to_reg(b))
    }

    /// `PF = S0 AND gate`.
    pub(crate) fn pf(&self, b: &mut FunctionBuilder<'_>) -> B {
        self.stack.top().and(b, self.gate)
    }
}

/// The state of the box instruction being lowered (the default outside boxes).
#[derive(Debug, Default)]
pub(crate) struct BoxState {
    /// The box has no pointer operand and no static error: it is lowered branch-free.
    pub(crate) free: bool,
    /// While a branch-free box runs under a power flow that is not constant.
    pub(crate) pred: Option<Pred>,
}

impl BoxState {
    /// The state at the start of a box; `free`: lower it branch-free.
    pub(crate) fn new(free: bool) -> BoxState {
        BoxState { free, pred: None }
    }

    /// The power flow the current box's writes are predicated on, if any.
    pub(crate) fn pf(&self) -> Option<Value> {
        self.pred.as_ref().map(|p| p.pf)
    }
}

/// The predicate of a branch-free box: writes of OUT and SMB1 keep the old value where its
/// power flow is zero (see [`Lower::set_byte_pred`](super::Lower::set_byte_pred)).
#[derive(Debug)]
pub(crate) struct Pred {
    /// The box's power flow as a boolean.
    pub(crate) flow: B,
    /// The same as a truth value for `select` (non-zero = run).
    pub(crate) pf: Value,
    /// Multi-byte values read since the box's last write, reused as the "old" value of a
    /// predicated write (every write of such a box is a no-op when PF is 0, so any value read
    /// inside it is the value at its start).
    pub(crate) reads: Vec<(Addr, Width, Value)>,
}

impl Pred {
    /// A predicate on the power flow `flow` (not a constant) with nothing read yet.
    pub(crate) fn new(flow: B, b: &mut FunctionBuilder<'_>) -> Pred {
        Pred {
            flow,
            pf: flow.cond(b),
            reads: Vec::new(),
        }
    }
}
