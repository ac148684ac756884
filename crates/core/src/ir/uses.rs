//! Which memory an op names directly, stated once: every value operand with the width the op
//! gives it ([`Op::operand_uses`]), every bit it names ([`Op::bit_uses`]) and the timers and
//! counters it addresses. The verifier checks these against the profile's areas, so no engine
//! ever meets a direct location outside the image; the widths of a conversion come from
//! [`Conversion::widths`].

use super::{BitLoc, Operand};
use super::{
    BoxOp, ClockOp, CommOp, Contact, Conversion, ExtBox, OmronBox, Op, StrArg, StrCompare,
};
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

/// The value operands of one op (at most four), kept inline so that an engine may ask for them
/// per execution without allocating.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Uses {
    items: [Option<OperandUse>; 4],
}

impl Uses {
    fn of(list: &[OperandUse]) -> Uses {
        let mut items = [None; 4];
        for (slot, u) in items.iter_mut().zip(list) {
            *slot = Some(*u);
        }
        Uses { items }
    }

    /// The operands in operand order.
    pub fn iter(&self) -> impl Iterator<Item = OperandUse> + '_ {
        self.items.iter().flatten().copied()
    }

    /// The operand the op reads as its input (the first read-only one), if any.
    pub fn input(&self) -> Option<OperandUse> {
        self.iter().find(|u| u.access == Access::Read)
    }

    /// The operand the op writes (its OUT), if any.
    pub fn output(&self) -> Option<OperandUse> {
        self.iter().find(|u| u.access != Access::Read)
    }
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

fn contact_operands(c: &Contact) -> Uses {
    match c {
        Contact::Compare { ty, lhs, rhs, .. } => {
            Uses::of(&[read(*lhs, ty.width()), read(*rhs, ty.width())])
        }
        Contact::Bit { .. } | Contact::ImmediateInput { .. } => Uses::of(&[]),
    }
}

impl BoxOp {
    /// Every value operand of the box with its width and access, in operand order.
    pub fn operand_uses(&self) -> Uses {
        use Width::{Byte, DWord, Word};
        match *self {
            BoxOp::Move { width, src, dst } => Uses::of(&[read(src, width), write(dst, width)]),
            BoxOp::Swap { dst } => Uses::of(&[update(dst, Word)]),
            // Only the first element of a block is a direct location; the rest is range-checked at
            // run time with the count.
            BoxOp::BlockMove {
                width,
                src,
                dst,
                count,
            } => Uses::of(&[read(src, width), write(dst, width), read(count, Byte)]),
            BoxOp::Fill { src, dst, count } => {
                Uses::of(&[read(src, Word), write(dst, Word), read(count, Byte)])
            }
            BoxOp::IntArith {
                width, src, dst, ..
            }
            | BoxOp::Logic {
                width, src, dst, ..
            } => Uses::of(&[read(src, width), update(dst, width)]),
            BoxOp::MulWide { src, dst } | BoxOp::DivWide { src, dst } => {
                Uses::of(&[read(src, Word), update(dst, DWord)])
            }
            BoxOp::RealArith { src, dst, .. } => Uses::of(&[read(src, DWord), update(dst, DWord)]),
            BoxOp::RealFunc { src, dst, .. } => Uses::of(&[read(src, DWord), write(dst, DWord)]),
            BoxOp::Step { width, dst, .. } | BoxOp::Invert { width, dst } => {
                Uses::of(&[update(dst, width)])
            }
            BoxOp::Shift {
                width, dst, count, ..
            }
            | BoxOp::Rotate {
                width, dst, count, ..
            } => Uses::of(&[update(dst, width), read(count, Byte)]),
            BoxOp::ShiftRegister { len, .. } => Uses::of(&[read(len, Byte)]),
            BoxOp::Convert { conv, src, dst } => {
                let (wi, wo) = conv.widths();
                // BCDI/IBCD convert in place: `src == dst`.
                Uses::of(&[read(src, wi), write(dst, wo)])
            }
            BoxOp::ImmediateRead { dst, .. } => Uses::of(&[write(dst, Byte)]),
            BoxOp::ImmediateWrite { src, .. } => Uses::of(&[read(src, Byte)]),
        }
    }
}

/// A string input's first byte, read (nothing for a constant string).
fn string(s: &StrArg) -> Option<OperandUse> {
    s.operand().map(|o| read(o, Width::Byte))
}

impl ExtBox {
    /// Every value operand with its width and access, in operand order: a run (table, buffer,
    /// string) by its first element, constant strings left out.
    pub fn operand_uses(&self) -> Uses {
        use Width::{Byte, DWord, Word};
        let list: Vec<OperandUse> = match self {
            ExtBox::TableAdd { data, table } => vec![read(*data, Word), update(*table, Word)],
            ExtBox::TableTake { table, data, .. } => vec![update(*table, Word), write(*data, Word)],
            ExtBox::TableFind {
                table,
                pattern,
                index,
                ..
            } => vec![
                read(*table, Word),
                read(*pattern, Word),
                update(*index, Word),
            ],
            // ATH keeps the low nibble of an odd LEN's last byte: OUT is updated.
            ExtBox::AsciiToHex { src, dst, len } => {
                vec![read(*src, Byte), update(*dst, Byte), read(*len, Byte)]
            }
            ExtBox::HexToAscii { src, dst, len } => {
                vec![read(*src, Byte), write(*dst, Byte), read(*len, Byte)]
            }
            ExtBox::NumToText {
                ty, src, dst, fmt, ..
            } => {
                vec![read(*src, ty.width()), write(*dst, Byte), read(*fmt, Byte)]
            }
            ExtBox::TextToNum {
                ty,
                src,
                index,
                dst,
            } => string(src)
                .into_iter()
                .chain([read(*index, Byte), write(*dst, ty.width())])
                .collect(),
            ExtBox::StrLen { src, dst } => {
                string(src).into_iter().chain([write(*dst, Byte)]).collect()
            }
            ExtBox::StrCopy { src, dst } => {
                string(src).into_iter().chain([write(*dst, Byte)]).collect()
            }
            ExtBox::StrCat { src, dst } => string(src)
                .into_iter()
                .chain([update(*dst, Byte)])
                .collect(),
            ExtBox::SubStr {
                src,
                index,
                count,
                dst,
            } => string(src)
                .into_iter()
                .chain([read(*index, Byte), read(*count, Byte), write(*dst, Byte)])
                .collect(),
            ExtBox::StrFind {
                src, pattern, pos, ..
            } => string(src)
                .into_iter()
                .chain(string(pattern))
                .chain([update(*pos, Byte)])
                .collect(),
            ExtBox::Clock { op, buf } => match op {
                ClockOp::Read | ClockOp::ReadExt => vec![write(*buf, Byte)],
                ClockOp::Write | ClockOp::WriteExt => vec![read(*buf, Byte)],
            },
            ExtBox::Pid { table, .. } => vec![update(*table, DWord)],
            // Fixed registers (the control byte, SMD, HC), no operands.
            ExtBox::HscDefine { .. } | ExtBox::Hsc { .. } | ExtBox::Pls { .. } => vec![],
            // The buffer or table is read (and its status byte written) now; a receive or a
            // network job writes it later, in the event phases, outside any op.
            ExtBox::Comm { op, table, .. } => match op {
                CommOp::GetAddress => vec![write(*table, Byte)],
                CommOp::SetAddress | CommOp::Transmit => vec![read(*table, Byte)],
                _ => vec![update(*table, Byte)],
            },
        };
        Uses::of(&list)
    }
}

impl StrCompare {
    /// The strings in memory the contact reads (constant strings left out).
    pub fn operand_uses(&self) -> Uses {
        let list: Vec<OperandUse> = string(&self.lhs)
            .into_iter()
            .chain(string(&self.rhs))
            .collect();
        Uses::of(&list)
    }
}

/// The width of an Omron operand of `words` words (1 or 2; a four-word result is two uses).
fn omron_width(words: u32) -> Width {
    if words == 1 {
        Width::Word
    } else {
        Width::DWord
    }
}

/// The location four bytes (two Omron words) after `operand`, for the upper half of a
/// four-word result; an operand that is not a location has none.
fn upper_half(operand: Operand) -> Option<Operand> {
    match operand {
        Operand::Mem(loc) => Some(Operand::Mem(super::Loc {
            offset: loc.offset + 4,
            ..loc
        })),
        _ => None,
    }
}

fn omron_uses(b: &OmronBox) -> Uses {
    match *b {
        OmronBox::Move { double, src, dst } => {
            let w = omron_width(if double { 2 } else { 1 });
            Uses::of(&[read(src, w), write(dst, w)])
        }
        OmronBox::Compare {
            double, lhs, rhs, ..
        } => {
            let w = omron_width(if double { 2 } else { 1 });
            Uses::of(&[read(lhs, w), read(rhs, w)])
        }
        OmronBox::Flags { .. } => Uses::of(&[]),
        OmronBox::SetIndex { ir, .. } => Uses::of(&[write(
            Operand::Mem(super::Loc {
                area: crate::area::Area::IndexReg,
                offset: 4 * u32::from(ir),
            }),
            Width::DWord,
        )]),
        OmronBox::Arith { op, lhs, rhs, dst } => {
            let w = omron_width(op.operand_words());
            let r = op.result_words();
            let first = write(dst, omron_width(r.min(2)));
            match upper_half(dst).filter(|_| r == 4) {
                Some(hi) => Uses::of(&[read(lhs, w), read(rhs, w), first, write(hi, Width::DWord)]),
                None => Uses::of(&[read(lhs, w), read(rhs, w), first]),
            }
        }
    }
}

impl Op {
    /// Every value operand of the op with its width and access, in operand order (a call's
    /// parameters, which may be up to 16, are in [`super::Arg::actual_use`] and
    /// [`super::Arg::formal_use`]).
    pub fn operand_uses(&self) -> Uses {
        use Width::{Byte, Word};
        match self {
            Op::Load(c) | Op::And(c) | Op::Or(c) => contact_operands(c),
            Op::SetRange { count, .. }
            | Op::ResetTimers { count, .. }
            | Op::ResetCounters { count, .. } => Uses::of(&[read(*count, Byte)]),
            Op::Timer { preset, .. } | Op::Counter { preset, .. } => {
                Uses::of(&[read(*preset, Word)])
            }
            Op::Box(b) => b.operand_uses(),
            Op::OmronTimer { set_value, .. } | Op::OmronCounter { set_value, .. } => {
                Uses::of(&[read(*set_value, Word)])
            }
            Op::Omron(b) => omron_uses(b),
            Op::Ext(b) => b.operand_uses(),
            Op::StrCompare(c) => c.operand_uses(),
            Op::For {
                index, init, limit, ..
            } => Uses::of(&[write(*index, Word), read(*init, Word), read(*limit, Word)]),
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
            | Op::CallArgs(_)
            | Op::Return { .. }
            | Op::End { .. }
            | Op::Stop
            | Op::Wdr
            | Op::Interrupt(_)
            | Op::Nop
            | Op::Next { .. }
            | Op::ScrBegin { .. }
            | Op::ScrTransition { .. }
            | Op::ScrCondEnd { .. }
            | Op::ScrEnd
            | Op::Interlock
            | Op::InterlockEnd
            | Op::TaskStart => Uses::of(&[]),
        }
    }

    /// Whether everything the op may read or write in the byte-addressed areas is named by
    /// [`Op::operand_uses`] and [`Op::bit_uses`], apart from an `S`/`R` range (from its first bit
    /// and count) and `BIW`'s Q byte (`BoxOp::ImmediateWrite::output`): false for an op that
    /// reaches past its first operand (block moves, fills, shift registers, tables, strings,
    /// communication buffers, pulse profiles), names call parameters, or compares strings.
    /// Pointer operands are the caller's to check. The JIT keeps bytes resident only in
    /// programs all of whose ops answer true (`stljit_jit`'s resident bits).
    pub fn footprint_stated(&self) -> bool {
        match self {
            // A block move, a fill and a shift register reach past their first operand.
            Op::Box(b) => matches!(
                b,
                BoxOp::Move { .. }
                    | BoxOp::Swap { .. }
                    | BoxOp::IntArith { .. }
                    | BoxOp::MulWide { .. }
                    | BoxOp::DivWide { .. }
                    | BoxOp::RealArith { .. }
                    | BoxOp::RealFunc { .. }
                    | BoxOp::Step { .. }
                    | BoxOp::Logic { .. }
                    | BoxOp::Invert { .. }
                    | BoxOp::Shift { .. }
                    | BoxOp::Rotate { .. }
                    | BoxOp::Convert { .. }
                    | BoxOp::ImmediateRead { .. }
                    | BoxOp::ImmediateWrite { .. }
            ),
            Op::Load(_)
            | Op::And(_)
            | Op::Or(_)
            | Op::Not
            | Op::AndBlock
            | Op::OrBlock
            | Op::Dup
            | Op::ReadSecond
            | Op::Pop
            | Op::Pick(_)
            | Op::AndEno
            | Op::Edge { .. }
            | Op::Assign { .. }
            | Op::SetRange { .. }
            | Op::ResetTimers { .. }
            | Op::ResetCounters { .. }
            | Op::Timer { .. }
            | Op::Counter { .. }
            | Op::Jump(_)
            | Op::Label(_)
            | Op::Call(_)
            | Op::Return { .. }
            | Op::End { .. }
            | Op::Stop
            | Op::Wdr
            | Op::Interrupt(_)
            | Op::Nop
            | Op::For { .. }
            | Op::Next { .. }
            | Op::ScrBegin { .. }
            | Op::ScrTransition { .. }
            | Op::ScrCondEnd { .. }
            | Op::ScrEnd => true,
            _ => false,
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
            Op::CallArgs(c) => c
                .args
                .iter()
                .filter_map(|a| a.bit_uses())
                .flatten()
                .collect(),
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
            op.operand_uses().iter().collect::<Vec<_>>(),
            vec![read(vw(0), Width::Word), update(vw(2), Width::Word)]
        );
        let conv = Op::Box(BoxOp::Convert {
            conv: Conversion::IntToDInt,
            src: vw(0),
            dst: vw(4),
        });
        let uses = conv.operand_uses();
        assert_eq!(uses.output().map(|u| u.width), Some(Width::DWord));
        assert_eq!(uses.input().map(|u| u.width), Some(Width::Word));
    }
}
