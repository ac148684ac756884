//! Pulse outputs (s7-200-more §9): a first-scan network that loads a channel's registers (and
//! now and then a small multi-segment profile in V) and starts it, and PLS networks anywhere
//! (a routine included) whose control bytes start, pipeline, retime, switch mode (0x000D) and
//! stop the generators. Cycles are a few ms or a few hundred µs and counts small, so trains
//! end inside the run (event 19/20, which the interrupt generator attaches) and HSC mode 12
//! sees their pulses.

use super::Gen;
use super::programs::{on, sm};
use stljit_core::ir::{BoxOp, ExtBox, Loc, Op, Operand};
use stljit_core::{Area, Width};

/// The V offset of the generated profile tables.
const TABLE_AT: u32 = 400;

impl Gen<'_, '_> {
    /// The channels the program drives: none in most programs, one or two in a quarter of
    /// those whose CPU has pulse outputs.
    pub(crate) fn plan_pulse(&mut self) -> Vec<u8> {
        let all: Vec<u8> = self.p.pulse.channels.iter().map(|c| c.number).collect();
        if all.is_empty() || !self.c.chance(1, 4) {
            return Vec::new();
        }
        let first = all[self.c.below(all.len() as u32) as usize];
        let mut out = vec![first];
        let second = all[self.c.below(all.len() as u32) as usize];
        if second != first && self.c.chance(1, 3) {
            out.push(second);
        }
        out
    }

    /// The first-scan network: per planned channel, its registers and PLS; sometimes a
    /// profile table.
    pub(crate) fn pulse_setup(&mut self) {
        self.emit(Op::Load(on(sm(0, 1))));
        if self.c.chance(1, 3) {
            self.profile_table();
        }
        for n in self.pulse_channels.clone() {
            let ctrl = self.pulse_ctrl();
            self.pulse_registers(n, ctrl);
            self.emit(Op::Ext(Box::new(ExtBox::Pls { channel: n })));
        }
    }

    /// A network under a random condition: maybe new registers, then PLS.
    pub(crate) fn pulse_network(&mut self) {
        self.expr(1);
        let all = self.pulse_channels.clone();
        let n = all[self.c.below(all.len() as u32) as usize];
        if self.c.chance(3, 4) {
            let ctrl = self.pulse_ctrl();
            self.pulse_registers(n, ctrl);
        }
        self.emit(Op::Ext(Box::new(ExtBox::Pls { channel: n })));
    }

    /// A control byte: mostly a PTO (single or multi segment) or PWM start with 1 ms or 1 µs
    /// base, sometimes a stop or anything.
    fn pulse_ctrl(&mut self) -> u32 {
        let base = if self.c.chance(2, 3) { 0x08 } else { 0 };
        match self.c.weighted(&[4, 3, 2, 1, 1]) {
            0 => 0x85 | base | self.c.below(2) << 1, // PTO single, update cycle/count
            1 => 0xC3 | base | self.c.below(2) << 4, // PWM, update cycle and width
            2 => 0xA0 | base,                        // PTO multi segment
            3 => self.c.below(0x80),                 // stop
            _ => self.c.bits() & 0xFF,
        }
    }

    /// MOVB of the control byte, MOVW of cycle and width, MOVD of the count, MOVW of the
    /// profile offset.
    fn pulse_registers(&mut self, n: u8, ctrl: u32) {
        let Some(c) = self.p.pulse.get(n).copied() else {
            return;
        };
        let ms = ctrl & 0x08 != 0;
        let cycle = if ms {
            self.c.range(0, 8)
        } else {
            self.c.range(1, 1200)
        };
        let width = self.c.range(0, cycle + 2);
        let count = self.c.range(0, 12);
        for (width_, v, at) in [
            (Width::Byte, ctrl, c.control_smb()),
            (Width::Word, cycle, c.cycle_smw()),
            (Width::Word, width, c.width_smw()),
            (Width::DWord, count, c.count_smd()),
            (Width::Word, TABLE_AT, c.table_smw()),
        ] {
            self.emit(mov(width_, v, Area::SM, at));
        }
    }

    /// A profile of 0–3 segments at [`TABLE_AT`] (§9.3 layout): small cycles in units, deltas
    /// that sometimes leave the range (delta calculation error), small counts.
    fn profile_table(&mut self) {
        let nseg = self.c.weighted(&[1, 4, 3, 2]) as u32;
        self.emit(mov(Width::Byte, nseg, Area::V, TABLE_AT));
        for s in 0..nseg {
            let at = TABLE_AT + 1 + 8 * s;
            let c0 = self.c.range(1, 8);
            let delta = (self.c.range(0, 5) as i32 - 2) as u32 & 0xFFFF;
            let count = self.c.range(0, 5);
            self.emit(mov(Width::Word, c0, Area::V, at));
            self.emit(mov(Width::Word, delta, Area::V, at + 2));
            self.emit(mov(Width::DWord, count, Area::V, at + 4));
        }
    }
}

/// `MOVx v, area offset`.
fn mov(width: Width, v: u32, area: Area, offset: u32) -> Op {
    Op::Box(BoxOp::Move {
        width,
        src: Operand::Const(v),
        dst: Operand::Mem(Loc { area, offset }),
    })
}
