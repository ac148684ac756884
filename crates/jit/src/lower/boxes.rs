//! Box instructions (spec §4.7–4.12).
//!
//! The hot, simple ones are inline: moves, SWAP, integer `+`/`-`, INC/DEC, word logic and
//! INV with their SMB1 rules (copied from `stljit_runtime::arith`/`bitops`, and checked against
//! them by the differential tests). Everything with an intricate rule (multiplication, division,
//! reals, shifts, rotates, conversions) calls the runtime's own computation through the value
//! shim [`Helper::Value`] (a `stljit_runtime::ffi::ValueOp`) and applies the outcome it returns. Writes that the flag rule forbids
//! are done as a write of the old value (`select`), which leaves the same bytes without a branch.

use super::Lower;
use super::cache::{Addr, FlagsChain};
use super::mem::{OnFail, Place};
use super::mf;
use super::state::BoxState;
use super::value::B;
use cranelift_codegen::ir::{
    InstBuilder, Value,
    condcodes::IntCC,
    types::{I16, I32},
};
use stljit_core::ir::{ArithOp, BoxOp, Loc, LogicOp, Operand};
use stljit_core::{Area, Width};
use stljit_runtime::ffi::{
    OUTCOME_CLEAR_SHIFT, OUTCOME_HAS_VALUE_SHIFT, OUTCOME_SET_SHIFT, ValueBox,
};
use stljit_runtime::flags;

impl Lower<'_, '_> {
    fn smb1(&self) -> Addr {
        self.area_addr(Area::SM, 1)
    }

    /// SMB1 := (SMB1 AND NOT clear_mask) OR bits (bits within the mask).
    fn put_flags(&mut self, clear_mask: i64, bits: Value) {
        let a = self.smb1();
        let old = self.byte(a);
        let new = self.merge_flags(old, clear_mask, bits);
        self.set_byte_pred(a, new);
    }

    /// `(smb1 AND NOT clear_mask) OR bits`.
    fn merge_flags(&mut self, smb1: Value, clear_mask: i64, bits: Value) -> Value {
        let kept = self.b.ins().band_imm_s(smb1, !clear_mask & 0xFF);
        self.b.ins().bor(kept, bits)
    }

    /// SM1.0–SM1.2 of an integer `+`/`-` whose result is `r` (sign-extended to `i32`) and
    /// whose signed overflow is `ovf`: overflow alone, or zero and negative of the result.
    /// Written as a link of a [`FlagsChain`]: where the previous SMB1 write was such a box's
    /// and is still cached, this box's result and overflow are selected over that box's by
    /// its power flow and the byte is derived from the chain's start, so the previous box's
    /// flag computation dies with its store (`dse`).
    fn put_result_flags(&mut self, r: Value, ovf: Value) {
        let a = self.smb1();
        let chain = self
            .block
            .cache
            .flags
            .filter(|c| self.block.cache.get(a) == Some(c.smb1));
        let pred = self.in_box.pred.as_ref().map(|p| (p.flow, p.pf));
        let (base, r, ovf, ran, ran_cond) = match (chain, pred) {
            // A new chain: this box alone, under its own predicate if it has one.
            (None, _) => {
                let ran = pred.map_or(B::K(true), |(flow, _)| flow);
                (self.byte(a), r, ovf, ran, pred.map(|(_, pf)| pf))
            }
            (Some(c), None) => (c.base, r, ovf, B::K(true), None),
            (Some(c), Some((flow, pf))) => {
                let r = self.b.ins().select(pf, r, c.r);
                let ovf = self.b.ins().select(pf, ovf, c.ovf);
                let ran = flow.or(&mut self.b, c.ran);
                let cond = match ran {
                    B::K(true) => None,
                    _ => Some(ran.cond(&mut self.b)),
                };
                (c.base, r, ovf, ran, cond)
            }
        };
        let zn = self.zn_bits(r);
        let ovf_bits = self.iconst(I32, i64::from(flags::OVERFLOW));
        let bits = self.b.ins().select(ovf, ovf_bits, zn);
        let new = self.merge_flags(base, i64::from(flags::RESULT), bits);
        let new = match ran_cond {
            Some(c) => self.b.ins().select(c, new, base),
            None => new,
        };
        self.set_byte(a, new);
        self.block.cache.flags = Some(FlagsChain {
            smb1: new,
            base,
            r,
            ovf,
            ran,
        });
    }

    /// SM1.0 and SM1.2 bits of a result (`r` sign-extended to i32 for the negative test).
    fn zn_bits(&mut self, r: Value) -> Value {
        const {
            assert!(
                flags::ZERO == 1,
                "the compare result is the zero flag as it is"
            )
        };
        let z = self.b.ins().icmp_imm_s(IntCC::Equal, r, 0);
        let z = self.b.ins().uextend(I32, z);
        let n = self.b.ins().ushr_imm_s(r, 31);
        let n = self
            .b
            .ins()
            .ishl_imm_s(n, i64::from(flags::NEGATIVE.trailing_zeros()));
        // The two bits are distinct, so `+` is `|`; x86 does the shift and the add in one `lea`.
        self.b.ins().iadd(z, n)
    }

    fn dst_place(&mut self, dst: &Operand, w: Width, fail: OnFail) -> Place {
        self.place(dst, w, true, fail)
            .unwrap_or(Place::Static(Addr::img(0)))
    }

    /// Whether a box can be lowered branch-free: no pointer operand (so no run-time error),
    /// no static error, and no shim that touches the image (the value shim is pure).
    fn branch_free(&self, bx: &BoxOp) -> bool {
        let direct = bx
            .operand_uses()
            .iter()
            .all(|u| !Self::is_indirect(&u.operand));
        match *bx {
            // The value boxes call only the pure value shim; the rest are inlined.
            stljit_runtime::value_boxes!()
            | BoxOp::Move { .. }
            | BoxOp::Logic { .. }
            | BoxOp::Swap { .. }
            | BoxOp::Invert { .. } => direct,
            BoxOp::ImmediateRead { input: n, .. } | BoxOp::ImmediateWrite { output: n, .. } => {
                n < self.io_limit(bx) && direct
            }
            // Their shims touch the image and check the element range at run time.
            BoxOp::BlockMove { .. } | BoxOp::Fill { .. } | BoxOp::ShiftRegister { .. } => false,
        }
    }

    pub(crate) fn lower_box(&mut self, bx: &BoxOp) {
        self.in_box = BoxState::new(self.branch_free(bx));
        self.lower_box_op(bx);
        self.in_box = BoxState::default();
    }

    fn lower_box_op(&mut self, bx: &BoxOp) {
        match *bx {
            BoxOp::Move {
                width,
                src: Operand::Mem(src),
                dst: Operand::Mem(dst),
            } if self.raw_move_applies(width, src, dst) => {
                let (src, dst) = (self.loc_addr(src), self.loc_addr(dst));
                self.boxed(|s, _| {
                    s.move_raw(width, src, dst);
                    B::K(true)
                });
            }
            BoxOp::Move {
                width,
                ref src,
                ref dst,
            } => self.boxed(|s, f| {
                let v = s.read_operand(src, width, f);
                let p = s.dst_place(dst, width, f);
                s.write_place(p, width, v);
                B::K(true)
            }),
            BoxOp::Swap { ref dst } => self.boxed(|s, f| {
                let p = s.dst_place(dst, Width::Word, f);
                let v = s.read_place(p, Width::Word);
                let hi = s.b.ins().ishl_imm_s(v, 8);
                let lo = s.b.ins().ushr_imm_s(v, 8);
                let r = s.b.ins().bor(hi, lo);
                let r = s.b.ins().band_imm_s(r, 0xFFFF);
                s.write_place(p, Width::Word, r);
                B::K(true)
            }),
            BoxOp::IntArith {
                op: op @ (ArithOp::Add | ArithOp::Sub),
                width,
                ref src,
                ref dst,
            } => self.inline_add_sub(op == ArithOp::Add, width, Some(src), dst),
            // INC/DEC of a word or dword is +1/-1 with the same flag rule.
            BoxOp::Step {
                width: width @ (Width::Word | Width::DWord),
                up,
                ref dst,
            } => self.inline_add_sub(up, width, None, dst),
            BoxOp::Logic {
                op,
                width,
                ref src,
                ref dst,
            } => self.boxed(|s, f| {
                let a = s.read_operand(src, width, f);
                let p = s.dst_place(dst, width, f);
                let d = s.read_place(p, width);
                let r = match op {
                    LogicOp::And => s.b.ins().band(d, a),
                    LogicOp::Or => s.b.ins().bor(d, a),
                    LogicOp::Xor => s.b.ins().bxor(d, a),
                };
                s.write_place(p, width, r);
                s.zero_flag(r);
                B::K(true)
            }),
            BoxOp::Invert { width, ref dst } => self.boxed(|s, f| {
                let p = s.dst_place(dst, width, f);
                let d = s.read_place(p, width);
                let r = s.b.ins().bnot(d);
                let r = s.b.ins().band_imm_s(r, i64::from(width.mask()));
                s.write_place(p, width, r);
                s.zero_flag(r);
                B::K(true)
            }),
            stljit_runtime::value_boxes!() => match ValueBox::of(bx) {
                Some(vb) => self.value_box(vb),
                // `ValueBox::of` covers exactly these variants (the runtime's tests say so).
                None => self.func.unsupported = Some(format!("{bx:?} is no value box")),
            },
            BoxOp::ImmediateRead { input, .. } | BoxOp::ImmediateWrite { output: input, .. }
                if input >= self.io_limit(bx) =>
            {
                self.boxed(|s, f| {
                    s.fail_now(f, stljit_core::ErrorCode::OperandRange as u16);
                    B::K(false)
                })
            }
            BoxOp::ImmediateRead { input, ref dst } => self.boxed(|s, f| {
                let a = Addr::img(s.env.layout.phys_in + input);
                let v = s.byte(a);
                let p = s.dst_place(dst, Width::Byte, f);
                s.write_place(p, Width::Byte, v);
                B::K(true)
            }),
            BoxOp::ImmediateWrite { ref src, output } => self.boxed(|s, f| {
                let v = s.read_operand(src, Width::Byte, f);
                let q = s.area_addr(Area::Q, output);
                s.write_static(q, Width::Byte, v);
                let o = Addr::img(s.env.layout.phys_out + output);
                s.write_static(o, Width::Byte, v);
                B::K(true)
            }),
            BoxOp::BlockMove {
                width,
                ref src,
                ref dst,
                ref count,
            } => self.block_move(width, src, dst, count),
            BoxOp::Fill {
                ref src,
                ref dst,
                ref count,
            } => self.fill(src, dst, count),
            BoxOp::ShiftRegister {
                data,
                start,
                ref len,
            } => self.shift_register(data, start, len),
        }
    }

    /// Whether a move of a word or double word between two static places can copy the bytes
    /// as they are (`move_raw`): no byte it reads is in the cache or was stored recently (a
    /// wide load of bytes still in the store buffer would stall; the general path assembles
    /// cached bytes instead). The destination is read too, for its old value, when the box
    /// has a predicate; it is checked either way.
    fn raw_move_applies(&self, width: Width, src: Loc, dst: Loc) -> bool {
        let now = self.block.cache.now;
        let cold = |a: Addr| {
            (0..width.bytes()).all(|i| self.block.cache.get(a.plus(i)).is_none())
                && self.func.stores.is_cold(a, width.bytes(), now)
        };
        width != Width::Byte && cold(self.loc_addr(src)) && cold(self.loc_addr(dst))
    }

    /// `MOVW`/`MOVD` without decoding: the image is big-endian and so is the destination, so
    /// the bytes are loaded and stored as they are, with no byte swap on either side (or on the
    /// old value kept where PF is 0). The written bytes enter the cache like any write.
    fn move_raw(&mut self, width: Width, src: Addr, dst: Addr) {
        let n = width.bytes();
        let ty = if width == Width::Word { I16 } else { I32 };
        let sb = self.base(src);
        let v = self.b.ins().load(ty, mf(), sb, src.off as i32);
        let db = self.base(dst);
        let v = match self.in_box.pf() {
            Some(p) => {
                let old = self.b.ins().load(ty, mf(), db, dst.off as i32);
                self.b.ins().select(p, v, old)
            }
            None => v,
        };
        self.b.ins().store(mf(), v, db, dst.off as i32);
        // Byte `i` of the destination is bits 8i.. of the (little-endian host's) load of it.
        let wide = if ty == I32 {
            v
        } else {
            self.b.ins().uextend(I32, v)
        };
        self.note_wide_write(dst, n, wide, |i| 8 * i);
        if let Some(pred) = &mut self.in_box.pred {
            pred.reads.clear();
        }
    }

    /// The byte count of the I or Q area an immediate box addresses.
    fn io_limit(&self, bx: &BoxOp) -> u32 {
        let area = if matches!(bx, BoxOp::ImmediateRead { .. }) {
            Area::I
        } else {
            Area::Q
        };
        self.env.layout.area_size(area)
    }

    fn zero_flag(&mut self, r: Value) {
        let z = self.b.ins().icmp_imm_s(IntCC::Equal, r, 0);
        let z = self.b.ins().uextend(I32, z);
        self.put_flags(i64::from(flags::ZERO), z);
    }

    /// Inline `+`/`-` (and INC/DEC of words and dwords) with the OK/OVF rules of
    /// `arith::int_arith`, over the runtime's flag bits: on overflow OUT keeps its value,
    /// SM1.1 = 1, SM1.0 = SM1.2 = 0; otherwise SM1.0/SM1.2 from the result and SM1.1 = 0.
    fn add_sub(&mut self, add: bool, width: Width, p: Place, d: Value, a: Value) -> B {
        // `r` is the wrapped result sign-extended to i32, `ovf` the signed-overflow flag. Words
        // and dwords use the native overflow flag (`add` + `seto`) instead of recomputing the
        // sum one size wider and comparing.
        let (r, ovf) = match width {
            Width::DWord => {
                if add {
                    self.b.ins().sadd_overflow(d, a)
                } else {
                    self.b.ins().ssub_overflow(d, a)
                }
            }
            Width::Word => {
                let d16 = self.b.ins().ireduce(I16, d);
                let a16 = self.b.ins().ireduce(I16, a);
                let (r16, ovf) = if add {
                    self.b.ins().sadd_overflow(d16, a16)
                } else {
                    self.b.ins().ssub_overflow(d16, a16)
                };
                (self.b.ins().sextend(I32, r16), ovf)
            }
            Width::Byte => {
                let ds = self.sext(d, width);
                let as_ = self.sext(a, width);
                let r = if add {
                    self.b.ins().iadd(ds, as_)
                } else {
                    self.b.ins().isub(ds, as_)
                };
                let back = self.sext(r, width);
                (r, self.b.ins().icmp(IntCC::NotEqual, back, r))
            }
        };
        self.put_result_flags(r, ovf);
        let masked = self.b.ins().band_imm_s(r, i64::from(width.mask()));
        let ovf32 = self.b.ins().uextend(I32, ovf);
        let ok = B::Not { v: ovf32, pos: 0 };
        match self.in_box.pred.as_ref().map(|p| p.flow) {
            // OUT changes where the box runs and did not overflow, which is its ENO: one
            // `select` on that instead of one on the overflow and the predicate's on top. The
            // ENO that `boxed_free` computes from `ok` is the same expression, so it is
            // emitted once.
            Some(flow) => {
                let go = flow.and(&mut self.b, ok).cond(&mut self.b);
                let out = self.b.ins().select(go, masked, d);
                self.write_place_unpredicated(p, width, out);
            }
            None => {
                let out = self.b.ins().select(ovf, d, masked);
                self.write_place(p, width, out);
            }
        }
        ok
    }

    /// A box computed by the runtime (value shim): reads IN1 (`src`) and OUT, calls, applies the
    /// SMB1 masks, writes OUT when the outcome has a value. `read_out` is false for boxes whose
    /// OUT is not an input (the shim then sees 0).
    /// `OUT := OUT ± IN` inlined (IN `None`: the constant 1 of INC/DEC), the runtime's flag rule
    /// through [`Lower::add_sub`].
    fn inline_add_sub(&mut self, add: bool, width: Width, src: Option<&Operand>, dst: &Operand) {
        self.boxed(|s, f| {
            let a = src.map(|src| s.read_operand(src, width, f));
            let p = s.dst_place(dst, width, f);
            let d = s.read_place(p, width);
            let a = a.unwrap_or_else(|| s.iconst(I32, 1));
            s.add_sub(add, width, p, d, a)
        })
    }

    /// A box that is one value computation ([`ValueBox`]): IN and OUT read, the runtime's pure
    /// value shim called, its packed outcome applied to OUT and SMB1.
    fn value_box(&mut self, vb: ValueBox) {
        let (vop, dw) = (vb.op, vb.out.width);
        self.boxed(|s, f| {
            let in1 = match vb.input {
                Some(u) => s.read_operand(&u.operand, u.width, f),
                None => s.iconst(I32, 0),
            };
            let p = s.dst_place(&vb.out.operand, dw, f);
            let old = s.read_place(p, dw);
            let out = if vb.reads_out() {
                old
            } else {
                s.iconst(I32, 0)
            };
            let r = s.call_value(vop, out, in1);
            let setm = s.b.ins().ushr_imm_s(r, i64::from(OUTCOME_SET_SHIFT));
            let setm = s.b.ins().ireduce(I32, setm);
            let setm = s.b.ins().band_imm_s(setm, 0xFF);
            let clr = s.b.ins().ushr_imm_s(r, i64::from(OUTCOME_CLEAR_SHIFT));
            let clr = s.b.ins().ireduce(I32, clr);
            let clr = s.b.ins().band_imm_s(clr, 0xFF);
            let a = s.smb1();
            let sm = s.byte(a);
            let kept = s.b.ins().band_not(sm, clr);
            let nsm = s.b.ins().bor(kept, setm);
            s.set_byte_pred(a, nsm);
            let has = s.b.ins().ushr_imm_s(r, i64::from(OUTCOME_HAS_VALUE_SHIFT));
            let has = s.b.ins().ireduce(I32, has);
            let has = s.b.ins().band_imm_s(has, 1);
            let val = s.b.ins().ireduce(I32, r);
            let val = s.b.ins().band_imm_s(val, i64::from(dw.mask()));
            let w = s.b.ins().select(has, val, old);
            s.write_place(p, dw, w);
            B::Bit { v: has, pos: 0 }
        })
    }
}
