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
pub mod symbols;

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

/// Why an address named outside a program (a stimulus column, a watch, an HMI write) was
/// rejected; every dialect's `parse_address` returns it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AddressError {
    /// The message, e.g. "`Q16.0` is out of range for the A5".
    pub message: String,
}

impl std::fmt::Display for AddressError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for AddressError {}

impl SourceFile {
    /// A file named `name` holding the UTF-8 text `text` (for tests and tools).
    pub fn from_text(name: &str, text: &str) -> SourceFile {
        SourceFile {
            name: name.to_owned(),
            bytes: text.as_bytes().to_vec(),
        }
    }
}

/// Decodes a project's program files (file ids `0..files.len()`) and its optional symbol table
/// (the next id), which `parse_symbols` reads: the decoded sources, the table, and every
/// diagnostic so far (encoding problems, bad symbol lines). Both front ends start here.
pub fn decode_project<S>(
    files: &[SourceFile],
    symbols: Option<&SourceFile>,
    parse_symbols: impl FnOnce(&str, FileId) -> (S, Vec<Diagnostic>),
) -> (Sources, Option<S>, Vec<Diagnostic>) {
    let mut diags = Vec::new();
    let mut sources = Sources::default();
    for (i, f) in files.iter().enumerate() {
        let text = decode_file(f, FileId::new(i), &mut diags);
        sources.files.push(text);
    }
    let table = symbols.map(|s| {
        let id = FileId::new(files.len());
        let text = decode_file(s, id, &mut diags);
        let (table, d) = parse_symbols(&text.text, id);
        diags.extend(d);
        sources.files.push(text);
        table
    });
    (sources, table, diags)
}

/// Decodes `file`, reporting undecodable bytes as [`Code::Encoding`] on `id`.
pub fn decode_file(file: &SourceFile, id: FileId, diags: &mut Vec<Diagnostic>) -> SourceText {
    let (text, encoding, issue) = decode::decode(&file.bytes);
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
        encoding,
    }
}
