//! MicroWIN symbol tables: one symbol a line, `name<TAB>address[<TAB>comment]` (leading tabs and
//! a header line allowed) or the same columns as CSV. Names may be any text, including non-ASCII.

use crate::operand::{Syn, SynError, parse_syn};
use std::collections::HashMap;
use stljit_core::FileId;
use stljit_source::Code;
use stljit_source::{Diagnostic, Span};

/// A program organisation unit named by a symbol (`Motor_Logic  SBR0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PouRef {
    /// `OB1`, the main program.
    Main,
    /// `SBRn`.
    Subroutine(u16),
    /// `INTn`.
    Interrupt(u16),
}

/// What a symbol stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SymTarget {
    /// A memory operand.
    Operand(Syn),
    /// A block.
    Pou(PouRef),
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

    /// Every symbol name, in no particular order (for reverse look-ups by the CLI).
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
            if trimmed.is_empty() || trimmed.starts_with("//") {
                continue;
            }
            let fields = split_fields(line);
            let header = first && is_header(&fields);
            first = false;
            if header {
                continue;
            }
            let span = |f: &str| Span {
                file,
                line: number,
                col: col_of(line, f),
                len: u32::try_from(f.chars().count()).unwrap_or(u32::MAX),
            };
            let (Some(&name), Some(&addr)) = (fields.first(), fields.get(1)) else {
                let f = fields.first().copied().unwrap_or(trimmed);
                diags.push(
                    Diagnostic::new(Code::SymbolAddress, span(f), f, "symbol without an address")
                        .help("write name<TAB>address[<TAB>comment] or name,address[,comment]"),
                );
                continue;
            };
            let name_text = unquote_csv(name);
            let target = match parse_target(addr) {
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
                            format!("`{}` is not a valid address for symbol `{}`", stljit_source::clip(addr), stljit_source::clip(&name_text)),
                        )
                        .help(format!("{why}; allowed: bit (I0.0), byte/word/dword (VB10, VW10, VD10), T, C, AC, HC, AIW, AQW, SBRn, INTn, OB1")),
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
                        format!(
                            "symbol `{}` is defined twice",
                            stljit_source::clip(&name_text)
                        ),
                    )
                    .help(format!("first defined on line {prev}")),
                );
                continue;
            }
            table.map.insert(name_text, (target, number));
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

/// Splits a line into trimmed, non-empty fields: by tabs if it has any, else as CSV.
fn split_fields(line: &str) -> Vec<&str> {
    if line.contains('\t') {
        return line
            .split('\t')
            .map(str::trim)
            .filter(|f| !f.is_empty())
            .collect();
    }
    let mut out = Vec::new();
    let b = line.as_bytes();
    let (mut start, mut quoted) = (0, false);
    for i in 0..=b.len() {
        match b.get(i) {
            Some(b'"') => quoted = !quoted,
            Some(b',') if !quoted => {
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

/// A CSV field without its quotes (`""` inside stands for one quote).
fn unquote_csv(f: &str) -> String {
    match f.strip_prefix('"').and_then(|s| s.strip_suffix('"')) {
        Some(inner) => inner.replace("\"\"", "\""),
        None => f.to_owned(),
    }
}

fn is_header(fields: &[&str]) -> bool {
    let is = |f: Option<&&str>, words: &[&str]| {
        f.is_some_and(|f| {
            let f = unquote_csv(f).to_lowercase();
            words.iter().any(|w| f == *w)
        })
    };
    is(
        fields.first(),
        &["symbol", "name", "symbol name", "符号", "名称"],
    ) || is(fields.get(1), &["address", "adresse", "addr", "地址"])
}

fn parse_target(addr: &str) -> Result<SymTarget, &'static str> {
    let addr = unquote_csv(addr);
    let upper = addr.to_ascii_uppercase();
    if upper == "OB1" {
        return Ok(SymTarget::Pou(PouRef::Main));
    }
    for (prefix, make) in [
        ("SBR", PouRef::Subroutine as fn(u16) -> PouRef),
        ("INT", PouRef::Interrupt),
    ] {
        if let Some(n) = upper.strip_prefix(prefix) {
            return n
                .parse::<u16>()
                .map(|n| SymTarget::Pou(make(n)))
                .map_err(|_| "bad block number");
        }
    }
    match parse_syn(&addr) {
        Ok(Syn::Const(_)) => Err("a symbol cannot name a constant"),
        Ok(Syn::Indirect { .. } | Syn::AddressOf { .. }) => Err("a symbol names a direct address"),
        Ok(s) => Ok(SymTarget::Operand(s)),
        Err(SynError::Malformed(m)) => Err(m),
        Err(SynError::NotAddress) => Err("not an address"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::Area;

    #[test]
    fn tab_table_with_header_and_leading_tabs() {
        let text = "Symbol\tAddress\tComment\r\n\t\tStart_Button\tI0.0\tgreen\r\n启动\tM0.1\r\nMotor_Logic\tSBR0\n";
        let (t, d) = SymbolTable::parse(text, FileId(3));
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(t.len(), 3);
        assert_eq!(
            t.get("Start_Button"),
            Some(&SymTarget::Operand(Syn::Bit {
                area: Area::I,
                byte: 0,
                bit: 0
            }))
        );
        assert!(t.get("启动").is_some());
        assert_eq!(
            t.get("Motor_Logic"),
            Some(&SymTarget::Pou(PouRef::Subroutine(0)))
        );
    }

    #[test]
    fn csv_with_quotes() {
        let text = "Name,Address,Comment\n\"Start Button\",I0.1,\"a, b\"\nSpeed,VW10\n";
        let (t, d) = SymbolTable::parse(text, FileId(0));
        assert!(d.is_empty(), "{d:?}");
        assert!(t.get("Start Button").is_some());
        assert!(t.get("Speed").is_some());
    }

    #[test]
    fn bad_address_and_duplicate_are_located() {
        let text = "A\tI0.0\nB\tXY12\nA\tI0.1\n";
        let (t, d) = SymbolTable::parse(text, FileId(1));
        assert_eq!(t.get("B"), Some(&SymTarget::Invalid));
        assert_eq!(d.len(), 2);
        assert_eq!(
            (d[0].code, d[0].line, d[0].col),
            (Code::SymbolAddress, 2, 3)
        );
        assert_eq!(
            (d[1].code, d[1].line, d[1].col),
            (Code::SymbolDuplicate, 3, 1)
        );
    }
}
