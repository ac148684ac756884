//! Spec §2.12 timer rules, §6.9's timer rows and §6.6's TIM rows (cycle_ms = 100: cycle k runs
//! at t = (k − 1) · 100 ms).

use super::*;
use crate::omron::flags::Flag;
use OmronTimerKind::*;

const OPEN: Gate = Gate::Open;
const IL: Gate = Gate::Closed(GatePolicy::OmronInterlock);

fn t_of(k: u64) -> u64 {
    (k - 1) * 100
}

/// Runs a TIM-family timer over cycles 1.. with `(gate, ec)` per cycle and checks
/// `(PV, flag)` after each.
fn run_tim(kind: OmronTimerKind, sv: u16, rows: &[(Gate, bool, u16, bool)]) {
    let mut t = OmronTimer::default();
    for (i, &(gate, ec, pv, flag)) in rows.iter().enumerate() {
        let k = i as u64 + 1;
        t.step(kind, ec, false, sv, t_of(k), gate);
        assert_eq!((t.pv, t.flag), (pv, flag), "k = {k}");
    }
}

#[test]
fn spec_6_9_tim() {
    // `TIM 0001 #0003`, input 0.00 per §6.9's "tim" column; (PV = D10, flag = T0001):
    // k1 EC OFF → reset: PV := SV. k2 start: PV := SV, no decrement. k3–k5: 100 ms per cycle
    // = 1 tick each, 3 → 0, flag at 0 (k5). k6 stays 0. k7 EC OFF → PV := SV, flag OFF.
    // k8 start again, k9 one tick.
    run_tim(
        Tim,
        0x0003,
        &[
            (OPEN, false, 0x0003, false),
            (OPEN, true, 0x0003, false),
            (OPEN, true, 0x0002, false),
            (OPEN, true, 0x0001, false),
            (OPEN, true, 0x0000, true),
            (OPEN, true, 0x0000, true),
            (OPEN, false, 0x0003, false),
            (OPEN, true, 0x0003, false),
            (OPEN, true, 0x0002, false),
        ],
    );
}

#[test]
fn spec_6_6_tim_in_an_interlock() {
    // `TIM 0000 #0003` on input a = 0.01 inside IL(0.00). §6.6 columns IL, a, T0000 PV; the
    // flag drives 100.02. Interlocked cycles (k5, k6, k11) reset: PV := SV, flag OFF; the
    // first open cycle after them starts from SV (k7, k12).
    run_tim(
        Tim,
        0x0003,
        &[
            (OPEN, false, 0x0003, false), // k1: a OFF, reset
            (OPEN, true, 0x0003, false),  // k2: start
            (OPEN, true, 0x0002, false),
            (OPEN, true, 0x0001, false),
            (IL, true, 0x0003, false),   // k5
            (IL, true, 0x0003, false),   // k6
            (OPEN, true, 0x0003, false), // k7: restart from SV
            (OPEN, true, 0x0002, false),
            (OPEN, true, 0x0001, false),
            (OPEN, true, 0x0000, true),  // k10: 100.02 ON
            (IL, true, 0x0003, false),   // k11: reset, 100.02 OFF
            (OPEN, true, 0x0003, false), // k12: restart
        ],
    );
}

#[test]
fn interlock_changes_no_flag_and_keeps_a_bad_sv_timer() {
    let mut t = OmronTimer {
        pv: 0x0001,
        flag: false,
        running: true,
        last_ms: 0,
        rem_ms: 40,
    };
    assert_eq!(t.step(Tim, true, false, 0x0005, 100, IL), FlagWrites::NONE);
    assert_eq!((t.pv, t.flag, t.running), (0x0005, false, false));
    // §2.12: with a non-BCD SV the interlock keeps PV and flag (running := false).
    let mut t = OmronTimer {
        pv: 0x0000,
        flag: true,
        running: true,
        last_ms: 0,
        rem_ms: 0,
    };
    assert_eq!(t.step(Tim, true, false, 0x00A0, 100, IL), FlagWrites::NONE);
    assert_eq!((t.pv, t.flag, t.running), (0x0000, true, false));
}

#[test]
fn bcd_errors() {
    // Reset with a non-BCD SV: ER ON, PV and flag kept, running := false.
    let mut t = OmronTimer {
        pv: 0x0000,
        flag: true,
        running: true,
        last_ms: 0,
        rem_ms: 0,
    };
    assert_eq!(
        t.step(Tim, false, false, 0x12A4, 100, OPEN),
        FlagWrites::ERROR
    );
    assert_eq!((t.pv, t.flag, t.running), (0x0000, true, false));
    // Start with a non-BCD SV: ER ON, nothing changes (still not running).
    let before = t;
    assert_eq!(
        t.step(Tim, true, false, 0x12A4, 200, OPEN),
        FlagWrites::ERROR
    );
    assert_eq!(t, before);
    // The binary kind takes the same word as a plain number: 0x12A4 = 4772 units.
    let mut x = OmronTimer::default();
    assert_eq!(x.step(TimX, true, false, 0x12A4, 0, OPEN), FlagWrites::OK);
    assert_eq!(x.step(TimX, true, false, 0x12A4, 100, OPEN), FlagWrites::OK);
    assert_eq!(x.pv, 0x12A3);
    // Running with a PV a program made non-BCD: ER, and PV, flag, rem and last are kept.
    let mut t = OmronTimer::default();
    t.step(Tim, true, false, 0x0010, 0, OPEN);
    t.step(Tim, true, false, 0x0010, 150, OPEN); // one tick, 50 ms left over
    assert_eq!((t.pv, t.rem_ms, t.last_ms), (0x0009, 50, 150));
    t.pv = 0x000B;
    let before = t;
    assert_eq!(
        t.step(Tim, true, false, 0x0010, 250, OPEN),
        FlagWrites::ERROR
    );
    assert_eq!(t, before);
    // Every normal execution turns ER OFF.
    t.pv = 0x0009;
    assert_eq!(t.step(Tim, true, false, 0x0010, 250, OPEN), FlagWrites::OK);
    assert!(FlagWrites::OK.writes(Flag::Er) && !FlagWrites::OK.sets(Flag::Er));
}

#[test]
fn units_remainder_and_catch_up() {
    // TIMH: 10 ms units; 100 ms per cycle = 10 ticks. SV #0025 = 25 → 15 → 5 → 0.
    let mut t = OmronTimer::default();
    let pvs: Vec<u16> = (1..=5)
        .map(|k| {
            t.step(TimH, true, false, 0x0025, t_of(k), OPEN);
            t.pv
        })
        .collect();
    assert_eq!(pvs, [0x0025, 0x0015, 0x0005, 0x0000, 0x0000]);
    // TMHHX: 1 ms binary; 100 ms of 150.
    let mut t = OmronTimer::default();
    t.step(TmhhX, true, false, 150, 0, OPEN);
    t.step(TmhhX, true, false, 150, 100, OPEN);
    assert_eq!((t.pv, t.flag), (50, false));
    // A 30 ms cycle with a 100 ms unit: rem collects 30, 60, 90, then 120 → 1 tick, rem 20.
    let mut t = OmronTimer::default();
    t.step(Tim, true, false, 0x0002, 0, OPEN);
    for (k, (pv, rem)) in [(1, (2, 30)), (2, (2, 60)), (3, (2, 90)), (4, (1, 20))] {
        t.step(Tim, true, false, 0x0002, 30 * k, OPEN);
        assert_eq!((t.pv, t.rem_ms), (pv, rem), "t = {}", 30 * k);
    }
    // Skipped (jumped) for 1 s and executed again: t − last = 1020 ms credited at once,
    // PV saturates at 0 and the flag turns ON (catch_up).
    t.step(Tim, true, false, 0x0002, 1140, OPEN);
    assert_eq!((t.pv, t.flag), (0, true));
    // A program write to the PV is honoured: MOV #0005 T → counts on from 5.
    t.pv = 0x0005;
    t.step(Tim, true, false, 0x0002, 1240, OPEN);
    assert_eq!((t.pv, t.flag), (0x0004, false));
}

#[test]
fn first_execution_and_zero_sv() {
    // Cold start: all zero memory, not PV = SV.
    assert_eq!(OmronTimer::default().pv, 0);
    assert_eq!(
        OmronTimer::idle(0x0003),
        OmronTimer {
            pv: 0x0003,
            ..OmronTimer::default()
        }
    );
    // U18: EC ON at the very first execution starts from SV in that cycle.
    let mut t = OmronTimer::default();
    t.step(Tim, true, false, 0x0003, 0, OPEN);
    assert_eq!((t.pv, t.flag, t.running), (0x0003, false, true));
    // SV 0: the flag is ON at the start.
    let mut t = OmronTimer::default();
    t.step(Tim, true, false, 0x0000, 0, OPEN);
    assert!(t.flag);
    // The TIM family ignores the reset input.
    let mut a = OmronTimer::default();
    let mut b = OmronTimer::default();
    for k in 1..=4 {
        a.step(Tim, true, false, 0x0003, t_of(k), OPEN);
        b.step(Tim, true, true, 0x0003, t_of(k), OPEN);
    }
    assert_eq!(a, b);
}

#[test]
fn ttim_accumulates_holds_and_resets() {
    // TTIM #0003: (input, reset) per cycle → (PV, flag). Input ON at k2 starts the clock
    // (no credit), k3/k4 add one 100-ms tick each, OFF at k5 holds PV 2, k6 ON again restarts
    // the clock without crediting the OFF time, k7 reaches 3 = SV: flag ON, k8 stays at SV
    // (saturates), k9 reset: PV 0, flag OFF.
    let rows = [
        (false, false, 0x0000, false),
        (true, false, 0x0000, false),
        (true, false, 0x0001, false),
        (true, false, 0x0002, false),
        (false, false, 0x0002, false),
        (true, false, 0x0002, false),
        (true, false, 0x0003, true),
        (true, false, 0x0003, true),
        (true, true, 0x0000, false),
        (true, false, 0x0000, false),
    ];
    let mut t = OmronTimer::default();
    for (i, &(input, reset, pv, flag)) in rows.iter().enumerate() {
        let k = i as u64 + 1;
        assert_eq!(
            t.step(Ttim, input, reset, 0x0003, t_of(k), OPEN),
            FlagWrites::OK
        );
        assert_eq!((t.pv, t.flag), (pv, flag), "k = {k}");
    }
}

#[test]
fn ttim_rules_fixed_here() {
    // Interlock (U4): PV and flag held, no flag change, and the interlocked time is not
    // credited: the next execution restarts the clock.
    let mut t = OmronTimer::default();
    t.step(TtimX, true, false, 10, 0, OPEN);
    t.step(TtimX, true, false, 10, 100, OPEN);
    assert_eq!(t.pv, 1);
    assert_eq!(t.step(TtimX, true, false, 10, 200, IL), FlagWrites::NONE);
    assert_eq!((t.pv, t.running), (1, false));
    t.step(TtimX, true, false, 10, 900, OPEN);
    assert_eq!(t.pv, 1);
    t.step(TtimX, true, false, 10, 1000, OPEN);
    assert_eq!(t.pv, 2);
    // A non-BCD SV: ER ON, nothing changes, reset included.
    let mut t = OmronTimer {
        pv: 0x0002,
        flag: false,
        running: true,
        last_ms: 0,
        rem_ms: 10,
    };
    let before = t;
    assert_eq!(
        t.step(Ttim, true, true, 0x00A0, 100, OPEN),
        FlagWrites::ERROR
    );
    assert_eq!(t, before);
    // A non-BCD PV while counting: ER ON, nothing changes.
    t.pv = 0x000C;
    let before = t;
    assert_eq!(
        t.step(Ttim, true, false, 0x0010, 100, OPEN),
        FlagWrites::ERROR
    );
    assert_eq!(t, before);
    // A PV above SV written by the program is kept, and the flag is PV ≥ SV.
    let mut t = OmronTimer {
        pv: 9,
        flag: false,
        running: true,
        last_ms: 0,
        rem_ms: 0,
    };
    t.step(TtimX, true, false, 5, 100, OPEN);
    assert_eq!((t.pv, t.flag), (9, true));
    // Reset clears the unconverted milliseconds too.
    let mut t = OmronTimer {
        pv: 3,
        flag: false,
        running: true,
        last_ms: 0,
        rem_ms: 70,
    };
    t.step(TtimX, false, true, 5, 100, OPEN);
    assert_eq!((t.pv, t.flag, t.rem_ms, t.running), (0, false, 0, false));
}

#[test]
fn never_panics_on_extreme_inputs() {
    for kind in OmronTimerKind::ALL {
        for sv in [0, 1, 0x9999, 0xFFFF] {
            for pv in [0, 0x9999, 0xFFFF] {
                for (last, now) in [(0, u64::MAX), (u64::MAX, 0), (5, 5)] {
                    let unit = kind.unit().millis();
                    let mut t = OmronTimer {
                        pv,
                        flag: true,
                        running: true,
                        last_ms: last,
                        rem_ms: unit - 1,
                    };
                    t.step(*kind, true, false, sv, now, OPEN);
                    assert!(t.rem_ms < unit, "{kind:?}");
                }
            }
        }
    }
}
