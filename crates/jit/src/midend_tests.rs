//! Tests of the mid-end passes and [`super::Midend`] on hand-built functions. A byte
//! load whose value the back end sees used once becomes `uextend(load.i8)` and is emitted as
//! `movzbl`; one it sees used more than once, directly or through a pure instruction, keeps
//! its `uload8` (its `movzbq` is then one instruction, not a load and a register extension).
//! Byte masks and bit tests get short immediates where nothing sees the upper bits, and a
//! constant used far from its previous use is defined again next to it.

use super::{CONSTANT_REACH, Midend, local_constants, narrow_byte_loads};
use crate::lower::mf;
use crate::{JitOptions, OptLevel};
use cranelift_codegen::Context;
use cranelift_codegen::ir::{Function, InstBuilder, InstructionData, Opcode, types::*};

/// The opcodes of `func`'s instructions in layout order.
fn opcodes(func: &Function) -> Vec<Opcode> {
    func.layout
        .blocks()
        .flat_map(|b| func.layout.block_insts(b))
        .map(|i| func.dfg.insts[i].opcode())
        .collect()
}

/// `fn(image)`: `x = uload8.i32 image+5`, then `use_it` makes the uses of `x`, the last value
/// it returns is stored to image+9.
fn with_byte_load(
    use_it: impl FnOnce(
        &mut cranelift_frontend::FunctionBuilder,
        cranelift_codegen::ir::Value,
    ) -> cranelift_codegen::ir::Value,
) -> Function {
    crate::test_fn::build(1, |b, p| {
        let x = b.ins().uload8(I32, mf(), p[0], 5);
        let y = use_it(b, x);
        b.ins().istore8(mf(), y, p[0], 9);
    })
}

#[test]
fn a_byte_used_once_is_loaded_as_a_byte_and_extended() {
    let mut f = with_byte_load(|b, x| b.ins().band_imm_u(x, 4));
    assert_eq!(narrow_byte_loads(&mut f), 1);
    let ops = opcodes(&f);
    assert!(!ops.contains(&Opcode::Uload8), "{ops:?}");
    let load = f
        .layout
        .blocks()
        .flat_map(|b| f.layout.block_insts(b))
        .find(|&i| f.dfg.insts[i].opcode() == Opcode::Load)
        .expect("a load");
    // Same address and offset as before, one byte wide, and its only user is the extension.
    assert_eq!(f.dfg.value_type(f.dfg.first_result(load)), I8);
    let InstructionData::Load { offset, .. } = f.dfg.insts[load] else {
        panic!()
    };
    assert_eq!(i32::from(offset), 5);
    let next = f.layout.next_inst(load).expect("the extension");
    assert_eq!(f.dfg.insts[next].opcode(), Opcode::Uextend);
    assert_eq!(f.dfg.value_type(f.dfg.first_result(next)), I32);
}

#[test]
fn a_byte_used_twice_keeps_its_uload8() {
    let mut f = with_byte_load(|b, x| {
        let y = b.ins().band_imm_u(x, 4);
        b.ins().bor(y, x)
    });
    assert_eq!(narrow_byte_loads(&mut f), 0);
    assert!(opcodes(&f).contains(&Opcode::Uload8));
}

#[test]
fn a_byte_under_a_shared_pure_value_keeps_its_uload8() {
    // `y` is used twice; the back end may compute it at each use, so `x` counts as used twice.
    let mut f = with_byte_load(|b, x| {
        let y = b.ins().band_imm_u(x, 4);
        let z = b.ins().ishl_imm_u(y, 1);
        b.ins().bor(z, y)
    });
    assert_eq!(narrow_byte_loads(&mut f), 0);
}

#[test]
fn a_byte_under_a_two_result_instruction_counts_once() {
    // Multi-result instructions are roots for the back end: their results' uses do not
    // multiply their operands'.
    let mut f = with_byte_load(|b, x| {
        let wide = b.ins().uextend(I64, x);
        let pair = b.ins().iconcat(wide, wide);
        let (lo, _) = b.ins().isplit(pair);
        let lo = b.ins().ireduce(I32, lo);
        let y = b.ins().band_imm_u(lo, 4);
        b.ins().bor(y, lo)
    });
    // `wide` is used twice by the iconcat, which is single-result: the byte is shared.
    assert_eq!(narrow_byte_loads(&mut f), 0);
    let mut f = with_byte_load(|b, x| {
        let wide = b.ins().uextend(I64, x);
        let other = b.ins().iconst(I64, 0);
        let pair = b.ins().iconcat(wide, other);
        let (lo, _) = b.ins().isplit(pair);
        let lo = b.ins().ireduce(I32, lo);
        let y = b.ins().band_imm_u(lo, 4);
        b.ins().bor(y, lo)
    });
    assert_eq!(narrow_byte_loads(&mut f), 1);
}

#[cfg(target_arch = "x86_64")]
#[test]
fn the_back_end_emits_movzbl_for_a_narrowed_load_and_movzbq_for_a_shared_one() {
    for opt in [OptLevel::None, OptLevel::Speed] {
        let opts = JitOptions::at(opt);
        let isa = crate::build::host_isa(&opts, "none").expect("host ISA");
        let midend = Midend::new(&opts).expect("mid-end");
        let asm = |f: Function| {
            let mut ctx = Context::for_function(f);
            midend.run(&mut ctx).expect("mid-end runs");
            ctx.set_disasm(true);
            let mut cp = cranelift_codegen::control::ControlPlane::default();
            let code = ctx.compile(isa.as_ref(), &mut cp).expect("compiles");
            code.vcode.clone().unwrap_or_default()
        };
        let once = asm(with_byte_load(|b, x| b.ins().band_imm_u(x, 4)));
        assert!(once.contains("movzbl 5("), "{opt:?}: {once}");
        assert!(
            !once.contains("movzbl %") && !once.contains("movzbq"),
            "{opt:?}: one load, no register extension: {once}"
        );
        // (x << 3) ^ x: nothing for the e-graph to simplify.
        let twice = asm(with_byte_load(|b, x| {
            let y = b.ins().ishl_imm_u(x, 3);
            b.ins().bxor(y, x)
        }));
        assert!(twice.contains("movzbq 5("), "{opt:?}: {twice}");
    }
}

/// The constant operand of `f`'s `and`, as its low 32 bits.
fn and_mask(f: &Function) -> i64 {
    let and = f
        .layout
        .blocks()
        .flat_map(|b| f.layout.block_insts(b))
        .find(|&i| f.dfg.insts[i].opcode() == Opcode::Band)
        .expect("the and");
    f.dfg
        .inst_args(and)
        .iter()
        .find_map(|&a| super::iconst_of(f, a))
        .expect("a constant operand")
}

#[test]
fn a_coil_mask_on_a_byte_gets_an_eight_bit_immediate() {
    // (x AND 0xF7) OR 8, stored as a byte: the upper bits of the mask never matter.
    let mut f = with_byte_load(|b, x| {
        let k = b.ins().iconst(I32, 0xF7);
        let cleared = b.ins().band(x, k);
        let eight = b.ins().iconst(I32, 8);
        b.ins().bor(cleared, eight)
    });
    assert_eq!(super::short_byte_masks(&mut f), 1);
    assert_eq!(and_mask(&f), 0xFFFF_FFF7);
}

#[test]
fn a_mask_whose_upper_bits_are_seen_keeps_its_value() {
    // p OR 0x80 of an arbitrary word p, shifted right before the store: the shift moves
    // upper bits into the stored byte, and p's upper bits may be set.
    let mut f = crate::test_fn::build(2, |b, p| {
        let word = b.ins().ireduce(I32, p[1]);
        let k = b.ins().iconst(I32, 0x80);
        let ored = b.ins().bor(word, k);
        let shifted = b.ins().ushr_imm_u(ored, 4);
        b.ins().istore8(mf(), shifted, p[0], 9);
    });
    assert_eq!(super::short_byte_masks(&mut f), 0);
    // An `and` of that word with 0x80, compared: p's upper bits would leak into the compare.
    let mut f = crate::test_fn::build(2, |b, p| {
        let word = b.ins().ireduce(I32, p[1]);
        let k = b.ins().iconst(I32, 0x80);
        let bit7 = b.ins().band(word, k);
        let set = b
            .ins()
            .icmp_imm_s(cranelift_codegen::ir::condcodes::IntCC::NotEqual, bit7, 0);
        b.ins().istore8(mf(), set, p[0], 9);
    });
    assert_eq!(super::short_byte_masks(&mut f), 0);
}

#[test]
fn an_and_of_a_byte_load_gets_the_short_mask_whatever_reads_it() {
    // (x AND 0x80) != 0 for a byte x: x has no upper bits, so AND -128 is the same test.
    let mut f = with_byte_load(|b, x| {
        let k = b.ins().iconst(I32, 0x80);
        let bit7 = b.ins().band(x, k);
        let set = b
            .ins()
            .icmp_imm_s(cranelift_codegen::ir::condcodes::IntCC::NotEqual, bit7, 0);
        b.ins().uextend(I32, set)
    });
    assert_eq!(super::short_byte_masks(&mut f), 1);
    assert_eq!(and_mask(&f), 0xFFFF_FF80);
}

#[test]
fn a_bit_test_that_only_chooses_is_made_on_the_low_byte() {
    // select(x AND 4, 1, 2) for a 32-bit x: the condition becomes (ireduce.i8 x) AND 4.
    let build = |also_store: bool| {
        crate::test_fn::build(2, |b, p| {
            let x = b.ins().ireduce(I32, p[1]);
            let bit = b.ins().band_imm_u(x, 4);
            let (one, two) = (b.ins().iconst(I32, 1), b.ins().iconst(I32, 2));
            let chosen = b.ins().select(bit, one, two);
            b.ins().istore8(mf(), chosen, p[0], 9);
            if also_store {
                b.ins().istore8(mf(), bit, p[0], 10);
            }
        })
    };
    let mut f = build(false);
    assert_eq!(super::byte_tests(&mut f), 1);
    let select = f
        .layout
        .blocks()
        .flat_map(|b| f.layout.block_insts(b))
        .find(|&i| f.dfg.insts[i].opcode() == Opcode::Select)
        .expect("the select");
    let cond = f.dfg.inst_args(select)[0];
    assert_eq!(f.dfg.value_type(cond), I8);
    let and = f.dfg.value_def(cond).inst().expect("an and");
    assert_eq!(f.dfg.insts[and].opcode(), Opcode::Band);
    let low = f.dfg.inst_args(and)[0];
    let reduce = f.dfg.value_def(low).inst().expect("a reduce");
    assert_eq!(f.dfg.insts[reduce].opcode(), Opcode::Ireduce);
    // Also stored: a value, not only a condition, so it stays 32 bits wide.
    let mut f = build(true);
    assert_eq!(super::byte_tests(&mut f), 0);
}

/// `fn(image)`: the constant 0x7FFF defined first, then `select(byte, 0x7FFF, byte)` stored at
/// three places: the first two selects right after each other, the third after `gap` byte
/// loads and stores in between.
fn selects_of_one_constant(gap: usize) -> Function {
    crate::test_fn::build(1, |b, p| {
        let k = b.ins().iconst(I32, 0x7FFF);
        let select_at = |b: &mut cranelift_frontend::FunctionBuilder, off: i32| {
            let x = b.ins().uload8(I32, mf(), p[0], off);
            let y = b.ins().select(x, k, x);
            b.ins().istore8(mf(), y, p[0], off);
        };
        select_at(b, 0);
        select_at(b, 1);
        for i in 0..gap {
            let x = b.ins().uload8(I32, mf(), p[0], 100 + i as i32);
            b.ins().istore8(mf(), x, p[0], 200 + i as i32);
        }
        select_at(b, 2);
    })
}

/// The `iconst` each `select` takes as its second argument, in layout order.
fn select_constants(f: &Function) -> Vec<cranelift_codegen::ir::Value> {
    f.layout
        .blocks()
        .flat_map(|b| f.layout.block_insts(b))
        .filter(|&i| f.dfg.insts[i].opcode() == Opcode::Select)
        .map(|i| f.dfg.inst_args(i)[1])
        .collect()
}

#[test]
fn a_constant_used_far_apart_is_defined_again_near_the_later_use() {
    let mut f = selects_of_one_constant(CONSTANT_REACH);
    // The first select gets a definition of its own right before it, the second (three
    // instructions on) shares it, the third is too far from the second.
    assert_eq!(local_constants(&mut f), 2);
    let ks = select_constants(&f);
    assert_eq!(ks[0], ks[1]);
    assert_ne!(ks[1], ks[2]);
    for k in ks {
        let def = f.dfg.value_def(k).inst().expect("an instruction");
        assert_eq!(f.dfg.insts[def].opcode(), Opcode::Iconst);
        assert_eq!(crate::dse::iconst(&f, k), Some(0x7FFF));
        // Each definition sits right before the select that first takes it.
        let next = f.layout.next_inst(def).expect("a user");
        assert_eq!(f.dfg.insts[next].opcode(), Opcode::Select);
    }
}

#[test]
fn uses_within_reach_share_one_definition() {
    let mut f = selects_of_one_constant(0);
    // Select, store, load, select: the third select is three instructions after the second.
    assert_eq!(local_constants(&mut f), 1);
    let ks = select_constants(&f);
    assert!(ks.iter().all(|&k| k == ks[0]), "{ks:?}");
}
