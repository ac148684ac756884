//! Terse IR builders and a scan-by-scan simulator for the tests.

use crate::Interpreter;
use stljit_core::ir::*;
use stljit_core::{Area, LabelId, OpIdx, PouId, ProfileId, ScanStatus, Width};
use stljit_runtime::{Engine, Image};

pub(crate) fn bit(area: Area, byte: u32, bit: u8) -> BitLoc {
    BitLoc { area, byte, bit }
}
pub(crate) fn i(byte: u32, b: u8) -> BitLoc {
    bit(Area::I, byte, b)
}
pub(crate) fn q(byte: u32, b: u8) -> BitLoc {
    bit(Area::Q, byte, b)
}
pub(crate) fn m(byte: u32, b: u8) -> BitLoc {
    bit(Area::M, byte, b)
}
pub(crate) fn sm(byte: u32, b: u8) -> BitLoc {
    bit(Area::SM, byte, b)
}
pub(crate) fn s(byte: u32, b: u8) -> BitLoc {
    bit(Area::S, byte, b)
}
pub(crate) fn tbit(n: u32) -> BitLoc {
    bit(Area::TimerBit, n, 0)
}
pub(crate) fn mem(area: Area, offset: u32) -> Operand {
    Operand::Mem(Loc { area, offset })
}
pub(crate) fn v(offset: u32) -> Operand {
    mem(Area::V, offset)
}
pub(crate) fn k(c: i64) -> Operand {
    Operand::Const(c as u32)
}
pub(crate) fn tv(n: u32) -> Operand {
    mem(Area::TimerValue, 2 * n)
}
pub(crate) fn cv(n: u32) -> Operand {
    mem(Area::CounterValue, 2 * n)
}
/// `ACn` as a dword.
pub(crate) fn ac(n: u32) -> Operand {
    mem(Area::AC, 4 * n)
}

fn c(b: BitLoc, negated: bool) -> Contact {
    Contact::Bit { bit: b, negated }
}
pub(crate) fn ld(b: BitLoc) -> Op {
    Op::Load(c(b, false))
}
pub(crate) fn ldn(b: BitLoc) -> Op {
    Op::Load(c(b, true))
}
pub(crate) fn out(b: BitLoc) -> Op {
    Op::Assign {
        bit: b,
        immediate: false,
    }
}
pub(crate) fn set(b: BitLoc, n: i64) -> Op {
    Op::SetRange {
        start: b,
        count: k(n),
        value: true,
        immediate: false,
    }
}
pub(crate) fn movw(src: Operand, dst: Operand) -> Op {
    Op::Box(BoxOp::Move {
        width: Width::Word,
        src,
        dst,
    })
}
pub(crate) fn movb(src: Operand, dst: Operand) -> Op {
    Op::Box(BoxOp::Move {
        width: Width::Byte,
        src,
        dst,
    })
}
pub(crate) fn movd(src: Operand, dst: Operand) -> Op {
    Op::Box(BoxOp::Move {
        width: Width::DWord,
        src,
        dst,
    })
}
pub(crate) fn jmp(l: u32) -> Op {
    Op::Jump(LabelId(l))
}
pub(crate) fn lbl(l: u32) -> Op {
    Op::Label(LabelId(l))
}
pub(crate) fn call(p: u32) -> Op {
    Op::Call(PouId(p))
}
pub(crate) fn op_idx(i: usize) -> OpIdx {
    OpIdx::new(i)
}

fn pou(name: &str, kind: PouKind, ops: Vec<Op>) -> Pou {
    let mut labels = Vec::new();
    for (at, op) in ops.iter().enumerate() {
        if let Op::Label(l) = op {
            if labels.len() <= l.index() {
                labels.resize(l.index() + 1, OpIdx(0));
            }
            labels[l.index()] = OpIdx::new(at);
        }
    }
    let locs = vec![SrcLoc::default(); ops.len()];
    Pou {
        name: name.into(),
        kind,
        ops,
        locs,
        labels,
    }
}

/// A program from its main ops and subroutines, declaring every timer, counter and edge slot used.
pub(crate) fn program(main: Vec<Op>, subs: Vec<Vec<Op>>) -> Program {
    let profile = ProfileId::A5;
    let mut pous = vec![pou("MAIN", PouKind::Main, main)];
    for (n, ops) in subs.into_iter().enumerate() {
        pous.push(pou(&format!("SBR{n}"), PouKind::Subroutine(n as u16), ops));
    }
    let mut timers: Vec<TimerDecl> = Vec::new();
    let mut counters: Vec<CounterDecl> = Vec::new();
    let mut edges = 0;
    for op in pous.iter().flat_map(|p| &p.ops) {
        match *op {
            Op::Timer { kind, timer, .. } if !timers.iter().any(|t| t.id == timer) => {
                let resolution = profile.profile().timer_resolution(timer.0, kind).unwrap();
                timers.push(TimerDecl {
                    id: timer,
                    kind,
                    resolution,
                });
            }
            Op::Counter { kind, counter, .. } if !counters.iter().any(|c| c.id == counter) => {
                counters.push(CounterDecl { id: counter, kind });
            }
            Op::Edge { slot, .. } => edges = edges.max(slot.index() + 1),
            _ => {}
        }
    }
    Program {
        profile,
        pous,
        timers,
        counters,
        edges: vec![EdgeDecl { init: false }; edges],
        logic_stack_depth: 9,
        files: vec!["test.stl".into()],
        data: Vec::new(),
    }
}

/// Runs a program scan by scan at `t = k * period`.
pub(crate) struct Sim {
    pub(crate) interp: Interpreter,
    pub(crate) img: Image,
    period: u64,
    k: u64,
}

impl Sim {
    pub(crate) fn new(main: Vec<Op>, subs: Vec<Vec<Op>>, period: u64) -> Sim {
        let p = program(main, subs);
        Sim {
            interp: Interpreter::new(&p).unwrap(),
            img: Image::cold_start(&p),
            period,
            k: 0,
        }
    }

    pub(crate) fn main(main: Vec<Op>) -> Sim {
        Sim::new(main, vec![], 10)
    }

    /// One scan with these input bits on (all others off).
    pub(crate) fn scan(&mut self, on: &[BitLoc]) -> ScanStatus {
        let mut inputs = [0u8; 16];
        for b in on {
            inputs[b.byte as usize] |= 1 << b.bit;
        }
        self.img.set_inputs(&inputs);
        let t = self.k * self.period;
        self.k += 1;
        self.interp.scan(&mut self.img, t)
    }

    pub(crate) fn bit(&self, b: BitLoc) -> bool {
        self.img.bit(b, 0).unwrap()
    }

    pub(crate) fn bits(&self, bs: &[BitLoc]) -> Vec<u8> {
        bs.iter().map(|&b| u8::from(self.bit(b))).collect()
    }

    pub(crate) fn word(&self, op: Operand) -> i16 {
        self.val(op, Width::Word) as u16 as i16
    }

    pub(crate) fn val(&self, op: Operand, w: Width) -> u32 {
        let Operand::Mem(loc) = op else {
            panic!("not a location")
        };
        self.img.read(loc, w, 0).unwrap()
    }
}
