//! CX-Programmer symbol tables: one symbol a line, `Name<TAB>Data type<TAB>Address<TAB>Comment`
//! (the export format), or the same columns separated by `,` or `;` (CSV), with an optional
//! header line. Names may be any text, including non-ASCII.

use crate::operand::{Syn, SynError, parse_syn};
use std::collections::HashMap;
use stljit_core::FileId;
use stljit_source::{Code, Diagnostic, Span, clip};

/// What a symbol stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SymTarget {
    /// An address.
    Operand(Syn),
    /// A symbol whose line has an error (already reported): uses stay silent.
    Invalid,
}

/// A parsed symbol table: names to addresses.
#[derive(Clone, Debug, Default)]
pub struct SymbolTable {
    map: HashMap<String, (SymTarget, u32)>,
}

impl SymbolTable {
    /// Number of symbols.
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// Whether the table is empty.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// Every symbol name, in no particular order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.map.keys().map(String::as_str)
    }

    /// The symbol's target.
    pub(crate) fn get(&self, name: &str) -> Option<&SymTarget> {
        self.map.get(name).map(|(t, _)| t)
    }

    /// Parses a symbol-table text (already decoded). Bad lines become diagnostics on `file`;
    /// the good lines still form the table.
    pub fn parse(text: &str, file: FileId) -> (SymbolTable, Vec<Diagnostic>) {
        let mut table = SymbolTable::default();
        let mut diags = Vec::new();
        let mut first = true;
        for (i, raw) in text.split('\n').enumerate() {
            let number = u32::try_from(i + 1).unwrap_or(u32::MAX);
            let line = raw.strip_suffix('\r').unwrap_or(raw);
            let trimmed = line.trim();
            if trimmed.is_empty() || trimmed.starts_with("//") || trimmed.starts_with(';') {
                continue;
            }
            let fields = split_fields(line);
            if std::mem::take(&mut first) && is_header(&fields) {
                continue;
            }
            let span = |f: &str| Span {
                file,
                line: number,
                col: col_of(line, f),
                len: u32::try_from(f.chars().count()).unwrap_or(u32::MAX),
            };
            // Name, data type, address: the address is the third column, or the second when
            // a line has only two.
            let name = fields.first().copied().unwrap_or(trimmed);
            let addr = match fields.len() {
                0 | 1 => None,
                2 => Some(fields[1]),
                _ => Some(fields[2]),
            };
            let Some(addr) = addr else {
                diags.push(
                    Diagnostic::new(Code::SymbolAddress, span(name), name, "symbol without an address")
                        .help("write Name<TAB>Data type<TAB>Address[<TAB>Comment] or Name,Type,Address[,Comment]"),
                );
                continue;
            };
            let name_text = unquote(name);
            let target = match parse_syn(&unquote(addr)) {
                Ok(Syn::Const(..)) => Err("a symbol cannot name a constant"),
                Ok(Syn::Unsupported(what)) => Err(what),
                Ok(s) => Ok(s),
                Err(SynError::Malformed(m)) => Err(m),
                Err(SynError::NotAddress) => Err("not an Omron address"),
            };
            let target = match target {
                Ok(t) => t,
                Err(why) => {
                    table
                        .map
                        .entry(name_text.clone())
                        .or_insert((SymTarget::Invalid, number));
                    diags.push(
                        Diagnostic::new(
                            Code::SymbolAddress,
                            span(addr),
                            addr,
                            format!("`{}` is not a valid address for symbol `{}`", clip(addr), clip(&name_text)),
                        )
                        .help(format!("{why}; allowed: CIO bits and words (0.00, 100), W/H/A bits and words, D words, T/C numbers, P_ flags")),
                    );
                    continue;
                }
            };
            if let Some((_, prev)) = table.map.get(name_text.as_str()) {
                diags.push(
                    Diagnostic::new(
                        Code::SymbolDuplicate,
                        span(name),
                        name,
                        format!("symbol `{}` is defined twice", clip(&name_text)),
                    )
                    .help(format!("first defined on line {prev}")),
                );
                continue;
            }
            table
                .map
                .insert(name_text, (SymTarget::Operand(target), number));
        }
        (table, diags)
    }
}

/// Column (1-based, in characters) of the sub-slice `field` inside `line`.
fn col_of(line: &str, field: &str) -> u32 {
    let off = (field.as_ptr() as usize).saturating_sub(line.as_ptr() as usize);
    let off = off.min(line.len());
    let chars = line.get(..off).map_or(off, |s| s.chars().count());
    u32::try_from(chars + 1).unwrap_or(u32::MAX)
}

/// Splits a line into trimmed fields: by tabs if it has any, else by `,` or `;` outside
/// quotes (whichever comes first). Empty tab fields are dropped (leading tabs).
fn split_fields(line: &str) -> Vec<&str> {
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
fn unquote(f: &str) -> String {
    match f.strip_prefix('"').and_then(|s| s.strip_suffix('"')) {
        Some(inner) => inner.replace("\"\"", "\""),
        None => f.to_owned(),
    }
}

fn is_header(fields: &[&str]) -> bool {
    let is = |f: Option<&&str>, words: &[&str]| {
        f.is_some_and(|f| {
            let f = unquote(f).to_lowercase();
            words.iter().any(|w| f == *w)
        })
    };
    is(
        fields.first(),
        &["name", "symbol", "symbol name", "名称", "符号"],
    ) || fields
        .iter()
        .any(|f| unquote(f).eq_ignore_ascii_case("address"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::omron::WordArea;

    #[test]
    fn cx_programmer_export_and_csv() {
        let text = "Name\tData Type\tAddress\tComment\nStart_PB\tBOOL\t0.00\tstart button\n启动\tBOOL\tW0.01\n";
        let (t, d) = SymbolTable::parse(text, FileId(1));
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(
            t.get("Start_PB"),
            Some(&SymTarget::Operand(Syn::Bit {
                area: WordArea::Cio,
                word: 0,
                bit: 0
            }))
        );
        assert!(t.get("启动").is_some());
        let (t, d) = SymbolTable::parse(
            "Name;Type;Address\nSpeed;CHANNEL;D100\n\"A, b\",BOOL,100.01,x\n",
            FileId(1),
        );
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(
            t.get("Speed"),
            Some(&SymTarget::Operand(Syn::Word {
                area: WordArea::Dm,
                word: 100
            }))
        );
        assert!(t.get("A, b").is_some());
    }

    #[test]
    fn bad_and_duplicate_lines_are_located() {
        let (t, d) =
            SymbolTable::parse("A\tBOOL\t0.00\nB\tBOOL\tXY\nA\tBOOL\t0.01\nC\n", FileId(2));
        assert_eq!(t.get("B"), Some(&SymTarget::Invalid));
        let got: Vec<_> = d.iter().map(|d| (d.code, d.line, d.col)).collect();
        assert_eq!(
            got,
            [
                (Code::SymbolAddress, 2, 8),
                (Code::SymbolDuplicate, 3, 1),
                (Code::SymbolAddress, 4, 1)
            ]
        );
    }
}
