//! Lowering of one task (all program files in order) to IR POUs: the per-line dispatch over
//! [`mnemonics::TABLE`](crate::mnemonics::TABLE), the function-code and option checks (E011,
//! E012), the circuit machine ([`Circuit`]) and the bit instructions. Timers, counters and data
//! boxes are in `boxes`, program control and regions in `control`. The patterns are the ones
//! the crate doc lists.

use crate::capacity::Capacity;
use crate::circuit::{Circuit, Class};
use crate::control::Control;
use crate::discipline::FlagBranches;
use crate::immediate::{Refresh, writes_of_bit};
use crate::lexer::{Line, Options, Tok};
use crate::mnemonics::{self, Group, Join, Mnemonic};
use crate::operand::Syn;
use crate::resolve::{Cx, Reported};
use crate::tasks::{Project, UnitKind};
use stljit_core::ir::{EdgeDecl, OmronBox, Op, Operand, Pou, SrcLoc};
use stljit_core::omron::tr_bit;
use stljit_core::{Area, EdgeSlot, LabelId, OpIdx};
use stljit_runtime::omron_written::flags_changed_by;
use stljit_source::{Code, clip};

/// A POU being built.
pub(crate) struct PouBuild {
    /// The finished part.
    pub(crate) pou: Pou,
    /// The program unit it belongs to (an index into `Project::units`).
    pub(crate) unit: usize,
}

/// The lowering state of a whole project.
pub(crate) struct Lowerer<'a> {
    /// Profile, symbols, diagnostics and the current line.
    pub(crate) cx: Cx<'a>,
    /// The POUs in source order: each unit's main body, and the subroutines.
    pub(crate) pous: Vec<PouBuild>,
    /// The units, subroutines, calls and the pairs left open.
    pub(crate) project: Project,
    /// Every edge slot.
    pub(crate) edges: Vec<EdgeDecl>,
    /// The circuit machine of the current POU.
    pub(crate) circuit: Circuit,
    /// Regions, jumps and interlocks of the current unit.
    pub(crate) control: Control,
    /// Timer and counter numbers in use, with the line of their first use (E021).
    pub(crate) objects: std::collections::HashMap<(Area, u16), u32>,
    /// Source location of the current line.
    pub(crate) loc: SrcLoc,
    /// Bits driven by OUT/OUT NOT/KEEP/DIFU/DIFD and direct words written by data
    /// instructions in the current unit, with the line of their first write (W020).
    pub(crate) written: std::collections::HashMap<Written, u32>,
    /// Whether an instruction of the current unit that changes condition flags has been
    /// lowered yet (W034).
    pub(crate) flags_changed: bool,
    /// The execution condition when it is exactly `P_On`/`P_First_Cycle` (true: ON in every
    /// cycle but perhaps the first) or `P_Off` (false), for W031.
    pub(crate) constant_ec: Option<bool>,
    /// The flag-changing instructions and branch points of the current circuit (W033).
    pub(crate) flag_branches: FlagBranches,
    /// The project's user-memory steps so far (E035).
    pub(crate) capacity: Capacity,
}

/// A bit or a word one instruction writes (the key of W020's check).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Written {
    /// A coil.
    Bit(stljit_core::ir::BitLoc),
    /// A destination word.
    Word(stljit_core::ir::Loc),
}

impl<'a> Lowerer<'a> {
    /// A lowerer for a project whose files are named `files`; the first unit starts at the first
    /// directive or instruction.
    pub(crate) fn new(cx: Cx<'a>, files: Vec<String>) -> Self {
        Lowerer {
            cx,
            pous: Vec::new(),
            project: Project::new(files),
            edges: Vec::new(),
            circuit: Circuit::default(),
            control: Control::default(),
            objects: Default::default(),
            loc: SrcLoc::default(),
            written: Default::default(),
            flags_changed: false,
            constant_ec: None,
            flag_branches: FlagBranches::default(),
            capacity: Capacity::default(),
        }
    }

    /// Forgets the state of the previous unit (a new unit is lowered like a program of its own).
    pub(crate) fn reset_unit_state(&mut self) {
        self.circuit.reset();
        self.control = Control::default();
        self.written.clear();
        self.flags_changed = false;
        self.constant_ec = None;
        self.flag_branches.new_circuit();
    }

    /// Appends `op` to the current POU with the current line's location.
    pub(crate) fn emit(&mut self, op: Op) {
        let pou = self.control.pou;
        let p = &mut self.pous[pou].pou;
        p.ops.push(op);
        p.locs.push(self.loc);
    }

    /// A new label of the current POU (placed later by [`Lowerer::place`]).
    pub(crate) fn new_label(&mut self) -> LabelId {
        let p = &mut self.pous[self.control.pou].pou;
        p.labels.push(OpIdx(u32::MAX));
        LabelId::new(p.labels.len() - 1)
    }

    /// Emits `Label(label)` here.
    pub(crate) fn place(&mut self, label: LabelId) {
        let p = &mut self.pous[self.control.pou].pou;
        if let Some(slot) = p.labels.get_mut(label.index()) {
            *slot = OpIdx::new(p.ops.len());
        }
        self.emit(Op::Label(label));
    }

    /// An edge op with a new slot (§2.6: rising memories start ON, falling ones OFF).
    pub(crate) fn edge(&mut self, falling: bool) -> Op {
        self.edges.push(EdgeDecl { init: !falling });
        Op::Edge {
            slot: EdgeSlot::new(self.edges.len() - 1),
            falling,
        }
    }

    /// W031: an edge instruction (`falling` or rising) whose input is the constant `on`
    /// (`P_On`/`P_First_Cycle` when true, `P_Off` when false) never executes (§2.6).
    pub(crate) fn never_fires(&mut self, l: &Line, falling: bool, on: bool) {
        if falling == on {
            return; // a falling edge of ON or a rising edge of OFF is a different mistake
        }
        let mn = self.cx.mn.clone();
        let start = if falling { "OFF" } else { "ON" };
        self.at_head(
            l,
            Code::OmrNeverFires,
            format!("{mn} will never execute — its edge memory starts {start}"),
        );
    }

    /// `Dup; Edge; <body>; Pop` for an `@`/`%` output, or just the body.
    pub(crate) fn edged(&mut self, options: Options, body: impl FnOnce(&mut Self)) {
        match options.edge {
            Some(falling) => {
                self.emit(Op::Dup);
                let e = self.edge(falling);
                self.emit(e);
                body(self);
                self.emit(Op::Pop);
            }
            None => body(self),
        }
    }

    /// Reports a diagnostic at the instruction word.
    pub(crate) fn at_head(&mut self, l: &Line, code: Code, message: String) -> Reported {
        let line = l.line;
        self.cx
            .report(code, &l.head, format!("line {line}: {message}"))
    }

    /// Runs the circuit machine for this instruction; true when it started a new circuit.
    pub(crate) fn class(&mut self, l: &Line, class: Class) -> bool {
        let (findings, new_circuit) = self.circuit.step(class, &self.cx.mn);
        for (code, message) in findings {
            self.at_head(l, code, message);
        }
        if new_circuit || class == Class::Unconditional {
            self.flag_branches.new_circuit();
        }
        new_circuit
    }

    /// The operands, if there are exactly `n` (else E013).
    pub(crate) fn operands<'l>(&mut self, l: &'l Line, n: usize) -> Result<&'l [Tok], Reported> {
        if let Some(t) = &l.dangling_cio {
            let line = l.line;
            return Err(self.cx.report(
                Code::OmrOperand,
                t,
                format!("line {line}: `CIO` must be followed by a CIO word or bit address"),
            ));
        }
        if l.operands.len() == n {
            return Ok(&l.operands);
        }
        let got: Vec<_> = l.operands.iter().map(|t| clip(&t.text)).collect();
        let mn = self.cx.mn.clone();
        Err(self.at_head(
            l,
            Code::OmrOperand,
            format!(
                "{mn} expects {n} operand(s), got {} ({})",
                got.len(),
                got.join(" ")
            ),
        ))
    }

    /// Lowers one lexed line.
    pub(crate) fn line(&mut self, l: &Line) {
        self.cx.mn = format!("{}{}", l.options.text(), l.mnemonic);
        if l.mnemonic.starts_with('$') {
            self.directive(l);
            return;
        }
        self.ensure_unit(self.cx.span(&l.head));
        self.count_steps(l);
        if !self.admit(l) || !self.allowed_in_unit(l) || !self.allowed_in_region(l) {
            return;
        }
        let Some(m) = self.instruction(l) else {
            // Unknown class: let whatever follows pass, so one bad line reports once.
            self.circuit.recover();
            return;
        };
        // The constant execution condition survives outputs (they continue with the same EC)
        // and ends at anything that changes the EC; an LD of a constant sets it anew.
        let prev = self.constant_ec.take();
        let class = class_of(m.group);
        if class == Class::Output {
            self.constant_ec = prev;
        }
        let edge_of_ec = match m.group {
            Group::Edge(falling) | Group::Differentiate(falling) => Some(falling),
            _ if class == Class::Output => l.options.edge,
            _ => None,
        };
        if let (Some(falling), Some(on)) = (edge_of_ec, prev) {
            self.never_fires(l, falling, on);
        }
        let (pou, start) = (self.control.pou, self.pous[self.control.pou].pou.ops.len());
        if !self.options_allowed(l, &m) || self.dispatch(l, &m).is_err() {
            // The error is reported; advance the circuit as the instruction would have, so
            // the lines after it are not blamed for it.
            let _ = self.circuit.step(class_of(m.group), "");
            return;
        }
        let what = format!("{}{}", l.options.text(), mnemonics::with_code(&l.mnemonic));
        if edge_of_ec.is_some() {
            let found = self.flag_branches.differentiated(&what, l.line);
            self.cx.diags.extend(found);
        }
        if self.control.pou == pou {
            let ops = std::mem::take(&mut self.pous[pou].pou.ops);
            self.count_constant_steps(&ops[start..], l);
            let mask = ops[start..]
                .iter()
                .fold(0, |m, op| m | flags_changed_by(op));
            self.pous[pou].pou.ops = ops;
            let differentiated = l.options.edge.is_some();
            self.flag_branches.wrote(what, l.line, mask, differentiated);
        }
    }

    /// E039 for an instruction a function-block body may not use (the line is then skipped).
    fn allowed_in_unit(&mut self, l: &Line) -> bool {
        if !matches!(self.unit_kind(), UnitKind::FunctionBlock(_)) {
            return true;
        }
        let listed = mnemonics::NOT_IN_FUNCTION_BLOCKS.contains(&l.mnemonic.as_str());
        if !listed && !l.options.immediate {
            return true;
        }
        let what = format!("{}{}", l.options.text(), mnemonics::with_code(&l.mnemonic));
        let why = if listed {
            ""
        } else {
            " (no `!` instruction is)"
        };
        self.at_head(
            l,
            Code::OmrFunctionBlock,
            format!("{what} cannot be used inside a function block{why}"),
        );
        self.circuit.recover();
        false
    }

    /// The supported instruction of the line, with its function code checked (E011).
    fn instruction(&mut self, l: &Line) -> Option<Mnemonic> {
        let name = l.mnemonic.as_str();
        let found = mnemonics::lookup(name).or_else(|| {
            mnemonics::compare(name).map(|c| Mnemonic {
                name: "",
                code: Some(c.code),
                group: Group::Contact(c.join, false),
                allowed: mnemonics::COMPARE_OPTIONS,
                steps: mnemonics::COMPARE_STEPS,
            })
        });
        let model = self.cx.profile.model;
        let Some(m) = found else {
            let msg = format!("{} is not an instruction of {model}", clip(name));
            self.at_head(l, Code::OmrInstruction, msg);
            return None;
        };
        match (&l.code, m.code) {
            (None, _) => {}
            (Some(Ok(c)), Some(c0)) if *c == c0 => {}
            (Some(Ok(c)), Some(c0)) => {
                self.at_head(
                    l,
                    Code::OmrInstruction,
                    format!("function code ({c:03}) does not match {name} ({c0:03})"),
                );
                return None;
            }
            (Some(Ok(c)), None) => {
                self.at_head(
                    l,
                    Code::OmrInstruction,
                    format!("function code ({c:03}) does not match {name}, which has none"),
                );
                return None;
            }
            (Some(Err(text)), _) => {
                let text = clip(text);
                self.at_head(
                    l,
                    Code::OmrInstruction,
                    format!("`{text}` is not a function code"),
                );
                return None;
            }
        }
        Some(m)
    }

    /// E012 for an option the instruction does not take.
    fn options_allowed(&mut self, l: &Line, m: &Mnemonic) -> bool {
        let o = l.options;
        let bad = match o.edge {
            Some(false) if !m.allowed.up => Some("@"),
            Some(true) if !m.allowed.down => Some("%"),
            _ if o.immediate && !m.allowed.immediate => Some("!"),
            _ => None,
        };
        let Some(opt) = bad else { return true };
        let mn = l.mnemonic.clone();
        let help = "use DIFU(013)/UP(521) for rising-edge and DIFD(014)/DOWN(522) for falling-edge execution";
        let line = l.line;
        self.cx.report_help(
            Code::OmrOption,
            &l.head,
            format!("line {line}: {opt}{mn} is not allowed"),
            help,
        );
        false
    }

    fn dispatch(&mut self, l: &Line, m: &Mnemonic) -> Result<(), Reported> {
        match m.group {
            Group::Contact(join, negated) => match mnemonics::compare(&l.mnemonic) {
                Some(c) if m.name.is_empty() => self.compare_contact(l, c),
                _ => self.contact(l, join, negated),
            },
            Group::Block(join) => {
                self.operands(l, 0)?;
                self.class(l, Class::Join);
                self.emit(if join == Join::And {
                    Op::AndBlock
                } else {
                    Op::OrBlock
                });
                Ok(())
            }
            Group::Not => {
                self.operands(l, 0)?;
                self.class(l, Class::Intermediate);
                self.emit(Op::Not);
                Ok(())
            }
            Group::Edge(falling) => {
                self.operands(l, 0)?;
                self.class(l, Class::Intermediate);
                let e = self.edge(falling);
                self.emit(e);
                Ok(())
            }
            Group::Out(negated) => self.out(l, negated),
            Group::SetReset(value) => self.set_reset(l, value),
            Group::Keep => self.keep(l),
            Group::Differentiate(falling) => self.differentiate(l, falling),
            Group::Timer(kind) => self.timer(l, kind),
            Group::Counter(kind) => self.counter(l, kind),
            Group::Move(double) => self.data(l, DataBox::Move(double)),
            Group::MoveAddress => self.move_address(l),
            Group::SaveFlags(save) => {
                self.operands(l, 0)?;
                self.class(l, Class::Output);
                self.flags_changed = true;
                self.edged(l.options, |s| s.emit(Op::Omron(OmronBox::Flags { save })));
                Ok(())
            }
            Group::Iorf => self.iorf(l),
            Group::Compare(double, signed) => self.data(l, DataBox::Compare(double, signed)),
            Group::Arith(op) => self.data(l, DataBox::Arith(op)),
            Group::Control(flow) => self.flow(l, flow),
        }
    }

    /// W020: `what` (written as `tok`) is also written by an earlier output instruction.
    pub(crate) fn note_write(&mut self, tok: &Tok, what: Written) {
        let line = self.cx.line;
        match self.written.get(&what) {
            Some(&first) => {
                self.cx.report(
                    Code::OmrDuplicateCoil,
                    tok,
                    format!(
                        "line {line}: {} is also written at line {first}; only the later write is visible at output refresh",
                        clip(&tok.text)
                    ),
                );
            }
            None => {
                self.written.insert(what, line);
            }
        }
    }

    /// `OUT b`, `OUT NOT b`, `OUT TRn`.
    fn out(&mut self, l: &Line, negated: bool) -> Result<(), Reported> {
        let ops = self.operands(l, 1)?;
        let tok = &ops[0];
        if let Syn::Tr(n) = self.cx.syn(tok)? {
            let n = self.tr_number(tok, n)?;
            if negated || l.options.immediate {
                let (line, mn) = (l.line, self.cx.mn.clone());
                return Err(self.cx.report(
                    Code::OmrTr,
                    tok,
                    format!("line {line}: TR{n} may only be used with OUT and LD, not {mn}"),
                ));
            }
            self.class(l, Class::Output);
            self.flag_branches.store_tr(n);
            if !self.circuit.store_tr(n) {
                let line = l.line;
                self.cx.report(
                    Code::OmrTr,
                    tok,
                    format!("line {line}: TR{n} is stored twice in this circuit"),
                );
            }
            self.emit(Op::Assign {
                bit: tr_bit(n),
                immediate: false,
            });
            return Ok(());
        }
        let bit = self.cx.bit(tok, true)?;
        self.note_write(tok, Written::Bit(bit));
        self.class(l, Class::Output);
        let assign = Op::Assign {
            bit,
            immediate: false,
        };
        if negated {
            self.emit(Op::Not);
            self.emit(assign);
            self.emit(Op::Not);
        } else {
            self.emit(assign);
        }
        if l.options.immediate {
            self.refresh_outputs(writes_of_bit(bit), Refresh::Always);
        }
        Ok(())
    }

    fn set_range(&self, start: stljit_core::ir::BitLoc, value: bool) -> Op {
        Op::SetRange {
            start,
            count: Operand::Const(1),
            value,
            immediate: false,
        }
    }

    /// `SET b` / `RSET b`, with `@`/`%`/`!`.
    fn set_reset(&mut self, l: &Line, value: bool) -> Result<(), Reported> {
        let ops = self.operands(l, 1)?;
        let bit = self.cx.bit(&ops[0], true)?;
        self.class(l, Class::Output);
        let op = self.set_range(bit, value);
        let immediate = l.options.immediate;
        self.edged(l.options, |s| {
            s.emit(op);
            if immediate {
                s.refresh_outputs(writes_of_bit(bit), Refresh::WhenExecuted);
            }
        });
        Ok(())
    }

    /// `KEEP(011) b`: S1 = set, S0 = reset; reset wins.
    fn keep(&mut self, l: &Line) -> Result<(), Reported> {
        let ops = self.operands(l, 1)?;
        let bit = self.cx.bit(&ops[0], true)?;
        self.note_write(&ops[0], Written::Bit(bit));
        self.class(l, Class::Multi(2));
        self.emit(self.set_range(bit, false));
        self.emit(Op::Not);
        self.emit(Op::AndBlock);
        self.emit(self.set_range(bit, true));
        if l.options.immediate {
            self.refresh_outputs(writes_of_bit(bit), Refresh::Always);
        }
        Ok(())
    }

    /// `DIFU(013)` / `DIFD(014)`: the bit is ON in the edge cycle, OFF otherwise.
    fn differentiate(&mut self, l: &Line, falling: bool) -> Result<(), Reported> {
        let ops = self.operands(l, 1)?;
        let bit = self.cx.bit(&ops[0], true)?;
        self.note_write(&ops[0], Written::Bit(bit));
        self.class(l, Class::Output);
        self.emit(Op::Dup);
        let e = self.edge(falling);
        self.emit(e);
        self.emit(self.set_range(bit, true));
        self.emit(Op::Not);
        self.emit(self.set_range(bit, false));
        self.emit(Op::Pop);
        Ok(())
    }
}

/// The data boxes `boxes::data` lowers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum DataBox {
    /// MOV / MOVL.
    Move(bool),
    /// CMP family: (double, signed).
    Compare(bool, bool),
    /// §3.6.
    Arith(stljit_core::ir::OmronArith),
}

/// The circuit class of an instruction group (§2.4).
pub(crate) fn class_of(group: Group) -> Class {
    use crate::mnemonics::Flow;
    match group {
        Group::Contact(Join::Load, _) => Class::Start,
        Group::Contact(..) => Class::Combine,
        Group::Block(_) => Class::Join,
        Group::Not | Group::Edge(_) => Class::Intermediate,
        Group::Keep => Class::Multi(2),
        Group::Timer(k) if k.conditions() > 1 => Class::Multi(u32::from(k.conditions())),
        Group::Counter(k) => Class::Multi(u32::from(k.conditions())),
        Group::Control(
            Flow::Il
            | Flow::Jmp
            | Flow::Cjp
            | Flow::Cjpn
            | Flow::Jmp0
            | Flow::Sbs
            | Flow::Break
            | Flow::Snxt
            | Flow::Bprg,
        ) => Class::Output,
        Group::Control(_) => Class::Unconditional,
        _ => Class::Output,
    }
}
