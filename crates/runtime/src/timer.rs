//! Timers (spec §5.2), as functions on the image bytes.
//!
//! A timer's visible state is its current value (area `TimerValue`, big-endian `i16` at `2n`) and
//! its bit (area `TimerBit`, byte `n`); the private state ([`TimerState`]) holds `run`, the TOF
//! phase, the kind and resolution written at cold start, and the preset seen at the last
//! execution (used by the clock refresh of 1-ms and 10-ms timers at scan start).
//!
//! The rules of an execution live in [`Timer::step`], over a decoded [`Timer`];
//! [`Timer::decode`]/[`Timer::encode`] are the only code that knows how those fields sit in the
//! timer's bytes. The interpreter reaches them
//! through [`execute`] (layout lookups, range check), the JIT through
//! [`crate::ffi::stljit_rt_timer_fast`] (offsets fixed at compile time), so both engines run the
//! same rules on the same bytes.

use crate::rules::{Gate, GatePolicy};
use crate::{block, mem};
use std::hint::select_unpredictable;
use stljit_core::ir::TimerKind;
use stljit_core::layout::{Layout, Sched, TIMER_STATE_SIZE, TimerState};
use stljit_core::{Area, ErrorCode};

/// Phase of an off-delay timer (the `TOF` byte of [`TimerState`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum TofPhase {
    /// Never switched on, or reset.
    Idle = 0,
    /// Input on: bit 1, CV 0.
    On = 1,
    /// Input went off: counting towards PT.
    Timing = 2,
    /// Reached PT: bit 0, CV = PT.
    Done = 3,
}

impl TofPhase {
    #[inline]
    fn from_u8(v: u8) -> TofPhase {
        match v {
            1 => TofPhase::On,
            2 => TofPhase::Timing,
            3 => TofPhase::Done,
            _ => TofPhase::Idle,
        }
    }
}

/// `min(cv + d, 32767)` (spec §5 `sat`). A negative CV written by a program counts up from there.
/// Computed in `i64`, so it cannot overflow.
#[inline]
fn sat_add(cv: i16, d: u32) -> i16 {
    (i64::from(cv) + i64::from(d)).min(i64::from(i16::MAX)) as i16
}

/// Bytes of a timer's private state block.
pub const STATE_BYTES: usize = TIMER_STATE_SIZE as usize;

const RUN: usize = TimerState::RUN as usize;
const TOF: usize = TimerState::TOF as usize;
const RES: usize = TimerState::RES as usize;
const PT: usize = TimerState::PT_CACHE as usize;

/// The fields of one timer the rules read and write, decoded from its value, bit and private
/// state bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timer {
    /// Current value.
    pub cv: i16,
    /// Timer bit.
    pub bit: bool,
    /// TON/TONR: timing active.
    pub run: bool,
    /// TOF phase.
    pub tof: TofPhase,
    /// Preset seen at the last execution (for the clock refresh).
    pub pt_cache: i16,
    /// Resolution in ms (1, 10, 100; 0 for an unused timer). Read only.
    pub res: u8,
}

impl Timer {
    /// Decodes the fields from the timer's value bytes (big-endian), bit byte and private state
    /// block (no indexing that can fail: the arrays have fixed sizes).
    #[inline]
    pub fn decode(value: &[u8; 2], bit: u8, state: &[u8; STATE_BYTES]) -> Timer {
        Timer {
            cv: i16::from_be_bytes(*value),
            bit: bit & 1 != 0,
            run: state[RUN] != 0,
            tof: TofPhase::from_u8(state[TOF]),
            pt_cache: i16::from_ne_bytes([state[PT], state[PT + 1]]),
            res: state[RES],
        }
    }

    /// Writes the fields back; only the run, TOF and PT-cache bytes of the state block are
    /// written (kind and resolution are read only).
    #[inline]
    pub fn encode(&self, value: &mut [u8; 2], bit: &mut u8, state: &mut [u8; STATE_BYTES]) {
        *value = self.cv.to_be_bytes();
        *bit = u8::from(self.bit);
        state[RUN] = u8::from(self.run);
        state[TOF] = self.tof as u8;
        [state[PT], state[PT + 1]] = self.pt_cache.to_ne_bytes();
    }

    /// Offsets of timer `n`'s value, bit and private state ([`Layout::timer_bytes`]).
    fn offsets(layout: &Layout, n: u16) -> (u32, u32, u32) {
        let [(v, _), (b, _), (s, _)] = layout.timer_bytes(n);
        (v, b, s)
    }

    fn load(img: &[u8], layout: &Layout, n: u16) -> Timer {
        let (v, b, s) = Timer::offsets(layout, n);
        let state = mem::get_array(img, s);
        Timer::decode(&mem::get_array(img, v), mem::get_u8(img, b), &state)
    }

    fn store(&self, img: &mut [u8], layout: &Layout, n: u16) {
        let (v, b, s) = Timer::offsets(layout, n);
        // Start from the current block: `encode` leaves the read-only bytes as they are.
        let (mut value, mut bit, mut state) = ([0; 2], 0, mem::get_array(img, s));
        self.encode(&mut value, &mut bit, &mut state);
        mem::set_array(img, v, value);
        mem::set_u8(img, b, bit);
        mem::set_array(img, s, state);
    }

    /// Executes `TON`/`TONR`/`TOF` on this timer (spec §5.2) under `gate`. Open: `IN = input`.
    /// Closed under [`GatePolicy::S7Scr`]: `IN = 0`, and a TOF is forced idle (inactive SCR
    /// rule). Closed under [`GatePolicy::OmronInterlock`]: TON resets, TONR and TOF are not
    /// executed. `d100` is the scan's 100-ms delta, credited only by a 100-ms timer. Cannot
    /// panic: no indexing, no division, and the only arithmetic is [`sat_add`].
    #[inline]
    pub fn step(&mut self, kind: TimerKind, input: bool, gate: Gate, preset: i16, d100: u32) {
        let t = self;
        let d100 = if t.res == 100 { d100 } else { 0 };
        if gate == Gate::Closed(GatePolicy::OmronInterlock) {
            if kind == TimerKind::On {
                t.run = false;
                t.cv = 0;
                t.bit = false;
            }
            return;
        }
        // Open: `IN = input`; closed under the S7 SCR policy: `IN = 0`.
        let gate = gate.is_open();
        let on = input & gate;
        match kind {
            TimerKind::On | TimerKind::Retentive => {
                // Spec §5.2, as selects: with IN on a running timer, CV = sat(CV + d100);
                // otherwise (starting, or IN off) a TON's CV is 0 and a TONR's is held. With IN
                // the bit is CV >= PT and the PT cache takes PT; without, a TON's bit is 0 and a
                // TONR's held. `run` = IN. No branches: the inputs follow the plant from scan to
                // scan, so a branch on them is mispredicted about half the time, which in the
                // JIT's timer shim cost more than the rule itself (docs/performance.md).
                let timing = on & t.run;
                let held = if kind == TimerKind::On { 0 } else { t.cv };
                t.cv = select_unpredictable(timing, sat_add(t.cv, d100), held);
                let held_bit = kind == TimerKind::Retentive && t.bit;
                // Bit and PT cache are chosen by one select of both packed together: a select
                // of the old PT cache on its own is compiled as a branch around its load.
                let pack = |pt: i16, bit: bool| (u32::from(pt as u16) << 16) | u32::from(bit);
                let chosen = select_unpredictable(
                    on,
                    pack(preset, t.cv >= preset),
                    pack(t.pt_cache, held_bit),
                );
                t.pt_cache = (chosen >> 16) as u16 as i16;
                t.bit = chosen & 1 != 0;
                t.run = on;
            }
            TimerKind::Off => {
                if !gate {
                    t.tof = TofPhase::Idle;
                    t.bit = false;
                    t.cv = 0;
                } else if on {
                    t.tof = TofPhase::On;
                    t.bit = true;
                    t.cv = 0;
                } else {
                    match t.tof {
                        TofPhase::On => t.tof = TofPhase::Timing,
                        TofPhase::Timing => t.cv = sat_add(t.cv, d100),
                        TofPhase::Idle | TofPhase::Done => {}
                    }
                    if t.tof == TofPhase::Timing {
                        t.pt_cache = preset;
                        if t.cv >= preset {
                            t.cv = preset;
                            t.bit = false;
                            t.tof = TofPhase::Done;
                        }
                    }
                }
            }
        }
    }
}

fn check(layout: &Layout, n: u16) -> Result<(), ErrorCode> {
    block::object_run(layout, Area::TimerBit, n, 1).map(drop)
}

/// Executes `TON`/`TONR`/`TOF Tn, PT` (spec §5.2) on the image: [`Timer::step`] with the scan's
/// `d100`. `input` is `S0`; `gate` the gate it runs under. Errors only for a timer the profile
/// lacks.
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    n: u16,
    kind: TimerKind,
    input: bool,
    gate: Gate,
    preset: i16,
) -> Result<(), ErrorCode> {
    check(layout, n)?;
    let mut t = Timer::load(img, layout, n);
    let d100 = mem::sched_u32(img, layout, Sched::D100);
    t.step(kind, input, gate, preset, d100);
    t.store(img, layout, n);
    Ok(())
}

/// Clock refresh of a 1-ms or 10-ms timer at scan start (spec §5.2 `refresh`), using the kind
/// and resolution stored at cold start. 100-ms and unused timers are left alone.
pub fn refresh(img: &mut [u8], layout: &Layout, n: u16) {
    if check(layout, n).is_err() {
        return;
    }
    // Every scan visits every timer in use, and most are 100-ms ones: decide on the resolution
    // byte alone before decoding the whole timer.
    let d = match mem::get_u8(img, layout.timer_state(n) + TimerState::RES) {
        1 => mem::sched_u32(img, layout, Sched::D1),
        10 => mem::sched_u32(img, layout, Sched::D10),
        _ => return,
    };
    let mut t = Timer::load(img, layout, n);
    let kind = mem::get_u8(img, layout.timer_state(n) + TimerState::KIND);
    if kind == TimerKind::Off.code() {
        if t.tof == TofPhase::Timing {
            t.cv = sat_add(t.cv, d);
            if t.cv >= t.pt_cache {
                t.cv = t.pt_cache;
                t.bit = false;
                t.tof = TofPhase::Done;
            }
        }
    } else if (kind == TimerKind::On.code() || kind == TimerKind::Retentive.code()) && t.run {
        t.cv = sat_add(t.cv, d);
        t.bit = t.cv >= t.pt_cache;
    }
    t.store(img, layout, n);
}

/// `R Tn, N`: full reset of `count` timers from `first`: CV 0, bit 0, timing stopped, TOF idle
/// (spec §5.2). Past the last timer: 0x0091, nothing reset (spec M11); `count = 0` is a no-op
/// (M12).
pub fn reset_range(
    img: &mut [u8],
    layout: &Layout,
    first: u16,
    count: u32,
) -> Result<(), ErrorCode> {
    for n in block::object_run(layout, Area::TimerBit, first, count)? {
        let mut t = Timer::load(img, layout, n);
        t.cv = 0;
        t.bit = false;
        t.run = false;
        t.tof = TofPhase::Idle;
        t.store(img, layout, n);
    }
    Ok(())
}

#[cfg(test)]
#[path = "timer_tests.rs"]
mod tests;
