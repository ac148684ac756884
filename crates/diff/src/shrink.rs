//! The shrinker: makes a failing case small while it keeps failing the same way.
//!
//! Passes, repeated until none makes progress: cut the scans after the failing one; drop whole
//! subroutines (with the calls to them); drop runs of ops, halving the run length down to single
//! ops; drop runs of scans; clear HMI writes and inputs. Every candidate is repaired into a
//! structurally sound program (indices of labels, FOR/NEXT and SCR partners remapped, edge slots
//! and timer/counter tables rebuilt) and then judged by the caller's `fails`, which is expected to
//! include [`crate::roundtrip::roundtrip`] (IR text and front end) so that only valid programs
//! are kept. Its result is written as IR text (`program.ir`, [`crate::repro::write_repro`]), so a
//! shrunk case does not depend on any dialect's printer.
//!
//! Omron programs are cut at the source instead (`lines`): the program is printed as Omron
//! text, runs of lines are dropped (halving down to single lines, then runs of three and two
//! lines at every offset, then pairs of lines) and each candidate text is compiled again; only
//! what the front end accepts is tried. An Omron op pattern spans several IR ops and its labels
//! are numbered in text order, so cutting IR ops would mostly give programs no text produces.

use crate::canon::canonicalize;
use crate::generate::{Case, ScanInput};
use crate::oracle::Finding;
use std::collections::BTreeMap;
use stljit_core::ir::{CounterDecl, EdgeDecl, Op, Pou, Program, TimerDecl};
use stljit_core::{CounterId, EdgeSlot, Family, OpIdx, PouId, TimerId};

mod lines;

/// Shrinks `case`, which fails with `finding`. `fails` re-checks a candidate and returns its
/// finding when it still fails; at most `budget` candidates are tried.
pub fn shrink(
    case: &Case,
    finding: &Finding,
    fails: &mut dyn FnMut(&Case) -> Option<Finding>,
    budget: usize,
) -> (Case, Finding) {
    let mut s = Shrinker {
        best: case.clone(),
        finding: finding.clone(),
        fails,
        budget,
    };
    if let Some(k) = finding.scan() {
        let mut c = s.best.clone();
        c.stimulus.scans.truncate(k as usize + 1);
        s.try_case(c);
    }
    loop {
        let before = size(&s.best);
        if s.best.program.profile.profile().family == Family::Omron {
            s.drop_lines();
        } else {
            s.drop_subroutines();
            s.drop_ops();
        }
        s.drop_scans();
        s.simplify_stimulus();
        if size(&s.best) >= before || s.budget == 0 {
            break;
        }
    }
    (s.best, s.finding)
}

/// Ops plus scans: what the shrinker minimises.
pub fn size(case: &Case) -> usize {
    case.program.op_count() + case.stimulus.len()
}

struct Shrinker<'f> {
    best: Case,
    finding: Finding,
    fails: &'f mut dyn FnMut(&Case) -> Option<Finding>,
    budget: usize,
}

impl Shrinker<'_> {
    /// Keeps `c` when it still fails the same way.
    fn try_case(&mut self, c: Case) -> bool {
        if self.budget == 0 {
            return false;
        }
        self.budget -= 1;
        match (self.fails)(&c) {
            Some(f) if f.same_kind(&self.finding) => {
                self.best = c;
                self.finding = f;
                true
            }
            _ => false,
        }
    }

    fn drop_subroutines(&mut self) {
        let mut id = self.best.program.pous.len();
        while id > 1 {
            id -= 1;
            if let Some(p) = remove_pou(&self.best.program, PouId::new(id)) {
                let c = Case {
                    program: p,
                    stimulus: self.best.stimulus.clone(),
                };
                self.try_case(c);
            }
        }
    }

    fn drop_ops(&mut self) {
        for pou in (0..self.best.program.pous.len()).rev() {
            let mut chunk = self.best.program.pous.get(pou).map_or(0, |p| p.ops.len());
            while chunk >= 1 {
                let mut start = 0;
                while let Some(len) = self.best.program.pous.get(pou).map(|p| p.ops.len()) {
                    if start >= len || self.budget == 0 {
                        break;
                    }
                    let end = (start + chunk).min(len);
                    let removed =
                        remove_ops(&self.best.program, pou, start, end).is_some_and(|p| {
                            let c = Case {
                                program: p,
                                stimulus: self.best.stimulus.clone(),
                            };
                            self.try_case(c)
                        });
                    if !removed {
                        start += chunk;
                    }
                }
                chunk /= 2;
            }
        }
    }

    fn drop_scans(&mut self) {
        let mut chunk = self.best.stimulus.len() / 2;
        while chunk >= 1 {
            let mut start = 0;
            while start < self.best.stimulus.len() && self.budget > 0 {
                let mut c = self.best.clone();
                let end = (start + chunk).min(c.stimulus.len());
                c.stimulus.scans.drain(start..end);
                if c.stimulus.is_empty() || !self.try_case(c) {
                    start += chunk;
                }
            }
            chunk /= 2;
        }
    }

    fn simplify_stimulus(&mut self) {
        let simplifications: [fn(&mut ScanInput); 4] = [
            |s| s.rx.clear(),
            |s| s.writes.clear(),
            |s| s.ai.iter_mut().for_each(|w| *w = 0),
            |s| s.inputs.iter_mut().for_each(|b| *b = 0),
        ];
        for f in simplifications {
            let mut c = self.best.clone();
            c.stimulus.scans.iter_mut().for_each(f);
            if c != self.best {
                self.try_case(c);
            }
        }
    }
}

/// The program without POU `id` and without every op naming it (calls, ATCH); `None` for the
/// main program.
pub fn remove_pou(p: &Program, id: PouId) -> Option<Program> {
    if id.index() == 0 || id.index() >= p.pous.len() {
        return None;
    }
    let mut q = p.clone();
    q.pous.remove(id.index());
    for pi in 0..q.pous.len() {
        let calls: Vec<usize> = q.pous[pi]
            .ops
            .iter()
            .enumerate()
            .filter(|(_, op)| op.pou_ref() == Some(id))
            .map(|(i, _)| i)
            .collect();
        for &i in calls.iter().rev() {
            q = remove_ops(&q, pi, i, i + 1)?;
        }
        for op in &mut q.pous[pi].ops {
            if let Some(c) = op.pou_ref_mut()
                && c.index() > id.index()
            {
                *c = PouId::new(c.index() - 1);
            }
        }
    }
    rebuild_tables(&mut q);
    Some(q)
}

/// The program without ops `start..end` of POU `pou`, repaired; `None` when the cut would split a
/// structural pair (a label from its jumps, FOR from NEXT, LSCR from SCRE).
pub fn remove_ops(p: &Program, pou: usize, start: usize, end: usize) -> Option<Program> {
    let old = p.pous.get(pou)?;
    if start >= end || end > old.ops.len() {
        return None;
    }
    let cut = |i: usize| (start..end).contains(&i);
    for (i, op) in old.ops.iter().enumerate() {
        let partner = match op {
            Op::For { next, .. } => Some(next.index()),
            Op::Next { head } => Some(head.index()),
            Op::Jump(l) => old.labels.get(l.index()).map(|at| at.index()),
            _ => None,
        };
        // A jump may go (its label stays, unused); a label may not leave its jumps behind.
        if let Some(j) = partner
            && !matches!(op, Op::Jump(_))
            && cut(i) != cut(j)
        {
            return None;
        }
        if let Op::Jump(_) = op
            && let Some(j) = partner
            && cut(j)
            && !cut(i)
        {
            return None;
        }
    }
    // SCR segments: an LSCR and its SCRE go together.
    let mut open: Option<usize> = None;
    for (i, op) in old.ops.iter().enumerate() {
        match op {
            Op::ScrBegin { .. } => open = Some(i),
            Op::ScrEnd => {
                if let Some(b) = open.take()
                    && cut(b) != cut(i)
                {
                    return None;
                }
            }
            _ => {}
        }
    }
    let n = end - start;
    let remap = |i: OpIdx| -> OpIdx {
        let i = i.index();
        OpIdx::new(if i >= end { i - n } else { i })
    };
    let mut q = p.clone();
    let new = &mut q.pous[pou];
    new.ops.drain(start..end);
    new.locs.drain(start..end.min(new.locs.len()));
    new.labels = new.labels.iter().map(|&at| remap(at)).collect();
    for op in &mut new.ops {
        match op {
            Op::For { next, .. } => *next = remap(*next),
            Op::Next { head } => *head = remap(*head),
            Op::ScrCondEnd { end } => *end = remap(*end),
            _ => {}
        }
    }
    // Labels whose LBL was cut (with all their jumps) must not keep a stale position.
    drop_unused_labels(new);
    rebuild_tables(&mut q);
    canonicalize(&mut q);
    Some(q)
}

fn drop_unused_labels(pou: &mut Pou) {
    let used: Vec<bool> = (0..pou.labels.len())
        .map(|l| {
            pou.ops
                .iter()
                .any(|op| matches!(op, Op::Label(x) if x.index() == l))
        })
        .collect();
    for (l, at) in pou.labels.iter_mut().enumerate() {
        if !used[l] {
            *at = OpIdx(0);
        }
    }
}

/// Renumbers edge slots in text order and rebuilds the timer and counter tables from the ops
/// that remain, as the front end would (an Omron rising edge's memory starts ON).
pub fn rebuild_tables(p: &mut Program) {
    let omron = p.profile.profile().family == Family::Omron;
    let mut inits = Vec::new();
    let mut slot = 0u16;
    let mut timers = BTreeMap::new();
    let mut counters = BTreeMap::new();
    for pou in &mut p.pous {
        for op in &mut pou.ops {
            match op {
                Op::Edge { slot: s, falling } => {
                    *s = EdgeSlot(slot);
                    inits.push(omron && !*falling);
                    slot += 1;
                }
                Op::Timer { kind, timer, .. } => {
                    timers.entry(timer.0).or_insert(*kind);
                }
                Op::Counter { kind, counter, .. } => {
                    counters.entry(counter.0).or_insert(*kind);
                }
                _ => {}
            }
        }
    }
    let old: BTreeMap<u16, TimerDecl> = p.timers.iter().map(|t| (t.id.0, *t)).collect();
    p.timers = timers
        .into_iter()
        .filter_map(|(n, kind)| {
            old.get(&n).copied().or_else(|| {
                let resolution = p.profile.profile().timer_resolution(n, kind)?;
                Some(TimerDecl {
                    id: TimerId(n),
                    kind,
                    resolution,
                })
            })
        })
        .collect();
    p.counters = counters
        .into_iter()
        .map(|(n, kind)| CounterDecl {
            id: CounterId(n),
            kind,
        })
        .collect();
    p.edges = inits.into_iter().map(|init| EdgeDecl { init }).collect();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{GenConfig, case_from_seed};
    use crate::roundtrip::roundtrip;

    /// A pretend bug: "fails" whenever the program still contains a DIV box. The shrinker must
    /// find a valid program with that box and very little else.
    #[test]
    fn shrinks_to_the_op_that_matters() {
        let cfg = GenConfig::default();
        let has_div = |c: &Case| {
            c.program
                .pous
                .iter()
                .flat_map(|p| &p.ops)
                .any(|op| matches!(op, Op::Box(stljit_core::ir::BoxOp::DivWide { .. })))
        };
        let case = (0..500)
            .map(|s| case_from_seed(s, &cfg))
            .find(|c| has_div(c) && c.program.op_count() > 60)
            .expect("some program has a DIV");
        let finding = Finding::Build {
            engine: "test",
            message: "DIV".into(),
        };
        let mut fails =
            |c: &Case| (roundtrip(&c.program).is_ok() && has_div(c)).then(|| finding.clone());
        let (small, _) = shrink(&case, &finding, &mut fails, 5000);
        assert!(roundtrip(&small.program).is_ok());
        assert!(has_div(&small));
        assert!(small.program.op_count() <= 3, "{:#?}", small.program);
        assert_eq!(small.stimulus.len(), 1);
    }

    /// The same for Omron programs, which shrink by source lines: a program that still holds
    /// a `/` (division) box ends as its condition, the box and END.
    #[test]
    fn omron_cases_shrink_by_source_lines() {
        use stljit_core::ir::{OmronArith, OmronBox};
        let has_div = |c: &Case| {
            c.program.pous.iter().flat_map(|p| &p.ops).any(|op| {
                matches!(
                    op,
                    Op::Omron(OmronBox::Arith {
                        op: OmronArith::Div,
                        ..
                    })
                )
            })
        };
        let case = (0..500)
            .filter_map(|s| {
                let mut c = crate::rng::Choices::from_seed(s);
                crate::generate::omron::generate(&mut c, &GenConfig::default()).ok()
            })
            .map(|g| g.case)
            .find(|c| has_div(c) && c.program.op_count() > 100)
            .expect("some program has a /");
        let finding = Finding::Build {
            engine: "test",
            message: "/".into(),
        };
        let mut fails =
            |c: &Case| (roundtrip(&c.program).is_ok() && has_div(c)).then(|| finding.clone());
        let (small, _) = shrink(&case, &finding, &mut fails, 5000);
        assert!(roundtrip(&small.program).is_ok());
        assert!(has_div(&small));
        // Counted in lines: a condition written with `!` is more ops than lines.
        let text = stljit_front_omron::print_program(&small.program).expect("prints");
        let lines = text.lines().filter(|l| !l.starts_with(';')).count();
        assert!(lines <= 3, "{text}");
        assert_eq!(small.stimulus.len(), 1);
    }

    /// The whole failure path on a real engine: a divergence found by the oracle (an interpreter
    /// against one with a byte overwritten after scan 3) shrinks to scan 3 and a minimal program,
    /// and its reproducer directory reads back to the same case.
    #[test]
    fn a_divergence_shrinks_and_writes_a_reproducer() {
        use crate::engines::EngineKind;
        use crate::inject::{Fault, Faulty};
        use crate::oracle::{RunOptions, run_pair};
        use crate::repro::{Meta, read_case, write_repro};
        let case = case_from_seed(11, &GenConfig::default());
        let layout = stljit_core::Layout::of(case.program.profile);
        let offset = layout.addr(stljit_core::Area::V, 1500, 0);
        let mut fails = |c: &Case| {
            let mut a = EngineKind::Interp.build(&c.program).ok()?;
            let b = EngineKind::Interp.build(&c.program).ok()?;
            let fault = Fault::SetByte {
                scan: 3,
                offset,
                value: 0xA5,
            };
            let mut b = Faulty::new(b, fault);
            let r = run_pair(
                &c.program,
                &c.stimulus,
                &mut *a,
                &mut b,
                &RunOptions::default(),
            );
            roundtrip(&c.program).ok()?;
            r.err()
        };
        let finding = fails(&case).expect("the fault is found");
        let (small, f) = shrink(&case, &finding, &mut fails, 3000);
        assert_eq!(f.scan(), Some(3));
        assert_eq!(small.stimulus.len(), 4);
        assert!(small.program.op_count() <= 1, "{:#?}", small.program);
        let dir = std::env::temp_dir().join(format!("stljit-shrink-test-{}", std::process::id()));
        let meta = Meta::new(small.program.profile, Some(11), "interp faulty");
        write_repro(&dir, &small, &meta, Some(&f)).unwrap();
        let readme = std::fs::read_to_string(dir.join("README.txt")).unwrap();
        assert!(
            readme.contains("after scan 3") && readme.contains("VB1500"),
            "{readme}"
        );
        let ir = std::fs::read_to_string(dir.join("program.ir")).unwrap();
        assert_eq!(stljit_core::text::parse(&ir).as_ref(), Ok(&small.program));
        let (back, _) = read_case(&dir).unwrap();
        assert_eq!(back.program, small.program);
        assert_eq!(back.stimulus, small.stimulus);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn removing_every_single_op_keeps_programs_sound() {
        let cfg = GenConfig::default();
        for seed in 0..30 {
            let p = case_from_seed(seed, &cfg).program;
            for pou in 0..p.pous.len() {
                for i in 0..p.pous[pou].ops.len() {
                    if let Some(q) = remove_ops(&p, pou, i, i + 1)
                        && let Err(e) = roundtrip(&q)
                    {
                        panic!("seed {seed}: removing op {i} of pou {pou}: {e}");
                    }
                }
            }
            for id in 1..p.pous.len() {
                if let Some(q) = remove_pou(&p, PouId::new(id))
                    && let Err(e) = roundtrip(&q)
                {
                    panic!("seed {seed}: removing pou {id}: {e}");
                }
            }
        }
    }
}
