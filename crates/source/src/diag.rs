//! Diagnostics and their rendering: rustc-style human text with the source line and a caret, and
//! one JSON object per diagnostic.

use crate::codes::{Code, Severity};
use std::fmt::Write as _;
use stljit_core::FileId;

/// Offending texts longer than this are shortened in messages (a 1 MB line must not make a 1 MB
/// diagnostic).
const MAX_TEXT: usize = 60;

/// One finding, located in a source file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// The stable code.
    pub code: Code,
    /// Error or warning (fixed by the code).
    pub severity: Severity,
    /// The file, an index into [`Sources`].
    pub file: FileId,
    /// Line, 1-based.
    pub line: u32,
    /// Column of the first offending character, 1-based, in characters.
    pub col: u32,
    /// Column just past the offending text.
    pub end_col: u32,
    /// What is wrong.
    pub message: String,
    /// The offending text (shortened if very long).
    pub text: String,
    /// What is allowed instead, if there is something useful to say.
    pub help: Option<String>,
}

/// Shortens `s` to at most [`MAX_TEXT`] characters for use inside messages.
pub fn clip(s: &str) -> String {
    if s.chars().count() <= MAX_TEXT {
        s.to_owned()
    } else {
        let mut t: String = s.chars().take(MAX_TEXT).collect();
        t.push('…');
        t
    }
}

/// A position range on one line, used while building diagnostics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Span {
    /// The file.
    pub file: FileId,
    /// Line, 1-based.
    pub line: u32,
    /// Start column, 1-based, in characters.
    pub col: u32,
    /// Length in characters.
    pub len: u32,
}

impl Diagnostic {
    /// Builds a diagnostic; the severity comes from the code.
    pub fn new(code: Code, span: Span, text: &str, message: impl Into<String>) -> Self {
        Diagnostic {
            code,
            severity: code.severity(),
            file: span.file,
            line: span.line,
            col: span.col,
            end_col: span.col + span.len.max(1),
            message: message.into(),
            text: clip(text),
            help: None,
        }
    }

    /// Adds a help line.
    pub fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }
}

/// One decoded source file.
#[derive(Clone, Debug, Default)]
pub struct SourceText {
    /// The name given by the caller (usually the path).
    pub name: String,
    /// The decoded text.
    pub text: String,
    /// The encoding the file was decoded from (constant strings keep its bytes).
    pub encoding: crate::Encoding,
}

/// The decoded texts of every file of a compilation (program files first, then the symbol table),
/// indexed by [`FileId`].
#[derive(Clone, Debug, Default)]
pub struct Sources {
    /// The files.
    pub files: Vec<SourceText>,
    /// Byte offsets of line starts per file, built on first use so that rendering many
    /// diagnostics of a large file stays linear.
    line_starts: std::sync::OnceLock<Vec<Vec<usize>>>,
}

impl Sources {
    /// The name of file `id` (empty if unknown).
    pub fn name(&self, id: FileId) -> &str {
        self.files.get(id.index()).map_or("", |f| f.name.as_str())
    }

    /// Line `line` (1-based) of file `id`, without its line end.
    pub fn line(&self, id: FileId, line: u32) -> Option<&str> {
        let text = &self.files.get(id.index())?.text;
        let starts = self.line_starts.get_or_init(|| {
            self.files
                .iter()
                .map(|f| {
                    std::iter::once(0)
                        .chain(f.text.match_indices('\n').map(|(i, _)| i + 1))
                        .collect()
                })
                .collect()
        });
        let starts = starts.get(id.index())?;
        let i = (line as usize).checked_sub(1)?;
        let start = *starts.get(i)?;
        let end = starts.get(i + 1).map_or(text.len(), |e| e - 1);
        let l = text.get(start..end)?;
        Some(l.strip_suffix('\r').unwrap_or(l))
    }

    /// Sources from decoded files.
    pub fn new(files: Vec<SourceText>) -> Self {
        Sources {
            files,
            line_starts: std::sync::OnceLock::new(),
        }
    }
}

/// Whether a character takes two terminal columns (CJK), for caret alignment.
fn is_wide(c: char) -> bool {
    matches!(c as u32, 0x1100..=0x115F | 0x2E80..=0xA4CF | 0xAC00..=0xD7A3 | 0xF900..=0xFAFF | 0xFE30..=0xFE4F | 0xFF00..=0xFF60 | 0xFFE0..=0xFFE6)
}

/// Renders a diagnostic the way rustc does:
///
/// ```text
/// error[E003]: address Q16.0 is out of range for the A5
///  --> main.stl:4:6
///   |
/// 4 | =    Q16.0
///   |      ^^^^^
///   = help: allowed: Q0.0 - Q15.7
/// ```
pub fn render_human(d: &Diagnostic, sources: &Sources) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "{}[{}]: {}", d.severity.name(), d.code, d.message);
    let _ = writeln!(out, " --> {}:{}:{}", sources.name(d.file), d.line, d.col);
    let num = d.line.to_string();
    let pad = " ".repeat(num.len());
    if let Some(src) = sources.line(d.file, d.line) {
        // Show at most a window of a long line around the offending column.
        let chars: Vec<char> = src.chars().collect();
        let col0 = (d.col as usize).saturating_sub(1).min(chars.len());
        let start = col0.saturating_sub(60);
        let end = chars.len().min(col0 + 100);
        let shown: String = chars[start..end].iter().collect();
        let lead = if start > 0 { "…" } else { "" };
        let tail = if end < chars.len() { "…" } else { "" };
        let _ = writeln!(out, "{pad} |");
        let _ = writeln!(out, "{num} | {lead}{shown}{tail}");
        let mut caret = lead.replace('…', " ");
        for &c in &chars[start..col0] {
            caret.push_str(match c {
                '\t' => "\t",
                c if is_wide(c) => "  ",
                _ => " ",
            });
        }
        let len = (d.end_col.saturating_sub(d.col)).max(1) as usize;
        let stop = (col0 + len).min(end);
        let width: usize = chars[col0..stop]
            .iter()
            .map(|&c| if is_wide(c) { 2 } else { 1 })
            .sum();
        caret.push_str(&"^".repeat(width.max(1)));
        let _ = writeln!(out, "{pad} | {caret}");
    }
    if let Some(help) = &d.help {
        let _ = writeln!(out, "{pad} = help: {help}");
    }
    out
}

/// Appends `s` as a JSON string literal.
fn json_str(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 || c == '\u{2028}' || c == '\u{2029}' => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

/// Renders a diagnostic as one JSON object on one line, with the fields `code`, `severity`,
/// `file`, `line`, `column`, `end_column`, `message`, `text` and `help` (null when absent).
pub fn render_json(d: &Diagnostic, sources: &Sources) -> String {
    let mut out = String::from("{\"code\":");
    json_str(&mut out, d.code.name());
    out.push_str(",\"severity\":");
    json_str(&mut out, d.severity.name());
    out.push_str(",\"file\":");
    json_str(&mut out, sources.name(d.file));
    let _ = write!(
        out,
        ",\"line\":{},\"column\":{},\"end_column\":{},\"message\":",
        d.line, d.col, d.end_col
    );
    json_str(&mut out, &d.message);
    out.push_str(",\"text\":");
    json_str(&mut out, &d.text);
    out.push_str(",\"help\":");
    match &d.help {
        Some(h) => json_str(&mut out, h),
        None => out.push_str("null"),
    }
    out.push('}');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sources() -> Sources {
        Sources::new(vec![SourceText {
            name: "a.stl".into(),
            text: "LD I0.0\r\n=\tQ16.0 // \"x\"\n".into(),
            encoding: crate::Encoding::Utf8,
        }])
    }

    fn diag() -> Diagnostic {
        let span = Span {
            file: FileId(0),
            line: 2,
            col: 3,
            len: 5,
        };
        Diagnostic::new(
            Code::OutOfRange,
            span,
            "Q16.0",
            "address Q16.0 is out of range",
        )
        .help("allowed: Q0.0 - Q15.7")
    }

    #[test]
    fn human_has_caret_under_the_text() {
        let s = render_human(&diag(), &sources());
        let expected = "error[E003]: address Q16.0 is out of range\n --> a.stl:2:3\n  |\n2 | =\tQ16.0 // \"x\"\n  |  \t^^^^^\n  = help: allowed: Q0.0 - Q15.7\n";
        assert_eq!(s, expected);
    }

    #[test]
    fn json_escapes() {
        let mut d = diag();
        d.message = "a \"b\"\n".into();
        let s = render_json(&d, &sources());
        assert_eq!(
            s,
            r#"{"code":"E003","severity":"error","file":"a.stl","line":2,"column":3,"end_column":8,"message":"a \"b\"\n","text":"Q16.0","help":"allowed: Q0.0 - Q15.7"}"#
        );
    }
}
