//! Program control (spec §4.13, §4.14, §2.5): CALL, RET/CRET, END, STOP, loop budget, fatal errors.

use super::build::*;
use crate::Interpreter;
use stljit_core::ir::{BoxOp, CmpOp, CmpType, Contact, Loc, Op, Operand};
use stljit_core::ir::{OpRule, VerifyError};
use stljit_core::{Area, ErrorCode, FatalCode, ScanStatus, Width};

fn incw(dst: Operand) -> Op {
    Op::Box(BoxOp::Step {
        width: Width::Word,
        up: true,
        dst,
    })
}

#[test]
fn call_restores_the_callers_stack() {
    // §3.2 CALL: the callee's pushes do not leak; after return S0/S1 are the caller's.
    let sub = vec![
        ldn(sm(0, 0)),
        ldn(sm(0, 0)),
        Op::Return { conditional: false },
    ];
    let main = vec![
        ld(sm(0, 0)),
        ld(sm(0, 0)),
        call(1),
        out(q(0, 0)),
        Op::Pop,
        out(q(0, 2)),
    ];
    let mut sim = Sim::new(main, vec![sub], 10);
    sim.scan(&[]);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 2)]), [1, 1]);
}

#[test]
fn callee_sees_s0_one_and_writes_its_own_frame() {
    let sub = vec![out(q(0, 1)), ld(sm(0, 0)), movb(k(5), mem(Area::L, 0))];
    let mut sim = Sim::new(
        vec![ld(sm(0, 0)), call(1), ldn(sm(0, 0)), out(q(0, 0))],
        vec![sub],
        10,
    );
    sim.scan(&[]);
    assert!(sim.bit(q(0, 1)), "callee's first coil sees S0 = 1");
    let lb0 = Loc {
        area: Area::L,
        offset: 0,
    };
    assert_eq!(sim.img.read(lb0, Width::Byte, 1), Ok(5));
    assert_eq!(sim.img.read(lb0, Width::Byte, 0), Ok(0));
}

#[test]
fn nesting_beyond_eight_is_0x0008() {
    // P6: SBR0 calls itself; levels 1..=8 run, the ninth CALL is skipped with 0x0008.
    let sub = vec![ld(sm(0, 0)), incw(v(0)), call(1)];
    let mut sim = Sim::new(vec![ld(sm(0, 0)), call(1)], vec![sub], 10);
    assert_eq!(sim.scan(&[]), ScanStatus::Ok);
    assert_eq!(sim.word(v(0)), 8);
    assert_eq!(sim.img.last_error(), ErrorCode::CallNesting as u16);
    assert_eq!(sim.img.error_site(), (1, 2));
    assert!(!sim.img.eno());
}

#[test]
fn cret_end_and_mend() {
    let sub = vec![
        ld(i(0, 0)),
        Op::Return { conditional: true },
        ld(sm(0, 0)),
        out(q(0, 2)),
    ];
    let main = vec![
        ld(sm(0, 0)),
        call(1),
        ld(i(0, 1)),
        Op::End { conditional: true },
        ld(sm(0, 0)),
        out(q(0, 0)),
        Op::End { conditional: false },
        out(q(0, 1)),
    ];
    let mut sim = Sim::new(main, vec![sub], 10);
    sim.scan(&[]);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1), q(0, 2)]), [1, 0, 1]);
    let mut sim2 = Sim::new(
        sim.interp.program().pous[0].ops.clone(),
        vec![sim.interp.program().pous[1].ops.clone()],
        10,
    );
    sim2.scan(&[i(0, 0), i(0, 1)]);
    assert_eq!(
        sim2.bits(&[q(0, 0), q(0, 1), q(0, 2)]),
        [0, 0, 0],
        "CRET and END taken"
    );
}

#[test]
fn stop_completes_the_scan_then_stops() {
    // P1 and §2.5.
    let mut sim = Sim::main(vec![ld(i(0, 0)), Op::Stop, ld(sm(0, 0)), out(q(0, 0))]);
    assert_eq!(sim.scan(&[]), ScanStatus::Ok);
    assert_eq!(sim.scan(&[i(0, 0)]), ScanStatus::Stopped);
    assert_eq!(sim.img.phys_out()[0], 1);
    assert_eq!(sim.scan(&[]), ScanStatus::Stopped);
    assert_eq!(sim.img.phys_out()[0], 0);
}

#[test]
fn endless_jump_is_a_watchdog_fatal_at_the_budget() {
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        out(q(0, 0)),
        lbl(0),
        ld(sm(0, 0)),
        incw(v(0)),
        jmp(0),
    ]);
    sim.img.set_loop_limit(100);
    assert_eq!(sim.scan(&[]), ScanStatus::Fatal);
    // The body ran once, then after each of the 100 allowed back-edges; the 101st is fatal.
    assert_eq!(sim.word(v(0)), 101);
    assert_eq!(sim.img.fatal(), FatalCode::Watchdog as u16);
    assert_eq!(sim.img.error_site(), (0, 5));
    assert_eq!(sim.img.phys_out()[0], 0, "fatal: no output write (E3)");
    assert!(sim.img.is_stopped());
}

#[test]
fn wdr_restarts_the_budget_and_forward_jumps_are_free() {
    let lt = Op::Load(Contact::Compare {
        ty: CmpType::Int,
        op: CmpOp::Lt,
        lhs: v(0),
        rhs: k(300),
    });
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        jmp(1),
        lbl(0),
        ld(sm(0, 0)),
        incw(v(0)),
        Op::Wdr,
        lbl(1),
        lt,
        jmp(0),
    ]);
    sim.img.set_loop_limit(100);
    assert_eq!(sim.scan(&[]), ScanStatus::Ok);
    assert_eq!(sim.word(v(0)), 300);
}

#[test]
fn for_loop_edge_cases() {
    // P2: disabled FOR skipped entirely; INIT > FINAL skipped with S0 = 1.
    let body = |n: usize| Op::For {
        index: v(0),
        init: k(5),
        limit: k(4),
        next: op_idx(n),
    };
    let mut sim = Sim::main(vec![
        ldn(sm(0, 0)),
        Op::For {
            index: v(2),
            init: k(1),
            limit: k(3),
            next: op_idx(3),
        },
        incw(v(4)),
        Op::Next { head: op_idx(1) },
        out(q(0, 0)),
        ldn(sm(0, 0)),
        ld(sm(0, 0)),
        body(9),
        incw(v(6)),
        Op::Next { head: op_idx(7) },
        out(q(0, 1)),
    ]);
    sim.scan(&[]);
    assert_eq!(
        (
            sim.word(v(2)),
            sim.word(v(4)),
            sim.word(v(0)),
            sim.word(v(6))
        ),
        (0, 0, 5, 0)
    );
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1)]), [0, 1]);
}

#[test]
fn for_to_32767_never_ends() {
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        Op::For {
            index: v(0),
            init: k(32760),
            limit: k(32767),
            next: op_idx(2),
        },
        Op::Next { head: op_idx(1) },
    ]);
    sim.img.set_loop_limit(1000);
    assert_eq!(sim.scan(&[]), ScanStatus::Fatal);
    assert_eq!(sim.img.fatal(), FatalCode::Watchdog as u16);
}

#[test]
fn nan_and_bad_pointer_compares_are_fatal() {
    let nan = k(i64::from(f32::NAN.to_bits()));
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        out(q(0, 0)),
        Op::Load(Contact::Compare {
            ty: CmpType::Real,
            op: CmpOp::Eq,
            lhs: v(0),
            rhs: nan,
        }),
    ]);
    assert_eq!(sim.scan(&[]), ScanStatus::Fatal);
    assert_eq!(sim.img.fatal(), FatalCode::CompareNaN as u16);
    assert_eq!(sim.img.phys_out()[0], 0);
    let bad = Operand::Indirect(Loc {
        area: Area::V,
        offset: 0,
    });
    let mut sim = Sim::main(vec![Op::Load(Contact::Compare {
        ty: CmpType::Int,
        op: CmpOp::Eq,
        lhs: bad,
        rhs: k(0),
    })]);
    assert_eq!(sim.scan(&[]), ScanStatus::Fatal);
    assert_eq!(sim.img.fatal(), FatalCode::CompareIndirect as u16);
}

#[test]
fn cscre_skips_the_rest_of_the_segment() {
    let mut sim = Sim::main(vec![
        ld(sm(0, 1)),
        set(s(0, 0), 1),
        Op::ScrBegin { bit: s(0, 0) },
        ld(i(0, 0)),
        Op::ScrCondEnd { end: op_idx(7) },
        ld(sm(0, 0)),
        out(q(0, 0)),
        Op::ScrEnd,
        ld(sm(0, 0)),
        out(q(0, 1)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1)]), [1, 1]);
    sim.scan(&[i(0, 0)]);
    assert_eq!(
        sim.bits(&[q(0, 0), q(0, 1)]),
        [1, 1],
        "skipped coil keeps its value"
    );
}

#[test]
fn new_rejects_dangling_references() {
    let mut p = program(vec![jmp(0)], vec![]);
    assert!(matches!(
        Interpreter::new(&p),
        Err(VerifyError::Op {
            rule: OpRule::UnknownLabel,
            ..
        })
    ));
    p = program(vec![call(3)], vec![]);
    assert!(Interpreter::new(&p).is_err());
    p = program(vec![Op::Next { head: op_idx(0) }], vec![]);
    assert!(Interpreter::new(&p).is_err());
    p = program(vec![], vec![]);
    p.logic_stack_depth = 0;
    assert_eq!(
        Interpreter::new(&p).unwrap_err(),
        VerifyError::StackDepth(0)
    );
    p.pous.clear();
    assert_eq!(Interpreter::new(&p).unwrap_err(), VerifyError::NoMain);
}
