//! Short displacements: extra base pointers into the image, chosen per function from the
//! addresses it uses, run on each lowered function after [`crate::dse`].
//!
//! Lowering addresses every static image byte as `image + offset`. x86-64 encodes an offset in
//! -128..=127 in one byte and any other in four, so every access to V memory, the timer and
//! counter areas or the special memory (all beyond the first 128 bytes) is three bytes longer
//! than it needs to be. In programs of a thousand instructions and more the code no longer fits
//! the processor's decoded-instruction cache, the decoders set the pace and these bytes cost
//! time: bitlogic_10k runs about 8 % faster with them gone (docs/performance.md).
//!
//! **Rule.** Among the function's loads and stores whose address is exactly the image pointer
//! (its first parameter) or an opaque copy of it, find the 256-byte window of offsets beyond -128..=127 that holds the
//! most accesses; if it holds at least [`MIN_ACCESSES`], and at least one per
//! [`MAX_INSTS_PER_ACCESS`] instructions of the function, define `image + bias` once at the
//! entry (the window's middle, so every offset in it becomes -128..=127) and let those accesses
//! use it. Repeat for up to [`MAX_EXTRA_BASES`] windows. The new base is passed through
//! `iconcat`/`isplit`, which Cranelift cannot see through, because otherwise the x86 back end
//! folds the constant straight back into every displacement.
//!
//! A function that calls anything is left alone: values live across its calls already crowd
//! the five callee-saved registers, and an extra pointer there was spilled and reloaded all over
//! mixed_10k (1.9 % more instructions per scan, no faster). Bit logic calls nothing.
//!
//! The rewrite changes only how an address is formed, never which byte it names, so memory is
//! the same after every instruction.

use cranelift_codegen::cursor::{Cursor, FuncCursor};
use cranelift_codegen::ir::{
    Block, Function, Inst, InstBuilder, InstructionData, Opcode, Value, ValueDef,
    immediates::Offset32,
};

/// Accesses a window must hold to get a base pointer of its own (each saves three bytes; the
/// pointer costs a register and a 7-byte `lea`).
pub(crate) const MIN_ACCESSES: usize = 16;

/// A base pointer lives across the whole function, and where its window's accesses are
/// sparse the register allocator spills it and reloads it before each use (five bytes and an
/// instruction, more than the three bytes a short displacement saves). So a window needs at
/// least one access per this many instructions of the function too. Measured on eight
/// generated programs: mostly the second pointer goes (mixed_10k's second windows hold one
/// access per 78–167 instructions, its first ones one per 27–41), 0.5 % fewer bytes in all.
pub(crate) const MAX_INSTS_PER_ACCESS: usize = 40;

/// At most this many extra base pointers per function.
pub(crate) const MAX_EXTRA_BASES: usize = 2;

/// The displacements x86-64 encodes in one byte.
const SHORT: std::ops::RangeInclusive<i64> = -128..=127;

/// Gives `func`'s far image accesses short displacements (module docs); returns how many
/// accesses were rewritten.
pub(crate) fn shorten_displacements(func: &mut Function) -> usize {
    let Some(entry) = func.layout.entry_block() else {
        return 0;
    };
    let Some(&image) = func.dfg.block_params(entry).first() else {
        return 0;
    };
    let mut far = Vec::new();
    for block in func.layout.blocks() {
        for inst in func.layout.block_insts(block) {
            let data = &func.dfg.insts[inst];
            if data.opcode().is_call() {
                return 0;
            }
            if let Some((addr, off)) = address(data)
                && !SHORT.contains(&off)
            {
                let copy = addr != image;
                if !copy || is_opaque_copy(func, addr, image) {
                    far.push(Far { off, inst, copy });
                }
            }
        }
    }
    let insts = crate::midend::layout_insts(func).count();
    let mut rewritten = 0;
    for _ in 0..MAX_EXTRA_BASES {
        let Some((bias, n)) = densest_window(&far) else {
            break;
        };
        if n < MIN_ACCESSES || n * MAX_INSTS_PER_ACCESS < insts {
            break;
        }
        let (base, copy) = opaque_offset(func, entry, image, bias);
        far.retain(|f| {
            let rel = f.off - bias;
            if !SHORT.contains(&rel) {
                return true;
            }
            let base = if f.copy { copy } else { base };
            set_address(&mut func.dfg.insts[f.inst], base, rel);
            rewritten += 1;
            false
        });
    }
    rewritten
}

/// A far access to the image.
struct Far {
    /// Its image offset.
    off: i64,
    /// The load or store.
    inst: Inst,
    /// Whether its address is an opaque copy of the image pointer rather than the pointer.
    copy: bool,
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

/// Whether `v` is `isplit(iconcat(image, image))`: lowering loads a byte a second time through
/// such a copy so that Cranelift cannot merge the two loads (see `write_bit_folded`). Its
/// accesses move to a copy of the new base, so they stay unmergeable.
fn is_opaque_copy(func: &Function, v: Value, image: Value) -> bool {
    let ValueDef::Result(split, 0) = func.dfg.value_def(v) else {
        return false;
    };
    let InstructionData::Unary {
        opcode: Opcode::Isplit,
        arg: pair,
    } = func.dfg.insts[split]
    else {
        return false;
    };
    let ValueDef::Result(concat, 0) = func.dfg.value_def(pair) else {
        return false;
    };
    matches!(
        func.dfg.insts[concat],
        InstructionData::Binary { opcode: Opcode::Iconcat, args } if args == [image, image]
    )
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

/// Defines `image + bias` at the top of `entry`, out of the back end's sight, and an opaque
/// copy of it (for the accesses through an opaque copy of the image).
fn opaque_offset(func: &mut Function, entry: Block, image: Value, bias: i64) -> (Value, Value) {
    let mut pos = FuncCursor::new(func).at_first_insertion_point(entry);
    let sum = pos.ins().iadd_imm_s(image, bias);
    let base = hidden(&mut pos, sum);
    let copy = hidden(&mut pos, base);
    (base, copy)
}

/// `v` through `isplit(iconcat(v, v))`: the same pointer, as a value Cranelift cannot trace
/// back to `v` (the form `write_bit_folded` uses and [`is_opaque_copy`] recognises).
fn hidden(pos: &mut FuncCursor, v: Value) -> Value {
    let pair = pos.ins().iconcat(v, v);
    pos.ins().isplit(pair).0
}

/// Makes a load or store address `base + rel`.
fn set_address(data: &mut InstructionData, base: Value, rel: i64) {
    // `rel` is in SHORT, so the conversion is exact.
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
