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
//!
//! **Short byte masks.** A coil or a flag writes a byte as `(old AND mask) OR bits`, and the
//! mask of a bit 0..=6 (`0xF7`, ...) does not fit x86's sign-extended 8-bit immediate: `and`
//! takes a 4-byte one (1,135 of them in mixed_10k). With all upper bits set (`0xFFFFFFF7`,
//! i.e. -9) it fits, and the low byte is the same. The rewrite is exact where nothing observes
//! the upper bits: the result of an `and`/`or`/`xor` only ever reaches byte stores through
//! bitwise operations and selects (`low_byte_only`), or an `and` whose other operand has no
//! bit above the low byte anyway (a byte load, say: `zero_above_byte`).
//!
//! **Byte-wide bit tests.** x86 `test` has no 8-bit immediate form for 32-bit operands: a bit
//! test `x AND K` (K <= 0xFF) that only decides a branch or a select is a 6-byte `testl $K`
//! (617 in mixed_10k). On the low byte of `x` (`ireduce.i8`, no instruction) it is a 3-byte
//! `testb $K`; the truth of `x AND K` is the same.
//!
//! **Constants near their uses.** The e-graph pass defines equal constants once per block, so a
//! constant that many timers, counters or boxes of a long block use where the back end needs it
//! in a register (a `select` arm is a `cmov` source: the timers' `0` and `0x7FFF`, the flags'
//! overflow bits) stays in a register from its first use to its last, across the bit logic in
//! between, and the register allocator spills other values (often the extra base pointers) to
//! make room. Each use whose previous use of the same constant is more than
//! [`CONSTANT_REACH`] instructions back gets a definition of its own just before it (measured:
//! 0.4-2.2 % fewer code bytes on eight generated S7 programs of 3,000-10,000 instructions, where
//! every use on its own was worse for the zeros of Omron programs). A use that takes an
//! immediate costs nothing either way. At `--opt none` there is no e-graph pass and the pass
//! does not run: lowering already defines a constant where it uses it.
//!
//! **Short displacements** ([`crate::rebase`]) come last, at every level: runs of nearby far
//! image accesses get a base pointer defined just before them, which the e-graph pass would
//! merge into one long-lived pointer again.

use crate::{JitError, JitOptions, OptLevel};
use cranelift_codegen::Context;
use cranelift_codegen::control::ControlPlane;
use cranelift_codegen::cursor::{Cursor, FuncCursor};
use cranelift_codegen::entity::SecondaryMap;
use cranelift_codegen::ir::{Function, Inst, InstBuilder, InstructionData, Opcode, Value, types};
use cranelift_codegen::isa::OwnedTargetIsa;
use std::collections::HashMap;

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
        // Before the load narrowing, which then also narrows the loads the tests read.
        byte_tests(&mut ctx.func);
        narrow_byte_loads(&mut ctx.func);
        short_byte_masks(&mut ctx.func);
        // Only the e-graph pass shares constants across a block; lowering defines one per use.
        if self.egraph.is_some() {
            local_constants(&mut ctx.func);
        }
        // Last: the e-graph pass would merge its local base pointers into one.
        crate::rebase::shorten_displacements(&mut ctx.func);
        Ok(())
    }
}

/// How many instructions apart two uses of one constant may be and still share its definition
/// ([`local_constants`]).
const CONSTANT_REACH: usize = 4;

/// Defines a constant again just before a use whose previous use in the block is more than
/// [`CONSTANT_REACH`] instructions back (module docs); returns how many definitions it added.
pub(crate) fn local_constants(func: &mut Function) -> usize {
    let mut added = 0;
    let blocks: Vec<_> = func.layout.blocks().collect();
    for block in blocks {
        // Per constant (type and bits): the definition its last use took, and where that was.
        let mut last: HashMap<(types::Type, i64), (Value, usize)> = HashMap::new();
        let insts: Vec<Inst> = func.layout.block_insts(block).collect();
        for (at, inst) in insts.into_iter().enumerate() {
            if func.dfg.insts[inst].opcode() == Opcode::Iconst {
                continue;
            }
            for i in 0..func.dfg.inst_args(inst).len() {
                let arg = func.dfg.inst_args(inst)[i];
                let Some(def) = func.dfg.value_def(arg).inst() else {
                    continue;
                };
                let InstructionData::UnaryImm {
                    opcode: Opcode::Iconst,
                    imm,
                } = func.dfg.insts[def]
                else {
                    continue;
                };
                let ty = func.dfg.value_type(arg);
                let k = match last.get(&(ty, imm.bits())) {
                    Some(&(k, prev)) if at - prev <= CONSTANT_REACH => k,
                    _ => {
                        added += 1;
                        FuncCursor::new(func).at_inst(inst).ins().iconst(ty, imm)
                    }
                };
                last.insert((ty, imm.bits()), (k, at));
                func.dfg.inst_args_mut(inst)[i] = k;
            }
        }
    }
    added
}

/// Rewrites `func`'s `uload8.i32` loads as `uextend.i32(load.i8)` (module docs); returns how
/// many.
pub(crate) fn narrow_byte_loads(func: &mut Function) -> usize {
    let mut loads = Vec::new();
    for inst in layout_insts(func) {
        if let InstructionData::Load {
            opcode: Opcode::Uload8,
            ..
        } = func.dfg.insts[inst]
            && func.dfg.ctrl_typevar(inst) == types::I32
        {
            loads.push(inst);
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

/// Gives byte masks whose result only reaches byte stores an 8-bit immediate (module docs);
/// returns how many masks changed.
pub(crate) fn short_byte_masks(func: &mut Function) -> usize {
    let low = low_byte_only(func);
    let mut masks = Vec::new();
    for inst in layout_insts(func) {
        let InstructionData::Binary { opcode, args } = func.dfg.insts[inst] else {
            continue;
        };
        if !matches!(opcode, Opcode::Band | Opcode::Bor | Opcode::Bxor)
            || func.dfg.ctrl_typevar(inst) != types::I32
        {
            continue;
        }
        for (i, &arg) in args.iter().enumerate() {
            let Some(k) = iconst_of(func, arg).filter(|k| (0x80..=0xff).contains(k)) else {
                continue;
            };
            // An `and` of a byte value keeps its upper bits zero either way; otherwise
            // nothing may look at the upper bits of the result.
            let other = args[1 - i];
            if low[func.dfg.first_result(inst)]
                || (opcode == Opcode::Band && zero_above_byte(func, other, 8))
            {
                masks.push((inst, i, k));
            }
        }
    }
    for &(inst, i, k) in &masks {
        let mut pos = FuncCursor::new(func).at_inst(inst);
        // The same low byte with every higher bit set: -128..=-1, an 8-bit immediate.
        let short = pos.ins().iconst(types::I32, k | 0xffff_ff00);
        if let InstructionData::Binary { args, .. } = &mut pos.func.dfg.insts[inst] {
            args[i] = short;
        }
    }
    masks.len()
}

/// Narrows bit tests of a low byte to 8 bits (module docs); returns how many.
pub(crate) fn byte_tests(func: &mut Function) -> usize {
    // Per value: its uses, and how many of them are the condition of a branch or a select.
    let mut uses: SecondaryMap<Value, (u32, u32)> = SecondaryMap::new();
    let mut tests = Vec::new();
    for inst in layout_insts(func) {
        let chooses = is_choice(&func.dfg.insts[inst]);
        for (i, v) in func.dfg.inst_values(inst).enumerate() {
            uses[v].0 += 1;
            uses[v].1 += u32::from(chooses && i == 0);
        }
        if let InstructionData::Binary {
            opcode: Opcode::Band,
            args,
        } = func.dfg.insts[inst]
            && func.dfg.ctrl_typevar(inst) == types::I32
        {
            for i in 0..2 {
                if let Some(k) = iconst_of(func, args[i]).filter(|&k| k <= 0xff) {
                    tests.push((inst, args[1 - i], k));
                    break;
                }
            }
        }
    }
    let mut narrowed: SecondaryMap<Value, Option<Value>> = SecondaryMap::new();
    let mut count = 0;
    for (inst, x, k) in tests {
        let v = func.dfg.first_result(inst);
        let (all, conditions) = uses[v];
        if all == 0 || all != conditions {
            continue;
        }
        let mut pos = FuncCursor::new(func).at_inst(inst);
        let low = pos.ins().ireduce(types::I8, x);
        narrowed[v] = Some(pos.ins().band_imm_u(low, k));
        count += 1;
    }
    if count > 0 {
        let choices: Vec<Inst> = layout_insts(func)
            .filter(|&i| is_choice(&func.dfg.insts[i]))
            .collect();
        for inst in choices {
            match &mut func.dfg.insts[inst] {
                InstructionData::Brif { arg, .. } => {
                    if let Some(bits) = narrowed[*arg] {
                        *arg = bits;
                    }
                }
                InstructionData::Ternary { args, .. } => {
                    if let Some(bits) = narrowed[args[0]] {
                        args[0] = bits;
                    }
                }
                _ => {}
            }
        }
    }
    count
}

/// Whether `data` is a branch or a select, whose first operand is a condition.
fn is_choice(data: &InstructionData) -> bool {
    matches!(
        data,
        InstructionData::Brif { .. }
            | InstructionData::Ternary {
                opcode: Opcode::Select,
                ..
            }
    )
}

/// Whether `v`, an `i32`, is known to have only its low 8 bits set (a byte load, a byte
/// zero-extended, a small constant, an `and` with one of them, an `or`/`xor` of two), looking
/// `depth` definitions deep.
fn zero_above_byte(func: &Function, v: Value, depth: u32) -> bool {
    if let Some(k) = iconst_of(func, v) {
        return k <= 0xff;
    }
    let Some(inst) = func.dfg.value_def(v).inst() else {
        return false;
    };
    if depth == 0 {
        return false;
    }
    match func.dfg.insts[inst] {
        InstructionData::Load {
            opcode: Opcode::Uload8,
            ..
        } => true,
        InstructionData::Unary {
            opcode: Opcode::Uextend,
            arg,
        } => func.dfg.value_type(arg) == types::I8,
        InstructionData::Binary {
            opcode: Opcode::Band,
            args: [a, b],
        } => zero_above_byte(func, a, depth - 1) || zero_above_byte(func, b, depth - 1),
        InstructionData::Binary {
            opcode: Opcode::Bor | Opcode::Bxor,
            args: [a, b],
        } => zero_above_byte(func, a, depth - 1) && zero_above_byte(func, b, depth - 1),
        _ => false,
    }
}

/// The value of `v` if an `iconst` defines it, as its low 32 bits.
fn iconst_of(func: &Function, v: Value) -> Option<i64> {
    crate::dse::iconst(func, v).map(|k| k & 0xffff_ffff)
}

/// The values only whose low 8 bits anything observes: every use is the stored value of an
/// `istore8`, the operand of a bitwise `and`/`or`/`xor`/`not` whose own value is such a value,
/// or an arm of such a `select`. Computed as the greatest fixed point: all values start in, and a
/// value leaves at any other use (a block argument, a shift, a compare, a wider store ...).
fn low_byte_only(func: &Function) -> SecondaryMap<Value, bool> {
    let mut low: SecondaryMap<Value, bool> = SecondaryMap::with_default(true);
    // Uses before definitions, so one pass settles straight-line code; a second confirms.
    let order: Vec<Inst> = layout_insts(func).collect();
    loop {
        let mut changed = false;
        for &inst in order.iter().rev() {
            let data = &func.dfg.insts[inst];
            let keeps: [bool; 3] = match *data {
                InstructionData::Store {
                    opcode: Opcode::Istore8,
                    ..
                } => [true, false, false],
                InstructionData::Binary {
                    opcode: Opcode::Band | Opcode::Bor | Opcode::Bxor,
                    ..
                } => {
                    let r = low[func.dfg.first_result(inst)];
                    [r, r, false]
                }
                InstructionData::Unary {
                    opcode: Opcode::Bnot,
                    ..
                } => [low[func.dfg.first_result(inst)], false, false],
                InstructionData::Ternary {
                    opcode: Opcode::Select,
                    ..
                } => {
                    let r = low[func.dfg.first_result(inst)];
                    [false, r, r]
                }
                _ => [false; 3],
            };
            for (i, v) in func.dfg.inst_values(inst).enumerate() {
                if !keeps.get(i).copied().unwrap_or(false) && low[v] {
                    low[v] = false;
                    changed = true;
                }
            }
        }
        if !changed {
            return low;
        }
    }
}

/// The values the back end counts as used more than once (`ValueUseState::Multiple` in
/// Cranelift's lowering): used by two instructions, or an operand, at any depth, of a
/// single-result instruction whose value is (the back end may compute such a value at each use).
/// A load is folded into its user only if its value is not among them.
fn used_more_than_once(func: &Function) -> SecondaryMap<Value, bool> {
    let mut uses: SecondaryMap<Value, u8> = SecondaryMap::new();
    for inst in layout_insts(func) {
        for v in func.dfg.inst_values(inst) {
            uses[v] = uses[v].saturating_add(1);
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

/// `func`'s instructions in layout order.
pub(crate) fn layout_insts(func: &Function) -> impl Iterator<Item = Inst> + '_ {
    func.layout
        .blocks()
        .flat_map(|b| func.layout.block_insts(b))
}

#[cfg(test)]
#[path = "midend_tests.rs"]
mod tests;
