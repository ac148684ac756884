//! The semantic switches and the gate policy both engines read, stated once.
//!
//! * [`Rules`]: the rules the spec leaves as a switch. [`Rules::IN_FORCE`] is the one place
//!   that says which rule stljit implements; an engine built with other [`Rules`] (tests only:
//!   `Interpreter::with_rules`, `JitProgram::compile_with_rules`) follows them everywhere,
//!   in the runtime's functions and in the JIT's inlined code alike.
//! * [`Gate`] and [`GatePolicy`]: what a closed gate (an inactive S7 SCR segment, an active
//!   Omron interlock) does to timers, counters and edge detectors. Coils and boxes only see
//!   power flow `S0 AND gate`, which is the same under both policies (a coil writes 0, a box
//!   does not run); the stateful instructions differ, and their rules read the policy here.

use crate::rule_ops::{Native, RuleOps};
use stljit_core::Family;

/// What the first scan does with edges (spec TC7).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FirstScanEdges {
    /// Only record inputs in the first scan; report no edge (the spec's rule).
    Suppress,
    /// Detect edges against the cold-start memory like in any other scan.
    Detect,
}

/// The semantic switches of the spec, as one value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rules {
    /// EU, ED and counter inputs in the first scan (spec §5.1, TC7).
    pub first_scan_edges: FirstScanEdges,
}

impl Rules {
    /// The rules stljit implements for S7 programs.
    pub const IN_FORCE: Rules = Rules {
        first_scan_edges: FirstScanEdges::Suppress,
    };

    /// The rules in force for a program of `family`: [`Rules::IN_FORCE`] for S7; Omron edge
    /// memories start at their instance's initial value instead of sitting out the first scan
    /// ([`Family::first_scan_suppresses_edges`]).
    pub fn in_force(family: Family) -> Rules {
        Rules {
            first_scan_edges: if family.first_scan_suppresses_edges() {
                FirstScanEdges::Suppress
            } else {
                FirstScanEdges::Detect
            },
        }
    }

    /// Whether edges are suppressed in a scan whose first-scan flag byte
    /// ([`stljit_core::layout::Sched::FIRST_SCAN`]) is `first_scan`.
    #[inline]
    pub fn edges_suppressed(self, first_scan: u8) -> bool {
        self.edges_suppressed_in(&mut Native, i64::from(first_scan)) != 0
    }

    /// [`Rules::edges_suppressed`] as a [`RuleOps`] value (a boolean), for rules written over
    /// [`RuleOps`]: the JIT emits it inline.
    #[inline]
    pub fn edges_suppressed_in<O: RuleOps>(self, o: &mut O, first_scan: O::V) -> O::V {
        if self.first_scan_suppresses() {
            o.ne0(first_scan)
        } else {
            o.k(0)
        }
    }

    /// Whether the first-scan flag suppresses edges at all (code generators test the flag
    /// only then).
    #[inline]
    pub fn first_scan_suppresses(self) -> bool {
        self.first_scan_edges == FirstScanEdges::Suppress
    }
}

impl Default for Rules {
    fn default() -> Rules {
        Rules::IN_FORCE
    }
}

pub use stljit_core::GatePolicy;

/// The policy of the S7 SCR gate (`Sched::SCR_ENABLE`); an Omron program's gate (the same
/// byte, set by IL/ILC) follows [`Family::gate_policy`] instead.
pub const SCR_POLICY: GatePolicy = GatePolicy::S7Scr;

/// The gate a timer, counter or edge detector executes under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gate {
    /// Power flows: the instruction sees its real inputs.
    Open,
    /// The gate is closed; the policy says what that does.
    Closed(GatePolicy),
}

impl Gate {
    /// The gate of the SCR enable (`Sched::SCR_ENABLE`): open, or closed under
    /// [`SCR_POLICY`].
    #[inline]
    pub fn scr(open: bool) -> Gate {
        Gate::with(open, SCR_POLICY)
    }

    /// The gate `open`, or closed under `policy`.
    #[inline]
    pub fn with(open: bool, policy: GatePolicy) -> Gate {
        if open {
            Gate::Open
        } else {
            Gate::Closed(policy)
        }
    }

    /// Whether power flows.
    #[inline]
    pub fn is_open(self) -> bool {
        self == Gate::Open
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_scan_rule_is_one_switch() {
        assert!(Rules::IN_FORCE.edges_suppressed(1));
        assert!(!Rules::IN_FORCE.edges_suppressed(0));
        let detect = Rules {
            first_scan_edges: FirstScanEdges::Detect,
        };
        assert!(!detect.edges_suppressed(1));
        assert_eq!(Rules::default(), Rules::IN_FORCE);
    }

    #[test]
    fn gates() {
        assert_eq!(Gate::scr(true), Gate::Open);
        assert_eq!(Gate::scr(false), Gate::Closed(GatePolicy::S7Scr));
        assert_eq!(
            Gate::with(false, GatePolicy::OmronInterlock),
            Gate::Closed(GatePolicy::OmronInterlock)
        );
        assert!(!Gate::scr(false).is_open());
    }

    #[test]
    fn omron_interlock_resets_tim_and_freezes_the_rest() {
        use crate::counter::Counter;
        use crate::timer::{Timer, TofPhase};
        use stljit_core::ir::{CounterKind, TimerKind};
        let il = Gate::Closed(GatePolicy::OmronInterlock);
        let running = Timer {
            cv: 7,
            bit: true,
            run: true,
            tof: TofPhase::Timing as u8,
            pt_cache: 5,
            res: 100,
        };
        for kind in TimerKind::ALL {
            let mut t = running;
            t.step(*kind, true, il, 5, 3);
            let want = match kind {
                TimerKind::On => Timer {
                    cv: 0,
                    bit: false,
                    run: false,
                    ..running
                },
                TimerKind::Retentive | TimerKind::Off => running,
            };
            assert_eq!(t, want, "{kind:?}");
            // S7 SCR, for contrast: TONR holds its value but stops, TOF is forced idle.
            let mut s7 = running;
            s7.step(*kind, true, Gate::scr(false), 5, 3);
            assert_ne!(s7, running, "{kind:?}: the S7 rule changes state");
        }
        let c0 = Counter {
            cv: 3,
            prev_up: 1,
            prev_down: 1,
        };
        for kind in CounterKind::ALL {
            let mut c = c0;
            assert_eq!(
                c.step(*kind, 0b111, il, 2, false),
                None,
                "{kind:?}: bit kept"
            );
            assert_eq!(c, c0, "{kind:?}: value and edge memories frozen");
            let mut s7 = c0;
            assert!(s7.step(*kind, 0b111, Gate::scr(false), 2, false).is_some());
            assert_ne!(s7, c0, "{kind:?}: S7 updates edge memories with 0");
        }
    }
}
