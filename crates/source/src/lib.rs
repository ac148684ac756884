//! What every stljit front end shares, whatever its dialect: the input files ([`SourceFile`]) and
//! their decoding (UTF-8 with or without BOM, GBK, CRLF: [`decode`]), spans and [`Diagnostic`]s
//! with stable [`Code`]s, their rendering as rustc-style text or JSON ([`render_human`],
//! [`render_json`]), and the [`Compilation`] a front end returns.
//!
//! A dialect's front end (`stljit-front-s7`, ...) builds on this crate; `stljit-front` puts the
//! dialects side by side behind one `Dialect` switch.

pub mod codes;
pub mod decode;
pub mod diag;

pub use codes::{Code, Severity};
pub use decode::Encoding;
pub use diag::{Diagnostic, SourceText, Sources, Span, clip, render_human, render_json};

use stljit_core::FileId;
use stljit_core::ir::Program;

/// One input file: its name (for messages) and raw bytes (any encoding the front end accepts).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceFile {
    /// The name shown in diagnostics, usually the path.
    pub name: String,
    /// The raw contents.
    pub bytes: Vec<u8>,
}

/// What compiling a project produced; `S` is the front end's symbol table.
#[derive(Clone, Debug)]
pub struct Compilation<S> {
    /// The checked program; `Some` iff there is no error diagnostic.
    pub program: Option<Program>,
    /// Every diagnostic of every file, sorted by file, line and column.
    pub diagnostics: Vec<Diagnostic>,
    /// The decoded sources (program files first, then the symbol table), for rendering.
    pub sources: Sources,
    /// The symbol table, when one was given (for resolving watch addresses by name).
    pub symbols: Option<S>,
}

impl<S> Compilation<S> {
    /// Number of error diagnostics.
    pub fn error_count(&self) -> usize {
        self.diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .count()
    }

    /// Number of warnings.
    pub fn warning_count(&self) -> usize {
        self.diagnostics.len() - self.error_count()
    }

    /// The same compilation with its symbol table mapped (a dialect's table into a common type).
    pub fn map_symbols<T>(self, f: impl FnOnce(S) -> T) -> Compilation<T> {
        Compilation {
            program: self.program,
            diagnostics: self.diagnostics,
            sources: self.sources,
            symbols: self.symbols.map(f),
        }
    }
}

/// Decodes `file`, reporting undecodable bytes as [`Code::Encoding`] on `id`.
pub fn decode_file(file: &SourceFile, id: FileId, diags: &mut Vec<Diagnostic>) -> SourceText {
    let (text, _, issue) = decode::decode(&file.bytes);
    if let Some(issue) = issue {
        let before = String::from_utf8_lossy(&file.bytes[..issue.byte.min(file.bytes.len())]);
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        let span = Span {
            file: id,
            line: u32::try_from(line).unwrap_or(u32::MAX),
            col: u32::try_from(col).unwrap_or(u32::MAX),
            len: 1,
        };
        diags.push(
            Diagnostic::new(
                Code::Encoding,
                span,
                "",
                "the file is neither UTF-8 nor GBK text (invalid byte sequence here)",
            )
            .help("save the program as UTF-8 or GBK text"),
        );
    }
    SourceText {
        name: file.name.clone(),
        text,
    }
}
