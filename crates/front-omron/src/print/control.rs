//! Program control read back: jumps and their labels (numbered in the order the text first
//! mentions them, as the front end allocates them; backward when the program was compiled with
//! `allow_backward_jumps`), FOR/NEXT/BREAK, IL/ILC, and step areas (`STEP B` … `STEP`, SNXT
//! is in `body`) with the block programs inside them.

use super::body::{Body, Res, Role};
use super::refresh::load_on;
use super::{control, line};
use crate::mnemonics::{Flow, Group};
use stljit_core::Area;
use stljit_core::LabelId;
use stljit_core::ir::{BitLoc, Contact, Loc, Op, Operand};

impl Body<'_> {
    /// The folded text of `Not; Assign; Not` (`OUT NOT b`, `!OUT NOT b` with its refresh) or
    /// `Not; Jump; Not` (`JMP n`, or `BPRG n` in a step area) at `i`, if the ops there are one:
    /// the text, the ops it covers, and whether only the folded form gives these ops.
    pub(super) fn fold(&mut self, ops: &[Op], i: usize) -> Res<Option<(String, usize, bool)>> {
        if let Some(bit) = out_not(ops, i) {
            let (text, used) = self.out(ops, i + 3, bit, true)?;
            return Ok(Some((text, used, used > 3)));
        }
        match (ops.get(i), ops.get(i + 1), ops.get(i + 2)) {
            (Some(Op::Not), Some(Op::Jump(l)), Some(Op::Not)) if !self.is_exit(*l) => {
                if self.step.is_some() {
                    let n = self.next_block;
                    if n >= u32::from(self.profile.omron.block_programs) {
                        return Err("more block programs than block numbers".into());
                    }
                    self.allocate(*l, Role::Block)?;
                    self.next_block += 1;
                    return Ok(Some((control(Flow::Bprg, &[n.to_string()])?, 3, true)));
                }
                let n = self.number(*l, i + 1)?;
                Ok(Some((control(Flow::Jmp, &[n])?, 3, false)))
            }
            _ => Ok(None),
        }
    }

    /// Whether the ops at `i` are a fold only its folded form gives (`!OUT NOT b` with its
    /// refresh), without allocating anything.
    pub(super) fn fold_only(&self, ops: &[Op], i: usize) -> Res<bool> {
        match out_not(ops, i) {
            Some(bit) => Ok(self.out(ops, i + 3, bit, true)?.1 > 3),
            None => Ok(false),
        }
    }

    /// A lone `Jump`: BREAK (to the innermost loop's exit) or CJP.
    pub(super) fn jump(&mut self, l: LabelId, i: usize) -> Res<(String, usize)> {
        if self.loops.last().is_some_and(|(_, exit)| *exit == l) {
            return Ok((control(Flow::Break, &[])?, 1));
        }
        if self.step.is_some() {
            return Err("a jump inside a step area".into());
        }
        let n = self.number(l, i)?;
        Ok((control(Flow::Cjp, &[n])?, 1))
    }

    /// A `Label`: JME, or BEND of a block program.
    pub(super) fn label(&mut self, l: LabelId, i: usize) -> Res<(String, usize)> {
        match self.roles.get(l.index()).copied().flatten() {
            Some(Role::Exit) => Err("a FOR loop's exit label away from its NEXT".into()),
            Some(Role::Block) => Ok((control(Flow::Bend, &[])?, 1)),
            _ if self.step.is_some() => Err("a JME inside a step area".into()),
            _ => {
                let n = self.number(l, i)?;
                Ok((control(Flow::Jme, &[n])?, 1))
            }
        }
    }

    /// `Next` at `i` of the FOR whose `For` is at `head`, followed by the loop's exit label.
    pub(super) fn next(&mut self, ops: &[Op], i: usize, head: usize) -> Res<(String, usize)> {
        let Some((at_for, exit)) = self.loops.pop() else {
            return Err("NEXT without FOR".into());
        };
        if head != at_for || ops.get(i + 1) != Some(&Op::Label(exit)) {
            return Err("NEXT is not the FOR pattern (`Next` then its exit label)".into());
        }
        Ok((control(Flow::Next, &[])?, 2))
    }

    /// `Load(P_On); For{…}` at `i - 1`: `FOR(503) N`, its exit label allocated now.
    pub(super) fn for_loop(&mut self, ops: &[Op], i: usize) -> Res<String> {
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
        control(Flow::For, &[super::operands::word(*limit, 1)?])
    }

    /// `Interlock`: IL(002).
    pub(super) fn interlock(&mut self) -> Res<(String, usize)> {
        if self.step.is_some() {
            return Err("an interlock inside a step area".into());
        }
        self.interlock = true;
        Ok((control(Flow::Il, &[])?, 1))
    }

    /// `InterlockEnd` at `i`: the next step (`STEP B`), the end of the step area (`STEP`), a
    /// step area opening outside IL–ILC, or ILC(003).
    pub(super) fn interlock_end(&mut self, ops: &[Op], i: usize) -> Res<(String, usize)> {
        match self.step {
            Some((_, saved)) => {
                if self.step_at(ops, i, saved).is_some() {
                    return self.step_open(ops, i, saved);
                }
                self.step = None;
                let restore = [Op::Load(self.saved_bit()), Op::Interlock, Op::Pop];
                let used = if !saved {
                    1
                } else if ops.get(i + 1..i + 4) == Some(&restore[..]) {
                    4
                } else {
                    return Err("a step area inside IL–ILC ends without its gate restored".into());
                };
                Ok((control(Flow::Step, &[])?, used))
            }
            None if !self.interlock && self.step_at(ops, i, false).is_some() => {
                self.step_open(ops, i, false)
            }
            None => {
                self.interlock = false;
                Ok((control(Flow::Ilc, &[])?, 1))
            }
        }
    }

    /// `STEP B` at `i` (`InterlockEnd; Load(B); [And(saved)]; Interlock; Pop`).
    pub(super) fn step_open(&mut self, ops: &[Op], i: usize, saved: bool) -> Res<(String, usize)> {
        let (bit, used) = self
            .step_at(ops, i, saved)
            .ok_or("a step area's first STEP is not the STEP pattern")?;
        self.step = Some((bit, saved));
        let h = super::head("", Group::Control(Flow::Step))?;
        Ok((line(&h, &[super::operands::bit_text(bit)?]), used))
    }

    /// The step bit and op count of `InterlockEnd; Load(B); [And(saved)]; Interlock; Pop` at
    /// `i` (the `And` exactly when `saved`).
    fn step_at(&self, ops: &[Op], i: usize, saved: bool) -> Option<(BitLoc, usize)> {
        let Some(Op::Load(Contact::Bit {
            bit,
            negated: false,
        })) = ops.get(i + 1)
        else {
            return None;
        };
        let mut want = vec![Op::InterlockEnd, ops[i + 1].clone()];
        if saved {
            want.push(Op::And(self.saved_bit()));
        }
        want.extend([Op::Interlock, Op::Pop]);
        (ops.get(i..i + want.len()) == Some(&want[..])).then_some((*bit, want.len()))
    }

    /// At a `Load(P_On)`: the op count of the first STEP's saving of the interlock's gate
    /// (`Load(P_On); Assign(saved); Pop` before the STEP pattern), inside IL–ILC with no step
    /// area open.
    pub(super) fn saved_gate(&self, ops: &[Op], i: usize) -> Option<usize> {
        let Contact::Bit { bit, .. } = self.saved_bit() else {
            return None;
        };
        let save = [
            load_on(),
            Op::Assign {
                bit,
                immediate: false,
            },
            Op::Pop,
        ];
        (self.interlock
            && self.step.is_none()
            && ops.get(i..i + 3) == Some(&save[..])
            && self.step_at(ops, i + 3, true).is_some())
        .then_some(3)
    }

    /// The front end's private bit holding the gate of the interlock around a step area (the
    /// first L byte after the FOR counters, bit 0) as a contact.
    fn saved_bit(&self) -> Contact {
        Contact::Bit {
            bit: BitLoc {
                area: Area::L,
                byte: 2 * u32::from(self.profile.max_for_depth),
                bit: 0,
            },
            negated: false,
        }
    }

    pub(super) fn is_exit(&self, l: LabelId) -> bool {
        self.roles.get(l.index()) == Some(&Some(Role::Exit))
    }

    /// Records that the text allocates label `l` now: the front end numbers labels in the
    /// order the text first mentions them.
    pub(super) fn allocate(&mut self, l: LabelId, role: Role) -> Res<()> {
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

    /// The jump number of label `l` mentioned by the jump or label op at `i`.
    pub(super) fn number(&mut self, l: LabelId, i: usize) -> Res<String> {
        let pou = &self.program.pous[self.pou];
        let here = matches!(pou.ops.get(i), Some(Op::Label(_)));
        match pou.labels.get(l.index()) {
            Some(at) if here == (at.index() == i) => {}
            _ => return Err(format!("label {} is not where its op says", l.index())),
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
            Role::Block => Err("a jump to a block program's end".into()),
        }
    }
}

/// The coil of `Not; Assign b; Not` at `i` (`OUT NOT b`; a TR bit is never one).
fn out_not(ops: &[Op], i: usize) -> Option<BitLoc> {
    match (ops.get(i), ops.get(i + 1), ops.get(i + 2)) {
        (
            Some(Op::Not),
            Some(Op::Assign {
                bit,
                immediate: false,
            }),
            Some(Op::Not),
        ) if bit.area != Area::Tr => Some(*bit),
        _ => None,
    }
}
