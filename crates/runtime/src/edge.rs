//! Edge detectors `EU`/`ED` (spec §5.1) and the first-scan edge rule shared with counters.
//!
//! Spec TC7 suppresses every edge in the first scan (EU, ED and counter inputs) and names a
//! config switch for it; [`FIRST_SCAN_EDGES`] is that switch, and [`suppressed`] is the one
//! place that reads it.

use crate::mem;
use stljit_core::layout::{Layout, Sched};

/// What the first scan does with edges (spec TC7).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FirstScanEdges {
    /// Only record inputs in the first scan; report no edge (the spec's rule).
    Suppress,
    /// Detect edges against the cold-start memory like in any other scan.
    Detect,
}

/// The rule in force.
pub const FIRST_SCAN_EDGES: FirstScanEdges = FirstScanEdges::Suppress;

/// Whether edges must be suppressed right now (first scan under [`FirstScanEdges::Suppress`]).
#[inline]
pub fn edges_suppressed(img: &[u8], layout: &Layout) -> bool {
    suppressed(mem::sched_u8(img, layout, Sched::FIRST_SCAN))
}

/// [`edges_suppressed`] given the scan's first-scan flag byte ([`Sched::FIRST_SCAN`]).
#[inline]
pub fn suppressed(first_scan: u8) -> bool {
    FIRST_SCAN_EDGES == FirstScanEdges::Suppress && first_scan != 0
}

/// Executes `EU` (`falling = false`) or `ED` on edge slot `slot` with `v = input AND gate`;
/// returns the new `S0`. A slot outside the edge block yields 0 and records nothing (the front end
/// never produces one).
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    slot: u16,
    input: bool,
    gate: bool,
    falling: bool,
) -> bool {
    if slot >= layout.profile.profile().max_edges {
        return false;
    }
    let at = layout.edges + u32::from(slot);
    let v = input && gate;
    let mem_v = mem::get_u8(img, at) != 0;
    let out = if falling { !v && mem_v } else { v && !mem_v } && !edges_suppressed(img, layout);
    mem::set_u8(img, at, u8::from(v));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::Rig;

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
                got.0 = execute(img, l, 0, a == 1, true, false);
                got.1 = execute(img, l, 1, b == 1, true, true);
            });
            assert_eq!(got, (eu, ed), "scan {k}");
        }
    }

    #[test]
    fn gate_closed_reads_as_zero() {
        let mut rig = Rig::new(10);
        rig.scan(|img, l| {
            execute(img, l, 3, true, true, true);
        });
        let mut got = false;
        rig.scan(|img, l| got = execute(img, l, 3, true, false, true));
        assert!(
            got,
            "closed SCR gate: input seen as 0 → falling edge (§3.6)"
        );
    }

    #[test]
    fn bad_slot_is_harmless() {
        let mut rig = Rig::new(10);
        let (img, l) = rig.img.split_mut();
        let before = img.to_vec();
        assert!(!execute(img, l, 256, true, true, false));
        assert_eq!(img, &before[..]);
    }
}
