//! High-speed counters (s7-200-more §8): a first-scan network that loads control bytes, new
//! CV/PV values and defines one or two of the profile's counters in one of their modes, and
//! HSC/HDEF networks anywhere (a routine included, where HDEF is error 0x0004), with control
//! bytes that enable, disable, reload and turn the counters. The stimulus drives their
//! activity per scan ([`super::stimulus`]); presets are small so CV meets them, and the
//! interrupt generator attaches their events now and then.

use super::Gen;
use super::programs::{on, sm};
use stljit_core::hsc::MAX_MODE;
use stljit_core::ir::{BoxOp, ExtBox, Loc, Op, Operand};
use stljit_core::{Area, Width};

impl Gen<'_, '_> {
    /// The counters the program defines: none in most programs, one or two in a quarter of
    /// those whose CPU has counters.
    pub(crate) fn plan_hsc(&mut self) -> Vec<u8> {
        let all: Vec<u8> = self.p.hsc.iter().map(|c| c.number).collect();
        if all.is_empty() || !self.c.chance(1, 4) {
            return Vec::new();
        }
        let first = all[self.c.below(all.len() as u32) as usize];
        let mut out = vec![first];
        if self.c.chance(1, 3) {
            let second = all[self.c.below(all.len() as u32) as usize];
            if second != first {
                out.push(second);
            }
        }
        out
    }

    /// The first-scan network: per planned counter, its registers, HDEF in a mode it has and
    /// usually HSC.
    pub(crate) fn hsc_setup(&mut self) {
        self.emit(Op::Load(on(sm(0, 1))));
        for n in self.hsc_counters.clone() {
            let ctrl = if self.c.chance(2, 3) {
                0xF8 | self.c.below(8)
            } else {
                self.c.bits() & 0xFF
            };
            self.registers(n, ctrl);
            let mode = self.mode(n);
            self.emit(Op::Ext(Box::new(ExtBox::HscDefine { counter: n, mode })));
            if self.c.chance(5, 6) {
                self.emit(Op::Ext(Box::new(ExtBox::Hsc { counter: n })));
            }
        }
    }

    /// A network under a random condition: new registers and HSC, or (rarely) an HDEF.
    pub(crate) fn hsc_network(&mut self) {
        self.expr(1);
        let all = self.hsc_counters.clone();
        let n = all[self.c.below(all.len() as u32) as usize];
        if self.c.chance(1, 8) {
            let mode = self.mode(n);
            self.emit(Op::Ext(Box::new(ExtBox::HscDefine { counter: n, mode })));
            return;
        }
        if self.c.chance(3, 4) {
            let ctrl = match self.c.weighted(&[3, 2, 1, 2]) {
                0 => 0xC0,                        // enable, reload CV
                1 => 0x90 | self.c.below(2) << 3, // enable, turn
                2 => 0x00,                        // disable
                _ => self.c.bits() & 0xFF,
            };
            self.registers(n, ctrl);
        }
        self.emit(Op::Ext(Box::new(ExtBox::Hsc { counter: n })));
    }

    /// MOVB of the control byte and MOVD of small new CV and PV values.
    fn registers(&mut self, n: u8, ctrl: u32) {
        let Some(info) = self.p.hsc.get(n).copied() else {
            return;
        };
        let sm_at = |offset| {
            Operand::Mem(Loc {
                area: Area::SM,
                offset,
            })
        };
        self.emit(Op::Box(BoxOp::Move {
            width: Width::Byte,
            src: Operand::Const(ctrl),
            dst: sm_at(info.control_smb()),
        }));
        for smb in [info.new_cv_smb(), info.new_pv_smb()] {
            let v = self.c.range(0, 40) as i32 - 20;
            self.emit(Op::Box(BoxOp::Move {
                width: Width::DWord,
                src: Operand::Const(v as u32),
                dst: sm_at(smb),
            }));
        }
    }

    /// A mode counter `n` accepts.
    fn mode(&mut self, n: u8) -> u8 {
        let modes: Vec<u8> = match self.p.hsc.get(n) {
            Some(info) => (0..=MAX_MODE).filter(|&m| info.has_mode(m)).collect(),
            None => vec![0],
        };
        modes[self.c.below(modes.len() as u32) as usize]
    }
}
