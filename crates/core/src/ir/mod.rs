//! The dialect-neutral IR.
//!
//! A [`Program`] is a list of POUs (main program first, then subroutines), each a flat list of
//! [`Op`]s with a parallel list of source locations. Control flow is explicit and resolved: jumps
//! name a [`LabelId`] whose position is in [`Pou::labels`], calls name a [`PouId`] (a call with
//! parameters also names each formal in the callee's L frame, [`CallArgs`]), FOR/NEXT and SCR
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

mod call;
mod ext;
mod facts;
mod omron;
mod op;
mod operand;
#[cfg(test)]
mod test_ops;
mod uses;
mod verify;

pub use call::{Arg, ArgDir, ArgValue, CallArgs};
pub use ext::{
    ClockOp, CommOp, ExtBox, FindRel, MAX_STRING, NumType, StackForm, StrArg, StrCompare,
};
pub use facts::{GateEffect, StackEffect, Successors, enclosing_loop, loop_entered_by};
pub use omron::{
    BoxOperands, IndexOffset, IndexStep, OmronArith, OmronBox, OmronCounterKind, OmronRef,
    OmronTimerKind,
};
pub use op::{ArithOp, BoxOp, Conversion, IntOp, LogicOp, Op, RealFn};
pub use operand::{Address, BitLoc, CmpOp, CmpType, Contact, Loc, Operand};
pub use uses::{Access, OperandUse, Uses};
pub use verify::{MAX_STACK_DEPTH, OpRule, PouRule, VerifyError, verify};

use crate::index::{CounterId, FileId, LabelId, OpIdx, PouId, TimerId};
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
    /// Initial values of V memory (MicroWIN's data block), written at cold start in this
    /// order (a later run wins where two overlap).
    pub data: Vec<DataInit>,
}

/// A run of V-memory bytes set at cold start (one line of a `DATA_BLOCK`, or several that
/// follow each other).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DataInit {
    /// The first V byte.
    pub offset: u32,
    /// The bytes.
    pub bytes: Vec<u8>,
}

impl Program {
    /// The main program's id.
    pub const MAIN: PouId = PouId(0);

    /// The POU with id `id`.
    pub fn pou(&self, id: PouId) -> &Pou {
        &self.pous[id.index()]
    }

    /// Whether the program has interrupt routines (then the scan runs the event phases).
    pub fn has_interrupts(&self) -> bool {
        self.pous.iter().any(|p| p.kind.interrupt().is_some())
    }

    /// Whether the program defines a high-speed counter (then the scan runs the event phases,
    /// which count its steps, whether or not it has interrupt routines).
    pub fn defines_hsc(&self) -> bool {
        self.pous
            .iter()
            .flat_map(|p| &p.ops)
            .any(|op| matches!(op, Op::Ext(b) if matches!(**b, ExtBox::HscDefine { .. })))
    }

    /// Whether the program has a PLS (then the scan runs the event phases, which advance its
    /// pulse trains).
    pub fn uses_pulse(&self) -> bool {
        self.pous
            .iter()
            .flat_map(|p| &p.ops)
            .any(|op| matches!(op, Op::Ext(b) if matches!(**b, ExtBox::Pls { .. })))
    }

    /// Whether the program starts communication that completes later (XMT, RCV, NETR, NETW,
    /// GET, PUT): then the scan runs the event phases, which time it (s7-200-more §10).
    pub fn uses_ports(&self) -> bool {
        self.pous.iter().flat_map(|p| &p.ops).any(
            |op| matches!(op, Op::Ext(b) if matches!(**b, ExtBox::Comm { op, .. } if op.timed())),
        )
    }

    /// Whether any POU has a `STOP` op, the only op that requests STOP (a program without one
    /// cannot leave RUN by itself).
    pub fn has_stop(&self) -> bool {
        self.pous
            .iter()
            .flat_map(|p| &p.ops)
            .any(|op| matches!(op, Op::Stop))
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
    /// An interrupt routine with its number; runs when an event attached to it is serviced
    /// (s7-200-more §3.6), never by CALL.
    Interrupt(u16),
}

impl PouKind {
    /// The interrupt routine's number, for an interrupt routine.
    pub fn interrupt(self) -> Option<u16> {
        match self {
            PouKind::Interrupt(n) => Some(n),
            PouKind::Main | PouKind::Subroutine(_) => None,
        }
    }
}

/// A program organisation unit: the main program, a subroutine or an interrupt routine.
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
    NumType: [Int, DInt, Real];
    FindRel: [Eq, Ne, Lt, Gt];
    ClockOp: [Read, Write, ReadExt, WriteExt];
    StackForm: [Load, And, Or];
    OmronTimerKind: [Tim, TimX, TimH, TimHX, Tmhh, TmhhX, Ttim, TtimX];
    OmronCounterKind: [Cnt, CntX, Cntr, CntrX];
    OmronArith: [
        Add, AddL, AddC, AddCL, AddB, AddBL, AddBC, AddBCL, Sub, SubL, SubC, SubCL, SubB, SubBL,
        SubBC, SubBCL, Mul, MulL, MulU, MulUL, MulB, MulBL, Div, DivL, DivU, DivUL, DivB, DivBL,
    ];
}
