//! Short displacements: local base pointers into the image for runs of nearby accesses, the
//! mid-end's last pass on every function.
//!
//! Lowering addresses every static image byte as `image + offset`. x86-64 encodes an offset in
//! -128..=127 in one byte and any other in four, so every access to V memory, the timer and
//! counter areas, the scan bookkeeping or the resident-bit shadow (all beyond the first 128
//! bytes) is three bytes longer than it needs to be. In programs of a thousand instructions
//! and more the code no longer fits the processor's decoded-instruction cache, the decoders
//! set the pace and these bytes cost time (docs/performance.md, "Short displacements" and
//! "Local base pointers").
//!
//! **Rule.** In each stretch of the function between calls (in layout order): among the loads
//! and stores whose address is the image pointer (the function's first parameter) or an opaque
//! copy of one (`image`, or `image + bias` hidden as below) and whose image offset is beyond
//! -128..=127, find the 256-byte window of offsets that holds the most. Split its accesses into
//! runs: an access joins the run before it if it comes at most [`LOCAL_REACH`] instructions
//! after the run's last access, in a block that the block of the run's first access dominates.
//! A run of at least [`MIN_RUN`] accesses gets `image + bias` (the window's middle, so every
//! offset in it becomes -128..=127) defined just before its first access; the accesses of a
//! shorter run address the image pointer with a four-byte displacement. Repeat while a window
//! holds [`MIN_RUN`]. The far accesses no window took address the image pointer too.
//!
//! **Why local.** A base pointer defined once per function lives across all of it; where its
//! accesses are sparse the register allocator spilled it and reloaded it before most uses, five
//! bytes and an instruction each (about 2,000 reloads per scan in mixed_10k). A run's pointer
//! lives a few dozen instructions and never across a call, so it stays in a caller-saved
//! register, and functions that call the runtime get short displacements too. Bit logic with
//! few live values could keep a pointer much longer (bitlogic_1k ran with two per function and
//! no spill), but a longer reach brought mixed_10k's spills back (`LOCAL_REACH`), and an
//! estimate of the live values along a run did not pick better runs on either.
//!
//! **Why last.** The e-graph pass would merge the local definitions of one bias back into a
//! single one and hoist it to the entry. Every base is `isplit(iconcat(v, v))` of its
//! `image + bias`, which the x86 back end cannot see through; it would otherwise fold the
//! constant straight back into every displacement. After the e-graph pass nothing merges
//! loads any more, so an access lowering made through an opaque copy of the image (see
//! `write_bit_folded`) may take any base.
//!
//! The rewrite changes only how an address is formed, never which byte it names, so memory is
//! the same after every instruction.

use cranelift_codegen::cursor::{Cursor, FuncCursor};
use cranelift_codegen::dominator_tree::DominatorTree;
use cranelift_codegen::flowgraph::ControlFlowGraph;
use cranelift_codegen::ir::{
    Block, Function, Inst, InstBuilder, InstructionData, Opcode, Value, ValueDef,
    immediates::Offset32,
};
use std::collections::HashMap;

/// Two accesses at most this many instructions apart belong to one run and share its base
/// pointer. Measured on mixed_10k (code bytes): 48 → 135.6 KB, 80 → 133.0 KB, 128 → 136.6 KB,
/// 200 → 137.3 KB; longer runs overlap more, and the allocator spills their pointers again.
pub(crate) const LOCAL_REACH: usize = 80;

/// Accesses a run needs to get a base pointer: the pointer's `lea` costs seven bytes and each
/// access saves three, and a register for the run's length (mixed_10k: 3 → 133.2 KB,
/// 4 → 133.0 KB, 5 → 133.2 KB).
pub(crate) const MIN_RUN: usize = 4;

/// The displacements x86-64 encodes in one byte.
pub(crate) const SHORT: std::ops::RangeInclusive<i64> = -128..=127;

/// Gives `func`'s runs of far image accesses local base pointers (module docs); returns how
/// many it defined.
pub(crate) fn shorten_displacements(func: &mut Function) -> usize {
    let Some(entry) = func.layout.entry_block() else {
        return 0;
    };
    let Some(&image) = func.dfg.block_params(entry).first() else {
        return 0;
    };
    let bias_of = image_pointers(func, image);
    let cfg = ControlFlowGraph::with_function(func);
    let domtree = DominatorTree::with_function(func, &cfg);
    let mut defined = 0;
    let mut stretch = Vec::new();
    let insts: Vec<(Block, Inst)> = func
        .layout
        .blocks()
        .flat_map(|b| func.layout.block_insts(b).map(move |i| (b, i)))
        .collect();
    for (at, (block, inst)) in insts.into_iter().enumerate() {
        let data = &func.dfg.insts[inst];
        if data.opcode().is_call() {
            defined += rebase_stretch(func, &domtree, image, std::mem::take(&mut stretch));
            continue;
        }
        let Some((addr, off)) = address(data) else {
            continue;
        };
        let Some(at_image) = bias_of.get(&addr).map(|&bias| bias + off) else {
            continue;
        };
        if !SHORT.contains(&at_image) && i32::try_from(at_image).is_ok() {
            stretch.push(Far {
                at,
                block,
                inst,
                off: at_image,
            });
        }
    }
    defined + rebase_stretch(func, &domtree, image, stretch)
}

/// A far access to the image.
#[derive(Clone, Copy)]
struct Far {
    /// Its position in the function's layout.
    at: usize,
    /// Its block.
    block: Block,
    /// The load or store.
    inst: Inst,
    /// The image offset it names.
    off: i64,
}

/// Every value that is the image pointer plus a constant, as the image pointer itself or an
/// opaque copy (`isplit(iconcat(v, v))`) of such a value, with its constant.
fn image_pointers(func: &Function, image: Value) -> HashMap<Value, i64> {
    let mut bias_of = HashMap::from([(image, 0)]);
    for inst in crate::midend::layout_insts(func) {
        let InstructionData::Unary {
            opcode: Opcode::Isplit,
            arg: pair,
        } = func.dfg.insts[inst]
        else {
            continue;
        };
        let ValueDef::Result(concat, 0) = func.dfg.value_def(pair) else {
            continue;
        };
        let InstructionData::Binary {
            opcode: Opcode::Iconcat,
            args: [a, b],
        } = func.dfg.insts[concat]
        else {
            continue;
        };
        let bias = if a == b {
            bias_of
                .get(&a)
                .copied()
                .or_else(|| offset_from(func, a, image))
        } else {
            None
        };
        if let Some(bias) = bias {
            bias_of.insert(func.dfg.first_result(inst), bias);
        }
    }
    bias_of
}

/// `k` if `v` is `image + k` for a constant `k`.
fn offset_from(func: &Function, v: Value, image: Value) -> Option<i64> {
    let ValueDef::Result(inst, 0) = func.dfg.value_def(v) else {
        return None;
    };
    match func.dfg.insts[inst] {
        InstructionData::Binary {
            opcode: Opcode::Iadd,
            args: [a, b],
        } if a == image => crate::dse::iconst(func, b),
        InstructionData::Binary {
            opcode: Opcode::Iadd,
            args: [a, b],
        } if b == image => crate::dse::iconst(func, a),
        _ => None,
    }
}

/// Rebases the far accesses of one call-free stretch of the function, densest window first
/// (module docs); returns how many base pointers it defined.
fn rebase_stretch(
    func: &mut Function,
    domtree: &DominatorTree,
    image: Value,
    mut pool: Vec<Far>,
) -> usize {
    let mut defined = 0;
    while let Some((bias, n)) = densest_window(&pool)
        && n >= MIN_RUN
    {
        let (inside, rest): (Vec<Far>, Vec<Far>) = pool
            .into_iter()
            .partition(|f| SHORT.contains(&(f.off - bias)));
        pool = rest;
        let mut start = 0;
        for end in 1..=inside.len() {
            let joins = inside.get(end).is_some_and(|f| {
                f.at - inside[end - 1].at <= LOCAL_REACH
                    && domtree.block_dominates(inside[start].block, f.block)
            });
            if !joins {
                defined += place_run(func, image, bias, &inside[start..end]);
                start = end;
            }
        }
    }
    pool_to_image(func, image, &pool);
    defined
}

/// Gives a run of accesses in one window a base pointer defined just before its first access,
/// or the image pointer if the run is too short; returns how many bases it defined.
fn place_run(func: &mut Function, image: Value, bias: i64, run: &[Far]) -> usize {
    if run.len() < MIN_RUN {
        pool_to_image(func, image, run);
        return 0;
    }
    let mut pos = FuncCursor::new(func).at_inst(run[0].inst);
    let sum = pos.ins().iadd_imm_s(image, bias);
    let pair = pos.ins().iconcat(sum, sum);
    let base = pos.ins().isplit(pair).0;
    for f in run {
        set_address(&mut func.dfg.insts[f.inst], base, f.off - bias);
    }
    1
}

/// Points far accesses at the image pointer itself, with their full offsets.
fn pool_to_image(func: &mut Function, image: Value, far: &[Far]) {
    for f in far {
        set_address(&mut func.dfg.insts[f.inst], image, f.off);
    }
}

/// The address and offset of a load or store.
fn address(data: &InstructionData) -> Option<(Value, i64)> {
    match *data {
        InstructionData::Load { arg, offset, .. } => Some((arg, i64::from(offset))),
        InstructionData::Store {
            args: [_, addr],
            offset,
            ..
        } => Some((addr, i64::from(offset))),
        _ => None,
    }
}

/// The bias (window middle) whose window `bias-128..=bias+127` holds the most of `far`, and
/// how many it holds; `None` if `far` is empty.
fn densest_window(far: &[Far]) -> Option<(i64, usize)> {
    let mut offs: Vec<i64> = far.iter().map(|f| f.off).collect();
    offs.sort_unstable();
    let span = SHORT.end() - SHORT.start();
    let mut best: Option<(i64, usize)> = None;
    let mut hi = 0;
    // Each window starts at some access's offset; two pointers over the sorted offsets.
    for (lo, &start) in offs.iter().enumerate() {
        while hi < offs.len() && offs[hi] - start <= span {
            hi += 1;
        }
        let n = hi - lo;
        if best.is_none_or(|(_, m)| n > m) {
            best = Some((start - SHORT.start(), n));
        }
    }
    best
}

/// Makes a load or store address `base + rel`; `rel` is an image offset or a displacement in
/// [`SHORT`], and both fit 32 bits (checked where the access was collected).
fn set_address(data: &mut InstructionData, base: Value, rel: i64) {
    let rel = Offset32::new(rel as i32);
    match data {
        InstructionData::Load { arg, offset, .. } => {
            *arg = base;
            *offset = rel;
        }
        InstructionData::Store {
            args: [_, addr],
            offset,
            ..
        } => {
            *addr = base;
            *offset = rel;
        }
        _ => {}
    }
}

#[cfg(test)]
#[path = "rebase_tests.rs"]
mod tests;
