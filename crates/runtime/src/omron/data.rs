//! Data movement and comparison (spec §3.5): MOV/MOVL, CMP/CMPL/CPS/CPSL and the comparison
//! contacts `LD=` … `LD>=` with their `L`/`S`/`SL` suffixes (§3.1).
//!
//! Values travel as raw bits, an `u32` whose low 16 bits are used for a one-word operand; a
//! double word is the Omron value (its low 16 bits are the lower-numbered word, spec §1.6).
//! A comparison contact's value and its flags come from the same [`compare`], so the contact
//! cannot disagree with the flag it leaves behind (U2's default: the six comparison flags set
//! as for CMP, ER OFF).

use super::flags::{Flag, FlagWrites, compare_writes};
use std::cmp::Ordering;
use stljit_core::ir::CmpOp;

/// The low `double ? 32 : 16` bits of `v`.
#[inline]
fn width_bits(double: bool, v: u32) -> u32 {
    if double { v } else { v & 0xFFFF }
}

/// `MOV(021)` (`double = false`) / `MOVL(498)`: the value to write (`src` cut to the width) and
/// the flags: ER OFF, `=` := value == 0, `N` := its most significant bit (bit 15 or 31).
pub fn mov(double: bool, src: u32) -> (u32, FlagWrites) {
    let v = width_bits(double, src);
    let msb = if double { 1 << 31 } else { 1 << 15 };
    let flags = FlagWrites::OK
        .write(Flag::Eq, v == 0)
        .write(Flag::N, v & msb != 0);
    (v, flags)
}

/// The order of `a` against `b` on the instruction's width and signedness.
pub fn ordering(double: bool, signed: bool, a: u32, b: u32) -> Ordering {
    match (double, signed) {
        (false, false) => (a as u16).cmp(&(b as u16)),
        (false, true) => (a as u16 as i16).cmp(&(b as u16 as i16)),
        (true, false) => a.cmp(&b),
        (true, true) => (a as i32).cmp(&(b as i32)),
    }
}

/// `CMP(020)` (unsigned 16), `CMPL(060)` (unsigned 32), `CPS(114)` (signed 16), `CPSL(115)`
/// (signed 32): the six comparison flags from `a` against `b`, ER OFF (spec §3.5).
pub fn compare(double: bool, signed: bool, a: u32, b: u32) -> FlagWrites {
    compare_writes(ordering(double, signed, a, b))
}

/// The flag that holds the outcome of relation `rel` after a comparison.
pub fn relation_flag(rel: CmpOp) -> Flag {
    match rel {
        CmpOp::Eq => Flag::Eq,
        CmpOp::Ne => Flag::Ne,
        CmpOp::Ge => Flag::Ge,
        CmpOp::Le => Flag::Le,
        CmpOp::Gt => Flag::Gt,
        CmpOp::Lt => Flag::Lt,
    }
}

/// A comparison contact `LD`/`AND`/`OR` + `rel` (`=` `<>` `<` `<=` `>` `>=`): no suffix is
/// unsigned 16 bit, `L` (`wide`) unsigned 32, `S` (`signed`) signed 16, `SL` signed 32
/// (spec §3.1). Returns the contact's value and its flags (U2: as [`compare`]).
pub fn compare_contact(rel: CmpOp, signed: bool, wide: bool, a: u32, b: u32) -> (bool, FlagWrites) {
    let flags = compare(wide, signed, a, b);
    (flags.sets(relation_flag(rel)), flags)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::omron::flags::CondFlags;

    #[test]
    fn mov_flags() {
        // §3.5 MOV: ER OFF, `=` := S == 0, N := bit 15 of S; §6.8 part C's `MOV #0000` sets `=`.
        let (v, f) = mov(false, 0x0000);
        assert_eq!(v, 0);
        assert_eq!(
            f,
            FlagWrites::OK.write(Flag::Eq, true).write(Flag::N, false)
        );
        // §6.10/§2.10 rule 5: `MOV #0200` clears `=`.
        assert!(!mov(false, 0x0200).1.sets(Flag::Eq));
        assert!(mov(false, 0x8000).1.sets(Flag::N));
        // Only the low word moves; the upper bits of the raw value do not count.
        assert_eq!(mov(false, 0x1_0000), (0, mov(false, 0).1));
        // MOVL: 32-bit zero and bit 31.
        assert!(!mov(true, 0x1_0000).1.sets(Flag::Eq));
        assert!(mov(true, 0x8000_0000).1.sets(Flag::N));
        assert!(!mov(true, 0x0000_8000).1.sets(Flag::N));
        // CY, OF and the comparison flags are not MOV's: unchanged.
        let before = CondFlags::from_bits(Flag::Cy.bit() | Flag::Gt.bit() | Flag::Er.bit());
        let after = mov(false, 5).1.apply(before);
        assert_eq!(after.bits(), Flag::Cy.bit() | Flag::Gt.bit());
    }

    #[test]
    fn compare_widths_and_signs() {
        // CMP is unsigned: #8000 > #7FFF; CPS signed: #8000 = -32768 < #7FFF.
        assert_eq!(ordering(false, false, 0x8000, 0x7FFF), Ordering::Greater);
        assert_eq!(ordering(false, true, 0x8000, 0x7FFF), Ordering::Less);
        // CMPL / CPSL on 32 bits.
        assert_eq!(ordering(true, false, 0xFFFF_FFFF, 0), Ordering::Greater);
        assert_eq!(ordering(true, true, 0xFFFF_FFFF, 0), Ordering::Less);
        assert_eq!(ordering(true, false, 0x1_0000, 0xFFFF), Ordering::Greater);
        // A 16-bit compare ignores the upper bits: 0x1_0005 and 5 are the same word.
        assert_eq!(ordering(false, false, 0x1_0005, 5), Ordering::Equal);
        // §6.8: CMP D100 #0010 with D100 = #0010 → `=` ON.
        assert!(compare(false, false, 0x10, 0x10).sets(Flag::Eq));
        assert_eq!(compare(false, false, 1, 2), compare_writes(Ordering::Less));
    }

    #[test]
    fn contacts() {
        use CmpOp::*;
        // §3.1's example `LD>=S D0 -5`: signed, D0 = -3 (#FFFD) ≥ -5 (#FFFB).
        let (v, f) = compare_contact(Ge, true, false, 0xFFFD, 0xFFFB);
        assert!(v);
        assert_eq!(f, compare(false, true, 0xFFFD, 0xFFFB));
        // No suffix is unsigned: #FFFD >= #FFFB as well, but #FFFD < 5 is false unsigned and
        // true signed.
        assert!(!compare_contact(Lt, false, false, 0xFFFD, 5).0);
        assert!(compare_contact(Lt, true, false, 0xFFFD, 5).0);
        // L: 32-bit unsigned; SL: 32-bit signed.
        assert!(compare_contact(Gt, false, true, 0x8000_0000, 1).0);
        assert!(!compare_contact(Gt, true, true, 0x8000_0000, 1).0);
        // Every relation against every order: the contact is the relation itself.
        for (a, b) in [(1, 2), (2, 2), (3, 2)] {
            for (rel, want) in [
                (Eq, a == b),
                (Ne, a != b),
                (Lt, a < b),
                (Le, a <= b),
                (Gt, a > b),
                (Ge, a >= b),
            ] {
                assert_eq!(
                    compare_contact(rel, false, false, a, b).0,
                    want,
                    "{a} {rel:?} {b}"
                );
            }
        }
    }
}
