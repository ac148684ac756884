//! What every dialect's symbol table shares: reading an export line by line (blank and comment
//! lines skipped, one optional header line), splitting a line into fields (by TABs, else as CSV
//! with `,` or `;`, quotes honoured), and the name → target map with its duplicate rule. Each
//! front end only says which field is the address and what an address means.

use crate::{Code, Diagnostic, Span, clip};
use std::collections::HashMap;
use stljit_core::FileId;

/// One data line of a symbol table.
#[derive(Clone, Debug)]
pub struct SymbolLine<'a> {
    /// Line number, 1-based.
    pub number: u32,
    /// The line without its line break.
    pub line: &'a str,
    /// Its trimmed, non-empty fields.
    pub fields: Vec<&'a str>,
    file: FileId,
}

impl<'a> SymbolLine<'a> {
    /// The span of `field`, a sub-slice of the line.
    pub fn span(&self, field: &str) -> Span {
        Span {
            file: self.file,
            line: self.number,
            col: col_of(self.line, field),
            len: u32::try_from(field.chars().count()).unwrap_or(u32::MAX),
        }
    }

    /// The first field, or the trimmed line when it has none.
    pub fn first(&self) -> &'a str {
        self.fields.first().copied().unwrap_or(self.line.trim())
    }
}

/// The data lines of symbol-table text `text` (of file `file`): blank lines and `//` or `;`
/// comment lines skipped, and the first non-blank line when it is a header
/// ([`is_header`]).
pub fn lines(text: &str, file: FileId) -> impl Iterator<Item = SymbolLine<'_>> {
    let mut first = true;
    text.split('\n').enumerate().filter_map(move |(i, raw)| {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with("//") || trimmed.starts_with(';') {
            return None;
        }
        let fields = split_fields(line);
        if std::mem::take(&mut first) && is_header(&fields) {
            return None;
        }
        Some(SymbolLine {
            number: u32::try_from(i + 1).unwrap_or(u32::MAX),
            line,
            fields,
            file,
        })
    })
}

/// Column (1-based, in characters) of the sub-slice `field` inside `line`.
fn col_of(line: &str, field: &str) -> u32 {
    let off = (field.as_ptr() as usize).saturating_sub(line.as_ptr() as usize);
    let off = off.min(line.len());
    let chars = line.get(..off).map_or(off, |s| s.chars().count());
    u32::try_from(chars + 1).unwrap_or(u32::MAX)
}

/// Splits a line into trimmed fields: by TABs if it has any (empty fields, from leading TABs,
/// dropped), else as CSV separated by `,` or `;` (whichever comes first: `;` is the CSV of
/// European locales), outside double quotes.
pub fn split_fields(line: &str) -> Vec<&str> {
    if line.contains('\t') {
        return line
            .split('\t')
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .collect();
    }
    let sep = line
        .bytes()
        .find(|&b| b == b',' || b == b';')
        .unwrap_or(b',');
    let mut out = Vec::new();
    let b = line.as_bytes();
    let (mut start, mut quoted) = (0, false);
    for i in 0..=b.len() {
        match b.get(i) {
            Some(b'"') => quoted = !quoted,
            Some(&c) if c == sep && !quoted => {
                out.push(line[start..i].trim());
                start = i + 1;
            }
            None => out.push(line[start..].trim()),
            _ => {}
        }
    }
    while out.last().is_some_and(|f| f.is_empty()) {
        out.pop();
    }
    out
}

/// A field without its CSV quotes (`""` inside stands for one quote).
pub fn unquote(f: &str) -> String {
    match f.strip_prefix('"').and_then(|s| s.strip_suffix('"')) {
        Some(inner) => inner.replace("\"\"", "\""),
        None => f.to_owned(),
    }
}

/// Whether `fields` are a header line: a name-like first column, or an address-like column.
pub fn is_header(fields: &[&str]) -> bool {
    let is = |f: &&str, words: &[&str]| {
        let f = unquote(f).to_lowercase();
        words.iter().any(|w| f == *w)
    };
    fields
        .first()
        .is_some_and(|f| is(f, &["symbol", "name", "symbol name", "符号", "名称"]))
        || fields
            .iter()
            .any(|f| is(f, &["address", "adresse", "addr", "地址"]))
}

/// Names to targets (`T`), each with the line that defined it.
#[derive(Clone, Debug)]
pub struct SymbolMap<T> {
    map: HashMap<String, (T, u32)>,
}

impl<T> Default for SymbolMap<T> {
    fn default() -> Self {
        SymbolMap {
            map: HashMap::new(),
        }
    }
}

impl<T> SymbolMap<T> {
    /// Number of symbols.
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// Whether the map is empty.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// Every name, in no particular order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.map.keys().map(String::as_str)
    }

    /// The target of `name`.
    pub fn get(&self, name: &str) -> Option<&T> {
        self.map.get(name).map(|(t, _)| t)
    }

    /// Defines `name` (written as `field` on line `l`) as `target`; a name defined before is
    /// a diagnostic (E011) naming the first line, and keeps its first target.
    pub fn define(
        &mut self,
        l: &SymbolLine<'_>,
        field: &str,
        name: String,
        target: T,
    ) -> Result<(), Diagnostic> {
        if let Some((_, prev)) = self.map.get(name.as_str()) {
            return Err(Diagnostic::new(
                Code::SymbolDuplicate,
                l.span(field),
                field,
                format!("symbol `{}` is defined twice", clip(&name)),
            )
            .help(format!("first defined on line {prev}")));
        }
        self.map.insert(name, (target, l.number));
        Ok(())
    }

    /// Records `name` as `invalid` unless it is defined already, so that its uses stay silent
    /// after its line's error was reported.
    pub fn define_invalid(&mut self, l: &SymbolLine<'_>, name: String, invalid: T) {
        self.map.entry(name).or_insert((invalid, l.number));
    }
}

/// The diagnostic of a line whose address field is missing.
pub fn missing_address(l: &SymbolLine<'_>, help: &str) -> Diagnostic {
    let f = l.first();
    Diagnostic::new(
        Code::SymbolAddress,
        l.span(f),
        f,
        "symbol without an address",
    )
    .help(help)
}

/// The diagnostic of a line whose address `addr` does not parse (`why`; `allowed` lists the
/// dialect's address forms).
pub fn bad_address(
    l: &SymbolLine<'_>,
    addr: &str,
    name: &str,
    why: &str,
    allowed: &str,
) -> Diagnostic {
    Diagnostic::new(
        Code::SymbolAddress,
        l.span(addr),
        addr,
        format!(
            "`{}` is not a valid address for symbol `{}`",
            clip(addr),
            clip(name)
        ),
    )
    .help(format!("{why}; allowed: {allowed}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_by_tab_comma_or_semicolon() {
        assert_eq!(split_fields("\t\tA\tI0.0\tc"), ["A", "I0.0", "c"]);
        assert_eq!(
            split_fields("\"A, b\",I0.1,\"x\""),
            ["\"A, b\"", "I0.1", "\"x\""]
        );
        assert_eq!(
            split_fields("A;BOOL;0.00;a, b"),
            ["A", "BOOL", "0.00", "a, b"]
        );
        assert_eq!(unquote("\"say \"\"hi\"\"\""), "say \"hi\"");
    }

    #[test]
    fn headers_comments_and_places() {
        let text = "Name\tAddress\n// note\n; note\n\n Start\tI0.0\n";
        let ls: Vec<_> = lines(text, FileId(2)).collect();
        assert_eq!(ls.len(), 1);
        assert_eq!(ls[0].number, 5);
        let s = ls[0].span(ls[0].fields[1]);
        assert_eq!((s.file, s.line, s.col, s.len), (FileId(2), 5, 8, 4));
        let mut m = SymbolMap::default();
        assert!(m.define(&ls[0], "Start", "Start".into(), 1).is_ok());
        let dup = m.define(&ls[0], "Start", "Start".into(), 2).unwrap_err();
        assert_eq!(dup.code, Code::SymbolDuplicate);
        assert_eq!(m.get("Start"), Some(&1));
    }
}
