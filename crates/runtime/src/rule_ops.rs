//! The operations the timer and counter rules are written in, so that one text of each rule
//! serves both engines.
//!
//! [`crate::timer::timer_rule`] and [`crate::counter::counter_rule`] are generic over
//! [`RuleOps`]: with [`Native`] they compute on plain integers (the interpreter, through
//! [`crate::timer::Timer::step`] and [`crate::counter::Counter::step`]); the JIT implements
//! the same trait by emitting Cranelift instructions, so a timer or counter in compiled code
//! is the rule itself, not a second copy of it. A rule written here cannot branch on a run-time value:
//! every decision is a [`RuleOps::select`], which is also what the rules want (the inputs
//! follow the plant from scan to scan, so a branch on them is mispredicted about half the time;
//! docs/performance.md).
//!
//! Values are 64-bit signed integers. Booleans are 0 or 1 and only ever combined with
//! [`RuleOps::and`], [`RuleOps::or`] and [`RuleOps::not`]; the comparisons return them.

/// The integer operations of the timer and counter rules (module docs).
pub trait RuleOps {
    /// A value: an `i64`, or something that computes one.
    type V: Copy;
    /// The constant `v`.
    fn k(&mut self, v: i64) -> Self::V;
    /// `a & b` of two booleans.
    fn and(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a | b` of two booleans.
    fn or(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `!a` of a boolean.
    fn not(&mut self, a: Self::V) -> Self::V;
    /// `a + b` (the rules keep every sum far inside `i64`).
    fn add(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a - b`.
    fn sub(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// The smaller of `a` and `b` (signed).
    fn min(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a == b` as a boolean.
    fn eq(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a >= b` (signed) as a boolean.
    fn ge(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a > b` (signed) as a boolean.
    fn gt(&mut self, a: Self::V, b: Self::V) -> Self::V;
    /// `a != 0` as a boolean (a byte that stores a flag).
    fn ne0(&mut self, a: Self::V) -> Self::V;
    /// `a & 1`: bit 0 of `a` as a boolean (a byte whose bit 0 is the flag).
    fn bit0(&mut self, a: Self::V) -> Self::V;
    /// The low 16 bits of `a`, sign-extended (an `i16` that wraps).
    fn wrap16(&mut self, a: Self::V) -> Self::V;
    /// `c ? a : b` for a boolean `c`, without a branch.
    fn select(&mut self, c: Self::V, a: Self::V, b: Self::V) -> Self::V;

    /// `a < b` (signed) as a boolean.
    fn lt(&mut self, a: Self::V, b: Self::V) -> Self::V {
        self.gt(b, a)
    }
    /// `min(a + d, 32767)`: the saturating count-up of a timer's current value (spec §5 `sat`).
    fn sat_add(&mut self, a: Self::V, d: Self::V) -> Self::V {
        let sum = self.add(a, d);
        let max = self.k(i64::from(i16::MAX));
        self.min(sum, max)
    }
}

/// [`RuleOps`] on plain `i64`s: the rules as the interpreter runs them.
#[derive(Clone, Copy, Debug, Default)]
pub struct Native;

impl RuleOps for Native {
    type V = i64;

    #[inline(always)]
    fn k(&mut self, v: i64) -> i64 {
        v
    }
    #[inline(always)]
    fn and(&mut self, a: i64, b: i64) -> i64 {
        a & b
    }
    #[inline(always)]
    fn or(&mut self, a: i64, b: i64) -> i64 {
        a | b
    }
    #[inline(always)]
    fn not(&mut self, a: i64) -> i64 {
        a ^ 1
    }
    #[inline(always)]
    fn add(&mut self, a: i64, b: i64) -> i64 {
        a.wrapping_add(b)
    }
    #[inline(always)]
    fn sub(&mut self, a: i64, b: i64) -> i64 {
        a.wrapping_sub(b)
    }
    #[inline(always)]
    fn min(&mut self, a: i64, b: i64) -> i64 {
        a.min(b)
    }
    #[inline(always)]
    fn eq(&mut self, a: i64, b: i64) -> i64 {
        i64::from(a == b)
    }
    #[inline(always)]
    fn ge(&mut self, a: i64, b: i64) -> i64 {
        i64::from(a >= b)
    }
    #[inline(always)]
    fn gt(&mut self, a: i64, b: i64) -> i64 {
        i64::from(a > b)
    }
    #[inline(always)]
    fn ne0(&mut self, a: i64) -> i64 {
        i64::from(a != 0)
    }
    #[inline(always)]
    fn bit0(&mut self, a: i64) -> i64 {
        a & 1
    }
    #[inline(always)]
    fn wrap16(&mut self, a: i64) -> i64 {
        i64::from(a as i16)
    }
    #[inline(always)]
    fn select(&mut self, c: i64, a: i64, b: i64) -> i64 {
        std::hint::select_unpredictable(c != 0, a, b)
    }
}

#[cfg(test)]
#[path = "rule_ops_tests.rs"]
pub(crate) mod spec_rows;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn native_ops() {
        let o = &mut Native;
        assert_eq!(o.sat_add(32760, 100), 32767);
        assert_eq!(o.sat_add(-5, 3), -2);
        assert_eq!(o.wrap16(32768), -32768);
        assert_eq!(o.lt(-1, 0), 1);
        assert_eq!(o.select(1, 7, 9), 7);
        assert_eq!(o.select(0, 7, 9), 9);
        assert_eq!((o.not(1), o.not(0), o.ne0(200), o.bit0(6)), (0, 1, 1, 0));
    }
}
