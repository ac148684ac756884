//! Box instructions (spec §4.0 common rules): resolve every operand first (an operand error writes
//! nothing), compute with the shared runtime helper, apply its SMB1 effect, write the result.
//! Returns ENO for a box that ran, or the non-fatal error that stopped it.

use crate::exec::Machine;
use crate::operand::Addr;
use stljit_core::ir::{BoxOp, Operand};
use stljit_core::{Area, ErrorCode, Width};
use stljit_runtime::ffi::ValueBox;
use stljit_runtime::flags::{Outcome, apply_flags};
use stljit_runtime::{bitops, block, mem};

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

    /// A box that is one value computation ([`ValueBox`], the operand shape both engines use):
    /// IN and OUT resolved in that order before anything is written, then the runtime's rule.
    fn value_box(&mut self, vb: &ValueBox, frame: u32) -> Result<bool, ErrorCode> {
        let input = match vb.input {
            Some(u) => Some((self.resolve(&u.operand, u.width, frame, false)?, u.width)),
            None => None,
        };
        let out_w = vb.out.width;
        let d = self.resolve(&vb.out.operand, out_w, frame, true)?;
        let out = if vb.reads_out() {
            self.load(d, out_w)
        } else {
            0
        };
        let in1 = input.map_or(0, |(a, w)| self.load(a, w));
        Ok(self.finish(vb.op.outcome(out, in1), d, out_w))
    }

    pub(crate) fn exec_box(&mut self, b: &BoxOp, frame: u32) -> Result<bool, ErrorCode> {
        use Width::{Byte, Word};
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
            BoxOp::ShiftRegister { data, start, len } => {
                let d = self.bit(data, frame);
                let n = self.read(&len, Byte, frame)? as u8 as i8;
                block::shift_register(self.img, self.layout, d, start, frame, n).map(|()| true)
            }
            stljit_runtime::value_boxes!() => match ValueBox::of(b) {
                Some(vb) => self.value_box(&vb, frame),
                // `ValueBox::of` covers exactly these variants (the runtime's tests say so).
                None => Err(ErrorCode::OperandRange),
            },
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
