//! `stljit bench`: compile and run each program on both engines in this process and print
//! compile time, ns per scan, ns per executed STL instruction and the JIT/interpreter ratio.
//!
//! Executed instructions are counted once by an instrumented JIT build (a counter per op), so
//! the timed runs carry no counting cost. Inputs are a fixed pseudo-random pattern per scan
//! written into the physical input copy, identical for both engines.

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
    /// CPU profile.
    #[arg(long, default_value = "a5")]
    cpu: String,
}

fn inputs(k: u64) -> [u8; 16] {
    let mut x = k.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x5DEE_CE66;
    let mut out = [0u8; 16];
    for b in &mut out {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        *b = (x >> 24) as u8;
    }
    out
}

/// Runs `scans` scans; returns the elapsed time and how many scans ran before a stop.
fn drive(e: &mut dyn Engine, program: &Program, scans: u64, scan_ms: u64) -> (Duration, u64) {
    let mut img = Image::cold_start(program);
    let start = Instant::now();
    let mut done = 0;
    for k in 0..scans {
        img.set_inputs(&inputs(k));
        done += 1;
        if e.scan(&mut img, k * scan_ms) != stljit_core::ScanStatus::Ok {
            break;
        }
    }
    (start.elapsed(), done)
}

fn ns(d: Duration, n: u64) -> f64 {
    d.as_nanos() as f64 / n.max(1) as f64
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let profile = stljit_core::ProfileId::from_name(&args.cpu)
        .ok_or_else(|| anyhow::anyhow!("unknown --cpu `{}`", args.cpu))?;
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
    for path in &args.files {
        let bytes = std::fs::read(path)?;
        let file = stljit_syntax::SourceFile {
            name: path.display().to_string(),
            bytes,
        };
        let c = stljit_syntax::compile(&[file], None, profile);
        let Some(program) = crate::project::checked_program(&c) else {
            return Ok(ExitCode::from(1));
        };
        let t = Instant::now();
        drop(JitProgram::compile(
            program,
            &JitOptions::at(OptLevel::None),
        )?);
        let c_none = t.elapsed();
        let t = Instant::now();
        let mut jit = JitProgram::compile(program, &JitOptions::at(OptLevel::Speed))?;
        let c_speed = t.elapsed();
        let mut counting = JitProgram::compile_counting(program, &JitOptions::default())?;
        let (_, counted_scans) = drive(&mut counting, program, args.scans, args.scan_ms);
        let executed = counting.executed_ops().unwrap_or(0);
        let mut interp = Interpreter::new(program)?;
        let (ti, si) = drive(&mut interp, program, args.scans, args.scan_ms);
        let (tj, sj) = drive(&mut jit, program, args.scans, args.scan_ms);
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
            ns(ti, si),
            ns(tj, sj),
            ns(ti, si) / per_scan_ops.max(1) as f64,
            ns(tj, sj) / per_scan_ops.max(1) as f64,
            ns(ti, si) / ns(tj, sj).max(1e-9),
        );
    }
    println!(
        "(compile times: JitProgram::compile; per-op figures divide by the executed ops per scan \
         counted by an instrumented build)"
    );
    Ok(ExitCode::SUCCESS)
}
