//! Control-flow constructs: forward jumps, bounded backward loops, FOR/NEXT nests, unstructured
//! ("wild") jumps and SCR sections. Each keeps the structure rules of [`super::programs`]: jumps
//! stay inside their POU and out of SCR segments, WDR never sits inside a loop, so every loop
//! either exits or runs into the watchdog.

use super::operands::Class;
use super::programs::{on, sm};
use super::{Ctx, Gen};
use stljit_core::ir::{BitLoc, BoxOp, CmpOp, CmpType, Contact, Loc, Op, Operand};
use stljit_core::{Area, OpIdx, Width};

impl Gen<'_, '_> {
    /// Unstructured jumps: a jump to a label placed later at a random network boundary outside
    /// every FOR body, or back to one placed earlier (possibly out of a FOR body).
    pub(crate) fn wild_jump(&mut self) {
        let back = !self.placed_wild.is_empty() && self.c.chance(1, 3);
        let l = if back {
            self.c.pick(&self.placed_wild.clone())
        } else {
            match self.new_label() {
                Some(l) => {
                    self.pending_wild.push(l);
                    l
                }
                None => return,
            }
        };
        self.expr(1);
        self.emit(Op::Jump(l));
    }

    /// Places some pending wild-jump labels here: never inside an SCR segment, and never inside
    /// a FOR body, since a jump from outside into one is rejected (spec §2.5, verifier rule
    /// `JumpIntoLoop`); jumps *out of* FOR bodies stay covered.
    pub(crate) fn place_wild(&mut self, ctx: Ctx) {
        if ctx.scr.is_some()
            || ctx.for_depth > 0
            || self.pending_wild.is_empty()
            || !self.c.chance(1, 3)
        {
            return;
        }
        let i = self.c.below(self.pending_wild.len() as u32) as usize;
        let l = self.pending_wild.swap_remove(i);
        self.place_label(l);
        self.placed_wild.push(l);
    }

    /// `cond; JMP l; <body>; LBL l`.
    pub(crate) fn forward_jump(&mut self, ctx: Ctx) {
        let Some(l) = self.new_label() else {
            return;
        };
        self.expr(1);
        self.emit(Op::Jump(l));
        self.body(Ctx {
            depth: ctx.depth + 1,
            ..ctx
        });
        self.place_label(l);
    }

    /// `LBL l; <body>; cond; JMP l`, with a loop counter unless endless loops are allowed.
    pub(crate) fn backward_loop(&mut self, ctx: Ctx) {
        let Some(l) = self.new_label() else {
            return;
        };
        let bounded = !self.allow_endless || self.c.chance(3, 4);
        let cell = self.loop_cell(u32::from(ctx.depth) % 4);
        if bounded {
            self.emit(Op::Load(on(sm(0, 0))));
            self.emit(Op::Box(BoxOp::Move {
                width: Width::Word,
                src: Operand::Const(0),
                dst: Operand::Mem(cell),
            }));
        }
        self.place_label(l);
        self.body(Ctx {
            in_loop: true,
            depth: ctx.depth + 1,
            ..ctx
        });
        if bounded {
            self.emit(Op::Load(on(sm(0, 0))));
            self.emit(Op::Box(BoxOp::Step {
                width: Width::Word,
                up: true,
                dst: Operand::Mem(cell),
            }));
            let rhs = Operand::Const(self.c.range(1, 6));
            self.emit(Op::Load(Contact::Compare {
                ty: CmpType::Int,
                op: CmpOp::Lt,
                lhs: Operand::Mem(cell),
                rhs,
            }));
        } else {
            self.expr(1);
        }
        self.emit(Op::Jump(l));
    }

    /// `cond; FOR idx, init, final; <body>; NEXT`.
    pub(crate) fn for_loop(&mut self, ctx: Ctx) {
        if self.c.chance(2, 3) {
            self.emit(Op::Load(on(sm(0, 0))));
        } else {
            self.expr(1);
        }
        let index = match self.c.weighted(&[6, 1, 1]) {
            0 => Operand::Mem(self.loop_cell(4 + u32::from(ctx.for_depth))),
            1 => Operand::Mem(Loc {
                area: Area::L,
                offset: 2 * self.c.below(8),
            }),
            _ => self.value(Width::Word, Class::OUT),
        };
        let init_v = self.c.range(0, 3);
        let mut init = Operand::Const(init_v);
        let mut limit = if self.c.chance(5, 6) {
            // Nested loops multiply; keep inner ones short.
            let span = if ctx.for_depth > 1 { 1 } else { 4 };
            Operand::Const((init_v + self.c.below(span + 1)).wrapping_sub(self.c.below(2)) & 0xFFFF)
        } else {
            self.value(Width::Word, Class::IN)
        };
        // Operands overlapping INDX (spec §4.14 order: INDX := INIT, then FINAL is read), and
        // writes to INDX inside the body, so the evaluation order stays covered (issue 16).
        let mut bump_index = false;
        if let Operand::Mem(at) = index {
            // Only byte-granular areas, with room for a word one byte past the index.
            let size = match at.area {
                Area::V => self.p.variable_memory,
                Area::L => self.p.local_frame,
                _ => 0,
            };
            if at.offset + 3 <= size && self.c.chance(1, 5) {
                let near = |g: &mut Self| {
                    Operand::Mem(Loc {
                        offset: at.offset.saturating_sub(1) + g.c.below(3),
                        ..at
                    })
                };
                match self.c.weighted(&[3, 1, 1]) {
                    0 => limit = near(self),
                    1 => init = near(self),
                    _ => (init, limit) = (near(self), near(self)),
                }
            }
            bump_index = self.c.chance(1, 6);
        }
        let head = self.emit(Op::For {
            index,
            init,
            limit,
            next: OpIdx(0),
        });
        if bump_index {
            // Counting down against NEXT's increment never ends: only where endless loops are.
            let up = !self.allow_endless || self.c.chance(3, 4);
            self.emit(Op::Load(on(sm(0, 0))));
            self.emit(Op::Box(BoxOp::Step {
                width: Width::Word,
                up,
                dst: index,
            }));
        }
        self.body(Ctx {
            in_loop: true,
            for_depth: ctx.for_depth + 1,
            depth: ctx.depth + 1,
            ..ctx
        });
        let next = self.emit(Op::Next { head });
        if let Op::For { next: n, .. } = &mut self.ops[head.index()] {
            *n = next;
        }
    }

    /// The inside of a construct: zero to three networks (a FOR nest may grow past depth 3 by
    /// itself, so that nesting up to the profile's limit is reached sometimes).
    pub(crate) fn body(&mut self, ctx: Ctx) {
        if ctx.for_depth > 0 && ctx.for_depth < self.p.max_for_depth && self.c.chance(1, 4) {
            self.for_loop(Ctx {
                depth: ctx.depth.min(2),
                ..ctx
            });
            return;
        }
        for _ in 0..self.c.below(4) {
            if !self.room() {
                return;
            }
            self.network(ctx);
        }
    }

    /// An SCR section: steps in this POU's own S byte, entered by the first scan.
    pub(crate) fn scr_section(&mut self) {
        let byte = self.pou.0;
        if byte >= self.p.sequence_relays {
            return;
        }
        let step = |bit: u32| BitLoc {
            area: Area::S,
            byte,
            bit: bit as u8,
        };
        self.emit(Op::Load(on(sm(0, 1))));
        self.emit(Op::SetRange {
            start: step(0),
            count: Operand::Const(1),
            value: true,
            immediate: false,
        });
        let n = self.c.range(1, 4);
        for i in 0..n {
            let me = step(i);
            self.emit(Op::ScrBegin { bit: me });
            let ctx = Ctx {
                scr: Some(me),
                ..Ctx::default()
            };
            let mut cond_ends = Vec::new();
            for _ in 0..self.c.range(1, 3) {
                match self.c.weighted(&[6, 3, 1]) {
                    0 => self.network(ctx),
                    1 => {
                        self.expr(1);
                        let to = step((i + 1 + self.c.below(n)) % n);
                        self.emit(Op::ScrTransition { to, from: me });
                    }
                    _ => {
                        self.expr(1);
                        cond_ends.push(self.emit(Op::ScrCondEnd { end: OpIdx(0) }));
                    }
                }
            }
            let end = self.emit(Op::ScrEnd);
            for at in cond_ends {
                self.ops[at.index()] = Op::ScrCondEnd { end };
            }
        }
    }
}
