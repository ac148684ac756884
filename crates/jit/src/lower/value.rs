//! Compile-time booleans and the symbolic logic stack.
//!
//! A boolean is kept lazily as "bit `pos` of an `i32` SSA value (or its complement), other bits
//! unspecified" so that a contact on bit 3 of a cached byte costs no instruction at all and an
//! `A` of two bits at the same position costs one `band`. Only a consumer that needs a clean 0/1 (a coil, a helper
//! argument, the stack register) pays for the shift and mask.
//!
//! The logic stack is exactly `depth` levels at every point, so a compile-time array of
//! booleans models push-loses-bottom and pop-fills-zero precisely; no depth analysis is needed.
//! At a basic-block boundary the array is packed into the `st` register (bit i = level i).

use cranelift_codegen::ir::{Function, InstBuilder, Opcode, Value, types::I32};
use cranelift_frontend::FunctionBuilder;

/// A boolean known at compile time or held in one bit of an SSA value, possibly negated.
///
/// The negated form makes `LDN`, `ON`, `AN` and `NOT` free: x86 has `andn` but no `orn`, and
/// by De Morgan every AND/OR of two bits of either polarity is one `and`, `or` or `andn` whose
/// result has some polarity; only a consumer that needs the plain bit pays for the `not`.
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
    /// The complement of bit `pos` of `v` (other bits garbage).
    Not {
        /// The value holding the complemented bit.
        v: Value,
        /// Which bit, 0..=31.
        pos: u8,
    },
}

/// Moves bit `from` of `v` to bit `to` (other bits garbage).
///
/// Emitted as a rotation, which [`settle_alignments`] turns into a shift where `v` has no
/// other use: only the one bit matters, so the two are interchangeable here (and only here;
/// the lowering emits no other rotation).
pub(crate) fn align(b: &mut FunctionBuilder<'_>, v: Value, from: u8, to: u8) -> Value {
    use std::cmp::Ordering::*;
    match from.cmp(&to) {
        Equal => v,
        Greater => b.ins().rotr_imm_s(v, i64::from(from - to)),
        Less => b.ins().rotl_imm_s(v, i64::from(to - from)),
    }
}

/// Chooses the instruction for every alignment of a finished function.
///
/// x86's `shl`/`shr` overwrite their operand, so shifting a value that is used again (a byte
/// tested twice, a stack level kept by `LPS`, an edge's power flow) costs a register copy
/// first; BMI2's `rorx` writes a third register instead. `rorx` is twice as long, though,
/// and a long straight-line program is limited by instruction fetch: rotations everywhere
/// made bitlogic_10k 7% slower than shifts. So a value used once is shifted, one used more
/// often is rotated.
pub(crate) fn settle_alignments(func: &mut Function) {
    use cranelift_codegen::entity::SecondaryMap;
    use cranelift_codegen::ir::InstructionData;
    let mut uses: SecondaryMap<Value, u32> = SecondaryMap::with_capacity(func.dfg.num_values());
    for block in func.layout.blocks() {
        for inst in func.layout.block_insts(block) {
            // Values passed to blocks are not counted: a miscount only costs a copy or a
            // longer instruction, never a different result.
            for &v in func.dfg.inst_args(inst) {
                uses[v] += 1;
            }
        }
    }
    let f = &mut func.stencil;
    for block in f.layout.blocks() {
        for inst in f.layout.block_insts(block) {
            let InstructionData::Binary { opcode, args } = &mut f.dfg.insts[inst] else {
                continue;
            };
            let used = |v: &Value| uses[*v];
            match *opcode {
                Opcode::Rotl if used(&args[0]) <= 1 => *opcode = Opcode::Ishl,
                Opcode::Rotr if used(&args[0]) <= 1 => *opcode = Opcode::Ushr,
                // The same for two-address `and`/`or`/`xor`: the first operand is the one
                // overwritten, so it should be the one that is not used again.
                Opcode::Band | Opcode::Bor | Opcode::Bxor
                    if used(&args[0]) > 1 && used(&args[1]) <= 1 =>
                {
                    args.swap(0, 1)
                }
                _ => {}
            }
        }
    }
}

/// A non-constant boolean as (value, bit, negated).
type Parts = (Value, u8, bool);

fn mk(v: Value, pos: u8, neg: bool) -> B {
    if neg {
        B::Not { v, pos }
    } else {
        B::Bit { v, pos }
    }
}

impl B {
    fn parts(self) -> Option<Parts> {
        match self {
            B::K(_) => None,
            B::Bit { v, pos } => Some((v, pos, false)),
            B::Not { v, pos } => Some((v, pos, true)),
        }
    }

    /// A clean 0/1 `i32`.
    pub(crate) fn to01(self, b: &mut FunctionBuilder<'_>) -> Value {
        self.at_bit(b, 0)
    }

    /// The boolean at bit `to` of an `i32` whose other bits are zero.
    pub(crate) fn at_bit(self, b: &mut FunctionBuilder<'_>, to: u8) -> Value {
        let m = 1i64 << to;
        match self {
            B::K(k) => b.ins().iconst(I32, if k { m } else { 0 }),
            B::Bit { v, pos } => {
                let s = align(b, v, pos, to);
                b.ins().band_imm_s(s, m)
            }
            B::Not { v, pos } => {
                let s = align(b, v, pos, to);
                let s = b.ins().band_imm_s(s, m);
                b.ins().bxor_imm_s(s, m)
            }
        }
    }

    /// An `i32` truth value for `brif`/`select` (non-zero = true).
    pub(crate) fn cond(self, b: &mut FunctionBuilder<'_>) -> Value {
        match self {
            B::K(k) => b.ins().iconst(I32, i64::from(k)),
            B::Bit { v, pos } => b.ins().band_imm_s(v, 1i64 << pos),
            B::Not { .. } => self.at_bit(b, 0),
        }
    }

    /// `self AND other`.
    pub(crate) fn and(self, b: &mut FunctionBuilder<'_>, o: B) -> B {
        self.and_toward(b, o, None)
    }

    /// `self AND other`, kept at bit `want` where an operand already is there (the position
    /// its consumer writes, `analysis::bit_targets`).
    pub(crate) fn and_toward(self, b: &mut FunctionBuilder<'_>, o: B, want: Option<u8>) -> B {
        match (self, o) {
            (B::K(false), _) | (_, B::K(false)) => B::K(false),
            (B::K(true), x) | (x, B::K(true)) => x,
            _ => {
                let (Some(x), Some(y)) = (self.parts(), o.parts()) else {
                    unreachable!("constants handled above")
                };
                and_parts(b, x, y, want)
            }
        }
    }

    /// `self OR other`.
    pub(crate) fn or(self, b: &mut FunctionBuilder<'_>, o: B) -> B {
        self.or_toward(b, o, None)
    }

    /// `self OR other`, kept at bit `want` like [`B::and_toward`].
    pub(crate) fn or_toward(self, b: &mut FunctionBuilder<'_>, o: B, want: Option<u8>) -> B {
        // De Morgan: a OR b = NOT (NOT a AND NOT b).
        self.neg().and_toward(b, o.neg(), want).neg()
    }

    /// `self AND NOT other`.
    pub(crate) fn and_not(self, b: &mut FunctionBuilder<'_>, o: B) -> B {
        self.and(b, o.neg())
    }

    /// `NOT self` (free: only the polarity changes).
    pub(crate) fn not(self, _b: &mut FunctionBuilder<'_>) -> B {
        self.neg()
    }

    fn neg(self) -> B {
        match self {
            B::K(k) => B::K(!k),
            B::Bit { v, pos } => B::Not { v, pos },
            B::Not { v, pos } => B::Bit { v, pos },
        }
    }
}

/// Whether `v` is `a AND NOT b` (one `andn`). The e-graph rewrites `NOT (a AND NOT b)` to
/// `NOT a OR b`, which it counts as cheaper but which costs x86 a `not` and an `or` where
/// `andn` of the original would have cost nothing extra, so such a value is not negated when
/// the other operand can be instead.
fn is_andn(b: &FunctionBuilder<'_>, v: Value) -> bool {
    let dfg = &b.func.dfg;
    let Some(inst) = dfg.value_def(v).inst() else {
        return false;
    };
    dfg.insts[inst].opcode() == Opcode::Band
        && dfg.inst_args(inst).iter().any(|&a| {
            dfg.value_def(a)
                .inst()
                .is_some_and(|i| dfg.insts[i].opcode() == Opcode::Bnot)
        })
}

/// Whether `v` is a plain load that the combining instruction can take as its memory operand:
/// `and`/`or` take either operand, `andn` only the one that is not complemented.
fn foldable(b: &FunctionBuilder<'_>, v: Value, neg: bool, other_neg: bool) -> bool {
    let dfg = &b.func.dfg;
    (neg == other_neg || !neg)
        && dfg
            .value_def(v)
            .inst()
            .is_some_and(|i| dfg.insts[i].opcode() == Opcode::Load)
}

/// `x AND y` for two non-constant booleans: one instruction, plus an alignment shift of the
/// operand not at bit `want` where the other is, else of `y`, or of `x` where only `y` is a
/// load that the instruction can fold.
fn and_parts(b: &mut FunctionBuilder<'_>, x: Parts, y: Parts, want: Option<u8>) -> B {
    let ((v, pos, nx), (w, q, ny)) = (x, y);
    if v == w && pos == q {
        // The same bit: x AND x = x, x AND NOT x = 0.
        return if nx == ny {
            mk(v, pos, nx)
        } else {
            B::K(false)
        };
    }
    // x86 folds a 32-bit load (a word contact, see `Lower::test_byte`) into the `and`, `or` or
    // `andn` that consumes it unshifted and not complemented, so the other operand moves.
    // Where both are foldable loads, the operand still folds: shifting the accumulator (one
    // load kept in a register) saves the operand's separate load.
    // An operand at the wanted bit stays there: the result's consumer then needs no
    // alignment, which saves an ALU operation where folding the load would only save a load.
    let (v, w, pos) = match want {
        Some(t) if q == t => (align(b, v, pos, q), w, q),
        Some(t) if pos == t => (v, align(b, w, q, pos), pos),
        _ if foldable(b, w, ny, nx) => (align(b, v, pos, q), w, q),
        _ => (v, align(b, w, q, pos), pos),
    };
    match (nx, ny) {
        (false, false) => mk(b.ins().band(v, w), pos, false),
        // v AND NOT w = NOT (NOT v OR w): see `is_andn`.
        (false, true) if is_andn(b, w) && !is_andn(b, v) => {
            let nv = b.ins().bnot(v);
            mk(b.ins().bor(nv, w), pos, true)
        }
        (false, true) => mk(b.ins().band_not(v, w), pos, false),
        (true, false) if is_andn(b, v) && !is_andn(b, w) => {
            let nw = b.ins().bnot(w);
            mk(b.ins().bor(v, nw), pos, true)
        }
        (true, false) => mk(b.ins().band_not(w, v), pos, false),
        // NOT v AND NOT w = NOT (v OR w)
        (true, true) => mk(b.ins().bor(v, w), pos, true),
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

    /// The stack with every level whose bit is clear in `live` replaced by 0.
    pub(crate) fn keeping(&self, live: u32) -> Stack {
        let lv = self
            .lv
            .iter()
            .enumerate()
            .map(|(i, &l)| if live & (1 << i) != 0 { l } else { B::K(false) })
            .collect();
        Stack { lv }
    }

    /// Packs the levels into one `i32` register value (bit i = level i). Levels that came from
    /// the same source value with the same bit distance share one shift and one mask, so an
    /// unchanged or uniformly pushed stack costs two or three instructions.
    pub(crate) fn to_reg(&self, b: &mut FunctionBuilder<'_>) -> Value {
        let mut konst: i64 = 0;
        // Target bits of negated levels: packed as their plain bit, then flipped with one
        // `xor` for all of them.
        let mut negs: i64 = 0;
        // (source value, shift = target - pos) -> mask of target bits
        let mut groups: Vec<(Value, i32, i64)> = Vec::new();
        for (i, l) in self.lv.iter().enumerate() {
            let (v, pos) = match *l {
                B::K(true) => {
                    konst |= 1 << i;
                    continue;
                }
                B::K(false) => continue,
                B::Bit { v, pos } => (v, pos),
                B::Not { v, pos } => {
                    negs |= 1 << i;
                    (v, pos)
                }
            };
            let sh = i as i32 - i32::from(pos);
            match groups.iter_mut().find(|g| g.0 == v && g.1 == sh) {
                Some(g) => g.2 |= 1 << i,
                None => groups.push((v, sh, 1 << i)),
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
        // Constant bits and negated bits are disjoint, so one `xor` sets both.
        let flip = konst | negs;
        match acc {
            None => b.ins().iconst(I32, konst),
            Some(a) if flip != 0 => b.ins().bxor_imm_s(a, flip),
            Some(a) => a,
        }
    }
}
