//! `stljit bench`: compile and run each program on both engines in this process and print
//! compile time, ns per scan, ns per executed STL instruction and the JIT/interpreter ratio.
//!
//! Executed instructions are counted once by an instrumented JIT build (a counter per op), so
//! the timed runs carry no counting cost. Inputs are a fixed pseudo-random pattern per scan
//! (computed before timing, 256 rows cycled) written into the physical input copy, identical
//! for both engines.
//!
//! The machine this runs on is usually shared, and other load only ever adds time. So each
//! compile is repeated and the fastest kept, and the scans run in interleaved rounds (a round
//! of the interpreter, then a round of the JIT, each continuing its own image) and each engine's
//! fastest round is reported: both engines see the same background load, and the ratio of the
//! best rounds is stable where one long run per engine is not.

use std::process::ExitCode;
use std::time::{Duration, Instant};
use stljit_core::ir::Program;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};
use stljit_runtime::{Engine, Image};

/// Arguments of `stljit bench`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Program files; each file is benchmarked as a project of its own.
    #[arg(required = true)]
    files: Vec<std::path::PathBuf>,
    /// Scans per engine.
    #[arg(long, default_value_t = 2000)]
    scans: u64,
    /// Virtual time per scan in ms.
    #[arg(long, default_value_t = 10)]
    scan_ms: u64,
    /// Program dialect (see `stljit check --help`; omitted: detected).
    #[arg(long)]
    dialect: Option<String>,
    /// CPU profile (default: the dialect's).
    #[arg(long)]
    cpu: Option<String>,
    /// MicroWIN symbol table used by every program (name<TAB>address, or CSV).
    #[arg(long)]
    symbols: Option<std::path::PathBuf>,
    /// Omron: bcd or binary timers and counters (see `stljit check --help`).
    #[arg(long)]
    tc_mode: Option<String>,
    /// Omron: accept backward jumps (see `stljit check --help`).
    #[arg(long)]
    allow_backward_jumps: bool,
    /// Interleaved rounds the scans are split into (the fastest round per engine is reported).
    #[arg(long, default_value_t = 10)]
    rounds: u64,
    /// Compilations per optimisation level (the fastest is reported).
    #[arg(long, default_value_t = 3)]
    compiles: u32,
    /// Split POUs longer than this many ops into chunk functions (0: never).
    #[arg(long, default_value_t = stljit_jit::DEFAULT_CHUNK_OPS)]
    chunk_ops: usize,
}

/// The input vectors the scans cycle through (scan `k` gets row `k mod` [`INPUT_ROWS`]).
/// Computed once before timing, so that the timed rounds measure the scan, not the harness's
/// pseudo-random generator (which cost about as much as an empty program's whole scan).
const INPUT_ROWS: usize = 256;

/// The input rows: a fixed xorshift pattern, the same for every engine and every run.
fn input_rows() -> Vec<[u8; 16]> {
    (0..INPUT_ROWS as u64)
        .map(|k| {
            let mut x = k.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x5DEE_CE66;
            let mut out = [0u8; 16];
            for b in &mut out {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                *b = (x >> 24) as u8;
            }
            out
        })
        .collect()
}

/// One engine being benchmarked: its image and how far it got.
struct Run<'a> {
    engine: &'a mut dyn Engine,
    inputs: &'a [[u8; 16]],
    img: Image,
    next_scan: u64,
    stopped: bool,
    /// The fastest round so far, in ns per scan.
    best: f64,
}

impl<'a> Run<'a> {
    fn new(engine: &'a mut dyn Engine, inputs: &'a [[u8; 16]], program: &Program) -> Self {
        Run {
            engine,
            inputs,
            img: Image::cold_start(program),
            next_scan: 0,
            stopped: false,
            best: f64::INFINITY,
        }
    }

    /// Runs up to `scans` more scans (fewer if the program stops) and records the round's
    /// time per scan.
    fn round(&mut self, scans: u64, scan_ms: u64) {
        if self.stopped {
            return;
        }
        let start = Instant::now();
        let mut done = 0;
        for _ in 0..scans {
            let k = self.next_scan;
            self.img
                .set_inputs(&self.inputs[k as usize % self.inputs.len()]);
            self.next_scan += 1;
            done += 1;
            if self.engine.scan(&mut self.img, k * scan_ms) != stljit_core::ScanStatus::Ok {
                self.stopped = true;
                break;
            }
        }
        self.best = self.best.min(ns(start.elapsed(), done));
    }
}

/// The fastest of `n` runs of `f` and the last result.
fn fastest<T>(n: u32, mut f: impl FnMut() -> anyhow::Result<T>) -> anyhow::Result<(Duration, T)> {
    let mut best = Duration::MAX;
    let mut last = None;
    for _ in 0..n.max(1) {
        let t = Instant::now();
        let r = f()?;
        best = best.min(t.elapsed());
        last = Some(r);
    }
    let last = last.ok_or_else(|| anyhow::anyhow!("no compilation ran"))?;
    Ok((best, last))
}

fn ns(d: Duration, n: u64) -> f64 {
    d.as_nanos() as f64 / n.max(1) as f64
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    println!(
        "{:<34} {:>7} {:>10} {:>10} {:>11} {:>11} {:>9} {:>9} {:>8}",
        "program",
        "ops",
        "jit none",
        "jit speed",
        "interp/scan",
        "jit/scan",
        "interp/op",
        "jit/op",
        "speedup"
    );
    let rows = input_rows();
    for path in &args.files {
        let input = crate::check::Input {
            files: vec![path.clone()],
            dialect: args.dialect.clone(),
            cpu: args.cpu.clone(),
            symbols: args.symbols.clone(),
            tc_mode: args.tc_mode.clone(),
            allow_backward_jumps: args.allow_backward_jumps,
            chosen: Default::default(),
        };
        let c = input.compile()?;
        let Some(program) = crate::project::checked_program(&c) else {
            return Ok(ExitCode::from(1));
        };
        let opts = |opt| JitOptions {
            opt,
            chunk_ops: args.chunk_ops,
            ..JitOptions::default()
        };
        let compile = |opt| Ok(JitProgram::compile(program, &opts(opt))?);
        let (c_none, _) = fastest(args.compiles, || compile(OptLevel::None))?;
        let (c_speed, mut jit) = fastest(args.compiles, || compile(OptLevel::Speed))?;
        let mut counting = JitProgram::compile_counting(program, &opts(OptLevel::None))?;
        let mut counted = Run::new(&mut counting, &rows, program);
        counted.round(args.scans, args.scan_ms);
        let counted_scans = counted.next_scan;
        let executed = counting.executed_ops().unwrap_or(0);
        let mut interp = Interpreter::new(program)?;
        let mut ri = Run::new(&mut interp, &rows, program);
        let mut rj = Run::new(&mut jit, &rows, program);
        let rounds = args.rounds.clamp(1, args.scans.max(1));
        for _ in 0..rounds {
            ri.round(args.scans / rounds, args.scan_ms);
            rj.round(args.scans / rounds, args.scan_ms);
        }
        let (ni, nj) = (ri.best, rj.best);
        let per_scan_ops = executed / counted_scans.max(1);
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        println!(
            "{:<34} {:>7} {:>8.1}ms {:>8.1}ms {:>9.0}ns {:>9.0}ns {:>7.2}ns {:>7.3}ns {:>7.1}x",
            name,
            program.op_count(),
            c_none.as_secs_f64() * 1e3,
            c_speed.as_secs_f64() * 1e3,
            ni,
            nj,
            ni / per_scan_ops.max(1) as f64,
            nj / per_scan_ops.max(1) as f64,
            ni / nj.max(1e-9),
        );
    }
    println!(
        "(compile: fastest of {} JitProgram::compile; scans: fastest of {} interleaved rounds per \
         engine, JIT at --opt speed; per-op figures divide by the executed ops per scan counted \
         by an instrumented build)",
        args.compiles, args.rounds
    );
    Ok(ExitCode::SUCCESS)
}
