//! The stimulus CSV's hardware columns driving real programs on every engine: `HSC0` steps into
//! a high-speed counter (s7-200-more §8.4) and `PORT0` bytes into a Freeport receive (§10.4).
//!
//! Each case runs twice per engine: with an observer that sees every scan (one engine call per
//! scan) and with one that does not (the driver hands the engine each stretch of scans between
//! two stimulus rows at once: the JIT's native loop). Steps must keep counting in every scan of
//! a stretch, and bytes must arrive exactly once, so both runs end with byte-identical images,
//! on every engine, and with the values derived beside each case.

use crate::conformance::harness::ENGINES;
use std::io;
use stljit_core::ir::Program;
use stljit_front::{Dialect, SourceFile};
use stljit_runtime::Image;
use stljit_sim::{Observer, ScanEvent, Simulation, Stimulus, Until, read_address};

fn compile(text: &str) -> Program {
    let source = SourceFile {
        name: "case.stl".into(),
        bytes: text.as_bytes().to_vec(),
    };
    let c = Dialect::S7.compile(&[source], None, Dialect::S7.default_profile());
    c.program
        .unwrap_or_else(|| panic!("does not compile: {:?}", c.diagnostics))
}

fn stimulus(program: &Program, csv: &str) -> Stimulus {
    let resolve = |name: &str| {
        Dialect::S7
            .parse_address(name, program.profile, None)
            .map_err(|e| e.message)
    };
    Stimulus::parse(csv, program.profile.profile(), &resolve).unwrap_or_else(|e| panic!("{e}"))
}

/// Records `names` after every scan it is shown; `every` says whether it must see each scan.
struct Values<'a> {
    every: bool,
    names: &'a [&'a str],
    program: &'a Program,
    rows: Vec<(u64, Vec<u32>)>,
}

impl Observer for Values<'_> {
    fn observe(&mut self, e: &ScanEvent<'_>) -> io::Result<()> {
        let values = self
            .names
            .iter()
            .map(|n| {
                let a = Dialect::S7
                    .parse_address(n, self.program.profile, None)
                    .expect("address");
                read_address(e.image, &a).expect("in the image")
            })
            .collect();
        self.rows.push((e.scan, values));
        Ok(())
    }

    fn needs_every_scan(&self) -> bool {
        self.every
    }
}

/// Runs `scans` scans on every engine, scan by scan and in stretches; checks the values after
/// every scan against `want` (one row per scan), the stretch runs' last row, and that all runs
/// leave the same image.
fn check(program_text: &str, csv: &str, scans: u64, names: &[&str], want: &[Vec<u32>]) {
    let program = compile(program_text);
    let stim = stimulus(&program, csv);
    let mut images: Vec<(String, Image)> = Vec::new();
    for (engine, build) in ENGINES {
        for every in [true, false] {
            let mut e = build(&program).unwrap_or_else(|e| panic!("{engine}: {e}"));
            let mut sim = Simulation::new(e.as_mut(), Image::cold_start(&program), 10).unwrap();
            let mut obs = Values {
                every,
                names,
                program: &program,
                rows: Vec::new(),
            };
            sim.run(Until::Scans(scans), &stim, &mut obs).unwrap();
            let run = format!("{engine}, every scan: {every}");
            if every {
                let got: Vec<Vec<u32>> = obs.rows.into_iter().map(|r| r.1).collect();
                assert_eq!(got, want, "{run}");
            } else {
                let last = obs.rows.last().expect("a scan ran");
                assert_eq!(last.0, scans - 1, "{run}");
                assert_eq!(&last.1, want.last().unwrap(), "{run}");
                assert!(obs.rows.len() < want.len(), "{run}: ran in stretches");
            }
            images.push((run, sim.into_image()));
        }
    }
    let (first, rest) = images.split_first().unwrap();
    for (run, image) in rest {
        assert!(
            image.bytes() == first.1.bytes(),
            "{run} and {} end with different images",
            first.0
        );
    }
}

/// s7-200-more §12 M6 (conformance c01): HSC0 in mode 0, PV 25, counting up; the CV = PV
/// routine (event 12) counts VW10, copies HC0 to VD104 and reloads CV = 0. Every scan copies HC0
/// to VD100.
const COUNTER: &str = "\
Network 1
LD     SM0.1
MOVB   16#F8, SMB37
MOVD   +0, SMD38
MOVD   +25, SMD42
HDEF   0, 0
HSC    0
ATCH   INT_2, 12
ENI
Network 2
LD     SM0.0
MOVD   HC0, VD100
MEND
INT    2
LD     SM0.0
INCW   VW10
MOVD   HC0, VD104
MOVB   16#C0, SMB37
MOVD   +0, SMD38
HSC    0
RETI
";

/// Derivation (§8.4: the steps held before scan k count in (T_{k−1}, T_k], spread evenly, the
/// last at T_k, before the program; scan 0 has no interval; mode 0 counts every step up).
/// Rows: 10 steps from scan 1, none from scan 6, 7 from scan 8 (stretches 0, 1–5, 6–7, 8–12).
/// Scan 1: 10, scan 2: 20. Scan 3: the 5th step reaches 25 = PV, the routine reloads (VW10 1),
/// the other 5 count: 5. Scan 4: 15. Scan 5: the 10th step, at T_5, reaches 25: VW10 2, CV 0.
/// Scans 6, 7: 0. Scan 8: 7, scan 9: 14, scan 10: 21. Scan 11: the 4th step reaches 25 (VW10
/// 3), 3 more: 3. Scan 12: 10. The routine saw HC0 = 25 each time (VD104).
#[test]
fn hsc_column_counts_in_every_scan_of_a_stretch() {
    let cv = [0, 10, 20, 5, 15, 0, 0, 0, 7, 14, 21, 3, 10];
    let hits = [0, 0, 0, 1, 1, 2, 2, 2, 2, 2, 2, 3, 3];
    let want: Vec<Vec<u32>> = cv
        .iter()
        .zip(hits)
        .map(|(&c, h)| vec![c, h, if h > 0 { 25 } else { 0 }])
        .collect();
    check(
        COUNTER,
        "scan,HSC0\n1,10\n6,0\n8,7\n",
        13,
        &["VD100", "VW10", "VD104"],
        &want,
    );
}

/// s7-200-more §12 M14 (conformance s02) plus a receive-character routine: port 0 in Freeport at
/// 9 600 baud (SMB30 = 16#09), RCV with end character CR and an any-response start (SMB87 =
/// 16#B0, SMW90 = 0), so the message starts at the RCV in scan 0. Event 8 (each character) runs
/// INT 1: VW270 counts characters, VB272 keeps the last (SMB2); event 23 (message complete) runs
/// INT 5: VB250 := SMB86.
const RECEIVER: &str = "\
Network 1
LD     SM0.1
MOVB   16#09, SMB30
MOVB   16#B0, SMB87
MOVB   16#0D, SMB89
MOVW   +0, SMW90
MOVB   20, SMB94
ATCH   INT_5, 23
ATCH   INT_1, 8
ENI
RCV    VB200, 0
MEND
INT    1
LD     SM0.0
INCW   VW270
MOVB   SMB2, VB272
RETI
INT    5
LD     SM0.0
MOVB   SMB86, VB250
RETI
";

/// Derivation (§10.1, §10.3, §10.4): the row at scan 1 queues `O K CR` for the interval before
/// scan 1; they complete back to back from T_0 = 0 at 1 042, 2 084 and 3 126 µs (C = 1 042 µs at
/// 9 600 baud 8N1). Each runs INT 1 (VW270 1, 2, 3) and is stored; CR ends the message: SMB86 =
/// 16#20 (e), INT 5 copies it to VB250; the buffer VB200.. is 3, 16#4F, 16#4B, 16#0D. The row at
/// scan 5 queues `A` (16#41): it completes at 41 042 µs, INT 1 counts it (VW270 4, VB272 16#41);
/// the receive is over, so the buffer keeps 3 characters. Stretches 0, 1–4, 5–7: had the bytes
/// been queued again in a later scan of a stretch, VW270 would count them twice.
#[test]
fn port_column_bytes_are_received_exactly_once() {
    let names = [
        "VB200", "VB201", "VB202", "VB203", "VB250", "VW270", "VB272",
    ];
    let before = vec![0, 0, 0, 0, 0, 0, 0];
    let message = vec![3, 0x4F, 0x4B, 0x0D, 0x20, 3, 0x0D];
    let after = vec![3, 0x4F, 0x4B, 0x0D, 0x20, 4, 0x41];
    let mut want = vec![before];
    want.extend(std::iter::repeat_n(message, 4));
    want.extend(std::iter::repeat_n(after, 3));
    check(
        RECEIVER,
        "scan,PORT0\n1,16#4F4B0D\n5,16#41\n",
        8,
        &names,
        &want,
    );
}

/// A fast encoder: 1,000 steps in every interval from scan 1 (the `COUNTER` program, PV 25).
/// Derivation (§8.4, as above): CV climbs from 0 and every 25th step reaches PV, whose routine
/// runs at that step's time and reloads CV = 0, so each interval's 1,000 steps raise 40 events
/// and the 1,000th (at T_k, before the program) leaves CV = 0: after scan k, VW10 = 40·k,
/// VD100 = 0, and the routine always saw 25. The runtime applies the 24 steps between two
/// events at once (`hsc::Counter::apply_before`); the count must come out step for step.
#[test]
fn fast_encoder_counts_every_step_between_presets() {
    let want: Vec<Vec<u32>> = (0..8u32)
        .map(|k| vec![0, 40 * k, if k > 0 { 25 } else { 0 }])
        .collect();
    check(
        COUNTER,
        "scan,HSC0\n1,1000\n",
        8,
        &["VD100", "VW10", "VD104"],
        &want,
    );
}

/// HSC0 in mode 0 counting up with a preset it never reaches (PV = 2,000,000,000).
const ENCODER: &str = "\
Network 1
LD     SM0.1
MOVB   16#F8, SMB37
MOVD   +0, SMD38
MOVD   +2000000000, SMD42
HDEF   0, 0
HSC    0
Network 2
LD     SM0.0
MOVD   HC0, VD100
";

/// A million steps per 10-ms interval (a 100 MHz count rate, far beyond the hardware's, to
/// make a step-by-step simulation visible in the test's time) from scan 1, 250,000 from scan 5:
/// after scan k ≤ 4, HC0 = 10^6·k; after scan k ≥ 5, 4·10^6 + 250,000·(k − 4) (§8.4: every step
/// counts, CV never reaches PV).
#[test]
fn a_million_steps_per_scan_count_exactly() {
    let want: Vec<Vec<u32>> = (0..8u32)
        .map(|k| {
            vec![if k <= 4 {
                1_000_000 * k
            } else {
                4_000_000 + 250_000 * (k - 4)
            }]
        })
        .collect();
    check(
        ENCODER,
        "scan,HSC0\n1,1000000\n5,250000\n",
        8,
        &["VD100"],
        &want,
    );
}
