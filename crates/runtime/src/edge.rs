//! Edge detectors `EU`/`ED` (spec §5.1). The first-scan rule they share with counters
//! (spec TC7) is [`Rules::edges_suppressed`]; what a closed gate does is [`Gate`]'s policy.

use crate::mem;
use crate::rules::{Gate, GatePolicy, Rules};
use stljit_core::layout::{Layout, Sched};

/// Executes `EU` (`falling = false`) or `ED` on edge slot `slot` with S0 = `input` under
/// `gate`; returns the new `S0`. Open gate, or closed under [`GatePolicy::S7Scr`]: `v = input
/// AND gate` is compared with the memory, which takes `v`; no edge while `rules` suppress the
/// first scan. Closed under [`GatePolicy::OmronInterlock`]: not executed, the memory is frozen
/// and S0 is 0. A slot outside the edge block yields 0 and records nothing (the front end never
/// produces one).
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    slot: u16,
    input: bool,
    gate: Gate,
    falling: bool,
    rules: Rules,
) -> bool {
    if slot >= layout.profile.profile().max_edges {
        return false;
    }
    let v = match gate {
        Gate::Open => input,
        Gate::Closed(GatePolicy::S7Scr) => false,
        Gate::Closed(GatePolicy::OmronInterlock) => return false,
    };
    let at = layout.edges + u32::from(slot);
    let mem_v = mem::get_u8(img, at) != 0;
    let quiet = rules.edges_suppressed(mem::sched_u8(img, layout, Sched::FIRST_SCAN));
    let out = if falling { !v && mem_v } else { v && !mem_v } && !quiet;
    mem::set_u8(img, at, u8::from(v));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::Rig;

    const R: Rules = Rules::IN_FORCE;

    #[test]
    fn t04_eu_ed_pulses_with_first_scan_rule() {
        // Spec §7 T04: (I0.0, I0.1) → (EU out, ED out) per scan.
        let rows = [
            (1, 0, false, false),
            (0, 0, false, false),
            (1, 0, true, false),
            (1, 1, false, false),
            (0, 1, false, false),
            (0, 0, false, true),
            (0, 0, false, false),
        ];
        let mut rig = Rig::new(10);
        for (k, (a, b, eu, ed)) in rows.into_iter().enumerate() {
            let mut got = (false, false);
            rig.scan(|img, l| {
                got.0 = execute(img, l, 0, a == 1, Gate::Open, false, R);
                got.1 = execute(img, l, 1, b == 1, Gate::Open, true, R);
            });
            assert_eq!(got, (eu, ed), "scan {k}");
        }
    }

    #[test]
    fn gate_closed_reads_as_zero() {
        let mut rig = Rig::new(10);
        rig.scan(|img, l| {
            execute(img, l, 3, true, Gate::Open, true, R);
        });
        let mut got = false;
        rig.scan(|img, l| got = execute(img, l, 3, true, Gate::scr(false), true, R));
        assert!(
            got,
            "closed SCR gate: input seen as 0 → falling edge (§3.6)"
        );
    }

    #[test]
    fn first_scan_rule_switch() {
        use crate::rules::FirstScanEdges;
        let detect = Rules {
            first_scan_edges: FirstScanEdges::Detect,
        };
        for (rules, want) in [(R, false), (detect, true)] {
            let mut rig = Rig::new(10);
            let mut got = None;
            rig.scan(|img, l| got = Some(execute(img, l, 0, true, Gate::Open, false, rules)));
            assert_eq!(got, Some(want), "{rules:?}");
        }
    }

    #[test]
    fn omron_interlock_freezes_the_memory() {
        let mut rig = Rig::new(10);
        let il = Gate::Closed(GatePolicy::OmronInterlock);
        rig.scan(|img, l| {
            execute(img, l, 2, true, Gate::Open, false, R);
        });
        let mut got = (true, true);
        rig.scan(|img, l| {
            got.0 = execute(img, l, 2, false, il, true, R);
        });
        // Back open with the input still on: the memory kept 1, so no rising edge.
        rig.scan(|img, l| got.1 = execute(img, l, 2, true, Gate::Open, false, R));
        assert_eq!(got, (false, false));
        // Under the S7 rule the closed gate had written 0: a rising edge now.
        rig.scan(|img, l| {
            execute(img, l, 2, true, Gate::scr(false), false, R);
        });
        let mut again = false;
        rig.scan(|img, l| again = execute(img, l, 2, true, Gate::Open, false, R));
        assert!(again);
    }

    #[test]
    fn bad_slot_is_harmless() {
        let mut rig = Rig::new(10);
        let (img, l) = rig.img.split_mut();
        let before = img.to_vec();
        assert!(!execute(img, l, 256, true, Gate::Open, false, R));
        assert_eq!(img, &before[..]);
    }
}
