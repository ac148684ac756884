//! The printing of one POU body (or one task's part of the main POU): the op patterns of the
//! contacts, outputs and data instructions read back into instruction lines; the program
//! control (jumps, FOR, IL, step areas) is in `control`.

use super::circuits;
use super::operands::{bit_text, ea_operand, tr, word};
use super::refresh::{self, Dir, load_on};
use super::{PrintError, edge_option, head, line, with_code};
use crate::immediate::{data_refresh, reads_of_bit, reads_of_words, writes_of_bit};
use crate::mnemonics::{
    COMPARE_JOINS, COMPARE_OPTIONS, COMPARE_SUFFIXES, Flow, Group, Join, RELATIONS, relation_flag,
};
use stljit_core::ir::{BitLoc, BoxOp, CmpOp, Contact, OmronBox, Op, Operand, PouKind, Program};
use stljit_core::{Area, CpuProfile, LabelId};

pub(super) type Res<T> = Result<T, String>;

/// A printed instruction line, and for the `NOT` that starts an unfolded `NOT; OUT b; NOT`
/// (or `NOT; CJP n; NOT`) the one line the three fold into (`OUT NOT b`, `JMP n`).
pub(super) struct Line {
    pub(super) text: String,
    pub(super) folded: Option<String>,
}

impl Line {
    pub(super) fn plain(text: String) -> Line {
        Line { text, folded: None }
    }
}

/// What a label of the POU is in the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Role {
    /// A jump number (`JMP n` / `JME n`).
    Number(u32),
    /// The exit of a FOR loop (placed by its NEXT, reached by BREAK).
    Exit,
    /// The end of a block program in a step area (`BPRG n` / `BEND`).
    Block,
}

/// The printing state of one POU (or one task of the main POU).
pub(super) struct Body<'a> {
    pub(super) program: &'a Program,
    pub(super) profile: &'static CpuProfile,
    pub(super) pou: usize,
    /// What each label id is, once the text has allocated it.
    pub(super) roles: Vec<Option<Role>>,
    /// The label id the front end allocates next (it allocates in text order).
    pub(super) next_label: usize,
    /// The jump number given next.
    pub(super) next_number: u32,
    /// The block program number given next.
    pub(super) next_block: u32,
    /// The open FOR loops: the index of their `For` and their exit label.
    pub(super) loops: Vec<(usize, LabelId)>,
    /// An IL(002) is open.
    pub(super) interlock: bool,
    /// The open step area: the current step's bit, and whether the area is inside IL–ILC.
    pub(super) step: Option<(BitLoc, bool)>,
}

impl<'a> Body<'a> {
    /// The body of POU `pou` whose first label is `first_label` (a task's part of the main
    /// POU starts behind the labels of the tasks before it).
    pub(super) fn new(program: &'a Program, pou: usize, first_label: usize) -> Body<'a> {
        Body {
            program,
            profile: program.profile.profile(),
            pou,
            roles: vec![None; program.pous[pou].labels.len()],
            next_label: first_label,
            next_number: 0,
            next_block: 0,
            loops: Vec::new(),
            interlock: false,
            step: None,
        }
    }

    /// Prints `ops[start..]` (`ops` is the POU's ops up to the end of the part printed, without
    /// its final END/RET; indices are the POU's).
    pub(super) fn print(
        mut self,
        ops: &[Op],
        start: usize,
        out: &mut String,
    ) -> Result<(), PrintError> {
        let mut lines = Vec::new();
        let mut i = start;
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
            // `NOT; OUT a; NOT; OUT b; NOT; <refresh of b>` is `NOT / OUT a / !OUT NOT b`: a
            // fold that only the folded form gives wins the shared NOT.
            let later = matches!(ops.get(i + 2), Some(Op::Not))
                && self.fold_only(ops, i + 2).map_err(err)?;
            if let Some((folded, used, always)) = self.fold(ops, i).map_err(err)?
                && (always || !later)
            {
                if always || !opens_block(ops, i + used) {
                    lines.push(Line::plain(folded));
                    i += used;
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
        let open = if !self.loops.is_empty() {
            Some("a FOR loop has no NEXT")
        } else if self.step.is_some() {
            Some("a step area is not closed")
        } else {
            None
        };
        match open {
            Some(message) => Err(PrintError::at_pou(self.pou, message)),
            None => Ok(()),
        }
    }

    /// The text of the instruction whose ops start at `i`, and how many ops it covers.
    fn instruction(&mut self, ops: &[Op], i: usize) -> Res<(String, usize)> {
        let at = |k: usize| ops.get(i + k);
        match &ops[i] {
            op if *op == load_on() => self.load_on(ops, i),
            Op::Load(_) | Op::And(_) | Op::Or(_) => self.contact(ops, i, None),
            Op::Not => Ok((line(&head("", Group::Not)?, &[]), 1)),
            Op::AndBlock => Ok((line(&head("", Group::Block(Join::And))?, &[]), 1)),
            Op::OrBlock => Ok((line(&head("", Group::Block(Join::Or))?, &[]), 1)),
            Op::Edge { falling, .. } => Ok((line(&head("", Group::Edge(*falling))?, &[]), 1)),
            Op::Assign {
                bit,
                immediate: false,
            } => self.out(ops, i + 1, *bit, false),
            Op::SetRange {
                start,
                value: false,
                immediate: false,
                ..
            } if matches!(
                (at(1), at(2), at(3)),
                (Some(Op::Not), Some(Op::AndBlock), Some(Op::SetRange { start: s, value: true, immediate: false, count }))
                    if s == start && *count == Operand::Const(1)
            ) =>
            {
                let b = self.coil(&ops[i], true)?;
                let (opt, used) = match refresh::always(ops, i + 4, Dir::Write) {
                    Some((bytes, n)) => {
                        refresh::check(&bytes, &writes_of_bit(*start))?;
                        ("!", 4 + n)
                    }
                    None => ("", 4),
                };
                Ok((line(&head(opt, Group::Keep)?, &[b]), used))
            }
            Op::SetRange { .. } if self.snxt(ops, i).is_some() => {
                let next = self.snxt(ops, i).ok_or("not SNXT")?;
                let h = head("", Group::Control(Flow::Snxt))?;
                Ok((line(&h, &[bit_text(next)?]), 2))
            }
            Op::SetRange { .. }
            | Op::Omron(_)
            | Op::Call(_)
            | Op::Box(BoxOp::ImmediateRead { .. }) => self.executed(ops, i, None),
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
            Op::Interlock => self.interlock(),
            Op::InterlockEnd => self.interlock_end(ops, i),
            Op::Jump(l) => self.jump(*l, i),
            Op::Label(l) => self.label(*l, i),
            Op::Next { head: h } => self.next(ops, i, h.index()),
            other => Err(format!(
                "{other:?} is not an op the Omron front end emits here"
            )),
        }
    }

    /// The instruction at a `Load(P_On)`: a `!` contact's refresh, a step area's saved gate,
    /// a comparison contact, FOR, or `LD P_On`.
    fn load_on(&mut self, ops: &[Op], i: usize) -> Res<(String, usize)> {
        if let Some((bytes, n)) = refresh::always(ops, i, Dir::Read) {
            let (text, used) = if is_compare(ops, i + n) {
                compare_contact(ops, i + n, Some(&bytes))?
            } else {
                self.contact(ops, i + n, Some(&bytes))?
            };
            return Ok((text, n + used));
        }
        if let Some(used) = self.saved_gate(ops, i) {
            let (text, rest) = self.step_open(ops, i + used, true)?;
            return Ok((text, used + rest));
        }
        if is_compare(ops, i) {
            return compare_contact(ops, i, None);
        }
        if let Some(Op::For { .. }) = ops.get(i + 1) {
            return Ok((self.for_loop(ops, i + 1)?, 2));
        }
        self.contact(ops, i, None)
    }

    /// `LD`/`AND`/`OR` (NOT forms), `LD TRn`, and the differentiated contacts (`Load; Edge` =
    /// `@LD`, `Load; Edge; AndBlock` = `@AND`, `… OrBlock` = `@OR`); `!` when `refreshed` holds
    /// the bytes of its every-cycle refresh.
    fn contact(&mut self, ops: &[Op], i: usize, refreshed: Option<&[u32]>) -> Res<(String, usize)> {
        let (join, c) = match &ops.get(i) {
            Some(Op::Load(c)) => (Join::Load, c),
            Some(Op::And(c)) => (Join::And, c),
            Some(Op::Or(c)) => (Join::Or, c),
            _ => return Err("a refresh that no contact follows".into()),
        };
        let Contact::Bit { bit, negated } = *c else {
            return Err(format!("{c:?} is not an Omron contact"));
        };
        if bit.area == Area::Tr {
            if join != Join::Load || negated || refreshed.is_some() {
                return Err("a TR bit is only read by a plain LD".into());
            }
            let h = head("", Group::Contact(Join::Load, false))?;
            return Ok((line(&h, &[tr(bit)]), 1));
        }
        if let Some(bytes) = refreshed {
            refresh::check(bytes, &reads_of_bit(bit))?;
        }
        let opt = if refreshed.is_some() { "!" } else { "" };
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

    /// `OUT`/`OUT NOT b` (`OUT TRn`), `!` when the every-cycle refresh of its word follows at
    /// `j`: the text and the ops it covers from its `Assign` (3 for OUT NOT's `Not; Assign;
    /// Not`, else 1) on.
    pub(super) fn out(
        &self,
        ops: &[Op],
        j: usize,
        bit: BitLoc,
        negated: bool,
    ) -> Res<(String, usize)> {
        let own = if negated { 3 } else { 1 };
        if bit.area == Area::Tr {
            if negated {
                return Err("a TR bit is only written by a plain OUT".into());
            }
            return Ok((line(&head("", Group::Out(false))?, &[tr(bit)]), own));
        }
        let (opt, used) = match refresh::always(ops, j, Dir::Write) {
            Some((bytes, n)) => {
                refresh::check(&bytes, &writes_of_bit(bit))?;
                ("!", own + n)
            }
            None => ("", own),
        };
        Ok((
            line(&head(opt, Group::Out(negated))?, &[bit_text(bit)?]),
            used,
        ))
    }

    /// The coil of a `SetRange` (count 1).
    fn coil(&self, op: &Op, keep: bool) -> Res<String> {
        let Op::SetRange {
            start,
            count: Operand::Const(1),
            immediate: false,
            ..
        } = op
        else {
            return Err("a set/reset of more than one bit, or an S7 immediate one".into());
        };
        if keep && start.area == Area::Tr {
            return Err("KEEP of a TR bit".into());
        }
        bit_text(*start)
    }

    /// SNXT(009) at `i` (`SetRange(current step, 0); SetRange(B, 1)` in a step area): B.
    fn snxt(&self, ops: &[Op], i: usize) -> Option<BitLoc> {
        let (current, _) = self.step?;
        let one = |op: Option<&Op>, v: bool| match op {
            Some(Op::SetRange {
                start,
                count: Operand::Const(1),
                value,
                immediate: false,
            }) if *value == v => Some(*start),
            _ => None,
        };
        (one(ops.get(i), false)? == current)
            .then(|| one(ops.get(i + 1), true))
            .flatten()
    }

    /// An instruction that refreshes when it executes (SET/RSET, a data box, SBS) at `i`:
    /// `[ImmediateRead…]; <op>; [ImmediateWrite…]`, with `edge` as its `@`/`%` option.
    fn executed(&self, ops: &[Op], i: usize, edge: Option<bool>) -> Res<(String, usize)> {
        let reads = refresh::boxes(ops, i, Dir::Read);
        let at = i + reads.len();
        let op = ops.get(at).ok_or("refresh boxes at the end")?;
        let writes = refresh::boxes(ops, at + 1, Dir::Write);
        let bang = !reads.is_empty() || !writes.is_empty();
        if bang {
            let (r, w) = match op {
                Op::SetRange { start, .. } => (Vec::new(), writes_of_bit(*start)),
                Op::Omron(b) => data_refresh(b),
                other => return Err(format!("refresh boxes around {other:?}")),
            };
            refresh::check(&reads, &r)?;
            refresh::check(&writes, &w)?;
        }
        let mut opt = String::from(if bang { "!" } else { "" });
        if let Some(falling) = edge {
            opt.push_str(edge_option(falling));
        }
        let text = match op {
            Op::SetRange { value, .. } => {
                let b = self.coil(op, false)?;
                line(&head(&opt, Group::SetReset(*value))?, &[b])
            }
            Op::Omron(b) => self.data_box(b, &opt)?,
            Op::Call(p) => {
                let callee = self
                    .program
                    .pous
                    .get(p.index())
                    .ok_or("a call to a missing POU")?;
                let PouKind::Subroutine(n) = callee.kind else {
                    return Err("a call to a POU that is not a subroutine".into());
                };
                line(&head(&opt, Group::Control(Flow::Sbs))?, &[n.to_string()])
            }
            other => return Err(format!("{other:?} is not an output instruction")),
        };
        Ok((text, reads.len() + 1 + writes.len()))
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
        let (text, used) = self.executed(ops, i + 2, Some(*falling))?;
        if ops.get(i + 2 + used) != Some(&Op::Pop) {
            return Err("`Dup; Edge` is not an @/% output or DIFU/DIFD".into());
        }
        Ok((text, used + 3))
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
                if e.ends_with('%') {
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
}

/// Whether the ops at `j` are a comparison contact (`Load(P_On); Compare; Pop; <flag>`).
fn is_compare(ops: &[Op], j: usize) -> bool {
    ops.get(j) == Some(&load_on())
        && matches!(
            (ops.get(j + 1), ops.get(j + 2), ops.get(j + 3)),
            (
                Some(Op::Omron(OmronBox::Compare { .. })),
                Some(Op::Pop),
                Some(_)
            )
        )
}

/// Whether the instruction printed from the ops at `j` is LD-type (a plain, `!` or comparison
/// LD, not FOR's `Load(P_On)` or a step area's saved gate).
pub(super) fn opens_block(ops: &[Op], j: usize) -> bool {
    if let Some((_, n)) = refresh::always(ops, j, Dir::Read) {
        return opens_block(ops, j + n);
    }
    match ops.get(j) {
        Some(op) if *op == load_on() => match (ops.get(j + 1), ops.get(j + 2), ops.get(j + 3)) {
            (Some(Op::For { .. }), ..) => false,
            (Some(Op::Assign { .. }), Some(Op::Pop), Some(Op::InterlockEnd)) => false,
            (Some(Op::Omron(OmronBox::Compare { .. })), Some(Op::Pop), Some(flag)) => {
                matches!(flag, Op::Load(_))
            }
            _ => true,
        },
        Some(Op::Load(_)) => true,
        _ => false,
    }
}

/// `LD>=S` … from the ops at `i` (`Load(P_On); Compare; Pop; <flag contact>`), `!` when
/// `refreshed` holds the bytes of its every-cycle refresh.
fn compare_contact(ops: &[Op], i: usize, refreshed: Option<&[u32]>) -> Res<(String, usize)> {
    let Some(&Op::Omron(OmronBox::Compare {
        double,
        signed,
        lhs,
        rhs,
    })) = ops.get(i + 1)
    else {
        return Err("not a compare".into());
    };
    let (join, flag) = match ops.get(i + 3) {
        Some(Op::Load(Contact::Bit {
            bit,
            negated: false,
        })) => (Join::Load, *bit),
        Some(Op::And(Contact::Bit {
            bit,
            negated: false,
        })) => (Join::And, *bit),
        Some(Op::Or(Contact::Bit {
            bit,
            negated: false,
        })) => (Join::Or, *bit),
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
    if let Some(bytes) = refreshed {
        if !COMPARE_OPTIONS.immediate {
            return Err("`!` on a comparison contact".into());
        }
        refresh::check(bytes, &reads_of_words(&[lhs, rhs], w))?;
    }
    let bang = if refreshed.is_some() { "!" } else { "" };
    Ok((
        line(&format!("{bang}{prefix}{rel}{suffix}({code:03})"), &[l, r]),
        4,
    ))
}
