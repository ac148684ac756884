//! Tests of [`super::shorten_displacements`] on hand-built functions: every access still names
//! the same image byte, far ones get short displacements through a base defined just before
//! their run, a run never spans a call or leaves the blocks its first block dominates, and
//! short runs keep long displacements.

use super::{LOCAL_REACH, MIN_RUN, SHORT, shorten_displacements};
use crate::lower::mf;
use cranelift_codegen::ir::{
    Function, Inst, InstBuilder, InstructionData, Opcode, Value, ValueDef, types::*,
};
use cranelift_codegen::settings;

/// What a hand-built function does, in order.
#[derive(Clone, Copy)]
enum Step {
    /// Accesses the image byte at this offset: a byte load, a word store at every third
    /// access and a load through an opaque copy of the image at every fourth, as lowering
    /// makes them.
    Access(i32),
    /// This many instructions that touch no memory.
    Filler(usize),
    /// An indirect call.
    Call,
    /// Ends the block and starts another, which only it jumps to.
    Block,
    /// Branches on a loaded value: the steps up to [`Step::Join`] run only if it is not 0.
    If,
    /// Where the branch of the last [`Step::If`] joins the other path.
    Join,
}

use Step::*;

/// Builds `fn(image, callee)` doing `steps`.
fn build(steps: &[Step]) -> Function {
    crate::test_fn::build(2, |b, p| {
        let (img, callee) = (p[0], p[1]);
        let pair = b.ins().iconcat(img, img);
        let img_copy = b.ins().isplit(pair).0;
        let mut i = 0;
        let mut joins = Vec::new();
        for &step in steps {
            match step {
                Access(off) => {
                    if i % 3 == 2 {
                        let v = b.ins().iconst(I16, 1);
                        b.ins().store(mf(), v, img, off);
                    } else if i % 4 == 3 {
                        b.ins().load(I32, mf(), img_copy, off);
                    } else {
                        b.ins().uload8(I32, mf(), img, off);
                    }
                    i += 1;
                }
                Filler(n) => {
                    for k in 0..n {
                        b.ins().iconst(I32, k as i64);
                    }
                }
                Call => crate::test_fn::call(b, callee),
                Block => crate::test_fn::next_block(b),
                If => {
                    let (then, join) = (b.create_block(), b.create_block());
                    let c = b.ins().uload8(I32, mf(), img, 0);
                    b.ins().brif(c, then, &[], join, &[]);
                    b.switch_to_block(then);
                    joins.push(join);
                }
                Join => {
                    let join = joins.pop().expect("an If before");
                    b.ins().jump(join, &[]);
                    b.switch_to_block(join);
                }
            }
        }
    })
}

/// The image offset a base value stands for: 0 for the image and its opaque copies, `bias`
/// for a base (`isplit(iconcat(image + bias, …))`).
fn bias_of(func: &Function, image: Value, v: Value) -> i64 {
    if v == image {
        return 0;
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
            bias_of(func, image, *a)
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
                } => imm.bits(),
                ref other => panic!("unexpected bias {other:?}"),
            }
        }
        ref other => panic!("unexpected base {other:?}"),
    }
}

/// One load or store after the pass.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Access {
    /// The image byte it names.
    at: i64,
    /// Its displacement.
    disp: i64,
    /// Its base pointer: `None` for the image or a copy of it made by the builder.
    base: Option<Value>,
    /// The offset of its base pointer into the image.
    bias: i64,
    /// The instruction.
    inst: Inst,
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
            let bias = bias_of(func, image, base);
            out.push(Access {
                at: bias + disp,
                disp,
                base: (bias != 0).then_some(base),
                bias,
                inst,
            });
        }
    }
    out
}

/// Runs the pass and checks what holds whatever it did: the same bytes in the same order, a
/// verifiable function (so each base dominates its accesses), a short displacement for every
/// access through a base, and no call between a base's definition and its accesses. Returns
/// the accesses after the pass and how many bases it defined.
fn run(steps: &[Step]) -> (Vec<Access>, usize) {
    let mut func = build(steps);
    let before = accesses(&func);
    let n = shorten_displacements(&mut func);
    let flags = settings::Flags::new(settings::builder());
    cranelift_codegen::verify_function(&func, &flags).expect("verifier");
    let after = accesses(&func);
    assert_eq!(after.len(), before.len());
    let order: Vec<Inst> = crate::midend::layout_insts(&func).collect();
    let at = |inst: Inst| order.iter().position(|&i| i == inst).unwrap();
    for (a, b) in after.iter().zip(&before) {
        assert_eq!(a.at, b.at, "{after:?}");
        let Some(base) = a.base else { continue };
        assert!(SHORT.contains(&a.disp), "{after:?}");
        let def = func.dfg.value_def(base).unwrap_inst();
        let between = &order[at(def)..at(a.inst)];
        assert!(
            between
                .iter()
                .all(|&i| !func.dfg.insts[i].opcode().is_call())
        );
    }
    let bases: std::collections::HashSet<Value> = after.iter().filter_map(|a| a.base).collect();
    assert_eq!(bases.len(), n);
    (after, n)
}

/// `n` accesses spread over `from..from + 200`, one instruction apart.
fn cluster(from: i32, n: usize) -> Vec<Step> {
    (0..n)
        .map(|i| Access(from + (i as i32 * 37) % 200))
        .collect()
}

/// How many accesses go through a base.
fn based(after: &[Access]) -> usize {
    after.iter().filter(|a| a.base.is_some()).count()
}

#[test]
fn a_run_of_far_accesses_gets_one_base() {
    // V memory of the a5 layout starts at 0x110; its bytes sit at 272 and up.
    let (after, n) = run(&cluster(272, MIN_RUN));
    assert_eq!(n, 1);
    assert_eq!(based(&after), MIN_RUN);
}

#[test]
fn a_short_run_keeps_long_displacements_even_through_a_copy() {
    let (after, n) = run(&cluster(272, MIN_RUN - 1));
    assert_eq!(n, 0);
    assert!(after.iter().all(|a| a.disp == a.at));
}

#[test]
fn near_accesses_stay_on_the_image() {
    // 0..=127 is already short; the far run is rewritten among them.
    let mut steps: Vec<Step> = (0..40).map(|i| Access(i * 3)).collect();
    steps.extend(cluster(4000, MIN_RUN));
    let (after, n) = run(&steps);
    assert_eq!(n, 1);
    assert!(after.iter().all(|a| (a.at < 128) == (a.bias == 0)));
}

#[test]
fn accesses_far_apart_in_time_take_a_base_each() {
    let mut steps = cluster(272, MIN_RUN);
    steps.push(Filler(LOCAL_REACH));
    steps.extend(cluster(272, MIN_RUN));
    let (after, n) = run(&steps);
    assert_eq!((n, based(&after)), (2, 2 * MIN_RUN));
    // Within the reach they share one.
    let mut steps = cluster(272, MIN_RUN);
    steps.push(Filler(LOCAL_REACH - 2));
    steps.extend(cluster(272, MIN_RUN));
    assert_eq!(run(&steps).1, 1);
}

#[test]
fn a_run_ends_at_a_call() {
    let mut steps = cluster(272, MIN_RUN);
    steps.push(Call);
    steps.extend(cluster(272, MIN_RUN));
    let (after, n) = run(&steps);
    assert_eq!((n, based(&after)), (2, 2 * MIN_RUN));
    // Too few on either side: none.
    let mut steps = cluster(272, MIN_RUN - 1);
    steps.push(Call);
    steps.extend(cluster(272, MIN_RUN - 1));
    assert_eq!(run(&steps).1, 0);
}

#[test]
fn a_run_goes_on_into_the_blocks_its_first_block_dominates() {
    // Into a block only the run's block jumps to, and past a branch that rejoins.
    let half = MIN_RUN / 2;
    let mut steps = cluster(272, half);
    steps.push(Block);
    steps.extend(cluster(272, half));
    steps.extend([If, Access(300), Join]);
    steps.extend(cluster(272, half));
    let (after, n) = run(&steps);
    assert_eq!((n, based(&after)), (1, 3 * half + 1));
}

#[test]
fn a_run_that_starts_in_a_branch_ends_where_it_joins() {
    // Inside the branch a run of its own; after the join another: the branch's base does
    // not dominate the code after it.
    let mut steps = vec![If];
    steps.extend(cluster(272, MIN_RUN));
    steps.push(Join);
    steps.extend(cluster(272, MIN_RUN));
    let (after, n) = run(&steps);
    assert_eq!((n, based(&after)), (2, 2 * MIN_RUN));
    // A run too short in the branch keeps long displacements, even though the accesses after
    // the join are in the same window.
    let mut steps = vec![If];
    steps.extend(cluster(272, MIN_RUN - 1));
    steps.push(Join);
    steps.extend(cluster(272, MIN_RUN));
    let (after, n) = run(&steps);
    assert_eq!((n, based(&after)), (1, MIN_RUN));
}

#[test]
fn the_densest_window_goes_first_and_each_dense_window_gets_a_base() {
    // Interleaved accesses to three windows; the sparse one keeps long displacements.
    let mut steps = Vec::new();
    for i in 0..MIN_RUN + 2 {
        steps.push(Access(300 + i as i32));
        steps.push(Access(5000 + i as i32));
        if i < MIN_RUN - 1 {
            steps.push(Access(2000 + i as i32));
        }
    }
    let (after, n) = run(&steps);
    assert_eq!(n, 2);
    assert!(
        after
            .iter()
            .filter(|a| a.base.is_none() && a.at >= 128)
            .all(|a| (2000..2100).contains(&a.at))
    );
}

#[test]
fn a_window_spans_exactly_256_bytes() {
    // 200 and 455 fit one window (bias 328: -128 and 127); 456 does not.
    let mut steps = vec![Access(200); MIN_RUN / 2];
    steps.extend(vec![Access(455); MIN_RUN / 2]);
    steps.push(Access(456));
    let (after, n) = run(&steps);
    assert_eq!((n, based(&after)), (1, MIN_RUN));
    assert!(after.iter().any(|a| a.disp == -128) && after.iter().any(|a| a.disp == 127));
}

#[test]
fn an_empty_function_is_fine() {
    assert_eq!(run(&[]).1, 0);
}
