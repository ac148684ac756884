//! [`Project`]: the program files, symbol table, dialect and CPU of one PLC program, and
//! [`Compiled`]: what compiling it produced (the checked program, every diagnostic, the symbol
//! table and the dialect that read it).
//!
//! The dialect is named or detected from the files' content ([`detect_dialect`]); the CPU
//! profile is named or the dialect's default ([`resolve_cpu`]). Both rules exist once, here; the
//! CLI's `--dialect`/`--cpu` and the Python package's `dialect=`/`cpu=` go through them.

use crate::Error;
use std::path::Path;
use stljit_core::ProfileId;
use stljit_core::ir::{Address, Program};
use stljit_front::{Compilation, Dialect, Options, SourceFile, Symbols, render_human};

/// Reads one file as a [`SourceFile`] named by its path (as diagnostics show it).
pub fn read_source(path: &Path) -> Result<SourceFile, Error> {
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(SourceFile {
        name: path.display().to_string(),
        bytes,
    })
}

/// The dialect called `name` (`s7`, `omron`).
pub fn dialect_named(name: &str) -> Result<Dialect, Error> {
    Dialect::from_name(name).ok_or_else(|| Error::UnknownDialect {
        name: name.to_string(),
    })
}

/// Why [`detect_dialect`] could not decide.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DetectError {
    /// No file was given.
    NoFiles,
    /// The file shows the marks of neither dialect (or of both).
    Unknown {
        /// The file's name.
        file: String,
    },
    /// Two files read as different dialects.
    Mixed {
        /// The later file's name.
        file: String,
        /// Its dialect.
        this: Dialect,
        /// The dialect of the files before it.
        earlier: Dialect,
    },
}

/// The dialect every file of a project is written in, from the content (the marks only one
/// dialect writes: `LD 0.00`, `MOV(021)` read as Omron; `LD I0.0`, `NETWORK` as S7).
pub fn detect_dialect(files: &[SourceFile]) -> Result<Dialect, DetectError> {
    let mut found: Option<Dialect> = None;
    for file in files {
        let text = String::from_utf8_lossy(&file.bytes);
        let Some(d) = Dialect::detect(&text) else {
            return Err(DetectError::Unknown {
                file: file.name.clone(),
            });
        };
        if let Some(earlier) = found
            && earlier != d
        {
            return Err(DetectError::Mixed {
                file: file.name.clone(),
                this: d,
                earlier,
            });
        }
        found = Some(d);
    }
    found.ok_or(DetectError::NoFiles)
}

impl From<DetectError> for Error {
    fn from(e: DetectError) -> Error {
        match e {
            DetectError::NoFiles => Error::NoSources,
            DetectError::Unknown { file } => Error::Dialect {
                message: format!(
                    "cannot tell the dialect of {file} from its content; name it (s7 or omron)"
                ),
            },
            DetectError::Mixed {
                file,
                this,
                earlier,
            } => Error::Dialect {
                message: format!(
                    "{file} reads as the {} dialect but an earlier file as {}; name the dialect",
                    this.name(),
                    earlier.name()
                ),
            },
        }
    }
}

/// The CPU profile called `cpu` among the dialect's, or the dialect's default for `None`.
pub fn resolve_cpu(dialect: Dialect, cpu: Option<&str>) -> Result<ProfileId, Error> {
    match cpu {
        None => Ok(dialect.default_profile()),
        Some(name) => ProfileId::from_name(name)
            .filter(|p| dialect.profiles().contains(p))
            .ok_or_else(|| Error::UnknownCpu {
                name: name.to_string(),
                known: dialect.profiles().iter().map(|p| p.name()).collect(),
            }),
    }
}

/// The inputs of one compilation. Build it with [`Project::new`] and the setters, then
/// [`Project::compile`].
#[derive(Clone, Debug, Default)]
pub struct Project {
    files: Vec<SourceFile>,
    symbols: Option<SourceFile>,
    dialect: Option<Dialect>,
    cpu: Option<String>,
    options: Options,
}

impl Project {
    /// An empty project (no files, dialect detected, the dialect's default CPU).
    pub fn new() -> Project {
        Project::default()
    }

    /// Adds a program file given as bytes (all files together are one program).
    pub fn source(mut self, file: SourceFile) -> Project {
        self.files.push(file);
        self
    }

    /// Adds a program file given as text.
    pub fn text(self, name: &str, text: &str) -> Project {
        self.source(SourceFile::from_text(name, text))
    }

    /// Reads and adds a program file.
    pub fn file(self, path: impl AsRef<Path>) -> Result<Project, Error> {
        Ok(self.source(read_source(path.as_ref())?))
    }

    /// Sets the symbol table (MicroWIN or CX-Programmer format, by dialect).
    pub fn symbols(mut self, file: SourceFile) -> Project {
        self.symbols = Some(file);
        self
    }

    /// Reads and sets the symbol table.
    pub fn symbols_file(self, path: impl AsRef<Path>) -> Result<Project, Error> {
        Ok(self.symbols(read_source(path.as_ref())?))
    }

    /// Names the dialect (otherwise it is detected from the files).
    pub fn dialect(mut self, dialect: Dialect) -> Project {
        self.dialect = Some(dialect);
        self
    }

    /// Names the CPU profile (`a5`, `s7-200`, `cp1h`, `cp1e`); checked by [`Project::compile`].
    pub fn cpu(mut self, cpu: &str) -> Project {
        self.cpu = Some(cpu.to_string());
        self
    }

    /// Sets the front ends' options (Omron: `tc_mode`, backward jumps; the CLI's `--tc-mode`,
    /// `--allow-backward-jumps`).
    pub fn options(mut self, options: Options) -> Project {
        self.options = options;
        self
    }

    /// The program files.
    pub fn files(&self) -> &[SourceFile] {
        &self.files
    }

    /// The symbol table file.
    pub fn symbols_source(&self) -> Option<&SourceFile> {
        self.symbols.as_ref()
    }

    /// The dialect named, or detected from the files.
    pub fn resolved_dialect(&self) -> Result<Dialect, Error> {
        match self.dialect {
            Some(d) => Ok(d),
            None => Ok(detect_dialect(&self.files)?),
        }
    }

    /// Compiles the project. `Err` only for what stops compilation from starting (no files, an
    /// unknown CPU, an undetectable dialect); program errors are diagnostics in the result, and
    /// [`Compiled::program`] turns them into [`Error::Compile`].
    pub fn compile(&self) -> Result<Compiled, Error> {
        if self.files.is_empty() {
            return Err(Error::NoSources);
        }
        let dialect = self.resolved_dialect()?;
        let profile = resolve_cpu(dialect, self.cpu.as_deref())?;
        let compilation =
            dialect.compile_with(&self.files, self.symbols.as_ref(), profile, self.options);
        Ok(Compiled {
            dialect,
            profile,
            compilation,
        })
    }
}

/// A compiled project: the dialect and the front end's [`Compilation`].
#[derive(Clone, Debug)]
pub struct Compiled {
    dialect: Dialect,
    profile: ProfileId,
    compilation: Compilation,
}

impl Compiled {
    /// Wraps a compilation made elsewhere (by a front end directly) for `profile`.
    pub fn new(dialect: Dialect, profile: ProfileId, compilation: Compilation) -> Compiled {
        Compiled {
            dialect,
            profile,
            compilation,
        }
    }

    /// The CPU profile the program was checked against.
    pub fn profile(&self) -> ProfileId {
        self.profile
    }

    /// Resolves an address or a symbol as the program's dialect writes it, against its profile
    /// and symbol table (the resolver stimulus files and watch lists use).
    pub fn resolve(&self, name: &str) -> Result<Address, String> {
        self.dialect
            .parse_address(name, self.profile, self.symbols())
            .map_err(|e| e.to_string())
    }

    /// Resolves a name (an address or symbol with an optional `:i`/`:u`/`:real` suffix) to a
    /// [`crate::Handle`] for any PLC of this program ([`crate::Plc::handle`] is the same).
    pub fn handle(&self, name: &str) -> Result<crate::Handle, Error> {
        let layout = stljit_core::Layout::of(self.profile);
        crate::Handle::resolve(name, &layout, &|n| self.resolve(n))
    }

    /// The name to show for an address: its symbol when the table has one, else the address in
    /// the dialect's spelling.
    pub fn names(&self) -> crate::used::Names {
        crate::used::Names::new(self.profile, self.dialect, self.symbols())
    }

    /// The dialect the program was read as.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// The front end's result, given up.
    pub fn into_compilation(self) -> Compilation {
        self.compilation
    }

    /// The front end's result: program, diagnostics, sources, symbols.
    pub fn compilation(&self) -> &Compilation {
        &self.compilation
    }

    /// The symbol table, when one was given.
    pub fn symbols(&self) -> Option<&Symbols> {
        self.compilation.symbols.as_ref()
    }

    /// The checked program, or [`Error::Compile`] with every diagnostic rendered.
    pub fn program(&self) -> Result<&Program, Error> {
        self.compilation
            .program
            .as_ref()
            .ok_or_else(|| Error::Compile {
                errors: self.compilation.error_count(),
                rendered: self.rendered_diagnostics(),
            })
    }

    /// Every diagnostic rendered as `stljit check` prints it, one after the other.
    pub fn rendered_diagnostics(&self) -> String {
        let c = &self.compilation;
        c.diagnostics
            .iter()
            .map(|d| render_human(d, &c.sources) + "\n")
            .collect()
    }
}
