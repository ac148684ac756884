//! The diagnostic codes: one typed table, each code with its stable name, severity and a one-line
//! explanation. `docs/diagnostics.md` lists the same codes (a test keeps the two in sync).

use std::fmt;

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// The program is not accepted; no IR is produced.
    Error,
    /// Suspicious but legal; the IR is still produced.
    Warning,
}

impl Severity {
    /// `error` or `warning`.
    pub fn name(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        }
    }
}

macro_rules! codes {
    ($($(#[$doc:meta])* $variant:ident = $name:literal, $sev:ident, $explain:literal;)*) => {
        /// A stable diagnostic code (`E0xx` errors, `W0xx` warnings).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum Code {
            $($(#[$doc])* $variant,)*
        }

        impl Code {
            /// Every code, in table order.
            pub const ALL: &'static [Code] = &[$(Code::$variant,)*];

            /// The stable name (`E003`).
            pub fn name(self) -> &'static str {
                match self { $(Code::$variant => $name,)* }
            }

            /// Whether the code is an error or a warning.
            pub fn severity(self) -> Severity {
                match self { $(Code::$variant => Severity::$sev,)* }
            }

            /// One line saying what the code means.
            pub fn explain(self) -> &'static str {
                match self { $(Code::$variant => $explain,)* }
            }
        }
    };
}

codes! {
    /// Unknown mnemonic.
    UnknownMnemonic = "E001", Error, "the instruction mnemonic is not known";
    /// Missing or extra operands.
    OperandCount = "E002", Error, "the instruction has too few or too many operands";
    /// Address outside the CPU profile's area.
    OutOfRange = "E003", Error, "the address lies outside the area of the selected CPU";
    /// Operand of the wrong class.
    OperandClass = "E004", Error, "the operand kind is not allowed for this instruction operand";
    /// Operand of the wrong width.
    OperandWidth = "E005", Error, "the operand has the wrong width (bit, byte, word or dword)";
    /// Write to a read-only operand.
    ReadOnly = "E006", Error, "the operand is written but is read-only (SM0-SM29, AIW, HC, constants)";
    /// Malformed operand text.
    Malformed = "E007", Error, "the operand or constant is malformed";
    /// Constant or number out of range.
    NumberRange = "E008", Error, "a constant or number is outside the range the operand allows";
    /// Unknown symbol.
    UnknownSymbol = "E009", Error, "the operand is neither an address nor a known symbol";
    /// Bad address in the symbol table.
    SymbolAddress = "E010", Error, "a symbol-table line has a missing or invalid address";
    /// Duplicate symbol name.
    SymbolDuplicate = "E011", Error, "a symbol name is defined twice in the symbol table";
    /// Jump to a label that does not exist.
    MissingLabel = "E012", Error, "a JMP names a label that no LBL in the same block defines";
    /// Label defined twice.
    DuplicateLabel = "E013", Error, "a label is defined twice in one block";
    /// Jump to a label of another block.
    JumpAcrossBlocks = "E014", Error, "a JMP names a label defined only in another block";
    /// Unknown subroutine.
    UnknownSubroutine = "E015", Error, "a CALL names a subroutine that is not defined";
    /// FOR without NEXT or NEXT without FOR.
    ForNext = "E016", Error, "FOR and NEXT do not pair up within the block";
    /// FOR nesting too deep.
    ForDepth = "E017", Error, "FOR loops are nested deeper than the CPU allows";
    /// SCR segment structure.
    ScrNesting = "E018", Error, "LSCR/SCRE segments are nested, unclosed, or SCRT/CSCRE is outside one";
    /// Instruction not allowed inside an SCR segment.
    InScr = "E019", Error, "JMP, LBL, FOR, NEXT and END are not allowed inside an SCR segment";
    /// Instruction not allowed in this kind of block.
    WrongBlock = "E020", Error, "the instruction is not allowed in this kind of block (END in a subroutine, RET in main)";
    /// Timer used as two kinds.
    TimerKindConflict = "E021", Error, "one timer number is used by two timer kinds";
    /// Timer kind not allowed for the number.
    TimerKindNumber = "E022", Error, "the CPU does not allow this timer kind on this timer number";
    /// Counter used as two kinds.
    CounterKindConflict = "E023", Error, "one counter number is used by two counter kinds";
    /// Too many edge instructions.
    TooManyEdges = "E024", Error, "the program has more EU/ED instructions than the CPU allows";
    /// Odd analog address.
    OddAnalog = "E025", Error, "AIW/AQW addresses must be even";
    /// LDS out of range.
    LdsRange = "E026", Error, "LDS takes a stack level 0..8";
    /// Out-of-scope instruction.
    Unsupported = "E027", Error, "the instruction is not supported in this version";
    /// Subroutine parameters.
    SubroutineParams = "E028", Error, "subroutine parameters are not supported yet";
    /// Block structure.
    Structure = "E029", Error, "the block structure (OB/SBR/INT blocks, SBR/INT markers) is malformed";
    /// Undecodable input.
    Encoding = "E030", Error, "the file is neither UTF-8 nor GBK text";
    /// One S bit used as segment flag in two blocks.
    ScrBitShared = "E031", Error, "one S bit is used as an SCR segment flag in two blocks";
    /// Jump into a FOR body.
    JumpIntoLoop = "E032", Error, "a JMP enters a FOR loop's body from outside the loop";
    /// Contact or stack operation consuming an unloaded level.
    StackUnderflow = "W001", Warning, "a contact or ALD/OLD/LPP/LRD consumes a stack level that nothing loaded";
    /// Too many live stack levels.
    StackOverflow = "W002", Warning, "more than nine stack levels are live; the bottom one is lost";
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_prefixed_by_severity() {
        let mut seen = std::collections::HashSet::new();
        for c in Code::ALL {
            assert!(seen.insert(c.name()), "{} twice", c.name());
            let prefix = match c.severity() {
                Severity::Error => 'E',
                Severity::Warning => 'W',
            };
            assert!(c.name().starts_with(prefix));
            assert_eq!(c.name().len(), 4);
        }
    }
}
