//! Static facts the lowering relies on: basic-block leaders and where the SCR gate is provably 1.
//!
//! **Leaders** are the ops where control may arrive from somewhere other than the previous op:
//! labels, FOR bodies and the ops after NEXT, SCRE (the target of CSCRE), and every op after a
//! branch. Between two leaders the lowering keeps the logic stack and image bytes in SSA values.
//!
//! **Gate.** Power flow is `S0 AND gate`; outside SCR segments the gate is 1, and knowing that
//! at compile time removes a load and an AND from every coil. A forward dataflow over each POU
//! computes, per op, whether the gate is 1 on every path reaching it. A POU is entered only by
//! a CALL that ran, i.e. with PF = 1 and hence gate = 1; a CALL leaves the gate at 1 when the
//! callee provably returns with gate 1 (computed as a greatest fixpoint over all POUs, which is
//! sound because call nesting is bounded).

use stljit_core::ir::{Op, Pou, Program};

/// Facts about one POU.
#[derive(Clone, Debug)]
pub(crate) struct PouInfo {
    /// `leader[i]`: a basic block starts at op `i`.
    pub(crate) leader: Vec<bool>,
    /// `gate_one[i]`: the gate is 1 whenever op `i` starts (true for unreachable ops).
    pub(crate) gate_one: Vec<bool>,
    /// Every return of the POU happens with gate 1.
    pub(crate) exits_one: bool,
}

/// Successor op indices of op `i` (`n` = the end of the POU, an exit).
fn successors(pou: &Pou, i: usize, out: &mut Vec<usize>) {
    out.clear();
    let n = pou.ops.len();
    let fall = i + 1;
    match &pou.ops[i] {
        Op::Jump(l) => {
            out.push(fall);
            out.push(pou.label_target(*l).index().min(n));
        }
        Op::Return { conditional } | Op::End { conditional } => {
            if *conditional {
                out.push(fall);
            }
        }
        Op::For { next, .. } => {
            out.push(fall);
            out.push((next.index() + 1).min(n));
        }
        Op::Next { head } => {
            out.push(fall);
            out.push((head.index() + 1).min(n));
        }
        Op::ScrCondEnd { end } => {
            out.push(fall);
            out.push(end.index().min(n));
        }
        _ => out.push(fall),
    }
}

/// Whether a label or loop target is inside the POU (the front end guarantees it; a malformed
/// program is rejected by [`crate::JitError::Malformed`] rather than miscompiled).
pub(crate) fn check_targets(prog: &Program) -> Result<(), String> {
    for (p, pou) in prog.pous.iter().enumerate() {
        let n = pou.ops.len();
        for (i, op) in pou.ops.iter().enumerate() {
            let bad = match op {
                Op::Jump(l) => pou.labels.get(l.index()).is_none_or(|t| t.index() >= n),
                Op::For { next, .. } => !matches!(pou.ops.get(next.index()), Some(Op::Next { .. })),
                Op::Next { head } => !matches!(pou.ops.get(head.index()), Some(Op::For { .. })),
                Op::ScrCondEnd { end } => !matches!(pou.ops.get(end.index()), Some(Op::ScrEnd)),
                Op::Call(c) => c.index() >= prog.pous.len() || c.index() == 0,
                _ => false,
            };
            if bad {
                return Err(format!("POU {p} op {i}: control target out of range"));
            }
        }
    }
    Ok(())
}

fn leaders(pou: &Pou) -> Vec<bool> {
    let n = pou.ops.len();
    let mut lead = vec![false; n + 1];
    if n > 0 {
        lead[0] = true;
    }
    let mut succ = Vec::new();
    for i in 0..n {
        successors(pou, i, &mut succ);
        let branches = !matches!(succ.as_slice(), [s] if *s == i + 1);
        if branches {
            for &s in &succ {
                lead[s] = true;
            }
            lead[i + 1] = true;
        }
        if matches!(pou.ops[i], Op::Label(_)) {
            lead[i] = true;
        }
    }
    // Very long straight-line code is cut into blocks of at most MAX_BLOCK ops: register
    // allocation time grows faster than linearly with the values live across one block, and
    // the cut costs only the write-back of the stack register and the dirty bytes.
    let mut since = 0;
    for l in lead.iter_mut().take(n) {
        if *l {
            since = 0;
        } else {
            since += 1;
            if since >= MAX_BLOCK {
                *l = true;
                since = 0;
            }
        }
    }
    lead.truncate(n);
    lead
}

/// Longest run of ops lowered as one basic block.
pub(crate) const MAX_BLOCK: usize = 128;

/// Forward dataflow of "gate is 1"; returns per-op facts and whether all exits have gate 1.
fn gate_flow(pou: &Pou, exits_one: &[bool]) -> (Vec<bool>, bool) {
    let n = pou.ops.len();
    // None = not reached yet; Some(true) = gate 1 on all paths so far.
    let mut state: Vec<Option<bool>> = vec![None; n + 1];
    state[0] = Some(true);
    let mut work = vec![0usize];
    let mut succ = Vec::new();
    let mut exit_ok = true;
    while let Some(i) = work.pop() {
        if i >= n {
            continue;
        }
        let Some(inp) = state[i] else { continue };
        let out = match &pou.ops[i] {
            Op::ScrBegin { .. } => false,
            Op::ScrEnd => true,
            Op::Call(p) => inp && exits_one.get(p.index()).copied().unwrap_or(false),
            _ => inp,
        };
        if matches!(pou.ops[i], Op::Return { .. } | Op::End { .. }) && !out {
            exit_ok = false;
        }
        successors(pou, i, &mut succ);
        for &s in &succ {
            let new = match state[s] {
                None => Some(out),
                Some(old) => Some(old && out),
            };
            if new != state[s] {
                state[s] = new;
                work.push(s);
            }
        }
    }
    if state[n] == Some(false) {
        exit_ok = false;
    }
    let facts = state[..n].iter().map(|s| s.unwrap_or(true)).collect();
    (facts, exit_ok)
}

/// Computes the facts for every POU.
pub(crate) fn analyse(prog: &Program) -> Vec<PouInfo> {
    let mut exits = vec![true; prog.pous.len()];
    // Greatest fixpoint: start optimistic, lower until stable (monotone, at most #POUs rounds).
    for _ in 0..=prog.pous.len() {
        let next: Vec<bool> = prog.pous.iter().map(|p| gate_flow(p, &exits).1).collect();
        if next == exits {
            break;
        }
        exits = next;
    }
    prog.pous
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (gate_one, _) = gate_flow(p, &exits);
            PouInfo {
                leader: leaders(p),
                gate_one,
                exits_one: exits[i],
            }
        })
        .collect()
}
