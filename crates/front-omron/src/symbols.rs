//! CX-Programmer symbol tables: one symbol a line, `Name<TAB>Data type<TAB>Address<TAB>Comment`
//! (the export format), or the same columns separated by `,` or `;` (CSV), with an optional
//! header line. Names may be any text, including non-ASCII.

use crate::operand::{Syn, SynError, parse_syn};
use stljit_core::FileId;
use stljit_source::Diagnostic;
use stljit_source::symbols::{self, SymbolMap};

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
    map: SymbolMap<SymTarget>,
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
        self.map.names()
    }

    /// The symbol's target.
    pub(crate) fn get(&self, name: &str) -> Option<&SymTarget> {
        self.map.get(name)
    }

    /// Parses a symbol-table text (already decoded). Bad lines become diagnostics on `file`;
    /// the good lines still form the table.
    pub fn parse(text: &str, file: FileId) -> (SymbolTable, Vec<Diagnostic>) {
        let mut table = SymbolTable::default();
        let mut diags = Vec::new();
        for l in symbols::lines(text, file) {
            // Name, data type, address: the address is the third column, or the second when
            // a line has only two.
            let name = l.first();
            let addr = match l.fields.len() {
                0 | 1 => None,
                2 => Some(l.fields[1]),
                _ => Some(l.fields[2]),
            };
            let Some(addr) = addr else {
                diags.push(symbols::missing_address(
                    &l,
                    "write Name<TAB>Data type<TAB>Address[<TAB>Comment] or Name,Type,Address[,Comment]",
                ));
                continue;
            };
            let name_text = symbols::unquote(name);
            let target = match parse_syn(&symbols::unquote(addr)) {
                Ok(Syn::Const(..)) => Err("a symbol cannot name a constant"),
                Ok(Syn::Indirect(_)) => Err("a symbol names a direct address"),
                Ok(Syn::Unsupported(what)) => Err(what),
                Ok(s) => Ok(s),
                Err(SynError::Malformed(m)) => Err(m),
                Err(SynError::NotAddress) => Err("not an Omron address"),
            };
            let result = match target {
                Ok(t) => table.map.define(&l, name, name_text, SymTarget::Operand(t)),
                Err(why) => {
                    let d = symbols::bad_address(&l, addr, &name_text, why, ALLOWED);
                    table.map.define_invalid(&l, name_text, SymTarget::Invalid);
                    Err(d)
                }
            };
            diags.extend(result.err());
        }
        (table, diags)
    }
}

/// The address forms a symbol may name, for messages.
const ALLOWED: &str =
    "CIO bits and words (0.00, 100), W/H/A bits and words, D words, T/C numbers, P_ flags";

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::omron::WordArea;
    use stljit_source::Code;

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
