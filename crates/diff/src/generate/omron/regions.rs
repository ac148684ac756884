//! The regions main's front end added: step areas (`SNXT` into the first step, `STEP B` …
//! `STEP`, transitions by SNXT; inside IL–ILC too, where the front end saves the interlock's
//! gate), block programs (`BPRG N` … `BEND` on a condition, in a step area too; their body
//! without the instructions a block may not hold), and backward jumps (with the option): a JME,
//! the loop's body, then a CJP back while a counter word is below its limit, or, 1 time in 6,
//! on any condition (a loop the watchdog may end).

use super::{Ctx, OmronGen};
use stljit_front_omron::mnemonics::{self, Flow, Group, Join};

impl OmronGen<'_, '_> {
    /// A fresh step bit: work bits W16.00 on, one per step of the project (a SNXT and its STEP
    /// must be in one task: E025).
    fn step_bit(&mut self) -> String {
        let k = self.step_bits;
        self.step_bits += 1;
        format!("W{}.{:02}", 16 + k / 16, k % 16)
    }

    /// Whether a rung may read a step bit (one of the project's so far).
    pub(crate) fn some_step_bit(&mut self) -> Option<String> {
        (self.step_bits > 0).then(|| {
            let k = self.c.below(self.step_bits);
            format!("W{}.{:02}", 16 + k / 16, k % 16)
        })
    }

    /// `cond SNXT B0`, `STEP B0` … `cond SNXT Bk`, `STEP Bk` …, `STEP`.
    pub(crate) fn step_area(&mut self, ctx: &Ctx) {
        let n = self.c.range(1, 4) as usize;
        let bits: Vec<String> = (0..n).map(|_| self.step_bit()).collect();
        if self.c.chance(2, 3) {
            self.op(
                "",
                Group::Contact(Join::Load, false),
                &["P_First_Cycle".into()],
            );
        } else {
            self.condition(0, 0);
        }
        self.op("", Group::Control(Flow::Snxt), &[bits[0].clone()]);
        let inner = Ctx {
            in_step: true,
            depth: ctx.depth + 1,
            loop_exits: Vec::new(),
            ..ctx.clone()
        };
        for k in 0..n {
            self.op("", Group::Control(Flow::Step), &[bits[k].clone()]);
            for _ in 0..self.c.range(1, 3) {
                if !self.room() {
                    break;
                }
                self.rung(&inner);
            }
            // The transition: mostly to the next step (the last one back to the first), now
            // and then to any step, or two transitions on two conditions.
            for _ in 0..self.c.weighted(&[0, 5, 1]) {
                let to = if self.c.chance(3, 4) {
                    bits[(k + 1) % n].clone()
                } else {
                    self.c
                        .pick(&bits.iter().map(String::as_str).collect::<Vec<_>>())
                        .to_owned()
                };
                self.condition(0, 0);
                self.op("", Group::Control(Flow::Snxt), &[to]);
            }
        }
        self.op("", Group::Control(Flow::Step), &[]);
    }

    /// `cond BPRG N` … `BEND` with a body a block program allows.
    pub(crate) fn block_program(&mut self, ctx: &Ctx) {
        let max = u32::from(self.p.omron.block_programs);
        let mut n = if self.c.chance(1, 10) {
            max - 1
        } else {
            self.c.below(8)
        };
        if self.blocks.contains(&n) {
            let Some(free) = (0..max).find(|m| !self.blocks.contains(m)) else {
                return self.logic_rung();
            };
            n = free;
        }
        self.blocks.insert(n);
        self.condition(0, 0);
        let t = if self.c.chance(1, 3) {
            format!("&{n}")
        } else {
            n.to_string()
        };
        self.op("", Group::Control(Flow::Bprg), &[t]);
        let inner = Ctx {
            in_block: true,
            depth: ctx.depth + 1,
            loop_exits: Vec::new(),
            ..ctx.clone()
        };
        let was = std::mem::replace(&mut self.block, true);
        for _ in 0..self.c.range(1, 4) {
            if !self.room() {
                break;
            }
            self.rung(&inner);
        }
        self.block = was;
        self.op("", Group::Control(Flow::Bend), &[]);
    }

    /// `JME n`, the loop's body, and the jump back to it.
    pub(crate) fn backward_jump(&mut self, ctx: &Ctx) {
        let Some(n) = self.new_jump() else {
            return self.logic_rung();
        };
        let bounded = self.c.chance(5, 6);
        let counter = format!("D{}", 200 + self.loop_words % 40);
        self.loop_words += 1;
        if bounded {
            self.op("", Group::Contact(Join::Load, false), &["P_On".into()]);
            self.op("", Group::Move(false), &["#0000".into(), counter.clone()]);
        }
        let t = self.jump_text(n);
        self.op("", Group::Control(Flow::Jme), &[t]);
        let inner = Ctx {
            depth: ctx.depth + 1,
            ..ctx.clone()
        };
        for _ in 0..self.c.range(0, 2) {
            if !self.room() {
                break;
            }
            self.rung(&inner);
        }
        if !bounded {
            return self.jump_to(n);
        }
        self.op("", Group::Contact(Join::Load, false), &["P_On".into()]);
        let add = mnemonics::lookup("+").map(|m| (m.name, m.code));
        if let Some((name, code)) = add {
            let one = "#0001".to_owned();
            self.ins("", name, code, &[counter.clone(), one, counter.clone()]);
        }
        let limit = format!("&{}", self.c.range(1, 12));
        if let Some(cc) = mnemonics::compare("LD<") {
            self.ins("", "LD<", Some(cc.code), &[counter, limit]);
        }
        let t = self.jump_text(n);
        self.op("", Group::Control(Flow::Cjp), &[t]);
    }
}
