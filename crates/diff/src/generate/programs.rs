//! Networks and POUs: a boolean expression on the logic stack followed by coils and boxes, plus
//! the structured constructs (forward jumps, backward loops, FOR/NEXT, SCR sections, calls).
//!
//! Structure rules that keep programs valid and terminating: jumps are generated as nested
//! if/while shapes inside one POU and never cross a FOR/NEXT or SCR boundary; nothing that
//! jumps, loops or ends is placed inside an SCR segment; WDR appears only in the main program
//! outside every loop, so each loop either exits or runs into the watchdog.

use super::operands::Class;
use super::{Ctx, Gen, SubPlan};
use stljit_core::ir::{
    ArithOp, BitLoc, BoxOp, CmpOp, CmpType, Contact, CounterKind, Loc, Op, Operand, StackForm,
    TimerKind,
};
use stljit_core::{Area, CounterId, PouId, TimerId, Width};

impl Gen<'_, '_> {
    /// The main program: optional pointer setup, networks, an optional SCR section, calls that
    /// start every deep call chain.
    pub(crate) fn main_body(&mut self, plan: &[SubPlan]) {
        let ctx = Ctx::default();
        if !self.hsc_counters.is_empty() {
            self.hsc_setup();
        }
        if !self.pulse_channels.is_empty() {
            self.pulse_setup();
        }
        if self.comm {
            self.comm_setup();
        }
        if !self.int_routines.is_empty() {
            self.interrupt_setup();
        }
        if self.c.chance(1, 2) && !self.cfg.plain {
            self.pointer_setup();
        }
        let targets: Vec<PouId> = plan.iter().filter_map(|s| s.chain_next).collect();
        for (i, sub) in plan.iter().enumerate() {
            let id = PouId::new(i + 1);
            if sub.chain_next.is_some() && !targets.contains(&id) {
                let c = self.contact();
                self.emit(Op::Load(c));
                let op = self.call_op(id);
                self.emit(op);
            }
        }
        // Now and then a main program four times as long: straight-line code past the JIT's
        // basic-block cap.
        let big = self.c.chance(1, 25);
        let n = if big {
            self.room_limit = 4 * self.cfg.max_ops_per_pou;
            4 * self.cfg.max_networks
        } else {
            self.c.range(1, self.cfg.max_networks)
        };
        let scr_at = self.c.chance(1, 5).then(|| self.c.below(n + 1));
        for k in 0..=n {
            if !self.room() {
                break;
            }
            if scr_at == Some(k) {
                self.scr_section();
            }
            if k < n {
                self.network(ctx);
            }
        }
        if self.c.chance(1, 2) {
            self.emit(Op::End { conditional: false });
        }
    }

    /// A subroutine: the next link of its chain, then networks.
    pub(crate) fn sub_body(&mut self, plan: &SubPlan) {
        let ctx = Ctx::default();
        if let Some(next) = plan.chain_next {
            self.emit(Op::Load(on(sm(0, 0))));
            let op = self.call_op(next);
            self.emit(op);
        }
        let scr_at = self.c.chance(1, 8).then(|| self.c.below(plan.networks + 1));
        for k in 0..=plan.networks {
            if !self.room() {
                break;
            }
            if scr_at == Some(k) {
                self.scr_section();
            }
            if k < plan.networks {
                self.network(ctx);
            }
        }
        if self.c.chance(1, 2) {
            self.emit(Op::Return { conditional: false });
        }
    }

    /// One network of any kind allowed in `ctx`.
    pub(crate) fn network(&mut self, ctx: Ctx) {
        let structured = ctx.scr.is_none() && ctx.depth < 3;
        let weights = [
            30,                                 // contacts and coils
            8,                                  // timer
            6,                                  // counter
            14,                                 // boxes
            if self.cfg.plain { 0 } else { 5 }, // pointers
            3,                                  // deep stack
            if structured { 4 } else { 0 },     // forward jump
            if structured { 3 } else { 0 },     // backward loop
            if structured && ctx.for_depth < self.p.max_for_depth {
                3
            } else {
                0
            }, // FOR
            if self.has_callee() { 4 } else { 0 }, // call
            5,                                  // LPS/LRD/LPP
            3,                                  // control
            3,                                  // immediate I/O
            4,                                  // flags
            if self.wild_jumps && ctx.scr.is_none() {
                3
            } else {
                0
            }, // wild jump
            if self.int_routines.is_empty() { 0 } else { 3 }, // interrupt instruction
            if self.hsc_counters.is_empty() { 0 } else { 3 }, // high-speed counter
            if self.pulse_channels.is_empty() { 0 } else { 3 }, // pulse output
            if self.has_ext() && !self.cfg.plain {
                6
            } else {
                0
            }, // tables, text, strings, clock, PID
            if self.comm { 4 } else { 0 },      // communication
        ];
        self.place_wild(ctx);
        match self.c.weighted(&weights) {
            0 => {
                self.expr(0);
                self.outputs(ctx);
            }
            1 => {
                self.expr(1);
                let op = self.timer_op();
                self.emit(op);
                if self.c.chance(1, 3) {
                    self.expr(2);
                    self.reset_objects(true);
                }
            }
            2 => self.counter_network(),
            3 => self.box_network(),
            4 => self.pointer_network(),
            5 => self.deep_stack(),
            6 => self.forward_jump(ctx),
            7 => self.backward_loop(ctx),
            8 => self.for_loop(ctx),
            9 => {
                self.expr(1);
                if let Some(id) = self.callee() {
                    let op = self.call_op(id);
                    self.emit(op);
                }
            }
            10 => self.branches(ctx),
            11 => self.control(ctx),
            12 => self.immediate_io(),
            13 => self.flag_network(),
            14 => self.wild_jump(),
            15 => self.interrupt_network(),
            16 => self.hsc_network(),
            17 => self.pulse_network(),
            18 => self.ext_network(),
            _ => self.comm_network(),
        }
    }

    fn has_callee(&self) -> bool {
        let sub = self.n_pous > 1;
        (self.pou.0 + 1) < self.n_pous || (self.recursion && sub) || (self.in_interrupt && sub)
    }

    /// A subroutine the current POU may call: a higher number (calls form a DAG), or in programs
    /// with recursion now and then any subroutine, the caller included; from an interrupt
    /// routine any subroutine (the routine's one nesting level, §1.6, then 0x0008).
    fn callee(&mut self) -> Option<PouId> {
        if self.in_interrupt {
            return (self.n_pous > 1).then(|| PouId(self.c.range(1, self.n_pous - 1)));
        }
        let higher = (self.pou.0 + 1) < self.n_pous;
        if self.recursion && self.n_pous > 1 && (!higher || self.c.chance(1, 4)) {
            return Some(PouId(self.c.range(1, self.n_pous - 1)));
        }
        higher.then(|| PouId(self.c.range(self.pou.0 + 1, self.n_pous - 1)))
    }

    /// A contact: mostly a bit, sometimes a compare or an immediate input.
    pub(crate) fn contact(&mut self) -> Contact {
        match self.c.weighted(&[14, 5, 1]) {
            0 => Contact::Bit {
                bit: self.bit_in(),
                negated: self.c.chance(1, 4),
            },
            1 => self.compare(),
            _ => Contact::ImmediateInput {
                bit: self.plain_bit(Area::I, false),
                negated: self.c.chance(1, 3),
            },
        }
    }

    fn compare(&mut self) -> Contact {
        let ty = [CmpType::Byte, CmpType::Int, CmpType::DInt, CmpType::Real]
            [self.c.weighted(&[3, 5, 2, 2])];
        let op = self.c.pick(CmpOp::ALL);
        let k = if ty == CmpType::Real {
            Class::REAL_IN
        } else {
            Class::IN
        };
        let lhs = self.cmp_operand(
            ty,
            Class {
                no_const: true,
                ..k
            },
        );
        let rhs = self.cmp_operand(ty, k);
        Contact::Compare { ty, op, lhs, rhs }
    }

    /// A compare operand. A bad pointer in a compare is fatal and ends the run, so pointers are
    /// rare here (they still occur, to test that both engines stop alike).
    fn cmp_operand(&mut self, ty: CmpType, k: Class) -> Operand {
        let o = self.value(ty.width(), k);
        if matches!(o, Operand::Indirect(_)) && !self.c.chance(1, 30) {
            return if ty == CmpType::Real {
                Operand::Mem(self.real_cell())
            } else {
                Operand::Mem(self.direct(ty.width(), false))
            };
        }
        o
    }

    /// Ops that push exactly one value.
    pub(crate) fn expr(&mut self, depth: u8) {
        match self.c.weighted(&[6, if depth < 3 { 2 } else { 0 }, 1]) {
            0 => {
                let c = self.contact();
                let op = self.maybe_str_compare(StackForm::Load, Op::Load(c));
                self.emit(op);
                for _ in 0..self.c.below(4) {
                    let c = self.contact();
                    let (op, form) = if self.c.chance(2, 3) {
                        (Op::And(c), StackForm::And)
                    } else {
                        (Op::Or(c), StackForm::Or)
                    };
                    let op = self.maybe_str_compare(form, op);
                    self.emit(op);
                }
            }
            1 => {
                self.expr(depth + 1);
                self.expr(depth + 1);
                let op = if self.c.chance(1, 2) {
                    Op::AndBlock
                } else {
                    Op::OrBlock
                };
                self.emit(op);
            }
            _ => {
                let c = self.contact();
                self.emit(Op::Load(c));
                let n = self.c.below(9) as u8;
                self.emit(Op::Pick(n));
                self.emit(Op::Pop);
            }
        }
        match self.c.weighted(&[12, 1, 2]) {
            1 => {
                self.emit(Op::Not);
            }
            2 => {
                if let Some(slot) = self.edge_slot() {
                    let falling = self.c.chance(1, 3);
                    self.emit(Op::Edge { slot, falling });
                }
            }
            _ => {}
        }
    }

    /// `op`, or one time in fifty a string compare contact of the same form instead.
    fn maybe_str_compare(&mut self, form: StackForm, op: Op) -> Op {
        if !self.c.chance(1, 50) || self.cfg.plain {
            return op;
        }
        self.str_compare(form).unwrap_or(op)
    }

    /// One to three consumers of the power flow.
    fn outputs(&mut self, ctx: Ctx) {
        for _ in 0..self.c.range(1, 3) {
            self.output(ctx);
        }
    }

    fn output(&mut self, ctx: Ctx) {
        match self.c.weighted(&[12, 1, 3, 1, 5, 2, 1, 1]) {
            0 => {
                let bit = self.bit_out(true);
                self.emit(Op::Assign {
                    bit,
                    immediate: false,
                });
            }
            1 => {
                let bit = self.plain_bit(Area::Q, true);
                self.emit(Op::Assign {
                    bit,
                    immediate: true,
                });
            }
            2 => self.set_range(),
            3 => {
                let t = self.c.chance(1, 2);
                self.reset_objects(t);
            }
            4 => {
                let b = self.box_op();
                self.emit(Op::Box(b));
                if self.c.chance(1, 3) {
                    self.emit(Op::AndEno);
                }
            }
            5 => {
                let op = self.timer_op();
                self.emit(op);
            }
            6 => {
                if let Some(id) = self.callee() {
                    let op = self.call_op(id);
                    self.emit(op);
                }
            }
            _ => {
                // AENO after a box that may fail chains a second box on its success.
                let b = self.box_op();
                self.emit(Op::Box(b));
                self.emit(Op::AndEno);
                self.assign_out();
            }
        }
        let _ = ctx;
    }

    /// `S`/`R`/`SI`/`RI` over a range that fits its area for constant counts.
    fn set_range(&mut self) {
        let immediate = self.c.chance(1, 8);
        let value = self.c.chance(1, 2);
        let (start, room) = if immediate {
            let b = self.plain_bit(Area::Q, true);
            (b, self.bits_left(b).min(128))
        } else if value && self.c.chance(1, 8) {
            // `S T5, 3` sets timer bits (a reset of timers is a different op).
            let n = self.timer_no();
            let b = BitLoc {
                area: Area::TimerBit,
                byte: u32::from(n),
                bit: 0,
            };
            (b, u32::from(self.p.timers) - u32::from(n))
        } else {
            let b = self.bit_out(false);
            (b, self.bits_left(b))
        };
        let count = if immediate {
            Operand::Const(self.c.range(1, room.min(16)))
        } else if self.c.chance(1, 10) {
            Operand::Const(0)
        } else {
            self.count(room.min(24))
        };
        self.emit(Op::SetRange {
            start,
            count,
            value,
            immediate,
        });
    }

    fn bits_left(&self, b: BitLoc) -> u32 {
        (self.p.area_size(b.area) - b.byte) * 8 - u32::from(b.bit)
    }

    /// `= bit` to a fresh output bit (not immediate).
    pub(crate) fn assign_out(&mut self) {
        let bit = self.bit_out(false);
        self.emit(Op::Assign {
            bit,
            immediate: false,
        });
    }

    /// `R T.., n` or `R C.., n`.
    fn reset_objects(&mut self, timers: bool) {
        let (n, objects) = if timers {
            (self.timer_no(), self.p.timers)
        } else {
            (self.counter_no(), self.p.counters)
        };
        let count = self.count((u32::from(objects) - u32::from(n)).min(8));
        self.emit(if timers {
            Op::ResetTimers {
                first: TimerId(n),
                count,
            }
        } else {
            Op::ResetCounters {
                first: CounterId(n),
                count,
            }
        });
    }

    /// A timer instruction; the number keeps the kind it was first used with.
    pub(crate) fn timer_op(&mut self) -> Op {
        let n = self.timer_no();
        let kind = match self.timers.get(&n) {
            Some(&k) => k,
            None => {
                let allowed: Vec<_> = TimerKind::ALL
                    .iter()
                    .copied()
                    .filter(|&k| self.p.timer_resolution(n, k).is_some())
                    .collect();
                let k = if allowed.is_empty() {
                    TimerKind::ALL[0]
                } else {
                    self.c.pick(&allowed)
                };
                self.timers.insert(n, k);
                k
            }
        };
        let preset = if self.c.chance(5, 6) {
            let pt = match self.c.weighted(&[10, 2, 1, 1]) {
                0 => self.c.range(1, 40),
                1 => self.c.range(40, 600),
                2 => 0,
                _ => self.constant(Width::Word, false),
            };
            Operand::Const(pt & 0xFFFF)
        } else {
            self.value(Width::Word, Class::IN)
        };
        Op::Timer {
            kind,
            timer: TimerId(n),
            preset,
        }
    }

    fn counter_network(&mut self) {
        let n = self.counter_no();
        let kind = match self.counters.get(&n) {
            Some(&k) => k,
            None => {
                let k = self.c.pick(CounterKind::ALL);
                self.counters.insert(n, k);
                k
            }
        };
        let inputs = if kind == CounterKind::ALL[2] { 3 } else { 2 };
        for i in 0..inputs {
            self.expr(if i + 1 == inputs { 2 } else { 1 });
        }
        let preset = if self.c.chance(4, 5) {
            Operand::Const(match self.c.weighted(&[8, 1, 1]) {
                0 => self.c.range(1, 12),
                1 => 0,
                _ => self.constant(Width::Word, false),
            })
        } else {
            self.value(Width::Word, Class::IN)
        };
        self.emit(Op::Counter {
            kind,
            counter: CounterId(n),
            preset,
        });
        if self.c.chance(1, 3) {
            self.emit(Op::Pop);
            self.assign_out();
        }
    }

    /// A condition, then one to three boxes, some chained with AENO.
    fn box_network(&mut self) {
        self.expr(1);
        for _ in 0..self.c.range(1, 3) {
            let b = self.box_op();
            self.emit(Op::Box(b));
            if self.c.chance(1, 4) {
                self.emit(Op::AndEno);
            }
        }
    }

    /// Arithmetic, then a network that reads SMB1 flags or ENO.
    fn flag_network(&mut self) {
        self.emit(Op::Load(on(sm(0, 0))));
        let b = self.arith_box();
        self.emit(Op::Box(b));
        if self.c.chance(1, 2) {
            self.emit(Op::AndEno);
            self.assign_out();
        }
        let flag = sm(1, self.c.below(8) as u8);
        self.emit(Op::Load(on(flag)));
        if self.c.chance(1, 2) {
            let bit = sm(1, self.c.below(8) as u8);
            let negated = self.c.chance(1, 2);
            self.emit(Op::Or(Contact::Bit { bit, negated }));
        }
        self.assign_out();
    }

    /// Pointers: `MOVD &x, cell`, stepping with `+D`/`INCD`, use through `*cell`.
    fn pointer_network(&mut self) {
        self.emit(Op::Load(on(sm(0, 0))));
        if self.c.chance(1, 3) {
            self.point_somewhere();
        }
        let cell = self.pointer_cell();
        let step = match self.c.weighted(&[3, 2, 1, 1]) {
            0 => BoxOp::IntArith {
                op: ArithOp::Add,
                width: Width::DWord,
                src: Operand::Const(self.c.pick(&[1, 2, 4, 8])),
                dst: Operand::Mem(cell),
            },
            1 => BoxOp::Step {
                width: Width::DWord,
                up: true,
                dst: Operand::Mem(cell),
            },
            2 => BoxOp::Step {
                width: Width::DWord,
                up: false,
                dst: Operand::Mem(cell),
            },
            _ => BoxOp::IntArith {
                op: ArithOp::Sub,
                width: Width::DWord,
                src: Operand::Const(self.c.pick(&[1, 2, 4])),
                dst: Operand::Mem(cell),
            },
        };
        self.emit(Op::Box(step));
        let w = self.c.pick(&Width::ALL);
        let ind = Operand::Indirect(cell);
        let op = if self.c.chance(1, 2) {
            let dst = self.value(w, Class::OUT);
            BoxOp::Move {
                width: w,
                src: ind,
                dst,
            }
        } else {
            let src = self.value(w, Class::IN);
            BoxOp::Move {
                width: w,
                src,
                dst: ind,
            }
        };
        self.emit(Op::Box(op));
    }

    /// `MOVD &target, cell`: a pointer cell aimed at a random target.
    fn point_somewhere(&mut self) {
        let target = self.address_target();
        let cell = self.pointer_cell();
        self.emit(Op::Box(BoxOp::Move {
            width: Width::DWord,
            src: Operand::AddressOf(target),
            dst: Operand::Mem(cell),
        }));
    }

    /// Initial pointers, so that `*` operands mostly point somewhere.
    fn pointer_setup(&mut self) {
        self.emit(Op::Load(on(sm(0, 1))));
        for _ in 0..self.c.range(1, 3) {
            self.point_somewhere();
        }
    }

    /// Ten or more pushes, so the bottom level falls off, then combine.
    fn deep_stack(&mut self) {
        let k = self.c.range(9, 13);
        for _ in 0..k {
            let c = self.contact();
            self.emit(Op::Load(c));
            if self.c.chance(1, 6) {
                let n = self.c.below(9) as u8;
                self.emit(Op::Pick(n));
            }
        }
        for _ in 1..k {
            let op = match self.c.weighted(&[4, 4, 1, 1]) {
                0 => Op::AndBlock,
                1 => Op::OrBlock,
                2 => Op::ReadSecond,
                _ => Op::Pop,
            };
            self.emit(op);
        }
        self.assign_out();
    }

    /// `LPS` / `LRD` / `LPP` branches, each with its own contacts and outputs.
    fn branches(&mut self, ctx: Ctx) {
        self.expr(1);
        self.emit(Op::Dup);
        let n = self.c.range(1, 3);
        for i in 0..=n {
            if i > 0 {
                self.emit(if i == n { Op::Pop } else { Op::ReadSecond });
            }
            let c = self.contact();
            self.emit(Op::And(c));
            self.output(ctx);
        }
    }

    fn control(&mut self, ctx: Ctx) {
        let main = self.pou == PouId(0);
        let top = ctx.depth == 0 && ctx.scr.is_none();
        // CRET in a subroutine, CRETI in an interrupt routine.
        let sub = !main;
        // END and CRET inside loops and segments leave FOR and SCR state behind: rarer, not never.
        let weights = [
            3,
            if main && top {
                3
            } else {
                u32::from(main && ctx.scr.is_none())
            },
            3 * u32::from(main && !ctx.in_loop && !self.wild_jumps),
            1,
            if sub && top { 3 } else { u32::from(sub) },
        ];
        self.expr(1);
        match self.c.weighted(&weights) {
            0 => {
                self.emit(Op::Nop);
            }
            1 => {
                // END ends the scan early; make it rare enough that later networks still run.
                let bit = self.bit_in();
                self.emit(Op::And(Contact::Bit {
                    bit,
                    negated: false,
                }));
                self.emit(Op::End { conditional: true });
            }
            2 => {
                self.emit(Op::Wdr);
            }
            3 => {
                // STOP ends the run for good; gate it behind an unlikely compare.
                let offset = 2 * self.c.below(16);
                let rhs = Operand::Const(self.c.range(2, 9));
                self.emit(Op::And(Contact::Compare {
                    ty: CmpType::Int,
                    op: CmpOp::Eq,
                    lhs: Operand::Mem(Loc {
                        area: Area::V,
                        offset,
                    }),
                    rhs,
                }));
                self.emit(Op::Stop);
            }
            _ => {
                self.emit(Op::Return { conditional: true });
            }
        }
    }

    fn immediate_io(&mut self) {
        self.expr(1);
        match self.c.below(3) {
            0 => {
                let input = self.c.below(self.p.inputs);
                let dst = self.value(Width::Byte, Class::OUT);
                self.emit(Op::Box(BoxOp::ImmediateRead { input, dst }));
            }
            1 => {
                let src = self.value(Width::Byte, Class::IN);
                let output = self.c.below(self.p.outputs);
                self.emit(Op::Box(BoxOp::ImmediateWrite { src, output }));
            }
            _ => {
                let bit = self.plain_bit(Area::Q, true);
                self.emit(Op::Assign {
                    bit,
                    immediate: true,
                });
            }
        }
    }
}

/// The contact `LD bit`.
pub(crate) fn on(bit: BitLoc) -> Contact {
    Contact::Bit {
        bit,
        negated: false,
    }
}

/// `SMx.y`.
pub(crate) fn sm(byte: u32, bit: u8) -> BitLoc {
    BitLoc {
        area: Area::SM,
        byte,
        bit,
    }
}
