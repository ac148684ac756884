//! Step areas (STEP(008)/SNXT(009)) and block programs (BPRG(096)/BEND(801)) of omron-cp.md
//! §2.9, their semantics (docs/semantics.md "Step areas and block programs") and the region
//! checks: which instructions a step area, a block program or a subroutine may not hold
//! (E026, E029 for SBN), which ones only a block program may (E027).
//!
//! Lowering (existing ops only):
//! * `STEP B`: `InterlockEnd; Load(B); [And(saved)]; Interlock; Pop` — the gate is B, so the
//!   step's instructions run while B is ON and are interlocked (OUT OFF, timers reset, the
//!   rest held: `GatePolicy::OmronInterlock`) while it is OFF. Inside IL–ILC the first STEP of
//!   the area first saves the interlock's gate in a private bit (`Load(P_On); Assign(saved);
//!   Pop`: `Assign` stores `S0 AND gate`) and every step ANDs it in.
//! * `STEP` (no operand): `InterlockEnd`, then inside IL–ILC `Load(saved); Interlock; Pop`
//!   (the enclosing interlock stays as it was).
//! * `SNXT B`: `SetRange(current step bit, 0); SetRange(B, 1)` on the power flow.
//! * `BPRG N`: `Not; Jump(after BEND); Not` (EC OFF: the block is not executed, everything in
//!   it holds); `BEND`: the label.

use crate::circuit::Class;
use crate::lexer::Line;
use crate::lower::Lowerer;
use crate::mnemonics::{self, BLOCK_ONLY, Group, NOT_IN_BLOCKS, NOT_IN_STEPS};
use crate::resolve::Reported;
use crate::tasks::Pair;
use stljit_core::ir::{BitLoc, Contact, Op, Operand};
use stljit_core::omron::SystemBit;
use stljit_core::{Area, LabelId};
use stljit_source::{Code, Span, clip};

/// An open step area.
#[derive(Clone, Debug)]
pub(crate) struct StepArea {
    /// The step being lowered: its control bit and its STEP line.
    current: (BitLoc, Span),
    /// The area is inside IL–ILC: the interlock's gate is saved and ANDed into every step.
    in_interlock: bool,
}

/// An open block program.
#[derive(Clone, Debug)]
pub(crate) struct OpenBlock {
    /// Its id (jumps inside pair with a JME of the same block).
    pub(crate) id: u32,
    /// Where BPRG's jump goes: after BEND.
    end: LabelId,
    span: Span,
}

/// The region names of the messages.
const STEP_REGION: &str = "STEP(008)–SNXT(009)";
const BLOCK_REGION: &str = "BPRG(096)–BEND(801)";

impl Lowerer<'_> {
    /// The private bit holding the gate of the interlock a step area is in: bit 0 of the first
    /// L byte after the FOR counters (a front-end word no operand names; step areas are only in
    /// the main program, call level 0).
    fn saved_interlock(&self) -> BitLoc {
        BitLoc {
            area: Area::L,
            byte: 2 * u32::from(self.cx.profile.max_for_depth),
            bit: 0,
        }
    }

    /// The open block program's id, if any.
    pub(crate) fn block_id(&self) -> Option<u32> {
        self.control.block.as_ref().map(|b| b.id)
    }

    /// E026/E027/E029 for an instruction its region does not allow; the line is then skipped.
    pub(crate) fn allowed_in_region(&mut self, l: &Line) -> bool {
        let name = l.mnemonic.as_str();
        if name == "END" {
            // END inside a region ends the program with the region open: closing the POU
            // reports the region as not closed, at its opening line.
            return true;
        }
        let block = self.control.block.as_ref().map(|b| b.span);
        let step = self.control.step.as_ref().map(|s| s.current.1);
        let (code, message) = if let Some((n, c)) = BLOCK_ONLY.iter().find(|(n, _)| *n == name) {
            match block {
                Some(_) => (
                    Code::OmrInstruction,
                    format!("{n}({c:03}) is not supported yet"),
                ),
                None => (
                    Code::OmrOutsideRegion,
                    format!("{n}({c:03}) is only allowed inside {BLOCK_REGION}"),
                ),
            }
        } else if let Some(open) = step.filter(|_| NOT_IN_STEPS.contains(&name)) {
            self.misplaced(l, STEP_REGION, open)
        } else if let Some(open) = block.filter(|_| self.not_in_blocks(l)) {
            self.misplaced(l, BLOCK_REGION, open)
        } else if matches!(name, "STEP" | "SNXT") && self.in_subroutine() {
            let what = mnemonics::with_code(name);
            (
                Code::OmrInRegion,
                format!("{what} is not allowed inside SBN(092)–RET(093)"),
            )
        } else {
            return true;
        };
        self.at_head(l, code, message);
        self.circuit.recover();
        false
    }

    /// Whether a block program may not hold the instruction of `l`.
    fn not_in_blocks(&self, l: &Line) -> bool {
        let timer = matches!(
            mnemonics::lookup(&l.mnemonic).map(|m| m.group),
            Some(Group::Timer(_))
        );
        NOT_IN_BLOCKS.contains(&l.mnemonic.as_str()) || timer || l.options.edge.is_some()
    }

    /// The diagnostic of an instruction inside a region that forbids it (SBN: E029).
    fn misplaced(&self, l: &Line, region: &str, open: Span) -> (Code, String) {
        let what = format!("{}{}", l.options.text(), mnemonics::with_code(&l.mnemonic));
        if l.mnemonic == "SBN" {
            let msg = format!(
                "SBN(092) cannot be placed inside {region} (opened at line {})",
                open.line
            );
            return (Code::OmrSubroutine, msg);
        }
        let msg = format!(
            "{what} is not allowed inside {region} (opened at line {})",
            open.line
        );
        (Code::OmrInRegion, msg)
    }

    /// `STEP B` / `STEP`.
    pub(crate) fn step(&mut self, l: &Line) -> Result<(), Reported> {
        if l.operands.is_empty() {
            return self.step_area_end(l);
        }
        let ops = self.operands(l, 1)?;
        let bit = self.cx.bit(&ops[0], false)?;
        self.class(l, Class::Unconditional);
        let span = self.cx.span(&l.head);
        let saved = self.saved_interlock();
        let in_interlock = match &self.control.step {
            Some(area) => area.in_interlock,
            None => {
                let in_interlock = self.control_in_interlock();
                if in_interlock {
                    self.emit(Op::Load(on()));
                    self.emit(Op::Assign {
                        bit: saved,
                        immediate: false,
                    });
                    self.emit(Op::Pop);
                }
                in_interlock
            }
        };
        self.control.step = Some(StepArea {
            current: (bit, span),
            in_interlock,
        });
        let what = format!("STEP(008) {}", clip(&ops[0].text));
        self.dangle(Pair::Step(bit), false, span, what, None);
        self.emit(Op::InterlockEnd);
        self.emit(Op::Load(Contact::Bit {
            bit,
            negated: false,
        }));
        if in_interlock {
            self.emit(Op::And(Contact::Bit {
                bit: saved,
                negated: false,
            }));
        }
        self.emit(Op::Interlock);
        self.emit(Op::Pop);
        Ok(())
    }

    /// `STEP` without operand: the step area ends; the gate is what it was before the area.
    fn step_area_end(&mut self, l: &Line) -> Result<(), Reported> {
        self.class(l, Class::Unconditional);
        let Some(area) = self.control.step.take() else {
            return Err(self.at_head(
                l,
                Code::OmrOutsideRegion,
                "STEP(008) without operand ends a step area, but none is open".into(),
            ));
        };
        self.emit(Op::InterlockEnd);
        if area.in_interlock {
            self.emit(Op::Load(Contact::Bit {
                bit: self.saved_interlock(),
                negated: false,
            }));
            self.emit(Op::Interlock);
            self.emit(Op::Pop);
        }
        Ok(())
    }

    /// `SNXT B`: with power flow, the current step's bit OFF, then B ON.
    pub(crate) fn snxt(&mut self, l: &Line) -> Result<(), Reported> {
        let ops = self.operands(l, 1)?;
        let bit = self.cx.bit(&ops[0], true)?;
        self.class(l, Class::Output);
        let span = self.cx.span(&l.head);
        let what = format!("SNXT(009) {}", clip(&ops[0].text));
        self.dangle(Pair::Step(bit), true, span, what, None);
        let set = |start: BitLoc, value: bool| Op::SetRange {
            start,
            count: Operand::Const(1),
            value,
            immediate: false,
        };
        if let Some(area) = &self.control.step {
            let current = area.current.0;
            self.emit(set(current, false));
        }
        self.emit(set(bit, true));
        Ok(())
    }

    /// `BPRG N`: EC OFF skips the block.
    pub(crate) fn bprg(&mut self, l: &Line) -> Result<(), Reported> {
        let ops = self.operands(l, 1)?;
        let max = u32::from(self.cx.profile.omron.block_programs).saturating_sub(1);
        let n = self.cx.number(&ops[0], max, "block program number")?;
        self.class(l, Class::Output);
        let span = self.cx.span(&l.head);
        if let Some(first) = self.control.block_numbers.insert(n, span) {
            let msg = format!(
                "block program {n} is already defined at line {}",
                first.line
            );
            return Err(self.at_head(l, Code::OmrNumberTwice, msg));
        }
        let end = self.new_label();
        self.control.blocks_opened += 1;
        self.control.block = Some(OpenBlock {
            id: self.control.blocks_opened,
            end,
            span,
        });
        self.emit(Op::Not);
        self.emit(Op::Jump(end));
        self.emit(Op::Not);
        Ok(())
    }

    /// `BEND`: the end of the block program; a jump of the block whose JME is not in it is
    /// E023.
    pub(crate) fn bend(&mut self, l: &Line) -> Result<(), Reported> {
        self.operands(l, 0)?;
        self.class(l, Class::Unconditional);
        let Some(block) = self.control.block.take() else {
            let span = self.cx.span(&l.head);
            let msg = format!("line {}: BEND(801) has no BPRG(096)", l.line);
            let plain = Some((Code::OmrOutsideRegion, msg));
            self.dangle(Pair::Block, false, span, "BEND(801)".into(), plain);
            return Err(Reported);
        };
        self.leave_block(block.id);
        self.place(block.end);
        Ok(())
    }

    /// What is left open in the POU when it closes: a step area (E026), a block program (E026,
    /// or E025 with its BEND in another task).
    pub(crate) fn close_regions(&mut self) {
        if let Some(area) = self.control.step.take() {
            let span = area.current.1;
            let msg = format!(
                "line {}: the step area of STEP(008) is not closed by STEP(008) without operand",
                span.line
            );
            self.cx.diags.push(stljit_source::Diagnostic::new(
                Code::OmrInRegion,
                span,
                "",
                msg,
            ));
        }
        if let Some(block) = self.control.block.take() {
            let msg = format!(
                "line {}: BPRG(096) is not closed by BEND(801)",
                block.span.line
            );
            let plain = Some((Code::OmrInRegion, msg));
            self.dangle(Pair::Block, true, block.span, "BPRG(096)".into(), plain);
        }
    }
}

/// `P_On` as a contact.
fn on() -> Contact {
    Contact::Bit {
        bit: SystemBit::On.bit_loc(),
        negated: false,
    }
}
