//! The timer and counter rules ([`timer_rule`](crate::timer::timer_rule),
//! [`counter_rule`](crate::counter::counter_rule)) against spec §5.2/§5.3, on one object's
//! bytes as the engines decode and encode them (expected values derived from the pseudo-code
//! there). The JIT emits the same rule text inline; the conformance cases and the differential
//! fuzzer hold the two engines to each other.

use crate::counter::Counter;
use crate::rules::Gate;
use crate::timer::TofPhase::{self, Done, Idle, On as TofOn, Timing};
use crate::timer::{STATE_BYTES, Timer};
use stljit_core::ir::{CounterKind, TimerKind};
use stljit_core::layout::TimerState;

/// A timer before or after one execution: (cv, bit, run, tof, pt_cache).
pub(crate) type T = (i16, bool, bool, TofPhase, i16);

/// (kind, res, before, input, gate, PT, d100, after).
pub(crate) type TimerRow = (TimerKind, u8, T, bool, bool, i16, u32, T);

#[rustfmt::skip]
pub(crate) const TIMER_ROWS: &[TimerRow] = {
    use TimerKind::{Off, On, Retentive};
    &[
        // TON: the enabling execution credits no time; then + d100 (100-ms only), sat at 32767.
        (On, 100, (0, false, false, Idle, 0), true, true, 5, 3, (0, false, true, Idle, 5)),
        (On, 100, (4, false, true, Idle, 5), true, true, 5, 3, (7, true, true, Idle, 5)),
        (On, 100, (32766, true, true, Idle, 5), true, true, 5, 10, (32767, true, true, Idle, 5)),
        (On, 10, (4, false, true, Idle, 5), true, true, 5, 3, (4, false, true, Idle, 5)),
        (On, 100, (7, true, true, Idle, 9), false, true, 5, 3, (0, false, false, Idle, 9)),
        (On, 100, (0, false, false, Idle, 0), true, true, -5, 0, (0, true, true, Idle, -5)),
        // Inactive SCR: IN = 0.
        (On, 100, (7, true, true, Idle, 5), true, false, 5, 3, (0, false, false, Idle, 5)),
        // TONR: holds cv and bit with IN off, resumes from the held cv.
        (Retentive, 100, (7, true, true, Idle, 5), false, true, 5, 3, (7, true, false, Idle, 5)),
        (Retentive, 100, (7, false, false, Idle, 5), true, true, 5, 3, (7, true, true, Idle, 5)),
        (Retentive, 100, (7, true, true, Idle, 9), true, true, 9, 1, (8, false, true, Idle, 9)),
        // TOF: on → bit 1, cv 0; on→off starts timing without credit; reaching PT → Done.
        (Off, 100, (0, false, false, Idle, 0), true, true, 3, 4, (0, true, false, TofOn, 0)),
        (Off, 100, (0, true, false, TofOn, 0), false, true, 3, 4, (0, true, false, Timing, 3)),
        (Off, 100, (1, true, false, Timing, 3), false, true, 3, 1, (2, true, false, Timing, 3)),
        (Off, 100, (1, true, false, Timing, 3), false, true, 3, 4, (3, false, false, Done, 3)),
        (Off, 10, (1, true, false, Timing, 3), false, true, 3, 4, (1, true, false, Timing, 3)),
        (Off, 100, (3, false, false, Done, 3), false, true, 7, 4, (3, false, false, Done, 3)),
        (Off, 100, (0, false, false, Idle, 0), false, true, 3, 4, (0, false, false, Idle, 0)),
        // TOF in an inactive SCR: forced idle.
        (Off, 100, (1, true, false, Timing, 3), false, false, 3, 4, (0, false, false, Idle, 3)),
        (Off, 100, (1, true, false, TofOn, 3), true, false, 3, 4, (0, false, false, Idle, 3)),
    ]
};

/// One timer's bytes: value, bit, private state.
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct TimerBytes {
    pub(crate) value: [u8; 2],
    pub(crate) bit: u8,
    pub(crate) state: [u8; STATE_BYTES],
}

pub(crate) fn timer_bytes(kind: TimerKind, res: u8, t: T) -> TimerBytes {
    let mut state = [0xA5; STATE_BYTES]; // bytes 6.. unused by S7 timers: must survive
    state[TimerState::KIND as usize] = kind.code();
    state[TimerState::RES as usize] = res;
    let mut b = TimerBytes {
        value: [0; 2],
        bit: 0,
        state,
    };
    let (cv, bit, run, tof, pt_cache) = t;
    let t = Timer {
        cv,
        bit,
        run,
        tof: tof as u8,
        pt_cache,
        res,
    };
    t.encode(&mut b.value, &mut b.bit, &mut b.state);
    b
}

#[test]
fn timer_rule_follows_spec_5_2() {
    for (i, &(kind, res, before, input, gate, pt, d100, after)) in TIMER_ROWS.iter().enumerate() {
        let mut b = timer_bytes(kind, res, before);
        let mut t = Timer::decode(&b.value, b.bit, &b.state);
        t.step(kind, input, Gate::scr(gate), pt, d100);
        t.encode(&mut b.value, &mut b.bit, &mut b.state);
        assert_eq!(b, timer_bytes(kind, res, after), "row {i}");
    }
}

#[test]
fn odd_private_bytes_follow_from_raw() {
    // A snapshot may carry any private bytes: bit 0 of the bit byte is the bit, any non-zero
    // run byte is `run` (`TimerFields::from_raw`); a TOF byte that is no phase is kept by TON
    // and read as Idle by TOF (with IN off and the gate open: stays idle, written as 0).
    let mut state = [0; STATE_BYTES];
    state[TimerState::RUN as usize] = 0x80;
    state[TimerState::TOF as usize] = 9;
    state[TimerState::RES as usize] = 100;
    let t = Timer::decode(&[0, 4], 0xFE, &state);
    assert_eq!((t.cv, t.bit, t.run, t.tof), (4, false, true, 9));
    let mut on = t;
    on.step(TimerKind::On, true, Gate::Open, 10, 3);
    assert_eq!((on.cv, on.bit, on.run, on.tof), (7, false, true, 9));
    let mut off = t;
    off.step(TimerKind::Off, false, Gate::Open, 10, 3);
    assert_eq!((off.cv, off.bit, off.tof), (4, false, Idle as u8));
}

/// A counter before or after one execution: (cv, bit, prev_up, prev_down).
type C = (i16, bool, u8, u8);

/// (kind, before, stack levels S0..S2, gate, first scan, PV, after).
type CounterRow = (CounterKind, C, [u8; 3], bool, bool, i16, C);

#[rustfmt::skip]
const COUNTER_ROWS: &[CounterRow] = {
    use CounterKind::{Down, Up, UpDown};
    &[
        // CTU: CU = S1, R = S0; counts rising edges up to 32767, bit = cv >= PV.
        (Up, (2, false, 0, 0), [0, 1, 0], true, false, 3, (3, true, 1, 0)),
        (Up, (2, false, 1, 0), [0, 1, 0], true, false, 3, (2, false, 1, 0)),
        (Up, (32767, true, 0, 0), [0, 1, 0], true, false, 3, (32767, true, 1, 0)),
        (Up, (2, true, 0, 0), [1, 1, 0], true, false, 3, (0, false, 1, 0)),
        (Up, (2, false, 0, 7), [0, 1, 0], true, true, 3, (2, false, 1, 7)),
        (Up, (2, false, 1, 0), [0, 0, 0], true, false, 1, (2, true, 0, 0)),
        // CTD: CD = S1, LD = S0; loads PV, counts down to 0 and stops, bit = cv == 0.
        (Down, (0, true, 0, 0), [1, 1, 0], true, false, 4, (4, false, 0, 1)),
        (Down, (1, false, 0, 0), [0, 1, 0], true, false, 4, (0, true, 0, 1)),
        (Down, (0, true, 0, 0), [0, 1, 0], true, false, 4, (0, true, 0, 1)),
        (Down, (-3, false, 0, 0), [0, 1, 0], true, false, 4, (-3, false, 0, 1)),
        // CTUD: CU = S2, CD = S1, R = S0; wraps both ways.
        (UpDown, (32767, true, 0, 0), [0, 0, 1], true, false, 5, (-32768, false, 1, 0)),
        (UpDown, (-32768, false, 0, 0), [0, 1, 0], true, false, 5, (32767, true, 0, 1)),
        (UpDown, (4, false, 0, 0), [0, 1, 1], true, false, 4, (4, true, 1, 1)),
        (UpDown, (4, true, 0, 0), [1, 1, 1], true, false, 4, (0, false, 1, 1)),
        // Inactive SCR: every input reads 0 (no reset, no edge), memories take 0.
        (UpDown, (4, false, 1, 1), [1, 1, 1], false, false, 4, (4, true, 0, 0)),
        (Up, (2, false, 0, 0), [1, 1, 0], false, false, 3, (2, false, 0, 0)),
    ]
};

fn stack_of(levels: [u8; 3]) -> u16 {
    levels
        .iter()
        .enumerate()
        .map(|(i, &v)| u16::from(v) << i)
        .sum()
}

#[test]
fn counter_rule_follows_spec_5_3() {
    for (i, &(kind, before, levels, gate, first, pv, after)) in COUNTER_ROWS.iter().enumerate() {
        let (cv, bit, up, down) = before;
        let mut value = cv.to_be_bytes();
        let mut bitb = u8::from(bit);
        let mut state = [up, down, kind.code(), 0x5A];
        let mut c = Counter::decode(value, &state);
        if let Some(on) = c.step(kind, stack_of(levels), Gate::scr(gate), pv, first) {
            bitb = u8::from(on);
        }
        c.encode(&mut value, &mut state);
        let (cv, bit, up, down) = after;
        let want = (
            cv.to_be_bytes(),
            u8::from(bit),
            [up, down, kind.code(), 0x5A],
        );
        assert_eq!((value, bitb, state), want, "row {i}");
    }
}
