//! Unit tests of the simulation driver, with a toy engine built on the real scan cycle.

use super::*;
use crate::stimulus::TimeBase;
use crate::test_resolver::{resolve, watches};
use stljit_core::layout::{PortState, Sched};
use stljit_core::{Area, ProfileId};
use stljit_runtime::mem;
use stljit_runtime::scan;

/// Per scan: QB0 := IB0, VW0 += 1, VB2 := AIW0 low byte; I0.7 requests STOP, I0.6 is fatal
/// (Watchdog) before anything else happens.
struct Toy;

impl Engine for Toy {
    fn name(&self) -> &'static str {
        "toy"
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
                let ib0 = mem::get_u8(b, l.base(Area::I));
                if ib0 & 0x40 != 0 {
                    scan::record_fatal(b, l, FatalCode::Watchdog, 0, 0);
                    return ScanStatus::Fatal;
                }
                mem::set_u8(b, l.base(Area::Q), ib0);
                let vw0 = l.base(Area::V);
                let n = mem::get_be(b, vw0, stljit_core::Width::Word);
                mem::set_be(b, vw0, stljit_core::Width::Word, n + 1);
                let ai = mem::get_u8(b, l.base(Area::AI) + 1);
                mem::set_u8(b, vw0 + 2, ai);
                if ib0 & 0x80 != 0 {
                    mem::set_sched_u8(b, l, Sched::STOP_REQ, 1);
                }
                ScanStatus::Ok
            },
        )
    }
}

fn stim(text: &str) -> Stimulus {
    Stimulus::parse(text, ProfileId::A5.profile(), &resolve).unwrap()
}

/// Records (scan, t, QB0, VW0, VB2, status) per scan.
#[derive(Default)]
struct Rec(Vec<(u64, u64, u8, u32, u8, ScanStatus)>);

impl Observer for Rec {
    fn observe(&mut self, e: &ScanEvent<'_>) -> io::Result<()> {
        let b = e.image.bytes();
        let l = e.image.layout();
        let v = l.base(Area::V);
        self.0.push((
            e.scan,
            e.t_ms,
            b[l.base(Area::Q) as usize],
            mem::get_be(b, v, stljit_core::Width::Word),
            b[v as usize + 2],
            e.status,
        ));
        Ok(())
    }
}

#[test]
fn rows_apply_before_their_scan_and_hold() {
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
    let s = stim("scan,I0.0,IB1,AIW0\n1,1,,7\n3,0,,\n");
    let mut rec = Rec::default();
    let r = sim.run(Until::Scans(5), &s, &mut rec).unwrap();
    assert_eq!(r.outcome, Outcome::Completed);
    assert_eq!((r.scans, r.next_scan, r.t_ms), (5, 5, 40));
    let q: Vec<_> = rec.0.iter().map(|r| (r.0, r.1, r.2, r.3, r.4)).collect();
    assert_eq!(
        q,
        vec![
            (0, 0, 0, 1, 0),
            (1, 10, 1, 2, 7),
            (2, 20, 1, 3, 7),
            (3, 30, 0, 4, 7),
            (4, 40, 0, 5, 7)
        ]
    );
}

#[test]
fn millisecond_rows_and_duration() {
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
    // 15 ms → scan 2 (t = 20), the first starting at or after 15.
    let s = stim("t_ms,I0.1\n15,1\n");
    let mut rec = Rec::default();
    let r = sim.run(Until::Duration(35), &s, &mut rec).unwrap();
    assert_eq!(r.scans, 4, "scans at 0, 10, 20, 30 start within 35 ms");
    let q: Vec<u8> = rec.0.iter().map(|r| r.2).collect();
    assert_eq!(q, vec![0, 0, 2, 2]);
}

#[test]
fn continuing_run_catches_up_and_numbers_scans_on() {
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 100).unwrap();
    let empty = Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile());
    sim.run(Until::Scans(2), &empty, &mut ()).unwrap();
    let s = stim("scan,IB0\n0,3\n1,5\n9,1\n");
    let mut rec = Rec::default();
    let r = sim.run(Until::Scans(2), &s, &mut rec).unwrap();
    assert_eq!(r.next_scan, 4);
    let q: Vec<_> = rec.0.iter().map(|r| (r.0, r.1, r.2)).collect();
    assert_eq!(q, vec![(2, 200, 5), (3, 300, 5)]);
}

#[test]
fn stop_and_fatal_end_the_run() {
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
    let mut rec = Rec::default();
    let r = sim
        .run(Until::Scans(10), &stim("scan,I0.7\n2,1\n"), &mut rec)
        .unwrap();
    assert_eq!(r.outcome, Outcome::Stopped);
    assert_eq!(r.scans, 3);
    assert_eq!(rec.0[2].5, ScanStatus::Stopped);
    assert_eq!(
        rec.0[2].2, 0x80,
        "the STOP scan completes and writes outputs"
    );
    let again = sim
        .run(
            Until::Scans(10),
            &Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile()),
            &mut (),
        )
        .unwrap();
    assert_eq!((again.scans, again.outcome), (0, Outcome::Stopped));

    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
    let r = sim
        .run(Until::Scans(10), &stim("scan,I0.6\n1,1\n"), &mut ())
        .unwrap();
    assert_eq!(
        r.outcome,
        Outcome::Fatal {
            code: FatalCode::Watchdog as u16
        }
    );
    assert_eq!(r.outcome.fatal_code(), Some(FatalCode::Watchdog));
    assert_eq!(r.scans, 2);
    assert_eq!(sim.image().fatal(), FatalCode::Watchdog as u16);
}

#[test]
fn cancel_and_progress() {
    let flag = AtomicBool::new(false);
    let mut seen = Vec::new();
    let mut on_progress = |p: Progress| seen.push(p);
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10)
        .unwrap()
        .with_cancel(&flag)
        .with_progress(&mut on_progress);
    let empty = Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile());
    let mut obs = FnObserver(|e: &ScanEvent<'_>| {
        if e.scan == 2 {
            flag.store(true, Ordering::Relaxed);
        }
        Ok(())
    });
    let r = sim.run(Until::Scans(100), &empty, &mut obs).unwrap();
    assert_eq!((r.scans, r.outcome), (3, Outcome::Cancelled));
    drop(sim);
    assert_eq!(seen.len(), 3);
    assert_eq!(
        seen[2],
        Progress {
            done: 3,
            total: 100,
            t_ms: 20
        }
    );
}

#[test]
fn setup_and_observer_errors() {
    let mut toy = Toy;
    assert!(matches!(
        Simulation::new(&mut toy, Image::blank(ProfileId::A5), 0),
        Err(SimError::ZeroScanTime)
    ));
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
    let mut failing = FnObserver(|_: &ScanEvent<'_>| Err(io::Error::other("disk full")));
    let empty = Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile());
    let e = sim.run(Until::Scans(3), &empty, &mut failing).unwrap_err();
    assert_eq!(e.to_string(), "trace output failed: disk full");
    // A stimulus built for a bigger V area than the image has.
    let mut s = Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile());
    s.add_column("VW2499", &resolve).unwrap();
    s.push_row(0, vec![Some(1)]).unwrap();
    let e = sim.run(Until::Scans(1), &s, &mut ()).unwrap_err();
    assert!(matches!(e, SimError::StimulusAddress { line: 2, .. }));
}

/// After each scan (or stretch): HSC0's activity per interval and the length of port 0's
/// receive FIFO. The toy engine runs no event phase, so nothing drains the FIFO: its length is
/// every byte the driver ever queued.
#[derive(Default)]
struct Hardware {
    every_scan: bool,
    seen: Vec<(u64, i32, u16)>,
}

impl Observer for Hardware {
    fn observe(&mut self, e: &ScanEvent<'_>) -> io::Result<()> {
        let (b, l) = (e.image.bytes(), e.image.layout());
        let rate = stljit_runtime::hsc::rate(b, l, 0);
        let fifo = mem::get_u16_ne(b, l.port_state(0, PortState::FIFO_LEN));
        self.seen.push((e.scan, rate, fifo));
        Ok(())
    }

    fn needs_every_scan(&self) -> bool {
        self.every_scan
    }
}

/// s7-200-more §11.2: `hsc_steps` is written before a scan and held until written again; `rx`
/// bytes are queued once, before the row's scan (§10.4). Rows at scans 1 and 4: HSC0 = 10 then
/// -4; PORT0 gets 2 bytes at scan 1 and 3 at scan 4. So the rate is 0, 10, 10, 10, -4, -4 and
/// the FIFO 0, 2, 2, 2, 5, 5 whether the driver runs scan by scan or in stretches between rows.
#[test]
fn hsc_steps_hold_and_received_bytes_arrive_once() {
    let s = stim("scan,HSC0,PORT0\n1,10,16#4F4B\n4,-4,16#414243\n");
    for every_scan in [true, false] {
        let mut toy = Toy;
        let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
        let mut obs = Hardware {
            every_scan,
            ..Hardware::default()
        };
        sim.run(Until::Scans(6), &s, &mut obs).unwrap();
        let want = [
            (0, 0, 0),
            (1, 10, 2),
            (2, 10, 2),
            (3, 10, 2),
            (4, -4, 5),
            (5, -4, 5),
        ];
        if every_scan {
            assert_eq!(obs.seen, want);
        } else {
            // Stretches end before each row: scan 0, scans 1-3, scans 4-5.
            assert_eq!(obs.seen, vec![want[0], want[3], want[5]]);
        }
    }
}

/// A run continued at scan 3 applies the held steps of the past row (scan 1) but not its bytes,
/// which belonged to the interval before scan 1; the row at scan 4 delivers its own.
#[test]
fn a_continued_run_does_not_receive_past_bytes_again() {
    let s = stim("scan,HSC0,PORT0\n1,10,16#4F4B\n4,-4,16#414243\n");
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
    let empty = Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile());
    sim.run(Until::Scans(3), &empty, &mut ()).unwrap();
    let mut obs = Hardware {
        every_scan: true,
        ..Hardware::default()
    };
    sim.run(Until::Scans(2), &s, &mut obs).unwrap();
    assert_eq!(obs.seen, vec![(3, 10, 0), (4, -4, 3)]);
}

/// A stimulus checked for the s7-200 (HSC0..HSC5) run on an a5 image (HSC0, HSC1 only).
#[test]
fn a_counter_the_image_lacks_is_an_error() {
    let mut s = Stimulus::empty(TimeBase::Scan, ProfileId::S7_200.profile());
    s.add_column("HSC4", &resolve).unwrap();
    s.push_row(0, vec![Some(1)]).unwrap();
    let mut toy = Toy;
    let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
    let e = sim.run(Until::Scans(1), &s, &mut ()).unwrap_err();
    assert_eq!(
        e.to_string(),
        "stimulus line 2: `HSC4`: the CPU has no such high-speed counter"
    );
}

/// A VCD trace through the driver's change-watching stretches writes the same bytes as when it
/// sees every scan, and is shown far fewer scans. The watches cover a byte the scans change
/// (QB0 := IB0), one a stimulus row writes like an HMI (M0.1: the stretch after the row must
/// end at its first scan, where the trace stamps the change), one that follows an analog input
/// (VB2), and one that changes every scan (VW0 in the second trace: every stretch is a scan).
#[test]
fn a_vcd_trace_in_change_watching_stretches_writes_what_it_writes_scan_by_scan() {
    use crate::trace_vcd::VcdTrace;
    /// The trace, hiding its `changes_of`: it then sees every scan.
    struct EveryScan<O>(O, u64);
    impl<O: Observer> Observer for EveryScan<O> {
        fn observe(&mut self, e: &ScanEvent<'_>) -> io::Result<()> {
            self.1 += 1;
            self.0.observe(e)
        }
    }
    /// Counts the scans the trace is shown, passing its `changes_of` on.
    struct Counted<O>(O, u64);
    impl<O: Observer> Observer for Counted<O> {
        fn observe(&mut self, e: &ScanEvent<'_>) -> io::Result<()> {
            self.1 += 1;
            self.0.observe(e)
        }
        fn changes_of(&self, layout: &Layout) -> Option<Vec<Range<usize>>> {
            self.0.changes_of(layout)
        }
    }
    let s = stim("scan,I0.0,M0.1,AIW0\n0,0,0,0\n5,1,,\n9,,1,\n12,0,,7\n20,,0,\n");
    for specs in [&["Q0.0", "M0.1", "VB2"][..], &["Q0.0", "VW0"][..]] {
        let trace = || VcdTrace::new(Vec::new(), watches(specs), "toy").unwrap();
        let run = |observer: &mut dyn Observer| {
            let mut toy = Toy;
            let mut sim = Simulation::new(&mut toy, Image::blank(ProfileId::A5), 10).unwrap();
            let r = sim.run(Until::Scans(30), &s, observer).unwrap();
            assert_eq!((r.outcome, r.scans), (Outcome::Completed, 30));
        };
        let mut every = EveryScan(trace(), 0);
        run(&mut every);
        let mut watched = Counted(trace(), 0);
        run(&mut watched);
        let want = String::from_utf8(every.0.finish().unwrap()).unwrap();
        let got = String::from_utf8(watched.0.finish().unwrap()).unwrap();
        assert_eq!(got, want, "{specs:?}");
        if specs.contains(&"M0.1") {
            assert!(want.contains("#90\n1\""), "M0.1 written at scan 9: {want}");
        }
        assert_eq!(every.1, 30);
        if specs.contains(&"VW0") {
            assert_eq!(watched.1, 30, "VW0 changes in every scan");
        } else {
            // The first scan, the scans that changed a watched byte (5, 9, 12, 20) and the
            // stretch ends before rows (4, 8, 11, 19) and at the end (29).
            assert!(watched.1 < 12, "shown {} scans", watched.1);
        }
    }
}
