//! Compile-time booleans and the symbolic logic stack.
//!
//! A boolean is kept lazily as "bit `pos` of an `i32` SSA value, other bits unspecified" so that a
//! contact on bit 3 of a cached byte costs no instruction at all and an `A` of two bits at the
//! same position costs one `band`. Only a consumer that needs a clean 0/1 (a coil, a helper
//! argument, the stack register) pays for the shift and mask.
//!
//! The logic stack is exactly `depth` levels at every point, so a compile-time array of
//! booleans models push-loses-bottom and pop-fills-zero precisely; no depth analysis is needed.
//! At a basic-block boundary the array is packed into the `st` register (bit i = level i).

use cranelift_codegen::ir::{InstBuilder, Value, types::I32};
use cranelift_frontend::FunctionBuilder;

/// A boolean known at compile time or held in one bit of an SSA value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum B {
    /// A constant.
    K(bool),
    /// Bit `pos` of `v` (an `i32`); the other bits are garbage.
    Bit {
        /// The value holding the bit.
        v: Value,
        /// Which bit, 0..=31.
        pos: u8,
    },
}

/// Moves bit `from` of `v` to bit `to` (other bits garbage).
pub(crate) fn align(b: &mut FunctionBuilder<'_>, v: Value, from: u8, to: u8) -> Value {
    use std::cmp::Ordering::*;
    match from.cmp(&to) {
        Equal => v,
        Greater => b.ins().ushr_imm_s(v, i64::from(from - to)),
        Less => b.ins().ishl_imm_s(v, i64::from(to - from)),
    }
}

impl B {
    /// A clean 0/1 `i32`.
    pub(crate) fn to01(self, b: &mut FunctionBuilder<'_>) -> Value {
        match self {
            B::K(k) => b.ins().iconst(I32, i64::from(k)),
            B::Bit { v, pos } => {
                let s = align(b, v, pos, 0);
                b.ins().band_imm_s(s, 1)
            }
        }
    }

    /// The boolean at bit `to` of an `i32` whose other bits are zero.
    pub(crate) fn at_bit(self, b: &mut FunctionBuilder<'_>, to: u8) -> Value {
        match self {
            B::K(k) => b.ins().iconst(I32, if k { 1i64 << to } else { 0 }),
            B::Bit { v, pos } => {
                let s = align(b, v, pos, to);
                b.ins().band_imm_s(s, 1i64 << to)
            }
        }
    }

    /// An `i8` truth value for `brif` (non-zero = true).
    pub(crate) fn cond(self, b: &mut FunctionBuilder<'_>) -> Value {
        match self {
            B::K(k) => b.ins().iconst(I32, i64::from(k)),
            B::Bit { v, pos } => b.ins().band_imm_s(v, 1i64 << pos),
        }
    }

    /// `self AND other`.
    pub(crate) fn and(self, b: &mut FunctionBuilder<'_>, o: B) -> B {
        match (self, o) {
            (B::K(false), _) | (_, B::K(false)) => B::K(false),
            (B::K(true), x) | (x, B::K(true)) => x,
            (B::Bit { v, pos }, B::Bit { v: w, pos: q }) => {
                if v == w && pos == q {
                    return self;
                }
                let w = align(b, w, q, pos);
                B::Bit {
                    v: b.ins().band(v, w),
                    pos,
                }
            }
        }
    }

    /// `self OR other`.
    pub(crate) fn or(self, b: &mut FunctionBuilder<'_>, o: B) -> B {
        match (self, o) {
            (B::K(true), _) | (_, B::K(true)) => B::K(true),
            (B::K(false), x) | (x, B::K(false)) => x,
            (B::Bit { v, pos }, B::Bit { v: w, pos: q }) => {
                if v == w && pos == q {
                    return self;
                }
                let w = align(b, w, q, pos);
                B::Bit {
                    v: b.ins().bor(v, w),
                    pos,
                }
            }
        }
    }

    /// `self AND NOT other` (one `band_not`).
    pub(crate) fn and_not(self, b: &mut FunctionBuilder<'_>, o: B) -> B {
        match (self, o) {
            (B::K(false), _) | (_, B::K(true)) => B::K(false),
            (x, B::K(false)) => x,
            (B::K(true), x) => x.not(b),
            (B::Bit { v, pos }, B::Bit { v: w, pos: q }) => {
                let w = align(b, w, q, pos);
                B::Bit {
                    v: b.ins().band_not(v, w),
                    pos,
                }
            }
        }
    }

    /// `self OR NOT other`.
    pub(crate) fn or_not(self, b: &mut FunctionBuilder<'_>, o: B) -> B {
        match (self, o) {
            (B::K(true), _) | (_, B::K(false)) => B::K(true),
            (x, B::K(true)) => x,
            (B::K(false), x) => x.not(b),
            (B::Bit { v, pos }, B::Bit { v: w, pos: q }) => {
                let w = align(b, w, q, pos);
                B::Bit {
                    v: b.ins().bor_not(v, w),
                    pos,
                }
            }
        }
    }

    /// `NOT self`.
    pub(crate) fn not(self, b: &mut FunctionBuilder<'_>) -> B {
        match self {
            B::K(k) => B::K(!k),
            B::Bit { v, pos } => B::Bit {
                v: b.ins().bnot(v),
                pos,
            },
        }
    }
}

/// The logic stack as compile-time booleans; `lv[0]` is `S0`.
#[derive(Clone, Debug)]
pub(crate) struct Stack {
    pub(crate) lv: Vec<B>,
}

impl Stack {
    /// The stack unpacked from the register value `st`.
    pub(crate) fn from_reg(st: Value, depth: u8) -> Stack {
        Stack {
            lv: (0..depth).map(|i| B::Bit { v: st, pos: i }).collect(),
        }
    }

    /// The stack a subroutine starts with: `S0 = 1`, the rest 0.
    pub(crate) fn fresh(depth: u8) -> Stack {
        let mut lv = vec![B::K(false); usize::from(depth)];
        if let Some(top) = lv.first_mut() {
            *top = B::K(true);
        }
        Stack { lv }
    }

    /// `S0`.
    pub(crate) fn top(&self) -> B {
        self.lv.first().copied().unwrap_or(B::K(false))
    }

    /// Level `n` (0 past the bottom).
    pub(crate) fn level(&self, n: usize) -> B {
        self.lv.get(n).copied().unwrap_or(B::K(false))
    }

    /// Replaces `S0`.
    pub(crate) fn set_top(&mut self, v: B) {
        if let Some(t) = self.lv.first_mut() {
            *t = v;
        }
    }

    /// Push: every level moves down, the bottom is lost.
    pub(crate) fn push(&mut self, v: B) {
        if self.lv.is_empty() {
            return;
        }
        self.lv.pop();
        self.lv.insert(0, v);
    }

    /// Pop: every level moves up, the bottom fills with 0.
    pub(crate) fn pop(&mut self) -> B {
        if self.lv.is_empty() {
            return B::K(false);
        }
        let t = self.lv.remove(0);
        self.lv.push(B::K(false));
        t
    }

    /// Packs the levels into one `i32` register value (bit i = level i). Levels that came from
    /// the same source value with the same bit distance share one shift and one mask, so an
    /// unchanged or uniformly pushed stack costs two or three instructions.
    pub(crate) fn to_reg(&self, b: &mut FunctionBuilder<'_>) -> Value {
        let mut konst: i64 = 0;
        // (source value, shift = target - pos) -> mask of target bits
        let mut groups: Vec<(Value, i32, i64)> = Vec::new();
        for (i, l) in self.lv.iter().enumerate() {
            match *l {
                B::K(true) => konst |= 1 << i,
                B::K(false) => {}
                B::Bit { v, pos } => {
                    let sh = i as i32 - i32::from(pos);
                    match groups.iter_mut().find(|g| g.0 == v && g.1 == sh) {
                        Some(g) => g.2 |= 1 << i,
                        None => groups.push((v, sh, 1 << i)),
                    }
                }
            }
        }
        let mut acc: Option<Value> = None;
        for (v, sh, mask) in groups {
            let s = match sh {
                0 => v,
                s if s > 0 => b.ins().ishl_imm_s(v, i64::from(s)),
                s => b.ins().ushr_imm_s(v, i64::from(-s)),
            };
            let m = b.ins().band_imm_s(s, mask);
            acc = Some(match acc {
                None => m,
                Some(a) => b.ins().bor(a, m),
            });
        }
        match acc {
            None => b.ins().iconst(I32, konst),
            Some(a) if konst != 0 => b.ins().bor_imm_s(a, konst),
            Some(a) => a,
        }
    }
}
