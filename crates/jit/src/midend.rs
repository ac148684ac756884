//! The mid-end: Cranelift's own optimisations at the level the options ask for, then the passes
//! that must see their result, on every function just before it is compiled.
//!
//! The module's ISA is always built at `opt_level = none`, so that `define_function` lowers the
//! function exactly as this mid-end left it; at `--opt speed` the e-graph pass runs here, on an
//! ISA of its own that differs only in that flag (Cranelift reads the flag nowhere else).
//!
//! **Shorter byte loads.** Cranelift's x86-64 back end lowers `uload8` to `movzbq` whatever the
//! result type, and the `REX.W` prefix that asks for 64 bits costs a byte: `movzbl` zero-extends
//! to 64 bits too. A `uextend.i32` of a single-use `load.i8` right after it is lowered to
//! `movzbl` with the load folded in. The rewrite must come after the e-graph pass: that pass
//! places a pure `uextend` just before its first use, often past a store, where the back end
//! may no longer fold the load into it (then it emits `movzbq` and a `movzbl` of the register).
//! Lowering and the passes before this one keep writing and recognising `uload8`; this changes
//! only the instruction that loads, not the value.

use crate::{JitError, JitOptions, OptLevel};
use cranelift_codegen::Context;
use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::cursor::{Cursor, FuncCursor};
use cranelift_codegen::entity::SecondaryMap;
use cranelift_codegen::ir::{Function, InstBuilder, InstructionData, Opcode, Value, types};
use cranelift_codegen::isa::OwnedTargetIsa;

/// The mid-end of one compilation (module docs).
pub(crate) struct Midend {
    /// The ISA to run the e-graph pass with; `None` at `--opt none`.
    egraph: Option<OwnedTargetIsa>,
}

impl Midend {
    /// The mid-end for `opts`.
    pub(crate) fn new(opts: &JitOptions) -> Result<Self, JitError> {
        let egraph = match opts.opt {
            OptLevel::None => None,
            OptLevel::Speed => Some(crate::build::host_isa(opts, "speed")?),
        };
        Ok(Midend { egraph })
    }

    /// Optimises `ctx.func` in place; `define_function` then only lowers it.
    pub(crate) fn run(&self, ctx: &mut Context) -> Result<(), JitError> {
        if let Some(isa) = &self.egraph {
            ctx.optimize(isa.as_ref(), &mut ControlPlane::default())
                .map_err(|e| JitError::Codegen(format!("{e:?}")))?;
        }
        narrow_byte_loads(&mut ctx.func);
        Ok(())
    }
}

/// Rewrites `func`'s `uload8.i32` loads as `uextend.i32(load.i8)` (module docs); returns how
/// many.
pub(crate) fn narrow_byte_loads(func: &mut Function) -> usize {
    let mut loads = Vec::new();
    for block in func.layout.blocks() {
        for inst in func.layout.block_insts(block) {
            if let InstructionData::Load {
                opcode: Opcode::Uload8,
                ..
            } = func.dfg.insts[inst]
                && func.dfg.ctrl_typevar(inst) == types::I32
            {
                loads.push(inst);
            }
        }
    }
    let shared = used_more_than_once(func);
    loads.retain(|&inst| !shared[func.dfg.first_result(inst)]);
    for &inst in &loads {
        let InstructionData::Load {
            arg, flags, offset, ..
        } = func.dfg.insts[inst]
        else {
            continue;
        };
        let mut pos = FuncCursor::new(func).at_inst(inst);
        let flags = pos.func.dfg.mem_flags[flags];
        let byte = pos.ins().load(types::I8, flags, arg, offset);
        pos.func.replace(inst).uextend(types::I32, byte);
    }
    loads.len()
}

/// The values the back end counts as used more than once (`ValueUseState::Multiple` in
/// Cranelift's lowering): used by two instructions, or an operand, at any depth, of a
/// single-result instruction whose value is (the back end may compute such a value at each use).
/// A load is folded into its user only if its value is not among them.
fn used_more_than_once(func: &Function) -> SecondaryMap<Value, bool> {
    let mut uses: SecondaryMap<Value, u8> = SecondaryMap::new();
    for block in func.layout.blocks() {
        for inst in func.layout.block_insts(block) {
            for v in func.dfg.inst_values(inst) {
                uses[v] = uses[v].saturating_add(1);
            }
        }
    }
    let mut shared: SecondaryMap<Value, bool> = SecondaryMap::new();
    let mut work: Vec<Value> = uses
        .iter()
        .filter(|&(_, &n)| n > 1)
        .map(|(v, _)| v)
        .collect();
    for &v in &work {
        shared[v] = true;
    }
    while let Some(v) = work.pop() {
        let Some(def) = func.dfg.value_def(v).inst() else {
            continue;
        };
        if func.dfg.inst_results(def).len() > 1 {
            continue;
        }
        for arg in func.dfg.inst_values(def) {
            if !shared[arg] {
                shared[arg] = true;
                work.push(arg);
            }
        }
    }
    shared
}

#[cfg(test)]
#[path = "midend_tests.rs"]
mod tests;
