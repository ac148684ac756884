//! `stljit check`: parse and check programs, print diagnostics.
//!
//! Exit codes: 0 when there is no error (warnings allowed), 1 when there are errors, 2 for usage
//! errors (unreadable file, unknown `--dialect` or `--cpu`).
//!
//! [`Input`] is the one seam between the command line and the front ends: every command that
//! reads programs compiles them through [`Input::compile`], which picks the dialect.

use anyhow::Context as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use stljit_core::ProfileId;
use stljit_front::{Compilation, Dialect, SourceFile, render_human, render_json};

/// Output format of the diagnostics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Format {
    /// rustc-style text with the source line and a caret.
    Human,
    /// One JSON object per diagnostic per line.
    Json,
}

/// Options shared by every command that compiles programs.
#[derive(clap::Args)]
pub(crate) struct Input {
    /// Program files (plain STL or MicroWIN .awl exports), checked as one project.
    #[arg(required = true)]
    pub(crate) files: Vec<PathBuf>,
    /// Program dialect: s7 (S7-200/A5 STL and MicroWIN exports; the default).
    #[arg(long, default_value = "s7")]
    pub(crate) dialect: String,
    /// CPU profile: a5 (the s7 default) or s7-200.
    #[arg(long)]
    pub(crate) cpu: Option<String>,
    /// MicroWIN symbol table (name<TAB>address[<TAB>comment], or CSV).
    #[arg(long)]
    pub(crate) symbols: Option<PathBuf>,
}

fn read(path: &Path) -> anyhow::Result<SourceFile> {
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    Ok(SourceFile {
        name: path.display().to_string(),
        bytes,
    })
}

impl Input {
    /// The dialect named by `--dialect`; `Err` is a usage error (exit 2).
    pub(crate) fn dialect(&self) -> anyhow::Result<Dialect> {
        Dialect::from_name(&self.dialect).with_context(|| {
            let names: Vec<_> = Dialect::ALL.iter().map(|d| d.name()).collect();
            format!(
                "unknown --dialect `{}` (known: {})",
                self.dialect,
                names.join(", ")
            )
        })
    }

    /// Reads every file and compiles the project; `Err` is a usage error (exit 2).
    pub(crate) fn compile(&self) -> anyhow::Result<Compilation> {
        let dialect = self.dialect()?;
        let profile = match &self.cpu {
            None => dialect.default_profile(),
            Some(cpu) => ProfileId::from_name(cpu)
                .filter(|p| dialect.profiles().contains(p))
                .with_context(|| {
                    let names: Vec<_> = dialect.profiles().iter().map(|p| p.name()).collect();
                    format!("unknown --cpu `{cpu}` (known: {})", names.join(", "))
                })?,
        };
        let files = self
            .files
            .iter()
            .map(|p| read(p))
            .collect::<anyhow::Result<Vec<_>>>()?;
        let symbols = self.symbols.as_deref().map(read).transpose()?;
        Ok(dialect.compile(&files, symbols.as_ref(), profile))
    }
}

/// Arguments of `stljit check`.
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(flatten)]
    input: Input,
    /// Diagnostic format.
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let c = args.input.compile()?;
    let mut out = String::new();
    for d in &c.diagnostics {
        match args.format {
            Format::Human => {
                out.push_str(&render_human(d, &c.sources));
                out.push('\n');
            }
            Format::Json => {
                out.push_str(&render_json(d, &c.sources));
                out.push('\n');
            }
        }
    }
    print!("{out}");
    let (errors, warnings) = (c.error_count(), c.warning_count());
    if args.format == Format::Human {
        eprintln!(
            "check: {} file(s), {errors} error(s), {warnings} warning(s)",
            args.input.files.len()
        );
    }
    Ok(if errors == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
