//! Counter tables of spec §7 (T11, T12, T13) and the §5.3 / TC rules.

use super::*;
use crate::rules::{Gate, Rules};
use crate::testutil::Rig;
use CounterKind::{Down, Up, UpDown};

fn state(img: &[u8], l: &Layout, n: u16) -> (bool, i16) {
    (
        mem::get_u8(img, bit_at(l, n)) != 0,
        mem::get_i16_be(img, value_at(l, n)),
    )
}

/// Stack after `LD a / LD b` (b on top) or `LD a / LD b / LD c`.
fn stack(levels: &[u8]) -> u16 {
    levels.iter().fold(0, |st, &v| (st << 1) | u16::from(v))
}

#[test]
fn t11_ctu_with_reset() {
    // (I0.0 = CU, I0.1 = R) → (Q0.0, VW0).
    let rows = [
        (0, 0, false, 0),
        (1, 0, false, 1),
        (0, 0, false, 1),
        (1, 0, false, 2),
        (1, 0, false, 2),
        (0, 0, false, 2),
        (1, 0, true, 3),
        (0, 0, true, 3),
        (1, 0, true, 4),
        (0, 1, false, 0),
        (1, 1, false, 0),
        (1, 0, false, 0),
    ];
    let mut rig = Rig::new(10).counter(0, 1);
    for (k, (cu, r, q, v)) in rows.into_iter().enumerate() {
        let mut got = (false, 0);
        rig.scan(|b, l| {
            execute(
                b,
                l,
                0,
                Up,
                stack(&[cu, r]),
                Gate::scr(true),
                3,
                Rules::IN_FORCE,
            )
            .unwrap();
            got = state(b, l, 0);
        });
        assert_eq!(got, (q, v), "scan {k}");
    }
}

#[test]
fn t12_ctd_with_load() {
    let rows = [
        (0, 0, true, 0),
        (0, 1, false, 2),
        (1, 0, false, 1),
        (0, 0, false, 1),
        (1, 0, true, 0),
        (0, 0, true, 0),
        (1, 0, true, 0),
        (0, 1, false, 2),
    ];
    let mut rig = Rig::new(10).counter(1, 2);
    for (k, (cd, ld, q, v)) in rows.into_iter().enumerate() {
        let mut got = (false, 0);
        rig.scan(|b, l| {
            execute(
                b,
                l,
                1,
                Down,
                stack(&[cd, ld]),
                Gate::scr(true),
                2,
                Rules::IN_FORCE,
            )
            .unwrap();
            got = state(b, l, 1);
        });
        assert_eq!(got, (q, v), "scan {k}");
    }
}

#[test]
fn t13_ctud_wraps() {
    let rows = [
        (0, 0, 0, true, 32766),
        (1, 0, 0, true, 32767),
        (0, 0, 0, true, 32767),
        (1, 0, 0, false, -32768),
        (0, 1, 0, true, 32767),
        (0, 0, 0, true, 32767),
        (0, 0, 1, false, 0),
    ];
    let mut rig = Rig::new(10).counter(2, 3);
    for (k, (cu, cd, r, q, v)) in rows.into_iter().enumerate() {
        let mut got = (false, 0);
        rig.scan(|b, l| {
            if k == 0 {
                mem::set_i16_be(b, value_at(l, 2), 32766); // MOVW +32766, C2 on SM0.1
            }
            execute(
                b,
                l,
                2,
                UpDown,
                stack(&[cu, cd, r]),
                Gate::scr(true),
                10,
                Rules::IN_FORCE,
            )
            .unwrap();
            got = state(b, l, 2);
        });
        assert_eq!(got, (q, v), "scan {k}");
    }
}

#[test]
fn first_scan_input_on_does_not_count() {
    // TC7: a counter whose input is already on at power-up does not count.
    let mut rig = Rig::new(10).counter(4, 1);
    let mut got = (true, 9);
    rig.scan(|b, l| {
        execute(
            b,
            l,
            4,
            Up,
            stack(&[1, 0]),
            Gate::scr(true),
            1,
            Rules::IN_FORCE,
        )
        .unwrap();
        got = state(b, l, 4);
    });
    assert_eq!(got, (false, 0));
}

#[test]
fn ctud_up_and_down_in_one_execution_cancel() {
    // TC9.
    let mut rig = Rig::new(10).counter(5, 3);
    rig.scan(|b, l| execute(b, l, 5, UpDown, 0, Gate::scr(true), 1, Rules::IN_FORCE).unwrap());
    let mut got = (true, 9);
    rig.scan(|b, l| {
        execute(
            b,
            l,
            5,
            UpDown,
            stack(&[1, 1, 0]),
            Gate::scr(true),
            1,
            Rules::IN_FORCE,
        )
        .unwrap();
        got = state(b, l, 5);
    });
    assert_eq!(got, (false, 0));
}

#[test]
fn ctd_negative_cv_does_not_decrement() {
    // TC8.
    let mut rig = Rig::new(10).counter(6, 2);
    rig.scan(|b, l| mem::set_i16_be(b, value_at(l, 6), -3));
    let mut got = (true, 0);
    rig.scan(|b, l| {
        execute(
            b,
            l,
            6,
            Down,
            stack(&[1, 0]),
            Gate::scr(true),
            1,
            Rules::IN_FORCE,
        )
        .unwrap();
        got = state(b, l, 6);
    });
    assert_eq!(got, (false, -3));
}

#[test]
fn closed_gate_sees_all_inputs_off_and_updates_memory() {
    // §3.6: counters in an inactive segment see 0 on every input; memories record 0, so the
    // input still being on when the gate opens counts as an edge.
    let mut rig = Rig::new(10).counter(7, 1);
    rig.scan(|b, l| {
        execute(
            b,
            l,
            7,
            Up,
            stack(&[1, 0]),
            Gate::scr(true),
            5,
            Rules::IN_FORCE,
        )
        .unwrap()
    });
    rig.scan(|b, l| {
        execute(
            b,
            l,
            7,
            Up,
            stack(&[1, 1]),
            Gate::scr(false),
            5,
            Rules::IN_FORCE,
        )
        .unwrap()
    });
    let mut got = (true, 0);
    rig.scan(|b, l| {
        execute(
            b,
            l,
            7,
            Up,
            stack(&[1, 0]),
            Gate::scr(true),
            5,
            Rules::IN_FORCE,
        )
        .unwrap();
        got = state(b, l, 7);
    });
    assert_eq!(got, (false, 1));
}

#[test]
fn reset_keeps_edge_memory_and_checks_range() {
    let mut rig = Rig::new(10).counter(0, 1);
    rig.scan(|b, l| execute(b, l, 0, Up, 0, Gate::scr(true), 5, Rules::IN_FORCE).unwrap());
    rig.scan(|b, l| {
        execute(
            b,
            l,
            0,
            Up,
            stack(&[1, 0]),
            Gate::scr(true),
            5,
            Rules::IN_FORCE,
        )
        .unwrap();
        reset_range(b, l, 0, 1).unwrap();
    });
    let mut got = (true, 9);
    rig.scan(|b, l| {
        execute(
            b,
            l,
            0,
            Up,
            stack(&[1, 0]),
            Gate::scr(true),
            5,
            Rules::IN_FORCE,
        )
        .unwrap();
        got = state(b, l, 0);
    });
    assert_eq!(got, (false, 0), "CU still high after R: no new edge");
    let (b, l) = rig.img.split_mut();
    assert_eq!(reset_range(b, l, 30, 3), Err(ErrorCode::OperandRange));
    assert_eq!(
        execute(b, l, 32, Up, 0, Gate::scr(true), 1, Rules::IN_FORCE),
        Err(ErrorCode::OperandRange)
    );
}
