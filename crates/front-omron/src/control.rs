//! Program control and regions of one program unit (omron-cp.md §2.7–§2.9, §3.4): IL/ILC, the
//! jumps, END, the subroutine region (SBN…RET, SBS), FOR/NEXT/BREAK, and which lines run at all
//! (W002 after END, W028 between the subroutine region and END). Checks E001, E022/W022, E023,
//! E024, E026, E027, E029; a pair left open in its POU goes to `tasks` (E025 if its partner is
//! in another unit). Step areas and block programs are in `regions`.

use crate::circuit::Class;
use crate::lexer::Line;
use crate::lower::{Lowerer, PouBuild};
use crate::mnemonics::{self, Flow};
use crate::regions::{OpenBlock, StepArea};
use crate::resolve::Reported;
use crate::tasks::{Pair, UnitKind};
use std::collections::HashMap;
use stljit_core::ir::{Contact, Loc, Op, Operand, Pou, PouKind};
use stljit_core::omron::SystemBit;
use stljit_core::{Area, LabelId, OpIdx, PouId};
use stljit_source::{Code, Span};

/// Where in the task the current line is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Region {
    /// The main program.
    #[default]
    Main,
    /// Inside `SBN n` … `RET`.
    Subroutine,
    /// After a `RET`, before the next SBN or END.
    AfterSubroutines,
    /// After the first END (with its line).
    AfterEnd(u32),
}

/// A jump waiting for its JME.
#[derive(Clone, Debug)]
struct PendingJump {
    number: u32,
    /// The jump instruction as written (`CJP(510)`).
    what: String,
    span: Span,
    interlock: Option<u32>,
    /// The block program it is in (its JME must be in the same one).
    block: Option<u32>,
}

/// Where a JME is: what a backward jump to it would have to stay inside.
#[derive(Clone, Debug)]
struct JmeSite {
    span: Span,
    interlock: Option<u32>,
    block: Option<u32>,
    /// The FOR loops around it (their `Op::For` indices).
    loops: Vec<usize>,
}

/// Region, interlock and jump state.
#[derive(Debug, Default)]
pub(crate) struct Control {
    /// The POU receiving ops (index into `Lowerer::pous`).
    pub(crate) pou: usize,
    region: Region,
    /// The open IL: its line and region id.
    il: Option<(Span, u32)>,
    /// Interlock regions opened so far (ids).
    il_regions: u32,
    /// Labels of jump numbers of the current POU.
    labels: HashMap<u32, LabelId>,
    /// JME numbers defined in the current POU, with where they are.
    defined: HashMap<u32, JmeSite>,
    jumps: Vec<PendingJump>,
    /// Open JMP0s: their labels, where they are and their interlock region.
    jmp0: Vec<(LabelId, Span, Option<u32>)>,
    /// The open FOR loops, innermost last.
    loops: Vec<OpenLoop>,
    /// The open step area.
    pub(crate) step: Option<StepArea>,
    /// The open block program.
    pub(crate) block: Option<OpenBlock>,
    /// Block programs opened so far (ids).
    pub(crate) blocks_opened: u32,
    /// Block program numbers in use, with their BPRG line.
    pub(crate) block_numbers: HashMap<u32, Span>,
}

/// A FOR(503) waiting for its NEXT(504).
#[derive(Clone, Debug)]
struct OpenLoop {
    /// The index of its `Op::For`.
    head: usize,
    /// Where BREAK(514) goes: just after the NEXT.
    exit: LabelId,
    span: Span,
    /// The jump numbers pending when the loop opened: their JME may not be inside the loop
    /// (a jump into a FOR body would reach NEXT with no FOR active).
    outside_jumps: Vec<u32>,
    /// Whether a JMP0 was pending when the loop opened: no JME0 may then be inside the loop.
    outside_jmp0: bool,
}

impl Lowerer<'_> {
    fn head_span(&self, l: &Line) -> Span {
        self.cx.span(&l.head)
    }

    fn report_span(&mut self, code: Code, span: Span, message: String) {
        let d = stljit_source::Diagnostic::new(code, span, "", message);
        self.cx.diags.push(d);
    }

    /// Whether the line is lowered at all (W002 after END, W028 after the subroutines).
    pub(crate) fn admit(&mut self, l: &Line) -> bool {
        let line = l.line;
        match self.control.region {
            Region::AfterEnd(end) => {
                self.at_head(
                    l,
                    Code::OmrAfterEnd,
                    format!(
                        "unreachable — execution of {} stops at the first END(001) (line {end})",
                        self.unit_name()
                    ),
                );
                false
            }
            Region::AfterSubroutines if !matches!(l.mnemonic.as_str(), "SBN" | "END") => {
                let _ = line;
                self.at_head(
                    l,
                    Code::OmrAfterSubroutines,
                    "never executed — code after the subroutine region".into(),
                );
                false
            }
            _ => true,
        }
    }

    /// Closes the current POU's regions: open IL (E022), jumps without JME (E023), JMP0
    /// without JME0 (E024), FOR without NEXT (E026) — each E025 instead if its partner is in
    /// another unit (decided at the end, `tasks`).
    fn close_pou(&mut self) {
        if let Some((span, _)) = self.control.il.take() {
            let msg = format!(
                "line {}: IL(002) is not closed by ILC(003) in {}",
                span.line,
                self.unit_name()
            );
            let what = "IL(002)".into();
            self.dangle(
                Pair::Interlock,
                true,
                span,
                what,
                Some((Code::OmrInterlock, msg)),
            );
        }
        for j in std::mem::take(&mut self.control.jumps) {
            let msg = format!(
                "line {}: JME {} not found after this jump",
                j.span.line, j.number
            );
            let (pair, what) = (Pair::Jump(j.number), format!("{} {}", j.what, j.number));
            self.dangle(pair, true, j.span, what, Some((Code::OmrJump, msg)));
        }
        for (_, span, _) in std::mem::take(&mut self.control.jmp0) {
            let msg = format!("line {}: JMP0(515) has no JME0(516)", span.line);
            let what = "JMP0(515)".into();
            self.dangle(Pair::Jmp0, true, span, what, Some((Code::OmrJmp0, msg)));
        }
        for lp in std::mem::take(&mut self.control.loops) {
            let msg = format!(
                "line {}: FOR(503) is not closed by NEXT(504) in this program",
                lp.span.line
            );
            let what = "FOR(503)".into();
            self.dangle(
                Pair::Loop,
                true,
                lp.span,
                what,
                Some((Code::OmrInRegion, msg)),
            );
        }
        self.close_regions();
        self.control.labels.clear();
        self.control.defined.clear();
        self.circuit.reset();
    }

    /// The label of jump number `n` in the current POU.
    fn jump_label(&mut self, n: u32) -> LabelId {
        if let Some(l) = self.control.labels.get(&n) {
            return *l;
        }
        let l = self.new_label();
        self.control.labels.insert(n, l);
        l
    }

    fn interlock_id(&self) -> Option<u32> {
        self.control.il.map(|(_, id)| id)
    }

    /// Whether an IL(002) is open.
    pub(crate) fn control_in_interlock(&self) -> bool {
        self.control.il.is_some()
    }

    /// Whether the line is in a subroutine (SBN … RET).
    pub(crate) fn in_subroutine(&self) -> bool {
        self.control.region == Region::Subroutine
    }

    /// A jump to a JME already placed (`site`): only with `allow_backward_jumps` (E023), and
    /// only within the JME's interlock region and block program (E023) and into no FOR loop
    /// (E026; the jump would reach NEXT with no FOR active).
    fn backward_jump(&mut self, l: &Line, n: u32, site: &JmeSite) -> Result<(), Reported> {
        if !self.cx.options.allow_backward_jumps {
            let msg = format!("JME {n} is before this jump; backward jumps are not allowed");
            let help = "a backward jump can loop for ever; the front-end option allow_backward_jumps (--allow-backward-jumps) admits it";
            return Err(self.cx.report_help(
                Code::OmrJump,
                &l.head,
                format!("line {}: {msg}", l.line),
                help,
            ));
        }
        let open: Vec<usize> = self.control.loops.iter().map(|lp| lp.head).collect();
        let (code, region) = if site.interlock != self.interlock_id() {
            (Code::OmrJump, "an IL(002)–ILC(003) region")
        } else if site.block != self.block_id() {
            (Code::OmrJump, "a BPRG(096)–BEND(801) block program")
        } else if !site.loops.iter().all(|h| open.contains(h)) {
            (Code::OmrInRegion, "a FOR(503)–NEXT(504) loop")
        } else {
            return Ok(());
        };
        let msg = format!(
            "jump {n} back to JME at line {} crosses the boundary of {region}",
            site.span.line
        );
        Err(self.at_head(l, code, msg))
    }

    /// BEND of block `id`: its jumps still waiting for a JME never get one (E023).
    pub(crate) fn leave_block(&mut self, id: u32) {
        let (mine, rest): (Vec<_>, Vec<_>) = std::mem::take(&mut self.control.jumps)
            .into_iter()
            .partition(|j| j.block == Some(id));
        self.control.jumps = rest;
        for j in mine {
            self.report_span(
                Code::OmrJump,
                j.span,
                format!(
                    "line {}: JME {} is not in this block program; a jump inside BPRG(096)–BEND(801) pairs with a JME of the same block",
                    j.span.line, j.number
                ),
            );
        }
    }

    /// Lowers a program-control instruction.
    pub(crate) fn flow(&mut self, l: &Line, flow: Flow) -> Result<(), Reported> {
        let max_jump = u32::from(self.cx.profile.omron.max_jump);
        let max_sub = u32::from(self.cx.profile.max_subroutine);
        match flow {
            Flow::Il => {
                self.operands(l, 0)?;
                self.class(l, Class::Output);
                if self.control.il.is_some() {
                    self.at_head(l, Code::OmrSharedIlc, "several IL(002) share one ILC(003); the first interlocked one holds up to the ILC".into());
                } else {
                    self.control.il_regions += 1;
                    self.control.il = Some((self.head_span(l), self.control.il_regions));
                }
                self.emit(Op::Interlock);
            }
            Flow::Ilc => {
                self.operands(l, 0)?;
                self.class(l, Class::Unconditional);
                if self.control.il.take().is_none() {
                    let span = self.head_span(l);
                    let msg = format!("line {}: ILC(003) has no open IL(002)", l.line);
                    let plain = Some((Code::OmrInterlock, msg));
                    self.dangle(Pair::Interlock, false, span, "ILC(003)".into(), plain);
                } else {
                    self.emit(Op::InterlockEnd);
                }
            }
            Flow::Jmp | Flow::Cjp | Flow::Cjpn => {
                let ops = self.operands(l, 1)?;
                let n = self.cx.number(&ops[0], max_jump, "jump number")?;
                self.class(l, Class::Output);
                if let Some(site) = self.control.defined.get(&n).cloned() {
                    self.backward_jump(l, n, &site)?;
                }
                let label = self.jump_label(n);
                let span = self.head_span(l);
                let interlock = self.interlock_id();
                let what = mnemonics::with_code(&l.mnemonic);
                let block = self.block_id();
                if !self.control.defined.contains_key(&n) {
                    self.control.jumps.push(PendingJump {
                        number: n,
                        what,
                        span,
                        interlock,
                        block,
                    });
                }
                // JMP and CJPN jump when the condition is OFF, CJP when it is ON.
                if flow == Flow::Cjp {
                    self.emit(Op::Jump(label));
                } else {
                    self.emit(Op::Not);
                    self.emit(Op::Jump(label));
                    self.emit(Op::Not);
                }
            }
            Flow::Jme => {
                let ops = self.operands(l, 1)?;
                let n = self.cx.number(&ops[0], max_jump, "jump number")?;
                self.class(l, Class::Unconditional);
                if self.control.defined.contains_key(&n) {
                    return Err(self.at_head(
                        l,
                        Code::OmrJump,
                        format!("jump number {n} defined twice"),
                    ));
                }
                if self
                    .control
                    .loops
                    .iter()
                    .any(|lp| lp.outside_jumps.contains(&n))
                {
                    return Err(self.at_head(
                        l,
                        Code::OmrInRegion,
                        format!(
                            "JME {n} is inside a FOR(503)–NEXT(504) loop its jump is outside of"
                        ),
                    ));
                }
                let here = self.interlock_id();
                let site = JmeSite {
                    span: self.head_span(l),
                    interlock: here,
                    block: self.block_id(),
                    loops: self.control.loops.iter().map(|lp| lp.head).collect(),
                };
                self.control.defined.insert(n, site);
                let span = self.head_span(l);
                self.dangle(Pair::Jump(n), false, span, format!("JME(005) {n}"), None);
                let (mine, rest): (Vec<_>, Vec<_>) = std::mem::take(&mut self.control.jumps)
                    .into_iter()
                    .partition(|j| j.number == n);
                self.control.jumps = rest;
                let block = self.block_id();
                for j in &mine {
                    let region = if j.interlock != here {
                        "an IL(002)–ILC(003) region"
                    } else if j.block != block {
                        "a BPRG(096)–BEND(801) block program"
                    } else {
                        continue;
                    };
                    self.report_span(
                        Code::OmrJump,
                        j.span,
                        format!(
                            "line {}: jump {n} crosses the boundary of {region}",
                            j.span.line
                        ),
                    );
                }
                let label = self.jump_label(n);
                self.place(label);
            }
            Flow::Jmp0 => {
                self.operands(l, 0)?;
                self.class(l, Class::Output);
                let label = self.new_label();
                let span = self.head_span(l);
                let interlock = self.interlock_id();
                self.control.jmp0.push((label, span, interlock));
                self.emit(Op::Not);
                self.emit(Op::Jump(label));
                self.emit(Op::Not);
            }
            Flow::Jme0 => {
                self.operands(l, 0)?;
                self.class(l, Class::Unconditional);
                if self.control.jmp0.is_empty() {
                    let span = self.head_span(l);
                    self.dangle(Pair::Jmp0, false, span, "JME0(516)".into(), None);
                }
                if self.control.loops.iter().any(|lp| lp.outside_jmp0) {
                    self.at_head(
                        l,
                        Code::OmrInRegion,
                        "JME0(516) is inside a FOR(503)–NEXT(504) loop its JMP0(515) is outside of"
                            .into(),
                    );
                }
                let here = self.interlock_id();
                for (label, span, interlock) in std::mem::take(&mut self.control.jmp0) {
                    if interlock != here {
                        self.report_span(
                            Code::OmrJump,
                            span,
                            format!(
                                "line {}: JMP0(515) crosses the boundary of an IL(002)–ILC(003) region",
                                span.line
                            ),
                        );
                    }
                    self.place(label);
                }
            }
            Flow::End => {
                self.operands(l, 0)?;
                self.class(l, Class::Unconditional);
                if self.control.region == Region::Subroutine {
                    self.at_head(
                        l,
                        Code::OmrSubroutine,
                        "SBN(092) is not closed by RET(093) before END(001)".into(),
                    );
                }
                self.close_pou();
                self.control.pou = self.unit_body();
                self.emit(Op::End { conditional: false });
                self.control.region = Region::AfterEnd(l.line);
            }
            Flow::Sbn => {
                let ops = self.operands(l, 1)?;
                let n = self.cx.number(&ops[0], max_sub, "subroutine number")?;
                self.class(l, Class::Unconditional);
                if self.control.region == Region::Subroutine {
                    self.at_head(
                        l,
                        Code::OmrSubroutine,
                        "SBN(092) cannot be placed inside SBN(092)–RET(093) (nested)".into(),
                    );
                }
                if !self.control.jmp0.is_empty() {
                    self.at_head(
                        l,
                        Code::OmrSubroutine,
                        "SBN(092) cannot be placed inside JMP0(515)–JME0(516)".into(),
                    );
                }
                self.close_pou();
                if self.project.subs.contains_key(&n) {
                    self.at_head(
                        l,
                        Code::OmrSubroutine,
                        format!("subroutine {n} is defined twice"),
                    );
                }
                let id = self.pous.len();
                let span = self.head_span(l);
                self.project.subs.entry(n).or_insert((id, span));
                self.pous.push(PouBuild {
                    pou: Pou {
                        name: format!("SBN{n}"),
                        kind: PouKind::Subroutine(n as u16),
                        ops: Vec::new(),
                        locs: Vec::new(),
                        labels: Vec::new(),
                    },
                    unit: self.project.unit(),
                });
                self.control.pou = self.pous.len() - 1;
                self.control.region = Region::Subroutine;
            }
            Flow::Ret => {
                self.operands(l, 0)?;
                self.class(l, Class::Unconditional);
                if self.control.region != Region::Subroutine {
                    return Err(self.at_head(
                        l,
                        Code::OmrSubroutine,
                        "RET(093) has no SBN(092)".into(),
                    ));
                }
                self.emit(Op::Return { conditional: false });
                self.close_pou();
                self.control.pou = self.unit_body();
                self.control.region = Region::AfterSubroutines;
            }
            Flow::For => {
                let ops = self.operands(l, 1)?;
                let count = self.cx.word(&ops[0], 1, false)?;
                self.class(l, Class::Unconditional);
                let depth = self.control.loops.len();
                if depth >= usize::from(self.cx.profile.max_for_depth) {
                    return Err(self.at_head(
                        l,
                        Code::OmrInRegion,
                        format!(
                            "FOR(503) loops nest at most {} deep",
                            self.cx.profile.max_for_depth
                        ),
                    ));
                }
                // FOR has no execution condition: its power flow is P_On (under an active
                // interlock the loop is skipped with everything else). The loop counter is a
                // private word of the call level's L frame, one per nesting depth.
                self.emit(Op::Load(Contact::Bit {
                    bit: SystemBit::On.bit_loc(),
                    negated: false,
                }));
                let pou = self.control.pou;
                let head = self.pous[pou].pou.ops.len();
                self.emit(Op::For {
                    index: Operand::Mem(Loc {
                        area: Area::L,
                        offset: 2 * depth as u32,
                    }),
                    init: Operand::Const(1),
                    limit: count,
                    next: OpIdx::new(head),
                });
                let exit = self.new_label();
                let span = self.head_span(l);
                let outside_jumps = self.control.jumps.iter().map(|j| j.number).collect();
                let outside_jmp0 = !self.control.jmp0.is_empty();
                self.control.loops.push(OpenLoop {
                    head,
                    exit,
                    span,
                    outside_jumps,
                    outside_jmp0,
                });
            }
            Flow::Next => {
                self.operands(l, 0)?;
                self.class(l, Class::Unconditional);
                let Some(lp) = self.control.loops.pop() else {
                    let span = self.head_span(l);
                    let msg = format!("line {}: NEXT(504) has no FOR(503)", l.line);
                    let plain = Some((Code::OmrOutsideRegion, msg));
                    self.dangle(Pair::Loop, false, span, "NEXT(504)".into(), plain);
                    return Err(Reported);
                };
                let pou = self.control.pou;
                let at = self.pous[pou].pou.ops.len();
                if let Some(Op::For { next, .. }) = self.pous[pou].pou.ops.get_mut(lp.head) {
                    *next = OpIdx::new(at);
                }
                self.emit(Op::Next {
                    head: OpIdx::new(lp.head),
                });
                self.place(lp.exit);
            }
            Flow::Break => {
                self.operands(l, 0)?;
                self.class(l, Class::Output);
                let Some(exit) = self.control.loops.last().map(|lp| lp.exit) else {
                    return Err(self.at_head(
                        l,
                        Code::OmrOutsideRegion,
                        "BREAK(514) is only allowed inside FOR(503)–NEXT(504)".into(),
                    ));
                };
                // The rest of the pass is skipped and the loop ends: a jump past NEXT.
                self.emit(Op::Jump(exit));
            }
            Flow::Step => self.step(l)?,
            Flow::Snxt => self.snxt(l)?,
            Flow::Bprg => self.bprg(l)?,
            Flow::Bend => self.bend(l)?,
            Flow::Sbs => {
                let ops = self.operands(l, 1)?;
                let n = self.cx.number(&ops[0], max_sub, "subroutine number")?;
                self.class(l, Class::Output);
                let span = self.head_span(l);
                let options = l.options;
                self.edged(options, |s| {
                    let pou = s.control.pou;
                    let at = s.pous[pou].pou.ops.len();
                    s.project.calls.push((pou, at, n, span));
                    s.emit(Op::Call(PouId(0)));
                });
            }
        }
        Ok(())
    }

    /// End of a unit (at `at`: the next directive, or the end of the project): E001 without
    /// END (a function-block body needs none), an SBN left open.
    pub(crate) fn finish_unit(&mut self, at: Span) {
        if matches!(self.control.region, Region::AfterEnd(_)) {
            return;
        }
        if self.control.region == Region::Subroutine {
            self.report_span(
                Code::OmrSubroutine,
                at,
                format!("line {}: SBN(092) is not closed by RET(093)", at.line),
            );
        }
        self.close_pou();
        if !matches!(self.unit_kind(), UnitKind::FunctionBlock(_)) {
            let msg = format!(
                "{}: program has no END(001) — the CPU would refuse to run it (\"no END\" program error)",
                self.unit_name()
            );
            self.report_span(Code::OmrNoEnd, at, msg);
        }
    }
}
