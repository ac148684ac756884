//! Interpreter speed: nanoseconds per executed STL instruction on a generated 10,000-instruction
//! program mixing bit logic, stack ops, timers, counters, moves, compares and arithmetic. The IR is
//! built directly so the bench does not depend on the front end. Throughput is reported in
//! instructions executed per scan (the program has no jumps, so every op executes every scan).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use stljit_core::ir::*;
use stljit_core::profile::Resolution;
use stljit_core::{Area, CounterId, EdgeSlot, OpIdx, ProfileId, TimerId, Width};
use stljit_interp::Interpreter;
use stljit_runtime::{Engine, Image};

const OPS: usize = 10_000;

fn bit(area: Area, byte: u32, bit: u8) -> Contact {
    Contact::Bit {
        bit: BitLoc { area, byte, bit },
        negated: false,
    }
}

fn v(offset: u32) -> Operand {
    Operand::Mem(Loc {
        area: Area::V,
        offset,
    })
}

/// One 20-op network; `j` varies the operands so timers, counters and addresses differ.
fn network(j: u32, ops: &mut Vec<Op>) {
    let j8 = (j % 8) as u8;
    ops.extend([
        Op::Load(bit(Area::I, j % 16, j8)),
        Op::And(bit(Area::M, j % 32, (j8 + 1) % 8)),
        Op::Or(bit(Area::I, (j + 3) % 16, j8)),
        Op::Assign {
            bit: BitLoc {
                area: Area::Q,
                byte: j % 16,
                bit: j8,
            },
            immediate: false,
        },
        Op::Load(bit(Area::SM, 0, 0)),
        Op::Timer {
            kind: TimerKind::On,
            timer: TimerId(20 + (j % 44) as u16),
            preset: Operand::Const(100),
        },
        Op::Load(bit(Area::I, 1, j8)),
        Op::Load(bit(Area::I, 2, j8)),
        Op::Counter {
            kind: CounterKind::Up,
            counter: CounterId((j % 32) as u16),
            preset: Operand::Const(10),
        },
        Op::Pop,
        Op::Box(BoxOp::Move {
            width: Width::Word,
            src: v(2 * (j % 100)),
            dst: v(200 + 2 * (j % 100)),
        }),
        Op::Load(Contact::Compare {
            ty: CmpType::Int,
            op: CmpOp::Ge,
            lhs: v(2 * (j % 50)),
            rhs: Operand::Const(5),
        }),
        Op::And(bit(Area::M, 1, j8)),
        Op::Box(BoxOp::IntArith {
            op: ArithOp::Add,
            width: Width::Word,
            src: Operand::Const(1),
            dst: v(400 + 2 * (j % 64)),
        }),
        Op::Dup,
        Op::Load(bit(Area::M, 2, j8)),
        Op::OrBlock,
        Op::Edge {
            slot: EdgeSlot((j % 256) as u16),
            falling: j.is_multiple_of(2),
        },
        Op::AndBlock,
        Op::Assign {
            bit: BitLoc {
                area: Area::M,
                byte: 3 + j % 8,
                bit: j8,
            },
            immediate: false,
        },
    ]);
}

fn program() -> Program {
    let mut ops = Vec::with_capacity(OPS);
    let mut j = 0;
    while ops.len() < OPS {
        network(j, &mut ops);
        j += 1;
    }
    ops.truncate(OPS);
    let profile = ProfileId::A5;
    let timers = (20..64)
        .map(|n| TimerDecl {
            id: TimerId(n),
            kind: TimerKind::On,
            resolution: Resolution::Ms100,
        })
        .collect();
    let counters = (0..32)
        .map(|n| CounterDecl {
            id: CounterId(n),
            kind: CounterKind::Up,
        })
        .collect();
    let locs = vec![SrcLoc::default(); ops.len()];
    let main = Pou {
        name: "MAIN".into(),
        kind: PouKind::Main,
        ops,
        locs,
        labels: Vec::<OpIdx>::new(),
    };
    Program {
        profile,
        pous: vec![main],
        timers,
        counters,
        edges: vec![EdgeDecl { init: false }; 256],
        logic_stack_depth: 9,
        files: vec![],
        data: Vec::new(),
    }
}

fn bench(c: &mut Criterion) {
    let p = program();
    let mut interp = Interpreter::new(&p).expect("generated program is valid");
    let mut img = Image::cold_start(&p);
    let mut t = 0u64;
    let mut group = c.benchmark_group("interp");
    group.throughput(Throughput::Elements(p.op_count() as u64));
    group.bench_function("scan_10k_ops", |b| {
        b.iter(|| {
            t += 10;
            img.set_inputs(&[(t / 10) as u8, (t / 30) as u8, (t / 70) as u8]);
            black_box(interp.scan(black_box(&mut img), t))
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
