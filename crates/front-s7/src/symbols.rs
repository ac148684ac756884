//! MicroWIN symbol tables: one symbol a line, `name<TAB>address[<TAB>comment]` (leading tabs and
//! a header line allowed) or the same columns as CSV. Names may be any text, including non-ASCII.

use crate::operand::{Syn, SynError, parse_syn};
use stljit_core::FileId;
use stljit_source::Diagnostic;
use stljit_source::symbols::{self, SymbolMap};

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

    /// Every symbol name, in no particular order (for reverse look-ups by the CLI).
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
            let (Some(&name), Some(&addr)) = (l.fields.first(), l.fields.get(1)) else {
                diags.push(symbols::missing_address(
                    &l,
                    "write name<TAB>address[<TAB>comment] or name,address[,comment]",
                ));
                continue;
            };
            let name_text = symbols::unquote(name);
            let result = match parse_target(addr) {
                Ok(t) => table.map.define(&l, name, name_text, t),
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
    "bit (I0.0), byte/word/dword (VB10, VW10, VD10), T, C, AC, HC, AIW, AQW, SBRn, INTn, OB1";

fn parse_target(addr: &str) -> Result<SymTarget, &'static str> {
    let addr = symbols::unquote(addr);
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
    use stljit_source::Code;

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
