//! `stljit diff`: run one user program on the interpreter and the JIT side by side with random
//! stimulus (input bits toggling, analog inputs, HMI writes, irregular scan times) and compare the
//! whole image after every scan.
//!
//! Exit codes: 0 the engines agree, 1 they diverge (a reproducer is written when `--out` is
//! given), 2 usage errors or a program that does not compile.

use crate::engines::OptArg;
use std::process::ExitCode;
use stljit_core::layout::DEFAULT_LOOP_LIMIT;
use stljit_diff::campaign::check_case;
use stljit_diff::engines::EngineKind;
use stljit_diff::generate::{Case, stimulus};
use stljit_diff::oracle::RunOptions;
use stljit_diff::repro::{Meta, write_repro};
use stljit_diff::rng::Choices;

/// Arguments of `stljit diff`.
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(flatten)]
    input: crate::check::Input,
    /// Scans to run.
    #[arg(long, default_value_t = 1000)]
    scans: u32,
    /// Seed of the random stimulus.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// JIT optimisation level.
    #[arg(long, value_enum, default_value = "speed")]
    opt: OptArg,
    /// Loop budget per scan (the watchdog).
    #[arg(long, default_value_t = DEFAULT_LOOP_LIMIT)]
    loop_limit: u32,
    /// Write a reproducer directory here when the engines diverge.
    #[arg(long)]
    out: Option<std::path::PathBuf>,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let c = args.input.compile()?;
    let Some(program) = crate::project::checked_program(&c) else {
        return Ok(ExitCode::from(2));
    };
    let mut choices = Choices::from_seed(args.seed);
    let case = Case {
        stimulus: stimulus::for_program(&mut choices, program, args.scans),
        program: program.clone(),
    };
    let engines = [EngineKind::Interp, EngineKind::Jit(args.opt.into())];
    let run = RunOptions {
        loop_limit: args.loop_limit,
        ..RunOptions::default()
    };
    match check_case(&case, engines, &run, false) {
        Ok(stats) => {
            println!(
                "{} and {} agree on {} scans (seed {}){}",
                engines[0],
                engines[1],
                stats.scans,
                args.seed,
                if stats.fatal {
                    ", ending in a fatal error"
                } else if stats.stopped {
                    ", ending in STOP"
                } else {
                    ""
                }
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(finding) => {
            println!("{finding}");
            if let Some(dir) = &args.out {
                let mut meta = Meta::new(
                    program.profile,
                    None,
                    &format!("{} {}", engines[0], engines[1]),
                );
                meta.loop_limit = args.loop_limit;
                write_repro(dir, &case, &meta, Some(&finding))?;
                println!("reproducer: {}", dir.display());
            }
            Ok(ExitCode::from(1))
        }
    }
}
