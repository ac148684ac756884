//! `stljit check`: parse and check programs, print diagnostics.

use std::process::ExitCode;

/// Arguments of `stljit check`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Program files (plain STL or MicroWIN .awl exports), checked as one project.
    #[arg(required = true)]
    files: Vec<std::path::PathBuf>,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    anyhow::bail!("check is not built yet ({} files given)", args.files.len())
}
