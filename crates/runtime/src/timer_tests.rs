//! Timing tables of spec §7 (T08, T09, T10, X3, X4) and the §5.2 rules, run against the timer
//! functions directly.

use super::*;
use crate::rules::Gate;
use crate::testutil::Rig;
use TimerKind::{Off, On, Retentive};

fn state(img: &[u8], l: &Layout, n: u16) -> (bool, i16) {
    let t = Timer::load(img, l, n);
    (t.bit, t.cv)
}

#[test]
fn t08_ton_t37() {
    // scan_ms = 1000; I0.0 off in scan 0, on in 1..=12, off in 13. (Q0.0, VW0) per scan.
    let mut want: Vec<(bool, i16)> = vec![(false, 0), (false, 0)];
    want.extend((2..=10).map(|k| (false, 10 * (k - 1))));
    want.extend([(true, 100), (true, 110), (false, 0)]);
    let mut rig = Rig::new(1000).timer(37, 1, 100);
    for (k, w) in want.into_iter().enumerate() {
        let input = (1..=12).contains(&k);
        let mut got = (false, 0);
        rig.scan(|b, l| {
            execute(b, l, 37, On, input, Gate::scr(true), 100, None).unwrap();
            got = state(b, l, 37);
        });
        assert_eq!(got, w, "scan {k}");
    }
}

#[test]
fn t09_tonr_t3_with_reset() {
    // scan_ms = 200: (I0.0, I0.1) → (Q0.0 before R, VW0 after R).
    let rows = [
        (1, 0, false, 0),
        (1, 0, false, 20),
        (1, 0, false, 40),
        (0, 0, false, 60),
        (0, 0, false, 60),
        (1, 0, false, 60),
        (1, 0, false, 80),
        (0, 0, true, 100),
        (0, 0, true, 100),
        (0, 1, true, 0),
        (0, 0, false, 0),
    ];
    let mut rig = Rig::new(200).timer(3, 2, 10);
    for (k, (i0, i1, q, vw)) in rows.into_iter().enumerate() {
        let mut got = (false, 0);
        rig.scan(|b, l| {
            execute(b, l, 3, Retentive, i0 == 1, Gate::scr(true), 100, None).unwrap();
            got.0 = state(b, l, 3).0;
            if i1 == 1 {
                reset_range(b, l, 3, 1).unwrap();
            }
            got.1 = state(b, l, 3).1;
        });
        assert_eq!(got, (q, vw), "scan {k}");
    }
}

#[test]
fn t10_tof_t2() {
    // scan_ms = 50: I0.0 → (Q0.0, VW0).
    let rows = [
        (0, false, 0),
        (1, true, 0),
        (0, true, 0),
        (0, true, 5),
        (0, true, 10),
        (1, true, 0),
        (0, true, 0),
        (0, true, 5),
        (0, true, 10),
        (0, true, 15),
        (0, false, 20),
        (0, false, 20),
    ];
    let mut rig = Rig::new(50).timer(2, 3, 10);
    for (k, (i0, q, vw)) in rows.into_iter().enumerate() {
        let mut got = (false, 0);
        rig.scan(|b, l| {
            execute(b, l, 2, Off, i0 == 1, Gate::scr(true), 20, None).unwrap();
            got = state(b, l, 2);
        });
        assert_eq!(got, (q, vw), "scan {k}");
    }
}

#[test]
fn x3_100ms_timer_twice_per_scan_gains_time_10ms_does_not() {
    for (n, res, want) in [(37, 100, [0, 2, 4, 6]), (5, 10, [0, 10, 20, 30])] {
        let mut rig = Rig::new(100).timer(n, 1, res);
        for (k, w) in want.into_iter().enumerate() {
            let mut got = 0;
            rig.scan(|b, l| {
                execute(b, l, n, On, true, Gate::scr(true), 1000, None).unwrap();
                execute(b, l, n, On, true, Gate::scr(true), 1000, None).unwrap();
                got = state(b, l, n).1;
            });
            assert_eq!(got, w, "T{n} scan {k}");
        }
    }
}

#[test]
fn x4_skipped_100ms_timer_loses_time() {
    let inputs = [0, 0, 0, 1, 1, 1, 0, 0];
    let want = [0, 1, 2, 2, 2, 2, 3, 4];
    let mut rig = Rig::new(100).timer(40, 1, 100);
    for k in 0..inputs.len() {
        let mut got = 0;
        rig.scan(|b, l| {
            if inputs[k] == 0 {
                execute(b, l, 40, On, true, Gate::scr(true), 1000, None).unwrap();
            }
            got = state(b, l, 40).1;
        });
        assert_eq!(got, want[k], "scan {k}");
    }
}

#[test]
fn skipped_10ms_timer_keeps_timing() {
    // §5.2: a 10-ms timer, once enabled, is refreshed at scan start even when not executed.
    let mut rig = Rig::new(100).timer(10, 1, 10);
    rig.scan(|b, l| execute(b, l, 10, On, true, Gate::scr(true), 25, None).unwrap());
    for k in 1..=3 {
        let mut got = (false, 0);
        rig.scan(|b, l| got = state(b, l, 10));
        assert_eq!(got, (k * 10 >= 25, k * 10), "scan {k}");
    }
}

#[test]
fn saturates_at_32767_and_keeps_bit() {
    // TC5.
    let mut rig = Rig::new(1000).timer(1, 1, 1);
    rig.scan(|b, l| execute(b, l, 1, On, true, Gate::scr(true), 5, None).unwrap());
    for _ in 0..40 {
        rig.scan(|b, l| execute(b, l, 1, On, true, Gate::scr(true), 5, None).unwrap());
    }
    let (b, l) = rig.img.split_mut();
    assert_eq!(state(b, l, 1), (true, 32767));
}

#[test]
fn negative_preset_turns_ton_on_at_once() {
    // TC11: PT compared as signed.
    let mut rig = Rig::new(10).timer(30, 1, 100);
    let mut got = (false, 0);
    rig.scan(|b, l| {
        execute(b, l, 30, On, true, Gate::scr(true), -1, None).unwrap();
        got = state(b, l, 30);
    });
    assert_eq!(got, (true, 0));
}

#[test]
fn inactive_scr_gate_rules() {
    // §3.6 / TC13: closed gate → TON reset, TONR hold, TOF forced idle even with input on.
    let mut rig = Rig::new(100)
        .timer(20, 1, 100)
        .timer(21, 2, 100)
        .timer(22, 3, 100);
    for i in 0..3 {
        rig.scan(|b, l| {
            execute(b, l, 20, On, true, Gate::scr(true), 1, None).unwrap();
            execute(b, l, 21, Retentive, true, Gate::scr(true), 1, None).unwrap();
            execute(b, l, 22, Off, i == 0, Gate::scr(true), 100, None).unwrap();
        });
    }
    let mut got = [(false, 0); 3];
    rig.scan(|b, l| {
        assert!(state(b, l, 22).0, "TOF still timing before the gate closes");
        execute(b, l, 20, On, true, Gate::scr(false), 1, None).unwrap();
        execute(b, l, 21, Retentive, true, Gate::scr(false), 1, None).unwrap();
        execute(b, l, 22, Off, true, Gate::scr(false), 100, None).unwrap();
        got = [state(b, l, 20), state(b, l, 21), state(b, l, 22)];
    });
    assert_eq!(got, [(false, 0), (true, 2), (false, 0)]);
    let (b, l) = rig.img.split_mut();
    assert_eq!(Timer::load(b, l, 22).tof, TofPhase::Idle as u8);
}

#[test]
fn tof_after_reset_needs_a_fresh_transition() {
    let mut rig = Rig::new(10).timer(4, 3, 10);
    rig.scan(|b, l| execute(b, l, 4, Off, true, Gate::scr(true), 5, None).unwrap());
    rig.scan(|b, l| reset_range(b, l, 4, 1).unwrap());
    for _ in 0..3 {
        let mut got = (true, 1);
        rig.scan(|b, l| {
            execute(b, l, 4, Off, false, Gate::scr(true), 5, None).unwrap();
            got = state(b, l, 4);
        });
        assert_eq!(got, (false, 0));
    }
}

#[test]
fn reset_range_checks_the_end() {
    let mut rig = Rig::new(10);
    let (b, l) = rig.img.split_mut();
    assert_eq!(reset_range(b, l, 60, 5), Err(ErrorCode::OperandRange));
    assert_eq!(reset_range(b, l, 60, 4), Ok(()));
    assert_eq!(reset_range(b, l, 63, 0), Ok(()));
    assert_eq!(
        execute(b, l, 64, On, true, Gate::scr(true), 1, None),
        Err(ErrorCode::OperandRange)
    );
}

#[test]
fn the_declared_resolution_rules_over_the_state_byte() {
    // Spec §5.2: a timer's resolution is "compile time, from the timer number". T37 is a
    // 100-ms TON; a restored snapshot whose resolution byte says 0 (an unused timer, which the
    // byte alone would never credit) still gets the scan's 100-ms delta when the resolution is
    // passed: scan_ms = 1000, so 10 per scan after the starting one. The byte is left as it
    // was. (The clock refresh at scan start reads the byte; 0 leaves the timer alone there.)
    let mut rig = Rig::new(1000).timer(37, 1, 0);
    let mut cvs = Vec::new();
    for _ in 0..3 {
        rig.scan(|b, l| {
            execute(b, l, 37, On, true, Gate::scr(true), 100, Some(100)).unwrap();
            cvs.push(state(b, l, 37).1);
            assert_eq!(b[(l.timer_state(37) + TimerState::RES) as usize], 0);
        });
    }
    assert_eq!(cvs, [0, 10, 20]);
}

#[test]
fn declared_resolutions_are_indexed_by_timer_number() {
    use stljit_core::TimerId;
    use stljit_core::ir::TimerDecl;
    use stljit_core::profile::Resolution;
    let program = Program {
        profile: stljit_core::ProfileId::A5,
        pous: vec![],
        counters: vec![],
        edges: vec![],
        logic_stack_depth: 9,
        files: vec![],
        data: Vec::new(),
        timers: vec![
            TimerDecl {
                id: TimerId(37),
                kind: On,
                resolution: Resolution::Ms100,
            },
            TimerDecl {
                id: TimerId(33),
                kind: Retentive,
                resolution: Resolution::Ms10,
            },
        ],
    };
    let res = declared_resolutions(&program);
    assert_eq!(res.len(), 38);
    assert_eq!(
        (res[37], res[33], res[0], res[36]),
        (Some(100), Some(10), None, None)
    );
}
