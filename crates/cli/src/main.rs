//! The `stljit` command line. Each subcommand lives in its own module with its own `Args`;
//! this file only dispatches. Exit codes: 0 success, 1 program errors, 2 usage or input errors,
//! 3 the PLC stopped on a fatal runtime error.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod batch;
mod bench;
mod check;
mod diff;
mod dump_clif;
mod dump_ir;
mod duration;
mod engines;
mod fmu;
mod fuzz;
mod project;
mod run;
mod shard;

/// Compile PLC statement-list programs to native code, run them on virtual time, and prove the
/// JIT equal to the reference interpreter.
#[derive(Parser)]
#[command(name = "stljit", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Check programs and report every diagnostic.
    Check(check::Args),
    /// Print the checked IR, one op per line with its source line.
    DumpIr(dump_ir::Args),
    /// Print the annotated Cranelift IR the JIT generates.
    DumpClif(dump_clif::Args),
    /// Compare JIT and interpreter speed (compile time, ns per scan and per instruction).
    Bench(bench::Args),
    /// Simulate programs on virtual time (JIT by default) with stimulus, watch and trace.
    Run(run::Args),
    /// Run one program on the interpreter and the JIT side by side with random stimulus.
    Diff(diff::Args),
    /// Differential fuzzing: generated programs on the JIT and the interpreter, compared.
    Fuzz(fuzz::Args),
    /// Export programs as an FMI 2.0 co-simulation FMU.
    Fmu(fmu::Args),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    let result = match cli.command {
        Command::Check(args) => check::main(args),
        Command::DumpIr(args) => dump_ir::main(args),
        Command::Run(args) => run::main(args),
        Command::Diff(args) => diff::main(args),
        Command::Fuzz(args) => fuzz::main(args),
        Command::DumpClif(args) => dump_clif::main(args),
        Command::Bench(args) => bench::main(args),
        Command::Fmu(args) => fmu::main(args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
