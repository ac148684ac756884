//! Fixed-seed differential fuzzing campaigns on every `cargo test`: 2,000 generated S7 programs
//! and 2,000 generated Omron programs of 50 scans each, interpreter against the JIT (the odd
//! programs split into one function per basic block), whole image compared after every scan.
//! It also proves the oracle is not blind: a JIT wrapped in a fault injector must be caught at
//! the exact scan and byte.

use stljit_core::{Area, Layout};
use stljit_diff::campaign::{self, CampaignConfig, Dialects, Report, Totals, check_case};
use stljit_diff::engines::EngineKind;
use stljit_diff::generate::{GenConfig, case_from_seed};
use stljit_diff::inject::{Fault, Faulty};
use stljit_diff::locate::Place;
use stljit_diff::oracle::{Finding, RunOptions, run_pair};
use stljit_jit::OptLevel;

/// Runs 2,000 programs of `dialects` from `seed` on 2 threads and requires no finding and
/// most programs running all their scans.
fn smoke(seed: u64, dialects: Dialects) -> Report {
    let cfg = CampaignConfig {
        seed,
        programs: Some(2000),
        jobs: 2,
        shard: (0, 1),
        engines: [EngineKind::Interp, EngineKind::Jit(OptLevel::None)],
        dialects,
        generator: GenConfig::default(),
        run: RunOptions::default(),
        roundtrip: true,
    };
    let report = campaign::run(&cfg, &|_: &Totals| true, &|_: &Totals| {});
    if let Some(f) = &report.failure {
        panic!(
            "program {} (seed {}) fails; reproduce with `stljit fuzz --dialect {} --seed {} \
             --programs {}`:\n{}",
            f.index,
            f.seed,
            if dialects == Dialects::Omron {
                "omron"
            } else {
                "s7"
            },
            cfg.seed,
            f.index + 1,
            f.finding
        );
    }
    let t = &report.totals;
    assert_eq!(t.programs, 2000);
    assert_eq!(t.scans, 2000 * 50);
    // Most programs must run all their scans: a generator that mostly produced programs stopping
    // in scan 0 would compare little.
    assert!(
        t.stopped < t.programs / 3,
        "{} of {} programs stopped",
        t.stopped,
        t.programs
    );
    report
}

#[test]
fn smoke_campaign_finds_no_divergence() {
    let report = smoke(0x5EED, Dialects::S7);
    let missing = report.coverage.missing();
    assert!(missing.is_empty(), "mnemonics never generated: {missing:?}");
}

#[test]
fn omron_smoke_campaign_finds_no_divergence() {
    let report = smoke(0x0E1D, Dialects::Omron);
    assert_eq!(report.totals.omron_programs, 2000);
    let missing = report.coverage.missing_omron();
    assert!(
        missing.is_empty(),
        "Omron forms never generated: {missing:?}"
    );
}

#[test]
fn a_faulty_jit_is_caught_at_the_exact_scan_and_byte() {
    let case = (0..100)
        .map(|s| case_from_seed(s, &GenConfig::default()))
        .find(|c| {
            check_case(
                c,
                [EngineKind::Interp, EngineKind::Jit(OptLevel::None)],
                &RunOptions::default(),
                false,
            )
            .is_ok_and(|s| !s.stopped)
        })
        .expect("a generated program that runs all 50 scans");
    let layout = Layout::of(case.program.profile);
    for (scan, offset) in [
        (0, layout.addr(Area::V, 2000, 0)),
        (17, layout.timer_state(5)),
        (49, layout.phys_out),
    ] {
        let mut interp = EngineKind::Interp.build(&case.program).unwrap();
        let jit = EngineKind::Jit(OptLevel::None)
            .build(&case.program)
            .unwrap();
        let mut faulty = Faulty::new(
            jit,
            Fault::FlipBit {
                scan,
                offset,
                bit: 6,
            },
        );
        let r = run_pair(
            &case.program,
            &case.stimulus,
            &mut *interp,
            &mut faulty,
            &RunOptions::default(),
        );
        let Err(Finding::Divergence(d)) = r else {
            panic!("fault at scan {scan} offset {offset:#x} not reported: {r:?}");
        };
        assert_eq!(
            (d.scan, d.diffs[0].offset, d.total),
            (scan as u32, offset, 1)
        );
        assert_eq!(d.diffs[0].bytes[0] ^ d.diffs[0].bytes[1], 1 << 6);
        assert_eq!(d.diffs[0].place, Place::of(&layout, offset));
    }
    let mut interp = EngineKind::Interp.build(&case.program).unwrap();
    let jit = EngineKind::Jit(OptLevel::None)
        .build(&case.program)
        .unwrap();
    let mut skipping = Faulty::new(jit, Fault::SkipScan { scan: 30 });
    let r = run_pair(
        &case.program,
        &case.stimulus,
        &mut *interp,
        &mut skipping,
        &RunOptions::default(),
    );
    assert!(matches!(r, Err(Finding::Divergence(d)) if d.scan == 30));
}
