//! The checks [`crate::Interpreter::new`] makes so that execution can follow every reference in
//! the IR without a failing lookup. A front end's checked program always passes.

use std::fmt;
use stljit_core::ir::{Op, Program};

/// Why a program cannot be interpreted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum InterpError {
    /// The program has no POU (the main program is missing).
    NoMain,
    /// `logic_stack_depth` is 0 or above 16 (the stack is a `u16`).
    StackDepth(u8),
    /// A reference in op `op` of POU `pou` points nowhere.
    BadReference {
        /// POU index.
        pou: usize,
        /// Op index.
        op: usize,
        /// What is wrong.
        what: &'static str,
    },
}

impl fmt::Display for InterpError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InterpError::NoMain => f.write_str("program has no main POU"),
            InterpError::StackDepth(d) => write!(f, "logic stack depth {d} not in 1..=16"),
            InterpError::BadReference { pou, op, what } => {
                write!(f, "pou{pou} op{op}: {what}")
            }
        }
    }
}

impl std::error::Error for InterpError {}

/// Checks every cross-reference of `program`.
pub(crate) fn check(program: &Program) -> Result<(), InterpError> {
    if program.pous.is_empty() {
        return Err(InterpError::NoMain);
    }
    if !(1..=16).contains(&program.logic_stack_depth) {
        return Err(InterpError::StackDepth(program.logic_stack_depth));
    }
    for (p, pou) in program.pous.iter().enumerate() {
        let n = pou.ops.len();
        let bad = |op, what| Err(InterpError::BadReference { pou: p, op, what });
        for (label, at) in pou.labels.iter().enumerate() {
            let ok = matches!(pou.ops.get(at.index()), Some(Op::Label(l)) if l.index() == label);
            if !ok {
                return bad(at.index(), "label position does not hold its LBL");
            }
        }
        for (i, op) in pou.ops.iter().enumerate() {
            match op {
                Op::Jump(l) if l.index() >= pou.labels.len() => return bad(i, "unknown label"),
                Op::Call(c) if c.index() >= program.pous.len() || c.index() == 0 => {
                    return bad(i, "call of an unknown POU or of main");
                }
                Op::For { next, .. } => {
                    let ok = matches!(pou.ops.get(next.index()), Some(Op::Next { head }) if head.index() == i);
                    if !ok {
                        return bad(i, "FOR without its NEXT");
                    }
                }
                Op::Next { head } => {
                    let ok = matches!(pou.ops.get(head.index()), Some(Op::For { next, .. }) if next.index() == i);
                    if !ok {
                        return bad(i, "NEXT without its FOR");
                    }
                }
                Op::ScrCondEnd { end } if !matches!(pou.ops.get(end.index()), Some(Op::ScrEnd)) => {
                    return bad(i, "CSCRE without its SCRE");
                }
                _ if n > u32::MAX as usize => return bad(i, "POU too long"),
                _ => {}
            }
        }
    }
    Ok(())
}
