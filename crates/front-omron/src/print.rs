//! IR → Omron mnemonic text: [`print_program`] reads the op patterns the lowering emits (the
//! crate doc lists them) back into instructions, so that the printed text compiles to the same
//! IR up to source locations. Fuzz reproducers (`program.omr`), the dialect round trip of
//! `stljit-diff` and the `parse`/`roundtrip` fuzz targets rely on that.
//!
//! Where an op sequence is not one the front end emits (an S7 op, a lone `Pop`, a `For` that is
//! not the FOR pattern, labels in an order no text allocates …) the printer returns a
//! [`PrintError`] naming the POU and op instead of text that would compile to something else.
//!
//! Choices where several texts give the same IR: `LD b` + `UP` is printed `@LD b`, `NOT` +
//! `OUT b` + `NOT` is `OUT NOT b`, every jump is a numbered `JMP`/`CJP` (JMP0/JME0 and CJPN
//! lower to the same ops as JMP/JME), `!` is written only where it changes the IR (an input
//! contact, an output coil), constants are `#hex`, and IORF, which lowers to nothing, never
//! appears.

use crate::mnemonics::{
    COMPARE_JOINS, COMPARE_SUFFIXES, Flow, Group, Join, RELATIONS, TABLE, relation_flag,
};
use operands::{bit_text, ea_operand, tr, word};
use std::fmt;
use stljit_core::ir::{BitLoc, CmpOp, Contact, Loc, OmronBox, Op, Operand, Pou, PouKind, Program};
use stljit_core::omron::SystemBit;
use stljit_core::{Area, CpuProfile, Family, LabelId};

/// Why a program cannot be printed as Omron text: it is not a program the Omron front end
/// produces (for example IR built by hand or cut by a shrinker).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PrintError {
    /// The POU (index into `Program::pous`).
    pub pou: usize,
    /// The op the pattern starts at, when the problem is an op.
    pub op: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for PrintError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.op {
            Some(op) => write!(f, "pou {} op {}: {}", self.pou, op, self.message),
            None => write!(f, "pou {}: {}", self.pou, self.message),
        }
    }
}

impl std::error::Error for PrintError {}

/// Prints `program` (one the Omron front end compiled, or equal to one up to source locations)
/// as Omron mnemonic text: the main program, the subroutines (`SBN(092) n` … `RET(093)`), then
/// `END(001)`.
pub fn print_program(program: &Program) -> Result<String, PrintError> {
    let profile = program.profile.profile();
    let err = |pou, message: &str| PrintError {
        pou,
        op: None,
        message: message.to_owned(),
    };
    let control = |pou, flow| {
        head("", Group::Control(flow)).map_err(|message| PrintError {
            pou,
            op: None,
            message,
        })
    };
    if profile.family != Family::Omron {
        return Err(err(0, "not an Omron profile"));
    }
    let mut out = format!(
        "; printed by stljit from IR (profile {})\n",
        program.profile.name()
    );
    let Some(main) = program.pous.first() else {
        return Err(err(0, "no main program"));
    };
    if main.kind != PouKind::Main {
        return Err(err(0, "the first POU is not the main program"));
    }
    let Some((Op::End { conditional: false }, body)) = main.ops.split_last() else {
        return Err(err(0, "the main program does not end with END(001)"));
    };
    Body::new(program, profile, 0).print(body, &mut out)?;
    for (i, pou) in program.pous.iter().enumerate().skip(1) {
        let PouKind::Subroutine(n) = pou.kind else {
            return Err(err(i, "only subroutines follow the main program"));
        };
        let Some((Op::Return { conditional: false }, body)) = pou.ops.split_last() else {
            return Err(err(i, "a subroutine does not end with RET(093)"));
        };
        out.push_str(&line(&control(i, Flow::Sbn)?, &[n.to_string()]));
        Body::new(program, profile, i).print(body, &mut out)?;
        out.push_str(&line(&control(i, Flow::Ret)?, &[]));
    }
    out.push_str(&line(&control(0, Flow::End)?, &[]));
    Ok(out)
}

/// A printed instruction line, and for the `NOT` that starts an unfolded `NOT; OUT b; NOT`
/// (or `NOT; CJP n; NOT`) the one line the three fold into (`OUT NOT b`, `JMP n`).
struct Line {
    text: String,
    folded: Option<String>,
}

impl Line {
    fn plain(text: String) -> Line {
        Line { text, folded: None }
    }
}

/// One instruction line.
fn line(head: &str, operands: &[String]) -> String {
    if operands.is_empty() {
        format!("{head}\n")
    } else {
        format!("{head:<10} {}\n", operands.join(" "))
    }
}

/// `options` + the table name of `group` + its function code.
fn head(options: &str, group: Group) -> Result<String, String> {
    let m = TABLE
        .iter()
        .find(|m| m.group == group)
        .ok_or_else(|| format!("no mnemonic for {group:?}"))?;
    let allowed = match options.trim_start_matches('!') {
        "@" => m.allowed.up,
        "%" => m.allowed.down,
        _ => true,
    } && (!options.starts_with('!') || m.allowed.immediate);
    if !allowed {
        return Err(format!("{options}{} is not allowed", m.name));
    }
    Ok(with_code(options, m.name, m.code))
}

fn with_code(options: &str, name: &str, code: Option<u16>) -> String {
    match code {
        Some(c) => format!("{options}{name}({c:03})"),
        None => format!("{options}{name}"),
    }
}

/// `@` or `%` for a rising or falling edge.
fn edge_option(falling: bool) -> &'static str {
    if falling { "%" } else { "@" }
}

/// What a label of the POU is in the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    /// A jump number (`JMP n` / `JME n`).
    Number(u32),
    /// The exit of a FOR loop (placed by its NEXT, reached by BREAK).
    Exit,
}

/// The printing state of one POU.
struct Body<'a> {
    program: &'a Program,
    profile: &'static CpuProfile,
    pou: usize,
    /// What each label id is, once the text has allocated it.
    roles: Vec<Option<Role>>,
    /// The label id the front end allocates next (it allocates in text order).
    next_label: usize,
    /// The jump number given next.
    next_number: u32,
    /// The open FOR loops: the index of their `For` and their exit label.
    loops: Vec<(usize, LabelId)>,
}

type Res<T> = Result<T, String>;

impl<'a> Body<'a> {
    fn new(program: &'a Program, profile: &'static CpuProfile, pou: usize) -> Body<'a> {
        Body {
            program,
            profile,
            pou,
            roles: vec![None; program.pous[pou].labels.len()],
            next_label: 0,
            next_number: 0,
            loops: Vec::new(),
        }
    }

    fn pou(&self) -> &'a Pou {
        &self.program.pous[self.pou]
    }

    /// Prints `ops` (the POU without its final END/RET).
    fn print(mut self, ops: &[Op], out: &mut String) -> Result<(), PrintError> {
        let mut lines = Vec::new();
        let mut i = 0;
        while i < ops.len() {
            let pou = self.pou;
            let err = |message| PrintError {
                pou,
                op: Some(i),
                message,
            };
            // `NOT; OUT b; NOT` and `OUT NOT b` (likewise `NOT; CJP n; NOT` and `JMP n`) give
            // the same ops but leave the circuit in a different place: the folded form is
            // printed unless an LD follows, whose role `circuits::separate` then settles.
            if let Some(folded) = self.fold(ops, i).map_err(err)? {
                if !opens_block(ops, i + 3) {
                    lines.push(Line::plain(folded));
                    i += 3;
                    continue;
                }
                let not = line(&head("", Group::Not).map_err(err)?, &[]);
                lines.push(Line {
                    text: not,
                    folded: Some(folded),
                });
                i += 1;
                continue;
            }
            let (text, used) = self.instruction(ops, i).map_err(err)?;
            lines.push(Line::plain(text));
            i += used;
        }
        circuits::separate(&mut lines);
        out.extend(lines.into_iter().map(|l| l.text));
        if !self.loops.is_empty() {
            return Err(PrintError {
                pou: self.pou,
                op: None,
                message: "a FOR loop has no NEXT".into(),
            });
        }
        Ok(())
    }

    /// The text of the instruction whose ops start at `i`, and how many ops it covers.
    fn instruction(&mut self, ops: &[Op], i: usize) -> Res<(String, usize)> {
        let at = |k: usize| ops.get(i + k);
        let on = SystemBit::On.bit_loc();
        match &ops[i] {
            Op::Load(Contact::Bit {
                bit,
                negated: false,
            }) if *bit == on => {
                if let (Some(Op::Omron(OmronBox::Compare { .. })), Some(Op::Pop), Some(flag)) =
                    (at(1), at(2), at(3))
                {
                    return Ok((compare_contact(&ops[i + 1], flag)?, 4));
                }
                if let Some(Op::For { .. }) = at(1) {
                    return Ok((self.for_loop(ops, i + 1)?, 2));
                }
                self.contact(ops, i, Join::Load)
            }
            Op::Load(_) => self.contact(ops, i, Join::Load),
            Op::And(_) => self.contact(ops, i, Join::And),
            Op::Or(_) => self.contact(ops, i, Join::Or),
            Op::Not => Ok((line(&head("", Group::Not)?, &[]), 1)),
            Op::AndBlock => Ok((line(&head("", Group::Block(Join::And))?, &[]), 1)),
            Op::OrBlock => Ok((line(&head("", Group::Block(Join::Or))?, &[]), 1)),
            Op::Edge { falling, .. } => Ok((line(&head("", Group::Edge(*falling))?, &[]), 1)),
            Op::Assign { bit, immediate } => Ok((self.out(*bit, *immediate, false)?, 1)),
            Op::SetRange {
                start,
                value: false,
                immediate,
                ..
            } if matches!(
                (at(1), at(2), at(3)),
                (Some(Op::Not), Some(Op::AndBlock), Some(Op::SetRange { start: s, value: true, immediate: m, count }))
                    if s == start && m == immediate && *count == Operand::Const(1)
            ) =>
            {
                let b = self.coil(&ops[i], true)?;
                let opt = if *immediate { "!" } else { "" };
                Ok((line(&head(opt, Group::Keep)?, &[b]), 4))
            }
            Op::SetRange { .. } | Op::Omron(_) | Op::Call(_) => {
                Ok((self.output(&ops[i], None)?, 1))
            }
            Op::Dup => self.edged(ops, i),
            Op::OmronTimer {
                kind,
                timer,
                set_value,
            } => {
                let sv = word(*set_value, 1)?;
                let h = head("", Group::Timer(*kind))?;
                Ok((line(&h, &[format!("{:04}", timer.0), sv]), 1))
            }
            Op::OmronCounter {
                kind,
                counter,
                set_value,
            } => {
                let sv = word(*set_value, 1)?;
                let h = head("", Group::Counter(*kind))?;
                Ok((line(&h, &[format!("{:04}", counter.0), sv]), 1))
            }
            Op::Interlock => Ok((line(&head("", Group::Control(Flow::Il))?, &[]), 1)),
            Op::InterlockEnd => Ok((line(&head("", Group::Control(Flow::Ilc))?, &[]), 1)),
            Op::Jump(l) => {
                if self.loops.last().is_some_and(|(_, exit)| exit == l) {
                    return Ok((line(&head("", Group::Control(Flow::Break))?, &[]), 1));
                }
                let n = self.number(*l, i)?;
                Ok((line(&head("", Group::Control(Flow::Cjp))?, &[n]), 1))
            }
            Op::Label(l) => {
                if self.is_exit(*l) {
                    return Err("a FOR loop's exit label away from its NEXT".into());
                }
                let n = self.number(*l, i)?;
                Ok((line(&head("", Group::Control(Flow::Jme))?, &[n]), 1))
            }
            Op::Next { head: h } => {
                let Some((at_for, exit)) = self.loops.pop() else {
                    return Err("NEXT without FOR".into());
                };
                if h.index() != at_for || at(1) != Some(&Op::Label(exit)) {
                    return Err("NEXT is not the FOR pattern (`Next` then its exit label)".into());
                }
                Ok((line(&head("", Group::Control(Flow::Next))?, &[]), 2))
            }
            other => Err(format!(
                "{other:?} is not an op the Omron front end emits here"
            )),
        }
    }

    /// The folded text of `Not; Assign; Not` (`OUT NOT b`) or `Not; Jump; Not` (`JMP n`) at
    /// `i`, if the ops there are one.
    fn fold(&mut self, ops: &[Op], i: usize) -> Res<Option<String>> {
        match (ops.get(i), ops.get(i + 1), ops.get(i + 2)) {
            (Some(Op::Not), Some(Op::Assign { bit, immediate }), Some(Op::Not))
                if bit.area != Area::Tr =>
            {
                Ok(Some(self.out(*bit, *immediate, true)?))
            }
            (Some(Op::Not), Some(Op::Jump(l)), Some(Op::Not)) if !self.is_exit(*l) => {
                let n = self.number(*l, i + 1)?;
                Ok(Some(line(&head("", Group::Control(Flow::Jmp))?, &[n])))
            }
            _ => Ok(None),
        }
    }

    /// `LD`/`AND`/`OR` (NOT forms, `!`), `LD TRn`, and the differentiated contacts
    /// (`Load; Edge` = `@LD`, `Load; Edge; AndBlock` = `@AND`, `… OrBlock` = `@OR`).
    fn contact(&mut self, ops: &[Op], i: usize, join: Join) -> Res<(String, usize)> {
        let (Op::Load(c) | Op::And(c) | Op::Or(c)) = &ops[i] else {
            return Err("not a contact".into());
        };
        let (bit, negated, immediate) = match *c {
            Contact::Bit { bit, negated } => (bit, negated, false),
            Contact::ImmediateInput { bit, negated } if bit.area == Area::I => (bit, negated, true),
            _ => return Err(format!("{c:?} is not an Omron contact")),
        };
        if bit.area == Area::Tr {
            if join != Join::Load || negated {
                return Err("a TR bit is only read by a plain LD".into());
            }
            let h = head("", Group::Contact(Join::Load, false))?;
            return Ok((line(&h, &[tr(bit)]), 1));
        }
        let opt = if immediate { "!" } else { "" };
        let b = bit_text(bit)?;
        if join == Join::Load
            && !negated
            && let Some(Op::Edge { falling, .. }) = ops.get(i + 1)
        {
            let opt = format!("{opt}{}", edge_option(*falling));
            let (j, used) = match ops.get(i + 2) {
                Some(Op::AndBlock) => (Join::And, 3),
                Some(Op::OrBlock) => (Join::Or, 3),
                _ => (Join::Load, 2),
            };
            return Ok((line(&head(&opt, Group::Contact(j, false))?, &[b]), used));
        }
        Ok((line(&head(opt, Group::Contact(join, negated))?, &[b]), 1))
    }

    /// `OUT`, `OUT NOT`, `OUT TRn`, with `!` on an output-word coil.
    fn out(&self, bit: BitLoc, immediate: bool, negated: bool) -> Res<String> {
        if bit.area == Area::Tr {
            if immediate || negated {
                return Err("a TR bit is only written by a plain OUT".into());
            }
            return Ok(line(&head("", Group::Out(false))?, &[tr(bit)]));
        }
        if immediate && bit.area != Area::Q {
            return Err("an immediate coil outside the output words".into());
        }
        let opt = if immediate { "!" } else { "" };
        Ok(line(&head(opt, Group::Out(negated))?, &[bit_text(bit)?]))
    }

    /// The coil of a `SetRange` (count 1; `!` only on an output word).
    fn coil(&self, op: &Op, keep: bool) -> Res<String> {
        let Op::SetRange {
            start,
            count: Operand::Const(1),
            immediate,
            ..
        } = op
        else {
            return Err("a set/reset of more than one bit".into());
        };
        if *immediate && start.area != Area::Q {
            return Err("an immediate set/reset outside the output words".into());
        }
        if keep && start.area == Area::Tr {
            return Err("KEEP of a TR bit".into());
        }
        bit_text(*start)
    }

    /// A single-op output (SET/RSET, a data box, SBS) with `edge` as its `@`/`%` option.
    fn output(&self, op: &Op, edge: Option<bool>) -> Res<String> {
        let e = edge.map_or("", edge_option);
        match op {
            Op::SetRange {
                value, immediate, ..
            } => {
                let b = self.coil(op, false)?;
                let opt = format!("{}{e}", if *immediate { "!" } else { "" });
                Ok(line(&head(&opt, Group::SetReset(*value))?, &[b]))
            }
            Op::Omron(b) => self.data_box(b, e),
            Op::Call(p) => {
                let callee = self
                    .program
                    .pous
                    .get(p.index())
                    .ok_or("a call to a missing POU")?;
                let PouKind::Subroutine(n) = callee.kind else {
                    return Err("a call to a POU that is not a subroutine".into());
                };
                Ok(line(&head(e, Group::Control(Flow::Sbs))?, &[n.to_string()]))
            }
            other => Err(format!("{other:?} takes no @/% option")),
        }
    }

    /// `Dup; Edge; <output>; Pop` (an `@`/`%` output) or DIFU/DIFD
    /// (`Dup; Edge; SetRange(b, 1); Not; SetRange(b, 0); Pop`).
    fn edged(&self, ops: &[Op], i: usize) -> Res<(String, usize)> {
        let Some(Op::Edge { falling, .. }) = ops.get(i + 1) else {
            return Err("`Dup` not followed by an edge".into());
        };
        let set = |k: usize, v: bool| matches!(ops.get(i + k), Some(Op::SetRange { count: Operand::Const(1), value, immediate: false, .. }) if *value == v);
        if set(2, true)
            && ops.get(i + 3) == Some(&Op::Not)
            && set(4, false)
            && ops.get(i + 5) == Some(&Op::Pop)
            && matches!((&ops[i + 2], &ops[i + 4]), (Op::SetRange { start: a, .. }, Op::SetRange { start: b, .. }) if a == b)
        {
            let b = self.coil(&ops[i + 2], false)?;
            return Ok((line(&head("", Group::Differentiate(*falling))?, &[b]), 6));
        }
        match (ops.get(i + 2), ops.get(i + 3)) {
            (Some(op), Some(Op::Pop)) => Ok((self.output(op, Some(*falling))?, 4)),
            _ => Err("`Dup; Edge` is not an @/% output or DIFU/DIFD".into()),
        }
    }

    /// MOV/MOVL, the compares, the arithmetic, MOVR, CCS/CCL with option text `e`.
    fn data_box(&self, b: &OmronBox, e: &str) -> Res<String> {
        match *b {
            OmronBox::Move { double, src, dst } => {
                let w = if double { 2 } else { 1 };
                let h = head(e, Group::Move(double))?;
                Ok(line(&h, &[word(src, w)?, word(dst, w)?]))
            }
            OmronBox::Compare {
                double,
                signed,
                lhs,
                rhs,
            } => {
                let w = if double { 2 } else { 1 };
                let h = head(e, Group::Compare(double, signed))?;
                Ok(line(&h, &[word(lhs, w)?, word(rhs, w)?]))
            }
            OmronBox::Arith { op, lhs, rhs, dst } => {
                if e == "%" {
                    return Err("%-differentiated arithmetic".into());
                }
                let w = op.operand_words();
                let h = with_code(e, op.mnemonic(), Some(op.function_code()));
                let d = word(dst, op.result_words())?;
                Ok(line(&h, &[word(lhs, w)?, word(rhs, w)?, d]))
            }
            OmronBox::SetIndex { ea, ir } => {
                let src =
                    ea_operand(self.profile, ea).ok_or("an effective address no operand names")?;
                Ok(line(
                    &head(e, Group::MoveAddress)?,
                    &[src, format!("IR{ir}")],
                ))
            }
            OmronBox::Flags { save } => Ok(line(&head(e, Group::SaveFlags(save))?, &[])),
        }
    }

    /// `Load(P_On); For{…}` at `i - 1`: `FOR(503) N`, its exit label allocated now.
    fn for_loop(&mut self, ops: &[Op], i: usize) -> Res<String> {
        let Op::For {
            index,
            init,
            limit,
            next,
        } = &ops[i]
        else {
            return Err("not a FOR".into());
        };
        let depth = self.loops.len() as u32;
        let counter = Operand::Mem(Loc {
            area: Area::L,
            offset: 2 * depth,
        });
        if *index != counter || *init != Operand::Const(1) {
            return Err("a FOR whose counter is not the front end's L word".into());
        }
        if depth >= u32::from(self.profile.max_for_depth) {
            return Err("FOR loops nested too deep".into());
        }
        let Some(Op::Label(exit)) = ops.get(next.index() + 1) else {
            return Err("a FOR whose NEXT has no exit label".into());
        };
        if !matches!(ops.get(next.index()), Some(Op::Next { head }) if head.index() == i) {
            return Err("a FOR whose NEXT does not point back at it".into());
        }
        self.allocate(*exit, Role::Exit)?;
        self.loops.push((i, *exit));
        Ok(line(
            &head("", Group::Control(Flow::For))?,
            &[word(*limit, 1)?],
        ))
    }

    fn is_exit(&self, l: LabelId) -> bool {
        self.roles.get(l.index()) == Some(&Some(Role::Exit))
    }

    /// Records that the text allocates label `l` now: the front end numbers labels in the
    /// order the text first mentions them.
    fn allocate(&mut self, l: LabelId, role: Role) -> Res<()> {
        if l.index() != self.next_label || l.index() >= self.roles.len() {
            return Err(format!(
                "label {} is not the next one the text allocates ({})",
                l.index(),
                self.next_label
            ));
        }
        self.roles[l.index()] = Some(role);
        self.next_label += 1;
        Ok(())
    }

    /// The jump number of label `l` (a jump at op `i` must go forward).
    fn number(&mut self, l: LabelId, i: usize) -> Res<String> {
        let pou = self.pou();
        let here = matches!(pou.ops.get(i), Some(Op::Label(_)));
        match pou.labels.get(l.index()) {
            Some(at) if (here && at.index() == i) || (!here && at.index() > i) => {}
            _ => return Err(format!("label {} is not ahead of its jump", l.index())),
        }
        let role = match self.roles.get(l.index()) {
            Some(Some(r)) => *r,
            _ => {
                if self.next_number > u32::from(self.profile.omron.max_jump) {
                    return Err("more jump labels than jump numbers".into());
                }
                let r = Role::Number(self.next_number);
                self.allocate(l, r)?;
                self.next_number += 1;
                r
            }
        };
        match role {
            Role::Number(n) => Ok(n.to_string()),
            Role::Exit => Err("a jump to a FOR exit that is not a BREAK".into()),
        }
    }
}

/// Whether the instruction printed from the ops at `j` is LD-type (a plain or comparison LD,
/// not FOR's `Load(P_On)`).
fn opens_block(ops: &[Op], j: usize) -> bool {
    let on = Op::Load(Contact::Bit {
        bit: SystemBit::On.bit_loc(),
        negated: false,
    });
    match ops.get(j) {
        Some(op) if *op == on => match (ops.get(j + 1), ops.get(j + 2), ops.get(j + 3)) {
            (Some(Op::For { .. }), ..) => false,
            (Some(Op::Omron(OmronBox::Compare { .. })), Some(Op::Pop), Some(flag)) => {
                matches!(flag, Op::Load(_))
            }
            _ => true,
        },
        Some(Op::Load(_)) => true,
        _ => false,
    }
}

/// `LD>=S` … from `Omron(Compare)` and the contact of the relation's flag.
fn compare_contact(cmp: &Op, flag_contact: &Op) -> Res<String> {
    let Op::Omron(OmronBox::Compare {
        double,
        signed,
        lhs,
        rhs,
    }) = *cmp
    else {
        return Err("not a compare".into());
    };
    let (join, flag) = match flag_contact {
        Op::Load(Contact::Bit {
            bit,
            negated: false,
        }) => (Join::Load, *bit),
        Op::And(Contact::Bit {
            bit,
            negated: false,
        }) => (Join::And, *bit),
        Op::Or(Contact::Bit {
            bit,
            negated: false,
        }) => (Join::Or, *bit),
        _ => return Err("a comparison contact without its flag contact".into()),
    };
    let op = CmpOp::ALL
        .iter()
        .copied()
        .find(|&o| relation_flag(o).bit_loc() == flag)
        .ok_or("a comparison contact reading a flag that is no relation")?;
    let prefix = COMPARE_JOINS.iter().find(|(_, j)| *j == join).map(|p| p.0);
    let rel = RELATIONS.iter().find(|r| r.1 == op).map(|r| r.0);
    let suffix = COMPARE_SUFFIXES
        .iter()
        .find(|s| s.1 == double && s.2 == signed);
    let (Some(prefix), Some(rel), Some(&(suffix, _, _, plus))) = (prefix, rel, suffix) else {
        return Err("no comparison contact spells this".into());
    };
    let code = RELATIONS.iter().find(|r| r.1 == op).map_or(0, |r| r.2) + plus;
    let w = if double { 2 } else { 1 };
    let (l, r) = (word(lhs, w)?, word(rhs, w)?);
    if matches!(lhs, Operand::Omron(_)) || matches!(rhs, Operand::Omron(_)) {
        return Err("a comparison contact with an indirect operand".into());
    }
    Ok(line(&format!("{prefix}{rel}{suffix}({code:03})"), &[l, r]))
}

mod circuits;
mod operands;
#[cfg(test)]
mod tests;
