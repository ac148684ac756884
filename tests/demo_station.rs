//! The corpus's demo station (`tests/corpus/smart200-mcp/demo_station`, a MicroWIN SMART
//! project of 18 blocks: SCR sequence, timers, counters, interrupts, HSC, PLS, free-port
//! communication, strings, the clock) runs ten minutes of virtual time closed-loop with a small
//! plant model, on the interpreter, the JIT at both optimisation levels and the split JIT, and
//! every engine's image must equal the interpreter's after every scan.
//!
//! The plant answers the station's outputs the way the machine would (a motor that runs long
//! enough brings the part into position, the clamp cylinder reaches its end switches after a
//! travel time, the spindle's encoder feeds HSC0, which the project's own wiring leaves
//! undefined: see the end), an operator starts the station, presses the
//! emergency stop once, resets, acknowledges and restarts it, and a host sends a framed message
//! to port 0 every five seconds. The run is deterministic: the same inputs reach every engine
//! before every scan.

use stljit_core::ir::Loc;
use stljit_core::{Area, ProfileId, Width};
use stljit_diff::engines::EngineKind;
use stljit_diff::oracle::compare_images;
use stljit_front::{Dialect, Severity, SourceFile};
use stljit_jit::OptLevel;
use stljit_runtime::{Engine, Image};

/// Scan time of the run (ms) and its length: ten minutes of virtual time.
const SCAN_MS: u64 = 10;
const SCANS: u64 = 10 * 60 * 1000 / SCAN_MS;

fn project() -> stljit_core::ir::Program {
    let root = stljit_harness::repo_root().join("tests/corpus/smart200-mcp/demo_station");
    let mut names: Vec<_> = std::fs::read_dir(root.join("src"))
        .expect("demo_station/src")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "awl"))
        .collect();
    names.sort();
    let load = |p: &std::path::Path| SourceFile {
        name: p.display().to_string(),
        bytes: std::fs::read(p).expect("readable corpus file"),
    };
    let files: Vec<SourceFile> = names.iter().map(|p| load(p)).collect();
    let symbols = load(&root.join("symbols.txt"));
    let c = Dialect::S7.compile(&files, Some(&symbols), ProfileId::Smart);
    let errors: Vec<_> = c
        .diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| format!("{}: {}", d.code.name(), d.text))
        .collect();
    assert!(
        errors.is_empty(),
        "the demo station must check clean: {errors:?}"
    );
    c.program.expect("a clean project has a program")
}

/// Input bits of the station (symbols.txt): byte 0 and byte 1 of the physical inputs.
mod input {
    pub(super) const ESTOP_NC: (usize, u8) = (0, 0);
    pub(super) const START: (usize, u8) = (0, 1);
    pub(super) const AUTO: (usize, u8) = (0, 3);
    pub(super) const RESET: (usize, u8) = (0, 4);
    pub(super) const FED: (usize, u8) = (0, 5);
    pub(super) const MACHINED: (usize, u8) = (0, 6);
    pub(super) const DISCHARGED: (usize, u8) = (0, 7);
    pub(super) const EXTENDED: (usize, u8) = (1, 0);
    pub(super) const RETRACTED: (usize, u8) = (1, 1);
    pub(super) const PART_PRESENT: (usize, u8) = (1, 2);
    pub(super) const DOOR_CLOSED: (usize, u8) = (1, 3);
    pub(super) const ACK: (usize, u8) = (1, 7);
}

/// Output bits (symbols.txt) in the physical output copy.
mod output {
    pub(super) const FEED_MOTOR: (usize, u8) = (0, 2);
    pub(super) const SPINDLE: (usize, u8) = (0, 3);
    pub(super) const DISCHARGE_MOTOR: (usize, u8) = (0, 4);
    pub(super) const CLAMP: (usize, u8) = (0, 5);
    pub(super) const HEARTBEAT: (usize, u8) = (1, 7);
}

fn bit(bytes: &[u8], (byte, bit): (usize, u8)) -> bool {
    bytes.get(byte).is_some_and(|b| b >> bit & 1 != 0)
}

fn set(bytes: &mut [u8], (byte, bit): (usize, u8), on: bool) {
    if let Some(b) = bytes.get_mut(byte) {
        *b = (*b & !(1 << bit)) | (u8::from(on) << bit);
    }
}

/// How long (ms) an output has been on, for travel times.
#[derive(Default)]
struct OnTimer(u64);

impl OnTimer {
    fn step(&mut self, on: bool) -> u64 {
        self.0 = if on { self.0 + SCAN_MS } else { 0 };
        self.0
    }
}

/// The machine around the PLC and its operator, as a function of virtual time and the last
/// scan's physical outputs.
#[derive(Default)]
struct Plant {
    feed: OnTimer,
    clamp: OnTimer,
    unclamp: OnTimer,
    spindle: OnTimer,
    discharge: OnTimer,
    /// Rising edges of the heartbeat output seen.
    heartbeats: u32,
    last_heartbeat: bool,
}

impl Plant {
    /// The inputs for the scan starting at `t` (ms), after outputs `q`.
    fn inputs(&mut self, t: u64, q: &[u8], inputs: &mut [u8]) {
        let s = t / 1000;
        let pulse = |at: u64| (at * 1000..at * 1000 + 500).contains(&t);
        // The operator: start at 1 s; emergency stop from 300 s to 302 s; reset at 305 s,
        // acknowledge at 306 s, restart at 310 s; manual mode from 400 s to 420 s.
        set(inputs, input::ESTOP_NC, !(300..302).contains(&s));
        set(inputs, input::START, pulse(1) || pulse(310) || pulse(421));
        set(inputs, input::AUTO, !(400..420).contains(&s));
        set(inputs, input::RESET, pulse(305));
        set(inputs, input::ACK, pulse(306));
        set(inputs, input::DOOR_CLOSED, true);
        set(inputs, input::PART_PRESENT, true);
        // The machine: travel and transport times of its actuators.
        let fed = self.feed.step(bit(q, output::FEED_MOTOR)) >= 2000;
        let clamp = bit(q, output::CLAMP);
        let extended = self.clamp.step(clamp) >= 500;
        let retracted = self.unclamp.step(!clamp) >= 500;
        let machined = self.spindle.step(bit(q, output::SPINDLE)) >= 1000;
        let discharged = self.discharge.step(bit(q, output::DISCHARGE_MOTOR)) >= 1500;
        set(inputs, input::FED, fed);
        set(inputs, input::EXTENDED, extended);
        set(inputs, input::RETRACTED, retracted);
        set(inputs, input::MACHINED, machined);
        set(inputs, input::DISCHARGED, discharged);
        let hb = bit(q, output::HEARTBEAT);
        self.heartbeats += u32::from(hb && !self.last_heartbeat);
        self.last_heartbeat = hb;
    }

    /// Encoder steps of the spindle for the interval before the scan (HSC0 counts them).
    fn encoder_steps(&self) -> i32 {
        if self.spindle.0 > 0 { 7 } else { 0 }
    }

    /// The analog input AIW16 (a slow triangle over the range the program scales).
    fn analog(t: u64) -> u32 {
        let phase = (t / 100) % 512;
        let tri = if phase < 256 { phase } else { 511 - phase };
        6400 + (tri as u32) * 100
    }
}

/// The host's message to port 0: STX, text, LF (the start and end characters the program
/// sets in SMB88/SMB89), every five seconds.
fn host_message(t: u64) -> Option<&'static [u8]> {
    (t % 5000 == 2500).then_some(b"\x02TEMP=23\n".as_slice())
}

#[test]
fn demo_station_runs_ten_minutes_closed_loop_with_identical_images() {
    let program = project();
    let kinds = [
        EngineKind::Interp,
        EngineKind::Jit(OptLevel::None),
        EngineKind::Jit(OptLevel::Speed),
        EngineKind::JitSplit(OptLevel::None),
    ];
    let mut engines: Vec<Box<dyn Engine>> = kinds
        .iter()
        .map(|k| k.build(&program).expect("the engine builds"))
        .collect();
    let mut images: Vec<Image> = kinds.iter().map(|_| Image::cold_start(&program)).collect();
    let mut plant = Plant::default();
    let mut inputs = vec![0u8; images[0].phys_in_mut().len()];
    for k in 0..SCANS {
        let t = k * SCAN_MS;
        let q = images[0].phys_out().to_vec();
        plant.inputs(t, &q, &mut inputs);
        for img in &mut images {
            img.set_inputs(&inputs);
            img.set_hsc_rate(0, plant.encoder_steps());
            let ai = Loc {
                area: Area::AI,
                offset: 16,
            };
            img.write(ai, Width::Word, 0, Plant::analog(t))
                .expect("AIW16 exists on the SMART profile");
            if let Some(msg) = host_message(t) {
                img.queue_rx(0, msg);
            }
        }
        for (e, img) in engines.iter_mut().zip(&mut images) {
            let status = e.scan(img, t);
            assert_eq!(
                status,
                stljit_core::ScanStatus::Ok,
                "{} stopped at scan {k}",
                e.name()
            );
        }
        for (kind, img) in kinds.iter().zip(&images).skip(1) {
            if let Some((diffs, total)) = compare_images(&images[0], img, 8) {
                panic!(
                    "scan {k} (t = {t} ms): {} differs from the interpreter in {total} bytes: {diffs:?}",
                    kind.name()
                );
            }
        }
    }
    let img = &images[0];
    let read = |area, offset, width| {
        img.read(Loc { area, offset }, width, 0)
            .expect("an address of the image")
    };
    // The run did what the station does, not only the same thing twice:
    // - the heartbeat Q1.7 follows SM0.5 (a 1 s clock: 0.5 s on, 0.5 s off, s7-200 manual
    //   §SM0), so ten minutes show 600 rising edges (one fewer or more at the ends);
    assert!(
        (599..=601).contains(&plant.heartbeats),
        "heartbeat edges: {}",
        plant.heartbeats
    );
    // - VW130 counts machined parts (08_scr step S0.3: `LD T42 / EU / INCW VW130`, once per
    //   cycle, when T42 is done). The first start is at 1 s and the first count after feed 2 s
    //   + clamp T41 3 s + machining T42 20 s, at 26 s; one cycle needs at least the program's
    //   own times, T41 3 s + T42 20 s + T43 3 s + T45 2 s, plus the plant's 2 s feed and 1.5 s
    //   discharge, 31.5 s, and at most ~0.5 s more (each 100-ms TON's resolution, two scans per
    //   step transition). The emergency stop (300 s to the restart at 310 s) and the manual
    //   phase (400 s to the restart at 421 s) hold the sequence for 31 s. So the 18th count
    //   comes at 26 + 17 x 31.5 + 31 = 592.5 s at the earliest, 601.5 s at the latest, and a
    //   19th would need 624 s.
    let parts = read(Area::V, 130, Width::Word);
    assert!((17..=18).contains(&parts), "machined parts VW130 = {parts}");
    // - the host's 120 messages (at 2.5 s, 7.5 s, ... 597.5 s) all arrived: each is 9
    //   characters at 9,600 baud (SMB30 = 16#09), under 10 ms, framed by the start and end
    //   characters the receive expects (SMB87 = 16#B0, SMB88 = STX, SMB89 = LF, at most 20
    //   characters), and INT_3 (receive complete, event 23) counts it in VW904 and restarts the
    //   receive.
    let received = read(Area::V, 904, Width::Word);
    assert_eq!(received, 120, "messages received (VW904)");
    // - the station's own HSC0 never counts: 05_init attaches INT_0 to event 0 (I0.0 rising)
    //   on the first scan before SBR10 runs `HDEF 0, 0`, and HSC0 in mode 0 clocks from I0.0
    //   (s7-200-more §8.3, the counter table), so HDEF fails with 0x0003 (inputs already used
    //   by an input interrupt), the `HSC 0` after it with 0x0001 (not defined), and the
    //   encoder's steps fed to HSC0 change nothing. The real CPU would do the same: the
    //   project wires its emergency stop to the counter's clock input.
    assert_eq!(read(Area::HC, 0, Width::DWord), 0, "HC0");
    assert_eq!(
        read(Area::V, 932, Width::DWord),
        0,
        "CV = PV interrupts (VD932)"
    );
}
