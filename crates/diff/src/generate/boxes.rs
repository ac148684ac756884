//! Box instructions (spec §4.7–§4.12): every [`BoxOp`] with operands of its classes.
//!
//! Direct operands of block moves, FILL and SHRB are placed so that constant counts fit their
//! area; variable counts and pointers are what reach the run-time range errors.

use super::Gen;
use super::operands::Class;
use stljit_core::ir::{ArithOp, BitLoc, BoxOp, Conversion, Loc, LogicOp, Operand, RealFn};
use stljit_core::{Area, Width};

/// The three access widths.
/// Areas a block move, FILL or SHRB may name directly.
const BLOCK_AREAS: [Area; 7] = [
    Area::V,
    Area::M,
    Area::Q,
    Area::I,
    Area::S,
    Area::L,
    Area::SM,
];

impl Gen<'_, '_> {
    /// Any box instruction; now and then with its input aliasing its output (the same location,
    /// or one byte off), which is where read-before-write ordering shows.
    pub(crate) fn box_op(&mut self) -> BoxOp {
        let b = self.box_op_raw();
        if !self.c.chance(1, 6) {
            return b;
        }
        match b {
            BoxOp::IntArith { op, width, dst, .. } => BoxOp::IntArith {
                op,
                width,
                src: self.alias(width, dst),
                dst,
            },
            BoxOp::Logic { op, width, dst, .. } => BoxOp::Logic {
                op,
                width,
                src: self.alias(width, dst),
                dst,
            },
            BoxOp::RealArith { op, dst, .. } => BoxOp::RealArith {
                op,
                src: self.alias(Width::DWord, dst),
                dst,
            },
            BoxOp::RealFunc { func, dst, .. } => BoxOp::RealFunc {
                func,
                src: self.alias(Width::DWord, dst),
                dst,
            },
            BoxOp::Move { width, dst, src }
                if !matches!(dst, Operand::Mem(Loc { area: Area::AQ, .. })) =>
            {
                let src = if matches!(src, Operand::AddressOf(_)) {
                    src
                } else {
                    self.alias(width, dst)
                };
                BoxOp::Move { width, src, dst }
            }
            BoxOp::BlockMove {
                width,
                src,
                dst,
                count,
            } => {
                // Overlapping block moves: the destination one element above or below the source.
                let dst = match src {
                    Operand::Mem(Loc { area, offset }) if area != Area::SM => {
                        let w = width.bytes();
                        let n = match count {
                            Operand::Const(n) => n,
                            _ => 1,
                        };
                        let size = self.p.area_size(area);
                        let up = offset + w;
                        if up + n * w <= size {
                            Operand::Mem(Loc { area, offset: up })
                        } else if offset >= w {
                            Operand::Mem(Loc {
                                area,
                                offset: offset - w,
                            })
                        } else {
                            dst
                        }
                    }
                    _ => dst,
                };
                BoxOp::BlockMove {
                    width,
                    src,
                    dst,
                    count,
                }
            }
            other => other,
        }
    }

    /// An input reading the output `dst` itself, or (for byte areas) a value one byte off.
    fn alias(&mut self, w: Width, dst: Operand) -> Operand {
        if let Operand::Mem(Loc { area, offset }) = dst
            && matches!(area, Area::V | Area::M | Area::L | Area::Q | Area::S)
            && self.c.chance(1, 3)
        {
            let size = self.p.area_size(area);
            let off = if offset + w.bytes() < size && self.c.chance(1, 2) {
                offset + 1
            } else {
                offset.saturating_sub(1)
            };
            return Operand::Mem(Loc { area, offset: off });
        }
        dst
    }

    fn box_op_raw(&mut self) -> BoxOp {
        // A plain program has no block move, fill or shift register.
        let (block, fill, shift_register) = if self.cfg.plain { (0, 0, 0) } else { (2, 1, 1) };
        match self.c.weighted(&[
            10,
            1,
            block,
            fill,
            10,
            2,
            2,
            1,
            3,
            shift_register,
            2,
            1,
            3,
            5,
            1,
            1,
        ]) {
            0 => self.move_box(),
            1 => BoxOp::Swap {
                dst: self.value(Width::Word, Class::OUT),
            },
            2 => self.block_move(),
            3 => self.fill(),
            4 => self.arith_box(),
            5 => {
                let w = self.c.pick(&Width::ALL);
                BoxOp::Step {
                    width: w,
                    up: self.c.chance(1, 2),
                    dst: self.value(w, Class::OUT),
                }
            }
            6 => {
                let w = self.c.pick(&Width::ALL);
                BoxOp::Logic {
                    op: self.c.pick(LogicOp::ALL),
                    width: w,
                    src: self.value(w, Class::IN),
                    dst: self.value(w, Class::OUT),
                }
            }
            7 => {
                let w = self.c.pick(&Width::ALL);
                BoxOp::Invert {
                    width: w,
                    dst: self.value(w, Class::OUT),
                }
            }
            8 => {
                let w = self.c.pick(&Width::ALL);
                let left = self.c.chance(1, 2);
                let dst = self.value(w, Class::OUT);
                let count = self.shift_count(w);
                if self.c.chance(1, 2) {
                    BoxOp::Shift {
                        left,
                        width: w,
                        dst,
                        count,
                    }
                } else {
                    BoxOp::Rotate {
                        left,
                        width: w,
                        dst,
                        count,
                    }
                }
            }
            9 => self.shift_register(),
            10 => self.real_box(),
            11 => BoxOp::ImmediateRead {
                input: self.c.below(self.p.inputs),
                dst: self.value(Width::Byte, Class::OUT),
            },
            12 => self.convert(),
            13 => self.real_box(),
            14 => BoxOp::ImmediateWrite {
                src: self.value(Width::Byte, Class::IN),
                output: self.c.below(self.p.outputs),
            },
            _ => self.move_box(),
        }
    }

    fn move_box(&mut self) -> BoxOp {
        match self.c.weighted(&[3, 4, 3, 2, 1]) {
            // Real cells poisoned with NaN, infinities, -0.0 or a subnormal: the bit patterns
            // real arithmetic must classify the same way in both engines.
            4 => BoxOp::Move {
                width: Width::DWord,
                src: Operand::Const(self.c.pick(&[
                    0x7FC0_0000,
                    0xFFC0_0001,
                    0x7F80_0000,
                    0xFF80_0000,
                    0x8000_0000,
                    0x0000_0001,
                    0x807F_FFFF,
                    0x7F7F_FFFF,
                ])),
                dst: Operand::Mem(self.real_cell()),
            },
            0 => BoxOp::Move {
                width: Width::Byte,
                src: self.value(Width::Byte, Class::IN),
                dst: self.value(Width::Byte, Class::OUT),
            },
            1 => BoxOp::Move {
                width: Width::Word,
                src: self.value(Width::Word, Class::IN),
                dst: self.value(
                    Width::Word,
                    Class {
                        aq: true,
                        ..Class::OUT
                    },
                ),
            },
            2 => BoxOp::Move {
                width: Width::DWord,
                src: self.value(
                    Width::DWord,
                    Class {
                        addr: true,
                        ..Class::IN
                    },
                ),
                dst: self.value(Width::DWord, Class::OUT),
            },
            // MOVR: the same op, with real operands.
            _ => BoxOp::Move {
                width: Width::DWord,
                src: self.value(Width::DWord, Class::REAL_IN),
                dst: self.value(Width::DWord, Class::REAL_OUT),
            },
        }
    }

    /// Integer arithmetic, the box most likely to set SMB1 flags.
    pub(crate) fn arith_box(&mut self) -> BoxOp {
        match self.c.weighted(&[6, 4, 1, 1, 3]) {
            0 => BoxOp::IntArith {
                op: self.c.pick(ArithOp::ALL),
                width: Width::Word,
                src: self.value(Width::Word, Class::IN),
                dst: self.value(Width::Word, Class::OUT),
            },
            1 => BoxOp::IntArith {
                op: self.c.pick(ArithOp::ALL),
                width: Width::DWord,
                src: self.value(Width::DWord, Class::IN),
                dst: self.value(Width::DWord, Class::OUT),
            },
            2 => BoxOp::MulWide {
                src: self.value(Width::Word, Class::IN),
                dst: self.value(Width::DWord, Class::OUT),
            },
            3 => BoxOp::DivWide {
                src: self.value(Width::Word, Class::IN),
                dst: self.value(Width::DWord, Class::OUT),
            },
            _ => self.real_box(),
        }
    }

    fn real_box(&mut self) -> BoxOp {
        if self.c.chance(2, 3) {
            BoxOp::RealArith {
                op: self.c.pick(ArithOp::ALL),
                src: self.value(Width::DWord, Class::REAL_IN),
                dst: self.value(Width::DWord, Class::REAL_OUT),
            }
        } else {
            BoxOp::RealFunc {
                func: self.c.pick(RealFn::ALL),
                src: self.value(Width::DWord, Class::REAL_IN),
                dst: self.value(Width::DWord, Class::REAL_OUT),
            }
        }
    }

    fn shift_count(&mut self, w: Width) -> Operand {
        if self.c.chance(5, 6) {
            let n = match self.c.weighted(&[6, 1, 1, 1]) {
                0 => self.c.range(1, w.bits() - 1),
                1 => 0,
                2 => w.bits(),
                _ => self.c.range(w.bits(), 255),
            };
            Operand::Const(n)
        } else {
            self.value(Width::Byte, Class::IN)
        }
    }

    fn convert(&mut self) -> BoxOp {
        let conv = self.c.pick(Conversion::ALL);
        if matches!(conv, Conversion::BcdToInt | Conversion::IntToBcd) {
            // In place: the front end lowers `BCDI OUT` to src == dst.
            let dst = self.value(Width::Word, Class::OUT);
            return BoxOp::Convert {
                conv,
                src: dst,
                dst,
            };
        }
        let (wi, wo) = conv.widths();
        // Which side is a real (drawn from the real-valued operand classes).
        let (ri, ro) = (
            matches!(conv, Conversion::Round | Conversion::Trunc),
            conv == Conversion::DIntToReal,
        );
        let src = self.value(wi, if ri { Class::REAL_IN } else { Class::IN });
        let dst = self.value(wo, if ro { Class::REAL_OUT } else { Class::OUT });
        BoxOp::Convert { conv, src, dst }
    }

    /// A start operand for `n` elements of `w` bytes: a direct location where they fit, or a
    /// pointer. Returns the operand and how many elements fit after it.
    fn block_operand(&mut self, w: Width, out: bool, want: u32) -> (Operand, u32) {
        if self.c.chance(1, 6) {
            return (Operand::Indirect(self.pointer_cell()), want);
        }
        // SM is read-only below SMB30; only sources read it.
        let area = BLOCK_AREAS[self.c.weighted(&[8, 3, 2, 1, 1, 2, u32::from(!out)])];
        let size = self.p.area_size(area);
        let fit = (size / w.bytes()).min(want).max(1);
        let room = size - fit * w.bytes();
        let offset = match self.c.weighted(&[6, 1, 1]) {
            0 => self.c.below(room.min(48) + 1),
            1 => room,
            _ => self.c.below(room + 1),
        };
        (Operand::Mem(Loc { area, offset }), fit)
    }

    fn block_count(&mut self, n: u32) -> Operand {
        if self.c.chance(5, 6) {
            Operand::Const(n)
        } else {
            self.variable(Width::Byte)
        }
    }

    fn block_move(&mut self) -> BoxOp {
        let w = self.c.pick(&Width::ALL);
        let want = if self.c.chance(1, 10) {
            self.c.range(1, 255)
        } else {
            self.c.range(1, 8)
        };
        let (src, a) = self.block_operand(w, false, want);
        let (dst, b) = self.block_operand(w, true, a);
        let n = a.min(b);
        BoxOp::BlockMove {
            width: w,
            src,
            dst,
            count: self.block_count(n),
        }
    }

    fn fill(&mut self) -> BoxOp {
        let want = self.c.range(1, 10);
        let src = self.value(Width::Word, Class::IN);
        let (dst, n) = self.block_operand(Width::Word, true, want);
        BoxOp::Fill {
            src,
            dst,
            count: self.block_count(n),
        }
    }

    /// `SHRB DATA, S_BIT, N` with the register inside its area for constant `N`.
    fn shift_register(&mut self) -> BoxOp {
        let data = self.bit_read(false);
        let area = [Area::V, Area::M, Area::Q][self.c.weighted(&[3, 3, 1])];
        let len = self.c.range(1, 64);
        let bits = self.p.area_size(area) * 8;
        let first = if self.c.chance(5, 6) {
            self.c.below(bits.min(128).saturating_sub(len) + 1)
        } else {
            bits - len
        };
        let start = BitLoc {
            area,
            byte: first / 8,
            bit: (first % 8) as u8,
        };
        let len = if self.c.chance(1, 8) {
            self.variable(Width::Byte)
        } else if self.c.chance(1, 3) {
            Operand::Const((len as u8).wrapping_neg().into())
        } else {
            Operand::Const(len)
        };
        BoxOp::ShiftRegister { data, start, len }
    }
}
