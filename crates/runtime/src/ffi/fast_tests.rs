//! The fast shims against spec §5.2/§5.3 (expected values derived from the pseudo-code there),
//! and against the interpreter's path ([`timer::execute`], [`counter::execute`]) on whole images.

use super::*;
use crate::image::Image;
use crate::rules::{Gate, Rules};
use crate::timer::STATE_BYTES;
use crate::timer::TofPhase::{self, Done, Idle, On as TofOn, Timing};
use crate::{counter, mem, timer};
use stljit_core::Area;
use stljit_core::ProfileId;
use stljit_core::ir::{CounterKind, TimerKind};
use stljit_core::layout::{CounterState, Layout, Sched, TimerState};

/// A timer before or after one execution: (cv, bit, run, tof, pt_cache).
type T = (i16, bool, bool, TofPhase, i16);

/// (kind, res, before, input, gate, PT, d100, after).
type TimerRow = (TimerKind, u8, T, bool, bool, i16, u32, T);

#[rustfmt::skip]
const TIMER_ROWS: &[TimerRow] = {
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
struct TimerBytes {
    value: [u8; 2],
    bit: u8,
    state: [u8; STATE_BYTES],
}

fn timer_bytes(kind: TimerKind, res: u8, t: T) -> TimerBytes {
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
        tof,
        pt_cache,
        res,
    };
    t.encode(&mut b.value, &mut b.bit, &mut b.state);
    b
}

fn ctl(low: u32, gate: bool) -> u32 {
    low | if gate { CTL_GATE } else { 0 }
}

#[test]
fn timer_fast_follows_spec_5_2() {
    for (i, &(kind, res, before, input, gate, pt, d100, after)) in TIMER_ROWS.iter().enumerate() {
        let mut b = timer_bytes(kind, res, before);
        let d = d100.to_ne_bytes();
        let c = ctl(u32::from(input), gate);
        // SAFETY: four distinct live locals of the documented sizes.
        let st = unsafe {
            timer_fast_fn(kind)(
                b.value.as_mut_ptr(),
                &mut b.bit,
                b.state.as_mut_ptr(),
                d.as_ptr(),
                c,
                i32::from(pt),
            )
        };
        assert_eq!(st, RT_OK, "row {i}");
        assert_eq!(b, timer_bytes(kind, res, after), "row {i}");
    }
}

/// Timer `n`'s (value, bit, state) offsets in `l`.
fn timer_at(l: &Layout, n: u16) -> (usize, usize, usize) {
    (
        (l.base(Area::TimerValue) + 2 * u32::from(n)) as usize,
        (l.base(Area::TimerBit) + u32::from(n)) as usize,
        l.timer_state(n) as usize,
    )
}

#[test]
fn timer_fast_matches_execute_on_the_image() {
    let n = 41;
    for (i, &(kind, res, before, input, gate, pt, d100, _)) in TIMER_ROWS.iter().enumerate() {
        let mut a = Image::blank(ProfileId::A5);
        let (buf, l) = a.split_mut();
        let (v, bt, s) = timer_at(l, n);
        let tb = timer_bytes(kind, res, before);
        buf[v..v + 2].copy_from_slice(&tb.value);
        buf[bt] = tb.bit;
        buf[s..s + STATE_BYTES].copy_from_slice(&tb.state);
        mem::set_u32_ne(buf, l.sched(Sched::D100), d100);
        let mut b = a.clone();
        let (buf, l) = a.split_mut();
        timer::execute(buf, l, n, kind, input, Gate::scr(gate), pt).unwrap();
        let (fb, l) = b.split_mut();
        let p = fb.as_mut_ptr();
        // SAFETY: disjoint in-range blocks of a live image (layout offsets of an existing timer).
        let st = unsafe {
            timer_fast_fn(kind)(
                p.add(v),
                p.add(bt),
                p.add(s),
                p.add(l.sched(Sched::D100) as usize),
                ctl(u32::from(input), gate),
                i32::from(pt),
            )
        };
        assert_eq!(st, RT_OK);
        assert!(a.bytes_mut() == b.bytes_mut(), "row {i}");
    }
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

fn stack_of(levels: [u8; 3]) -> u32 {
    levels
        .iter()
        .enumerate()
        .map(|(i, &v)| u32::from(v) << i)
        .sum()
}

#[test]
fn counter_fast_follows_spec_5_3() {
    for (i, &(kind, before, levels, gate, first, pv, after)) in COUNTER_ROWS.iter().enumerate() {
        let (cv, bit, up, down) = before;
        let mut value = cv.to_be_bytes();
        let mut bitb = u8::from(bit);
        let mut state = [up, down, kind.code(), 0x5A];
        let fs = u8::from(first);
        // SAFETY: four distinct live locals of the documented sizes.
        let st = unsafe {
            counter_fast_fn(kind)(
                value.as_mut_ptr(),
                &mut bitb,
                state.as_mut_ptr(),
                &fs,
                ctl(stack_of(levels), gate),
                i32::from(pv),
            )
        };
        assert_eq!(st, RT_OK, "row {i}");
        let (cv, bit, up, down) = after;
        let want = (
            cv.to_be_bytes(),
            u8::from(bit),
            [up, down, kind.code(), 0x5A],
        );
        assert_eq!((value, bitb, state), want, "row {i}");
    }
}

#[test]
fn counter_fast_matches_execute_on_the_image() {
    let n = 29;
    for (i, &(kind, before, levels, gate, first, pv, _)) in COUNTER_ROWS.iter().enumerate() {
        let mut a = Image::blank(ProfileId::A5);
        let (buf, l) = a.split_mut();
        let v = (l.base(Area::CounterValue) + 2 * u32::from(n)) as usize;
        let bt = (l.base(Area::CounterBit) + u32::from(n)) as usize;
        let s = l.counter_state(n) as usize;
        let (cv, bit, up, down) = before;
        buf[v..v + 2].copy_from_slice(&cv.to_be_bytes());
        buf[bt] = u8::from(bit);
        buf[s + CounterState::PREV_UP as usize] = up;
        buf[s + CounterState::PREV_DOWN as usize] = down;
        mem::set_u8(buf, l.sched(Sched::FIRST_SCAN), u8::from(first));
        let mut b = a.clone();
        let (buf, l) = a.split_mut();
        let stack = stack_of(levels) as u16;
        counter::execute(buf, l, n, kind, stack, Gate::scr(gate), pv, Rules::IN_FORCE).unwrap();
        let (fb, l) = b.split_mut();
        let p = fb.as_mut_ptr();
        // SAFETY: disjoint in-range blocks of a live image (layout offsets of an existing counter).
        let st = unsafe {
            counter_fast_fn(kind)(
                p.add(v),
                p.add(bt),
                p.add(s),
                p.add(l.sched(Sched::FIRST_SCAN) as usize),
                ctl(u32::from(stack), gate),
                i32::from(pv),
            )
        };
        assert_eq!(st, RT_OK);
        assert!(a.bytes_mut() == b.bytes_mut(), "row {i}");
    }
}

#[test]
fn ctl_bits_above_the_gate_are_ignored() {
    // A TON on, gate open, with garbage in the unused ctl bits behaves like the clean call.
    let run = |c: u32| {
        let mut b = timer_bytes(TimerKind::On, 100, (4, false, true, Idle, 5));
        let d = 3u32.to_ne_bytes();
        // SAFETY: four distinct live locals of the documented sizes.
        unsafe {
            stljit_rt_ton_fast(
                b.value.as_mut_ptr(),
                &mut b.bit,
                b.state.as_mut_ptr(),
                d.as_ptr(),
                c,
                5,
            )
        };
        b
    };
    assert_eq!(run(ctl(1, true) | 0xFFFF_0000), run(ctl(1, true)));
    assert_eq!(
        run(ctl(1, true)),
        timer_bytes(TimerKind::On, 100, (7, true, true, Idle, 5))
    );
}
