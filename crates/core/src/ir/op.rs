//! The instructions: [`Op`] and the box operations [`BoxOp`] with their small enums.

use super::call::CallArgs;
use super::operand::{BitLoc, Contact, Operand};
use super::{CounterKind, OmronBox, OmronCounterKind, OmronTimerKind, TimerKind};
use crate::area::Width;
use crate::index::{CounterId, EdgeSlot, LabelId, OpIdx, PouId, TimerId};

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
    /// If PF: call a subroutine with parameters, copied into its L frame before and back after
    /// the call; ENO = 1 after the call, 0 without PF (s7-200-more §1.5, see [`CallArgs`]).
    CallArgs(Box<CallArgs>),
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

    // ---- Omron CP ----------------------------------------------------------------------------
    /// `IL(002)`: gate := PF, so an IL whose condition is OFF interlocks everything up to the
    /// next [`Op::InterlockEnd`], and a later IL cannot lift an earlier one (omron-cp.md §2.7).
    Interlock,
    /// `ILC(003)`: gate := 1.
    InterlockEnd,
    /// The start of an Omron cyclic task after the first of the scan: the condition flags are
    /// cleared and the gate opens (`runtime::scan::task_start`, omron-cp.md §2.3).
    TaskStart,
    /// An Omron timer: TIM family `EC = S0`; TTIM timer input `S1`, reset `S0`. The gate's
    /// policy (interlock) is applied by the runtime.
    OmronTimer {
        /// Which instruction.
        kind: OmronTimerKind,
        /// Which timer (PV in `TimerValue`, completion flag in `TimerBit`).
        timer: TimerId,
        /// The set value, a word operand.
        set_value: Operand,
    },
    /// An Omron counter: CNT count `S1`, reset `S0`; CNTR increment `S2`, decrement `S1`, reset
    /// `S0`.
    OmronCounter {
        /// Which instruction.
        kind: OmronCounterKind,
        /// Which counter.
        counter: CounterId,
        /// The set value, a word operand.
        set_value: Operand,
    },
    /// An Omron data, compare or arithmetic box: runs when PF.
    Omron(OmronBox),
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

impl BoxOp {
    /// `SLx`/`SRx` (`rotate` false) or `RLx`/`RRx` (`rotate` true): the two differ only in the
    /// bits shifted in, so front ends and readers build them from one flag.
    pub fn shift_or_rotate(
        rotate: bool,
        left: bool,
        width: Width,
        dst: Operand,
        count: Operand,
    ) -> BoxOp {
        if rotate {
            BoxOp::Rotate {
                left,
                width,
                dst,
                count,
            }
        } else {
            BoxOp::Shift {
                left,
                width,
                dst,
                count,
            }
        }
    }
}
