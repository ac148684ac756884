//! `stljit run`: simulate a program on virtual time with either engine.
//!
//! The run goes through the embedding API (`stljit_api::Plc`), as every other tool that drives
//! a PLC does. Scan k starts at k × scan time. Several stimulus files or a parameter sweep make
//! a batch of runs on every core (`crate::batch`). A stimulus file drives inputs, HMI writes,
//! high-speed counter steps and received bytes (`stljit_sim::stimulus`), `--watch` prints one
//! CSV row per scan, `--trace` writes a CSV or VCD file. Exit codes: 0 ok, 1 program errors,
//! 2 usage or stimulus errors, 3 the PLC stopped on a fatal runtime error.

use crate::check::Input;
use crate::duration::parse_duration;
use crate::engines::{EngineKind, OptArg};
use anyhow::{Context as _, bail};
use std::io::{IsTerminal as _, Write as _};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};
use stljit_api::used::{self, Names};
use stljit_api::{Compiled, Options, Plc, Run};
use stljit_core::ir::{Address, Program};
use stljit_runtime::Image;
use stljit_sim::{
    CsvTrace, Observer, Outcome, Progress, RunReport, ScanEvent, Stimulus, TimeBase, Until,
    VcdTrace, WatchSpec,
};

/// Arguments of `stljit run`.
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(flatten)]
    input: Input,
    /// Engine: the Cranelift JIT (default) or the reference interpreter.
    #[arg(long, value_enum, default_value = "jit")]
    engine: EngineKind,
    /// JIT optimisation: `none` compiles fastest, `speed` runs fastest.
    #[arg(long, value_enum, default_value = "speed")]
    opt: OptArg,
    /// Number of scans to run (default 100 when no --for is given).
    #[arg(long, conflicts_with = "duration")]
    scans: Option<u64>,
    /// Virtual time to run, e.g. 500ms, 1.5s, 2m, 24h.
    #[arg(long = "for", value_name = "DURATION", value_parser = parse_duration)]
    duration: Option<u64>,
    /// Virtual time per scan.
    #[arg(long, value_name = "DURATION", default_value = "10ms", value_parser = parse_duration)]
    scan_time: u64,
    /// Stimulus CSV: `scan,ADDR,...` or `t_ms,ADDR,...`; columns `HSC0`..`HSC5` give a
    /// high-speed counter's steps per scan interval, `PORT0`/`PORT1` the bytes a serial port
    /// receives (`16#4F4B0D`). Several files make a batch: one run per file.
    #[arg(long, value_name = "STIMULUS.csv", num_args = 1.., action = clap::ArgAction::Append)]
    inputs: Vec<PathBuf>,
    /// A parameter sweep, ADDR=V1,V2,...: one run per value, written like an HMI write before
    /// the first scan (several --sweep: every combination). Makes a batch.
    #[arg(long, value_name = "ADDR=V1,V2,...")]
    pub(crate) sweep: Vec<String>,
    /// Batch: the directory that gets one CSV trace per run (of --watch, or of every I/Q/M bit
    /// the program uses), named by run.
    #[arg(long, value_name = "DIR")]
    pub(crate) out_dir: Option<PathBuf>,
    /// Batch: worker threads (default: every core).
    #[arg(long)]
    pub(crate) jobs: Option<usize>,
    /// Batch: run only shard K of N (run i belongs to shard i mod N), e.g. 0/4.
    #[arg(long, value_parser = crate::shard::parse_shard)]
    pub(crate) shard: Option<(u64, u64)>,
    /// Addresses to print after each scan, e.g. `Q0.0,VW10,VD50:real,T37`.
    #[arg(long, value_delimiter = ',', value_name = "ADDR,...")]
    watch: Vec<String>,
    /// Write the watched addresses (all I/Q/M bits the program uses when no --watch) to a
    /// `.vcd` or `.csv` file.
    #[arg(long, value_name = "OUT.vcd|OUT.csv")]
    pub(crate) trace: Option<PathBuf>,
    /// Add scan-time figures (wall clock per scan) to the summary.
    #[arg(long)]
    stats: bool,
    /// The date and time the real-time clock shows at the first scan, `YYYY-MM-DD` or
    /// `YYYY-MM-DD HH:MM:SS` (default 2000-01-01 00:00:00); it then runs on virtual time.
    #[arg(long, value_name = "DATE", value_parser = stljit_runtime::rtc::DateTime::parse)]
    start_time: Option<stljit_runtime::rtc::DateTime>,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let compiled = Arc::new(args.input.compiled()?);
    let Some(program) = crate::project::checked_program(compiled.compilation()) else {
        return Ok(ExitCode::from(1));
    };
    let profile = program.profile.profile();
    let resolve = |name: &str| compiled.resolve(name);
    let mut stimuli = Vec::new();
    for path in &args.inputs {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let stimulus = Stimulus::parse(&text, profile, &resolve)
            .map_err(|e| anyhow::anyhow!("{}:{e}", path.display()))?;
        let stem = path
            .file_stem()
            .map_or_else(|| "run".into(), |s| s.to_string_lossy().into_owned());
        stimuli.push((stem, stimulus));
    }
    if stimuli.is_empty() {
        stimuli.push(("run".to_string(), Stimulus::empty(TimeBase::Scan, profile)));
    }
    let layout = stljit_core::Layout::new(profile);
    let batch = args.is_batch();
    let watch = watch_list(&args, program, &compiled, &resolve, &layout, batch)?;
    let options = Options {
        engine: args.engine.into(),
        opt: args.opt.into(),
        scan_ms: args.scan_time,
        clock_start: args.start_time,
    };
    let until = match (args.scans, args.duration) {
        (Some(n), _) => Until::Scans(n),
        (None, Some(ms)) => Until::Duration(ms),
        (None, None) => Until::Scans(100),
    };
    if options.scan_ms == 0 {
        anyhow::bail!("scan time must be at least 1 ms");
    }
    if batch {
        return crate::batch::main(&args, compiled.clone(), stimuli, watch, options, until);
    }
    let stimulus = &stimuli[0].1;
    let mut plc = Plc::new(compiled.clone(), &options)?;

    // Ctrl-C stops the run between two scans; the trace collected so far is still written.
    static CANCEL: AtomicBool = AtomicBool::new(false);
    let _ = ctrlc::set_handler(|| CANCEL.store(true, Ordering::Relaxed));
    let mut bar = ProgressBar::new(std::io::stderr().is_terminal());
    let mut progress = |p: Progress| bar.update(p);
    let mut stats = ScanStats::default();
    let mut stdout = std::io::stdout().lock();
    let report = {
        let mut observers: Vec<Box<dyn Observer + '_>> = Vec::new();
        if args.stats {
            observers.push(Box::new(&mut stats));
        }
        match (&args.trace, args.watch.is_empty()) {
            (Some(path), _) => observers.push(trace_writer(path, &watch, &scope_name(&args))?),
            (None, false) => observers.push(Box::new(CsvTrace::new(&mut stdout, watch.clone())?)),
            (None, true) => {}
        }
        let mut all = Fanout(observers);
        let run = Run::new(until)
            .stimulus(stimulus)
            .observer(&mut all)
            .cancel(&CANCEL)
            .progress(&mut progress);
        let report = plc.simulate(run).map_err(sim_error)?;
        all.finish()?;
        report
    };
    summarise(&args, program, &compiled, &report, plc.image(), &stats);
    bar.clear();
    Ok(match report.outcome {
        Outcome::Fatal { .. } => ExitCode::from(3),
        _ => ExitCode::SUCCESS,
    })
}

/// A simulation error as the CLI reported it before the API existed (the `SimError` itself, so
/// its cause is printed once).
fn sim_error(e: stljit_api::Error) -> anyhow::Error {
    match e {
        stljit_api::Error::Sim(e) => e.into(),
        other => other.into(),
    }
}

impl Args {
    /// Whether the arguments ask for a batch (several stimulus files, a sweep, or a batch option).
    fn is_batch(&self) -> bool {
        self.inputs.len() > 1
            || !self.sweep.is_empty()
            || self.out_dir.is_some()
            || self.jobs.is_some()
            || self.shard.is_some()
    }
}

/// The watch list: `--watch` as given, or for a trace (or a batch's traces) without one, every
/// I/Q/M bit the program reads or writes.
fn watch_list(
    args: &Args,
    program: &Program,
    compiled: &Compiled,
    resolve: &dyn Fn(&str) -> Result<Address, String>,
    layout: &stljit_core::Layout,
    batch: bool,
) -> anyhow::Result<Vec<WatchSpec>> {
    let names: Vec<String> = if args.watch.is_empty() && (args.trace.is_some() || batch) {
        let names: Names = compiled.names();
        used::io_bits(program)
            .into_iter()
            .map(|b| names.watch_name(&Address::Bit(b)))
            .collect()
    } else {
        args.watch.clone()
    };
    names
        .iter()
        .map(|n| {
            let spec = WatchSpec::parse(n, resolve).map_err(|e| anyhow::anyhow!("--watch: {e}"))?;
            spec.check(layout)
                .map_err(|e| anyhow::anyhow!("--watch: {e}"))?;
            Ok(spec)
        })
        .collect()
}

/// The VCD scope: the first program file's stem (`traffic_light`).
fn scope_name(args: &Args) -> String {
    args.input
        .files
        .first()
        .and_then(|f| f.file_stem())
        .map_or_else(|| "plc".to_string(), |s| s.to_string_lossy().into_owned())
}

fn trace_writer<'a>(
    path: &std::path::Path,
    watch: &[WatchSpec],
    scope: &str,
) -> anyhow::Result<Box<dyn Observer + 'a>> {
    let file =
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let out = std::io::BufWriter::new(file);
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("vcd") => {
            Ok(Box::new(VcdTrace::new(out, watch.to_vec(), scope)?))
        }
        Some(e) if e.eq_ignore_ascii_case("csv") => {
            Ok(Box::new(CsvTrace::new(out, watch.to_vec())?))
        }
        _ => bail!("--trace: {} must end in .vcd or .csv", path.display()),
    }
}

/// Every observer sees every scan; `finish` flushes them.
struct Fanout<'a>(Vec<Box<dyn Observer + 'a>>);

impl Observer for Fanout<'_> {
    fn observe(&mut self, event: &ScanEvent<'_>) -> std::io::Result<()> {
        self.0.iter_mut().try_for_each(|o| o.observe(event))
    }

    fn needs_every_scan(&self) -> bool {
        self.0.iter().any(|o| o.needs_every_scan())
    }

    fn changes_of(
        &self,
        layout: &stljit_core::layout::Layout,
    ) -> Option<Vec<std::ops::Range<usize>>> {
        stljit_sim::driver::changes_of_all(
            self.0.iter().map(|o| o.as_ref() as &dyn Observer),
            layout,
        )
    }
}

impl Fanout<'_> {
    fn finish(self) -> std::io::Result<()> {
        drop(self.0);
        std::io::stdout().flush()
    }
}

/// Wall-clock time between consecutive scans, for `--stats`.
#[derive(Default)]
struct ScanStats {
    last: Option<Instant>,
    samples: Vec<Duration>,
}

impl Observer for &mut ScanStats {
    fn observe(&mut self, _: &ScanEvent<'_>) -> std::io::Result<()> {
        let now = Instant::now();
        if let Some(last) = self.last.replace(now) {
            self.samples.push(now - last);
        }
        Ok(())
    }
}

impl ScanStats {
    fn summary(&self) -> Option<String> {
        let mut s = self.samples.clone();
        if s.is_empty() {
            return None;
        }
        s.sort_unstable();
        let pick = |q: f64| s[((s.len() - 1) as f64 * q) as usize];
        let total: Duration = s.iter().sum();
        Some(format!(
            "scan time (wall, {} scans): mean {:?}, p50 {:?}, p99 {:?}, max {:?}",
            s.len(),
            total / u32::try_from(s.len()).unwrap_or(u32::MAX),
            pick(0.5),
            pick(0.99),
            s[s.len() - 1]
        ))
    }
}

fn summarise(
    args: &Args,
    program: &Program,
    compiled: &Compiled,
    report: &RunReport,
    image: &Image,
    stats: &ScanStats,
) {
    let mut err = std::io::stderr().lock();
    let _ = writeln!(
        err,
        "{} scans on the {} engine, virtual time {} ({}), scan time {} ms",
        report.scans,
        args.engine.name(),
        crate::duration::format_ms(report.t_ms.saturating_add(if report.scans > 0 {
            args.scan_time
        } else {
            0
        })),
        report.outcome,
        args.scan_time,
    );
    if let Outcome::Fatal { .. } = report.outcome {
        let _ = writeln!(
            err,
            "PLC stopped: {} at {}",
            report.outcome,
            site(program, image)
        );
    }
    let last = image.last_error();
    if last != 0 {
        let name = stljit_core::ErrorCode::try_from(last)
            .map_or_else(|raw| format!("error 16#{raw:04X}"), |c| c.to_string());
        let _ = writeln!(
            err,
            "last non-fatal error: {name} at {}",
            site(program, image)
        );
    }
    if args.watch.is_empty() {
        let outputs = used::outputs(program);
        if !outputs.is_empty() {
            let _ = writeln!(err, "outputs after the last scan:");
            let names = compiled.names();
            for (name, value) in used::describe(&outputs, image, &names) {
                let _ = writeln!(err, "  {name:<24} {value}");
            }
        }
    }
    if let Some(s) = stats.summary() {
        let _ = writeln!(err, "{s}");
    }
}

/// `file:line` of the instruction that raised the image's last error.
fn site(program: &Program, image: &Image) -> String {
    let (pou, op) = image.error_site();
    program
        .pous
        .get(usize::from(pou))
        .and_then(|p| p.locs.get(op as usize).map(|l| (p, l)))
        .map_or_else(
            || "an unknown instruction".to_string(),
            |(p, l)| {
                let file = program
                    .files
                    .get(l.file.index())
                    .map_or("?", String::as_str);
                format!("{file}:{}:{} (in {})", l.line, l.col, p.name)
            },
        )
}

/// A one-line progress bar on stderr, redrawn at most every 100 ms, only on a terminal.
struct ProgressBar {
    enabled: bool,
    last: Option<Instant>,
    drawn: bool,
}

impl ProgressBar {
    fn new(enabled: bool) -> ProgressBar {
        ProgressBar {
            enabled,
            last: None,
            drawn: false,
        }
    }

    fn update(&mut self, p: Progress) {
        if !self.enabled || p.total < 10_000 {
            return;
        }
        let now = Instant::now();
        if self
            .last
            .is_some_and(|t| now - t < Duration::from_millis(100))
        {
            return;
        }
        self.last = Some(now);
        let width = 30u64;
        let filled = (p.done * width / p.total.max(1)) as usize;
        let bar = "#".repeat(filled) + &"-".repeat(width as usize - filled);
        eprint!(
            "\r[{bar}] {:>3}%  t = {}",
            p.done * 100 / p.total.max(1),
            crate::duration::format_ms(p.t_ms)
        );
        self.drawn = true;
    }

    fn clear(&mut self) {
        if self.drawn {
            eprint!("\r{:60}\r", "");
        }
    }
}
