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
        /// A stable diagnostic code (`E0xx` errors, `W0xx` warnings; the Omron dialect's own
        /// codes carry the prefix `OMR-`).
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
    /// Known instruction, not supported yet.
    Unsupported = "E027", Error, "the instruction is known but not supported yet";
    /// CALL with the wrong number of parameters.
    CallParamCount = "E028", Error, "a CALL passes a different number of parameters than the subroutine declares";
    /// Block structure.
    Structure = "E029", Error, "the block structure (OB/SBR/INT blocks, SBR/INT markers) is malformed";
    /// Undecodable input.
    Encoding = "E030", Error, "the file is neither UTF-8 nor GBK text";
    /// One S bit used as segment flag in two blocks.
    ScrBitShared = "E031", Error, "one S bit is used as an SCR segment flag in two blocks";
    /// Jump into a FOR body.
    JumpIntoLoop = "E032", Error, "a JMP enters a FOR loop's body from outside the loop";
    /// Instruction the selected CPU does not have.
    NotAvailable = "E033", Error, "the instruction is not available on the selected CPU";
    /// Actual parameter that does not fit its declared parameter.
    CallParamKind = "E034", Error, "a CALL's actual parameter does not fit the declared parameter (type, width, direction)";
    /// Malformed local variable declaration.
    LocalDecl = "E035", Error, "a local variable declaration (VAR_INPUT … END_VAR) is malformed or not allowed here";
    /// Local variable table beyond the CPU's limits.
    LocalLimit = "E036", Error, "the local variables exceed 64 bytes of L memory or 16 parameters";
    /// `Symbol:Address` whose symbol names another address.
    SymbolMismatch = "E037", Error, "in a `symbol:address` operand the symbol names a different address";
    /// ATCH names no interrupt routine.
    UnknownInterrupt = "E050", Error, "ATCH names an interrupt routine that is not defined, or a block that is not an interrupt routine";
    /// Event number not on the CPU.
    EventNumber = "E051", Error, "the interrupt event does not exist on the selected CPU";
    /// Two PID instructions with one loop number.
    PidLoopTwice = "E060", Error, "two PID instructions use the same loop number";
    /// A data block entry that cannot be loaded.
    DataBlock = "E061", Error, "a DATA_BLOCK line is malformed, or its value does not fit its address";
    /// High-speed counter number not on the CPU.
    HscNumber = "E070", Error, "the high-speed counter does not exist on the selected CPU";
    /// HDEF mode the counter does not have.
    HscMode = "E071", Error, "the high-speed counter does not support this mode on the selected CPU";
    /// Pulse output number not on the CPU.
    PulseNumber = "E072", Error, "the pulse output does not exist on the selected CPU";
    /// Port number not on the CPU.
    PortNumber = "E080", Error, "the communication port does not exist on the selected CPU, or its SM area lacks the port's registers";
    /// Contact or stack operation consuming an unloaded level.
    StackUnderflow = "W001", Warning, "a contact or ALD/OLD/LPP/LRD consumes a stack level that nothing loaded";
    /// Too many live stack levels.
    StackOverflow = "W002", Warning, "more than nine stack levels are live; the bottom one is lost";
    /// Locals reaching into L60–L63.
    LadLocals = "W003", Warning, "the local variables use L60-L63, which LAD/FBD-generated code also uses";
    /// A local variable named without `#`.
    UnprefixedLocal = "W004", Warning, "a name without `#` is taken as the block's local variable";
    /// `Symbol:Address` with a symbol no table defines.
    UncheckedSymbol = "W005", Warning, "in a `symbol:address` operand the symbol is not defined; the address is used";
    /// ENI/DISI in an interrupt routine.
    EnableInInterrupt = "W051", Warning, "ENI or DISI in an interrupt routine has no effect (run-time error 16#0004)";
    /// HDEF in an interrupt routine.
    HdefInInterrupt = "W070", Warning, "HDEF in an interrupt routine has no effect (run-time error 16#0004)";
    /// Two data block values for one V byte.
    DataOverlap = "W060", Warning, "a DATA_BLOCK value sets V bytes an earlier value already set; the later one wins";
    /// A clock instruction on a CPU without a clock.
    NoClock = "W061", Warning, "the selected CPU has no real-time clock: the clock instruction fails with error 16#000C at run time";

    // ---- Omron CP dialect (omron-cp.md §5; the spec's numbers with the `OMR-` prefix) --------
    /// A task program without END.
    OmrNoEnd = "OMR-E001", Error, "the task program has no END(001)";
    /// Instructions after the first END.
    OmrAfterEnd = "OMR-W002", Warning, "instructions after the first END(001) never run";
    /// Output directly on the left bus.
    OmrNoCondition = "OMR-E003", Error, "an output-type instruction has no execution condition";
    /// AND/OR-type instruction at circuit start.
    OmrNoLoad = "OMR-E004", Error, "an AND/OR-type instruction has no preceding LD";
    /// Unclosed logic blocks at an output.
    OmrOpenBlock = "OMR-E005", Error, "logic blocks opened by LD are not combined before an output";
    /// AND LD / OR LD with nothing to combine.
    OmrNothingToCombine = "OMR-E006", Error, "AND LD / OR LD has no pending block to combine";
    /// Wrong number of execution conditions.
    OmrConditionCount = "OMR-E007", Error, "a multi-condition instruction gets the wrong number of execution conditions";
    /// A circuit continued after a multi-condition instruction.
    OmrAfterMulti = "OMR-E008", Error, "a circuit cannot continue after KEEP/CNT/CNTR/TTIM";
    /// Unconditional instruction preceded by conditions.
    OmrNotOnBus = "OMR-E009", Error, "an unconditional instruction must connect directly to the left bus";
    /// TR misuse.
    OmrTr = "OMR-E010", Error, "a TR bit is read before it is set in the circuit, set twice, or used by another instruction";
    /// Unknown or unsupported instruction, or wrong function code.
    OmrInstruction = "OMR-E011", Error, "unknown or unsupported instruction, or a wrong function code";
    /// Option not allowed.
    OmrOption = "OMR-E012", Error, "the option (@, %, !) is not allowed on this instruction";
    /// Operand count or kind mismatch.
    OmrOperand = "OMR-E013", Error, "the operand count or kind does not match the instruction";
    /// Operand outside the model's area.
    OmrRange = "OMR-E014", Error, "the operand lies outside the area of the selected model";
    /// Bad constant.
    OmrConstant = "OMR-E015", Error, "a constant or number has a bad form or range";
    /// Write to a read-only location.
    OmrReadOnly = "OMR-E016", Error, "the operand is written but is read-only";
    /// Output to an input word bit.
    OmrInputWrite = "OMR-W017", Warning, "an output instruction writes a bit of a physical input word";
    /// Multi-word operand crossing areas.
    OmrAreaCross = "OMR-E018", Error, "a multi-word operand crosses from one area into another";
    /// Multi-word operand past its area.
    OmrWords = "OMR-E019", Error, "a double-length operand needs consecutive words its area does not have";
    /// The same bit or word written by two output instructions.
    OmrDuplicateCoil = "OMR-W020", Warning, "the same bit (OUT, OUT NOT, KEEP, DIFU, DIFD) or word (a data instruction's destination) is written by two instructions";
    /// Timer/counter number used twice.
    OmrNumberTwice = "OMR-E021", Error, "a timer, counter or block-program number is used by two instructions";
    /// IL/ILC pairing.
    OmrInterlock = "OMR-E022", Error, "IL(002) and ILC(003) do not pair up (unclosed, unopened or nested)";
    /// Several ILs share one ILC.
    OmrSharedIlc = "OMR-W022", Warning, "several IL(002) share one ILC(003)";
    /// Jump pairing.
    OmrJump = "OMR-E023", Error, "a jump has no JME after it, a JME is defined twice, or a jump crosses an IL region or a block program";
    /// JMP0 without JME0.
    OmrJmp0 = "OMR-E024", Error, "JMP0(515) has no JME0(516)";
    /// A paired instruction split between tasks.
    OmrSplitPair = "OMR-E025", Error, "the two instructions of a pair (IL/ILC, JMP/JME, SBS/SBN, FOR/NEXT, JMP0/JME0, BPRG/BEND) are in different tasks";
    /// A FOR–NEXT region broken.
    OmrInRegion = "OMR-E026", Error, "an instruction is not allowed inside its region (step area, block program, subroutine, FOR–NEXT), or a region is not closed";
    /// An instruction allowed only inside a region.
    OmrOutsideRegion = "OMR-E027", Error, "an instruction allowed only inside a region is outside it (NEXT/BREAK outside FOR–NEXT, IF/ELSE/IEND/BPPS/BPRS … outside BPRG–BEND)";
    /// Code between the subroutine region and END.
    OmrAfterSubroutines = "OMR-W028", Warning, "code between the subroutine region and END never runs";
    /// Subroutine placement.
    OmrSubroutine = "OMR-E029", Error, "a subroutine region is misplaced (in a step area or block program, nested), unclosed or defined twice";
    /// An edge instruction fed only by a constant.
    OmrNeverFires = "OMR-W031", Warning, "a rising-edge instruction fed only by P_On or P_First_Cycle, or a falling-edge one fed only by P_Off, never executes";
    /// A circuit starting with a condition flag.
    OmrFlagAtStart = "OMR-W032", Warning, "a circuit starts with a condition flag";
    /// A condition flag read after another instruction overwrote it, or by a differentiated
    /// instruction.
    OmrFlagOverwritten = "OMR-W033", Warning, "a condition flag is read after an intervening instruction changed it, or its reading depends on a differentiated instruction";
    /// A condition flag read before anything could set it.
    OmrFlagNeverSet = "OMR-W034", Warning, "a condition flag is read before any instruction of the task can have changed it (flags are cleared at task start)";
    /// The program does not fit the model's user memory.
    OmrCapacity = "OMR-E035", Error, "the program needs more steps than the model's user memory (UM) holds";
    /// The task structure.
    OmrTask = "OMR-E036", Error, "no cyclic task starts at RUN, or a task number is given to two programs";
    /// A program assigned to no task.
    OmrUnassigned = "OMR-W037", Warning, "a program is assigned to no task and never runs";
    /// A DM bit on a model without DM bit addressing.
    OmrDmBit = "OMR-E038", Error, "bit access to D words is not supported on the selected model";
    /// An instruction a function-block body may not use.
    OmrFunctionBlock = "OMR-E039", Error, "the instruction is not allowed inside a function-block body";
    /// More than 8 pending blocks.
    OmrDeepBlocks = "OMR-W040", Warning, "more than 8 logic blocks are pending";
    /// More than 13 pending blocks.
    OmrTooDeep = "OMR-E041", Error, "more than 13 logic blocks are pending";
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
            let bare = c.name().strip_prefix("OMR-").unwrap_or(c.name());
            assert!(bare.starts_with(prefix), "{}", c.name());
            assert_eq!(bare.len(), 4, "{}", c.name());
        }
    }
}
