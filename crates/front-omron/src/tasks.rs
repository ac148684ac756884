//! The program units of a project (docs/omron.md "Tasks"): the `$TASK` and `$FB` directives
//! that start them, the checks that span units (omron-cp.md §2.1, §5: E025 for a pair split
//! between tasks, E036 for the task structure, W037 for an unassigned program) and the
//! assembly of the IR: the main POU runs the cyclic tasks started at RUN in ascending number,
//! each after an `Op::TaskStart` but the first (the scan's start does the first one's resets).
//!
//! A unit is lowered like a whole program of its own (its own END, circuit, regions, jumps and
//! W020/W034 state); only timer and counter numbers, edge slots and subroutine numbers are
//! shared by the project.

use crate::lexer::Line;
use crate::lower::{Lowerer, PouBuild};
use crate::resolve::Reported;
use std::collections::HashMap;
use stljit_core::ir::{Op, Pou, PouKind};
use stljit_core::{LabelId, OpIdx, PouId};
use stljit_source::{Code, Diagnostic, Span, clip};

/// What a unit of the project is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum UnitKind {
    /// Cyclic task `number`; `started` at RUN, or in standby (never run: stljit has no TKON).
    Cyclic {
        /// The task number.
        number: u8,
        /// Started at RUN.
        started: bool,
    },
    /// `$TASK UNASSIGNED`: checked, never run (W037).
    Unassigned,
    /// `$TASK INTERRUPT n`: reported (E011), checked like an unassigned program.
    Interrupt(u32),
    /// `$FB name`: a function-block body, checked with the FB restrictions, never run.
    FunctionBlock(String),
}

impl UnitKind {
    /// How messages name the unit.
    pub(crate) fn name(&self) -> String {
        match self {
            UnitKind::Cyclic { number, .. } => format!("task {number}"),
            UnitKind::Unassigned => "unassigned program".into(),
            UnitKind::Interrupt(n) => format!("interrupt task {n}"),
            UnitKind::FunctionBlock(name) => format!("function block `{name}`"),
        }
    }

    /// Whether the unit runs every cycle.
    fn runs(&self) -> bool {
        matches!(self, UnitKind::Cyclic { started: true, .. })
    }
}

/// One program unit.
#[derive(Clone, Debug)]
pub(crate) struct Unit {
    /// What it is.
    pub(crate) kind: UnitKind,
    /// Its directive, `None` for the implicit task 0 before any directive.
    directive: Option<Span>,
    /// Where it starts: its directive, or the implicit task's first instruction.
    start: Span,
    /// Its main body: an index into `Lowerer::pous`.
    pub(crate) body: usize,
}

/// The two instructions of a pair that must be in one task (§2.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Pair {
    /// IL(002) … ILC(003).
    Interlock,
    /// JMP/CJP/CJPN n … JME n.
    Jump(u32),
    /// JMP0(515) … JME0(516).
    Jmp0,
    /// FOR(503) … NEXT(504).
    Loop,
    /// BPRG(096) … BEND(801).
    Block,
    /// SNXT(009) B … STEP(008) B.
    Step(stljit_core::ir::BitLoc),
}

/// One half of a pair that found no partner in its own POU: reported as `plain` unless its
/// partner is in another unit (then E025 instead).
#[derive(Clone, Debug)]
pub(crate) struct Dangling {
    pair: Pair,
    /// The opening instruction (else the closing one).
    opener: bool,
    /// The instruction as messages name it (`JMP(004) 1`).
    what: String,
    unit: usize,
    span: Span,
    /// The error when no other unit holds the partner; `None` for a closer that is fine alone
    /// (a JME or a JME0 nothing jumps to).
    plain: Option<(Code, String)>,
}

/// The project-wide state: units, subroutines, calls and the pairs left open.
#[derive(Debug, Default)]
pub(crate) struct Project {
    /// The units in source order; the last is the current one.
    pub(crate) units: Vec<Unit>,
    /// Subroutine numbers to their POUs (indices into `Lowerer::pous`) and SBN lines.
    pub(crate) subs: HashMap<u32, (usize, Span)>,
    /// `SBS` calls to resolve at the end: POU index, op index, number, place.
    pub(crate) calls: Vec<(usize, usize, u32, Span)>,
    dangling: Vec<Dangling>,
    /// The file names, for places in other files.
    pub(crate) files: Vec<String>,
}

impl Project {
    /// A project of the files named `files`, with no unit yet.
    pub(crate) fn new(files: Vec<String>) -> Project {
        Project {
            files,
            ..Project::default()
        }
    }

    /// The current unit's index.
    pub(crate) fn unit(&self) -> usize {
        self.units.len().saturating_sub(1)
    }

    /// `line 12` in `at`'s file, else `b.omr:12`.
    fn place(&self, span: Span, at: Span) -> String {
        if span.file == at.file {
            format!("line {}", span.line)
        } else {
            let name = self
                .files
                .get(span.file.index())
                .map_or("?", |s| s.as_str());
            format!("{name}:{}", span.line)
        }
    }
}

impl Lowerer<'_> {
    /// The current unit's name for messages (`task 0`).
    pub(crate) fn unit_name(&self) -> String {
        self.project
            .units
            .last()
            .map_or_else(|| "task 0".into(), |u| u.kind.name())
    }

    /// The current unit's kind.
    pub(crate) fn unit_kind(&self) -> &UnitKind {
        &self.project.units[self.project.unit()].kind
    }

    /// The current unit's main body (an index into `pous`).
    pub(crate) fn unit_body(&self) -> usize {
        self.project.units[self.project.unit()].body
    }

    /// Starts a unit: a fresh main body and fresh per-unit state.
    pub(crate) fn start_unit(&mut self, kind: UnitKind, directive: Option<Span>, start: Span) {
        let body = self.pous.len();
        self.pous.push(PouBuild {
            pou: Pou {
                name: "MAIN".into(),
                kind: PouKind::Main,
                ops: Vec::new(),
                locs: Vec::new(),
                labels: Vec::new(),
            },
            unit: self.project.units.len(),
        });
        self.project.units.push(Unit {
            kind,
            directive,
            start,
            body,
        });
        self.reset_unit_state();
        self.control.pou = body;
    }

    /// Records half of a pair that stays open in its POU.
    pub(crate) fn dangle(
        &mut self,
        pair: Pair,
        opener: bool,
        span: Span,
        what: String,
        plain: Option<(Code, String)>,
    ) {
        let unit = self.project.unit();
        self.project.dangling.push(Dangling {
            pair,
            opener,
            what,
            unit,
            span,
            plain,
        });
    }

    /// A `$…` directive line.
    pub(crate) fn directive(&mut self, l: &Line) {
        let span = self.cx.span(&l.head);
        let words: Vec<String> = l
            .operands
            .iter()
            .map(|t| t.text.to_ascii_uppercase())
            .collect();
        let words: Vec<&str> = words.iter().map(String::as_str).collect();
        let kind = match (l.mnemonic.as_str(), words.as_slice()) {
            ("$TASK", ["CYCLIC", n, rest @ ..]) if matches!(rest, [] | ["STANDBY"]) => {
                self.task_number(l, n).map(|number| UnitKind::Cyclic {
                    number,
                    started: rest.is_empty(),
                })
            }
            ("$TASK", ["UNASSIGNED"]) => Ok(UnitKind::Unassigned),
            ("$TASK", ["INTERRUPT", n]) if n.bytes().all(|b| b.is_ascii_digit()) => {
                let n = n.parse().unwrap_or(u32::MAX);
                self.at_head(
                    l,
                    Code::OmrInstruction,
                    format!("interrupt tasks are not supported yet (INTERRUPT {n})"),
                );
                Ok(UnitKind::Interrupt(n))
            }
            ("$FB", [_]) => Ok(UnitKind::FunctionBlock(clip(&l.operands[0].text))),
            ("$TASK", _) => Err(self.at_head(
                l,
                Code::OmrOperand,
                "$TASK expects CYCLIC n, CYCLIC n STANDBY, UNASSIGNED or INTERRUPT n".into(),
            )),
            ("$FB", _) => Err(self.at_head(
                l,
                Code::OmrOperand,
                "$FB expects the function block's name".into(),
            )),
            (other, _) => {
                // Not a directive at all: reported, and the current unit goes on.
                self.at_head(
                    l,
                    Code::OmrInstruction,
                    format!("{} is not a directive ($TASK, $FB)", clip(other)),
                );
                return;
            }
        };
        // A malformed directive still starts a unit (the lines after it belong to it); it is
        // checked like an unassigned program, without a W037 on top of the error.
        let (kind, well_formed) = match kind {
            Ok(k) => (k, true),
            Err(Reported) => (UnitKind::Unassigned, false),
        };
        if let UnitKind::Cyclic { number, .. } = kind
            && let Some(first) = self
                .project
                .units
                .iter()
                .find(|u| matches!(u.kind, UnitKind::Cyclic { number: n, .. } if n == number))
        {
            let place = self.project.place(first.start, span);
            let what = if first.directive.is_some() {
                "the $TASK"
            } else {
                "the program before the first $TASK, which starts"
            };
            self.at_head(
                l,
                Code::OmrTask,
                format!("task {number} is given twice: {what} at {place} is task {number} too"),
            );
        }
        if kind == UnitKind::Unassigned && well_formed {
            self.at_head(
                l,
                Code::OmrUnassigned,
                "this program is assigned to no task; it is checked but never runs".into(),
            );
        }
        if !self.project.units.is_empty() {
            self.finish_unit(span);
        }
        self.start_unit(kind, Some(span), span);
    }

    /// Before the first instruction of a project without a leading directive: the implicit
    /// cyclic task 0, started at RUN.
    pub(crate) fn ensure_unit(&mut self, first: Span) {
        if self.project.units.is_empty() {
            let task0 = UnitKind::Cyclic {
                number: 0,
                started: true,
            };
            self.start_unit(task0, None, first);
        }
    }

    /// The number of a cyclic task, within the profile's tasks (E014).
    fn task_number(&mut self, l: &Line, n: &str) -> Result<u8, Reported> {
        let max = self.cx.profile.omron.cyclic_tasks;
        match n.parse::<u32>() {
            Ok(v) if v < u32::from(max) && n.bytes().all(|b| b.is_ascii_digit()) => Ok(v as u8),
            _ => {
                let model = self.cx.profile.model;
                let tok = &l.operands[1];
                let line = l.line;
                Err(self.cx.report(
                    Code::OmrRange,
                    tok,
                    format!(
                        "line {line}: {} is outside the cyclic tasks (0–{}) of {model}",
                        clip(&tok.text),
                        max.saturating_sub(1)
                    ),
                ))
            }
        }
    }

    /// End of the project: the last unit closed, then the checks across units (E036, E025)
    /// and the calls resolved.
    pub(crate) fn finish(&mut self, last: Span) {
        self.ensure_unit(last);
        self.finish_unit(last);
        if !self.project.units.iter().any(|u| u.kind.runs()) {
            let at = self
                .project
                .units
                .iter()
                .find_map(|u| u.directive)
                .unwrap_or(last);
            let d = Diagnostic::new(
                Code::OmrTask,
                at,
                "",
                format!(
                    "line {}: no cyclic task starts at RUN — every program is in standby, unassigned, an interrupt task or a function block",
                    at.line
                ),
            );
            self.cx.diags.push(d);
        }
        self.resolve_pairs();
        self.resolve_calls();
        self.check_capacity();
    }

    /// E025 for the halves whose partner is in another unit, the plain error for the rest.
    fn resolve_pairs(&mut self) {
        let dangling = std::mem::take(&mut self.project.dangling);
        for d in &dangling {
            let partners = |same: bool| {
                dangling.iter().filter(move |o| {
                    o.pair == d.pair && o.opener != d.opener && (o.unit == d.unit) == same
                })
            };
            // A partner in its own unit (another POU of it) makes it a plain error.
            let partner = partners(false)
                .next()
                .filter(|_| partners(true).next().is_none());
            match (partner, &d.plain) {
                (Some(o), _) if d.opener || d.plain.is_some() => {
                    let msg = format!(
                        "line {}: {} pairs with {} at {} in {}; both must be in the same task",
                        d.span.line,
                        d.what,
                        o.what,
                        self.project.place(o.span, d.span),
                        self.project.units[o.unit].kind.name()
                    );
                    self.cx
                        .diags
                        .push(Diagnostic::new(Code::OmrSplitPair, d.span, "", msg));
                }
                (_, Some((code, msg))) => {
                    self.cx
                        .diags
                        .push(Diagnostic::new(*code, d.span, "", msg.clone()));
                }
                _ => {}
            }
        }
    }

    /// Every SBS resolved to its SBN's POU; a call into another unit is E025.
    fn resolve_calls(&mut self) {
        for (pou, at, n, span) in std::mem::take(&mut self.project.calls) {
            let Some(&(sub, sbn)) = self.project.subs.get(&n) else {
                let msg = format!(
                    "line {}: SBS {n} calls a subroutine that no SBN(092) defines",
                    span.line
                );
                self.cx
                    .diags
                    .push(Diagnostic::new(Code::OmrOperand, span, "", msg));
                continue;
            };
            let (from, to) = (self.pous[pou].unit, self.pous[sub].unit);
            if from != to {
                let msg = format!(
                    "line {}: SBS(091) {n} calls SBN(092) {n} at {} in {}; a subroutine is called only from its own task",
                    span.line,
                    self.project.place(sbn, span),
                    self.project.units[to].kind.name()
                );
                self.cx
                    .diags
                    .push(Diagnostic::new(Code::OmrSplitPair, span, "", msg));
            }
            self.pous[pou].pou.ops[at] = Op::Call(PouId::new(sub));
        }
    }

    /// The IR POUs of a checked project: the main POU (the started cyclic tasks in ascending
    /// number, an `Op::TaskStart` before each but the first, every END but the last one's
    /// falling through into the next task) and the subroutines of those tasks in source order.
    pub(crate) fn assemble(self) -> Vec<Pou> {
        let mut order: Vec<(u8, usize)> = self
            .project
            .units
            .iter()
            .filter_map(|u| match u.kind {
                UnitKind::Cyclic {
                    number,
                    started: true,
                } => Some((number, u.body)),
                _ => None,
            })
            .collect();
        order.sort_unstable();
        let running: Vec<usize> = self
            .project
            .units
            .iter()
            .enumerate()
            .filter(|(_, u)| u.kind.runs())
            .map(|(i, _)| i)
            .collect();
        // New POU ids: main 0, then the running units' subroutines in source order.
        let mut ids: HashMap<usize, PouId> = HashMap::new();
        let mut subs = Vec::new();
        for (i, b) in self.pous.iter().enumerate() {
            if matches!(b.pou.kind, PouKind::Subroutine(_)) && running.contains(&b.unit) {
                ids.insert(i, PouId::new(1 + subs.len()));
                subs.push(i);
            }
        }
        let mut pous: Vec<Option<PouBuild>> = self.pous.into_iter().map(Some).collect();
        let mut main = Pou {
            name: "MAIN".into(),
            kind: PouKind::Main,
            ops: Vec::new(),
            locs: Vec::new(),
            labels: Vec::new(),
        };
        let last = order.len().saturating_sub(1);
        for (k, &(_, body)) in order.iter().enumerate() {
            let Some(b) = pous[body].take() else { continue };
            if k > 0 {
                let loc = b.pou.locs.first().copied().unwrap_or_default();
                main.ops.push(Op::TaskStart);
                main.locs.push(loc);
            }
            append(&mut main, relink(b.pou, &ids), k == last);
        }
        let mut out = vec![main];
        for i in subs {
            if let Some(b) = pous[i].take() {
                out.push(relink(b.pou, &ids));
            }
        }
        out
    }
}

/// `pou` with its calls pointing at the new POU ids.
fn relink(mut pou: Pou, ids: &HashMap<usize, PouId>) -> Pou {
    for op in &mut pou.ops {
        if let Op::Call(id) = op
            && let Some(new) = ids.get(&id.index())
        {
            *id = *new;
        }
    }
    pou
}

/// Appends a task's body to the main POU, its op indices and labels moved past what is there;
/// a body that is not the last drops its final END, so control falls into the next task.
fn append(main: &mut Pou, mut body: Pou, keep_end: bool) {
    if !keep_end && body.ops.last() == Some(&Op::End { conditional: false }) {
        body.ops.pop();
        body.locs.pop();
    }
    let ops = main.ops.len();
    let labels = main.labels.len();
    let op = |i: OpIdx| OpIdx::new(i.index() + ops);
    let label = |l: LabelId| LabelId::new(l.index() + labels);
    for o in &mut body.ops {
        match o {
            Op::Jump(l) | Op::Label(l) => *l = label(*l),
            Op::For { next, .. } => *next = op(*next),
            Op::Next { head } => *head = op(*head),
            Op::ScrCondEnd { end } => *end = op(*end),
            _ => {}
        }
    }
    main.labels.extend(body.labels.into_iter().map(op));
    main.ops.extend(body.ops);
    main.locs.extend(body.locs);
}
