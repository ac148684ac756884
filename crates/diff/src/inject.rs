//! A fault injector: wraps an [`Engine`] and breaks it in one precise way at one scan, so tests can
//! check that the oracle reports exactly that scan and address. The oracle's value rests on never
//! missing a difference; these faults are the smallest differences there are.

use stljit_core::ScanStatus;
use stljit_runtime::{Engine, Image};

/// One fault.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    /// After scan `scan`, flip bit `bit` of image byte `offset`.
    FlipBit {
        /// The scan (0-based).
        scan: u64,
        /// Image offset.
        offset: u32,
        /// Bit 0..=7.
        bit: u8,
    },
    /// After scan `scan`, overwrite image byte `offset`.
    SetByte {
        /// The scan.
        scan: u64,
        /// Image offset.
        offset: u32,
        /// The new value.
        value: u8,
    },
    /// Do not run scan `scan` at all (report `Ok` without touching the image).
    SkipScan {
        /// The scan.
        scan: u64,
    },
}

/// An engine with a fault.
pub struct Faulty<E> {
    inner: E,
    fault: Fault,
    scans: u64,
}

impl<E: Engine> Faulty<E> {
    /// Wraps `inner`.
    pub fn new(inner: E, fault: Fault) -> Faulty<E> {
        Faulty {
            inner,
            fault,
            scans: 0,
        }
    }
}

impl<E: Engine> Engine for Faulty<E> {
    fn name(&self) -> &'static str {
        "faulty"
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        let k = self.scans;
        self.scans += 1;
        if self.fault == (Fault::SkipScan { scan: k }) {
            return ScanStatus::Ok;
        }
        let status = self.inner.scan(image, t_ms);
        let bytes = image.bytes_mut();
        match self.fault {
            Fault::FlipBit { scan, offset, bit } if scan == k => {
                if let Some(b) = bytes.get_mut(offset as usize) {
                    *b ^= 1 << (bit & 7);
                }
            }
            Fault::SetByte {
                scan,
                offset,
                value,
            } if scan == k => {
                if let Some(b) = bytes.get_mut(offset as usize) {
                    *b = value;
                }
            }
            _ => {}
        }
        status
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{ScanInput, Stimulus};
    use crate::locate::Place;
    use crate::oracle::{Finding, RunOptions, run_pair};
    use stljit_core::ir::{Pou, PouKind, Program};
    use stljit_core::layout::Sched;
    use stljit_core::{Area, ProfileId};
    use stljit_runtime::{mem, scan};

    /// A stand-in engine: copies IB0 to QB0 and counts scans in VB0, around the real scan cycle.
    struct Copier;

    impl Engine for Copier {
        fn name(&self) -> &'static str {
            "copier"
        }

        fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
            let plan = scan::ScanPlan::every_timer(image.layout());
            let (b, l) = image.split_mut();
            scan::run(
                b,
                l,
                &plan,
                t_ms,
                &mut stljit_runtime::interrupt::NoIsr,
                |b, l| {
                    let i = mem::get_u8(b, l.base(Area::I));
                    mem::set_u8(b, l.base(Area::Q), i);
                    let v = mem::get_u8(b, l.base(Area::V));
                    mem::set_u8(b, l.base(Area::V), v.wrapping_add(1));
                    ScanStatus::Ok
                },
            )
        }
    }

    fn program() -> Program {
        Program {
            profile: ProfileId::A5,
            pous: vec![Pou {
                name: "MAIN".into(),
                kind: PouKind::Main,
                ops: vec![],
                locs: vec![],
                labels: vec![],
            }],
            timers: vec![],
            counters: vec![],
            edges: vec![],
            logic_stack_depth: 9,
            files: vec![],
            data: Vec::new(),
        }
    }

    fn stimulus(n: u64) -> Stimulus {
        Stimulus {
            scans: (0..n)
                .map(|k| ScanInput {
                    t_ms: 10 * k,
                    inputs: vec![k as u8; 16],
                    ai: vec![0; 16],
                    writes: vec![],
                    hsc: vec![],
                    rx: vec![],
                })
                .collect(),
        }
    }

    fn run(fault: Fault) -> Finding {
        let mut faulty = Faulty::new(Copier, fault);
        let r = run_pair(
            &program(),
            &stimulus(20),
            &mut Copier,
            &mut faulty,
            &RunOptions::default(),
        );
        r.expect_err("the fault must be found")
    }

    #[test]
    fn clean_engines_agree() {
        let r = run_pair(
            &program(),
            &stimulus(20),
            &mut Copier,
            &mut Copier,
            &RunOptions::default(),
        );
        assert_eq!(r.map(|s| s.scans), Ok(20));
    }

    #[test]
    fn flipped_bit_is_reported_at_its_scan_and_address() {
        let layout = stljit_core::Layout::of(ProfileId::A5);
        for (scan, area, offset, bit) in [
            (7, Area::V, 10, 3),
            (0, Area::M, 31, 7),
            (19, Area::AC, 5, 0),
        ] {
            let at = layout.addr(area, offset, 0);
            let Finding::Divergence(d) = run(Fault::FlipBit {
                scan,
                offset: at,
                bit,
            }) else {
                panic!("expected a divergence");
            };
            assert_eq!(d.scan, scan as u32);
            assert_eq!(d.total, 1);
            assert_eq!(d.diffs[0].offset, at);
            assert!(
                matches!(d.diffs[0].place, Place::Area { area: a, offset: o, .. } if a == area && o == offset)
            );
            assert_eq!(d.diffs[0].bytes[0] ^ d.diffs[0].bytes[1], 1 << bit);
        }
    }

    #[test]
    fn set_byte_in_private_state_is_named() {
        let layout = stljit_core::Layout::of(ProfileId::A5);
        let at = layout.sched(Sched::LOOP_COUNT);
        let Finding::Divergence(d) = run(Fault::SetByte {
            scan: 4,
            offset: at,
            value: 9,
        }) else {
            panic!("expected a divergence");
        };
        assert_eq!(d.scan, 4);
        assert_eq!(d.diffs[0].offset, at);
        assert_eq!(d.diffs[0].field, Some([0, 9]));
        assert!(d.to_string().contains("Sched.LOOP_COUNT"), "{d}");
    }

    #[test]
    fn skipped_scan_is_reported_at_that_scan() {
        let layout = stljit_core::Layout::of(ProfileId::A5);
        let Finding::Divergence(d) = run(Fault::SkipScan { scan: 5 }) else {
            panic!("expected a divergence");
        };
        assert_eq!(d.scan, 5);
        // The first difference is the earliest byte the skipped scan would have written: IB0
        // keeps the previous input (4) while the clean engine latched this scan's (5).
        assert_eq!(d.diffs[0].offset, layout.base(Area::I));
        assert_eq!(d.diffs[0].bytes, [5, 4]);
        // With max_diffs = 8 the list stops early, but the scan counter is among the differences.
        assert!(d.total > d.diffs.len());
    }
}
