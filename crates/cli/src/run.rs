//! `stljit run`: simulate a program on virtual time with either engine.
//!
//! Scan k starts at k × scan time. A stimulus file drives inputs and HMI writes, `--watch` prints
//! one CSV row per scan, `--trace` writes a CSV or VCD file. Exit codes: 0 ok, 1 program errors,
//! 2 usage or stimulus errors, 3 the PLC stopped on a fatal runtime error.

use crate::check::Input;
use crate::duration::parse_duration;
use crate::engines::{EngineKind, OptArg, build_engine};
use anyhow::{Context as _, bail};
use std::io::{IsTerminal as _, Write as _};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};
use stljit_core::ir::{Address, Program};
use stljit_front::{Compilation, Dialect};
use stljit_runtime::Image;
use stljit_sim::{
    CsvTrace, Observer, Outcome, Progress, RunReport, ScanEvent, Simulation, Stimulus, TimeBase,
    Until, VcdTrace, WatchSpec,
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
    /// Stimulus CSV: `scan,ADDR,...` or `t_ms,ADDR,...`.
    #[arg(long, value_name = "STIMULUS.csv")]
    inputs: Option<PathBuf>,
    /// Addresses to print after each scan, e.g. `Q0.0,VW10,VD50:real,T37`.
    #[arg(long, value_delimiter = ',', value_name = "ADDR,...")]
    watch: Vec<String>,
    /// Write the watched addresses (all I/Q/M bits the program uses when no --watch) to a
    /// `.vcd` or `.csv` file.
    #[arg(long, value_name = "OUT.vcd|OUT.csv")]
    trace: Option<PathBuf>,
    /// Add scan-time figures (wall clock per scan) to the summary.
    #[arg(long)]
    stats: bool,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let compilation = args.input.compile()?;
    let Some(program) = crate::project::checked_program(&compilation) else {
        return Ok(ExitCode::from(1));
    };
    let dialect = args.input.dialect()?;
    let profile = program.profile.profile();
    let resolve = |name: &str| -> Result<Address, String> {
        dialect
            .parse_address(name, program.profile, compilation.symbols.as_ref())
            .map_err(|e| e.to_string())
    };
    let stimulus = match &args.inputs {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            Stimulus::parse(&text, profile, &resolve)
                .map_err(|e| anyhow::anyhow!("{}:{e}", path.display()))?
        }
        None => Stimulus::empty(TimeBase::Scan, profile),
    };
    let layout = stljit_core::Layout::new(profile);
    let watch = watch_list(&args, program, (dialect, &compilation), &resolve, &layout)?;
    let mut engine = build_engine(args.engine, args.opt, program)?;
    let until = match (args.scans, args.duration) {
        (Some(n), _) => Until::Scans(n),
        (None, Some(ms)) => Until::Duration(ms),
        (None, None) => Until::Scans(100),
    };

    // Ctrl-C stops the run between two scans; the trace collected so far is still written.
    static CANCEL: AtomicBool = AtomicBool::new(false);
    let _ = ctrlc::set_handler(|| CANCEL.store(true, Ordering::Relaxed));
    let mut bar = ProgressBar::new(std::io::stderr().is_terminal());
    let mut progress = |p: Progress| bar.update(p);
    let mut stats = ScanStats::default();
    let mut stdout = std::io::stdout().lock();
    let report = {
        let mut sim = Simulation::new(engine.as_mut(), Image::cold_start(program), args.scan_time)?
            .with_cancel(&CANCEL)
            .with_progress(&mut progress);
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
        let report = sim.run(until, &stimulus, &mut all)?;
        all.finish()?;
        summarise(
            &args,
            program,
            (dialect, &compilation),
            &report,
            sim.image(),
            &stats,
        );
        report
    };
    bar.clear();
    Ok(match report.outcome {
        Outcome::Fatal { .. } => ExitCode::from(3),
        _ => ExitCode::SUCCESS,
    })
}

/// The watch list: `--watch` as given, or for a trace without one, every I/Q/M bit the program
/// reads or writes.
fn watch_list(
    args: &Args,
    program: &Program,
    (dialect, compilation): (Dialect, &Compilation),
    resolve: &dyn Fn(&str) -> Result<Address, String>,
    layout: &stljit_core::Layout,
) -> anyhow::Result<Vec<WatchSpec>> {
    let names: Vec<String> = if args.watch.is_empty() && args.trace.is_some() {
        let names = crate::used::Names::new(program, dialect, compilation.symbols.as_ref());
        crate::used::io_bits(program)
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
    (dialect, compilation): (Dialect, &Compilation),
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
        let outputs = crate::used::outputs(program);
        if !outputs.is_empty() {
            let _ = writeln!(err, "outputs after the last scan:");
            let names = crate::used::Names::new(program, dialect, compilation.symbols.as_ref());
            for (name, value) in crate::used::describe(&outputs, image, &names) {
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
