//! `stljit dump-clif`: the Cranelift IR the JIT generates for a program, with a comment naming
//! the STL source line and op above the instructions of each op.

use std::process::ExitCode;

/// Arguments of `stljit dump-clif`.
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(flatten)]
    input: crate::check::Input,
    /// Optimisation level the IR is generated for.
    #[arg(long, value_enum, default_value = "none")]
    opt: crate::engines::OptArg,
    /// Print the generated machine code (Cranelift's disassembly) instead of the IR.
    #[arg(long, conflicts_with = "optimized")]
    asm: bool,
    /// Print the IR after the mid-end (Cranelift's optimiser, then stljit's encoding passes:
    /// what is lowered to machine code) instead of the IR the JIT generates.
    #[arg(long)]
    optimized: bool,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let c = args.input.compile()?;
    let Some(program) = crate::project::checked_program(&c) else {
        return Ok(ExitCode::from(1));
    };
    let opts = stljit_jit::JitOptions::at(args.opt.into());
    let text = if args.asm {
        stljit_jit::asm_text(program, &opts)?
    } else if args.optimized {
        stljit_jit::optimized_clif_text(program, &opts)?
    } else {
        stljit_jit::clif_text(program, &opts)?
    };
    print!("{text}");
    Ok(ExitCode::SUCCESS)
}
