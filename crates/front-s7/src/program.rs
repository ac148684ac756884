//! The lowering driver: walks every POU's lines, lowers each instruction (see `lower.rs` and
//! `control.rs`), resolves labels, FOR/NEXT and SCR partners, and collects the program-wide
//! tables (timers, counters, edge slots) into an [`stljit_core::ir::Program`].

use crate::classes::Cx;
use crate::lexer::{Line, Tok, upper};
use crate::locals::Locals;
use crate::mnemonics;
use crate::spelling::{counter_mnemonic, timer_mnemonic};
use crate::stack::StackCheck;
use crate::structure::PouSrc;
use std::collections::HashMap;
use std::rc::Rc;
use stljit_core::ir::{
    BitLoc, CounterDecl, CounterKind, EdgeDecl, Op, Pou, PouKind, Program, SrcLoc, TimerDecl,
    TimerKind, loop_entered_by,
};
use stljit_core::{CounterId, LabelId, OpIdx, PouId, TimerId};
use stljit_source::Code;
use stljit_source::{Diagnostic, Span, clip};

/// An open SCR segment.
pub(crate) struct OpenScr {
    /// The LSCR op.
    pub(crate) at: OpIdx,
    /// Its S bit.
    pub(crate) bit: BitLoc,
    /// Where it was opened.
    pub(crate) span: Span,
    /// CSCRE ops waiting for the SCRE.
    pub(crate) cond_ends: Vec<OpIdx>,
}

/// Lowering state of one POU.
pub(crate) struct PouState {
    /// Index of the POU.
    pub(crate) id: PouId,
    /// Its kind.
    pub(crate) kind: PouKind,
    /// Ops so far.
    pub(crate) ops: Vec<Op>,
    /// Their locations.
    pub(crate) locs: Vec<SrcLoc>,
    /// Label number → id, assigned at first appearance.
    pub(crate) label_ids: HashMap<u32, LabelId>,
    /// Per label id: its LBL op and where it was defined.
    pub(crate) label_defs: Vec<Option<(OpIdx, Span)>>,
    /// JMPs: label number, where, the operand as written, and the JMP op.
    pub(crate) jumps: Vec<(u32, Span, String, OpIdx)>,
    /// Open FOR ops.
    pub(crate) fors: Vec<(OpIdx, Span)>,
    /// The open SCR segment.
    pub(crate) scr: Option<OpenScr>,
    stack: StackCheck,
}

impl PouState {
    /// Index the next op will get.
    pub(crate) fn next_idx(&self) -> OpIdx {
        OpIdx::new(self.ops.len())
    }

    /// The label id for number `n`.
    pub(crate) fn label(&mut self, n: u32) -> LabelId {
        let next = LabelId::new(self.label_defs.len());
        let id = *self.label_ids.entry(n).or_insert(next);
        if id == next {
            self.label_defs.push(None);
        }
        id
    }
}

/// Program-wide lowering state.
pub(crate) struct Lowerer<'s> {
    /// Operand checking and diagnostics.
    pub(crate) cx: Cx<'s>,
    /// Subroutines by number.
    pub(crate) subs: HashMap<u16, PouId>,
    /// Blocks by name.
    pub(crate) names: HashMap<String, (PouId, PouKind)>,
    /// Timers used by a timer instruction: kind and first use.
    pub(crate) timers: HashMap<u16, (TimerKind, Span)>,
    /// Counters used by a counter instruction.
    pub(crate) counters: HashMap<u16, (CounterKind, Span)>,
    /// Edge slots handed out.
    pub(crate) edges: usize,
    /// S bits used as segment flags, and the POU using each.
    pub(crate) scr_bits: HashMap<BitLoc, (PouId, Span)>,
    /// The op being lowered's mnemonic token.
    pub(crate) mnemonic: Tok<'s>,
    /// Every POU's local variable table, by POU index (a CALL checks its actuals against the
    /// callee's).
    pub(crate) locals: Vec<Rc<Locals>>,
    /// Every POU's name and where it is declared, by POU index (for CALL messages).
    pub(crate) pou_names: Vec<String>,
    /// See `pou_names`.
    pub(crate) pou_spans: Vec<Span>,
}

impl<'s> Lowerer<'s> {
    /// Appends an op for the current line.
    pub(crate) fn emit(&mut self, ps: &mut PouState, op: Op) -> OpIdx {
        let span = self.cx.span(self.mnemonic);
        ps.stack
            .step(&op, span, self.mnemonic.text, &mut self.cx.diags);
        let idx = ps.next_idx();
        ps.ops.push(op);
        ps.locs.push(SrcLoc {
            file: span.file,
            line: span.line,
            col: span.col,
        });
        idx
    }

    fn lower_line(&mut self, ps: &mut PouState, line: &Line<'s>) {
        self.cx.line = line.line;
        self.mnemonic = line.mnemonic;
        let before = ps.ops.len();
        self.lower_checked(ps, line);
        if ps.ops.len() == before {
            ps.stack.lost_line();
        }
    }

    /// Lowers one line after the availability check; errors are reported, not returned.
    fn lower_checked(&mut self, ps: &mut PouState, line: &Line<'s>) {
        let mut buf = [0u8; 16];
        let Some(m) = upper(line.mnemonic.text, &mut buf) else {
            self.unknown(line.mnemonic);
            return;
        };
        if let Some(set) = mnemonics::family(m)
            && !self.cx.profile.has(set)
        {
            self.cx.report(
                Code::NotAvailable,
                line.mnemonic,
                format!(
                    "`{m}` is not available on the {}: it has no {}",
                    self.cx.profile.model,
                    set.describe()
                ),
                Some(mnemonics::instead(set).to_owned()),
            );
            return;
        }
        // Errors are already reported; lowering simply moves on to the next line.
        let _ = self.instr(ps, m, line);
    }

    /// Reports an unknown mnemonic, or a known one that is not supported yet.
    pub(crate) fn unknown(&mut self, t: Tok<'_>) {
        let up = t.text.to_ascii_uppercase();
        if let Some(set) = mnemonics::family(&up) {
            self.cx.report(
                Code::Unsupported,
                t,
                format!("`{}` is not supported yet", clip(t.text)),
                Some(mnemonics::not_yet(set).into()),
            );
            return;
        }
        let help = mnemonics::closest(&up).map(|s| format!("did you mean `{s}`?"));
        self.cx.report(
            Code::UnknownMnemonic,
            t,
            format!("unknown instruction `{}`", clip(t.text)),
            help,
        );
    }

    /// Checks the kinds of a timer use (spec §4.4, §6.3 TC12).
    pub(crate) fn use_timer(&mut self, t: Tok<'_>, id: TimerId, kind: TimerKind) {
        let allowed = self.cx.profile.timer_kinds(id.0);
        if !allowed.contains(&kind) {
            let names: Vec<_> = allowed.iter().map(|&k| timer_mnemonic(k)).collect();
            self.cx.report(
                Code::TimerKindNumber,
                t,
                format!(
                    "{id} cannot be a {} timer on the {}",
                    timer_mnemonic(kind),
                    self.cx.profile.model
                ),
                Some(format!("{id} allows: {}", names.join(", "))),
            );
            return;
        }
        let span = self.cx.span(t);
        match self.timers.get(&id.0) {
            Some(&(k, first)) if k != kind => {
                self.cx.report(
                    Code::TimerKindConflict,
                    t,
                    format!(
                        "{id} is used as {} here but as {} on line {}",
                        timer_mnemonic(kind),
                        timer_mnemonic(k),
                        first.line
                    ),
                    Some("use one timer number per timer kind".into()),
                );
            }
            Some(_) => {}
            None => {
                self.timers.insert(id.0, (kind, span));
            }
        }
    }

    /// Checks the kinds of a counter use.
    pub(crate) fn use_counter(&mut self, t: Tok<'_>, id: CounterId, kind: CounterKind) {
        let span = self.cx.span(t);
        match self.counters.get(&id.0) {
            Some(&(k, first)) if k != kind => {
                self.cx.report(
                    Code::CounterKindConflict,
                    t,
                    format!(
                        "{id} is used as {} here but as {} on line {}",
                        counter_mnemonic(kind),
                        counter_mnemonic(k),
                        first.line
                    ),
                    Some("use one counter number per counter kind".into()),
                );
            }
            Some(_) => {}
            None => {
                self.counters.insert(id.0, (kind, span));
            }
        }
    }

    fn lower_pou(&mut self, id: PouId, src: &PouSrc<'s>) -> (PouState, Pou) {
        let start = match src.kind {
            PouKind::Subroutine(_) => 1,
            _ => 0,
        };
        let mut ps = PouState {
            id,
            kind: src.kind,
            ops: Vec::with_capacity(src.lines.len()),
            locs: Vec::with_capacity(src.lines.len()),
            label_ids: HashMap::new(),
            label_defs: Vec::new(),
            jumps: Vec::new(),
            fors: Vec::new(),
            scr: None,
            stack: StackCheck::new(start, 9),
        };
        self.cx.file = src.file;
        self.cx.locals = self.locals.get(id.index()).cloned();
        for line in &src.lines {
            self.lower_line(&mut ps, line);
        }
        self.finish_pou(&mut ps);
        let labels = ps
            .label_defs
            .iter()
            .map(|d| d.map_or(OpIdx(0), |(at, _)| at))
            .collect();
        let pou = Pou {
            name: src.name.clone(),
            kind: src.kind,
            ops: std::mem::take(&mut ps.ops),
            locs: std::mem::take(&mut ps.locs),
            labels,
        };
        (ps, pou)
    }

    /// End-of-POU checks: unclosed FOR and SCR.
    fn finish_pou(&mut self, ps: &mut PouState) {
        for (_, span) in std::mem::take(&mut ps.fors) {
            self.cx.diags.push(
                Diagnostic::new(Code::ForNext, span, "FOR", "FOR without NEXT")
                    .help("close the loop with NEXT in the same block"),
            );
        }
        if let Some(open) = ps.scr.take() {
            self.cx.diags.push(
                Diagnostic::new(Code::ScrNesting, open.span, "LSCR", "LSCR without SCRE")
                    .help("end the segment with SCRE in the same block"),
            );
        }
    }
}

/// Lowers every POU; returns the program (meaningful only without errors) and the diagnostics.
pub(crate) fn lower<'s>(
    srcs: &[PouSrc<'s>],
    mut cx: Cx<'s>,
    files: Vec<String>,
) -> (Program, Vec<Diagnostic>) {
    let mut subs = HashMap::new();
    let mut names = HashMap::new();
    for (i, p) in srcs.iter().enumerate() {
        let id = PouId::new(i);
        if let PouKind::Subroutine(n) = p.kind {
            subs.entry(n).or_insert(id);
        }
        names.entry(p.name.clone()).or_insert((id, p.kind));
    }
    cx.file = srcs.first().map_or(cx.file, |p| p.file);
    let locals = srcs
        .iter()
        .map(|p| Rc::new(Locals::build(p.decls.clone(), p.kind, &mut cx.diags)))
        .collect();
    let mut lw = Lowerer {
        cx,
        subs,
        names,
        timers: HashMap::new(),
        counters: HashMap::new(),
        edges: 0,
        scr_bits: HashMap::new(),
        mnemonic: Tok::default(),
        locals,
        pou_names: srcs.iter().map(|p| p.name.clone()).collect(),
        pou_spans: srcs.iter().map(|p| p.decl).collect(),
    };
    let mut states = Vec::with_capacity(srcs.len());
    let mut pous = Vec::with_capacity(srcs.len());
    for (i, src) in srcs.iter().enumerate() {
        let (ps, pou) = lw.lower_pou(PouId::new(i), src);
        states.push(ps);
        pous.push(pou);
    }
    // Jumps resolve only inside their POU; a label of another POU gets a sharper message.
    for ps in &states {
        for (n, span, text, at) in &ps.jumps {
            let def = ps.label_ids.get(n).and_then(|id| ps.label_defs[id.index()]);
            if let Some((target, label_span)) = def {
                let pou = &pous[ps.id.index()];
                if let Some((head, _)) = loop_entered_by(pou, at.index(), target.index()) {
                    let for_line = pou.locs.get(head).map_or(0, |l| l.line);
                    lw.cx.diags.push(
                        Diagnostic::new(
                            Code::JumpIntoLoop,
                            *span,
                            text,
                            format!(
                                "`JMP {n}` enters the FOR loop of line {for_line} at `LBL {n}` (line {})",
                                label_span.line
                            ),
                        )
                        .help("NEXT would run with no active FOR; jump to a label before the FOR or after its NEXT"),
                    );
                }
                continue;
            }
            let elsewhere = states.iter().find(|o| {
                o.id != ps.id
                    && o.label_ids
                        .get(n)
                        .is_some_and(|id| o.label_defs[id.index()].is_some())
            });
            let d = match elsewhere {
                Some(o) => Diagnostic::new(
                    Code::JumpAcrossBlocks,
                    *span,
                    text,
                    format!(
                        "label {n} is defined in block `{}`, not in this one",
                        srcs[o.id.index()].name
                    ),
                )
                .help("JMP may only target an LBL of the same block"),
                None => Diagnostic::new(
                    Code::MissingLabel,
                    *span,
                    text,
                    format!("label {n} is not defined"),
                )
                .help(format!("add `LBL {n}` to this block")),
            };
            lw.cx.diags.push(d);
        }
    }
    let profile = lw.cx.profile;
    let mut timers: Vec<_> = lw
        .timers
        .iter()
        .map(|(&n, &(kind, _))| TimerDecl {
            id: TimerId(n),
            kind,
            resolution: profile
                .timer_resolution(n, kind)
                .unwrap_or(stljit_core::profile::Resolution::Ms100),
        })
        .collect();
    timers.sort_by_key(|t| t.id);
    let mut counters: Vec<_> = lw
        .counters
        .iter()
        .map(|(&n, &(kind, _))| CounterDecl {
            id: CounterId(n),
            kind,
        })
        .collect();
    counters.sort_by_key(|c| c.id);
    let program = Program {
        profile: profile.id,
        pous,
        timers,
        counters,
        edges: vec![EdgeDecl { init: false }; lw.edges],
        logic_stack_depth: 9,
        files,
    };
    (program, lw.cx.diags)
}
