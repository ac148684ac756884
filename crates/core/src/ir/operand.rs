//! Operands: locations, bits, value operands, contacts and compare types, and [`Address`], the
//! form an address takes outside a program.

use crate::area::{Area, Width};

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
    /// An Omron indirect operand (`@D20`, `*D21`, `+2,IR0`), only in Omron boxes.
    Omron(super::OmronRef),
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

/// An address named outside a program (stimulus files, watch lists, HMI writes): a bit or a
/// value of a width. Parsed by the front end (`stljit_front_s7::parse_address`), applied by the
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
