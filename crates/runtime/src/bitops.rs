//! Word logic, shifts and rotates (spec §4.10, §4.11, M7) on raw operand bits.

use crate::flags::{OVERFLOW, Outcome, SmFlags, ZERO};
use stljit_core::Width;
use stljit_core::ir::LogicOp;

fn zero_flag(r: u32) -> SmFlags {
    SmFlags::assign(ZERO, if r == 0 { ZERO } else { 0 })
}

/// `ANDx/ORx/XORx IN1, OUT`: `OUT := OUT op IN1`; SM1.0 = result zero.
pub fn logic(op: LogicOp, width: Width, out: u32, in1: u32) -> Outcome {
    let r = match op {
        LogicOp::And => out & in1,
        LogicOp::Or => out | in1,
        LogicOp::Xor => out ^ in1,
    } & width.mask();
    Outcome {
        value: Some(r),
        flags: zero_flag(r),
    }
}

/// `INVx OUT`: one's complement; SM1.0 = result zero.
pub fn invert(width: Width, x: u32) -> Outcome {
    let r = !x & width.mask();
    Outcome {
        value: Some(r),
        flags: zero_flag(r),
    }
}

fn with_carry(r: u32, carry: Option<bool>) -> Outcome {
    let mut flags = zero_flag(r);
    if let Some(c) = carry {
        let f = SmFlags::assign(OVERFLOW, if c { OVERFLOW } else { 0 });
        flags = SmFlags {
            set: flags.set | f.set,
            clear: flags.clear | f.clear,
        };
    }
    Outcome {
        value: Some(r),
        flags,
    }
}

/// `SLx/SRx OUT, N`: logical shift by `min(N, w)`; SM1.1 = last bit shifted out (only if n > 0).
pub fn shift(left: bool, width: Width, x: u32, count: u8) -> Outcome {
    let w = width.bits();
    let x = x & width.mask();
    let n = u32::from(count).min(w);
    if n == 0 {
        return with_carry(x, None);
    }
    let (r, carry) = if left {
        (
            x.checked_shl(n).unwrap_or(0) & width.mask(),
            (x >> (w - n)) & 1,
        )
    } else {
        (x.checked_shr(n).unwrap_or(0), (x >> (n - 1)) & 1)
    };
    with_carry(r, Some(carry != 0))
}

/// `RLx/RRx OUT, N`: rotate by `N mod w`; SM1.0 = value zero; SM1.1 = the last bit carried round
/// (only if the rotation is not 0, spec M7).
pub fn rotate(left: bool, width: Width, x: u32, count: u8) -> Outcome {
    let w = width.bits();
    let x = x & width.mask();
    let n = u32::from(count) % w;
    if n == 0 {
        return with_carry(x, None);
    }
    let r = if left {
        (x << n | x >> (w - n)) & width.mask()
    } else {
        (x >> n | x << (w - n)) & width.mask()
    };
    let carry = if left { r & 1 } else { (r >> (w - 1)) & 1 };
    with_carry(r, Some(carry != 0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use Width::*;

    fn sm(o: Outcome, before: u8) -> u8 {
        o.flags.apply(before)
    }

    #[test]
    fn logic_and_invert() {
        let o = logic(LogicOp::And, Byte, 0xF0, 0x0F);
        assert_eq!((o.value, sm(o, 0)), (Some(0), ZERO));
        let o = logic(LogicOp::Xor, Word, 0xFFFF, 0x00FF);
        assert_eq!((o.value, sm(o, ZERO | OVERFLOW)), (Some(0xFF00), OVERFLOW));
        assert_eq!(invert(Word, 0x00FF).value, Some(0xFF00));
        assert_eq!(invert(DWord, 0xFFFF_FFFF).value, Some(0));
    }

    #[test]
    fn shifts_4_11() {
        // SLB 0b1000_0001 by 1: carry is bit 7.
        let o = shift(true, Byte, 0x81, 1);
        assert_eq!((o.value, sm(o, 0)), (Some(0x02), OVERFLOW));
        // Count above the width: n = w, result 0, carry = bit 0 (w − n = 0).
        let o = shift(true, Byte, 0x01, 200);
        assert_eq!((o.value, sm(o, 0)), (Some(0), ZERO | OVERFLOW));
        // SRW by 4: carry = bit 3.
        let o = shift(false, Word, 0x8008, 4);
        assert_eq!((o.value, sm(o, 0)), (Some(0x0800), OVERFLOW));
        // Logical: sign bit not preserved.
        assert_eq!(shift(false, DWord, 0x8000_0000, 31).value, Some(1));
        assert_eq!(shift(false, DWord, 0x8000_0000, 32).value, Some(0));
        // M7: count 0 leaves OUT and SM1.1, updates SM1.0.
        let o = shift(true, Word, 0, 0);
        assert_eq!((o.value, sm(o, OVERFLOW)), (Some(0), OVERFLOW | ZERO));
    }

    #[test]
    fn rotates_4_11() {
        let o = rotate(true, Byte, 0x81, 1);
        assert_eq!((o.value, sm(o, 0)), (Some(0x03), OVERFLOW));
        let o = rotate(false, Word, 0x0001, 1);
        assert_eq!((o.value, sm(o, 0)), (Some(0x8000), OVERFLOW));
        let o = rotate(false, Word, 0x0002, 1);
        assert_eq!((o.value, sm(o, OVERFLOW)), (Some(0x0001), 0));
        // N mod w = 0: unchanged, SM1.1 kept.
        let o = rotate(true, DWord, 0x1234, 64);
        assert_eq!((o.value, sm(o, OVERFLOW)), (Some(0x1234), OVERFLOW));
        assert_eq!(rotate(true, DWord, 0x8000_0001, 4).value, Some(0x0000_0018));
    }
}
