//! The value shim: one pure `extern "C"` entry to every box computation with an intricate flag
//! rule ([`arith`], [`bitops`], [`convert`]). Part of [`crate::ffi`].
//!
//! Compiled code reads the operands itself, calls the shim of the box's [`ValueOp`]
//! ([`VALUE_SHIMS`], by the operation's position in one constant table of every operation,
//! [`FfiCode`]), and applies the packed [`Outcome`] (value and SMB1 masks) with its own stores,
//! so the call touches no memory and the byte cache survives it. [`ValueOp::outcome`] is the
//! dispatch, an exhaustive match, which each shim resolves at compile time.
//!
//! [`ValueBox`] says which boxes are one value computation and with which operands (read from
//! core's [`BoxOp::operand_uses`]), so both engines dispatch those boxes through it.

use crate::flags::Outcome;
use crate::{arith, bitops, convert};
use std::panic::{AssertUnwindSafe, catch_unwind};
use stljit_core::Width;
use stljit_core::ir::{Access, ArithOp, BoxOp, Conversion, OperandUse, RealFn};

use super::FfiCode;

/// A box computation the value shim runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ValueOp {
    /// [`arith::int_arith`].
    IntArith(ArithOp, Width),
    /// [`arith::mul_wide`].
    MulWide,
    /// [`arith::div_wide`].
    DivWide,
    /// [`arith::step`] (INC/DEC).
    Step {
        /// Operand width.
        width: Width,
        /// INC (true) or DEC.
        up: bool,
    },
    /// [`arith::real_arith`].
    RealArith(ArithOp),
    /// [`arith::real_func`].
    RealFunc(RealFn),
    /// [`bitops::shift`].
    Shift {
        /// SL (true) or SR.
        left: bool,
        /// Operand width.
        width: Width,
    },
    /// [`bitops::rotate`].
    Rotate {
        /// RL (true) or RR.
        left: bool,
        /// Operand width.
        width: Width,
    },
    /// [`convert::convert`].
    Convert(Conversion),
}

/// Every [`ValueOp`], in the order of their codes (the position here, [`FfiCode`]; the value
/// shim of code `n` is `VALUE_SHIMS[n]`).
const VALUE_OPS: [ValueOp; VALUE_OP_COUNT] = every_value_op();

/// How many value computations there are.
pub const VALUE_OP_COUNT: usize = 2
    + Width::ALL.len() * (ArithOp::ALL.len() + 6)
    + ArithOp::ALL.len()
    + RealFn::ALL.len()
    + Conversion::ALL.len();

/// [`VALUE_OPS`]: the wide multiplication and division; per width the integer operations,
/// then DEC/INC, shift and rotate (right/down before left/up); the real operations; the real
/// functions; the conversions.
const fn every_value_op() -> [ValueOp; VALUE_OP_COUNT] {
    let mut ops = [ValueOp::MulWide; VALUE_OP_COUNT];
    let mut n = 0;
    ops[n] = ValueOp::MulWide;
    ops[n + 1] = ValueOp::DivWide;
    n += 2;
    let mut w = 0;
    while w < Width::ALL.len() {
        let width = Width::ALL[w];
        let mut a = 0;
        while a < ArithOp::ALL.len() {
            ops[n] = ValueOp::IntArith(ArithOp::ALL[a], width);
            n += 1;
            a += 1;
        }
        let mut d = 0;
        while d < 2 {
            // DEC, SR, RR first, then INC, SL, RL.
            let (up, left) = (d == 1, d == 1);
            ops[n] = ValueOp::Step { width, up };
            ops[n + 1] = ValueOp::Shift { left, width };
            ops[n + 2] = ValueOp::Rotate { left, width };
            n += 3;
            d += 1;
        }
        w += 1;
    }
    let mut a = 0;
    while a < ArithOp::ALL.len() {
        ops[n] = ValueOp::RealArith(ArithOp::ALL[a]);
        n += 1;
        a += 1;
    }
    let mut f = 0;
    while f < RealFn::ALL.len() {
        ops[n] = ValueOp::RealFunc(RealFn::ALL[f]);
        n += 1;
        f += 1;
    }
    let mut c = 0;
    while c < Conversion::ALL.len() {
        ops[n] = ValueOp::Convert(Conversion::ALL[c]);
        n += 1;
        c += 1;
    }
    assert!(n == VALUE_OP_COUNT);
    ops
}

impl FfiCode for ValueOp {
    const ALL: &'static [Self] = &VALUE_OPS;
}

impl ValueOp {
    /// Runs the computation on the operands' raw bits (`out`: OUT's old value, 0 where OUT is
    /// not an input; `in1`: IN1, or the count byte of a shift/rotate). Inlined into each value
    /// shim, where `self` is a constant and the match folds away.
    #[inline]
    pub fn outcome(self, out: u32, in1: u32) -> Outcome {
        match self {
            ValueOp::IntArith(op, w) => arith::int_arith(op, w, out, in1),
            ValueOp::MulWide => arith::mul_wide(out, in1),
            ValueOp::DivWide => arith::div_wide(out, in1),
            ValueOp::Step { width, up } => arith::step(width, up, out),
            ValueOp::RealArith(op) => arith::real_arith(op, out, in1),
            ValueOp::RealFunc(f) => arith::real_func(f, in1),
            ValueOp::Shift { left, width } => bitops::shift(left, width, out, in1 as u8),
            ValueOp::Rotate { left, width } => bitops::rotate(left, width, out, in1 as u8),
            ValueOp::Convert(c) => convert::convert(c, in1),
        }
    }
}

/// The pattern of every [`BoxOp`] variant that is a [`ValueBox`], the one list of them, for the
/// engines' exhaustive matches: `stljit_runtime::value_boxes!() => ...`.
#[macro_export]
macro_rules! value_boxes {
    () => {
        ::stljit_core::ir::BoxOp::IntArith { .. }
            | ::stljit_core::ir::BoxOp::MulWide { .. }
            | ::stljit_core::ir::BoxOp::DivWide { .. }
            | ::stljit_core::ir::BoxOp::RealArith { .. }
            | ::stljit_core::ir::BoxOp::RealFunc { .. }
            | ::stljit_core::ir::BoxOp::Step { .. }
            | ::stljit_core::ir::BoxOp::Shift { .. }
            | ::stljit_core::ir::BoxOp::Rotate { .. }
            | ::stljit_core::ir::BoxOp::Convert { .. }
    };
}

/// A box whose whole effect is one value computation: `OUT := op(OUT, IN)` and the SMB1 flags
/// of the [`Outcome`]. The operands are core's statement of the box's operands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ValueBox {
    /// The computation.
    pub op: ValueOp,
    /// IN (for shifts and rotates the count); `None` for INC/DEC, which read only OUT.
    pub input: Option<OperandUse>,
    /// OUT; its access says whether its old value is an input ([`Access::ReadWrite`]).
    pub out: OperandUse,
}

impl ValueBox {
    /// The value computation box `b` is, or `None` for a box the engines handle otherwise
    /// (moves, block moves, fills, word logic, inversion, SWAP, SHRB, immediate I/O).
    pub fn of(b: &BoxOp) -> Option<ValueBox> {
        let op = match *b {
            BoxOp::IntArith { op, width, .. } => ValueOp::IntArith(op, width),
            BoxOp::MulWide { .. } => ValueOp::MulWide,
            BoxOp::DivWide { .. } => ValueOp::DivWide,
            BoxOp::Step { width, up, .. } => ValueOp::Step { width, up },
            BoxOp::RealArith { op, .. } => ValueOp::RealArith(op),
            BoxOp::RealFunc { func, .. } => ValueOp::RealFunc(func),
            BoxOp::Shift { left, width, .. } => ValueOp::Shift { left, width },
            BoxOp::Rotate { left, width, .. } => ValueOp::Rotate { left, width },
            BoxOp::Convert { conv, .. } => ValueOp::Convert(conv),
            BoxOp::Move { .. }
            | BoxOp::Swap { .. }
            | BoxOp::BlockMove { .. }
            | BoxOp::Fill { .. }
            | BoxOp::Logic { .. }
            | BoxOp::Invert { .. }
            | BoxOp::ShiftRegister { .. }
            | BoxOp::ImmediateRead { .. }
            | BoxOp::ImmediateWrite { .. } => return None,
        };
        let uses = b.operand_uses();
        Some(ValueBox {
            op,
            input: uses.input(),
            out: uses.output()?,
        })
    }

    /// Whether OUT's old value is an input of the computation.
    pub fn reads_out(&self) -> bool {
        self.out.access == Access::ReadWrite
    }
}

/// Bit position of the SMB1 set mask in a packed outcome (see [`pack_outcome`]).
pub const OUTCOME_SET_SHIFT: u32 = 40;
/// Bit position of the SMB1 clear mask in a packed outcome.
pub const OUTCOME_CLEAR_SHIFT: u32 = 48;
/// Bit position of the "has a value" bit in a packed outcome.
pub const OUTCOME_HAS_VALUE_SHIFT: u32 = 32;

/// Packs an outcome: bits 0–31 the value, bit 32 set when there is one, bits 40–47 the SMB1
/// bits to set, bits 48–55 the bits to clear.
pub fn pack_outcome(o: Outcome) -> u64 {
    let (v, has) = match o.value {
        Some(v) => (u64::from(v), 1u64 << OUTCOME_HAS_VALUE_SHIFT),
        None => (0, 0),
    };
    v | has
        | u64::from(o.flags.set) << OUTCOME_SET_SHIFT
        | u64::from(o.flags.clear) << OUTCOME_CLEAR_SHIFT
}

/// A value shim: `(out, in1)` → the packed outcome ([`pack_outcome`]) of one [`ValueOp`]
/// (`out`: OUT's old value, 0 where OUT is not an input; `in1`: IN1, or the count byte of a
/// shift/rotate). Touches no memory. A panic (a runtime bug) reads as "no value, no flags",
/// i.e. ENO = 0; it never unwinds across the boundary.
pub type ValueShim = extern "C" fn(out: u32, in1: u32) -> u64;

/// The value shim of the operation with code `CODE` ([`FfiCode`]): the operation is a
/// constant here, so its dispatch is resolved when the runtime is compiled and a call runs
/// just the computation (compiled code knows each box's operation).
extern "C" fn value_shim<const CODE: usize>(out: u32, in1: u32) -> u64 {
    let op = VALUE_OPS[CODE];
    catch_unwind(AssertUnwindSafe(|| pack_outcome(op.outcome(out, in1)))).unwrap_or(0)
}

macro_rules! value_shims {
    ($($code:literal)+) => {
        [$(value_shim::<$code> as ValueShim),+]
    };
}

/// The value shim of every operation, by code: `VALUE_SHIMS[op.ffi_code()]`. (Its type has
/// [`VALUE_OP_COUNT`] entries, so the list of codes below cannot fall out of step with
/// [`VALUE_OPS`].)
pub static VALUE_SHIMS: [ValueShim; VALUE_OP_COUNT] = value_shims!(
    0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 32
    33 34 35 36 37 38 39 40 41 42 43 44 45 46 47 48 49 50 51 52 53
);

/// The symbol compiled code imports the value shim of code `code` by:
/// `stljit_rt_value_<code>`.
pub fn value_shim_symbol(code: u32) -> String {
    format!("stljit_rt_value_{code}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn every_op() -> Vec<ValueOp> {
        let widths = [Width::Byte, Width::Word, Width::DWord];
        let mut v = vec![ValueOp::MulWide, ValueOp::DivWide];
        for &w in &widths {
            for &op in ArithOp::ALL {
                v.push(ValueOp::IntArith(op, w));
            }
            for left in [false, true] {
                v.push(ValueOp::Step { width: w, up: left });
                v.push(ValueOp::Shift { left, width: w });
                v.push(ValueOp::Rotate { left, width: w });
            }
        }
        v.extend(ArithOp::ALL.iter().map(|&op| ValueOp::RealArith(op)));
        v.extend(RealFn::ALL.iter().map(|&f| ValueOp::RealFunc(f)));
        v.extend(Conversion::ALL.iter().map(|&c| ValueOp::Convert(c)));
        v
    }

    #[test]
    fn value_boxes_take_core_operands_and_cover_the_value_variants() {
        use stljit_core::ir::{Loc, LogicOp, Operand};
        let v = |offset| {
            Operand::Mem(Loc {
                area: stljit_core::Area::V,
                offset,
            })
        };
        let (a, b) = (v(0), v(4));
        let shift = ValueBox::of(&BoxOp::Shift {
            left: true,
            width: Width::Word,
            dst: a,
            count: b,
        })
        .expect("a value box");
        assert_eq!(
            shift.input.map(|u| (u.operand, u.width)),
            Some((b, Width::Byte))
        );
        assert_eq!((shift.out.operand, shift.out.width), (a, Width::Word));
        assert!(shift.reads_out());
        let conv = BoxOp::Convert {
            conv: Conversion::IntToDInt,
            src: a,
            dst: b,
        };
        let conv = ValueBox::of(&conv).expect("a value box");
        assert!(!conv.reads_out());
        assert_eq!(conv.out.width, Width::DWord);
        let inc = ValueBox::of(&BoxOp::Step {
            width: Width::Byte,
            up: true,
            dst: a,
        })
        .expect("a value box");
        assert_eq!(inc.input, None);
        let word_logic = BoxOp::Logic {
            op: LogicOp::And,
            width: Width::Word,
            src: a,
            dst: b,
        };
        assert_eq!(ValueBox::of(&word_logic), None);
        // Every value computation is reachable from a box.
        let boxes = [
            BoxOp::MulWide { src: a, dst: b },
            BoxOp::DivWide { src: a, dst: b },
            BoxOp::RealArith {
                op: ArithOp::Div,
                src: a,
                dst: b,
            },
            BoxOp::RealFunc {
                func: RealFn::Ln,
                src: a,
                dst: b,
            },
        ];
        assert!(boxes.iter().all(|b| ValueBox::of(b).is_some()));
    }

    #[test]
    fn every_operation_has_one_code_and_nothing_else_decodes() {
        let ops = every_op();
        assert_eq!(ValueOp::ALL.len(), ops.len());
        for &v in &ops {
            let code = v.ffi_code();
            assert_eq!(ValueOp::from_ffi(code), Some(v), "{v:?}");
            assert_eq!(ValueOp::ALL.iter().filter(|&&x| x == v).count(), 1, "{v:?}");
        }
        assert_eq!(ValueOp::from_ffi(ops.len() as u32), None);
        assert_eq!(VALUE_SHIMS.len(), ops.len());
        assert_eq!(value_shim_symbol(7), "stljit_rt_value_7");
    }

    #[test]
    fn shim_packs_the_helpers_outcome() {
        let samples = [
            0u32,
            1,
            0x7FFF,
            0x8000,
            0xFFFF,
            0x3F80_0000,
            0x7FC0_0000,
            0xFFFF_FFFF,
        ];
        for v in every_op() {
            let shim = VALUE_SHIMS[v.ffi_code() as usize];
            for &x in &samples {
                for &y in &samples {
                    assert_eq!(
                        shim(x, y),
                        pack_outcome(v.outcome(x, y)),
                        "{v:?} {x:#x} {y:#x}"
                    );
                }
            }
        }
        // +I 32767 + 1: overflow, no value, SM1.1 set, SM1.0/SM1.2 cleared.
        let op = ValueOp::IntArith(ArithOp::Add, Width::Word).ffi_code();
        let r = VALUE_SHIMS[op as usize](32767, 1);
        assert_eq!(r >> OUTCOME_HAS_VALUE_SHIFT & 1, 0);
        assert_eq!((r >> OUTCOME_SET_SHIFT) as u8, crate::flags::OVERFLOW);
    }
}
