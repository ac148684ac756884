//! The Omron counters (spec §3.3, §1.9): CNT/CNTX count down from the set value on each
//! rising edge of the count input, CNTR/CNTRX count a ring 0 … SV up and down.
//!
//! [`OmronCounter`] is one counter's state: the PV word and Completion Flag the program sees,
//! and the count inputs' edge memories. [`OmronCounter::step`] is one execution with every
//! detail §3.3 fixes by design: edge memories start OFF (U7) and are updated by every execution
//! outside an active interlock, also when the execution is an error or a reset; an active
//! interlock does not execute the counter at all (PV, flag and edge memories frozen, no flag
//! change, U17). A closed gate under the S7 SCR policy (never the case for an Omron program)
//! sees its inputs OFF, as S7's rule says.

use super::bcd::Format;
use super::flags::FlagWrites;
use crate::rules::{Gate, GatePolicy};
use stljit_core::ir::OmronCounterKind;

/// One Omron counter's state. `Default` is the cold-start memory (all zero).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct OmronCounter {
    /// The present value as stored (BCD or binary, per the kind).
    pub pv: u16,
    /// The Completion Flag.
    pub flag: bool,
    /// The count (CNT) or increment (CNTR) input at the last execution.
    pub prev_count: bool,
    /// CNTR's decrement input at the last execution (CNT leaves it alone).
    pub prev_dec: bool,
}

/// Index of the count (CNT) or increment (CNTR) input in [`OmronCounter::step`]'s inputs.
pub const COUNT: usize = 0;
/// Index of CNTR's decrement input (unused by CNT).
pub const DEC: usize = 1;
/// Index of the reset input.
pub const RESET: usize = 2;

impl OmronCounter {
    /// One execution of counter instruction `kind` under `gate`; `inputs` are indexed by
    /// [`COUNT`], [`DEC`], [`RESET`] and `sv` is the set value word as read. Returns the
    /// condition flags written: ER ON on invalid BCD data, else ER OFF; nothing under an active
    /// interlock.
    #[inline(always)]
    pub fn step(
        &mut self,
        kind: OmronCounterKind,
        inputs: [bool; 3],
        sv: u16,
        gate: Gate,
    ) -> FlagWrites {
        let [count, dec, reset] = match gate {
            Gate::Open => inputs,
            Gate::Closed(GatePolicy::S7Scr) => [false; 3],
            Gate::Closed(GatePolicy::OmronInterlock) => return FlagWrites::NONE,
        };
        let ring = kind.ring();
        let up = count && !self.prev_count;
        let down = ring && dec && !self.prev_dec;
        self.prev_count = count;
        if ring {
            self.prev_dec = dec;
        }
        let format = Format::of(kind.bcd());
        // A non-BCD SV: the execution does nothing, neither reset nor count.
        let Some(set) = format.decode(sv) else {
            return FlagWrites::ERROR;
        };
        if reset {
            // A count edge while reset is ON is not counted.
            self.pv = if ring { format.encode(0) } else { sv };
            self.flag = false;
            return FlagWrites::OK;
        }
        if !up && !down {
            return FlagWrites::OK;
        }
        // A count meets a PV the program made non-BCD: the count is lost, PV and flag kept.
        let Some(pv) = format.decode(self.pv) else {
            return FlagWrites::ERROR;
        };
        if ring {
            self.ring_count(format, up, down, pv, set, sv);
        } else {
            // Down to 0, where the flag turns ON and stays; a count at 0 (also with the flag
            // still OFF, on a fresh counter) keeps 0 with the flag ON.
            let pv = pv.saturating_sub(1);
            self.pv = format.encode(pv);
            self.flag = pv == 0;
        }
        FlagWrites::OK
    }

    /// CNTR: increment at SV (or above it, after a program write) wraps to 0 and decrement at
    /// 0 wraps to SV, both with the flag ON; any other count clears the flag; both edges at
    /// once change nothing, flag included.
    fn ring_count(&mut self, format: Format, up: bool, down: bool, pv: u16, set: u16, sv: u16) {
        match (up, down) {
            (true, false) if pv >= set => (self.pv, self.flag) = (format.encode(0), true),
            (true, false) => (self.pv, self.flag) = (format.encode(pv + 1), false), // pv < set
            (false, true) if pv == 0 => (self.pv, self.flag) = (sv, true),
            (false, true) => (self.pv, self.flag) = (format.encode(pv - 1), false),
            _ => {}
        }
    }
}

#[cfg(test)]
#[path = "counter_tests.rs"]
mod tests;
