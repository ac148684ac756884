//! The arithmetic instructions of spec §3.6 (`+` … `/BL`, core's [`OmronArith`]) with their
//! condition flags.
//!
//! Operands travel as raw bits: the low 16 bits of the `u32` for a one-word operand, the
//! Omron double word (low 16 bits = lower-numbered word, spec §1.6) for a two-word one. The
//! result is an `u64` whose **word `i` (bits `16i..16i+15`) is written to `R+i`**, for the
//! [`OmronArith::result_words`] words of the instruction ([`ArithOutcome::words`]); so a 16-bit
//! product is `R` = low word, `R+1` = high word, a 16-bit division `R` = quotient, `R+1` =
//! remainder, and a 32-bit division `R:R+1` = quotient, `R+2:R+3` = remainder.
//!
//! Rules fixed here where the spec leaves room (each stated once, in its function):
//! * Signed division truncates toward zero and the remainder takes the dividend's sign;
//!   −32768 / −1 gives quotient `#8000` and remainder 0 with no ER (U13), −2³¹ / −1 likewise.
//! * `/`'s N is "quotient < 0" read in the instruction's own number format: the stored
//!   quotient's sign bit for `/` and `/L` (so ON for U13's `#8000`), always OFF for the unsigned
//!   and BCD forms, whose quotient cannot be negative.
//! * With carry in (`+C`, `-C`, …) CY and OF/UF come from the exact sum `a + b + CY` or
//!   difference `a − b − CY`: CY = the unsigned result does not fit, OF/UF = the signed result
//!   is above / below the signed range (for `+`/`-` these are the spec's sign formulas).
//! * BCD: a non-BCD operand (or a zero BCD divisor) sets ER only and nothing is written.

use super::bcd;
use super::flags::{Flag, FlagWrites};
use stljit_core::ir::OmronArith;

/// What an arithmetic instruction produced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArithOutcome {
    /// The result words (word `i` = bits `16i..16i+15`, written to `R+i`), or `None`: ER,
    /// nothing is written.
    pub result: Option<u64>,
    /// The condition flags the instruction writes.
    pub flags: FlagWrites,
}

impl ArithOutcome {
    /// The result as words in writing order (`[R, R+1, R+2, R+3]`); only the first
    /// [`OmronArith::result_words`] of them are written.
    pub fn words(self) -> Option<[u16; 4]> {
        self.result.map(|r| {
            let w = |i: u32| (r >> (16 * i)) as u16;
            [w(0), w(1), w(2), w(3)]
        })
    }

    const ERROR: ArithOutcome = ArithOutcome {
        result: None,
        flags: FlagWrites::ERROR,
    };

    fn ok(result: u64, flags: FlagWrites) -> ArithOutcome {
        ArithOutcome {
            result: Some(result),
            flags,
        }
    }
}

/// The operand width of an instruction: 16 bits (one word) or 32 bits (two words, `L` forms).
#[derive(Clone, Copy)]
struct Width {
    bits: u32,
}

impl Width {
    fn of(kind: OmronArith) -> Width {
        Width {
            bits: 16 * kind.operand_words(),
        }
    }

    fn mask(self) -> u64 {
        (1u64 << self.bits) - 1
    }

    fn unsigned(self, v: u32) -> u64 {
        u64::from(v) & self.mask()
    }

    fn signed(self, v: u32) -> i64 {
        let shift = 64 - self.bits;
        ((self.unsigned(v) << shift) as i64) >> shift
    }

    fn min(self) -> i64 {
        -(1i64 << (self.bits - 1))
    }

    fn max(self) -> i64 {
        (1i64 << (self.bits - 1)) - 1
    }

    /// `10^digits`: the BCD modulus (a constant per width, so no `pow` on the hot path).
    fn bcd_modulus(self) -> u64 {
        if self.bits == 16 { 10_000 } else { 100_000_000 }
    }

    /// The value of BCD operand `v`, or `None` if it is not BCD.
    fn bcd(self, v: u32) -> Option<u64> {
        if self.bits == 16 {
            bcd::bcd16_to_bin(v as u16).map(u64::from)
        } else {
            bcd::bcd32_to_bin(v).map(u64::from)
        }
    }

    /// `v` (below `10^(2·digits)`) as BCD of `2·digits` digits, as a double-width result.
    fn to_bcd(v: u64) -> u64 {
        bcd::bin_to_bcd64(v).unwrap_or(0) // callers pass products and quotients that fit
    }
}

/// The binary sums and differences (`+`, `+L`, `+C`, `+CL`, `-`, `-L`, `-C`, `-CL`): what
/// compiled code may compute inline, with the flag rule of `add`/`sub` here (the JIT's copy is
/// held equal to it by the differential tests; `binary_sum_shapes` below holds this table
/// equal to [`execute`]'s dispatch).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BinarySum {
    /// `+` forms; else `-` forms (CY is the borrow).
    pub add: bool,
    /// The `C` forms: the carry flag before the instruction is added (subtracted).
    pub carry_in: bool,
}

impl BinarySum {
    /// The shape of `kind`, if it is a binary sum or difference.
    pub fn of(kind: OmronArith) -> Option<BinarySum> {
        use OmronArith::*;
        let (add, carry_in) = match kind {
            Add | AddL => (true, false),
            AddC | AddCL => (true, true),
            Sub | SubL => (false, false),
            SubC | SubCL => (false, true),
            _ => return None,
        };
        Some(BinarySum { add, carry_in })
    }
}

/// Runs arithmetic instruction `kind` on `a` (augend, minuend, multiplicand, dividend) and `b`;
/// `cy` is the carry flag before the instruction (read by the `C` forms only).
pub fn execute(kind: OmronArith, a: u32, b: u32, cy: bool) -> ArithOutcome {
    use OmronArith::*;
    let w = Width::of(kind);
    match kind {
        Add | AddL => add(w, a, b, false),
        AddC | AddCL => add(w, a, b, cy),
        AddB | AddBL => add_bcd(w, a, b, false),
        AddBC | AddBCL => add_bcd(w, a, b, cy),
        Sub | SubL => sub(w, a, b, false),
        SubC | SubCL => sub(w, a, b, cy),
        SubB | SubBL => sub_bcd(w, a, b, false),
        SubBC | SubBCL => sub_bcd(w, a, b, cy),
        Mul | MulL => {
            let p = (w.signed(a) * w.signed(b)) as u64; // |p| ≤ 2^62: no overflow
            product(w, p, true)
        }
        MulU | MulUL => product(w, w.unsigned(a) * w.unsigned(b), true), // < 2^64
        MulB | MulBL => match (w.bcd(a), w.bcd(b)) {
            (Some(x), Some(y)) => product(w, Width::to_bcd(x * y), false), // < 10^16
            _ => ArithOutcome::ERROR,
        },
        Div | DivL => divide_signed(w, a, b),
        DivU | DivUL => match (w.unsigned(a), w.unsigned(b)) {
            (_, 0) => ArithOutcome::ERROR,
            (x, y) => quotient(w, x / y, x % y, false),
        },
        DivB | DivBL => match (w.bcd(a), w.bcd(b)) {
            (Some(_), Some(0)) | (None, _) | (_, None) => ArithOutcome::ERROR,
            (Some(x), Some(y)) => quotient(
                w,
                bcd::bin_to_bcd64(x / y).unwrap_or(0), // below the dividend: fits
                bcd::bin_to_bcd64(x % y).unwrap_or(0), // below the divisor: fits
                false,
            ),
        },
    }
}

/// The flags of a binary `+`/`-` result: ER OFF, CY, `=`, N, OF, UF.
fn binary_flags(w: Width, r: u64, carry: bool, exact: i64) -> FlagWrites {
    FlagWrites::OK
        .write(Flag::Cy, carry)
        .write(Flag::Eq, r == 0)
        .write(Flag::N, (r >> (w.bits - 1)) & 1 != 0)
        .write(Flag::Of, exact > w.max())
        .write(Flag::Uf, exact < w.min())
}

/// `+`, `+L`, `+C`, `+CL`: `R := (a + b + cin) mod 2^bits`.
fn add(w: Width, a: u32, b: u32, cin: bool) -> ArithOutcome {
    let c = u64::from(cin);
    let sum = w.unsigned(a) + w.unsigned(b) + c;
    let r = sum & w.mask();
    let exact = w.signed(a) + w.signed(b) + c as i64;
    ArithOutcome::ok(r, binary_flags(w, r, sum > w.mask(), exact))
}

/// `-`, `-L`, `-C`, `-CL`: `R := (a − b − bin) mod 2^bits`, CY = borrow.
fn sub(w: Width, a: u32, b: u32, bin: bool) -> ArithOutcome {
    let c = u64::from(bin);
    let (x, y) = (w.unsigned(a), w.unsigned(b) + c);
    let r = x.wrapping_sub(y) & w.mask();
    let exact = w.signed(a) - w.signed(b) - c as i64;
    ArithOutcome::ok(r, binary_flags(w, r, x < y, exact))
}

/// `+B`, `+BL`, `+BC`, `+BCL`: `R := (a + b + cin) mod 10^digits`, CY := the sum does not fit.
fn add_bcd(w: Width, a: u32, b: u32, cin: bool) -> ArithOutcome {
    let (Some(x), Some(y)) = (w.bcd(a), w.bcd(b)) else {
        return ArithOutcome::ERROR;
    };
    let sum = x + y + u64::from(cin);
    // Both operands are below the modulus, so the sum is below twice it.
    let carry = sum >= w.bcd_modulus();
    let r = if carry { sum - w.bcd_modulus() } else { sum };
    bcd_result(w, r, carry)
}

/// `-B`, `-BL`, `-BC`, `-BCL`: `a − b − bin` if not negative (CY OFF), else its ten's
/// complement `10^digits − (b + bin − a)` (CY ON).
fn sub_bcd(w: Width, a: u32, b: u32, bin: bool) -> ArithOutcome {
    let (Some(x), Some(y)) = (w.bcd(a), w.bcd(b)) else {
        return ArithOutcome::ERROR;
    };
    let y = y + u64::from(bin);
    if x >= y {
        bcd_result(w, x - y, false)
    } else {
        // y − x ≤ 10^digits, so the complement is 0 ..= 10^digits − 1.
        bcd_result(w, w.bcd_modulus() - (y - x), true)
    }
}

/// A BCD sum or difference `r` (below the modulus): ER OFF, CY, `=`.
fn bcd_result(w: Width, r: u64, carry: bool) -> ArithOutcome {
    let flags = FlagWrites::OK
        .write(Flag::Cy, carry)
        .write(Flag::Eq, r == 0);
    // `r` has the operands' digits, so the encoding of their width always succeeds.
    let bcd = if w.bits == 16 {
        bcd::bin_to_bcd16(r as u16).map(u64::from)
    } else {
        bcd::bin_to_bcd32(r as u32).map(u64::from)
    };
    ArithOutcome::ok(bcd.unwrap_or(0), flags)
}

/// A product of double width: ER OFF, `=` := it is 0, and (binary forms) N := its top bit.
fn product(w: Width, p: u64, binary: bool) -> ArithOutcome {
    let p = if w.bits == 16 { p & 0xFFFF_FFFF } else { p };
    let mut flags = FlagWrites::OK.write(Flag::Eq, p == 0);
    if binary {
        flags = flags.write(Flag::N, (p >> (2 * w.bits - 1)) & 1 != 0);
    }
    ArithOutcome::ok(p, flags)
}

/// `/`, `/L`: truncating division, the remainder with the dividend's sign (U13); the most
/// negative dividend over −1 stores the wrapped quotient (`#8000`) with remainder 0, no ER.
fn divide_signed(w: Width, a: u32, b: u32) -> ArithOutcome {
    let (x, y) = (w.signed(a), w.signed(b));
    if y == 0 {
        return ArithOutcome::ERROR;
    }
    // In i64 the 16- and 32-bit extremes (−2^31 / −1 = 2^31) cannot overflow.
    let (q, r) = (x / y, x % y);
    let q = q as u64 & w.mask();
    quotient(w, q, r as u64 & w.mask(), true)
}

/// Quotient `q` in `R` (`R:R+1` for 32 bits) and remainder `r` above it: ER OFF, `=` := the
/// quotient is 0, N := the quotient is negative (`signed`: its stored sign bit; else never).
fn quotient(w: Width, q: u64, r: u64, signed: bool) -> ArithOutcome {
    let negative = signed && (q >> (w.bits - 1)) & 1 != 0;
    let flags = FlagWrites::OK
        .write(Flag::Eq, q == 0)
        .write(Flag::N, negative);
    ArithOutcome::ok(q | r << w.bits, flags)
}

#[cfg(test)]
#[path = "arith_tests.rs"]
mod tests;
