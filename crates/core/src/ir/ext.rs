//! The instructions of s7-200-more §4–§7 that work on runs of memory: tables, ASCII and
//! number-to-text conversions, strings, the real-time clock and PID ([`ExtBox`], the payload of
//! [`Op::Ext`](super::Op::Ext)), and the string compare contacts ([`StrCompare`], the payload of
//! [`Op::StrCompare`](super::Op::StrCompare)); and the high-speed counter instructions of §8
//! (HDEF, HSC) and the pulse output of §9 (PLS), which share the path: one runtime function both engines call with the op.
//!
//! They are their own ops rather than [`BoxOp`](super::BoxOp) variants because a string input
//! may be a constant string (bytes that are no [`Operand`]), so they are boxed like a call's
//! parameters. Each one's semantics is one function of the runtime (`runtime::ext`), which both
//! engines call with the op itself: operand resolution included, so the order in which the
//! operands of these multi-operand instructions are resolved exists once.

use super::operand::Operand;
use crate::area::Width;

/// The most characters a string holds (s7-200-more §5.1): its length byte is 0..=254.
pub const MAX_STRING: usize = 254;

/// A string input: a string in memory (its length byte, then the characters) or a constant
/// string from the program text.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum StrArg {
    /// A string starting at this byte (`VB100`, `*VD4`).
    Mem(Operand),
    /// A constant string (`"HELLO"`), its bytes as the file encodes them, 0..=254 of them.
    Const(Vec<u8>),
}

impl StrArg {
    /// The operand naming the string's first byte, unless it is a constant.
    pub fn operand(&self) -> Option<Operand> {
        match self {
            StrArg::Mem(o) => Some(*o),
            StrArg::Const(_) => None,
        }
    }
}

/// The number type of a conversion to or from text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NumType {
    /// INT (`ITA`, `ITS`, `STI`).
    Int,
    /// DINT (`DTA`, `DTS`, `STD`).
    DInt,
    /// REAL (`RTA`, `RTS`, `STR`).
    Real,
}

impl NumType {
    /// The width of the number operand.
    pub fn width(self) -> Width {
        match self {
            NumType::Int => Width::Word,
            NumType::DInt | NumType::Real => Width::DWord,
        }
    }
}

/// The relation of a table find (`FND=`, `FND<>`, `FND<`, `FND>`; TBL_FIND's CMD 1–4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FindRel {
    /// `=`
    Eq,
    /// `<>`
    Ne,
    /// `<`
    Lt,
    /// `>`
    Gt,
}

/// Which clock instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClockOp {
    /// `TODR`: read the clock into an 8-byte buffer.
    Read,
    /// `TODW`: set the clock from an 8-byte buffer.
    Write,
    /// `TODRX`: read into the 19-byte buffer with the daylight-saving settings.
    ReadExt,
    /// `TODWX`: set from the 19-byte buffer.
    WriteExt,
}

/// How a contact combines its value with the logic stack.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StackForm {
    /// Push (`LD…`).
    Load,
    /// `S0 &= value` (`A…`).
    And,
    /// `S0 |= value` (`O…`).
    Or,
}

/// A box of s7-200-more §4–§7. Run starts (tables, buffers, strings) are operands naming their
/// first byte (or word); how far the run reaches is read at run time.
#[derive(Clone, Debug, PartialEq)]
pub enum ExtBox {
    /// `ATT DATA, TBL` (§4.2).
    TableAdd {
        /// DATA, an INT input.
        data: Operand,
        /// TBL, the table's TL word.
        table: Operand,
    },
    /// `FIFO TBL, DATA` / `LIFO TBL, DATA`.
    TableTake {
        /// LIFO instead of FIFO.
        lifo: bool,
        /// TBL, the table's TL word.
        table: Operand,
        /// DATA, a word output.
        data: Operand,
    },
    /// `FND= TBL, PTN, INDX` and its relations.
    TableFind {
        /// The relation.
        rel: FindRel,
        /// TBL, the table's **EC** word.
        table: Operand,
        /// PTN, an INT input.
        pattern: Operand,
        /// INDX, a word in/out.
        index: Operand,
    },
    /// `ATH IN, OUT, LEN` (§5.2).
    AsciiToHex {
        /// The first character.
        src: Operand,
        /// The first output byte.
        dst: Operand,
        /// LEN, a byte input.
        len: Operand,
    },
    /// `HTA IN, OUT, LEN`.
    HexToAscii {
        /// The first input byte.
        src: Operand,
        /// The first output character.
        dst: Operand,
        /// LEN (hex digits), a byte input.
        len: Operand,
    },
    /// `ITA`/`DTA`/`RTA` (an ASCII buffer) and `ITS`/`DTS`/`RTS` (a string), §5.3.
    NumToText {
        /// The number's type.
        ty: NumType,
        /// Into a string (length byte first) instead of a plain buffer.
        string: bool,
        /// IN, the number.
        src: Operand,
        /// OUT, the first byte of the buffer or string.
        dst: Operand,
        /// FMT, a byte input.
        fmt: Operand,
    },
    /// `STI`/`STD`/`STR IN, INDX, OUT` (§5.4).
    TextToNum {
        /// The result's type.
        ty: NumType,
        /// IN, the string.
        src: StrArg,
        /// INDX, a byte input: the 1-based position to start at.
        index: Operand,
        /// OUT, the number.
        dst: Operand,
    },
    /// `SLEN IN, OUT` (§5.5).
    StrLen {
        /// IN.
        src: StrArg,
        /// OUT, a byte.
        dst: Operand,
    },
    /// `SCPY IN, OUT`.
    StrCopy {
        /// IN.
        src: StrArg,
        /// OUT, the first byte of the string.
        dst: Operand,
    },
    /// `SCAT IN, OUT`: OUT := OUT followed by IN.
    StrCat {
        /// IN.
        src: StrArg,
        /// OUT, the first byte of the string.
        dst: Operand,
    },
    /// `SSCPY IN, INDX, N, OUT`.
    SubStr {
        /// IN.
        src: StrArg,
        /// INDX, a byte input (1-based).
        index: Operand,
        /// N, a byte input.
        count: Operand,
        /// OUT, the first byte of the string.
        dst: Operand,
    },
    /// `SFND IN1, IN2, OUT` (a substring) or `CFND IN1, IN2, OUT` (any character of IN2).
    StrFind {
        /// CFND instead of SFND.
        chars: bool,
        /// IN1, the string searched.
        src: StrArg,
        /// IN2, what is searched for.
        pattern: StrArg,
        /// OUT, a byte in/out: the position to start at, then the position found (0: none).
        pos: Operand,
    },
    /// `TODR`, `TODW`, `TODRX`, `TODWX T` (§6).
    Clock {
        /// Which one.
        op: ClockOp,
        /// T, the first byte of the buffer.
        buf: Operand,
    },
    /// `PID TBL, LOOP` (§7): runs with and without power flow (its history bit).
    Pid {
        /// TBL, the loop table in V (a constant address).
        table: Operand,
        /// LOOP, 0..=7.
        lp: u8,
    },
    /// `HDEF HSC, MODE` (§8.1): define high-speed counter `counter` with `mode`, reading
    /// bits 0–2 of its control byte now. The runtime's `hsc` module is its semantics.
    HscDefine {
        /// HSC, a counter of the profile's table.
        counter: u8,
        /// MODE, one the counter accepts.
        mode: u8,
    },
    /// `HSC N` (§8.1): apply counter `counter`'s control byte.
    Hsc {
        /// N, a counter of the profile's table.
        counter: u8,
    },
    /// `PLS Q` (§9.2): apply pulse channel `channel`'s control byte (start, stop or update
    /// its PTO/PWM generator). The runtime's `pulse` module is its semantics.
    Pls {
        /// Q, a channel of the profile's table.
        channel: u8,
    },
    /// A communication instruction of §10 (XMT, RCV, NETR, NETW, GET, PUT, GPA, SPA): the
    /// runtime's `comm` module is its semantics.
    Comm {
        /// Which instruction.
        op: CommOp,
        /// TBL (XMT/RCV buffer, NETR/NETW/GET/PUT table) or ADDR (GPA/SPA byte).
        table: Operand,
        /// PORT, 0 or 1 (0 for GET/PUT, which use the Ethernet port).
        port: u8,
    },
}

/// The communication instructions (s7-200-more §10).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CommOp {
    /// `XMT TBL, PORT` (§10.2).
    Transmit,
    /// `RCV TBL, PORT` (§10.3).
    Receive,
    /// `NETR TBL, PORT` (§10.5).
    NetRead,
    /// `NETW TBL, PORT` (§10.5).
    NetWrite,
    /// `GET TBL` (§10.5).
    Get,
    /// `PUT TBL` (§10.5).
    Put,
    /// `GPA ADDR, PORT` (§10.6).
    GetAddress,
    /// `SPA ADDR, PORT` (§10.6).
    SetAddress,
}

impl CommOp {
    /// Every op, in mnemonic order.
    pub const ALL: [CommOp; 8] = [
        CommOp::Transmit,
        CommOp::Receive,
        CommOp::NetRead,
        CommOp::NetWrite,
        CommOp::Get,
        CommOp::Put,
        CommOp::GetAddress,
        CommOp::SetAddress,
    ];

    /// The STL mnemonic.
    pub fn mnemonic(self) -> &'static str {
        match self {
            CommOp::Transmit => "XMT",
            CommOp::Receive => "RCV",
            CommOp::NetRead => "NETR",
            CommOp::NetWrite => "NETW",
            CommOp::Get => "GET",
            CommOp::Put => "PUT",
            CommOp::GetAddress => "GPA",
            CommOp::SetAddress => "SPA",
        }
    }

    /// Whether the instruction names a port (all but GET/PUT).
    pub fn has_port(self) -> bool {
        !matches!(self, CommOp::Get | CommOp::Put)
    }

    /// Whether it starts activity that completes later in virtual time (so the scan must run
    /// the event phases): all but GPA/SPA.
    pub fn timed(self) -> bool {
        !matches!(self, CommOp::GetAddress | CommOp::SetAddress)
    }
}

/// A string compare contact (`LDS=`, `AS<>`, `OS=`, …; §5.6): evaluated regardless of power
/// flow, like the other compare contacts.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct StrCompare {
    /// Push, AND or OR.
    pub form: StackForm,
    /// `<>` instead of `=`.
    pub ne: bool,
    /// IN1.
    pub lhs: StrArg,
    /// IN2.
    pub rhs: StrArg,
}

impl ExtBox {
    /// Every string input of the box (constant or not), for the checks on constants.
    pub fn strings(&self) -> Vec<&StrArg> {
        match self {
            ExtBox::TextToNum { src, .. }
            | ExtBox::StrLen { src, .. }
            | ExtBox::StrCopy { src, .. }
            | ExtBox::StrCat { src, .. }
            | ExtBox::SubStr { src, .. } => vec![src],
            ExtBox::StrFind { src, pattern, .. } => vec![src, pattern],
            _ => vec![],
        }
    }
}
