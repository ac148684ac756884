//! Which memory an op names directly, stated once: every value operand with the width the op
//! gives it ([`Op::operand_uses`]), every bit it names ([`Op::bit_uses`]) and the timers and
//! counters it addresses. The verifier checks these against the profile's areas, so no engine
//! ever meets a direct location outside the image; the widths of a conversion come from
//! [`Conversion::widths`].

use super::{BitLoc, Operand};
use super::{BoxOp, Contact, Conversion, Op};
use crate::area::Width;

/// How an op uses a location.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// Only read.
    Read,
    /// Only written.
    Write,
    /// Read, then written (in-place boxes: `INCW VW0`, two-operand arithmetic's OUT).
    ReadWrite,
}

/// One value operand of an op, with the width the op reads or writes it at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OperandUse {
    /// The operand.
    pub operand: Operand,
    /// Its width in this op.
    pub width: Width,
    /// Whether the op reads or writes it.
    pub access: Access,
}

impl Conversion {
    /// The widths of the conversion's input and output operands.
    pub fn widths(self) -> (Width, Width) {
        use Width::{Byte, DWord, Word};
        match self {
            Conversion::ByteToInt | Conversion::Decode => (Byte, Word),
            Conversion::IntToByte | Conversion::Encode => (Word, Byte),
            Conversion::IntToDInt => (Word, DWord),
            Conversion::DIntToInt => (DWord, Word),
            Conversion::DIntToReal | Conversion::Round | Conversion::Trunc => (DWord, DWord),
            Conversion::BcdToInt | Conversion::IntToBcd => (Word, Word),
            Conversion::Segment => (Byte, Byte),
        }
    }
}

fn read(operand: Operand, width: Width) -> OperandUse {
    OperandUse {
        operand,
        width,
        access: Access::Read,
    }
}

fn write(operand: Operand, width: Width) -> OperandUse {
    OperandUse {
        operand,
        width,
        access: Access::Write,
    }
}

fn update(operand: Operand, width: Width) -> OperandUse {
    OperandUse {
        operand,
        width,
        access: Access::ReadWrite,
    }
}

fn contact_operands(c: &Contact) -> Vec<OperandUse> {
    match c {
        Contact::Compare { ty, lhs, rhs, .. } => {
            vec![read(*lhs, ty.width()), read(*rhs, ty.width())]
        }
        Contact::Bit { .. } | Contact::ImmediateInput { .. } => vec![],
    }
}

fn box_operands(b: &BoxOp) -> Vec<OperandUse> {
    use Width::{Byte, DWord, Word};
    match *b {
        BoxOp::Move { width, src, dst } => vec![read(src, width), write(dst, width)],
        BoxOp::Swap { dst } => vec![update(dst, Word)],
        // Only the first element of a block is a direct location; the rest is range-checked at
        // run time with the count.
        BoxOp::BlockMove {
            width,
            src,
            dst,
            count,
        } => vec![read(src, width), write(dst, width), read(count, Byte)],
        BoxOp::Fill { src, dst, count } => {
            vec![read(src, Word), write(dst, Word), read(count, Byte)]
        }
        BoxOp::IntArith {
            width, src, dst, ..
        }
        | BoxOp::Logic {
            width, src, dst, ..
        } => {
            vec![read(src, width), update(dst, width)]
        }
        BoxOp::MulWide { src, dst } | BoxOp::DivWide { src, dst } => {
            vec![read(src, Word), update(dst, DWord)]
        }
        BoxOp::RealArith { src, dst, .. } => vec![read(src, DWord), update(dst, DWord)],
        BoxOp::RealFunc { src, dst, .. } => vec![read(src, DWord), write(dst, DWord)],
        BoxOp::Step { width, dst, .. } | BoxOp::Invert { width, dst } => vec![update(dst, width)],
        BoxOp::Shift {
            width, dst, count, ..
        }
        | BoxOp::Rotate {
            width, dst, count, ..
        } => vec![update(dst, width), read(count, Byte)],
        BoxOp::ShiftRegister { len, .. } => vec![read(len, Byte)],
        BoxOp::Convert { conv, src, dst } => {
            let (wi, wo) = conv.widths();
            // BCDI/IBCD convert in place: `src == dst`.
            vec![read(src, wi), write(dst, wo)]
        }
        BoxOp::ImmediateRead { dst, .. } => vec![write(dst, Byte)],
        BoxOp::ImmediateWrite { src, .. } => vec![read(src, Byte)],
    }
}

impl Op {
    /// Every value operand of the op with its width and access, in operand order.
    pub fn operand_uses(&self) -> Vec<OperandUse> {
        use Width::{Byte, Word};
        match self {
            Op::Load(c) | Op::And(c) | Op::Or(c) => contact_operands(c),
            Op::SetRange { count, .. }
            | Op::ResetTimers { count, .. }
            | Op::ResetCounters { count, .. } => vec![read(*count, Byte)],
            Op::Timer { preset, .. } | Op::Counter { preset, .. } => vec![read(*preset, Word)],
            Op::Box(b) => box_operands(b),
            Op::For {
                index, init, limit, ..
            } => vec![write(*index, Word), read(*init, Word), read(*limit, Word)],
            Op::Not
            | Op::AndBlock
            | Op::OrBlock
            | Op::Dup
            | Op::ReadSecond
            | Op::Pop
            | Op::Pick(_)
            | Op::AndEno
            | Op::Edge { .. }
            | Op::Assign { .. }
            | Op::Jump(_)
            | Op::Label(_)
            | Op::Call(_)
            | Op::Return { .. }
            | Op::End { .. }
            | Op::Stop
            | Op::Wdr
            | Op::Nop
            | Op::Next { .. }
            | Op::ScrBegin { .. }
            | Op::ScrTransition { .. }
            | Op::ScrCondEnd { .. }
            | Op::ScrEnd => vec![],
        }
    }

    /// Every bit the op names directly (the first bit of a range for S/R and SHRB).
    pub fn bit_uses(&self) -> Vec<(BitLoc, Access)> {
        match self {
            Op::Load(c) | Op::And(c) | Op::Or(c) => match c {
                Contact::Bit { bit, .. } | Contact::ImmediateInput { bit, .. } => {
                    vec![(*bit, Access::Read)]
                }
                Contact::Compare { .. } => vec![],
            },
            Op::Assign { bit, .. } => vec![(*bit, Access::Write)],
            Op::SetRange { start, .. } => vec![(*start, Access::Write)],
            Op::ScrBegin { bit } => vec![(*bit, Access::Read)],
            Op::ScrTransition { to, from } => vec![(*to, Access::Write), (*from, Access::Write)],
            Op::Box(BoxOp::ShiftRegister { data, start, .. }) => {
                vec![(*data, Access::Read), (*start, Access::ReadWrite)]
            }
            _ => vec![],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::area::Area;
    use crate::ir::{ArithOp, Loc};

    #[test]
    fn two_operand_arithmetic_updates_its_out() {
        let vw = |o| {
            Operand::Mem(Loc {
                area: Area::V,
                offset: o,
            })
        };
        let op = Op::Box(BoxOp::IntArith {
            op: ArithOp::Add,
            width: Width::Word,
            src: vw(0),
            dst: vw(2),
        });
        assert_eq!(
            op.operand_uses(),
            vec![read(vw(0), Width::Word), update(vw(2), Width::Word)]
        );
        let conv = Op::Box(BoxOp::Convert {
            conv: Conversion::IntToDInt,
            src: vw(0),
            dst: vw(4),
        });
        assert_eq!(conv.operand_uses()[1].width, Width::DWord);
    }
}
