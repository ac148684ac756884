//! Spec §4.8/§4.9 flag rules (OK/OVF/DIV0), M1–M5, and T15's arithmetic.

use super::*;
use crate::flags::SmFlags;
use ArithOp::*;

fn run(o: Outcome, before: u8) -> (Option<u32>, u8) {
    (o.value, o.flags.apply(before))
}

#[test]
fn int_ok_ovf_div0() {
    // T15: 32766 + 1 = 32767 OK; 32767 + 1 overflows, OUT not written, SM1.1 only.
    assert_eq!(
        run(int_arith(Add, Width::Word, 32766, 1), 0),
        (Some(32767), 0)
    );
    assert_eq!(
        run(int_arith(Add, Width::Word, 32767, 1), ZERO | NEGATIVE),
        (None, OVERFLOW)
    );
    // /I by 0: SM1.3 set, other bits unchanged (E1).
    assert_eq!(
        run(int_arith(Div, Width::Word, 100, 0), OVERFLOW),
        (None, OVERFLOW | DIV_ZERO)
    );
    // OK clears SM1.1 and, for division, SM1.3.
    assert_eq!(
        run(int_arith(Div, Width::Word, 7, 2), OVERFLOW | DIV_ZERO),
        (Some(3), 0)
    );
    assert_eq!(
        run(int_arith(Div, Width::Word, (-7i16) as u16 as u32, 2), 0),
        (Some(0xFFFD), NEGATIVE)
    );
    assert_eq!(run(int_arith(Sub, Width::Word, 5, 5), 0), (Some(0), ZERO));
    assert_eq!(
        run(int_arith(Div, Width::Word, 0x8000, 0xFFFF), DIV_ZERO),
        (None, OVERFLOW)
    );
    assert_eq!(
        run(int_arith(Mul, Width::DWord, 0x10000, 0x10000), 0),
        (None, OVERFLOW)
    );
    assert_eq!(
        run(int_arith(Mul, Width::DWord, 0xFFFF_FFFF, 3), 0),
        (Some(0xFFFF_FFFD), NEGATIVE)
    );
    assert_eq!(
        run(int_arith(Sub, Width::DWord, 0x8000_0000, 1), 0),
        (None, OVERFLOW)
    );
}

#[test]
fn mul_div_wide() {
    // MUL: low word of OUT × IN1, high word of OUT ignored.
    assert_eq!(
        run(mul_wide(0xABCD_FFFE, 300), 0),
        (Some((-600i32) as u32), NEGATIVE)
    );
    assert_eq!(mul_wide(0x7FFF, 0x7FFF).value, Some(0x3FFF_0001));
    // DIV: 7 ÷ 2 → remainder 1 in the high word, quotient 3 in the low word.
    assert_eq!(
        run(div_wide(0xFFFF_0007, 2), OVERFLOW),
        (Some(0x0001_0003), 0)
    );
    assert_eq!(
        div_wide((-7i32) as u32, 2).value,
        Some(0xFFFF_FFFD),
        "r = -1, q = -3"
    );
    assert_eq!(run(div_wide(0x8000, 0xFFFF), 0), (None, OVERFLOW));
    assert_eq!(run(div_wide(5, 0), 0), (None, DIV_ZERO));
}

#[test]
fn inc_dec_m2() {
    assert_eq!(run(step(Width::Byte, true, 254), 0), (Some(255), 0));
    assert_eq!(
        run(step(Width::Byte, true, 255), ZERO | NEGATIVE),
        (None, OVERFLOW | NEGATIVE)
    );
    assert_eq!(run(step(Width::Byte, false, 1), 0), (Some(0), ZERO));
    assert_eq!(run(step(Width::Byte, false, 0), 0), (None, OVERFLOW));
    assert_eq!(
        run(step(Width::Word, false, 0), 0),
        (Some(0xFFFF), NEGATIVE)
    );
    assert_eq!(run(step(Width::Word, true, 0x7FFF), 0), (None, OVERFLOW));
    assert_eq!(
        run(step(Width::DWord, true, 0x0600_00C8), 0),
        (Some(0x0600_00C9), 0)
    );
}

#[test]
fn real_rules_4_9() {
    let r = |x: f32| x.to_bits();
    assert_eq!(run(real_arith(Add, r(1.5), r(-1.5)), 0), (Some(0), ZERO));
    assert_eq!(
        run(real_arith(Sub, r(1.0), r(3.0)), 0),
        (Some(r(-2.0)), NEGATIVE)
    );
    assert_eq!(run(real_arith(Mul, r(3e38), r(10.0)), 0), (None, OVERFLOW));
    assert_eq!(
        run(real_arith(Div, r(1.0), r(-0.0)), OVERFLOW),
        (None, OVERFLOW | DIV_ZERO)
    );
    assert_eq!(
        run(real_arith(Div, r(f32::NAN), r(0.0)), 0),
        (None, OVERFLOW)
    );
    assert_eq!(
        run(real_arith(Div, r(1.0), r(4.0)), DIV_ZERO),
        (Some(r(0.25)), 0)
    );
    // M5: -0.0 is zero and not negative; subnormals kept.
    assert_eq!(
        run(real_arith(Mul, r(-1.0), r(0.0)), 0),
        (Some(r(-0.0)), ZERO)
    );
    let tiny = f32::from_bits(1);
    assert_eq!(real_arith(Add, r(tiny), r(0.0)).value, Some(1));
    assert_eq!(run(real_func(RealFn::Sqrt, r(-1.0)), 0), (None, OVERFLOW));
    assert_eq!(run(real_func(RealFn::Ln, r(0.0)), 0), (None, OVERFLOW));
    assert_eq!(real_func(RealFn::Sqrt, r(2.25)).value, Some(r(1.5)));
    assert_eq!(real_func(RealFn::Exp, r(0.0)).value, Some(r(1.0)));
    assert_eq!(real_func(RealFn::Sin, r(0.0)).value, Some(r(0.0)));
    assert_eq!(real_func(RealFn::Cos, r(0.0)).value, Some(r(1.0)));
    let t = f32::from_bits(real_func(RealFn::Tan, r(1.0)).value.unwrap());
    assert!((t - 1.557_407_7).abs() < 1e-6);
    assert_eq!(run(real_func(RealFn::Exp, r(100.0)), 0), (None, OVERFLOW));
    assert_eq!(SmFlags::NONE.apply(0x5A), 0x5A);
}
