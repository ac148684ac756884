//! A fuzzing campaign: program `i` of campaign seed `s` is generated from
//! [`program_seed`]`(s, i)` in the dialect [`campaign_family`] picks (S7, Omron, or both in
//! turn: programs `4k, 4k+1` S7 and `4k+2, 4k+3` Omron, so each dialect meets the whole and the
//! split JIT), checked (the IR text and front-end round trips, then both engines side by side),
//! and counted. A generated Omron program its front end rejects is a finding too (of the
//! generator). Programs are split across threads (`jobs`) and machines (`shard K/N`: program `i`
//! belongs to shard `i mod N`), and the split never changes which program a number denotes, so a
//! finding is reproduced from its seed alone.
//!
//! No clock is read here: the caller decides when to stop (`keep_going`) and when to print
//! (`observe`), both called from worker threads.

use crate::coverage::Coverage;
use crate::engines::EngineKind;
use crate::generate::{Case, GenConfig, Generated, generate_in};
use crate::oracle::{Finding, RunOptions, RunStats, run_pair};
use crate::rng::{Choices, program_seed};
use crate::roundtrip::{RoundTripError, roundtrip};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use stljit_core::Family;

/// Which dialects a campaign generates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialects {
    /// S7 programs only (built as IR).
    S7,
    /// Omron programs only (written as text, compiled by the Omron front end).
    Omron,
    /// Both, in turn.
    Both,
}

/// What to run.
#[derive(Clone, Debug)]
pub struct CampaignConfig {
    /// The campaign seed.
    pub seed: u64,
    /// Stop after this many programs of this shard (`None`: until `keep_going` says stop).
    pub programs: Option<u64>,
    /// Worker threads.
    pub jobs: usize,
    /// This machine's shard `(k, n)`: it runs programs `i` with `i mod n == k`.
    pub shard: (u64, u64),
    /// The two engines compared.
    pub engines: [EngineKind; 2],
    /// The dialects generated (a `generator.profile` fixes its own dialect).
    pub dialects: Dialects,
    /// Generator knobs.
    pub generator: GenConfig,
    /// Oracle knobs.
    pub run: RunOptions,
    /// Also require every program to survive both round trips ([`roundtrip`]): IR text print →
    /// parse, and print → compile in the program's dialect.
    pub roundtrip: bool,
}

/// Running totals.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Totals {
    /// Programs checked.
    pub programs: u64,
    /// Of which Omron programs.
    pub omron_programs: u64,
    /// Scans compared (per engine).
    pub scans: u64,
    /// Programs that ended in a fatal error (watchdog, NaN or bad pointer in a compare).
    pub fatal: u64,
    /// Programs that ended in STOP (fatal or a STOP instruction).
    pub stopped: u64,
    /// IR ops generated.
    pub ops: u64,
    /// Programs per fatal error code they ended with.
    pub fatal_codes: std::collections::BTreeMap<u16, u64>,
}

/// A failing program.
#[derive(Clone, Debug)]
pub struct Failure {
    /// Its number in the campaign.
    pub index: u64,
    /// Its seed ([`campaign_case`] rebuilds it).
    pub seed: u64,
    /// Its dialect.
    pub family: Family,
    /// The program and stimulus (`None` when the generated Omron text did not compile).
    pub case: Option<Case>,
    /// The generated source text (Omron programs).
    pub source: Option<String>,
    /// The engines it was run on ([`campaign_engines`]).
    pub engines: [EngineKind; 2],
    /// What went wrong.
    pub finding: Finding,
}

/// What a campaign did.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Totals.
    pub totals: Totals,
    /// Generated-op coverage.
    pub coverage: Coverage,
    /// The first failure, if any (the campaign stops at it).
    pub failure: Option<Failure>,
}

/// Checks one case: the round trips (optional; a failure is a build finding of "ir text" or
/// "front end"), then both engines, each built fresh. Panics while building are findings like
/// panics while running.
pub fn check_case(
    case: &Case,
    engines: [EngineKind; 2],
    run: &RunOptions,
    with_roundtrip: bool,
) -> Result<RunStats, Finding> {
    if with_roundtrip {
        let rt = catch_unwind(|| roundtrip(&case.program)).map_err(|_| Finding::Build {
            engine: "front end",
            message: "panicked on the printed program".into(),
        })?;
        rt.map_err(|e| Finding::Build {
            engine: match e {
                RoundTripError::IrTextRejected { .. } | RoundTripError::IrTextChanged { .. } => {
                    "ir text"
                }
                RoundTripError::NotPrintable { .. }
                | RoundTripError::FrontEndRejected { .. }
                | RoundTripError::FrontEndChanged { .. } => "front end",
            },
            message: e.to_string(),
        })?;
    }
    let build = |k: EngineKind| {
        catch_unwind(AssertUnwindSafe(|| k.build(&case.program)))
            .map_err(|_| Finding::Build {
                engine: k.name(),
                message: "panicked while building".into(),
            })?
            .map_err(|e| Finding::Build {
                engine: e.engine,
                message: e.message,
            })
    };
    let mut a = build(engines[0])?;
    let mut b = build(engines[1])?;
    run_pair(&case.program, &case.stimulus, &mut *a, &mut *b, run)
}

/// The engines program `index` of a campaign runs on: `cfg.engines`, with the JIT split into
/// one function per basic block ([`EngineKind::split`]) for every odd index.
pub fn campaign_engines(cfg: &CampaignConfig, index: u64) -> [EngineKind; 2] {
    if index % 2 == 1 {
        cfg.engines.map(EngineKind::split)
    } else {
        cfg.engines
    }
}

/// The dialect of program `index` of a campaign.
pub fn campaign_family(cfg: &CampaignConfig, index: u64) -> Family {
    if let Some(p) = cfg.generator.profile {
        return p.profile().family;
    }
    match cfg.dialects {
        Dialects::S7 => Family::S7,
        Dialects::Omron => Family::Omron,
        Dialects::Both if (index >> 1) & 1 == 0 => Family::S7,
        Dialects::Both => Family::Omron,
    }
}

/// The case of program `index` of a campaign (with its seed and dialect); an `Err` is a
/// generated Omron text its front end rejects.
pub fn campaign_case(
    cfg: &CampaignConfig,
    index: u64,
) -> (
    u64,
    Family,
    Result<Generated, crate::generate::omron::GenError>,
) {
    let seed = program_seed(cfg.seed, index);
    let family = campaign_family(cfg, index);
    let mut c = Choices::from_seed(seed);
    // Every fourth program plain (`GenConfig::plain`), whatever its dialect and engines.
    let generator = GenConfig {
        plain: cfg.generator.plain || (index >> 2) & 3 == 3,
        ..cfg.generator.clone()
    };
    (seed, family, generate_in(family, &mut c, &generator))
}

/// Runs a campaign until `cfg.programs` are done, `keep_going` returns false, or a failure.
/// `observe` sees the totals after every program.
pub fn run(
    cfg: &CampaignConfig,
    keep_going: &(dyn Fn(&Totals) -> bool + Sync),
    observe: &(dyn Fn(&Totals) + Sync),
) -> Report {
    let (k, n) = (cfg.shard.0, cfg.shard.1.max(1));
    let next = AtomicU64::new(0);
    let stop = AtomicBool::new(false);
    let totals = Mutex::new(Totals::default());
    let coverage = Mutex::new(Coverage::default());
    let failure: Mutex<Option<Failure>> = Mutex::new(None);
    let worker = || {
        let mut cov = Coverage::default();
        loop {
            if stop.load(Ordering::Relaxed) {
                break;
            }
            let j = next.fetch_add(1, Ordering::Relaxed);
            if cfg.programs.is_some_and(|p| j >= p) {
                break;
            }
            let index = k + j * n;
            let (seed, family, generated) = campaign_case(cfg, index);
            let engines = campaign_engines(cfg, index);
            let (case, source, result) = match generated {
                Ok(Generated {
                    case,
                    source,
                    options,
                }) => {
                    match &source {
                        Some(text) => cov.add_omron_source(text, options),
                        None => cov.add_program(&case.program),
                    }
                    let result = check_case(&case, engines, &cfg.run, cfg.roundtrip);
                    (Some(case), source, result)
                }
                Err(e) => {
                    let finding = Finding::Build {
                        engine: "generator",
                        message: e.to_string(),
                    };
                    (None, Some(e.source), Err(finding))
                }
            };
            let snapshot = {
                let mut t = totals.lock().unwrap_or_else(|e| e.into_inner());
                t.programs += 1;
                t.omron_programs += u64::from(family == Family::Omron);
                t.ops += case.as_ref().map_or(0, |c| c.program.op_count() as u64);
                match &result {
                    Ok(s) => {
                        t.scans += s.scans;
                        t.fatal += u64::from(s.fatal);
                        if s.fatal_code != 0 {
                            *t.fatal_codes.entry(s.fatal_code).or_default() += 1;
                        }
                        t.stopped += u64::from(s.stopped);
                    }
                    Err(f) => t.scans += u64::from(f.scan().unwrap_or(0)) + 1,
                }
                t.clone()
            };
            if let Err(finding) = result {
                stop.store(true, Ordering::Relaxed);
                let mut slot = failure.lock().unwrap_or_else(|e| e.into_inner());
                // Keep the lowest-numbered failure so that reruns with other job counts agree.
                if slot.as_ref().is_none_or(|f| f.index > index) {
                    *slot = Some(Failure {
                        index,
                        seed,
                        family,
                        case,
                        source,
                        engines,
                        finding,
                    });
                }
                break;
            }
            observe(&snapshot);
            if !keep_going(&snapshot) {
                stop.store(true, Ordering::Relaxed);
                break;
            }
        }
        coverage
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .merge(&cov);
    };
    std::thread::scope(|s| {
        for _ in 1..cfg.jobs.max(1) {
            s.spawn(worker);
        }
        worker();
    });
    Report {
        totals: totals.into_inner().unwrap_or_else(|e| e.into_inner()),
        coverage: coverage.into_inner().unwrap_or_else(|e| e.into_inner()),
        failure: failure.into_inner().unwrap_or_else(|e| e.into_inner()),
    }
}
