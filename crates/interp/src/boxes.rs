//! Box instructions (spec §4.0 common rules): resolve every operand first (an operand error writes
//! nothing), compute with the shared runtime helper, apply its SMB1 effect, write the result.
//! Returns ENO for a box that ran, or the non-fatal error that stopped it.

use crate::exec::Machine;
use crate::operand::Addr;
use stljit_core::ir::{BoxOp, Operand};
use stljit_core::{Area, ErrorCode, Width};
use stljit_runtime::flags::{Outcome, apply_flags};
use stljit_runtime::{arith, bitops, block, convert, mem};

impl Machine<'_> {
    /// Writes `o`'s value (if any) to the already-resolved `dst` and applies its flags.
    fn finish(&mut self, o: Outcome, dst: Addr, width: Width) -> bool {
        apply_flags(self.img, self.layout, o.flags);
        if let Some(v) = o.value {
            self.store(dst, width, v);
        }
        o.ok()
    }

    /// `OUT := f(OUT, IN)` with `IN` of `src_w` and `OUT` of `dst_w`; `f` gets 0 for OUT's old
    /// value unless `READS_OUT` (the [`stljit_runtime::ffi::ValueOp::outcome`] convention).
    fn compute<const READS_OUT: bool>(
        &mut self,
        src: &Operand,
        src_w: Width,
        dst: &Operand,
        dst_w: Width,
        frame: u32,
        f: impl FnOnce(u32, u32) -> Outcome,
    ) -> Result<bool, ErrorCode> {
        let a = self.resolve(src, src_w, frame, false)?;
        let d = self.resolve(dst, dst_w, frame, true)?;
        let out = if READS_OUT { self.load(d, dst_w) } else { 0 };
        let o = f(out, self.load(a, src_w));
        Ok(self.finish(o, d, dst_w))
    }

    /// `OUT := f(OUT)` in place.
    fn in_place(
        &mut self,
        dst: &Operand,
        width: Width,
        frame: u32,
        f: impl FnOnce(u32) -> Outcome,
    ) -> Result<bool, ErrorCode> {
        let d = self.resolve(dst, width, frame, true)?;
        let o = f(self.load(d, width));
        Ok(self.finish(o, d, width))
    }

    pub(crate) fn exec_box(&mut self, b: &BoxOp, frame: u32) -> Result<bool, ErrorCode> {
        use Width::{Byte, DWord, Word};
        match *b {
            BoxOp::Move { width, src, dst } => {
                self.compute::<false>(&src, width, &dst, width, frame, |_, x| Outcome::plain(x))
            }
            BoxOp::Swap { dst } => self.in_place(&dst, Word, frame, |x| {
                Outcome::plain(u32::from((x as u16).swap_bytes()))
            }),
            BoxOp::BlockMove {
                width,
                src,
                dst,
                count,
            } => {
                let n = self.read(&count, Byte, frame)?;
                let s = self.span(&src, width, frame, false)?;
                let d = self.span(&dst, width, frame, true)?;
                block::block_move(self.img, s, d, width, n).map(|()| true)
            }
            BoxOp::Fill { src, dst, count } => {
                let v = self.read(&src, Word, frame)?;
                let n = self.read(&count, Byte, frame)?;
                let d = self.span(&dst, Word, frame, true)?;
                block::fill(self.img, v as u16, d, n).map(|()| true)
            }
            BoxOp::IntArith {
                op,
                width,
                src,
                dst,
            } => self.compute::<true>(&src, width, &dst, width, frame, |o, i| {
                arith::int_arith(op, width, o, i)
            }),
            BoxOp::MulWide { src, dst } | BoxOp::DivWide { src, dst } => {
                let f = if matches!(b, BoxOp::MulWide { .. }) {
                    arith::mul_wide
                } else {
                    arith::div_wide
                };
                self.compute::<true>(&src, Word, &dst, DWord, frame, f)
            }
            BoxOp::RealArith { op, src, dst } => {
                self.compute::<true>(&src, DWord, &dst, DWord, frame, |o, i| {
                    arith::real_arith(op, o, i)
                })
            }
            BoxOp::RealFunc { func, src, dst } => {
                self.compute::<false>(&src, DWord, &dst, DWord, frame, |_, x| {
                    arith::real_func(func, x)
                })
            }
            BoxOp::Step { width, up, dst } => {
                self.in_place(&dst, width, frame, |x| arith::step(width, up, x))
            }
            BoxOp::Logic {
                op,
                width,
                src,
                dst,
            } => self.compute::<true>(&src, width, &dst, width, frame, |o, i| {
                bitops::logic(op, width, o, i)
            }),
            BoxOp::Invert { width, dst } => {
                self.in_place(&dst, width, frame, |x| bitops::invert(width, x))
            }
            BoxOp::Shift {
                left,
                width,
                dst,
                count,
            }
            | BoxOp::Rotate {
                left,
                width,
                dst,
                count,
            } => {
                let f = if matches!(b, BoxOp::Shift { .. }) {
                    bitops::shift
                } else {
                    bitops::rotate
                };
                let n = self.read(&count, Byte, frame)? as u8;
                self.in_place(&dst, width, frame, |x| f(left, width, x, n))
            }
            BoxOp::ShiftRegister { data, start, len } => {
                let d = self.bit(data, frame);
                let n = self.read(&len, Byte, frame)? as u8 as i8;
                block::shift_register(self.img, self.layout, d, start, frame, n).map(|()| true)
            }
            BoxOp::Convert { conv, src, dst } => {
                let (sw, dw) = convert::widths(conv);
                self.compute::<false>(&src, sw, &dst, dw, frame, |_, x| convert::convert(conv, x))
            }
            BoxOp::ImmediateRead { input, dst } => {
                if input >= self.layout.area_size(Area::I) {
                    return Err(ErrorCode::OperandRange);
                }
                let v = u32::from(mem::get_u8(self.img, self.layout.phys_in + input));
                let d = self.resolve(&dst, Byte, frame, true)?;
                self.store(d, Byte, v);
                Ok(true)
            }
            BoxOp::ImmediateWrite { src, output } => {
                if output >= self.layout.area_size(Area::Q) {
                    return Err(ErrorCode::OperandRange);
                }
                let v = self.read(&src, Byte, frame)? as u8;
                mem::set_u8(self.img, self.layout.base(Area::Q) + output, v);
                mem::set_u8(self.img, self.layout.phys_out + output, v);
                Ok(true)
            }
        }
    }
}
