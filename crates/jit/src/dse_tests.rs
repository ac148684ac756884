//! Tests of [`super::remove_dead_stores`] on small hand-built functions: which stores go and,
//! as important, which must stay.

use super::remove_dead_stores;
use cranelift_codegen::ir::{
    AbiParam, Function, InstBuilder, Signature, UserFuncName, Value, types::*,
};
use cranelift_codegen::isa::CallConv;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};

/// Builds `fn(image: i64, other: i64, callee: i64)` whose body `body` writes into one block
/// (or more, if it makes them).
fn build(body: impl FnOnce(&mut FunctionBuilder, [Value; 3])) -> Function {
    let mut sig = Signature::new(CallConv::SystemV);
    sig.params = vec![AbiParam::new(I64); 3];
    let mut func = Function::with_name_signature(UserFuncName::user(0, 0), sig);
    let mut ctx = FunctionBuilderContext::new();
    let mut b = FunctionBuilder::new(&mut func, &mut ctx);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let p = b.block_params(entry);
    let params = [p[0], p[1], p[2]];
    body(&mut b, params);
    b.ins().return_(&[]);
    b.seal_all_blocks();
    b.finalize(cranelift_codegen::isa::TargetFrontendConfig {
        default_call_conv: CallConv::SystemV,
        pointer_width: target_lexicon::PointerWidth::U64,
        page_size_align_log2: 12,
    });
    func
}

fn stores(func: &Function) -> usize {
    func.layout
        .blocks()
        .flat_map(|b| func.layout.block_insts(b))
        .filter(|&i| func.dfg.insts[i].opcode().can_store())
        .count()
}

fn byte(b: &mut FunctionBuilder, v: i64) -> Value {
    b.ins().iconst(I32, v)
}

/// Runs the pass and returns (removed, stores left).
fn run(mut func: Function) -> (usize, usize) {
    let removed = remove_dead_stores(&mut func);
    (removed, stores(&func))
}

#[test]
fn a_byte_stored_twice_keeps_only_the_second_store() {
    let f = build(|b, [img, ..]| {
        let (x, y) = (byte(b, 1), byte(b, 2));
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        b.ins().istore8(crate::lower::mf(), y, img, 5);
    });
    assert_eq!(run(f), (1, 1));
}

#[test]
fn a_load_between_keeps_both_stores() {
    let f = build(|b, [img, ..]| {
        let (x, y) = (byte(b, 1), byte(b, 2));
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        b.ins().uload8(I32, crate::lower::mf(), img, 5);
        b.ins().istore8(crate::lower::mf(), y, img, 5);
    });
    assert_eq!(run(f), (0, 2));
}

#[test]
fn a_wide_load_over_the_byte_keeps_both_stores() {
    let f = build(|b, [img, ..]| {
        let (x, y) = (byte(b, 1), byte(b, 2));
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        b.ins().load(I32, crate::lower::mf(), img, 2); // bytes 2..6
        b.ins().istore8(crate::lower::mf(), y, img, 5);
    });
    assert_eq!(run(f), (0, 2));
}

#[test]
fn a_load_of_another_byte_does_not_matter() {
    let f = build(|b, [img, ..]| {
        let (x, y) = (byte(b, 1), byte(b, 2));
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        b.ins().uload8(I32, crate::lower::mf(), img, 6);
        b.ins().load(I16, crate::lower::mf(), img, 3); // bytes 3..5
        b.ins().istore8(crate::lower::mf(), y, img, 5);
    });
    assert_eq!(run(f), (1, 1));
}

#[test]
fn a_store_is_dead_only_when_every_byte_is_overwritten() {
    // A byte inside a later word store goes; a word store of which only half is stored again
    // stays.
    let f = build(|b, [img, ..]| {
        let (x, w) = (byte(b, 1), b.ins().iconst(I16, 0x1234));
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        b.ins().store(crate::lower::mf(), w, img, 4); // bytes 4, 5
        b.ins().istore8(crate::lower::mf(), x, img, 5);
    });
    assert_eq!(run(f), (1, 2));
}

#[test]
fn constant_offsets_in_the_address_are_seen_through() {
    let f = build(|b, [img, ..]| {
        let x = byte(b, 1);
        let c = b.ins().iconst(I64, 100);
        let frame = b.ins().iadd(img, c);
        b.ins().istore8(crate::lower::mf(), x, frame, 4); // image byte 104
        let frame2 = b.ins().iadd_imm_s(img, 104);
        b.ins().istore8(crate::lower::mf(), x, frame2, 0); // image byte 104 again
    });
    assert_eq!(run(f), (1, 1));
}

#[test]
fn a_load_through_another_root_may_read_anything() {
    // `other` may point into the image: its load may read byte 5.
    let f = build(|b, [img, other, _]| {
        let x = byte(b, 1);
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        b.ins().uload8(I32, crate::lower::mf(), other, 0);
        b.ins().istore8(crate::lower::mf(), x, img, 5);
    });
    assert_eq!(run(f), (0, 2));
}

#[test]
fn a_call_may_read_anything() {
    let f = build(|b, [img, _, callee]| {
        let x = byte(b, 1);
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        let sig = b.import_signature(Signature::new(CallConv::SystemV));
        b.ins().call_indirect(sig, callee, &[]);
        b.ins().istore8(crate::lower::mf(), x, img, 5);
    });
    assert_eq!(run(f), (0, 2));
}

#[test]
fn a_store_before_the_block_ends_stays() {
    // The successor (or the caller) sees memory at the block's end.
    let f = build(|b, [img, ..]| {
        let x = byte(b, 1);
        b.ins().istore8(crate::lower::mf(), x, img, 5);
        let next = b.create_block();
        b.ins().jump(next, &[]);
        b.switch_to_block(next);
        b.ins().istore8(crate::lower::mf(), x, img, 5);
    });
    assert_eq!(run(f), (0, 2));
}
