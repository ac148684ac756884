//! The dialect-neutral IR.
//!
//! A [`Program`] is a list of POUs (main program first, then subroutines), each a flat list of
//! [`Op`]s with a parallel list of source locations. Control flow is explicit and resolved: jumps
//! name a [`LabelId`] whose position is in [`Pou::labels`], calls name a [`PouId`], FOR/NEXT and SCR
//! ops name their partner's [`OpIdx`]. Every operand is resolved to an [`Area`] and a byte offset
//! (checked against the profile at compile time) or to a constant or a pointer read at run time.
//!
//! **Boolean evaluation** uses a *logic stack* of [`Program::logic_stack_depth`] one-bit levels
//! (`S0` is the top). A push loses the bottom level, a pop fills it with 0. S7-200 STL maps onto it
//! one to one with depth 9; a front end whose stack is unbounded (Omron's block stack) picks a depth
//! its static checks prove is never exceeded, so the truncation rule never fires. Engines may keep
//! the stack in a register or in SSA values, as long as truncation and fill are preserved.
//!
//! **Power flow** `PF = S0 AND gate`, where the gate is 1 outside gated regions (SCR segments).
//! Consumers (coils, boxes, timers, jumps, ...) read `PF`; no consumer pops the stack.

use crate::area::{Area, Width};
use crate::index::{CounterId, EdgeSlot, FileId, LabelId, OpIdx, PouId, TimerId};
use crate::profile::{ProfileId, Resolution};

/// A checked program, ready for any engine.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// The CPU profile the program was checked against; fixes the image layout.
    pub profile: ProfileId,
    /// The POUs; `pous[0]` is the main program.
    pub pous: Vec<Pou>,
    /// Timers the program uses, with their kind and resolution fixed at compile time.
    pub timers: Vec<TimerDecl>,
    /// Counters the program uses, with their kind.
    pub counters: Vec<CounterDecl>,
    /// One entry per edge slot ([`EdgeSlot`] indexes it).
    pub edges: Vec<EdgeDecl>,
    /// Number of logic-stack levels (9 for S7-200 STL).
    pub logic_stack_depth: u8,
    /// Source file names, indexed by [`FileId`].
    pub files: Vec<String>,
}

impl Program {
    /// The main program's id.
    pub const MAIN: PouId = PouId(0);

    /// The POU with id `id`.
    pub fn pou(&self, id: PouId) -> &Pou {
        &self.pous[id.index()]
    }

    /// Total number of IR ops over all POUs.
    pub fn op_count(&self) -> usize {
        self.pous.iter().map(|p| p.ops.len()).sum()
    }
}

/// What a POU is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PouKind {
    /// The main program (OB1); runs once per scan.
    Main,
    /// A subroutine with its number (`SBR0`).
    Subroutine(u16),
    /// An interrupt routine with its number; parsed and checked, never executed (spec P8).
    Interrupt(u16),
}

/// A program organisation unit: the main program or a subroutine.
#[derive(Clone, Debug, PartialEq)]
pub struct Pou {
    /// Symbolic name (`MAIN`, `Motor_Logic`, `SBR0`).
    pub name: String,
    /// Main, subroutine or interrupt.
    pub kind: PouKind,
    /// The instructions.
    pub ops: Vec<Op>,
    /// Source location of each op (`locs[i]` belongs to `ops[i]`).
    pub locs: Vec<SrcLoc>,
    /// Position of each label's [`Op::Label`].
    pub labels: Vec<OpIdx>,
}

impl Pou {
    /// The op a label marks.
    pub fn label_target(&self, label: LabelId) -> OpIdx {
        self.labels[label.index()]
    }
}

/// A position in a source file, 1-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct SrcLoc {
    /// The file.
    pub file: FileId,
    /// Line, 1-based.
    pub line: u32,
    /// Column (in characters), 1-based.
    pub col: u32,
}

/// Timer behaviour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TimerKind {
    /// On-delay (`TON`).
    On,
    /// Retentive on-delay (`TONR`).
    Retentive,
    /// Off-delay (`TOF`, `TOFF`).
    Off,
}

impl TimerKind {
    /// The value stored in the timer's private `KIND` byte (0 means unused).
    pub fn code(self) -> u8 {
        match self {
            TimerKind::On => 1,
            TimerKind::Retentive => 2,
            TimerKind::Off => 3,
        }
    }

    /// The S7-200 mnemonic.
    pub fn mnemonic(self) -> &'static str {
        match self {
            TimerKind::On => "TON",
            TimerKind::Retentive => "TONR",
            TimerKind::Off => "TOF",
        }
    }
}

/// A timer the program uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimerDecl {
    /// Its number.
    pub id: TimerId,
    /// Its only kind in this program.
    pub kind: TimerKind,
    /// Its resolution, from the profile's table.
    pub resolution: Resolution,
}

/// Counter behaviour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CounterKind {
    /// Count up (`CTU`): `CU = S1`, `R = S0`.
    Up,
    /// Count down (`CTD`): `CD = S1`, `LD = S0`.
    Down,
    /// Count up/down (`CTUD`): `CU = S2`, `CD = S1`, `R = S0`.
    UpDown,
}

impl CounterKind {
    /// The value stored in the counter's private `KIND` byte (0 means unused).
    pub fn code(self) -> u8 {
        match self {
            CounterKind::Up => 1,
            CounterKind::Down => 2,
            CounterKind::UpDown => 3,
        }
    }

    /// The S7-200 mnemonic.
    pub fn mnemonic(self) -> &'static str {
        match self {
            CounterKind::Up => "CTU",
            CounterKind::Down => "CTD",
            CounterKind::UpDown => "CTUD",
        }
    }
}

/// A counter the program uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CounterDecl {
    /// Its number.
    pub id: CounterId,
    /// Its kind (a counter number used by two kinds is rejected by the front end).
    pub kind: CounterKind,
}

/// One edge-memory slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeDecl {
    /// Value of the memory at cold start (0 for S7-200; Omron's rising edges start at 1).
    pub init: bool,
}

/// A byte-addressed location: `offset` is the first byte of the value inside `area` (for
/// accumulators, `4n + 4 - width`, so `AC1` as a byte is offset 7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Loc {
    /// The area.
    pub area: Area,
    /// Byte offset inside the area (inside the current frame for `L`).
    pub offset: u32,
}

/// A single bit: bit `bit` (0 = LSB) of byte `byte` of `area`. Timer and counter bits are bit 0
/// of their byte in [`Area::TimerBit`] / [`Area::CounterBit`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BitLoc {
    /// The area.
    pub area: Area,
    /// Byte offset inside the area.
    pub byte: u32,
    /// Bit number 0..=7.
    pub bit: u8,
}

/// A value operand. Its width is fixed by the instruction that uses it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Operand {
    /// A memory location.
    Mem(Loc),
    /// A constant bit pattern (reals as their IEEE bits), truncated to the operand width.
    Const(u32),
    /// `*VD100`, `*LD4`, `*AC1`: the dword at this location is a pointer, resolved at run time.
    Indirect(Loc),
    /// `&VB100`: the pointer to a location, a dword constant (spec §1.6 encoding).
    AddressOf(Loc),
}

/// Operand type of a compare contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CmpType {
    /// Unsigned byte.
    Byte,
    /// Signed 16-bit integer.
    Int,
    /// Signed 32-bit integer.
    DInt,
    /// IEEE binary32; a NaN operand is a fatal error.
    Real,
}

impl CmpType {
    /// The width of both operands.
    pub fn width(self) -> Width {
        match self {
            CmpType::Byte => Width::Byte,
            CmpType::Int => Width::Word,
            CmpType::DInt | CmpType::Real => Width::DWord,
        }
    }
}

/// Compare relation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CmpOp {
    /// `=`
    Eq,
    /// `<>`
    Ne,
    /// `>=`
    Ge,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `<`
    Lt,
}

/// The value a contact produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Contact {
    /// A bit of the image, optionally inverted.
    Bit {
        /// The bit.
        bit: BitLoc,
        /// `LDN`/`AN`/`ON`.
        negated: bool,
    },
    /// A bit of the physical input copy (`LDI`, `AI`, ...), optionally inverted.
    ImmediateInput {
        /// The input bit (area `I`).
        bit: BitLoc,
        /// `LDNI`/`ANI`/`ONI`.
        negated: bool,
    },
    /// A compare; evaluated regardless of power flow.
    Compare {
        /// Operand type.
        ty: CmpType,
        /// Relation.
        op: CmpOp,
        /// Left operand.
        lhs: Operand,
        /// Right operand.
        rhs: Operand,
    },
}

/// One IR instruction.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    // ---- logic stack -------------------------------------------------------------------------
    /// Push the contact's value (`LD`).
    Load(Contact),
    /// `S0 &= value` (`A`).
    And(Contact),
    /// `S0 |= value` (`O`).
    Or(Contact),
    /// `S0 = !S0`.
    Not,
    /// Pop twice, push the AND (`ALD`); the bottom fills with 0.
    AndBlock,
    /// Pop twice, push the OR (`OLD`).
    OrBlock,
    /// Push a copy of `S0` (`LPS`).
    Dup,
    /// `S0 = S1` (`LRD`).
    ReadSecond,
    /// Pop (`LPP`).
    Pop,
    /// Push a copy of level `n`, taken before the push (`LDS n`).
    Pick(u8),
    /// `S0 &= ENO` (`AENO`).
    AndEno,
    /// Edge detector on `S0 AND gate` (`EU`/`ED`); replaces `S0`.
    Edge {
        /// Its memory.
        slot: EdgeSlot,
        /// `ED` (1 → 0) instead of `EU` (0 → 1).
        falling: bool,
    },

    // ---- bit outputs -------------------------------------------------------------------------
    /// `bit := PF` (`=`); with `immediate`, also the physical output copy (`=I`).
    Assign {
        /// The coil.
        bit: BitLoc,
        /// `=I`.
        immediate: bool,
    },
    /// If PF: write `value` into `count` consecutive bits from `start` (`S`/`R`/`SI`/`RI`; `S` on
    /// timer/counter bits steps one timer/counter per bit). A range past the area end is error
    /// 0x0091 and writes nothing.
    SetRange {
        /// First bit.
        start: BitLoc,
        /// Count, a byte operand (0 = no-op).
        count: Operand,
        /// 1 for S, 0 for R.
        value: bool,
        /// `SI`/`RI`: also the physical output copy.
        immediate: bool,
    },
    /// If PF: fully reset `count` timers from `first` (`R T37, n`).
    ResetTimers {
        /// First timer.
        first: TimerId,
        /// Count, a byte operand.
        count: Operand,
    },
    /// If PF: fully reset `count` counters from `first` (`R C5, n`).
    ResetCounters {
        /// First counter.
        first: CounterId,
        /// Count, a byte operand.
        count: Operand,
    },

    // ---- timers and counters -----------------------------------------------------------------
    /// A timer instruction; `IN = PF`, preset a word operand.
    Timer {
        /// TON / TONR / TOF.
        kind: TimerKind,
        /// Which timer.
        timer: TimerId,
        /// The preset (PT), a word operand.
        preset: Operand,
    },
    /// A counter instruction; inputs read from stack levels per [`CounterKind`].
    Counter {
        /// CTU / CTD / CTUD.
        kind: CounterKind,
        /// Which counter.
        counter: CounterId,
        /// The preset (PV), a word operand.
        preset: Operand,
    },

    // ---- boxes -------------------------------------------------------------------------------
    /// A box instruction: runs when PF, sets ENO.
    Box(BoxOp),

    // ---- control -----------------------------------------------------------------------------
    /// If PF: continue at the label (same POU). A backward jump counts against the loop budget.
    Jump(LabelId),
    /// A jump target.
    Label(LabelId),
    /// If PF: call a subroutine (nesting beyond the profile's limit is error 0x0008).
    Call(PouId),
    /// Return from a subroutine: `CRET` when `conditional` (on PF), `RET` otherwise.
    Return {
        /// CRET.
        conditional: bool,
    },
    /// End of the main program's scan: `END` when `conditional`, `MEND` otherwise.
    End {
        /// END.
        conditional: bool,
    },
    /// If PF: request STOP after this scan.
    Stop,
    /// If PF: reset the loop budget.
    Wdr,
    /// Nothing (`NOP`, kept so that op indices match source lines).
    Nop,
    /// `FOR INDX, INIT, FINAL` (spec §4.14).
    For {
        /// INDX, a word location.
        index: Operand,
        /// INIT.
        init: Operand,
        /// FINAL, re-read at every NEXT.
        limit: Operand,
        /// The matching [`Op::Next`].
        next: OpIdx,
    },
    /// End of a FOR body: increment INDX, `S0 = 1`, loop back while `INDX <= FINAL`.
    Next {
        /// The matching [`Op::For`].
        head: OpIdx,
    },
    /// `LSCR bit`: gate := bit; push bit.
    ScrBegin {
        /// The segment's S bit.
        bit: BitLoc,
    },
    /// `SCRT bit`: if PF, set `to` and reset the segment's own bit `from`.
    ScrTransition {
        /// The step to activate.
        to: BitLoc,
        /// The bit of the enclosing LSCR.
        from: BitLoc,
    },
    /// `CSCRE`: if PF, continue at the segment's [`Op::ScrEnd`].
    ScrCondEnd {
        /// The matching SCRE.
        end: OpIdx,
    },
    /// `SCRE`: gate := 1.
    ScrEnd,
}

/// Integer arithmetic operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArithOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
}

/// Bitwise operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LogicOp {
    /// AND
    And,
    /// OR
    Or,
    /// XOR
    Xor,
}

/// Real function (one shared implementation in the runtime).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RealFn {
    /// Square root.
    Sqrt,
    /// Natural logarithm.
    Ln,
    /// e^x.
    Exp,
    /// Sine (radians).
    Sin,
    /// Cosine.
    Cos,
    /// Tangent.
    Tan,
}

/// Conversion box.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Conversion {
    /// Byte → int, zero-extended.
    ByteToInt,
    /// Int → byte, SM1.1 if out of 0..=255.
    IntToByte,
    /// Int → dint, sign-extended.
    IntToDInt,
    /// Dint → int, SM1.1 if it does not fit.
    DIntToInt,
    /// Dint → real.
    DIntToReal,
    /// Real → dint, half away from zero.
    Round,
    /// Real → dint, toward zero.
    Trunc,
    /// BCD word → binary word (in place: `src == dst`).
    BcdToInt,
    /// Binary word → BCD word.
    IntToBcd,
    /// Byte → word with bit `IN & 15` set.
    Decode,
    /// Word → byte: number of the lowest set bit.
    Encode,
    /// Byte → 7-segment pattern.
    Segment,
}

/// A box instruction's operation. Two-operand STL arithmetic is `dst := dst op src`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BoxOp {
    /// `MOVB`/`MOVW`/`MOVD`/`MOVR`.
    Move {
        /// Width (reals are dwords).
        width: Width,
        /// Source.
        src: Operand,
        /// Destination.
        dst: Operand,
    },
    /// `SWAP`: exchange the bytes of a word in place.
    Swap {
        /// The word.
        dst: Operand,
    },
    /// `BMB`/`BMW`/`BMD`: copy `count` elements, ascending.
    BlockMove {
        /// Element width.
        width: Width,
        /// First source element (a location or pointer).
        src: Operand,
        /// First destination element.
        dst: Operand,
        /// Element count, a byte operand 1..=255.
        count: Operand,
    },
    /// `FILL`: write the word `src` into `count` words from `dst`.
    Fill {
        /// The word value.
        src: Operand,
        /// First destination word.
        dst: Operand,
        /// Count, a byte operand 1..=255.
        count: Operand,
    },
    /// `+I`/`-I`/`*I`/`/I` (Word) and `+D`/`-D`/`*D`/`/D` (DWord).
    IntArith {
        /// Operation.
        op: ArithOp,
        /// Word or DWord.
        width: Width,
        /// IN1.
        src: Operand,
        /// OUT (also the second input).
        dst: Operand,
    },
    /// `MUL`: dword `dst := (i16) low word of dst × (i16) src`.
    MulWide {
        /// Word factor.
        src: Operand,
        /// Dword OUT.
        dst: Operand,
    },
    /// `DIV`: dword `dst := remainder << 16 | quotient` of `(i16) low word of dst ÷ src`.
    DivWide {
        /// Word divisor.
        src: Operand,
        /// Dword OUT.
        dst: Operand,
    },
    /// `+R`/`-R`/`*R`/`/R`.
    RealArith {
        /// Operation.
        op: ArithOp,
        /// IN1.
        src: Operand,
        /// OUT.
        dst: Operand,
    },
    /// `SQRT`, `LN`, `EXP`, `SIN`, `COS`, `TAN`.
    RealFunc {
        /// The function.
        func: RealFn,
        /// IN.
        src: Operand,
        /// OUT.
        dst: Operand,
    },
    /// `INCB`/`DECB`/`INCW`/`DECW`/`INCD`/`DECD`.
    Step {
        /// Width.
        width: Width,
        /// INC instead of DEC.
        up: bool,
        /// OUT (in place).
        dst: Operand,
    },
    /// `ANDB`/`ORW`/`XORD`...
    Logic {
        /// Operation.
        op: LogicOp,
        /// Width.
        width: Width,
        /// IN1.
        src: Operand,
        /// OUT.
        dst: Operand,
    },
    /// `INVB`/`INVW`/`INVD`.
    Invert {
        /// Width.
        width: Width,
        /// OUT (in place).
        dst: Operand,
    },
    /// `SLx`/`SRx`: logical shifts.
    Shift {
        /// Left instead of right.
        left: bool,
        /// Width.
        width: Width,
        /// OUT (in place).
        dst: Operand,
        /// Shift count, a byte operand.
        count: Operand,
    },
    /// `RLx`/`RRx`: rotates.
    Rotate {
        /// Left instead of right.
        left: bool,
        /// Width.
        width: Width,
        /// OUT (in place).
        dst: Operand,
        /// Rotate count, a byte operand.
        count: Operand,
    },
    /// `SHRB DATA, S_BIT, N`.
    ShiftRegister {
        /// The bit shifted in.
        data: BitLoc,
        /// The register's lowest bit.
        start: BitLoc,
        /// Signed length, a byte operand read as `i8`.
        len: Operand,
    },
    /// A conversion (`BCDI`/`IBCD` have `src == dst`).
    Convert {
        /// Which conversion.
        conv: Conversion,
        /// IN.
        src: Operand,
        /// OUT.
        dst: Operand,
    },
    /// `BIR IN, OUT`: read a physical input byte.
    ImmediateRead {
        /// Input byte offset (area I).
        input: u32,
        /// Byte OUT.
        dst: Operand,
    },
    /// `BIW IN, OUT`: write a physical output byte and its image byte.
    ImmediateWrite {
        /// Byte IN.
        src: Operand,
        /// Output byte offset (area Q).
        output: u32,
    },
}

/// An address named outside a program (stimulus files, watch lists, HMI writes): a bit or a
/// value of a width. Parsed by the front end (`stljit_syntax::parse_address`), applied by the
/// runtime's simulation driver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Address {
    /// `I0.3`, `M1.0`, `T37` (the timer bit).
    Bit(BitLoc),
    /// `IB1`, `VW100`, `VD50`, `AIW0`, `AC0`.
    Value {
        /// Where.
        loc: Loc,
        /// How wide.
        width: Width,
    },
}

/// Every variant of the small operation enums, in declaration order. The position of a variant in
/// its `ALL` list is the integer code it crosses the JIT's `extern "C"` boundary as, and the
/// program generator draws from the same lists, so one list serves both.
macro_rules! all_variants {
    ($($ty:ident: [$($v:ident),+ $(,)?];)+) => {$(
        impl $ty {
            /// Every variant, in declaration order.
            pub const ALL: &'static [$ty] = &[$($ty::$v),+];
        }
    )+};
}

all_variants! {
    ArithOp: [Add, Sub, Mul, Div];
    LogicOp: [And, Or, Xor];
    RealFn: [Sqrt, Ln, Exp, Sin, Cos, Tan];
    Conversion: [
        ByteToInt, IntToByte, IntToDInt, DIntToInt, DIntToReal, Round, Trunc, BcdToInt, IntToBcd,
        Decode, Encode, Segment,
    ];
    CmpType: [Byte, Int, DInt, Real];
    CmpOp: [Eq, Ne, Ge, Le, Gt, Lt];
    TimerKind: [On, Retentive, Off];
    CounterKind: [Up, Down, UpDown];
}
