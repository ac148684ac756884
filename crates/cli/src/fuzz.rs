//! `stljit fuzz`: a differential fuzzing campaign, JIT against the interpreter.
//!
//! Programs come from `stljit_diff`'s generator (program `i` of seed `S` is fixed whatever the job
//! count or shard), S7 or Omron (`--dialect`, default both in turn); each is round-tripped
//! through its front end and run on both engines with the whole image compared after every
//! scan. Progress goes to stderr about once a second. On the first failure the case is shrunk,
//! written as a reproducer directory under `--out`, and the command exits 1 with its path.

use crate::duration::parse_duration;
use crate::engines::OptArg;
use crate::shard::parse_shard;
use anyhow::Context as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};
use stljit_core::{Family, ProfileId};
use stljit_diff::campaign::{self, CampaignConfig, Dialects, Totals, check_case};
use stljit_diff::engines::EngineKind;
use stljit_diff::generate::{Case, GenConfig};
use stljit_diff::oracle::RunOptions;
use stljit_diff::repro::{Meta, write_repro};
use stljit_diff::shrink::shrink;

/// Arguments of `stljit fuzz`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Campaign seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Number of programs (of this shard) to check; default 1000 unless --time is given.
    #[arg(long, conflicts_with = "time")]
    programs: Option<u64>,
    /// Run for this long (e.g. 90s, 10m, 1h).
    #[arg(long, value_parser = parse_duration)]
    time: Option<u64>,
    /// Worker threads.
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Run only shard K of N (program i belongs to shard i mod N), e.g. 0/4.
    #[arg(long, value_parser = parse_shard)]
    shard: Option<(u64, u64)>,
    /// Where reproducer directories go.
    #[arg(long, default_value = "fuzz-out")]
    out: PathBuf,
    /// JIT optimisation level.
    #[arg(long, value_enum, default_value = "none")]
    opt: OptArg,
    /// Scans per program.
    #[arg(long, default_value_t = 50)]
    scans: u32,
    /// Dialects to generate: s7, omron, or both in turn.
    #[arg(long, value_enum, default_value = "both")]
    dialect: DialectArg,
    /// Only this CPU profile (default: a mix of a5 and s7-200, and of cp1h and cp1e).
    #[arg(long)]
    cpu: Option<String>,
    /// Report the first failure as found, without shrinking it.
    #[arg(long)]
    no_shrink: bool,
}

/// `--dialect` of `stljit fuzz`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum DialectArg {
    /// S7-200/A5 STL.
    S7,
    /// Omron CP mnemonics.
    Omron,
    /// Both, in turn.
    Both,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let profile = match &args.cpu {
        Some(name) => {
            Some(ProfileId::from_name(name).with_context(|| format!("unknown --cpu `{name}`"))?)
        }
        None => None,
    };
    let dialects = match args.dialect {
        DialectArg::S7 => Dialects::S7,
        DialectArg::Omron => Dialects::Omron,
        DialectArg::Both => Dialects::Both,
    };
    if let Some(p) = profile {
        let family = p.profile().family;
        let clash = matches!(
            (dialects, family),
            (Dialects::S7, Family::Omron) | (Dialects::Omron, Family::S7)
        );
        if clash {
            anyhow::bail!("--cpu {} is not a profile of --dialect", p.name());
        }
    }
    let engines = [EngineKind::Interp, EngineKind::Jit(args.opt.into())];
    let cfg = CampaignConfig {
        seed: args.seed,
        programs: match (args.programs, args.time) {
            (Some(n), _) => Some(n),
            (None, Some(_)) => None,
            (None, None) => Some(1000),
        },
        jobs: args.jobs.max(1),
        shard: args.shard.unwrap_or((0, 1)),
        engines,
        dialects,
        generator: GenConfig {
            profile,
            scans: args.scans,
            ..GenConfig::default()
        },
        run: RunOptions::default(),
        roundtrip: true,
    };
    eprintln!(
        "fuzz: seed {}, {} program(s), shard {}/{}, {} job(s), {} vs {} (split into basic blocks \
         for odd programs), {} scans per program{}",
        cfg.seed,
        match dialects {
            Dialects::S7 => "S7",
            Dialects::Omron => "Omron",
            Dialects::Both => "S7 and Omron",
        },
        cfg.shard.0,
        cfg.shard.1,
        cfg.jobs,
        engines[0],
        engines[1],
        args.scans,
        match (cfg.programs, args.time) {
            (Some(n), _) => format!(", {n} programs"),
            (None, Some(ms)) => format!(", for {}", crate::duration::format_ms(ms)),
            _ => String::new(),
        }
    );
    let start = Instant::now();
    let deadline = args.time.map(|ms| start + Duration::from_millis(ms));
    let interrupted = AtomicBool::new(false);
    let flag: &'static AtomicBool = Box::leak(Box::new(AtomicBool::new(false)));
    // A second Ctrl-C kills the process the usual way; the first finishes the running programs.
    let _ = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
    let last_print = Mutex::new(start);
    let keep_going = |_: &Totals| {
        let stop = flag.load(Ordering::Relaxed) || deadline.is_some_and(|d| Instant::now() >= d);
        if flag.load(Ordering::Relaxed) {
            interrupted.store(true, Ordering::Relaxed);
        }
        !stop
    };
    let observe = |t: &Totals| {
        let now = Instant::now();
        let mut last = last_print.lock().unwrap_or_else(|e| e.into_inner());
        if now.duration_since(*last) >= Duration::from_secs(1) {
            *last = now;
            eprintln!("{}", progress_line(t, now.duration_since(start)));
        }
    };
    let report = campaign::run(&cfg, &keep_going, &observe);
    let elapsed = start.elapsed();
    eprintln!("{}", progress_line(&report.totals, elapsed));
    print_summary(&report, elapsed, cfg.jobs);
    if interrupted.load(Ordering::Relaxed) {
        eprintln!("interrupted");
    }
    let Some(failure) = report.failure else {
        println!("no divergence");
        return Ok(ExitCode::SUCCESS);
    };
    eprintln!(
        "\nFAILURE in program {} (seed {}, {}):\n{}",
        failure.index,
        failure.seed,
        family_name(failure.family),
        failure.finding
    );
    let dir = args.out.join(format!("case-{}", failure.seed));
    let Some(case) = failure.case else {
        // The generator wrote Omron text its front end rejects: keep the text.
        std::fs::create_dir_all(&dir)?;
        let text = failure.source.unwrap_or_default();
        std::fs::write(dir.join("generated.omr"), text)?;
        std::fs::write(dir.join("README.txt"), failure.finding.to_string())?;
        println!("{}", dir.display());
        return Ok(ExitCode::from(1));
    };
    let meta = Meta::new(
        case.program.profile,
        Some(failure.seed),
        &format!("{} {}", failure.engines[0], failure.engines[1]),
    );
    write_repro(&dir.join("original"), &case, &meta, Some(&failure.finding))?;
    if let Some(text) = &failure.source {
        std::fs::write(dir.join("original").join("generated.omr"), text)?;
    }
    let (case, finding) = if args.no_shrink {
        (case, failure.finding)
    } else {
        eprintln!(
            "shrinking ({} ops, {} scans)...",
            case.program.op_count(),
            case.stimulus.len()
        );
        shrink_quietly(&case, &failure.finding, failure.engines, &cfg.run)
    };
    write_repro(&dir, &case, &meta, Some(&finding))?;
    eprintln!(
        "minimized to {} ops, {} scans:\n{finding}",
        case.program.op_count(),
        case.stimulus.len()
    );
    println!("{}", dir.display());
    Ok(ExitCode::from(1))
}

fn family_name(f: Family) -> &'static str {
    match f {
        Family::S7 => "S7",
        Family::Omron => "Omron",
    }
}

/// Shrinks with the panic hook silenced: candidates that panic are expected and already caught.
fn shrink_quietly(
    case: &Case,
    finding: &stljit_diff::oracle::Finding,
    engines: [EngineKind; 2],
    run: &RunOptions,
) -> (Case, stljit_diff::oracle::Finding) {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut fails = |c: &Case| check_case(c, engines, run, true).err();
    let out = shrink(case, finding, &mut fails, 20_000);
    std::panic::set_hook(hook);
    out
}

fn rate(n: u64, d: Duration) -> f64 {
    n as f64 / d.as_secs_f64().max(1e-9)
}

fn progress_line(t: &Totals, d: Duration) -> String {
    format!(
        "[{:>7.1} s] {} programs ({:.0}/s), {} scans ({:.0}/s), {} ended in STOP ({} fatal)",
        d.as_secs_f64(),
        t.programs,
        rate(t.programs, d),
        t.scans,
        rate(t.scans, d),
        t.stopped,
        t.fatal
    )
}

fn print_summary(report: &campaign::Report, elapsed: Duration, jobs: usize) {
    let t = &report.totals;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "programs {}  scans {}  ops {}  time {:.1} s  programs/s {:.1} ({:.1} per job)  scans/s {:.0}",
        t.programs,
        t.scans,
        t.ops,
        elapsed.as_secs_f64(),
        rate(t.programs, elapsed),
        rate(t.programs, elapsed) / jobs as f64,
        rate(t.scans, elapsed)
    );
    let fatal: Vec<String> = t
        .fatal_codes
        .iter()
        .map(|(&code, n)| match stljit_core::FatalCode::try_from(code) {
            Ok(f) => format!("{n} x {f}"),
            Err(c) => format!("{n} x code {c:#x}"),
        })
        .collect();
    if !fatal.is_empty() {
        let _ = writeln!(out, "fatal endings: {}", fatal.join("; "));
    }
    let s7 = t.programs - t.omron_programs;
    if s7 > 0 {
        let _ = writeln!(
            out,
            "S7 coverage ({s7} programs; generated ops per mnemonic):"
        );
        table(
            &mut out,
            report.coverage.mnemonics.iter().map(|(m, n)| (*m, *n)),
        );
        let missing = report.coverage.missing();
        if !missing.is_empty() {
            let _ = writeln!(out, "never generated: {}", missing.join(" "));
        }
        let kinds: Vec<String> = report
            .coverage
            .operands
            .iter()
            .map(|(k, n)| format!("{k} {n}"))
            .collect();
        let _ = writeln!(out, "operands: {}", kinds.join(", "));
    }
    if t.omron_programs > 0 {
        let c = &report.coverage;
        let _ = writeln!(
            out,
            "Omron coverage ({} programs; generated instructions per form as written):",
            t.omron_programs
        );
        table(
            &mut out,
            c.omron_mnemonics.iter().map(|(m, n)| (m.as_str(), *n)),
        );
        let kinds: Vec<String> = c
            .omron_operands
            .iter()
            .map(|(k, n)| format!("{k} {n}"))
            .collect();
        let _ = writeln!(out, "operands: {}", kinds.join(", "));
        let programs: Vec<String> = c
            .omron_programs
            .iter()
            .map(|(k, n)| format!("{k} {n}"))
            .collect();
        let _ = writeln!(out, "programs: {}", programs.join(", "));
        let missing = c.missing_omron();
        if !missing.is_empty() {
            let _ = writeln!(out, "never generated: {}", missing.join(", "));
        }
    }
}

/// Prints `name count` pairs eight to a line.
fn table<'a>(out: &mut impl std::io::Write, rows: impl Iterator<Item = (&'a str, u64)>) {
    let mut line = String::new();
    for (i, (m, n)) in rows.enumerate() {
        line.push_str(&format!("{m:>9} {n:<8}"));
        if i % 8 == 7 {
            let _ = writeln!(out, "  {}", line.trim_end());
            line.clear();
        }
    }
    if !line.is_empty() {
        let _ = writeln!(out, "  {}", line.trim_end());
    }
}
