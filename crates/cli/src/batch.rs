//! `stljit run` over many runs: several stimulus files (`--inputs a.csv b.csv ...`) and/or
//! parameter sweeps (`--sweep VW100=10,20,30`), on every core (`--jobs`), one shard of the list
//! (`--shard K/N`), one CSV trace per run in `--out-dir`.
//!
//! The list of runs is fixed by the command line alone: every stimulus file (in the order given)
//! times every combination of sweep values (the first `--sweep` varying slowest). Run `i` is
//! written to `<out-dir>/<i>_<stimulus stem>[__<addr>=<value>...].csv` and belongs to shard
//! `i mod N`. Each worker compiles the program once and cold-starts it for every run, so a run's
//! file does not depend on the job count, the shard, or which worker ran it; the summary on stdout
//! (one CSV row per run: name, scans, outcome, the watched values after the last scan) is printed
//! in run order once all runs are done.

use crate::run::Args;
use anyhow::Context as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use stljit_api::{Compiled, Handle, Options, Outcome, Plc, Run, Until};
use stljit_sim::{CsvTrace, Stimulus, ValueKind, WatchSpec, parse_value};

/// One `--sweep ADDR=V1,V2,...`.
struct Sweep {
    name: String,
    handle: Handle,
    /// `(as written, raw bits)`.
    values: Vec<(String, u32)>,
}

/// One run of the batch.
struct Job {
    index: usize,
    file: String,
    stimulus: usize,
    /// Index into each sweep's values.
    choice: Vec<usize>,
}

/// What a run left, for the summary.
struct Done {
    scans: u64,
    outcome: Outcome,
    values: Vec<String>,
}

fn parse_sweep(text: &str, compiled: &Compiled) -> anyhow::Result<Sweep> {
    let (name, list) = text
        .split_once('=')
        .with_context(|| format!("--sweep `{text}`: expected ADDR=V1,V2,..."))?;
    let name = name.trim();
    let handle = compiled
        .handle(name)
        .map_err(|e| anyhow::anyhow!("--sweep `{text}`: {e}"))?;
    handle
        .check_writable()
        .map_err(|e| anyhow::anyhow!("--sweep `{text}`: {e}"))?;
    let kind = ValueKind::of(handle.address());
    let values = list
        .split(',')
        .map(|v| {
            let raw = parse_value(v, kind)
                .map_err(|e| anyhow::anyhow!("--sweep `{text}`: value `{}`: {e}", v.trim()))?;
            Ok((v.trim().to_string(), raw))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok(Sweep {
        name: name.to_string(),
        handle,
        values,
    })
}

/// A file-name-safe version of `s`.
fn safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_alphanumeric() || matches!(c, '-' | '.' | '=' | '+') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Every run, in order: stimulus files outermost, then the sweeps' combinations.
fn jobs(stems: &[String], sweeps: &[Sweep]) -> Vec<Job> {
    let mut combos: Vec<Vec<usize>> = vec![Vec::new()];
    for s in sweeps {
        combos = combos
            .into_iter()
            .flat_map(|c| {
                (0..s.values.len()).map(move |v| {
                    let mut c = c.clone();
                    c.push(v);
                    c
                })
            })
            .collect();
    }
    let total = stems.len() * combos.len();
    let width = total.saturating_sub(1).to_string().len();
    let mut out = Vec::with_capacity(total);
    for (si, stem) in stems.iter().enumerate() {
        for choice in &combos {
            let index = out.len();
            let mut name = format!("{index:0width$}_{}", safe(stem));
            for (s, &v) in sweeps.iter().zip(choice) {
                name += &format!("__{}={}", safe(&s.name), safe(&s.values[v].0));
            }
            out.push(Job {
                index,
                file: name + ".csv",
                stimulus: si,
                choice: choice.clone(),
            });
        }
    }
    out
}

/// Runs the batch the arguments describe.
pub(crate) fn main(
    args: &Args,
    compiled: Arc<Compiled>,
    stimuli: Vec<(String, Stimulus)>,
    watch: Vec<WatchSpec>,
    options: Options,
    until: Until,
) -> anyhow::Result<ExitCode> {
    let out_dir: PathBuf = args
        .out_dir
        .clone()
        .context("a batch writes one result file per run: give --out-dir DIR")?;
    if args.trace.is_some() {
        anyhow::bail!("--trace names one file; a batch writes one per run into --out-dir");
    }
    let sweeps = args
        .sweep
        .iter()
        .map(|s| parse_sweep(s, &compiled))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let stems: Vec<String> = stimuli.iter().map(|(s, _)| s.clone()).collect();
    let (k, n) = args.shard.unwrap_or((0, 1));
    let list: Vec<Job> = jobs(&stems, &sweeps)
        .into_iter()
        .filter(|j| j.index as u64 % n == k)
        .collect();
    std::fs::create_dir_all(&out_dir)
        .with_context(|| format!("cannot create {}", out_dir.display()))?;
    let workers = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |p| p.get()))
        .clamp(1, list.len().max(1));
    eprintln!(
        "batch: {} run(s) of {} (shard {k}/{n}) on {workers} job(s), results in {}",
        list.len(),
        stems.len() * sweeps.iter().map(|s| s.values.len()).product::<usize>(),
        out_dir.display()
    );

    static CANCEL: AtomicBool = AtomicBool::new(false);
    let _ = ctrlc::set_handler(|| CANCEL.store(true, Ordering::Relaxed));
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<anyhow::Result<Done>>>> =
        Mutex::new((0..list.len()).map(|_| None).collect());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                let mut plc = match Plc::new(compiled.clone(), &options) {
                    Ok(p) => Some(p),
                    Err(e) => {
                        let mut r = results.lock().unwrap_or_else(|p| p.into_inner());
                        if let Some(slot) = r.iter_mut().find(|s| s.is_none()) {
                            *slot = Some(Err(e.into()));
                        }
                        None
                    }
                };
                while let Some(plc) = plc.as_mut() {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(job) = list.get(i) else { break };
                    if CANCEL.load(Ordering::Relaxed) {
                        break;
                    }
                    let done = run_one(plc, job, &sweeps, &stimuli, &watch, until, &out_dir);
                    results.lock().unwrap_or_else(|p| p.into_inner())[i] = Some(done);
                }
            });
        }
    });

    let results = results.into_inner().unwrap_or_else(|p| p.into_inner());
    let mut stdout = std::io::stdout().lock();
    let mut header = vec!["run".to_string(), "scans".into(), "outcome".into()];
    header.extend(watch.iter().map(|w| w.text.clone()));
    writeln!(stdout, "{}", header.join(","))?;
    let mut fatal = false;
    for (job, result) in list.iter().zip(results) {
        let name = job.file.trim_end_matches(".csv");
        match result {
            Some(Ok(d)) => {
                fatal |= matches!(d.outcome, Outcome::Fatal { .. });
                let mut row = vec![name.to_string(), d.scans.to_string(), d.outcome.to_string()];
                row.extend(d.values);
                writeln!(stdout, "{}", row.join(","))?;
            }
            Some(Err(e)) => anyhow::bail!("run {name}: {e:#}"),
            None => writeln!(stdout, "{name},0,not run (cancelled)")?,
        }
    }
    Ok(if fatal {
        ExitCode::from(3)
    } else {
        ExitCode::SUCCESS
    })
}

fn run_one(
    plc: &mut Plc,
    job: &Job,
    sweeps: &[Sweep],
    stimuli: &[(String, Stimulus)],
    watch: &[WatchSpec],
    until: Until,
    out_dir: &std::path::Path,
) -> anyhow::Result<Done> {
    plc.reset();
    for (s, &v) in sweeps.iter().zip(&job.choice) {
        plc.set_raw(&s.handle, s.values[v].1)?;
    }
    let path = out_dir.join(&job.file);
    let file = std::fs::File::create(&path)
        .with_context(|| format!("cannot create {}", path.display()))?;
    let mut trace = CsvTrace::new(std::io::BufWriter::new(file), watch.to_vec())?;
    // A started run completes (Ctrl-C stops the batch between runs): every file is a whole run.
    let report = plc.simulate(
        Run::new(until)
            .stimulus(&stimuli[job.stimulus].1)
            .observer(&mut trace),
    )?;
    trace
        .finish()?
        .into_inner()
        .map_err(|e| e.into_error())
        .with_context(|| format!("cannot write {}", path.display()))?
        .sync_all()
        .ok();
    let values = watch
        .iter()
        .map(|w| w.read(plc.image()).map_or("?".into(), |v| w.format(v)))
        .collect();
    Ok(Done {
        scans: report.scans,
        outcome: report.outcome,
        values,
    })
}

#[cfg(test)]
mod tests {
    use super::safe;

    #[test]
    fn file_names_keep_only_safe_characters() {
        assert_eq!(safe("VD100:real"), "VD100_real");
        assert_eq!(safe("a b/c"), "a_b_c");
        assert_eq!(safe("-1.5"), "-1.5");
    }
}
