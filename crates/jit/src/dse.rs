//! Dead-store elimination within a basic block, run on each lowered function before Cranelift
//! compiles it (Cranelift has no such pass).
//!
//! Lowering stores every write at once (see [`crate::lower::cache`]), so a byte written twice
//! in one block is stored twice. Most such stores are bookkeeping that the next box overwrites:
//! every box stores ENO and most store SMB1, and a box is usually followed by another one in
//! the same block long before anything loads those bytes (`AENO` and the next box take them
//! from the byte cache, not from memory). Removing the earlier store also lets Cranelift drop
//! the computation of a value nobody reads any more (an ENO without an `AENO`, the flags of a
//! box whose SMB1 the next box of a chain derives anew: `lower::cache::FlagsChain`).
//!
//! **Rule.** Walking a block backwards, a byte is *covered* when a later store of the same
//! block writes it and nothing between that store and the current point may read it. A store
//! all of whose bytes are covered is removed. Addresses are compared as *root value + constant
//! offset* (the root being what remains after peeling `iadd` of constants); bytes of one root
//! never alias another root's as far as this pass knows, so a load from one root uncovers the
//! bytes of every other root, and anything else that may read memory (a call, an unrecognised
//! load, a trapping or side-effecting instruction) uncovers everything. A block's end uncovers
//! everything too: its successors, the caller and the scan loop see memory there. So the pass
//! only ever removes a store whose bytes are certainly stored again, unread, later in the same
//! block, which leaves memory identical at every point where anything can observe it.

use cranelift_codegen::ir::{
    Function, Inst, InstructionData, Opcode, Value, ValueDef, immediates::Offset32,
};
use std::collections::{HashMap, HashSet};

/// Root value and byte offset of a memory access's first byte.
type Place = (Value, i64);

/// Peels `iadd` of constants off an address; at most a few levels, which is
/// all lowering ever emits.
fn root_of(func: &Function, mut v: Value, offset: Offset32) -> Place {
    // Wrapping, as the machine's address arithmetic: no constant can make this panic.
    let mut off = i64::from(offset);
    for _ in 0..4 {
        let ValueDef::Result(inst, 0) = func.dfg.value_def(v) else {
            break;
        };
        match func.dfg.insts[inst] {
            InstructionData::Binary {
                opcode: Opcode::Iadd,
                args: [a, b],
            } => match (iconst(func, a), iconst(func, b)) {
                (_, Some(c)) => {
                    off = off.wrapping_add(c);
                    v = a;
                }
                (Some(c), None) => {
                    off = off.wrapping_add(c);
                    v = b;
                }
                (None, None) => break,
            },
            _ => break,
        }
    }
    (v, off)
}

/// The immediate of the `iconst` that defines `v`, if one does.
pub(crate) fn iconst(func: &Function, v: Value) -> Option<i64> {
    let ValueDef::Result(inst, 0) = func.dfg.value_def(v) else {
        return None;
    };
    match func.dfg.insts[inst] {
        InstructionData::UnaryImm {
            opcode: Opcode::Iconst,
            imm,
        } => Some(imm.bits()),
        _ => None,
    }
}

/// The bytes a plain scalar load or store accesses, or `None` for anything else (vector and
/// atomic accesses included).
fn access_bytes(func: &Function, inst: Inst, opcode: Opcode) -> Option<u32> {
    let ty = match func.dfg.insts[inst] {
        InstructionData::Store { args, .. } => func.dfg.value_type(args[0]),
        _ => func.dfg.value_type(func.dfg.first_result(inst)),
    };
    if ty.is_vector() {
        return None;
    }
    Some(match opcode {
        Opcode::Uload8 | Opcode::Sload8 | Opcode::Istore8 => 1,
        Opcode::Uload16 | Opcode::Sload16 | Opcode::Istore16 => 2,
        Opcode::Uload32 | Opcode::Sload32 | Opcode::Istore32 => 4,
        Opcode::Load | Opcode::Store => ty.bytes(),
        _ => return None,
    })
}

/// The covered bytes (module docs), by root; nearly every access has the image as its root.
#[derive(Default)]
struct Covered(HashMap<Value, HashSet<i64>>);

/// The `n` byte addresses from `off`, wrapping like the machine's address arithmetic (a range
/// `off..off + n` could overflow, or wrap to an empty range that would cover nothing yet
/// make every store look dead).
fn bytes(off: i64, n: u32) -> impl Iterator<Item = i64> + Clone {
    (0..i64::from(n)).map(move |i| off.wrapping_add(i))
}

impl Covered {
    /// Whether all `n` bytes from `off` of `root` are covered.
    fn all(&self, (root, off): Place, n: u32) -> bool {
        self.0
            .get(&root)
            .is_some_and(|s| bytes(off, n).all(|b| s.contains(&b)))
    }

    /// A store of `n` bytes from `off` of `root`.
    fn stored(&mut self, (root, off): Place, n: u32) {
        self.0.entry(root).or_default().extend(bytes(off, n));
    }

    /// A load of `n` bytes from `off` of `root`: those bytes and every other root's are read
    /// (or may be).
    fn loaded(&mut self, (root, off): Place, n: u32) {
        self.0.retain(|&r, _| r == root);
        if let Some(s) = self.0.get_mut(&root) {
            for b in bytes(off, n) {
                s.remove(&b);
            }
        }
    }
}

/// Removes the dead stores of every block of `func` (module docs); returns how many.
pub(crate) fn remove_dead_stores(func: &mut Function) -> usize {
    let mut dead = Vec::new();
    let blocks: Vec<_> = func.layout.blocks().collect();
    for block in blocks {
        let mut covered = Covered::default();
        let mut at = func.layout.last_inst(block);
        while let Some(inst) = at {
            at = func.layout.prev_inst(inst);
            visit(func, inst, &mut covered, &mut dead);
        }
    }
    let n = dead.len();
    for inst in dead {
        func.layout.remove_inst(inst);
    }
    n
}

/// One instruction of the backward walk.
fn visit(func: &Function, inst: Inst, covered: &mut Covered, dead: &mut Vec<Inst>) {
    let data = func.dfg.insts[inst];
    let opcode = data.opcode();
    match data {
        InstructionData::Store {
            args: [_, addr],
            offset,
            ..
        } => match access_bytes(func, inst, opcode) {
            Some(n) => {
                let place = root_of(func, addr, offset);
                if covered.all(place, n) {
                    dead.push(inst);
                } else {
                    covered.stored(place, n);
                }
            }
            // Not a plain store: treated as something that may read, to stay simple.
            None => covered.0.clear(),
        },
        InstructionData::Load { arg, offset, .. } => match access_bytes(func, inst, opcode) {
            Some(n) => covered.loaded(root_of(func, arg, offset), n),
            None => covered.0.clear(),
        },
        _ => {
            if opcode.can_load()
                || opcode.is_call()
                || opcode.can_trap()
                || opcode.other_side_effects()
                || opcode.is_terminator()
                || opcode.is_branch()
            {
                covered.0.clear();
            }
        }
    }
}

#[cfg(test)]
#[path = "dse_tests.rs"]
mod tests;
