//! The program units of a printed program. The front end lowers each `$TASK` unit like a
//! program of its own and assembles the IR's main POU from the started cyclic tasks in run
//! order (an `Op::TaskStart` between two), followed by those tasks' subroutines in source order;
//! edge slots are numbered in source order over every unit, run or not. [`plan`] reads that
//! back: the tasks, which subroutines belong to which task (the calls decide; an uncalled one
//! joins its neighbour's task, else another, whichever gives a layout the front end produces),
//! and a source order that gives the same subroutine order and edge slots, with the slots no
//! op uses (the edges of units that never run) put back as `$TASK UNASSIGNED` programs where
//! they were.

use super::body::Body;
use super::{PrintError, callee, control, edge_option, head, line};
use crate::mnemonics::{Flow, Group, Join};
use std::ops::Range;
use stljit_core::ir::{Op, PouKind, Program};

/// One unit of the printed text, in source order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) enum Unit {
    /// The task that runs `k`-th (printed as cyclic task `k`).
    Task(usize),
    /// A program that never runs, holding edge memories no op uses (their `init` values).
    Unused(Vec<bool>),
}

/// One task of the main POU.
#[derive(Clone, Debug)]
struct Task {
    /// Its ops in the main POU (without the `TaskStart` before it and the final END).
    ops: Range<usize>,
    /// Its first label: the main POU's labels are the tasks' in run order.
    first_label: usize,
    /// Its subroutines (POU indices, in order).
    subs: Vec<usize>,
    /// The edge slots its ops use, in text order (body, then subroutines).
    slots: Vec<usize>,
}

/// The units of a program and their order.
#[derive(Debug)]
pub(super) struct Plan {
    tasks: Vec<Task>,
    /// The units in source order.
    pub(super) units: Vec<Unit>,
}

/// The units of `program` in a source order the front end turns back into it.
pub(super) fn plan(program: &Program) -> Result<Plan, PrintError> {
    let err = |pou, message: &str| PrintError::at_pou(pou, message);
    let Some(main) = program.pous.first() else {
        return Err(err(0, "no main program"));
    };
    if main.kind != PouKind::Main {
        return Err(err(0, "the first POU is not the main program"));
    }
    let Some((Op::End { conditional: false }, body)) = main.ops.split_last() else {
        return Err(err(0, "the main program does not end with END(001)"));
    };
    for (i, pou) in program.pous.iter().enumerate().skip(1) {
        if !matches!(pou.kind, PouKind::Subroutine(_)) {
            return Err(err(i, "only subroutines follow the main program"));
        }
        if pou.ops.last() != Some(&Op::Return { conditional: false }) {
            return Err(err(i, "a subroutine does not end with RET(093)"));
        }
    }
    let mut tasks = Vec::new();
    let mut start = 0;
    for end in body
        .iter()
        .enumerate()
        .filter(|(_, op)| **op == Op::TaskStart)
        .map(|(i, _)| i)
        .chain([body.len()])
    {
        let first_label = main.labels.iter().filter(|l| l.index() < start).count();
        tasks.push(Task {
            ops: start..end,
            first_label,
            subs: Vec::new(),
            slots: Vec::new(),
        });
        start = end + 1;
    }
    let called = called_owners(program, &tasks)?;
    // A subroutine no task calls could have been in any task: try its neighbour's first, then
    // the others, until the layout is one the front end gives (bounded: such subroutines are
    // few; a program with too many is refused).
    let free: Vec<usize> = (1..program.pous.len())
        .filter(|&s| called[s].is_none())
        .collect();
    let n = tasks.len();
    let tries = u32::try_from(free.len())
        .ok()
        .and_then(|k| n.checked_pow(k))
        .filter(|&t| t <= 4096)
        .ok_or_else(|| err(0, "too many subroutines no task calls"))?;
    let mut last = "no layout";
    for mut code in 0..tries {
        let mut owner = called.clone();
        let mut ok = true;
        for &s in &free {
            let digit = code % n;
            code /= n;
            if owner[s].is_some() {
                continue;
            }
            let guess = preferred(program, &owner, s);
            let k = (guess + digit) % n;
            ok &= claim(program, &mut owner, vec![(s, k)]).is_ok();
        }
        if !ok {
            continue;
        }
        let owner: Vec<usize> = owner.into_iter().map(|o| o.unwrap_or(0)).collect();
        match layout(program, &tasks, &owner) {
            Ok(plan) => return Ok(plan),
            Err(message) => last = message,
        }
    }
    Err(err(0, last))
}

/// The `tasks` (none with subroutines yet) with their subroutines (`owner`), in a source order
/// giving the program's edge slots and subroutine order, with the unused edge slots as units of
/// their own.
fn layout(program: &Program, tasks: &[Task], owner: &[usize]) -> Result<Plan, &'static str> {
    let main = &program.pous[0];
    let mut tasks = tasks.to_vec();
    for (sub, &k) in owner.iter().enumerate().skip(1) {
        tasks[k].subs.push(sub);
    }
    // The subroutines of a task are consecutive POUs (a unit's SBNs are written together).
    let mut seen = Vec::new();
    for &k in owner.iter().skip(1) {
        if seen.last() != Some(&k) {
            if seen.contains(&k) {
                return Err("a task's subroutines are not consecutive POUs");
            }
            seen.push(k);
        }
    }
    for t in &mut tasks {
        let ops = main.ops[t.ops.clone()]
            .iter()
            .chain(t.subs.iter().flat_map(|&s| &program.pous[s].ops));
        t.slots = ops
            .filter_map(|op| match op {
                Op::Edge { slot, .. } => Some(slot.index()),
                _ => None,
            })
            .collect();
        if t.slots.windows(2).any(|w| w[1] != w[0] + 1) {
            return Err("a task's edge slots are not consecutive in text order");
        }
    }
    let order = source_order(&tasks)
        .ok_or("no source order of the tasks gives these edge slots and subroutines")?;
    let mut units = Vec::new();
    let mut next = 0;
    let unused = |r: Range<usize>| Unit::Unused(program.edges[r].iter().map(|e| e.init).collect());
    for k in order {
        if let (Some(&first), Some(&last)) = (tasks[k].slots.first(), tasks[k].slots.last()) {
            if first < next || last >= program.edges.len() {
                return Err("the tasks' edge slots overlap");
            }
            if first > next {
                units.push(unused(next..first));
            }
            next = last + 1;
        }
        units.push(Unit::Task(k));
    }
    if next < program.edges.len() {
        units.push(unused(next..program.edges.len()));
    }
    Ok(Plan { tasks, units })
}

/// The task each subroutine belongs to when some task's code calls it, directly or through
/// other subroutines (`None` for the rest).
fn called_owners(program: &Program, tasks: &[Task]) -> Result<Vec<Option<usize>>, PrintError> {
    let mut owner: Vec<Option<usize>> = vec![None; program.pous.len()];
    let main = &program.pous[0];
    let mut calls = Vec::new();
    for (k, t) in tasks.iter().enumerate() {
        calls.extend(
            main.ops[t.ops.clone()]
                .iter()
                .filter_map(callee)
                .map(|p| (p.index(), k)),
        );
    }
    claim(program, &mut owner, calls)?;
    Ok(owner)
}

/// The likeliest task of subroutine `s`, which no task calls: the task of a subroutine it
/// calls, else of the subroutine before it (or after it), else the first.
fn preferred(program: &Program, owner: &[Option<usize>], s: usize) -> usize {
    let n = owner.len();
    reached_owner(program, owner, s)
        .or_else(|| (1..s).rev().find_map(|p| owner[p]))
        .or_else(|| (s + 1..n).find_map(|p| owner[p]))
        .unwrap_or(0)
}

/// Gives each subroutine of `calls` (and everything it calls) to its task.
fn claim(
    program: &Program,
    owner: &mut [Option<usize>],
    mut calls: Vec<(usize, usize)>,
) -> Result<(), PrintError> {
    while let Some((s, k)) = calls.pop() {
        match owner.get(s).copied() {
            None => return Err(PrintError::at_pou(0, "a call to a missing POU")),
            Some(_) if s == 0 => return Err(PrintError::at_pou(0, "a call to the main program")),
            Some(Some(o)) if o == k => {}
            Some(Some(_)) => {
                let msg = "a subroutine is called from two tasks";
                return Err(PrintError::at_pou(s, msg));
            }
            Some(None) => {
                owner[s] = Some(k);
                calls.extend(
                    program.pous[s]
                        .ops
                        .iter()
                        .filter_map(callee)
                        .map(|p| (p.index(), k)),
                );
            }
        }
    }
    Ok(())
}

/// The task of a subroutine that `s` calls, directly or not.
fn reached_owner(program: &Program, owner: &[Option<usize>], s: usize) -> Option<usize> {
    let mut seen = vec![false; owner.len()];
    let mut stack = vec![s];
    while let Some(p) = stack.pop() {
        if std::mem::replace(seen.get_mut(p)?, true) {
            continue;
        }
        if let Some(k) = owner[p] {
            return Some(k);
        }
        stack.extend(
            program.pous[p]
                .ops
                .iter()
                .filter_map(callee)
                .map(|c| c.index()),
        );
    }
    None
}

/// A source order of the tasks: the ones with edges ordered by their first slot, the ones with
/// subroutines by their first subroutine; otherwise in run order. `None` if the two orders
/// contradict each other.
fn source_order(tasks: &[Task]) -> Option<Vec<usize>> {
    let chain = |key: &dyn Fn(&Task) -> Option<usize>| {
        let mut c: Vec<(usize, usize)> = tasks
            .iter()
            .enumerate()
            .filter_map(|(k, t)| key(t).map(|v| (v, k)))
            .collect();
        c.sort_unstable();
        c.into_iter().map(|(_, k)| k).collect::<Vec<_>>()
    };
    let by_slot = chain(&|t| t.slots.first().copied());
    let by_sub = chain(&|t| t.subs.first().copied());
    let mut before: Vec<Vec<usize>> = vec![Vec::new(); tasks.len()];
    for c in [&by_slot, &by_sub] {
        for w in c.windows(2) {
            before[w[1]].push(w[0]);
        }
    }
    let mut order = Vec::new();
    let mut placed = vec![false; tasks.len()];
    while order.len() < tasks.len() {
        let k = (0..tasks.len()).find(|&k| !placed[k] && before[k].iter().all(|&b| placed[b]))?;
        placed[k] = true;
        order.push(k);
    }
    Some(order)
}

impl Plan {
    /// Prints task `k`: its part of the main POU, its subroutines, END.
    pub(super) fn print_task(
        &self,
        program: &Program,
        k: usize,
        out: &mut String,
    ) -> Result<(), PrintError> {
        let t = &self.tasks[k];
        let ctl = |pou, flow, operands: &[String]| {
            control(flow, operands).map_err(|m| PrintError::at_pou(pou, m))
        };
        let main = &program.pous[0];
        Body::new(program, 0, t.first_label).print(&main.ops[..t.ops.end], t.ops.start, out)?;
        for &s in &t.subs {
            let pou = &program.pous[s];
            let PouKind::Subroutine(n) = pou.kind else {
                return Err(PrintError::at_pou(s, "not a subroutine"));
            };
            out.push_str(&ctl(s, Flow::Sbn, &[n.to_string()])?);
            let body = &pou.ops[..pou.ops.len().saturating_sub(1)];
            Body::new(program, s, 0).print(body, 0, out)?;
            out.push_str(&ctl(s, Flow::Ret, &[])?);
        }
        out.push_str(&ctl(0, Flow::End, &[])?);
        Ok(())
    }
}

/// A program assigned to no task (never run, W037) holding edge memories with the `init`
/// values `edges`: one circuit of differentiated contacts (`@` starts ON, `%` OFF).
pub(super) fn print_unused(edges: &[bool], out: &mut String) {
    out.push_str("$TASK UNASSIGNED\n");
    for (i, init) in edges.iter().enumerate() {
        let join = if i == 0 { Join::Load } else { Join::And };
        let h = head(edge_option(!init), Group::Contact(join, false));
        out.push_str(&line(&h.unwrap_or_default(), &["0.00".into()]));
    }
    let out_line = head("", Group::Out(false)).unwrap_or_default();
    out.push_str(&line(&out_line, &["W0.00".into()]));
    out.push_str(&control(Flow::End, &[]).unwrap_or_default());
}
