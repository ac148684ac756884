//! Static facts the lowering relies on: basic-block leaders and where the SCR gate is provably 1.
//!
//! **Leaders** are the ops where control may arrive from somewhere other than the previous op:
//! labels, FOR bodies and the ops after NEXT, SCRE (the target of CSCRE), and every op after a
//! branch. Between two leaders the lowering keeps the logic stack and image bytes in SSA values.
//!
//! **Gate.** Power flow is `S0 AND gate`; outside SCR segments and Omron interlocks the gate is
//! 1, and knowing that at compile time removes a load and an AND from every coil. A forward
//! dataflow over each POU (each op's effect is core's `Op::gate_effect`) computes, per op,
//! whether the gate is 1 on every path reaching it. A POU is entered only by
//! a CALL that ran, i.e. with PF = 1 and hence gate = 1; a CALL leaves the gate at 1 when the
//! callee provably returns with gate 1 (computed as a greatest fixpoint over all POUs, which is
//! sound because call nesting is bounded).

use crate::resident::Resident;
use stljit_core::ir::{GateEffect, Op, Pou, Program};

/// Facts about one POU.
#[derive(Clone, Debug)]
pub(crate) struct PouInfo {
    /// `leader[i]`: a basic block starts at op `i`.
    pub(crate) leader: Vec<bool>,
    /// `cut[i]`: op `i` starts a block only because a long straight run was cut there
    /// ([`MAX_BLOCK`]), so it is entered only by falling through from op `i - 1`.
    pub(crate) cut: Vec<bool>,
    /// `gate_one[i]`: the gate is 1 whenever op `i` starts (true for unreachable ops).
    pub(crate) gate_one: Vec<bool>,
    /// Every return of the POU happens with gate 1.
    pub(crate) exits_one: bool,
    /// `stack_live[i]`: bit `k` set if logic-stack level `k` on entry to op `i` (or the end,
    /// `i = ops.len()`) may still be read; the others are dead and need not be kept.
    pub(crate) stack_live: Vec<u32>,
    /// `bit_target[i]`: the bit position where the value op `i` leaves in S0 is wanted (see
    /// [`bit_targets`]).
    pub(crate) bit_target: Vec<Option<u8>>,
}

/// For every op, the bit position (0..=7) at which the value it leaves in S0 is consumed: the
/// bit of the coil (`=`) that writes it, or bit 0 for an edge, found through the `A`, `O`,
/// `NOT`, `ALD` and `OLD` that combine it into the value the coil takes, within a straight run
/// of ops; `None` where nothing in the run takes it at a known position.
///
/// The lowering keeps a boolean at the bit position of one of its operands, and every operand
/// at another position costs an alignment (`value::and_parts`); where one operand of a
/// combination already sits at the position its consumer wants, keeping the result there
/// saves the consumer's alignment. Only a hint: any answer gives the same bits.
fn bit_targets(pou: &Pou, leader: &[bool], cut: &[bool], resident: &Resident) -> Vec<Option<u8>> {
    // Values are numbered as they are made; a value's `into` is the (later) value it is
    // combined into, `direct` the position its first direct consumer wants.
    let mut into: Vec<Option<usize>> = Vec::new();
    let mut direct: Vec<Option<u8>> = Vec::new();
    let mut made: Vec<Option<usize>> = Vec::with_capacity(pou.ops.len());
    // The logic stack as value numbers, S0 last; `None` for a level this run did not make.
    let mut stack: Vec<Option<usize>> = Vec::new();
    let fresh = |into: &mut Vec<Option<usize>>, direct: &mut Vec<Option<u8>>| {
        into.push(None);
        direct.push(None);
        into.len() - 1
    };
    for (i, op) in pou.ops.iter().enumerate() {
        if leader[i] && !cut[i] {
            stack.clear();
        }
        let top = stack.last().copied().flatten();
        match op {
            Op::Load(_) | Op::Pick(_) => {
                let v = fresh(&mut into, &mut direct);
                stack.push(Some(v));
            }
            Op::And(_) | Op::Or(_) | Op::Not => {
                let v = fresh(&mut into, &mut direct);
                if let Some(t) = top {
                    into[t].get_or_insert(v);
                }
                stack.pop();
                stack.push(Some(v));
            }
            Op::AndBlock | Op::OrBlock => {
                let v = fresh(&mut into, &mut direct);
                stack.pop();
                for t in [top, stack.pop().flatten()].into_iter().flatten() {
                    into[t].get_or_insert(v);
                }
                stack.push(Some(v));
            }
            Op::Dup => stack.push(top),
            Op::ReadSecond => {
                let s1 = stack.len().checked_sub(2).and_then(|k| stack[k]);
                stack.pop();
                stack.push(s1);
            }
            Op::Pop => {
                stack.pop();
            }
            Op::Assign { bit, .. } => {
                if let Some(t) = top {
                    // A resident bit is stored from bit 0 (`crate::resident`).
                    direct[t].get_or_insert(if resident.holds(*bit) { 0 } else { bit.bit });
                }
            }
            Op::Edge { .. } => {
                if let Some(t) = top {
                    direct[t].get_or_insert(0);
                }
                let v = fresh(&mut into, &mut direct);
                stack.pop();
                stack.push(Some(v));
            }
            _ => stack.clear(),
        }
        made.push(stack.last().copied().flatten());
    }
    // A value is combined only into later ones, so one pass from the last settles every want.
    let mut want: Vec<Option<u8>> = vec![None; into.len()];
    for v in (0..into.len()).rev() {
        want[v] = direct[v].or_else(|| into[v].and_then(|p| want[p]));
    }
    made.iter().map(|m| m.and_then(|v| want[v])).collect()
}

/// Which logic-stack levels are live on entry to every op, by backward dataflow to a fixed
/// point over the op graph, through each op's [`StackEffect`](stljit_core::ir::StackEffect). A
/// level is live if some path reads it before it is pushed off the bottom or overwritten, and
/// every POU ends with nothing live (a subroutine's stack is its own).
fn stack_liveness(pou: &Pou, depth: u8) -> Vec<u32> {
    let n = pou.ops.len();
    let full: u32 = if depth >= 32 {
        u32::MAX
    } else {
        (1u32 << depth) - 1
    };
    let effects: Vec<_> = pou.ops.iter().map(Op::stack_effect).collect();
    let mut live = vec![0u32; n + 1];
    let mut changed = true;
    while changed {
        changed = false;
        for i in (0..n).rev() {
            let out = successors(pou, i).fold(0, |m, s| m | live[s]);
            let new = effects[i].live_in(out, full);
            if new != live[i] {
                live[i] = new;
                changed = true;
            }
        }
    }
    live
}

/// Successor op indices of op `i` (`ops.len()` = the end of the POU, an exit).
fn successors(pou: &Pou, i: usize) -> impl Iterator<Item = usize> {
    pou.ops[i].successors(pou).indices(i)
}

#[cfg(test)]
fn leaders(pou: &Pou) -> Vec<bool> {
    leaders_and_cuts(pou).0
}

/// The block leaders, and which of them are only cuts of a long straight run.
fn leaders_and_cuts(pou: &Pou) -> (Vec<bool>, Vec<bool>) {
    let n = pou.ops.len();
    let mut lead = vec![false; n + 1];
    if n > 0 {
        lead[0] = true;
    }
    for i in 0..n {
        if !pou.ops[i].successors(pou).is_straight() {
            for s in successors(pou, i) {
                lead[s] = true;
            }
            lead[i + 1] = true;
        }
        if matches!(pou.ops[i], Op::Label(_)) {
            lead[i] = true;
        }
    }
    // Very long straight-line code is cut into blocks of at most MAX_BLOCK ops: register
    // allocation time grows faster than linearly with the values live across one block. A
    // cut is entered only by falling through, so the lowering carries the logic stack and the
    // cached bytes across it unchanged and it costs no instruction.
    let mut cut = vec![false; n];
    let mut since = 0;
    for (l, c) in lead.iter_mut().zip(cut.iter_mut()) {
        if *l {
            since = 0;
        } else {
            since += 1;
            if since >= MAX_BLOCK {
                *l = true;
                *c = true;
                since = 0;
            }
        }
    }
    lead.truncate(n);
    (lead, cut)
}

/// Longest run of ops lowered as one basic block.
pub(crate) const MAX_BLOCK: usize = 128;

/// How a long POU is split into chunk functions (see [`crate::lower`], "Chunks").
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ChunkPlan {
    /// First op of each chunk: chunk `k` covers `starts[k]..starts[k + 1]`, the last chunk runs
    /// to the end of the POU and also owns the end position (`ops.len()`).
    pub(crate) starts: Vec<usize>,
    /// Per chunk, the ops where control may enter it (sorted, the chunk's start first): its
    /// start, and every target of a jump, loop or skip from another chunk.
    pub(crate) entries: Vec<Vec<usize>>,
}

impl ChunkPlan {
    /// The chunk that contains op `i` (the end position belongs to the last chunk).
    pub(crate) fn chunk_of(&self, i: usize) -> usize {
        self.starts.partition_point(|&s| s <= i).saturating_sub(1)
    }

    /// The op range of chunk `k` (the last one excludes the end position).
    pub(crate) fn range(&self, k: usize, n: usize) -> std::ops::Range<usize> {
        self.starts[k]..self.starts.get(k + 1).copied().unwrap_or(n)
    }
}

/// Splits a POU longer than `chunk_ops` at block leaders into chunks of at least `chunk_ops`
/// ops; `None` keeps it one function. Compilation time of one Cranelift function grows faster
/// than its length, so a 100k-op main program compiles much faster as many mid-sized functions.
pub(crate) fn plan_chunks(pou: &Pou, leader: &[bool], chunk_ops: usize) -> Option<ChunkPlan> {
    let n = pou.ops.len();
    if chunk_ops == 0 || n <= chunk_ops {
        return None;
    }
    let mut starts = vec![0];
    for (i, &lead) in leader.iter().enumerate().take(n).skip(1) {
        if lead && i >= starts[starts.len() - 1] + chunk_ops {
            starts.push(i);
        }
    }
    if starts.len() < 2 {
        return None;
    }
    let mut plan = ChunkPlan {
        entries: starts.iter().map(|&s| vec![s]).collect(),
        starts,
    };
    for i in 0..n {
        let from = plan.chunk_of(i);
        for t in successors(pou, i) {
            let to = plan.chunk_of(t);
            if to != from && !plan.entries[to].contains(&t) {
                plan.entries[to].push(t);
            }
        }
    }
    for e in &mut plan.entries {
        e.sort_unstable();
    }
    Some(plan)
}

/// Forward dataflow of "gate is 1"; returns per-op facts and whether all exits have gate 1.
fn gate_flow(pou: &Pou, exits_one: &[bool]) -> (Vec<bool>, bool) {
    let n = pou.ops.len();
    // None = not reached yet; Some(true) = gate 1 on all paths so far.
    let mut state: Vec<Option<bool>> = vec![None; n + 1];
    state[0] = Some(true);
    let mut work = vec![0usize];
    let mut exit_ok = true;
    while let Some(i) = work.pop() {
        if i >= n {
            continue;
        }
        let Some(inp) = state[i] else { continue };
        let op = &pou.ops[i];
        let out = match op.gate_effect() {
            GateEffect::Keeps => inp,
            GateEffect::Opens => true,
            GateEffect::Sets => false,
            GateEffect::Callee => match op.callee() {
                Some(p) => inp && exits_one.get(p.index()).copied().unwrap_or(false),
                None => false,
            },
        };
        if pou.ops[i].may_exit() && !out {
            exit_ok = false;
        }
        for s in successors(pou, i) {
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
pub(crate) fn analyse(prog: &Program, resident: &Resident) -> Vec<PouInfo> {
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
            let (leader, cut) = leaders_and_cuts(p);
            let bit_target = bit_targets(p, &leader, &cut, resident);
            PouInfo {
                leader,
                cut,
                gate_one,
                exits_one: exits[i],
                stack_live: stack_liveness(p, prog.logic_stack_depth),
                bit_target,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pou(text: &str) -> Pou {
        let c = stljit_front_s7::compile_str("t.stl", text, stljit_core::ProfileId::A5);
        let prog = c.program.expect("compiles");
        prog.pous[0].clone()
    }

    #[test]
    fn stack_levels_are_live_until_read_or_pushed_off() {
        // ops: 0 LD, 1 LD, 2 LPS, 3 JMP 1, 4 LBL 1, 5 LRD, 6 = , 7 LPP, 8 ALD, 9 = , 10 LD,
        //      11 = ; depth 3 (a small stack makes the bottom drop visible)
        let p = pou(
            "LD I0.0\nLD I0.1\nLPS\nJMP 1\nLBL 1\nLRD\n= Q0.0\nLPP\nALD\n= Q0.1\n\
                     LD I0.2\n= Q0.2\n",
        );
        let live = stack_liveness(&p, 3);
        // After the last coil nothing is read again; the final LD's push needs nothing.
        assert_eq!(live[12], 0);
        assert_eq!(live[11], 0b001);
        assert_eq!(live[10], 0b000);
        // `= Q0.1` reads the top only.
        assert_eq!(live[9], 0b001);
        // ALD reads the top two; LPP drops the top and moves the levels up.
        assert_eq!(live[8], 0b011);
        assert_eq!(live[7], 0b110);
        // The coil reads the top; LRD replaces the top by level 1, so only levels 1 and 2 are
        // live before it, at the label and before the jump (which also reads its condition).
        assert_eq!(live[6], 0b111);
        assert_eq!(live[5], 0b110);
        assert_eq!(live[4], 0b110);
        assert_eq!(live[3], 0b111);
        // LPS copies the top; the two LDs push it down, the first LD's push needs nothing.
        assert_eq!(live[2], 0b011);
        assert_eq!(live[1], 0b001);
        assert_eq!(live[0], 0b000);
    }

    #[test]
    fn boxes_and_counters_read_only_their_levels() {
        // A box reads the power flow only: the levels under it are dead.
        let p = pou("LD I0.0\nMOVW 1, VW0\nLD I0.1\n= Q0.0\n");
        let live = stack_liveness(&p, 4);
        assert_eq!(live[1], 0b0001);
        assert_eq!(live[0], 0b0000);
        // CTUD reads S0..S2 (R, CD, CU); the level under them is dead.
        let p = pou("LD I0.0\nLD I0.1\nLD I0.2\nLD I0.3\nCTUD C0, 5\n");
        let live = stack_liveness(&p, 9);
        assert_eq!(live[4], 0b0111);
    }

    #[test]
    fn short_pou_is_not_split() {
        let p = pou("LD I0.0\n= Q0.0\n");
        assert_eq!(plan_chunks(&p, &leaders(&p), 2), None);
        assert_eq!(plan_chunks(&p, &leaders(&p), 0), None);
    }

    #[test]
    fn chunks_start_at_leaders_and_list_cross_chunk_targets() {
        // ops: 0 LD, 1 JMP 1, 2 LD, 3 =, 4 LBL 1, 5 LD, 6 = ; leaders 0, 2 (after JMP), 4 (LBL)
        let p = pou("LD I0.0\nJMP 1\nLD I0.1\n= Q0.0\nLBL 1\nLD I0.2\n= Q0.1\n");
        let lead = leaders(&p);
        let plan = plan_chunks(&p, &lead, 1).expect("split");
        assert_eq!(plan.starts, vec![0, 2, 4]);
        // The jump from chunk 0 lands on chunk 2's start; nothing enters mid-chunk.
        assert_eq!(plan.entries, vec![vec![0], vec![2], vec![4]]);
        assert_eq!(plan.chunk_of(3), 1);
        assert_eq!(
            plan.chunk_of(7),
            2,
            "the end position belongs to the last chunk"
        );
        assert_eq!(plan.range(2, 7), 4..7);
    }

    #[test]
    fn a_jump_into_the_middle_of_a_chunk_is_an_entry() {
        // Leaders 0, 2, 3 (LBL 2), 6 (LBL 1). JMP 1 at op 1 targets op 6 and the backward
        // JMP 2 at op 8 targets op 3: a chunk start with chunks of >= 3 ops, but the middle of
        // chunk 0 with chunks of >= 4 ops.
        let p = pou("LD I0.0\nJMP 1\nLD I0.1\nLBL 2\nLD I0.2\n= Q0.0\nLBL 1\nLD I0.3\nJMP 2\n");
        let plan = plan_chunks(&p, &leaders(&p), 3).expect("split");
        assert_eq!(plan.starts, vec![0, 3, 6]);
        assert_eq!(plan.entries, vec![vec![0], vec![3], vec![6]]);
        let plan = plan_chunks(&p, &leaders(&p), 4).expect("split");
        assert_eq!(plan.starts, vec![0, 6]);
        assert_eq!(plan.entries, vec![vec![0, 3], vec![6]]);
    }

    fn targets(text: &str) -> Vec<Option<u8>> {
        let p = pou(text);
        let (leader, cut) = leaders_and_cuts(&p);
        bit_targets(&p, &leader, &cut, &Resident::default())
    }

    #[test]
    fn a_rung_is_wanted_at_its_coil_bit() {
        // ops: 0 LD, 1 A, 2 =: the contacts' combination and what the coil leaves in S0.
        assert_eq!(
            targets("LD I0.1\nA I0.2\n= Q0.5\n"),
            [Some(5), Some(5), Some(5)]
        );
        // ALD of an OR block: every value on the way is the coil's.
        assert_eq!(
            targets("LD I0.0\nLD I0.1\nO I0.2\nALD\n= Q1.4\n"),
            [Some(4); 5]
        );
        // NOT keeps the want.
        assert_eq!(targets("LD I0.0\nNOT\n= Q0.3\n"), [Some(3); 3]);
    }

    #[test]
    fn branches_edges_and_other_consumers() {
        // ops: 0 LD, 1 LPS, 2 A, 3 =, 4 LPP, 5 A, 6 =: the shared value goes to the first
        // combination that takes it, each branch to its own coil.
        assert_eq!(
            targets("LD I0.0\nLPS\nA I0.1\n= Q0.3\nLPP\nA I0.2\n= Q0.6\n"),
            [
                Some(3),
                Some(3),
                Some(3),
                Some(3),
                Some(3),
                Some(6),
                Some(6)
            ]
        );
        // An edge takes its input at bit 0; its output goes on to the coil.
        assert_eq!(
            targets("LD I0.0\nA I0.1\nEU\n= Q0.2\n"),
            [Some(0), Some(0), Some(2), Some(2)]
        );
        // S takes its condition at any position; a label ends the run.
        assert_eq!(targets("LD I0.0\nA I0.1\nS Q0.0, 1\n"), [None; 3]);
        assert_eq!(
            targets("LD I0.0\nA I0.1\nLBL 1\n= Q0.7\n"),
            [None, None, None, None]
        );
    }
}
