//! Program control as properly nested regions of one POU: IL–ILC (and, now and then, a second
//! IL sharing the ILC: W022), JMP/CJP/CJPN–JME with several jumps to one JME, JMP0–JME0,
//! FOR–NEXT with BREAK and jumps that leave the loop, and subroutine calls (a DAG, or any
//! subroutine in programs with recursion, which ends at the nesting limit).
//!
//! Jumps go forward to a JME of the same POU and IL level, and no JME sits inside a loop its
//! jump is outside of (E023, E026): a region's JME is written where the region closes, and a
//! jump that leaves a loop targets a JME written right after that loop's NEXT.

use super::{Ctx, OmronGen};
use stljit_front_omron::mnemonics::{Flow, Group};

impl OmronGen<'_, '_> {
    /// An unused jump number of the current POU.
    pub(crate) fn new_jump(&mut self) -> Option<u32> {
        let max = u32::from(self.p.omron.max_jump);
        for _ in 0..6 {
            let n = if self.c.chance(1, 10) {
                max - self.c.below(3)
            } else {
                self.c.below(32)
            };
            if self.jumps.insert(n) {
                return Some(n);
            }
        }
        None
    }

    /// A jump number as written: `&5`, `5` or `#0005`.
    pub(crate) fn jump_text(&mut self, n: u32) -> String {
        match self.c.weighted(&[3, 2, 1]) {
            0 => format!("&{n}"),
            1 => n.to_string(),
            _ => format!("#{n:04X}"),
        }
    }

    /// JMP, CJP or CJPN to `n` on a fresh condition.
    pub(crate) fn jump_to(&mut self, n: u32) {
        self.condition(0, 0);
        let flow = [Flow::Jmp, Flow::Cjp, Flow::Cjpn][self.c.weighted(&[3, 2, 2])];
        let t = self.jump_text(n);
        self.op("", Group::Control(flow), &[t]);
    }

    /// `count` rungs of a region's body in `ctx`.
    fn body(&mut self, ctx: &Ctx, count: u32) {
        for _ in 0..count {
            if !self.room() {
                break;
            }
            self.rung(ctx);
        }
    }

    /// `cond IL(002)` … `ILC(003)`; inside a region already, only the extra IL (W022).
    pub(crate) fn interlock(&mut self, ctx: &Ctx) {
        self.condition(0, 0);
        if self.c.chance(1, 4) {
            self.bit_output();
        }
        self.op("", Group::Control(Flow::Il), &[]);
        if ctx.in_il {
            return;
        }
        let inner = Ctx {
            in_il: true,
            depth: ctx.depth + 1,
            loop_exits: Vec::new(),
            ..ctx.clone()
        };
        let n = self.c.range(1, 4);
        self.body(&inner, n);
        self.op("", Group::Control(Flow::Ilc), &[]);
    }

    /// A jump over a few rungs, sometimes two jumps to the same JME.
    pub(crate) fn jump_region(&mut self, ctx: &Ctx) {
        let Some(n) = self.new_jump() else {
            return self.logic_rung();
        };
        self.jump_to(n);
        let inner = Ctx {
            depth: ctx.depth + 1,
            ..ctx.clone()
        };
        let k = self.c.range(0, 3);
        self.body(&inner, k);
        if self.c.chance(1, 3) {
            self.jump_to(n);
            let k = self.c.range(0, 2);
            self.body(&inner, k);
        }
        let t = self.jump_text(n);
        self.op("", Group::Control(Flow::Jme), &[t]);
    }

    /// `cond JMP0(515)` … `JME0(516)`, sometimes with a second JMP0 inside.
    pub(crate) fn jmp0_region(&mut self, ctx: &Ctx) {
        self.condition(0, 0);
        self.op("", Group::Control(Flow::Jmp0), &[]);
        let inner = Ctx {
            in_jmp0: true,
            depth: ctx.depth + 1,
            ..ctx.clone()
        };
        let k = self.c.range(0, 3);
        self.body(&inner, k);
        if self.c.chance(1, 3) {
            self.condition(0, 0);
            self.op("", Group::Control(Flow::Jmp0), &[]);
            let k = self.c.range(0, 2);
            self.body(&inner, k);
        }
        self.op("", Group::Control(Flow::Jme0), &[]);
    }

    /// `FOR(503) N` … `NEXT(504)`: mostly a few passes, sometimes a word count (anything,
    /// up to zero passes above 32767) or enough passes to meet the loop budget; BREAK and
    /// jumps out of the loop come from [`OmronGen::leave_loop`] in the body.
    pub(crate) fn for_loop(&mut self, ctx: &Ctx) {
        let count = match self.c.weighted(&[6, 1, 2, 1]) {
            0 => format!("&{}", self.c.below(5)),
            1 => format!("#{:04}", self.c.below(5)),
            2 => self.loc_word(1, false),
            _ => format!("&{}", self.c.range(20, 60)),
        };
        let exit = if self.c.chance(1, 4) {
            self.new_jump()
        } else {
            None
        };
        self.op("", Group::Control(Flow::For), &[count]);
        let inner = Ctx {
            for_depth: ctx.for_depth + 1,
            depth: ctx.depth + 1,
            loop_exits: exit.into_iter().collect(),
            ..ctx.clone()
        };
        let k = self.c.range(1, 3);
        self.body(&inner, k);
        self.op("", Group::Control(Flow::Next), &[]);
        if let Some(n) = exit {
            let t = self.jump_text(n);
            self.op("", Group::Control(Flow::Jme), &[t]);
        }
    }

    /// Inside a loop: `cond BREAK(514)`, or a jump to a JME after the loop's NEXT.
    pub(crate) fn leave_loop(&mut self, ctx: &Ctx) {
        if !ctx.loop_exits.is_empty() && self.c.chance(1, 3) {
            let n = self.c.pick(&ctx.loop_exits);
            return self.jump_to(n);
        }
        self.condition(0, 0);
        self.op("", Group::Control(Flow::Break), &[]);
    }

    /// Whether the POU being written may call a subroutine.
    pub(crate) fn has_callee(&self) -> bool {
        match self.current_sub {
            None => !self.subs.is_empty(),
            Some(i) => i + 1 < self.subs.len() || self.recursion,
        }
    }

    /// `cond SBS(091) n` (or `@SBS`): a later subroutine, or with recursion any.
    pub(crate) fn call_rung(&mut self) {
        let first = match self.current_sub {
            Some(i) if !self.recursion || self.c.chance(3, 4) => i + 1,
            _ => 0,
        };
        if first >= self.subs.len() {
            return self.logic_rung();
        }
        let i = self.c.range(first as u32, self.subs.len() as u32 - 1) as usize;
        let n = self.subs[i];
        self.condition(0, 0);
        let options = self.options(Group::Control(Flow::Sbs));
        self.op(&options, Group::Control(Flow::Sbs), &[n.to_string()]);
    }
}
