//! `stljit check`: parse and check programs, print diagnostics.
//!
//! Exit codes: 0 when there is no error (warnings allowed), 1 when there are errors, 2 for usage
//! errors (unreadable file, unknown `--dialect` or `--cpu`).
//!
//! [`Input`] is the one seam between the command line and the front ends: every command that
//! reads programs compiles them through [`Input::compile`], which picks the dialect and builds a
//! `stljit_api::Project` (the rules for dialects and CPUs live there, once).

use anyhow::Context as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use stljit_api::{Compiled, DetectError, Project};
use stljit_front::{Compilation, Dialect, Options, SourceFile, TcMode, render_human, render_json};

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
    /// Program files (plain STL, MicroWIN .awl exports or Omron CX-Programmer mnemonics),
    /// checked as one project.
    #[arg(required = true)]
    pub(crate) files: Vec<PathBuf>,
    /// Program dialect: s7 (S7-200/A5 STL and MicroWIN exports) or omron (CP-series
    /// mnemonics). Omitted: detected from the files' content (a note says which was chosen).
    #[arg(long)]
    pub(crate) dialect: Option<String>,
    /// CPU profile: a5 (the s7 default), s7-200 or smart (S7-200 SMART); cp1h (the omron
    /// default) or cp1e.
    #[arg(long)]
    pub(crate) cpu: Option<String>,
    /// Symbol table: MicroWIN (name<TAB>address[<TAB>comment], or CSV) or CX-Programmer
    /// (name<TAB>type<TAB>address[<TAB>comment], or CSV).
    #[arg(long)]
    pub(crate) symbols: Option<PathBuf>,
    /// Omron: how TIM, TIMH, TMHH, TTIM, CNT and CNTR read set values and keep PVs: bcd (the
    /// default) or binary (CX-Programmer's binary mode: as TIMX, CNTX …).
    #[arg(long)]
    pub(crate) tc_mode: Option<String>,
    /// Omron: accept a JME before its jump (a backward jump; each one taken counts against the
    /// scan's loop budget).
    #[arg(long)]
    pub(crate) allow_backward_jumps: bool,
    /// The dialect once chosen (detection runs and reports once).
    #[arg(skip)]
    pub(crate) chosen: std::cell::OnceCell<Dialect>,
}

fn read(path: &Path) -> anyhow::Result<SourceFile> {
    Ok(stljit_api::read_source(path)?)
}

impl Input {
    /// The dialect named by `--dialect`, or the one the files' content shows (a note on stderr
    /// says so); `Err` is a usage error (exit 2): an unknown name, or files whose dialect cannot
    /// be told.
    pub(crate) fn dialect(&self) -> anyhow::Result<Dialect> {
        if let Some(d) = self.chosen.get() {
            return Ok(*d);
        }
        let d = match &self.dialect {
            Some(name) => Dialect::from_name(name).with_context(|| {
                let names: Vec<_> = Dialect::ALL.iter().map(|d| d.name()).collect();
                format!("unknown --dialect `{name}` (known: {})", names.join(", "))
            })?,
            None => self.detect()?,
        };
        Ok(*self.chosen.get_or_init(|| d))
    }

    /// The dialect of the files by their content (`stljit_api::detect_dialect`): every file must
    /// show the same one.
    fn detect(&self) -> anyhow::Result<Dialect> {
        let files = self
            .files
            .iter()
            .map(|p| read(p))
            .collect::<anyhow::Result<Vec<_>>>()?;
        let d = stljit_api::detect_dialect(&files).map_err(|e| match e {
            DetectError::NoFiles => anyhow::anyhow!("no program files"),
            DetectError::Unknown { file } => anyhow::anyhow!(
                "cannot tell the dialect of {file} from its content; pass --dialect {}",
                Dialect::ALL
                    .iter()
                    .map(|d| d.name())
                    .collect::<Vec<_>>()
                    .join(" or --dialect ")
            ),
            DetectError::Mixed {
                file,
                this,
                earlier,
            } => anyhow::anyhow!(
                "{file} reads as the {} dialect but an earlier file as {}; pass --dialect",
                this.name(),
                earlier.name()
            ),
        })?;
        eprintln!(
            "note: reading the program as the {} dialect (detected from its content; \
             --dialect {} says so explicitly)",
            d.name(),
            d.name()
        );
        Ok(d)
    }

    /// The project the options name: files read, dialect chosen, `--cpu` checked; `Err` is a
    /// usage error (exit 2).
    pub(crate) fn project(&self) -> anyhow::Result<Project> {
        let dialect = self.dialect()?;
        let cpu = self.cpu.as_deref();
        stljit_api::resolve_cpu(dialect, cpu).map_err(|e| match e {
            stljit_api::Error::UnknownCpu { name, known } => {
                anyhow::anyhow!("unknown --cpu `{name}` (known: {})", known.join(", "))
            }
            other => other.into(),
        })?;
        let mut project = Project::new().dialect(dialect);
        if let Some(cpu) = cpu {
            project = project.cpu(cpu);
        }
        for path in &self.files {
            project = project.source(read(path)?);
        }
        if let Some(path) = &self.symbols {
            project = project.symbols(read(path)?);
        }
        Ok(project.options(self.options(dialect)?))
    }

    /// Reads every file and compiles the project; `Err` is a usage error (exit 2).
    pub(crate) fn compile(&self) -> anyhow::Result<Compilation> {
        Ok(self.compiled()?.into_compilation())
    }

    /// As [`Input::compile`], keeping the dialect with the compilation.
    pub(crate) fn compiled(&self) -> anyhow::Result<Compiled> {
        Ok(self.project()?.compile()?)
    }

    /// The front-end options of the command line; `Err` is a usage error: an unknown
    /// `--tc-mode`, or an Omron option for another dialect.
    fn options(&self, dialect: Dialect) -> anyhow::Result<Options> {
        let omron_only = [
            ("--tc-mode", self.tc_mode.is_some()),
            ("--allow-backward-jumps", self.allow_backward_jumps),
        ];
        if let Some((flag, _)) = omron_only.iter().find(|(_, set)| *set)
            && dialect != Dialect::Omron
        {
            anyhow::bail!(
                "{flag} is an option of the omron dialect, not {}",
                dialect.name()
            );
        }
        let tc_mode = match &self.tc_mode {
            None => TcMode::default(),
            Some(name) => TcMode::from_name(name).with_context(|| {
                let names: Vec<_> = TcMode::ALL.iter().map(|m| m.name()).collect();
                format!("unknown --tc-mode `{name}` (known: {})", names.join(", "))
            })?,
        };
        let mut options = Options::default();
        options.omron.tc_mode = tc_mode;
        options.omron.allow_backward_jumps = self.allow_backward_jumps;
        Ok(options)
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
