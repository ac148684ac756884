//! Local variable tables (s7-200-more §1.1–§1.3): the declaration lines MicroWIN writes between
//! a block's header and `BEGIN` (`VAR_INPUT` … `END_VAR`), their allocation in L memory (§1.2,
//! [`allocate`]) and the checked table that `#name` operands and `CALL` parameters are resolved
//! against ([`Locals`]).

use crate::operand::{Syn, parse_syn};
use stljit_core::ir::{Address, BitLoc, Loc, PouKind};
use stljit_core::{Area, FileId, Width};
use stljit_source::{Code, Diagnostic, Span, clip};

/// Parameters a subroutine may declare (IN + IN_OUT + OUT; TEMP does not count) [S7-200 manual,
/// recalled; s7-200-more §13 S3].
pub const MAX_PARAMS: usize = 16;

/// Bytes of L memory that LAD/FBD-generated code uses at the end of each frame (L60–L63).
const LAD_RESERVE: u32 = 4;

/// The section of a local variable table a variable is declared in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Section {
    /// `VAR_INPUT`: copied in at the call.
    In,
    /// `VAR_IN_OUT` (also spelled `VAR_INOUT`): copied in and back.
    InOut,
    /// `VAR_OUTPUT`: copied back after the call.
    Out,
    /// `VAR` / `VAR_TEMP`: the block's own scratch memory.
    Temp,
}

impl Section {
    /// Every section, in allocation (table) order.
    pub const ALL: [Section; 4] = [Section::In, Section::InOut, Section::Out, Section::Temp];

    /// The section a keyword opens (case-insensitive): `VAR_INOUT` is accepted for
    /// `VAR_IN_OUT` and `VAR_TEMP` for `VAR` [design].
    pub fn from_keyword(kw: &str) -> Option<Section> {
        let k = kw.to_ascii_uppercase();
        Some(match k.as_str() {
            "VAR_INPUT" => Section::In,
            "VAR_IN_OUT" | "VAR_INOUT" => Section::InOut,
            "VAR_OUTPUT" => Section::Out,
            "VAR" | "VAR_TEMP" => Section::Temp,
            _ => return None,
        })
    }

    /// The keyword MicroWIN exports for it.
    pub fn keyword(self) -> &'static str {
        match self {
            Section::In => "VAR_INPUT",
            Section::InOut => "VAR_IN_OUT",
            Section::Out => "VAR_OUTPUT",
            Section::Temp => "VAR",
        }
    }

    /// The name MicroWIN's variable table shows (`IN`, `IN_OUT`, `OUT`, `TEMP`).
    pub fn name(self) -> &'static str {
        match self {
            Section::In => "IN",
            Section::InOut => "IN_OUT",
            Section::Out => "OUT",
            Section::Temp => "TEMP",
        }
    }

    /// Whether variables of this section are parameters of a CALL.
    pub fn is_param(self) -> bool {
        self != Section::Temp
    }
}

/// The data type of a local variable (the Micro/WIN local types that fit L memory).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LocalType {
    /// One bit.
    Bool,
    /// 8 bits.
    Byte,
    /// 16 bits, unsigned by convention.
    Word,
    /// 16 bits, signed.
    Int,
    /// 32 bits, unsigned by convention (also a pointer).
    DWord,
    /// 32 bits, signed.
    DInt,
    /// IEEE binary32.
    Real,
}

impl LocalType {
    /// Every type.
    pub const ALL: [LocalType; 7] = [
        LocalType::Bool,
        LocalType::Byte,
        LocalType::Word,
        LocalType::Int,
        LocalType::DWord,
        LocalType::DInt,
        LocalType::Real,
    ];

    /// The keyword (`BOOL`, `INT`, …).
    pub fn name(self) -> &'static str {
        match self {
            LocalType::Bool => "BOOL",
            LocalType::Byte => "BYTE",
            LocalType::Word => "WORD",
            LocalType::Int => "INT",
            LocalType::DWord => "DWORD",
            LocalType::DInt => "DINT",
            LocalType::Real => "REAL",
        }
    }

    /// The width of a value type; `None` for BOOL.
    pub fn width(self) -> Option<Width> {
        match self {
            LocalType::Bool => None,
            LocalType::Byte => Some(Width::Byte),
            LocalType::Word | LocalType::Int => Some(Width::Word),
            LocalType::DWord | LocalType::DInt | LocalType::Real => Some(Width::DWord),
        }
    }

    /// The type a keyword names (case-insensitive), or why it cannot be a local's type.
    fn parse(text: &str) -> Result<LocalType, String> {
        let up = text.to_ascii_uppercase();
        if let Some(t) = LocalType::ALL.into_iter().find(|t| t.name() == up) {
            return Ok(t);
        }
        Err(if up == "STRING" || up == "CHAR" {
            format!(
                "{up} locals are not supported: a string does not fit the L-memory model of \
                 parameters (s7-200-more §1.1)"
            )
        } else {
            format!("unknown type `{}`", clip(text))
        })
    }
}

/// One declaration as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Decl {
    /// The name, without `#`.
    pub(crate) name: String,
    /// Its type.
    pub(crate) ty: LocalType,
    /// Its section.
    pub(crate) section: Section,
    /// Where the name is written.
    pub(crate) span: Span,
}

const ALLOWED_TYPES: &str = "allowed types: BOOL, BYTE, WORD, INT, DWORD, DINT, REAL";

/// Reads one line of a `VAR_…` section (`RAW:INT;  // raw value`); `Ok(None)` for a blank or
/// comment line. The `;` may be left out.
pub(crate) fn parse_decl(
    raw: &str,
    line: u32,
    file: FileId,
    section: Section,
) -> Result<Option<Decl>, Diagnostic> {
    let code = raw.find("//").map_or(raw, |i| &raw[..i]);
    let col_of = |s: &str| {
        let off = (s.as_ptr() as usize).saturating_sub(raw.as_ptr() as usize);
        let chars = raw.get(..off).map_or(off, |p| p.chars().count());
        u32::try_from(chars + 1).unwrap_or(u32::MAX)
    };
    let span_of = |s: &str| Span {
        file,
        line,
        col: col_of(s),
        len: u32::try_from(s.chars().count()).unwrap_or(u32::MAX),
    };
    let err = |s: &str, msg: String, help: &str| {
        Err(Diagnostic::new(Code::LocalDecl, span_of(s), s, msg).help(help))
    };
    let text = code.trim_matches(|c: char| c.is_whitespace() || c == '\u{feff}');
    if text.is_empty() {
        return Ok(None);
    }
    let Some((name, ty)) = text.split_once(':') else {
        return err(
            text,
            format!(
                "expected a declaration `name:TYPE;`, found `{}`",
                clip(text)
            ),
            ALLOWED_TYPES,
        );
    };
    let name = name.trim();
    let name = name.strip_prefix('#').unwrap_or(name);
    let ty = ty.trim();
    let ty = ty.strip_suffix(';').unwrap_or(ty).trim_end();
    if name.is_empty() || name.contains(char::is_whitespace) || name.contains(',') {
        return err(
            if name.is_empty() { text } else { name },
            format!("`{}` is not a variable name", clip(name)),
            "a name is one word, e.g. RAW or 原始值",
        );
    }
    match LocalType::parse(ty) {
        Ok(ty) => Ok(Some(Decl {
            name: name.to_owned(),
            ty,
            section,
            span: span_of(name),
        })),
        Err(why) => err(if ty.is_empty() { text } else { ty }, why, ALLOWED_TYPES),
    }
}

/// The L address of every item (section, type) of a local variable table, in the items' order,
/// and the bytes used: s7-200-more §1.2. Items are allocated in table order (IN, IN_OUT, OUT,
/// TEMP; declaration order inside a section), one to eight consecutive BOOLs share a byte,
/// values sit on byte boundaries without alignment, and BOOL packing continues across section
/// boundaries [design, §13 S2].
pub fn allocate(items: &[(Section, LocalType)]) -> (Vec<Address>, u32) {
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by_key(|&i| Section::ALL.iter().position(|&s| s == items[i].0));
    let mut addrs = vec![Address::Bit(l_bit(0, 0)); items.len()];
    let (mut off, mut bit, mut open) = (0u32, 0u8, false);
    for i in order {
        addrs[i] = match items[i].1.width() {
            None => {
                if !open {
                    open = true;
                    bit = 0;
                } else if bit == 8 {
                    off += 1;
                    bit = 0;
                }
                bit += 1;
                Address::Bit(l_bit(off, bit - 1))
            }
            Some(width) => {
                if open {
                    off += 1;
                    open = false;
                }
                let at = off;
                off += width.bytes();
                Address::Value {
                    loc: Loc {
                        area: Area::L,
                        offset: at,
                    },
                    width,
                }
            }
        };
    }
    (addrs, off + u32::from(open))
}

fn l_bit(byte: u32, bit: u8) -> BitLoc {
    BitLoc {
        area: Area::L,
        byte,
        bit,
    }
}

/// One checked local variable.
#[derive(Clone, Debug)]
pub(crate) struct Local {
    /// Its declaration.
    pub(crate) decl: Decl,
    /// Its L address.
    pub(crate) addr: Address,
    /// False when its declaration had an error (already reported): uses stay silent.
    pub(crate) valid: bool,
}

impl Local {
    /// The operand `#name` stands for: the absolute L operand of its address and width.
    pub(crate) fn syn(&self) -> Syn {
        match self.addr {
            Address::Bit(b) => Syn::Bit {
                area: b.area,
                byte: b.byte,
                bit: b.bit,
            },
            Address::Value { loc, width } => Syn::Mem {
                area: loc.area,
                width,
                offset: loc.offset,
            },
        }
    }

    /// `IN INT LW1`, for messages.
    pub(crate) fn describe(&self) -> String {
        let at = match self.addr {
            Address::Bit(b) => format!("L{}.{}", b.byte, b.bit),
            Address::Value { loc, width } => {
                format!("L{}{}", crate::spelling::width_letter(width), loc.offset)
            }
        };
        format!("{} {} {at}", self.decl.section.name(), self.decl.ty.name())
    }
}

/// The checked local variable table of one POU.
#[derive(Clone, Debug, Default)]
pub(crate) struct Locals {
    vars: Vec<Local>,
}

impl Locals {
    /// Checks and allocates the declarations of a POU of kind `kind`: parameters only in
    /// subroutines, unique names that are neither mnemonics nor addresses, at most
    /// [`MAX_PARAMS`] parameters, at most 64 bytes (a warning above 60).
    pub(crate) fn build(decls: Vec<Decl>, kind: PouKind, diags: &mut Vec<Diagnostic>) -> Locals {
        let items: Vec<_> = decls.iter().map(|d| (d.section, d.ty)).collect();
        let (addrs, _) = allocate(&items);
        let mut vars: Vec<Local> = Vec::with_capacity(decls.len());
        let mut params = 0;
        let (mut warned, mut overflowed) = (false, false);
        for (decl, addr) in decls.into_iter().zip(addrs) {
            let report = |code: Code, msg: String, help: String| {
                Diagnostic::new(code, decl.span, &decl.name, msg).help(help)
            };
            let mut valid = true;
            if decl.section.is_param() && !matches!(kind, PouKind::Subroutine(_)) {
                diags.push(report(
                    Code::LocalDecl,
                    format!(
                        "`{}` is declared {}, but only subroutines have parameters",
                        clip(&decl.name),
                        decl.section.keyword()
                    ),
                    "the main program and interrupt routines may only declare TEMP variables (VAR)"
                        .into(),
                ));
                valid = false;
            } else if let Some(prev) = vars.iter().find(|v| v.decl.name == decl.name) {
                diags.push(report(
                    Code::LocalDecl,
                    format!("local variable `{}` is declared twice", clip(&decl.name)),
                    format!("first declared on line {}", prev.decl.span.line),
                ));
                valid = false;
            } else if let Some(why) = reserved(&decl.name) {
                diags.push(report(
                    Code::LocalDecl,
                    format!("`{}` cannot name a local variable: {why}", clip(&decl.name)),
                    "choose a name that is neither an instruction nor an address".into(),
                ));
                valid = false;
            }
            if decl.section.is_param() {
                params += 1;
                if params == MAX_PARAMS + 1 {
                    diags.push(report(
                        Code::LocalLimit,
                        format!("more than {MAX_PARAMS} parameters"),
                        format!(
                            "a subroutine has at most {MAX_PARAMS} IN, IN_OUT and OUT parameters \
                             together; pass more data through V memory"
                        ),
                    ));
                }
            }
            let end = match addr {
                Address::Bit(b) => b.byte + 1,
                Address::Value { loc, width } => loc.offset + width.bytes(),
            };
            if end > 64 {
                if !std::mem::replace(&mut overflowed, true) {
                    diags.push(report(
                        Code::LocalLimit,
                        format!("local variable `{}` ends at L byte {end}", clip(&decl.name)),
                        "a block has 64 bytes of local memory (LB0-LB63)".into(),
                    ));
                }
                valid = false;
            } else if end > 64 - LAD_RESERVE && !warned {
                warned = true;
                diags.push(report(
                    Code::LadLocals,
                    format!(
                        "local variable `{}` reaches into L{}-L63",
                        clip(&decl.name),
                        64 - LAD_RESERVE
                    ),
                    "LAD and FBD use the last 4 bytes of L memory; a block written in STL only may use them".into(),
                ));
            }
            vars.push(Local { decl, addr, valid });
        }
        Locals { vars }
    }

    /// The variable called `name`.
    pub(crate) fn get(&self, name: &str) -> Option<&Local> {
        self.vars.iter().find(|v| v.decl.name == name)
    }

    /// The parameters (IN, IN_OUT, OUT) in table order: the order of a CALL's actuals.
    pub(crate) fn params(&self) -> Vec<&Local> {
        let mut p: Vec<&Local> = self
            .vars
            .iter()
            .filter(|v| v.decl.section.is_param())
            .collect();
        p.sort_by_key(|v| Section::ALL.iter().position(|&s| s == v.decl.section));
        p
    }

    /// The declared names, for "did you mean" help.
    pub(crate) fn names(&self) -> Vec<&str> {
        self.vars.iter().map(|v| v.decl.name.as_str()).collect()
    }
}

/// Why `name` may not name a local variable: it is a mnemonic, an address or a number.
fn reserved(name: &str) -> Option<&'static str> {
    let up = name.to_ascii_uppercase();
    if crate::mnemonics::group(&up).is_some() || crate::mnemonics::family(&up).is_some() {
        return Some("it is an instruction mnemonic");
    }
    match parse_syn(name) {
        Ok(Syn::Const(_)) => Some("it is a number"),
        Ok(_) => Some("it is an address"),
        Err(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn addr(a: &Address) -> String {
        match a {
            Address::Bit(b) => format!("L{}.{}", b.byte, b.bit),
            Address::Value { loc, width } => {
                format!("L{}{}", crate::spelling::width_letter(*width), loc.offset)
            }
        }
    }

    /// s7-200-more §1.2's worked table (the `SCALE` example of §1.1).
    #[test]
    fn scale_example_allocation() {
        use LocalType::*;
        use Section::*;
        let items = [
            (In, Bool),
            (In, Int),
            (In, Int),
            (InOut, DInt),
            (Out, Int),
            (Out, Bool),
            (Temp, DInt),
        ];
        let (a, used) = allocate(&items);
        let got: Vec<_> = a.iter().map(addr).collect();
        assert_eq!(
            got,
            ["L0.0", "LW1", "LW3", "LD5", "LW9", "L11.0", "LD12"],
            "§1.2 table"
        );
        assert_eq!(used, 16);
    }

    /// s7-200-more §12 M2: nine BOOLs spill into a second byte, sections are allocated in table
    /// order whatever their textual order.
    #[test]
    fn m2_allocation() {
        use LocalType::*;
        use Section::*;
        let mut items = vec![(Temp, Real), (Out, Bool), (Out, Word)];
        items.extend(std::iter::repeat_n((In, Bool), 9));
        items.push((In, Byte));
        let (a, used) = allocate(&items);
        let got: Vec<_> = a.iter().map(addr).collect();
        assert_eq!(got[0], "LD6", "t");
        assert_eq!(got[1], "L3.0", "o");
        assert_eq!(got[2], "LW4", "w");
        assert_eq!(
            &got[3..11],
            [
                "L0.0", "L0.1", "L0.2", "L0.3", "L0.4", "L0.5", "L0.6", "L0.7"
            ]
        );
        assert_eq!(got[11], "L1.0", "b9");
        assert_eq!(got[12], "LB2", "x");
        assert_eq!(used, 10);
    }

    #[test]
    fn declaration_lines() {
        let d = parse_decl("RAW:INT;\t// raw value", 4, FileId(0), Section::In)
            .unwrap()
            .unwrap();
        assert_eq!(
            (d.name.as_str(), d.ty, d.span.col),
            ("RAW", LocalType::Int, 1)
        );
        let d = parse_decl("\t 原始值 : real ", 1, FileId(0), Section::Temp)
            .unwrap()
            .unwrap();
        assert_eq!(
            (d.name.as_str(), d.ty, d.span.col),
            ("原始值", LocalType::Real, 3)
        );
        assert_eq!(
            parse_decl("  // only a comment", 1, FileId(0), Section::In),
            Ok(None)
        );
        let e = parse_decl("TXT:STRING;", 7, FileId(0), Section::In).unwrap_err();
        assert_eq!((e.code, e.line, e.col), (Code::LocalDecl, 7, 5));
        assert!(e.message.contains("STRING"));
        let e = parse_decl("JUST_A_NAME", 1, FileId(0), Section::In).unwrap_err();
        assert_eq!(e.code, Code::LocalDecl);
    }
}
