//! The machinery on its own, with a fake engine whose "routine" is a closure: the queue rules,
//! the event phases and the context of a routine, against s7-200-more §3 (the full programs on
//! both engines are the conformance cases `tests/conformance/i*.toml`).

use super::*;
use crate::image::Image;
use crate::scan::{self, ScanPlan};
use stljit_core::interrupt::EventGroup;
use stljit_core::ir::{Pou, PouKind, SrcLoc};
use stljit_core::layout::{QueueEntry, Sched};
use stljit_core::{PouId, ProfileId, ScanStatus, Width};

/// A program with an empty main and the interrupt routines `ints` (POU `i + 1` is INT
/// `ints[i]`): enough for a plan.
fn program(profile: ProfileId, ints: &[u16]) -> Program {
    let pou = |name: String, kind| Pou {
        name,
        kind,
        ops: vec![],
        locs: Vec::<SrcLoc>::new(),
        labels: vec![],
    };
    let mut pous = vec![pou("MAIN".into(), PouKind::Main)];
    pous.extend(
        ints.iter()
            .map(|&n| pou(format!("INT{n}"), PouKind::Interrupt(n))),
    );
    Program {
        profile,
        pous,
        timers: vec![],
        counters: vec![],
        edges: vec![],
        logic_stack_depth: 9,
        files: vec![],
        data: vec![],
    }
}

/// An engine whose routines are one closure of the POU and the time it runs at (µs).
struct Fake<F>(F);

impl<F: FnMut(&mut [u8], &Layout, PouId, u64) -> ScanStatus> Isr for Fake<F> {
    fn run(&mut self, img: &mut [u8], layout: &Layout, pou: PouId) -> ScanStatus {
        let tau = now(img, layout);
        (self.0)(img, layout, pou, tau)
    }
}

/// A PLC: image, plan and the scan time.
struct Plc {
    img: Image,
    plan: ScanPlan,
    k: u64,
    scan_ms: u64,
}

impl Plc {
    fn new(profile: ProfileId, ints: &[u16], scan_ms: u64) -> Plc {
        Plc::with_timers(profile, ints, &[], scan_ms)
    }

    /// With the 1-ms TONs `timers` declared (T32, T96 on the Siemens profiles).
    fn with_timers(profile: ProfileId, ints: &[u16], timers: &[u16], scan_ms: u64) -> Plc {
        let mut p = program(profile, ints);
        p.timers
            .extend(timers.iter().map(|&n| stljit_core::ir::TimerDecl {
                id: stljit_core::TimerId(n),
                kind: stljit_core::ir::TimerKind::On,
                resolution: stljit_core::profile::Resolution::Ms1,
            }));
        Plc {
            img: Image::cold_start(&p),
            plan: ScanPlan::of(&p),
            k: 0,
            scan_ms,
        }
    }

    /// One scan with the physical inputs `ib0`, routines `isr` and main program `main`.
    fn scan(
        &mut self,
        ib0: u8,
        isr: &mut dyn Isr,
        main: impl FnOnce(&mut [u8], &Layout),
    ) -> ScanStatus {
        self.img.set_inputs(&[ib0]);
        let t = self.k * self.scan_ms;
        self.k += 1;
        let (b, l) = self.img.split_mut();
        scan::run(b, l, &self.plan, t, isr, |b, l| {
            main(b, l);
            ScanStatus::Ok
        })
    }

    fn vw(&self, at: u32) -> u32 {
        let l = self.img.layout();
        mem::get_be(self.img.bytes(), l.base(Area::V) + at, Width::Word)
    }

    fn sm4(&self) -> u8 {
        mem::get_u8(self.img.bytes(), self.img.layout().base(Area::SM) + SMB4)
    }

    fn queued(&self, g: usize) -> u8 {
        let l = self.img.layout();
        mem::get_u8(
            self.img.bytes(),
            l.int_state(IntState::QUEUE_LEN) + g as u32,
        )
    }
}

fn run(img: &mut [u8], l: &Layout, a: Action) {
    execute(img, l, a).expect("no error");
}

/// `INCW VW<at>` as a routine body.
fn incw(img: &mut [u8], l: &Layout, at: u32) {
    let a = l.base(Area::V) + at;
    let v = mem::get_be(img, a, Width::Word);
    mem::set_be(img, a, Width::Word, v + 1);
}

fn attach(routine: u16, event: u8) -> Action {
    Action::Attach { routine, event }
}

/// `MOVB ms, SMB34` and `ATCH INT0, 10`.
fn attach_timed(b: &mut [u8], l: &Layout, ms: u8) {
    mem::set_u8(b, l.base(Area::SM) + 34, ms);
    run(b, l, attach(0, 10));
}

#[test]
fn m3_timed_interrupt_faster_than_the_scan() {
    // §12 M3: SMB34 = 5 at ATCH, 10-ms scans: due at 5, 10, 15 … ms, two runs per interval,
    // each at its own due time; changing SMB34 later has no effect (captured at ATCH).
    let mut plc = Plc::new(ProfileId::A5, &[0], 10);
    let mut times = Vec::new();
    let mut isr = Fake(|img: &mut [u8], l: &Layout, _, tau| {
        times.push(tau);
        incw(img, l, 0);
        ScanStatus::Ok
    });
    plc.scan(0, &mut isr, |b, l| {
        attach_timed(b, l, 5);
        run(b, l, Action::Enable);
        mem::set_u8(b, l.base(Area::SM) + 34, 1);
    });
    for _ in 1..5 {
        plc.scan(0, &mut isr, |_, _| {});
    }
    assert_eq!(plc.vw(0), 8, "2 per scan after scan 0");
    assert_eq!(times, [5, 10, 15, 20, 25, 30, 35, 40].map(|ms| ms * 1000));
    assert_eq!(plc.sm4() & 0b111, 0);
}

#[test]
fn m4_disabled_interrupts_overflow_and_pending_service() {
    // §12 M4: a 1-ms timed interrupt attached while disabled: scan 1 queues the events at
    // 1 … 8 ms, loses 9 and 10 ms (SM4.2); ENI in scan 1; scan 2 runs the 8 pending routines at
    // τ = 10 ms (they see SM4.2 = 1), clears SM4.2, then 10 more.
    let mut plc = Plc::new(ProfileId::A5, &[0], 10);
    let mut seen = Vec::new();
    let mut isr = Fake(|img: &mut [u8], l: &Layout, _, tau| {
        incw(img, l, 0);
        seen.push((tau, mem::get_u8(img, l.base(Area::SM) + SMB4) & 0b100 != 0));
        ScanStatus::Ok
    });
    plc.scan(0, &mut isr, |b, l| attach_timed(b, l, 1));
    plc.scan(1, &mut isr, |b, l| run(b, l, Action::Enable));
    assert_eq!((plc.vw(0), plc.sm4() & 0b100, plc.queued(2)), (0, 0b100, 8));
    plc.scan(0, &mut isr, |_, _| {});
    assert_eq!((plc.vw(0), plc.sm4() & 0b100, plc.queued(2)), (18, 0, 0));
    plc.scan(0, &mut isr, |_, _| {});
    assert_eq!(plc.vw(0), 28);
    assert!(seen[..8].iter().all(|&(t, ovf)| t == 10_000 && ovf));
    let later: Vec<u64> = seen[8..18].iter().map(|&(t, _)| t).collect();
    assert_eq!(later, (11..=20).map(|ms| ms * 1000).collect::<Vec<_>>());
    assert!(seen[8..].iter().all(|&(_, ovf)| !ovf));
}

#[test]
fn m5_input_edges_at_the_scan_instant() {
    // §12 M5: ATCH INT1 to event 0 (I0.0 rising); inputs 0, 1, 1, 0, 1 → runs in scans 1
    // and 4; the falling edge (event 1) is not attached.
    let mut plc = Plc::new(ProfileId::A5, &[1], 10);
    let mut runs = Vec::new();
    for (k, ib0) in [0, 1, 1, 0, 1].into_iter().enumerate() {
        let mut isr = Fake(|img: &mut [u8], l: &Layout, _, _| {
            // The routine sees the new input image (E2 is after the input read).
            runs.push((k, mem::get_u8(img, l.base(Area::I)) & 1));
            ScanStatus::Ok
        });
        plc.scan(ib0, &mut isr, |b, l| {
            if k == 0 {
                run(b, l, attach(1, 0));
                run(b, l, Action::Enable);
            }
        });
    }
    assert_eq!(runs, [(1, 1), (4, 1)]);
}

#[test]
fn simultaneous_events_run_by_group_then_priority() {
    // §3.3: one instant, four edges and a timed event queued while disabled: the discrete
    // group first, inside it by priority (rising I0.1 before rising I0.3 before falling
    // I0.0), the timed group last.
    let mut plc = Plc::new(ProfileId::A5, &[0, 1, 2, 3], 10);
    let mut order = Vec::new();
    let mut isr = Fake(|_: &mut [u8], _: &Layout, pou: PouId, _| {
        order.push(pou.0);
        ScanStatus::Ok
    });
    plc.scan(0b0001, &mut isr, |b, l| {
        mem::set_u8(b, l.base(Area::SM) + 34, 10);
        run(b, l, attach(0, 10)); // INT0 (POU 1): timed, due at 10 ms
        run(b, l, attach(1, 1)); // INT1: I0.0 falling
        run(b, l, attach(2, 6)); // INT2: I0.3 rising
        run(b, l, attach(3, 2)); // INT3: I0.1 rising
    });
    // Scan 1 (10 ms): the timed event in E1, queued (disabled); E2: I0.0 falls, I0.1 and I0.3
    // rise; ENI in the main program.
    plc.scan(0b1010, &mut isr, |b, l| run(b, l, Action::Enable));
    assert_eq!((plc.queued(1), plc.queued(2)), (3, 1));
    plc.scan(0b1010, &mut isr, |_, _| {});
    // Scan 2: the leading service at 10 ms runs the four queued ones (discrete by priority:
    // I0.1 rising pri 3, I0.3 rising pri 5, I0.0 falling pri 6; then timed), then the
    // happening at 20 ms its own.
    assert_eq!(order, [4, 3, 2, 1, 1]);
}

#[test]
fn detach_and_clear_drop_queued_entries() {
    let mut plc = Plc::new(ProfileId::A5, &[0, 1], 10);
    let mut runs = Vec::new();
    let mut isr = Fake(|_: &mut [u8], _: &Layout, pou: PouId, _| {
        runs.push(pou.0);
        ScanStatus::Ok
    });
    plc.scan(0, &mut isr, |b, l| {
        mem::set_u8(b, l.base(Area::SM) + 34, 2);
        mem::set_u8(b, l.base(Area::SM) + 35, 5);
        run(b, l, attach(0, 10));
        run(b, l, attach(1, 11));
    });
    // Scan 1 queued 2, 4, 6, 8, 10 ms (event 10) and 5, 10 ms (event 11), in time order;
    // CEVNT 10 drops the five of event 10, DTCH 11 the two of event 11 and its schedule.
    let mut seen = Vec::new();
    let (timed, _) = ProfileId::A5.profile().interrupts.queue(EventGroup::Timed);
    plc.scan(0, &mut isr, |b, l| {
        seen = (0..7)
            .map(|i| mem::get_u8(b, l.queue_entry(timed + i) + QueueEntry::EVENT))
            .collect();
        run(b, l, Action::Clear(10));
        run(b, l, Action::Detach(11));
    });
    assert_eq!(seen, [10, 10, 11, 10, 10, 10, 11]);
    assert_eq!(plc.queued(2), 0);
    plc.scan(0, &mut isr, |b, l| run(b, l, Action::Enable));
    assert_eq!(
        plc.queued(2),
        5,
        "scan 2 queued 12 … 20 ms of event 10 only"
    );
    plc.scan(0, &mut isr, |_, _| {});
    assert_eq!(runs, [1; 10], "5 pending, then 22 … 30 ms; INT1 never");
}

#[test]
fn a_routine_runs_in_its_own_context() {
    // §3.6.4: AC0–AC3, ENO and SMB1 are restored after the routine; what else it writes stays;
    // ENI/DISI in it are 0x0004 and change nothing.
    let mut plc = Plc::new(ProfileId::S7_200, &[0], 10);
    let mut isr = Fake(|img: &mut [u8], l: &Layout, _, _| {
        assert_eq!(mem::sched_u8(img, l, Sched::ENO), 0, "ENO 0 at entry");
        assert_eq!(
            mem::sched_u8(img, l, Sched::SCR_ENABLE),
            1,
            "gate open at entry"
        );
        assert_eq!(
            execute(img, l, Action::Disable),
            Err(ErrorCode::InInterrupt)
        );
        mem::set_array(img, l.base(Area::AC), [0xEE; 16]);
        mem::set_u8(img, l.base(Area::SM) + 1, 0xFF);
        mem::set_sched_u8(img, l, Sched::ENO, 1);
        mem::set_sched_u8(img, l, Sched::SCR_ENABLE, 0);
        incw(img, l, 0);
        ScanStatus::Ok
    });
    plc.scan(0, &mut isr, |b, l| {
        run(b, l, attach(0, 0));
        run(b, l, Action::Enable);
    });
    let l = plc.img.layout().clone();
    let b = plc.img.bytes_mut();
    mem::set_array(b, l.base(Area::AC), [7; 16]);
    mem::set_u8(b, l.base(Area::SM) + 1, 0x05);
    mem::set_sched_u8(b, &l, Sched::ENO, 1);
    plc.scan(1, &mut isr, |b, l| {
        assert_eq!(mem::get_array::<16>(b, l.base(Area::AC)), [7; 16]);
        assert_eq!(mem::get_u8(b, l.base(Area::SM) + 1), 0x05);
        assert_eq!(
            mem::sched_u8(b, l, Sched::ENO),
            0,
            "the scan's reset, restored"
        );
        assert_eq!(mem::sched_u8(b, l, Sched::SCR_ENABLE), 1);
    });
    assert_eq!(plc.vw(0), 1);
    assert_eq!(get(plc.img.bytes(), &l, IntState::ENABLED), 1);
    assert_eq!(plc.sm4() >> SM4_ENABLED & 1, 1, "SM4.4 mirrors ENI");
}

#[test]
fn stop_in_a_routine_discards_the_queue_and_the_scan_completes() {
    let mut plc = Plc::new(ProfileId::A5, &[0], 10);
    let mut runs = 0;
    let mut isr = Fake(|img: &mut [u8], l: &Layout, _, _| {
        runs += 1;
        mem::set_sched_u8(img, l, Sched::STOP_REQ, 1);
        ScanStatus::Stopped
    });
    plc.scan(0, &mut isr, |b, l| attach_timed(b, l, 1));
    plc.scan(0, &mut isr, |b, l| run(b, l, Action::Enable));
    let mut main_ran = false;
    let st = plc.scan(0, &mut isr, |_, _| main_ran = true);
    assert_eq!((st, runs, main_ran), (ScanStatus::Stopped, 1, true));
    // The seven entries left at 10 ms were discarded; what the rest of the interval queued
    // (11 ms on) is never serviced.
    let l = plc.img.layout().clone();
    let (timed, _) = ProfileId::A5.profile().interrupts.queue(EventGroup::Timed);
    let tau = mem::get_u64_ne(plc.img.bytes(), l.queue_entry(timed) + QueueEntry::TAU);
    assert_eq!((plc.queued(2), tau), (8, 11_000));
}

#[test]
fn a_fatal_routine_aborts_the_scan() {
    let mut plc = Plc::new(ProfileId::A5, &[0], 10);
    let mut isr = Fake(|_: &mut [u8], _: &Layout, _, _| ScanStatus::Fatal);
    plc.scan(0, &mut isr, |b, l| {
        run(b, l, attach(0, 0));
        run(b, l, Action::Enable);
    });
    let mut main_ran = false;
    let st = plc.scan(1, &mut isr, |_, _| main_ran = true);
    assert_eq!((st, main_ran), (ScanStatus::Fatal, false));
}

#[test]
fn a_long_interval_runs_every_due_time_within_the_budget() {
    // A 1-ms timed interrupt over a 70-s interval: 70 000 routine runs in one E1; the loop
    // budget counts only back-edges (none here), so the scan completes.
    let mut plc = Plc::new(ProfileId::A5, &[0], 70_000);
    let mut isr = Fake(|img: &mut [u8], l: &Layout, _, _| {
        incw(img, l, 0);
        ScanStatus::Ok
    });
    plc.scan(0, &mut isr, |b, l| {
        attach_timed(b, l, 1);
        run(b, l, Action::Enable);
    });
    assert_eq!(plc.scan(0, &mut isr, |_, _| {}), ScanStatus::Ok);
    assert_eq!(plc.vw(0), 70_000 % 65_536);
}

#[test]
fn routines_cannot_raise_timer_events_for_their_own_instant() {
    // INT0 (event 21) turns T32's bit off and T96's on, INT1 (event 22) the other way round:
    // polled after every routine they would raise each other's event forever at one instant.
    // The timer sources are polled at the phase starts only: two runs per scan.
    let mut plc = Plc::with_timers(ProfileId::S7_200, &[0, 1], &[32, 96], 10);
    let mut runs = Vec::new();
    let mut isr = Fake(|img: &mut [u8], l: &Layout, pou: PouId, _| {
        runs.push(pou.0);
        let on = |n: u32| l.base(Area::TimerBit) + n;
        let (off, set) = if pou.0 == 1 { (32, 96) } else { (96, 32) };
        mem::set_u8(img, on(off), 0);
        mem::set_u8(img, on(set), 1);
        ScanStatus::Ok
    });
    plc.scan(0, &mut isr, |b, l| {
        run(b, l, attach(0, 21));
        run(b, l, attach(1, 22));
        run(b, l, Action::Enable);
        mem::set_u8(b, l.base(Area::TimerBit) + 32, 1);
    });
    for _ in 0..4 {
        plc.scan(0, &mut isr, |_, _| {});
    }
    assert_eq!(runs, [1, 2, 1, 2, 1, 2, 1, 2]);
}

#[test]
fn t32_reaching_its_preset_is_an_event_at_the_scan_instant() {
    // §3.5.3: T32 (1 ms, TON) with PT 15, running from scan 0: CT = 10 after the refresh of
    // scan 1, 20 in scan 2 → event 21 at 20 ms, once.
    let mut plc = Plc::with_timers(ProfileId::S7_200, &[0], &[32], 10);
    let mut times = Vec::new();
    let mut isr = Fake(|_: &mut [u8], _: &Layout, _, tau| {
        times.push(tau);
        ScanStatus::Ok
    });
    let ton = |b: &mut [u8], l: &Layout| {
        let gate = crate::rules::Gate::Open;
        crate::timer::execute(
            b,
            l,
            32,
            stljit_core::ir::TimerKind::On,
            true,
            gate,
            15,
            Some(1),
        )
        .expect("T32");
    };
    plc.scan(0, &mut isr, |b, l| {
        run(b, l, attach(0, 21));
        run(b, l, Action::Enable);
        ton(b, l);
    });
    for _ in 0..4 {
        plc.scan(0, &mut isr, ton);
    }
    assert_eq!(times, [20_000]);
}

#[test]
fn actions_cross_the_boundary_as_three_integers() {
    let all = [
        attach(127, 38),
        Action::Detach(0),
        Action::Enable,
        Action::Disable,
        Action::Clear(11),
    ];
    for a in all {
        let (k, e, r) = a.encode();
        assert_eq!(Action::decode(k, e, r), Some(a));
    }
    assert_eq!(Action::decode(9, 0, 0), None);
    assert_eq!(Action::decode(1, 256, 0), None);
}
