//! Timers (spec §5.2), as functions on the image bytes.
//!
//! A timer's visible state is its current value (area `TimerValue`, big-endian `i16` at `2n`) and
//! its bit (area `TimerBit`, byte `n`); the private state ([`TimerState`]) holds `run`, the TOF
//! phase, the kind and resolution written at cold start, and the preset seen at the last
//! execution (used by the clock refresh of 1-ms and 10-ms timers at scan start).

use crate::mem;
use stljit_core::ir::TimerKind;
use stljit_core::layout::{Layout, Sched, TimerState};
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
#[inline]
fn sat_add(cv: i16, d: u32) -> i16 {
    (i64::from(cv) + i64::from(d)).min(i64::from(i16::MAX)) as i16
}

/// The mutable fields of one timer, loaded from and stored to the image.
struct Timer {
    cv: i16,
    bit: bool,
    run: bool,
    tof: TofPhase,
    pt_cache: i16,
    res: u8,
}

impl Timer {
    fn load(img: &[u8], layout: &Layout, n: u16) -> Timer {
        let st = layout.timer_state(n);
        Timer {
            cv: mem::get_i16_be(img, layout.base(Area::TimerValue) + 2 * u32::from(n)),
            bit: mem::get_u8(img, layout.base(Area::TimerBit) + u32::from(n)) & 1 != 0,
            run: mem::get_u8(img, st + TimerState::RUN) != 0,
            tof: TofPhase::from_u8(mem::get_u8(img, st + TimerState::TOF)),
            pt_cache: mem::get_i16_ne(img, st + TimerState::PT_CACHE),
            res: mem::get_u8(img, st + TimerState::RES),
        }
    }

    fn store(&self, img: &mut [u8], layout: &Layout, n: u16) {
        let st = layout.timer_state(n);
        mem::set_i16_be(
            img,
            layout.base(Area::TimerValue) + 2 * u32::from(n),
            self.cv,
        );
        mem::set_u8(
            img,
            layout.base(Area::TimerBit) + u32::from(n),
            u8::from(self.bit),
        );
        mem::set_u8(img, st + TimerState::RUN, u8::from(self.run));
        mem::set_u8(img, st + TimerState::TOF, self.tof as u8);
        mem::set_i16_ne(img, st + TimerState::PT_CACHE, self.pt_cache);
    }
}

fn check(layout: &Layout, n: u16) -> Result<(), ErrorCode> {
    if u32::from(n) < layout.area_size(Area::TimerBit) {
        Ok(())
    } else {
        Err(ErrorCode::OperandRange)
    }
}

/// Executes `TON`/`TONR`/`TOF Tn, PT` (spec §5.2). `input` is `S0`; `gate` is the SCR enable, so
/// `IN = input AND gate`, and a TOF with a closed gate is forced idle (inactive SCR rule).
/// 100-ms timers credit the scan's `d100` here. Errors only for a timer the profile lacks.
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    n: u16,
    kind: TimerKind,
    input: bool,
    gate: bool,
    preset: i16,
) -> Result<(), ErrorCode> {
    check(layout, n)?;
    let mut t = Timer::load(img, layout, n);
    let d100 = if t.res == 100 {
        mem::sched_u32(img, layout, Sched::D100)
    } else {
        0
    };
    let on = input && gate;
    match kind {
        TimerKind::On | TimerKind::Retentive => {
            if on {
                if !t.run {
                    t.run = true;
                    if kind == TimerKind::On {
                        t.cv = 0; // TON starts from 0; TONR resumes from the held value
                    }
                } else {
                    t.cv = sat_add(t.cv, d100);
                }
                t.pt_cache = preset;
                t.bit = t.cv >= preset;
            } else {
                t.run = false;
                if kind == TimerKind::On {
                    t.cv = 0;
                    t.bit = false;
                }
            }
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
    t.store(img, layout, n);
    Ok(())
}

/// Clock refresh of a 1-ms or 10-ms timer at scan start (spec §5.2 `refresh`), using the kind
/// and resolution stored at cold start. 100-ms and unused timers are left alone.
pub fn refresh(img: &mut [u8], layout: &Layout, n: u16) {
    if check(layout, n).is_err() {
        return;
    }
    let mut t = Timer::load(img, layout, n);
    let d = match t.res {
        1 => mem::sched_u32(img, layout, Sched::D1),
        10 => mem::sched_u32(img, layout, Sched::D10),
        _ => return,
    };
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

/// Full reset of one timer (`R Tn`): CV 0, bit 0, timing stopped, TOF idle (spec §5.2).
pub fn reset(img: &mut [u8], layout: &Layout, n: u16) -> Result<(), ErrorCode> {
    reset_range(img, layout, n, 1)
}

/// `R Tn, N`: resets `count` timers from `first`. Past the last timer: 0x0091, nothing reset
/// (spec M11); `count = 0` is a no-op (M12).
pub fn reset_range(
    img: &mut [u8],
    layout: &Layout,
    first: u16,
    count: u32,
) -> Result<(), ErrorCode> {
    if u32::from(first) + count > layout.area_size(Area::TimerBit) {
        return Err(ErrorCode::OperandRange);
    }
    for n in u32::from(first)..u32::from(first) + count {
        let n = n as u16;
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
