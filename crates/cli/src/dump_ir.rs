//! `stljit dump-ir`: print the checked IR in its dialect-neutral text form
//! (`stljit_core::text`, grammar in `docs/ir-text.md`): the declarations, then every POU with
//! its label targets and one op per line with its index and source location. The text parses
//! back to the same program, which is how fuzz reproducers and `tests/regressions/` store
//! programs.

use std::process::ExitCode;
use stljit_front::render_human;

/// Arguments of `stljit dump-ir`.
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(flatten)]
    input: crate::check::Input,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let c = args.input.compile()?;
    for d in &c.diagnostics {
        eprintln!("{}", render_human(d, &c.sources));
    }
    let Some(program) = &c.program else {
        return Ok(ExitCode::from(1));
    };
    print!("{}", stljit_core::text::print(program));
    Ok(ExitCode::SUCCESS)
}
