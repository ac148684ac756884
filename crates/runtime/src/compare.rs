//! Compare contacts (spec §4.6): bytes unsigned, words and dwords signed, reals by IEEE order
//! with a NaN operand fatal (M8); `-0.0 = +0.0`.

use stljit_core::FatalCode;
use stljit_core::ir::{CmpOp, CmpType};

fn relate<T: PartialOrd>(op: CmpOp, a: T, b: T) -> bool {
    match op {
        CmpOp::Eq => a == b,
        CmpOp::Ne => a != b,
        CmpOp::Ge => a >= b,
        CmpOp::Le => a <= b,
        CmpOp::Gt => a > b,
        CmpOp::Lt => a < b,
    }
}

/// `lhs op rhs` on the operands' raw bits.
pub fn compare(ty: CmpType, op: CmpOp, lhs: u32, rhs: u32) -> Result<bool, FatalCode> {
    Ok(match ty {
        CmpType::Byte => relate(op, lhs as u8, rhs as u8),
        CmpType::Int => relate(op, lhs as u16 as i16, rhs as u16 as i16),
        CmpType::DInt => relate(op, lhs as i32, rhs as i32),
        CmpType::Real => {
            let (a, b) = (f32::from_bits(lhs), f32::from_bits(rhs));
            if a.is_nan() || b.is_nan() {
                return Err(FatalCode::CompareNaN);
            }
            relate(op, a, b)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use CmpOp::*;
    use CmpType::*;

    #[test]
    fn types_4_6() {
        assert_eq!(compare(Byte, Gt, 0x80, 0x7F), Ok(true), "bytes unsigned");
        assert_eq!(compare(Int, Gt, 0x8000, 0x7FFF), Ok(false), "words signed");
        assert_eq!(compare(Int, Ge, 32767, 32767), Ok(true));
        assert_eq!(compare(DInt, Lt, 0xFFFF_FFFF, 0), Ok(true));
        let r = |x: f32| x.to_bits();
        assert_eq!(compare(Real, Eq, r(-0.0), r(0.0)), Ok(true));
        assert_eq!(compare(Real, Gt, r(f32::INFINITY), r(1e30)), Ok(true));
        assert_eq!(
            compare(Real, Ne, r(f32::NAN), r(0.0)),
            Err(FatalCode::CompareNaN)
        );
        assert_eq!(compare(Int, Ne, 1, 2), Ok(true));
        assert_eq!(compare(Int, Le, 2, 2), Ok(true));
    }
}
