//! The Omron timers (spec §2.12, §3.3, §1.9): the TIM family (TIM/TIMX, TIMH/TIMHX,
//! TMHH/TMHHX) counts down from the set value, TTIM/TTIMX accumulates up to it, both on the
//! virtual clock.
//!
//! [`OmronTimer`] is one timer's state: the PV word and Completion Flag the program sees and
//! the hidden state of §2.12 (`running`, the time of the last execution, the milliseconds not
//! yet converted into PV units). [`OmronTimer::step`] is one execution; it returns the
//! condition flags it writes (only ER). A timer is updated only when it executes, and the time
//! credited is `t − last`, so a running timer skipped by a jump catches up at its next
//! execution (§2.8's `catch_up` policy) without a rule of its own.
//!
//! Rules fixed here where the spec leaves room:
//! * TTIM in an active interlock (§2.7, U4: "PV held"): PV, flag and the unconverted
//!   milliseconds are kept and `running` is cleared, so the interlocked time is not credited;
//!   its next execution with the input ON restarts from `t` like an input that was OFF.
//! * TTIM with a non-BCD SV (BCD kinds): ER ON and nothing changes at all (§1.9: "the
//!   instruction does nothing"), reset included. A PV already above the SV (a program wrote it)
//!   is kept, never lowered; the flag is `PV ≥ SV`. While the input is OFF PV and flag are held.
//! * A closed gate under the S7 SCR policy (never the case for an Omron program) sees its
//!   inputs OFF, as S7's rule says.

use super::bcd::Format;
use super::flags::FlagWrites;
use crate::rules::{Gate, GatePolicy};
use stljit_core::ir::OmronTimerKind;

/// One Omron timer's visible and hidden state. `Default` is the cold-start memory (all zero):
/// what a never-executed timer shows. The `PV = SV` of an idle timer ([`OmronTimer::idle`])
/// appears at its first execution with EC OFF.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct OmronTimer {
    /// The present value as stored (BCD or binary, per the kind).
    pub pv: u16,
    /// The Completion Flag.
    pub flag: bool,
    /// TIM family: timing (started and not reset); TTIM: the input was ON at the last
    /// execution, so `last_ms` is where the next credit starts.
    pub running: bool,
    /// Virtual time (ms) of the last execution that credited time or started the timer.
    pub last_ms: u64,
    /// Milliseconds not yet converted into PV units; every execution that credits time leaves
    /// it below the unit (at most 99, so it fits a byte).
    pub rem_ms: u32,
}

impl OmronTimer {
    /// The state after a reset of a TIM-family timer: `PV = SV`, flag OFF, not running.
    pub fn idle(sv: u16) -> OmronTimer {
        OmronTimer {
            pv: sv,
            ..OmronTimer::default()
        }
    }

    /// One execution of timer instruction `kind` at virtual time `t_ms` under `gate`. `ec` is
    /// the execution condition (TTIM: the timer input), `reset` TTIM's reset input (unused by
    /// the TIM family), `sv` the set value word as read. Returns the condition flags written:
    /// ER ON on invalid BCD data, else ER OFF; nothing under an active interlock.
    pub fn step(
        &mut self,
        kind: OmronTimerKind,
        ec: bool,
        reset: bool,
        sv: u16,
        t_ms: u64,
        gate: Gate,
    ) -> FlagWrites {
        let format = Format::of(kind.bcd());
        let (ec, reset) = match gate {
            Gate::Open => (ec, reset),
            Gate::Closed(GatePolicy::S7Scr) => (false, false),
            Gate::Closed(GatePolicy::OmronInterlock) => {
                self.interlocked(kind, format, sv);
                return FlagWrites::NONE;
            }
        };
        if kind.totalizing() {
            self.totalize(format, ec, reset, sv, t_ms)
        } else {
            let unit = u64::from(kind.unit().millis());
            self.count_down(format, unit, ec, sv, t_ms)
        }
    }

    /// §2.7/§2.12: an active interlock resets a TIM-family timer (PV := SV, flag OFF; a non-BCD
    /// SV keeps both) and holds a TTIM; no condition flag changes.
    fn interlocked(&mut self, kind: OmronTimerKind, format: Format, sv: u16) {
        if !kind.totalizing() && format.decode(sv).is_some() {
            self.pv = sv;
            self.flag = false;
        }
        self.running = false;
    }

    /// The TIM family, §2.12 literally.
    fn count_down(&mut self, format: Format, unit: u64, ec: bool, sv: u16, t: u64) -> FlagWrites {
        if !ec {
            // Reset. A non-BCD SV: ER, PV and flag kept.
            self.running = false;
            if format.decode(sv).is_none() {
                return FlagWrites::ERROR;
            }
            self.pv = sv;
            self.flag = false;
            return FlagWrites::OK;
        }
        if !self.running {
            // Start: a non-BCD SV changes nothing.
            let Some(value) = format.decode(sv) else {
                return FlagWrites::ERROR;
            };
            self.pv = sv;
            self.rem_ms = 0;
            self.last_ms = t;
            self.running = true;
            self.flag = value == 0;
            return FlagWrites::OK;
        }
        // Running: the PV is read back, so a program's write is honoured; a non-BCD one is an
        // error that changes nothing (rem and last kept).
        let Some(pv) = format.decode(self.pv) else {
            return FlagWrites::ERROR;
        };
        let ticks = self.credit(t, unit);
        let pv = u64::from(pv).saturating_sub(ticks) as u16; // at most the old PV
        self.pv = format.encode(pv);
        self.flag = pv == 0;
        FlagWrites::OK
    }

    /// TTIM/TTIMX (unit 100 ms): the PV grows by the elapsed ticks while the input is ON,
    /// saturating at SV; reset wins.
    fn totalize(
        &mut self,
        format: Format,
        input: bool,
        reset: bool,
        sv: u16,
        t: u64,
    ) -> FlagWrites {
        const UNIT: u64 = 100;
        let Some(sv) = format.decode(sv) else {
            return FlagWrites::ERROR;
        };
        if reset {
            self.pv = format.encode(0);
            self.flag = false;
            self.rem_ms = 0;
            self.running = false;
            return FlagWrites::OK;
        }
        if !input {
            self.running = false;
            return FlagWrites::OK;
        }
        let Some(pv) = format.decode(self.pv) else {
            return FlagWrites::ERROR;
        };
        let pv = if self.running {
            let grown = u64::from(pv).saturating_add(self.credit(t, UNIT));
            grown.min(u64::from(sv)).max(u64::from(pv)) as u16 // between PV and max(PV, SV)
        } else {
            // The input came back ON: time counts from now.
            self.last_ms = t;
            self.running = true;
            pv
        };
        self.pv = format.encode(pv);
        self.flag = pv >= sv;
        FlagWrites::OK
    }

    /// Credits the time since the last execution: `rem += t − last; last := t`, and returns
    /// the whole units taken out of `rem`. Time never runs backwards; if it did, nothing is
    /// credited.
    fn credit(&mut self, t: u64, unit: u64) -> u64 {
        let total = u64::from(self.rem_ms).saturating_add(t.saturating_sub(self.last_ms));
        self.last_ms = t;
        // One arm per timer unit, so each divides by a constant (a multiplication) instead of
        // a hardware division on every running timer's execution.
        let (ticks, rem) = match unit {
            1 => (total, 0),
            10 => (total / 10, total % 10),
            100 => (total / 100, total % 100),
            _ => (total / unit.max(1), total % unit.max(1)),
        };
        self.rem_ms = rem as u32; // below the unit
        ticks
    }
}

#[cfg(test)]
#[path = "timer_tests.rs"]
mod tests;
