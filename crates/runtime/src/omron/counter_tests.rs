//! Spec §3.3 counter rules, §6.9's counter rows and §6.6's CNT rows.

use super::*;
use OmronCounterKind::*;

const OPEN: Gate = Gate::Open;
const IL: Gate = Gate::Closed(GatePolicy::OmronInterlock);

/// Runs `kind` with `(gate, [count, dec, reset])` per cycle, checking `(PV, flag)` after each.
fn run(kind: OmronCounterKind, sv: u16, rows: &[(Gate, [bool; 3], u16, bool)]) {
    let mut c = OmronCounter::default();
    for (i, &(gate, inputs, pv, flag)) in rows.iter().enumerate() {
        c.step(kind, inputs, sv, gate);
        assert_eq!((c.pv, c.flag), (pv, flag), "k = {}", i + 1);
    }
}

#[test]
fn spec_6_9_cnt() {
    // `CNT 0002 #0002`, count 0.01, reset 0.02 (§6.9 columns cnt, rst; C0002 PV, 100.01):
    // k1 reset: PV := SV. k3 and k5 are rising edges of cnt: 2 → 1 → 0, flag ON at 0 (k5).
    // k6: cnt still ON, no edge. k8 reset: PV := SV, flag OFF.
    let c = |cnt, rst| [cnt, false, rst];
    run(
        Cnt,
        0x0002,
        &[
            (OPEN, c(false, true), 0x0002, false),
            (OPEN, c(false, false), 0x0002, false),
            (OPEN, c(true, false), 0x0001, false),
            (OPEN, c(false, false), 0x0001, false),
            (OPEN, c(true, false), 0x0000, true),
            (OPEN, c(true, false), 0x0000, true),
            (OPEN, c(false, false), 0x0000, true),
            (OPEN, c(false, true), 0x0002, false),
            (OPEN, c(false, false), 0x0002, false),
        ],
    );
}

#[test]
fn spec_6_9_cntr() {
    // `CNTR(012) 0003 #0002`, inc 0.03, dec 0.04, reset 0.05 (§6.9 columns inc, dec, rst2;
    // C0003 PV, 100.02): k1 reset: PV 0. k2 inc: 1. k4 inc: 2 = SV, flag stays OFF. k6 inc at
    // SV: wraps to 0, flag ON. k7 dec at 0: wraps to SV, flag ON. k8 no edge: kept. k9 dec:
    // 1, flag OFF.
    let c = |inc, dec, rst| [inc, dec, rst];
    run(
        Cntr,
        0x0002,
        &[
            (OPEN, c(false, false, true), 0x0000, false),
            (OPEN, c(true, false, false), 0x0001, false),
            (OPEN, c(false, false, false), 0x0001, false),
            (OPEN, c(true, false, false), 0x0002, false),
            (OPEN, c(false, false, false), 0x0002, false),
            (OPEN, c(true, false, false), 0x0000, true),
            (OPEN, c(false, true, false), 0x0002, true),
            (OPEN, c(false, false, false), 0x0002, true),
            (OPEN, c(false, true, false), 0x0001, false),
        ],
    );
}

#[test]
fn spec_6_6_cnt_in_an_interlock() {
    // `CNT 0000 #0005`, count 0.02, reset 0.03 inside IL(0.00) (§6.6 columns IL, cnt, rst;
    // C0000 PV): k2 and k4 count (5 → 4 → 3). k5–k6 are interlocked: not executed, so k6's
    // pulse is not counted and the edge memory keeps k4's ON; k7 (cnt OFF) refreshes it, so
    // k8 and k10 count (3 → 2 → 1). k11 is interlocked, k12 has cnt OFF: PV stays 1.
    let c = |cnt, rst| [cnt, false, rst];
    run(
        Cnt,
        0x0005,
        &[
            (OPEN, c(false, true), 0x0005, false),
            (OPEN, c(true, false), 0x0004, false),
            (OPEN, c(false, false), 0x0004, false),
            (OPEN, c(true, false), 0x0003, false),
            (IL, c(false, false), 0x0003, false),
            (IL, c(true, false), 0x0003, false),
            (OPEN, c(false, false), 0x0003, false),
            (OPEN, c(true, false), 0x0002, false),
            (OPEN, c(false, false), 0x0002, false),
            (OPEN, c(true, false), 0x0001, false),
            (IL, c(false, false), 0x0001, false),
            (OPEN, c(false, false), 0x0001, false),
        ],
    );
}

#[test]
fn interlock_freezes_everything() {
    // U17: the edge memory is frozen: ON before the interlock, OFF during it, ON at release
    // → no count at release.
    let mut c = OmronCounter::default();
    c.step(CntX, [false, false, true], 5, OPEN);
    c.step(CntX, [true, false, false], 5, OPEN);
    assert_eq!(c.pv, 4);
    let before = c;
    for kind in OmronCounterKind::ALL {
        let mut d = before;
        assert_eq!(d.step(*kind, [false, true, true], 5, IL), FlagWrites::NONE);
        assert_eq!(d, before, "{kind:?}");
    }
    c.step(CntX, [true, false, false], 5, OPEN);
    assert_eq!(c.pv, 4, "still ON since before the interlock: no edge");
}

#[test]
fn edges_resets_and_errors() {
    // Initial edge memory OFF (U7): a count input ON at the first execution counts.
    let mut c = OmronCounter {
        pv: 0x0003,
        ..OmronCounter::default()
    };
    c.step(Cnt, [true, false, false], 0x0003, OPEN);
    assert_eq!(c.pv, 0x0002);
    // A count edge while reset is ON is not counted, but the memory is updated.
    let mut c = OmronCounter::default();
    assert_eq!(
        c.step(Cnt, [true, false, true], 0x0003, OPEN),
        FlagWrites::OK
    );
    assert_eq!((c.pv, c.flag, c.prev_count), (0x0003, false, true));
    c.step(Cnt, [true, false, false], 0x0003, OPEN);
    assert_eq!(c.pv, 0x0003, "no new edge");
    // Counting at PV 0 with the flag OFF (fresh memory): PV 0, flag ON.
    let mut c = OmronCounter::default();
    c.step(CntX, [true, false, false], 7, OPEN);
    assert_eq!((c.pv, c.flag), (0, true));
    // A non-BCD SV: ER ON, no reset and no count, edge memories still updated.
    let mut c = OmronCounter {
        pv: 0x0004,
        ..OmronCounter::default()
    };
    assert_eq!(
        c.step(Cntr, [true, true, true], 0x00A0, OPEN),
        FlagWrites::ERROR
    );
    assert_eq!(
        (c.pv, c.flag, c.prev_count, c.prev_dec),
        (0x0004, false, true, true)
    );
    // A count meeting a non-BCD PV: ER, count lost, PV and flag kept, memory updated.
    let mut c = OmronCounter {
        pv: 0x000A,
        ..OmronCounter::default()
    };
    assert_eq!(
        c.step(Cnt, [true, false, false], 0x0005, OPEN),
        FlagWrites::ERROR
    );
    assert_eq!((c.pv, c.flag, c.prev_count), (0x000A, false, true));
    // …but an execution without a count edge is fine: ER OFF.
    assert_eq!(
        c.step(Cnt, [true, false, false], 0x0005, OPEN),
        FlagWrites::OK
    );
    // BCD counting crosses a digit: #0010 − 1 = #0009.
    let mut c = OmronCounter {
        pv: 0x0010,
        ..OmronCounter::default()
    };
    c.step(Cnt, [true, false, false], 0x0020, OPEN);
    assert_eq!(c.pv, 0x0009);
    // CNT ignores the decrement input and its memory.
    let mut c = OmronCounter {
        pv: 3,
        ..OmronCounter::default()
    };
    c.step(CntX, [false, true, false], 5, OPEN);
    assert_eq!((c.pv, c.prev_dec), (3, false));
}

#[test]
fn ring_details() {
    // Both edges at once: PV unchanged, flag unchanged too.
    let mut c = OmronCounter {
        pv: 2,
        flag: true,
        ..OmronCounter::default()
    };
    assert_eq!(c.step(CntrX, [true, true, false], 5, OPEN), FlagWrites::OK);
    assert_eq!((c.pv, c.flag), (2, true));
    // PV above SV (a program wrote it): increment wraps as at SV; decrement goes one down.
    let mut c = OmronCounter {
        pv: 9,
        ..OmronCounter::default()
    };
    c.step(CntrX, [true, false, false], 5, OPEN);
    assert_eq!((c.pv, c.flag), (0, true));
    let mut c = OmronCounter {
        pv: 9,
        flag: true,
        ..OmronCounter::default()
    };
    c.step(CntrX, [false, true, false], 5, OPEN);
    assert_eq!((c.pv, c.flag), (8, false));
    // BCD ring: #0009 + 1 = #0010 with SV #0012.
    let mut c = OmronCounter {
        pv: 0x0009,
        ..OmronCounter::default()
    };
    c.step(Cntr, [true, false, false], 0x0012, OPEN);
    assert_eq!(c.pv, 0x0010);
    // Decrement at 0 loads the SV word as written.
    let mut c = OmronCounter::default();
    c.step(Cntr, [false, true, false], 0x0012, OPEN);
    assert_eq!((c.pv, c.flag), (0x0012, true));
    // Reset: PV 0, flag OFF.
    c.step(Cntr, [false, false, true], 0x0012, OPEN);
    assert_eq!((c.pv, c.flag), (0, false));
}

#[test]
fn never_panics() {
    for kind in OmronCounterKind::ALL {
        for sv in [0, 0x9999, 0xFFFF] {
            for pv in [0, 0x9999, 0xFFFF] {
                for bits in 0..8u8 {
                    let inputs = [bits & 1 != 0, bits & 2 != 0, bits & 4 != 0];
                    let mut c = OmronCounter {
                        pv,
                        ..OmronCounter::default()
                    };
                    c.step(*kind, inputs, sv, OPEN);
                }
            }
        }
    }
}
