//! The `!` refresh boxes read back: a `!` instruction lowers to its own ops with
//! `Box(ImmediateRead)` before it (one per input byte) and `Box(ImmediateWrite)` after it (one
//! per output byte), either bare (SET, RSET and the data instructions: on their power flow) or
//! on a pushed `P_On` (`Load(P_On); …; Pop`: contacts, OUT, OUT NOT, KEEP, in every cycle).
//! Which bytes an instruction refreshes is `crate::immediate`'s (the lowering's) answer; the
//! printer writes `!` where the boxes are exactly those.

use stljit_core::Area;
use stljit_core::ir::{BoxOp, Contact, Loc, Op, Operand};
use stljit_core::omron::SystemBit;

/// Which way a refresh box copies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Dir {
    /// Physical input byte → image (`ImmediateRead`).
    Read,
    /// Image → physical output byte (`ImmediateWrite`).
    Write,
}

/// `Load(P_On)`: the push of FOR, of the comparison contacts, of the every-cycle refresh and of
/// the step area's saved gate.
pub(super) fn load_on() -> Op {
    Op::Load(Contact::Bit {
        bit: SystemBit::On.bit_loc(),
        negated: false,
    })
}

/// The byte a refresh box of direction `dir` copies, if `op` is one as the lowering writes it.
fn byte(op: &Op, dir: Dir) -> Option<u32> {
    match (op, dir) {
        (
            Op::Box(BoxOp::ImmediateRead {
                input,
                dst:
                    Operand::Mem(Loc {
                        area: Area::I,
                        offset,
                    }),
            }),
            Dir::Read,
        ) if offset == input => Some(*input),
        (
            Op::Box(BoxOp::ImmediateWrite {
                src:
                    Operand::Mem(Loc {
                        area: Area::Q,
                        offset,
                    }),
                output,
            }),
            Dir::Write,
        ) if offset == output => Some(*output),
        _ => None,
    }
}

/// The bytes of the run of refresh boxes of direction `dir` starting at `j` (empty if none).
pub(super) fn boxes(ops: &[Op], j: usize, dir: Dir) -> Vec<u32> {
    let mut bytes = Vec::new();
    while let Some(b) = ops.get(j + bytes.len()).and_then(|op| byte(op, dir)) {
        bytes.push(b);
    }
    bytes
}

/// The every-cycle refresh at `j` (`Load(P_On)`, boxes of direction `dir`, `Pop`): its bytes
/// and how many ops it takes.
pub(super) fn always(ops: &[Op], j: usize, dir: Dir) -> Option<(Vec<u32>, usize)> {
    if ops.get(j) != Some(&load_on()) {
        return None;
    }
    let bytes = boxes(ops, j + 1, dir);
    let n = bytes.len();
    (n > 0 && ops.get(j + 1 + n) == Some(&Op::Pop)).then_some((bytes, n + 2))
}

/// `Ok` when the boxes found are the ones the instruction refreshes.
pub(super) fn check(found: &[u32], expected: &[u32]) -> Result<(), String> {
    if found == expected {
        Ok(())
    } else {
        Err(format!(
            "refresh boxes of bytes {found:?} where `!` refreshes {expected:?}"
        ))
    }
}
