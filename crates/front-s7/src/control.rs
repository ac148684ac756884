//! Program control (spec §4.13): END/MEND/STOP/WDR, JMP/LBL, CALL/RET/CRET, FOR/NEXT and the SCR
//! instructions, with the block-structure checks they need.

use crate::classes::{BitClass, R};
use crate::lexer::{Line, Tok};
use crate::mnemonics::Flow;
use crate::names::unquote;
use crate::program::{Lowerer, OpenScr, PouState};
use crate::symbols::{PouRef, SymTarget};
use stljit_core::ir::{Op, PouKind};
use stljit_core::{LabelId, OpIdx, PouId, Width};
use stljit_source::Code;
use stljit_source::clip;

impl Lowerer<'_> {
    /// Rejects `what` inside an open SCR segment.
    fn not_in_scr(&mut self, ps: &PouState) -> R<()> {
        match &ps.scr {
            Some(open) => {
                let line = open.span.line;
                Err(self.cx.report(
                    Code::InScr,
                    self.mnemonic,
                    format!(
                        "`{}` is not allowed inside an SCR segment",
                        self.mnemonic.text
                    ),
                    Some(format!(
                        "the segment opened by LSCR on line {line} must be closed with SCRE first"
                    )),
                ))
            }
            None => Ok(()),
        }
    }

    fn only_in(&mut self, ps: &PouState, ok: bool, where_: &str) -> R<()> {
        if ok {
            return Ok(());
        }
        let kind = match ps.kind {
            PouKind::Main => "the main program",
            PouKind::Subroutine(_) => "a subroutine",
            PouKind::Interrupt(_) => "an interrupt routine",
        };
        Err(self.cx.report(
            Code::WrongBlock,
            self.mnemonic,
            format!("`{}` is not allowed in {kind}", self.mnemonic.text),
            Some(format!(
                "`{}` is allowed only in {where_}",
                self.mnemonic.text
            )),
        ))
    }

    /// Lowers the program-control instruction `m` (upper case) of routine `flow`.
    pub(crate) fn control(
        &mut self,
        ps: &mut PouState,
        flow: Flow,
        m: &str,
        line: &Line<'_>,
    ) -> R<()> {
        let o = line.ops;
        let main = ps.kind == PouKind::Main;
        let op = match flow {
            Flow::End => {
                self.arity(line, 0, 0)?;
                self.only_in(ps, main, "the main program")?;
                if m == "END" {
                    self.not_in_scr(ps)?;
                }
                Op::End {
                    conditional: m == "END",
                }
            }
            Flow::Stop => {
                self.arity(line, 0, 0)?;
                Op::Stop
            }
            Flow::WatchdogReset => {
                self.arity(line, 0, 0)?;
                Op::Wdr
            }
            Flow::Return => {
                self.arity(line, 0, 0)?;
                self.only_in(
                    ps,
                    matches!(ps.kind, PouKind::Subroutine(_)),
                    "a subroutine",
                )?;
                Op::Return {
                    conditional: m == "CRET",
                }
            }
            Flow::ReturnFromInterrupt => {
                self.arity(line, 0, 0)?;
                self.only_in(
                    ps,
                    matches!(ps.kind, PouKind::Interrupt(_)),
                    "an interrupt routine",
                )?;
                Op::Return {
                    conditional: m == "CRETI",
                }
            }
            Flow::Jump => {
                let (n, id) = self.label_operand(ps, line)?;
                let span = self.cx.span(o[0]);
                ps.jumps
                    .push((n, span, o[0].text.to_owned(), ps.next_idx()));
                Op::Jump(id)
            }
            Flow::Label => {
                let (n, id) = self.label_operand(ps, line)?;
                let span = self.cx.span(o[0]);
                if let Some((_, first)) = ps.label_defs[id.index()] {
                    return Err(self.cx.report(
                        Code::DuplicateLabel,
                        o[0],
                        format!("label {n} is defined twice in this block"),
                        Some(format!("first defined on line {}", first.line)),
                    ));
                }
                ps.label_defs[id.index()] = Some((ps.next_idx(), span));
                Op::Label(id)
            }
            Flow::Call => {
                let ops = crate::lexer::all_operands(line);
                if ops.is_empty() {
                    return self.arity(line, 1, 1);
                }
                let callee = self.call_target(ops[0])?;
                self.call_op(callee, line, &ops[1..])?
            }
            Flow::For => {
                self.arity(line, 3, 3)?;
                self.not_in_scr(ps)?;
                let w = Width::Word;
                let index = self.cx.value(o[0], crate::classes::Val::output(w));
                let init = self.cx.value(o[1], crate::classes::Val::input(w));
                let limit = self.cx.value(o[2], crate::classes::Val::input(w));
                let (index, init, limit) = (index?, init?, limit?);
                let max = usize::from(self.cx.profile.max_for_depth);
                if ps.fors.len() >= max {
                    self.cx.report(
                        Code::ForDepth,
                        self.mnemonic,
                        format!("FOR loops nested deeper than {max}"),
                        Some(format!(
                            "the {} allows {max} nested FOR loops",
                            self.cx.profile.model
                        )),
                    );
                }
                let span = self.cx.span(self.mnemonic);
                ps.fors.push((ps.next_idx(), span));
                Op::For {
                    index,
                    init,
                    limit,
                    next: OpIdx(0),
                }
            }
            Flow::Next => {
                self.arity(line, 0, 0)?;
                self.not_in_scr(ps)?;
                let Some((head, _)) = ps.fors.pop() else {
                    return Err(self.cx.report(
                        Code::ForNext,
                        self.mnemonic,
                        "NEXT without FOR".to_owned(),
                        Some("every NEXT closes the nearest open FOR of the same block".into()),
                    ));
                };
                let here = ps.next_idx();
                if let Some(Op::For { next, .. }) = ps.ops.get_mut(head.index()) {
                    *next = here;
                }
                Op::Next { head }
            }
            Flow::ScrBegin => {
                self.arity(line, 1, 1)?;
                let bit = self.cx.bit(o[0], BitClass::Seq)?;
                let span = self.cx.span(self.mnemonic);
                if let Some(open) = &ps.scr {
                    let l = open.span.line;
                    return Err(self.cx.report(
                        Code::ScrNesting,
                        self.mnemonic,
                        "LSCR inside an open SCR segment".to_owned(),
                        Some(format!(
                            "close the segment opened on line {l} with SCRE first"
                        )),
                    ));
                }
                match self.scr_bits.get(&bit) {
                    Some(&(pou, first)) if pou != ps.id => {
                        self.cx.report(
                            Code::ScrBitShared,
                            o[0],
                            format!(
                                "`{}` is already a segment flag in another block",
                                clip(o[0].text)
                            ),
                            Some(format!("first used on {}", self.cx.place(first))),
                        );
                    }
                    Some(_) => {}
                    None => {
                        self.scr_bits.insert(bit, (ps.id, self.cx.span(o[0])));
                    }
                }
                ps.scr = Some(OpenScr {
                    at: ps.next_idx(),
                    bit,
                    span,
                    cond_ends: Vec::new(),
                });
                Op::ScrBegin { bit }
            }
            Flow::ScrTransition => {
                self.arity(line, 1, 1)?;
                let to = self.cx.bit(o[0], BitClass::Seq)?;
                let from = self.open_scr(ps)?;
                Op::ScrTransition { to, from }
            }
            Flow::ScrCondEnd => {
                self.arity(line, 0, 0)?;
                self.open_scr(ps)?;
                let here = ps.next_idx();
                if let Some(open) = &mut ps.scr {
                    open.cond_ends.push(here);
                }
                Op::ScrCondEnd { end: OpIdx(0) }
            }
            Flow::ScrEnd => {
                self.arity(line, 0, 0)?;
                self.open_scr(ps)?;
                let here = ps.next_idx();
                if let Some(open) = ps.scr.take() {
                    let _ = open.at;
                    for i in open.cond_ends {
                        if let Some(Op::ScrCondEnd { end }) = ps.ops.get_mut(i.index()) {
                            *end = here;
                        }
                    }
                }
                Op::ScrEnd
            }
        };
        self.emit(ps, op);
        Ok(())
    }

    /// The label number operand of `JMP`/`LBL` (outside any SCR segment) and its label id.
    fn label_operand(&mut self, ps: &mut PouState, line: &Line<'_>) -> R<(u32, LabelId)> {
        self.arity(line, 1, 1)?;
        self.not_in_scr(ps)?;
        let max = u32::from(self.cx.profile.max_label);
        let n = self
            .cx
            .number(line.ops[0], 0, max, "label", Code::NumberRange)?;
        Ok((n, ps.label(n)))
    }

    /// The S bit of the open segment, or an error for SCRT/CSCRE/SCRE outside one.
    fn open_scr(&mut self, ps: &PouState) -> R<stljit_core::ir::BitLoc> {
        match &ps.scr {
            Some(open) => Ok(open.bit),
            None => Err(self.cx.report(
                Code::ScrNesting,
                self.mnemonic,
                format!("`{}` outside an SCR segment", self.mnemonic.text),
                Some("SCRT, CSCRE and SCRE belong between LSCR and SCRE".into()),
            )),
        }
    }

    /// Resolves a CALL target: a number, `SBRn`, a block name, a symbol naming `SBRn`, or
    /// `SBR_n`.
    fn call_target(&mut self, t: Tok<'_>) -> R<PouId> {
        let text = unquote(t.text).unwrap_or(t.text);
        let upper = text.to_ascii_uppercase();
        let number = text.parse::<u32>().ok().or_else(|| {
            upper
                .strip_prefix("SBR")
                .filter(|d| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit()))
                .and_then(|d| d.parse::<u32>().ok())
        });
        let number = match number {
            Some(n) => Some(n),
            None => match self.names.get(text) {
                Some(&(id, PouKind::Subroutine(_))) => return Ok(id),
                Some(&(_, _)) => {
                    return Err(self.cx.report(
                        Code::UnknownSubroutine,
                        t,
                        format!("`{}` is not a subroutine", clip(text)),
                        Some("CALL takes a subroutine (SBRn or its name)".into()),
                    ));
                }
                None => match self.cx.symbols.and_then(|s| s.get(text)) {
                    Some(SymTarget::Pou(PouRef::Subroutine(n))) => Some(u32::from(*n)),
                    // `SBR_n`: MicroWIN's default symbol of SBRn (s7-200-more §1.4).
                    _ => upper
                        .strip_prefix("SBR_")
                        .filter(|d| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit()))
                        .and_then(|d| d.parse::<u32>().ok()),
                },
            },
        };
        let max = u32::from(self.cx.profile.max_subroutine);
        if let Some(n) = number {
            if n > max {
                return Err(self.cx.report(
                    Code::NumberRange,
                    t,
                    format!("subroutine number {n} is out of range"),
                    Some(format!("allowed: SBR0 - SBR{max}")),
                ));
            }
            if let Some(&id) = u16::try_from(n).ok().and_then(|n| self.subs.get(&n)) {
                return Ok(id);
            }
        }
        let mut known: Vec<String> = self
            .names
            .iter()
            .filter_map(|(name, &(_, k))| match k {
                PouKind::Subroutine(n) if *name == format!("SBR{n}") => Some(name.clone()),
                PouKind::Subroutine(n) => Some(format!("{name} (SBR{n})")),
                _ => None,
            })
            .collect();
        known.sort();
        known.truncate(8);
        let help = if known.is_empty() {
            "no subroutine is defined".to_owned()
        } else {
            format!("defined: {}", known.join(", "))
        };
        Err(self.cx.report(
            Code::UnknownSubroutine,
            t,
            format!("unknown subroutine `{}`", clip(text)),
            Some(help),
        ))
    }
}
