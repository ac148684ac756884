//! The conformance programs of spec §7 (T01–T15, X1, X2, X4, X6) as IR, checked scan by scan.

use super::build::*;
use stljit_core::ir::{BoxOp, CmpOp, CmpType, CounterKind, Op, Operand, TimerKind};
use stljit_core::{Area, Width};

/// Runs `rows` of (inputs on, expected bits) and compares after each scan.
fn table(
    sim: &mut Sim,
    watch: &[stljit_core::ir::BitLoc],
    rows: &[(&[stljit_core::ir::BitLoc], &[u8])],
) {
    for (k, (inputs, want)) in rows.iter().enumerate() {
        sim.scan(inputs);
        assert_eq!(sim.bits(watch), *want, "scan {k}");
    }
}

#[test]
fn t01_parallel_outputs() {
    let mut sim = Sim::main(vec![ld(i(0, 0)), out(m(0, 0)), out(q(0, 0))]);
    let on: &[_] = &[i(0, 0)];
    table(
        &mut sim,
        &[m(0, 0), q(0, 0)],
        &[(&[], &[0, 0]), (on, &[1, 1]), (on, &[1, 1]), (&[], &[0, 0])],
    );
}

#[test]
fn t02_nc_contacts_and_not() {
    let mut sim = Sim::main(vec![
        ld(i(0, 0)),
        an(i(0, 1)),
        out(q(0, 0)),
        ldn(i(0, 0)),
        on(i(0, 1)),
        out(q(0, 1)),
        ld(i(0, 0)),
        o(i(0, 1)),
        Op::Not,
        out(q(0, 2)),
    ]);
    let w = [q(0, 0), q(0, 1), q(0, 2)];
    table(
        &mut sim,
        &w,
        &[
            (&[], &[0, 1, 1]),
            (&[i(0, 1)], &[0, 1, 0]),
            (&[i(0, 0)], &[1, 1, 0]),
            (&[i(0, 0), i(0, 1)], &[0, 0, 0]),
        ],
    );
}

#[test]
fn t03_set_n3_later_wins() {
    let mut sim = Sim::main(vec![
        ld(i(0, 0)),
        set(q(0, 0), 3),
        ld(i(0, 1)),
        reset(q(0, 1), 1),
    ]);
    let w = [q(0, 0), q(0, 1), q(0, 2), q(0, 3)];
    let (a, b) = (i(0, 0), i(0, 1));
    table(
        &mut sim,
        &w,
        &[
            (&[], &[0, 0, 0, 0]),
            (&[a], &[1, 1, 1, 0]),
            (&[], &[1, 1, 1, 0]),
            (&[a, b], &[1, 0, 1, 0]),
            (&[], &[1, 0, 1, 0]),
            (&[a], &[1, 1, 1, 0]),
            (&[b], &[1, 0, 1, 0]),
        ],
    );
}

#[test]
fn t04_eu_ed_latch() {
    let mut sim = Sim::main(vec![
        ld(i(0, 0)),
        edge(0, false),
        out(m(0, 0)),
        ld(i(0, 1)),
        edge(1, true),
        out(m(0, 1)),
        ld(m(0, 0)),
        set(q(0, 0), 1),
        ld(m(0, 1)),
        reset(q(0, 0), 1),
    ]);
    let (a, b) = (i(0, 0), i(0, 1));
    table(
        &mut sim,
        &[m(0, 0), m(0, 1), q(0, 0)],
        &[
            (&[a], &[0, 0, 0]),
            (&[], &[0, 0, 0]),
            (&[a], &[1, 0, 1]),
            (&[a, b], &[0, 0, 1]),
            (&[b], &[0, 0, 1]),
            (&[], &[0, 1, 0]),
            (&[], &[0, 0, 0]),
        ],
    );
}

#[test]
fn t05_ald_old() {
    let mut sim = Sim::main(vec![
        ld(i(0, 0)),
        ld(i(0, 1)),
        ld(i(2, 0)),
        a(i(2, 1)),
        Op::OrBlock,
        Op::AndBlock,
        out(q(5, 0)),
    ]);
    let (a0, a1, b0, b1) = (i(0, 0), i(0, 1), i(2, 0), i(2, 1));
    table(
        &mut sim,
        &[q(5, 0)],
        &[
            (&[a1, b0, b1], &[0]),
            (&[a0], &[0]),
            (&[a0, a1], &[1]),
            (&[a0, b0], &[0]),
            (&[a0, b0, b1], &[1]),
            (&[b0, b1], &[0]),
        ],
    );
}

#[test]
fn t06_lps_lrd_lpp() {
    let mut sim = Sim::main(vec![
        ld(i(0, 0)),
        Op::Dup,
        ld(i(0, 5)),
        o(i(0, 6)),
        Op::AndBlock,
        out(q(7, 0)),
        Op::ReadSecond,
        ld(i(2, 1)),
        o(i(1, 3)),
        Op::AndBlock,
        out(q(6, 0)),
        Op::Pop,
        a(i(1, 0)),
        out(q(3, 0)),
    ]);
    let (i00, i05, i06, i21, i13, i10) = (i(0, 0), i(0, 5), i(0, 6), i(2, 1), i(1, 3), i(1, 0));
    table(
        &mut sim,
        &[q(7, 0), q(6, 0), q(3, 0)],
        &[
            (&[i05, i06, i21, i13, i10], &[0, 0, 0]),
            (&[i00], &[0, 0, 0]),
            (&[i00, i05], &[1, 0, 0]),
            (&[i00, i06, i21], &[1, 1, 0]),
            (&[i00, i13, i10], &[0, 1, 1]),
            (&[i00, i10], &[0, 0, 1]),
        ],
    );
}

#[test]
fn t07_nine_levels_and_lds() {
    let mut ops = vec![ld(sm(0, 0))];
    ops.extend((0..8).map(|_| ldn(sm(0, 0))));
    ops.extend((0..8).map(|_| Op::OrBlock));
    ops.push(out(q(0, 0)));
    ops.push(ld(sm(0, 0)));
    ops.extend((0..9).map(|_| ldn(sm(0, 0))));
    ops.extend((0..9).map(|_| Op::OrBlock));
    ops.push(out(q(0, 1)));
    ops.extend([
        ld(i(0, 0)),
        ld(i(0, 1)),
        ld(i(0, 2)),
        Op::Pick(2),
        out(q(0, 2)),
        Op::Pop,
        out(q(0, 3)),
    ]);
    let mut sim = Sim::main(ops);
    let w = [q(0, 0), q(0, 1), q(0, 2), q(0, 3)];
    table(
        &mut sim,
        &w,
        &[
            (&[i(0, 0)], &[1, 0, 1, 0]),
            (&[i(0, 1), i(0, 2)], &[1, 0, 0, 1]),
        ],
    );
}

#[test]
fn t08_ton_t37() {
    let prog = vec![
        ld(i(0, 0)),
        ton(TimerKind::On, 37, 100),
        ld(tbit(37)),
        out(q(0, 0)),
        ld(sm(0, 0)),
        movw(tv(37), v(0)),
    ];
    let mut sim = Sim::new(prog, vec![], 1000);
    for k in 0..14 {
        let on = (1..=12).contains(&k);
        let i00 = [i(0, 0)];
        sim.scan(if on { &i00 } else { &[] });
        let want_v = match k {
            0 | 1 | 13 => 0,
            _ => 10 * (k as i16 - 1),
        };
        assert_eq!(
            (sim.bit(q(0, 0)), sim.word(v(0))),
            (k == 11 || k == 12, want_v),
            "scan {k}"
        );
    }
}

#[test]
fn t09_tonr_t3_reset() {
    let prog = vec![
        ld(i(0, 0)),
        ton(TimerKind::Retentive, 3, 100),
        ld(tbit(3)),
        out(q(0, 0)),
        ld(i(0, 1)),
        Op::ResetTimers {
            first: stljit_core::TimerId(3),
            count: k(1),
        },
        ld(sm(0, 0)),
        movw(tv(3), v(0)),
    ];
    let mut sim = Sim::new(prog, vec![], 200);
    let rows = [
        (1, 0, 0, 0),
        (1, 0, 0, 20),
        (1, 0, 0, 40),
        (0, 0, 0, 60),
        (0, 0, 0, 60),
        (1, 0, 0, 60),
        (1, 0, 0, 80),
        (0, 0, 1, 100),
        (0, 0, 1, 100),
        (0, 1, 1, 0),
        (0, 0, 0, 0),
    ];
    for (n, (a, b, q0, vw)) in rows.into_iter().enumerate() {
        let mut on = vec![];
        if a == 1 {
            on.push(i(0, 0));
        }
        if b == 1 {
            on.push(i(0, 1));
        }
        sim.scan(&on);
        assert_eq!(
            (u8::from(sim.bit(q(0, 0))), sim.word(v(0))),
            (q0, vw),
            "scan {n}"
        );
    }
}

#[test]
fn t10_tof_t2() {
    let prog = vec![
        ld(i(0, 0)),
        ton(TimerKind::Off, 2, 20),
        ld(tbit(2)),
        out(q(0, 0)),
        ld(sm(0, 0)),
        movw(tv(2), v(0)),
    ];
    let mut sim = Sim::new(prog, vec![], 50);
    let rows = [
        (0, 0, 0),
        (1, 1, 0),
        (0, 1, 0),
        (0, 1, 5),
        (0, 1, 10),
        (1, 1, 0),
        (0, 1, 0),
        (0, 1, 5),
        (0, 1, 10),
        (0, 1, 15),
        (0, 0, 20),
        (0, 0, 20),
    ];
    for (n, (a, q0, vw)) in rows.into_iter().enumerate() {
        let i00 = [i(0, 0)];
        sim.scan(if a == 1 { &i00 } else { &[] });
        assert_eq!(
            (u8::from(sim.bit(q(0, 0))), sim.word(v(0))),
            (q0, vw),
            "scan {n}"
        );
    }
}

#[test]
fn t11_t12_t13_counters() {
    // T11 CTU.
    let mut sim = Sim::main(vec![
        ld(i(0, 0)),
        ld(i(0, 1)),
        ctr(CounterKind::Up, 0, 3),
        ld(cbit(0)),
        out(q(0, 0)),
        ld(sm(0, 0)),
        movw(cv(0), v(0)),
    ]);
    let rows = [
        (0, 0, 0, 0),
        (1, 0, 0, 1),
        (0, 0, 0, 1),
        (1, 0, 0, 2),
        (1, 0, 0, 2),
        (0, 0, 0, 2),
        (1, 0, 1, 3),
        (0, 0, 1, 3),
        (1, 0, 1, 4),
        (0, 1, 0, 0),
        (1, 1, 0, 0),
        (1, 0, 0, 0),
    ];
    for (n, (a, b, q0, vw)) in rows.into_iter().enumerate() {
        let on: Vec<_> = [(a, i(0, 0)), (b, i(0, 1))]
            .into_iter()
            .filter(|x| x.0 == 1)
            .map(|x| x.1)
            .collect();
        sim.scan(&on);
        assert_eq!(
            (u8::from(sim.bit(q(0, 0))), sim.word(v(0))),
            (q0, vw),
            "T11 scan {n}"
        );
    }
    // T12 CTD.
    let mut sim = Sim::main(vec![
        ld(i(0, 0)),
        ld(i(0, 1)),
        ctr(CounterKind::Down, 1, 2),
        ld(cbit(1)),
        out(q(0, 0)),
        ld(sm(0, 0)),
        movw(cv(1), v(2)),
    ]);
    let rows = [
        (0, 0, 1, 0),
        (0, 1, 0, 2),
        (1, 0, 0, 1),
        (0, 0, 0, 1),
        (1, 0, 1, 0),
        (0, 0, 1, 0),
        (1, 0, 1, 0),
        (0, 1, 0, 2),
    ];
    for (n, (a, b, q0, vw)) in rows.into_iter().enumerate() {
        let on: Vec<_> = [(a, i(0, 0)), (b, i(0, 1))]
            .into_iter()
            .filter(|x| x.0 == 1)
            .map(|x| x.1)
            .collect();
        sim.scan(&on);
        assert_eq!(
            (u8::from(sim.bit(q(0, 0))), sim.word(v(2))),
            (q0, vw),
            "T12 scan {n}"
        );
    }
    // T13 CTUD wrap-around.
    let mut sim = Sim::main(vec![
        ld(sm(0, 1)),
        movw(k(32766), cv(2)),
        ld(i(0, 0)),
        ld(i(0, 1)),
        ld(i(0, 2)),
        ctr(CounterKind::UpDown, 2, 10),
        ld(cbit(2)),
        out(q(0, 0)),
        ld(sm(0, 0)),
        movw(cv(2), v(4)),
    ]);
    let rows = [
        (0, 0, 0, 1, 32766),
        (1, 0, 0, 1, 32767),
        (0, 0, 0, 1, 32767),
        (1, 0, 0, 0, -32768),
        (0, 1, 0, 1, 32767),
        (0, 0, 0, 1, 32767),
        (0, 0, 1, 0, 0),
    ];
    for (n, (a, b, c, q0, vw)) in rows.into_iter().enumerate() {
        let on: Vec<_> = [(a, i(0, 0)), (b, i(0, 1)), (c, i(0, 2))]
            .into_iter()
            .filter(|x| x.0 == 1)
            .map(|x| x.1)
            .collect();
        sim.scan(&on);
        assert_eq!(
            (u8::from(sim.bit(q(0, 0))), sim.word(v(4))),
            (q0, vw),
            "T13 scan {n}"
        );
    }
}

#[test]
fn t14_movw_big_endian() {
    let mut sim = Sim::main(vec![
        ld(sm(0, 1)),
        movb(k(0x12), v(10)),
        movb(k(0x34), v(11)),
        ld(i(0, 1)),
        movw(v(10), v(100)),
        ld(sm(0, 0)),
        movb(v(101), mem(Area::Q, 0)),
        movb(v(100), mem(Area::Q, 1)),
    ]);
    let qb = |s: &Sim, n| s.val(mem(Area::Q, n), Width::Byte);
    sim.scan(&[]);
    assert_eq!((sim.word(v(100)), qb(&sim, 0), qb(&sim, 1)), (0, 0, 0));
    sim.scan(&[i(0, 1)]);
    assert_eq!(
        (sim.word(v(100)), qb(&sim, 0), qb(&sim, 1)),
        (0x1234, 0x34, 0x12)
    );
    assert_eq!(sim.img.phys_out()[..2], [0x34, 0x12]);
    sim.scan(&[]);
    assert_eq!(sim.word(v(100)), 0x1234);
}

#[test]
fn t15_flags_eno_aeno_compare() {
    use stljit_core::ir::ArithOp::{Add, Div};
    let arith = |op, src: Operand, dst| {
        Op::Box(BoxOp::IntArith {
            op,
            width: Width::Word,
            src,
            dst,
        })
    };
    let mut sim = Sim::main(vec![
        ld(sm(0, 1)),
        movw(k(32766), v(0)),
        movw(k(100), v(2)),
        movw(k(0), v(4)),
        ld(i(0, 0)),
        arith(Add, k(1), v(0)),
        Op::AndEno,
        out(q(0, 0)),
        ld(sm(1, 1)),
        out(q(0, 2)),
        ld(i(0, 1)),
        arith(Div, v(4), v(2)),
        Op::AndEno,
        out(q(0, 3)),
        ld(sm(1, 3)),
        out(q(0, 4)),
        Op::Load(cmp(CmpType::Int, CmpOp::Ge, v(0), k(32767))),
        out(q(0, 5)),
    ]);
    let w = [q(0, 0), q(0, 2), q(0, 3), q(0, 4), q(0, 5)];
    let rows: [(&[_], [u8; 5], i16); 4] = [
        (&[], [0, 0, 0, 0, 0], 32766),
        (&[i(0, 0)], [1, 0, 0, 0, 1], 32767),
        (&[i(0, 0)], [0, 1, 0, 0, 1], 32767),
        (&[i(0, 1)], [0, 1, 0, 1, 1], 32767),
    ];
    for (n, (on, want, vw0)) in rows.into_iter().enumerate() {
        sim.scan(on);
        assert_eq!(
            (sim.bits(&w), sim.word(v(0)), sim.word(v(2))),
            (want.to_vec(), vw0, 100),
            "scan {n}"
        );
    }
}

#[test]
fn x1_scr_sequence() {
    let scrt = |to, from| Op::ScrTransition { to, from };
    let mut sim = Sim::main(vec![
        ld(sm(0, 1)),
        set(s(0, 0), 1),
        Op::ScrBegin { bit: s(0, 0) },
        ld(sm(0, 0)),
        out(q(0, 0)),
        ld(i(0, 0)),
        scrt(s(0, 1), s(0, 0)),
        Op::ScrEnd,
        Op::ScrBegin { bit: s(0, 1) },
        ld(sm(0, 0)),
        out(q(0, 1)),
        ld(i(0, 1)),
        scrt(s(0, 0), s(0, 1)),
        Op::ScrEnd,
    ]);
    table(
        &mut sim,
        &[s(0, 0), s(0, 1), q(0, 0), q(0, 1)],
        &[
            (&[], &[1, 0, 1, 0]),
            (&[i(0, 0)], &[0, 1, 1, 1]),
            (&[], &[0, 1, 0, 1]),
            (&[i(0, 1)], &[1, 0, 0, 1]),
            (&[], &[1, 0, 1, 0]),
        ],
    );
}

#[test]
fn x2_for_next() {
    use stljit_core::ir::ArithOp::Add;
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        movw(k(0), v(10)),
        Op::For {
            index: v(0),
            init: k(1),
            limit: k(10),
            next: op_idx(6),
        },
        ld(sm(0, 0)),
        Op::Box(BoxOp::IntArith {
            op: Add,
            width: Width::Word,
            src: v(0),
            dst: v(10),
        }),
        Op::Nop,
        Op::Next { head: op_idx(2) },
        ld(sm(0, 0)),
        movw(v(0), v(20)),
    ]);
    sim.scan(&[]);
    assert_eq!(
        (sim.word(v(10)), sim.word(v(0)), sim.word(v(20))),
        (55, 11, 11)
    );
    assert_eq!(
        sim.img.loop_count(),
        9,
        "nine loop-backs counted (spec §2.5)"
    );
}

#[test]
fn x4_jump_skips_100ms_timer() {
    let prog = vec![
        ld(i(0, 0)),
        jmp(0),
        ld(sm(0, 0)),
        ton(TimerKind::On, 40, 1000),
        lbl(0),
        ld(sm(0, 0)),
        movw(tv(40), v(0)),
    ];
    let mut sim = Sim::new(prog, vec![], 100);
    let inputs = [0, 0, 0, 1, 1, 1, 0, 0];
    let want = [0, 1, 2, 2, 2, 2, 3, 4];
    for n in 0..8 {
        let i00 = [i(0, 0)];
        sim.scan(if inputs[n] == 1 { &i00 } else { &[] });
        assert_eq!(sim.word(v(0)), want[n], "scan {n}");
    }
}

#[test]
fn x6_pointers_and_overlap() {
    use stljit_core::ir::Loc;
    let ind = Operand::Indirect(Loc {
        area: Area::AC,
        offset: 4,
    });
    let inc = Op::Box(BoxOp::Step {
        width: Width::DWord,
        up: true,
        dst: ac(1),
    });
    let mut sim = Sim::main(vec![
        ld(sm(0, 1)),
        movd(
            Operand::AddressOf(Loc {
                area: Area::V,
                offset: 200,
            }),
            ac(1),
        ),
        movw(k(0xABCD), ind),
        inc.clone(),
        inc,
        movw(k(7), ind),
        ld(sm(0, 0)),
        movw(v(201), v(210)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.word(v(200)) as u16, 0xABCD);
    assert_eq!(sim.word(v(202)), 7);
    assert_eq!(sim.word(v(210)) as u16, 0xCD00);
}
