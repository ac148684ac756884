//! Tests of [`super::shorten_displacements`] on hand-built functions: every access still names
//! the same image byte, far ones get short displacements when a window is dense enough, and
//! functions with calls are left alone.

use super::{MAX_EXTRA_BASES, MAX_INSTS_PER_ACCESS, MIN_ACCESSES, SHORT, shorten_displacements};
use crate::lower::mf;
use cranelift_codegen::ir::{
    Function, InstBuilder, InstructionData, Opcode, Signature, Value, ValueDef, types::*,
};
use cranelift_codegen::isa::CallConv;
use cranelift_codegen::settings;

/// Builds `fn(image, callee)` with a byte load at each offset (a word store at every third,
/// so stores are rewritten too, and a load through an opaque copy of the image at every
/// fourth, as lowering makes them), in two blocks, and an indirect call at the end if `call`.
fn build(offsets: &[i32], call: bool) -> Function {
    crate::test_fn::build(2, |b, p| {
        let (img, callee) = (p[0], p[1]);
        let pair = b.ins().iconcat(img, img);
        let img_copy = b.ins().isplit(pair).0;
        for (i, &off) in offsets.iter().enumerate() {
            if i == offsets.len() / 2 {
                let next = b.create_block();
                b.ins().jump(next, &[]);
                b.switch_to_block(next);
            }
            if i % 3 == 2 {
                let v = b.ins().iconst(I16, 1);
                b.ins().store(mf(), v, img, off);
            } else if i % 4 == 3 {
                b.ins().load(I32, mf(), img_copy, off);
            } else {
                b.ins().uload8(I32, mf(), img, off);
            }
        }
        if call {
            let sig = b.import_signature(Signature::new(CallConv::SystemV));
            b.ins().call_indirect(sig, callee, &[]);
        }
    })
}

/// The image offset a base value stands for, and whether it went through an opaque copy
/// (`isplit(iconcat(x, x))` of a base): 0 for the image, `bias` for an extra base
/// (`isplit(iconcat(image + bias, …))`).
fn bias_of(func: &Function, image: Value, v: Value) -> (i64, bool) {
    if v == image {
        return (0, false);
    }
    let ValueDef::Result(inst, 0) = func.dfg.value_def(v) else {
        panic!("a base that is not an instruction result")
    };
    match func.dfg.insts[inst] {
        InstructionData::Unary {
            opcode: Opcode::Isplit,
            arg,
        } => {
            let ValueDef::Result(concat, 0) = func.dfg.value_def(arg) else {
                panic!()
            };
            let [a, b] = func.dfg.insts[concat].arguments(&func.dfg.value_lists) else {
                panic!()
            };
            assert_eq!(a, b);
            let (bias, _) = bias_of(func, image, *a);
            // A copy of a copy, or of the image: what lowering made or a copy of a new base.
            let copy = *a == image || is_split(func, *a);
            (bias, copy)
        }
        // `iadd_imm` builds an `iconst` and an `iadd`.
        InstructionData::Binary {
            opcode: Opcode::Iadd,
            args: [arg, c],
        } if arg == image => {
            let ValueDef::Result(c, 0) = func.dfg.value_def(c) else {
                panic!()
            };
            match func.dfg.insts[c] {
                InstructionData::UnaryImm {
                    opcode: Opcode::Iconst,
                    imm,
                } => (imm.bits(), false),
                ref other => panic!("unexpected bias {other:?}"),
            }
        }
        ref other => panic!("unexpected base {other:?}"),
    }
}

fn is_split(func: &Function, v: Value) -> bool {
    matches!(func.dfg.value_def(v), ValueDef::Result(i, 0)
        if func.dfg.insts[i].opcode() == Opcode::Isplit)
}

/// One load or store after the pass.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Access {
    /// The image byte it names.
    at: i64,
    /// Its displacement.
    disp: i64,
    /// The offset of its base pointer into the image.
    bias: i64,
    /// Whether its base is an opaque copy.
    copy: bool,
}

/// Every load and store, in layout order.
fn accesses(func: &Function) -> Vec<Access> {
    let entry = func.layout.entry_block().unwrap();
    let image = func.dfg.block_params(entry)[0];
    let mut out = Vec::new();
    for block in func.layout.blocks() {
        for inst in func.layout.block_insts(block) {
            let (base, disp) = match func.dfg.insts[inst] {
                InstructionData::Load { arg, offset, .. } => (arg, i64::from(offset)),
                InstructionData::Store {
                    args: [_, addr],
                    offset,
                    ..
                } => (addr, i64::from(offset)),
                _ => continue,
            };
            let (bias, copy) = bias_of(func, image, base);
            out.push(Access {
                at: bias + disp,
                disp,
                bias,
                copy,
            });
        }
    }
    out
}

/// Runs the pass and checks what holds whatever it did: the same bytes in the same order, a
/// verifiable function, short displacements for every rewritten access. Returns the accesses
/// after the pass and how many were rewritten.
fn run(offsets: &[i32], call: bool) -> (Vec<Access>, usize) {
    let mut func = build(offsets, call);
    let before = accesses(&func);
    let n = shorten_displacements(&mut func);
    let flags = settings::Flags::new(settings::builder());
    cranelift_codegen::verify_function(&func, &flags).expect("verifier");
    let after = accesses(&func);
    assert_eq!(after.len(), before.len());
    for (a, b) in after.iter().zip(&before) {
        // The same byte, through a copy exactly when it was.
        assert_eq!((a.at, a.copy), (b.at, b.copy), "{after:?}");
        assert!(a.bias == 0 || SHORT.contains(&a.disp), "{after:?}");
    }
    assert_eq!(after.iter().filter(|a| a.bias != 0).count(), n);
    (after, n)
}

/// `n` offsets spread over `from..from + 200`.
fn cluster(from: i32, n: usize) -> Vec<i32> {
    (0..n).map(|i| from + (i as i32 * 37) % 200).collect()
}

#[test]
fn a_dense_far_window_gets_its_own_base() {
    // V memory of the a5 layout starts at 0x110; its bytes sit at 272 and up.
    let offs = cluster(272, MIN_ACCESSES);
    let (after, n) = run(&offs, false);
    assert_eq!(n, MIN_ACCESSES);
    // One base for all of them.
    let biases: std::collections::HashSet<i64> = after.iter().map(|a| a.bias).collect();
    assert_eq!(biases.len(), 1);
}

#[test]
fn a_sparse_window_keeps_long_displacements() {
    let (_, n) = run(&cluster(272, MIN_ACCESSES - 1), false);
    assert_eq!(n, 0);
}

#[test]
fn near_accesses_stay_on_the_image() {
    // 0..=127 is already short; the far cluster is rewritten around them.
    let mut offs: Vec<i32> = (0..40).map(|i| i * 3).collect();
    offs.extend(cluster(4000, MIN_ACCESSES));
    let (after, n) = run(&offs, false);
    assert_eq!(n, MIN_ACCESSES);
    assert!(after.iter().all(|a| (a.at < 128) == (a.bias == 0)));
}

#[test]
fn the_densest_windows_win_up_to_the_limit() {
    // Three far clusters of different sizes: the two largest get bases.
    let mut offs = cluster(300, MIN_ACCESSES + 10);
    offs.extend(cluster(2000, MIN_ACCESSES));
    offs.extend(cluster(5000, MIN_ACCESSES + 5));
    let (after, n) = run(&offs, false);
    assert_eq!(MAX_EXTRA_BASES, 2);
    assert_eq!(n, 2 * MIN_ACCESSES + 15);
    assert!(
        after
            .iter()
            .filter(|a| a.bias == 0)
            .all(|a| (2000..2200).contains(&a.at))
    );
}

#[test]
fn a_window_spans_exactly_256_bytes() {
    // 200 and 455 fit one window (bias 328: -128 and 127); 456 does not.
    let mut offs = vec![200; MIN_ACCESSES / 2];
    offs.extend(vec![455; MIN_ACCESSES / 2]);
    offs.push(456);
    let (after, n) = run(&offs, false);
    assert_eq!(n, MIN_ACCESSES);
    assert!(after.iter().any(|a| a.disp == -128) && after.iter().any(|a| a.disp == 127));
}

#[test]
fn a_function_that_calls_is_left_alone() {
    let (_, n) = run(&cluster(272, 4 * MIN_ACCESSES), true);
    assert_eq!(n, 0);
}

#[test]
fn an_empty_function_is_fine() {
    let (_, n) = run(&[], false);
    assert_eq!(n, 0);
}

#[test]
fn a_window_sparse_in_a_long_function_keeps_long_displacements() {
    // The same dense window of far accesses, alone and among enough near ones (which need no
    // base) that it holds fewer than one access per `MAX_INSTS_PER_ACCESS` instructions: a
    // pointer that long-lived and that little used would be spilled and reloaded.
    let far = cluster(600, MIN_ACCESSES);
    assert_eq!(run(&far, false).1, MIN_ACCESSES);
    let mut long = far.clone();
    long.extend((0..MIN_ACCESSES * MAX_INSTS_PER_ACCESS).map(|i| (i % 100) as i32));
    assert_eq!(run(&long, false).1, 0);
}
