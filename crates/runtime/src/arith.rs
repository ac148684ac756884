//! Integer and real arithmetic with the SMB1 rules of spec §4.8, §4.9 and §6.4 (M1–M5, M9).
//!
//! Values travel as the raw bits of their width (`u32`, low bits used), exactly what an engine
//! reads from the image; the helpers interpret them as signed or IEEE as the instruction says.
//!
//! Rules fixed here where the spec leaves room:
//! * Division overflow (`-32768 / -1`) clears SM1.3 along with SM1.0 and SM1.2 (the manual says
//!   the other bits are cleared for `*` and `/`), since the divisor was not zero.
//! * `/R`: a non-finite input is checked first (OVF), then a zero divisor (DIV0), then the result.
//! * Transcendentals are computed in `f64` and rounded once to `f32`; both engines call this code,
//!   so they agree bit for bit on one host. (They use the host's libm: another host may differ in
//!   the last bit, so conformance data should not pin such bits.)

use crate::flags::{DIV_ZERO, NEGATIVE, OVERFLOW, Outcome, RESULT, SmFlags, ZERO};
use stljit_core::Width;
use stljit_core::ir::{ArithOp, RealFn};

/// OK rule: SM1.0 = zero, SM1.1 = 0, SM1.2 = negative (plus SM1.3 = 0 for divisions).
fn ok_flags(zero: bool, negative: bool, division: bool) -> SmFlags {
    let v = if zero { ZERO } else { 0 } | if negative { NEGATIVE } else { 0 };
    let mask = RESULT | if division { DIV_ZERO } else { 0 };
    SmFlags::assign(mask, v)
}

/// OVF rule: OUT not written, SM1.1 = 1, SM1.0 = SM1.2 = 0 (division: SM1.3 = 0 too).
fn overflow(division: bool) -> Outcome {
    let mask = RESULT | if division { DIV_ZERO } else { 0 };
    Outcome {
        value: None,
        flags: SmFlags::assign(mask, OVERFLOW),
    }
}

/// DIV0 rule: OUT not written, SM1.3 = 1, other bits unchanged.
fn div_zero() -> Outcome {
    Outcome {
        value: None,
        flags: SmFlags {
            set: DIV_ZERO,
            clear: 0,
        },
    }
}

fn sign_extend(v: u32, width: Width) -> i64 {
    match width {
        Width::Byte => i64::from(v as u8),
        Width::Word => i64::from(v as u16 as i16),
        Width::DWord => i64::from(v as i32),
    }
}

fn fits(r: i64, width: Width) -> bool {
    match width {
        Width::Byte => (0..=255).contains(&r),
        Width::Word => i16::try_from(r).is_ok(),
        Width::DWord => i32::try_from(r).is_ok(),
    }
}

fn checked_result(r: i64, width: Width, division: bool) -> Outcome {
    if !fits(r, width) {
        return overflow(division);
    }
    Outcome {
        value: Some(r as u32 & width.mask()),
        flags: ok_flags(r == 0, r < 0, division),
    }
}

/// `+I -I *I /I` (Word) and `+D -D *D /D` (DWord): `OUT := OUT op IN1` (spec §4.8).
/// `Width::Byte` is not an instruction; it computes unsigned like INCB for completeness.
pub fn int_arith(op: ArithOp, width: Width, out: u32, in1: u32) -> Outcome {
    let (a, b) = (sign_extend(out, width), sign_extend(in1, width));
    let r = match op {
        ArithOp::Add => a + b,
        ArithOp::Sub => a - b,
        ArithOp::Mul => a * b,
        ArithOp::Div => {
            if b == 0 {
                return div_zero();
            }
            a / b // i64 truncates toward zero; -32768 / -1 = 32768 is caught by `fits`
        }
    };
    checked_result(r, width, op == ArithOp::Div)
}

/// `MUL IN1, OUT`: `OUT := (i16) OUT.low16 × (i16) IN1` as a dword; never overflows.
pub fn mul_wide(out: u32, in1: u32) -> Outcome {
    let r = i32::from(out as u16 as i16) * i32::from(in1 as u16 as i16);
    Outcome {
        value: Some(r as u32),
        flags: ok_flags(r == 0, r < 0, false),
    }
}

/// `DIV IN1, OUT`: dividend `(i16) OUT.low16`; `OUT := remainder << 16 | quotient`; flags from
/// the quotient (spec M4).
pub fn div_wide(out: u32, in1: u32) -> Outcome {
    let (a, b) = (i32::from(out as u16 as i16), i32::from(in1 as u16 as i16));
    if b == 0 {
        return div_zero();
    }
    let (q, r) = (a / b, a % b);
    if i16::try_from(q).is_err() {
        return overflow(true);
    }
    Outcome {
        value: Some(((r as u32) << 16) | (q as u32 & 0xFFFF)),
        flags: ok_flags(q == 0, q < 0, true),
    }
}

/// `INCB/DECB` (unsigned; leaving 0..=255 is OVF and touches only SM1.0/SM1.1),
/// `INCW/DECW/INCD/DECD` (signed, OK/OVF) — spec §4.8 and M2.
pub fn step(width: Width, up: bool, x: u32) -> Outcome {
    let d = if up { 1 } else { -1 };
    if width == Width::Byte {
        let r = i64::from(x as u8) + d;
        return if (0..=255).contains(&r) {
            Outcome {
                value: Some(r as u32),
                flags: SmFlags::assign(ZERO | OVERFLOW, if r == 0 { ZERO } else { 0 }),
            }
        } else {
            Outcome {
                value: None,
                flags: SmFlags::assign(ZERO | OVERFLOW, OVERFLOW),
            }
        };
    }
    checked_result(sign_extend(x, width) + d, width, false)
}

fn real_result(r: f32, division: bool) -> Outcome {
    if !r.is_finite() {
        return overflow(division);
    }
    Outcome {
        value: Some(r.to_bits()),
        flags: ok_flags(r == 0.0, r < 0.0, division),
    }
}

/// `+R -R *R /R`: `OUT := OUT op IN1` on IEEE binary32 bits (spec §4.9, M5).
pub fn real_arith(op: ArithOp, out: u32, in1: u32) -> Outcome {
    let (a, b) = (f32::from_bits(out), f32::from_bits(in1));
    let division = op == ArithOp::Div;
    if !a.is_finite() || !b.is_finite() {
        return overflow(division);
    }
    let r = match op {
        ArithOp::Add => a + b,
        ArithOp::Sub => a - b,
        ArithOp::Mul => a * b,
        ArithOp::Div => {
            if b == 0.0 {
                return div_zero();
            }
            a / b
        }
    };
    real_result(r, division)
}

/// The shared implementation of the real functions (spec M9), on plain `f32`.
pub fn real_fn_value(func: RealFn, x: f32) -> f32 {
    let y = f64::from(x);
    let r = match func {
        RealFn::Sqrt => return x.sqrt(),
        RealFn::Ln => y.ln(),
        RealFn::Exp => y.exp(),
        RealFn::Sin => y.sin(),
        RealFn::Cos => y.cos(),
        RealFn::Tan => y.tan(),
    };
    r as f32
}

/// `SQRT LN EXP SIN COS TAN IN, OUT` on IEEE bits, with the §4.9 flags.
pub fn real_func(func: RealFn, in1: u32) -> Outcome {
    let x = f32::from_bits(in1);
    if !x.is_finite() {
        return overflow(false);
    }
    real_result(real_fn_value(func, x), false)
}

#[cfg(test)]
#[path = "arith_tests.rs"]
mod tests;
