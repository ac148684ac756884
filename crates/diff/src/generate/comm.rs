//! Communication (s7-200-more §10): a first-scan network that puts port 0 (and sometimes
//! port 1) into Freeport or PPI master mode, loads the receive registers (and often starts a
//! receive), a transmit buffer and network tables, and communication networks anywhere (a
//! routine included): XMT, RCV, NETR/NETW or GET/PUT as the CPU has them, GPA/SPA, mode
//! changes and reads of the status bytes. The stimulus brings received bytes ([`super::stimulus::for_program`], built around
//! [`START_CHARS`] and [`END_CHARS`]); the interrupt generator attaches the port events of a
//! communicating program often, other programs' now and then.

use super::Gen;
use super::programs::{on, sm};
use stljit_core::comm::{PORTS, rcv};
use stljit_core::instr_set::InstrSet;
use stljit_core::ir::{BoxOp, CommOp, ExtBox, Loc, Op, Operand};
use stljit_core::{Area, Family, Width};

/// V offsets of the generated buffers and tables, inside every S7 profile's V area and clear
/// of the slots other generators use most (they may still write here: any byte is legal).
const XMT_BUF: u32 = 900;
const RCV_BUF: [u32; 2] = [940, 980];
const NET_TABLE: u32 = 1020;

/// The start characters (SMB88/SMB188) the setup network chooses from; the stimulus builds
/// received messages around the same ones.
pub(crate) const START_CHARS: [u8; 3] = [0x02, 0x41, 0x00];
/// The end characters (SMB89/SMB189) the setup network chooses from.
pub(crate) const END_CHARS: [u8; 3] = [0x0D, 0x03, 0x42];

fn at(area: Area, offset: u32) -> Operand {
    Operand::Mem(Loc { area, offset })
}

impl Gen<'_, '_> {
    /// Whether the program communicates: one S7 program in six.
    pub(crate) fn plan_comm(&mut self) -> bool {
        self.p.family == Family::S7
            && self.p.has(InstrSet::Freeport)
            && self.p.area_size(Area::V) > NET_TABLE + 32
            && self.c.chance(1, 6)
    }

    fn mov(&mut self, width: Width, v: u32, dst: Operand) {
        self.emit(Op::Box(BoxOp::Move {
            width,
            src: Operand::Const(v),
            dst,
        }));
    }

    /// A mode byte: mostly Freeport at a common rate, sometimes PPI master or anything.
    fn mode_byte(&mut self) -> u32 {
        match self.c.weighted(&[6, 2, 1]) {
            0 => self.c.pick(&[0x09, 0x01, 0x05, 0x19, 0x49, 0xC9]),
            1 => 0x0A,
            _ => self.c.bits() & 0xFF,
        }
    }

    /// The first-scan network: modes, receive registers, the transmit buffer and a network
    /// table.
    pub(crate) fn comm_setup(&mut self) {
        self.emit(Op::Load(on(sm(0, 1))));
        for p in &PORTS {
            if p.port == 1 && !self.c.chance(1, 2) {
                continue;
            }
            let m = self.mode_byte();
            self.mov(Width::Byte, m, at(Area::SM, p.mode_smb));
            // Often a receive starts at once, so the stimulus's bytes find one waiting.
            if self.receive_registers(p.rcv_smb) && self.c.chance(1, 2) {
                let table = at(Area::V, RCV_BUF[usize::from(p.port)]);
                self.emit(Op::Ext(Box::new(ExtBox::Comm {
                    op: CommOp::Receive,
                    table,
                    port: p.port,
                })));
            }
        }
        let n = self.c.range(0, 6);
        self.mov(Width::Byte, n, at(Area::V, XMT_BUF));
        for i in 1..=n {
            let ch = self.c.bits() & 0xFF;
            self.mov(Width::Byte, ch, at(Area::V, XMT_BUF + i));
        }
        self.net_table();
    }

    /// The receive registers of the port whose status byte is SMB`base` (if the CPU's SM area
    /// has them, which it returns): control byte, start/end characters, idle and timer times,
    /// maximum count.
    fn receive_registers(&mut self, base: u32) -> bool {
        if base + rcv::MAX_COUNT >= self.p.area_size(Area::SM) {
            return false;
        }
        let ctl = match self.c.weighted(&[3, 3, 2, 1]) {
            0 => 0xB0, // en, ec, il: any response to an end character
            1 => 0xC4, // en, sc, tmr
            2 => 0x90 | (self.c.bits() & 0x2C),
            _ => self.c.bits() & 0xFF,
        };
        let sc = u32::from(self.c.pick(&START_CHARS));
        let ec = u32::from(self.c.pick(&END_CHARS));
        let idle = self.c.pick(&[0, 0, 1, 3]);
        let timer = self.c.pick(&[0, 2, 5, 20]);
        let max = self.c.pick(&[1, 3, 8, 20, 0]);
        self.mov(Width::Byte, ctl, at(Area::SM, base + rcv::CONTROL));
        self.mov(Width::Byte, sc, at(Area::SM, base + rcv::START_CHAR));
        self.mov(Width::Byte, ec, at(Area::SM, base + rcv::END_CHAR));
        self.mov(Width::Word, idle, at(Area::SM, base + rcv::IDLE_MS));
        self.mov(Width::Word, timer, at(Area::SM, base + rcv::TIMER_MS));
        self.mov(Width::Byte, max, at(Area::SM, base + rcv::MAX_COUNT));
        true
    }

    /// A network table at [`NET_TABLE`], valid for both layouts in most programs: remote
    /// station/IP, a pointer to VB0 where both kinds expect one, a small length.
    fn net_table(&mut self) {
        // &VB0: the V area's pointer code in the top byte (a5-stl §1.6).
        let ptr = u32::from(Area::V.pointer_code().unwrap_or(0)) << 24;
        self.mov(Width::DWord, 0x0300_0000, at(Area::V, NET_TABLE));
        self.mov(Width::DWord, ptr, at(Area::V, NET_TABLE + 2));
        let len = if self.c.chance(4, 5) {
            self.c.range(1, 16)
        } else {
            self.c.bits() & 0xFF
        };
        self.mov(Width::Byte, len, at(Area::V, NET_TABLE + 6));
        self.mov(Width::Word, 0, at(Area::V, NET_TABLE + 5));
        self.mov(Width::DWord, ptr, at(Area::V, NET_TABLE + 7));
        self.mov(Width::Byte, len, at(Area::V, NET_TABLE + 11));
        self.mov(Width::DWord, ptr, at(Area::V, NET_TABLE + 12));
    }

    /// A network under a random condition with one communication instruction (or a mode
    /// change, or a read of the receive status into V).
    pub(crate) fn comm_network(&mut self) {
        self.expr(1);
        let port = if self.c.chance(3, 4) { 0 } else { 1 };
        let regs = PORTS[usize::from(port)];
        let sm_size = self.p.area_size(Area::SM);
        let rcv_ok = regs.rcv_smb + rcv::MAX_COUNT < sm_size;
        let net = self.p.has(InstrSet::NetReadWrite);
        let getput = self.p.has(InstrSet::GetPut);
        let choice = self.c.weighted(&[
            5,
            if rcv_ok { 5 } else { 0 },
            if net || getput { 3 } else { 0 },
            2,
            2,
            if rcv_ok { 2 } else { 0 },
        ]);
        let (op, table) = match choice {
            0 => (CommOp::Transmit, at(Area::V, XMT_BUF)),
            1 => (CommOp::Receive, at(Area::V, RCV_BUF[usize::from(port)])),
            2 => {
                let op = match (net, self.c.chance(1, 2)) {
                    (true, true) => CommOp::NetRead,
                    (true, false) => CommOp::NetWrite,
                    (false, true) => CommOp::Get,
                    (false, false) => CommOp::Put,
                };
                (op, at(Area::V, NET_TABLE))
            }
            3 => {
                let op = if self.c.chance(1, 2) {
                    CommOp::GetAddress
                } else {
                    CommOp::SetAddress
                };
                let t = if op == CommOp::SetAddress && self.c.chance(1, 2) {
                    Operand::Const(self.c.pick(&[0, 1, 5, 126, 127, 200]))
                } else {
                    at(Area::V, XMT_BUF + 20)
                };
                (op, t)
            }
            4 => {
                let m = self.mode_byte();
                self.mov(Width::Byte, m, at(Area::SM, regs.mode_smb));
                return;
            }
            _ => {
                self.emit(Op::Box(BoxOp::Move {
                    width: Width::Byte,
                    src: at(Area::SM, regs.rcv_smb),
                    dst: at(Area::V, XMT_BUF + 21),
                }));
                return;
            }
        };
        let port = if op.has_port() { port } else { 0 };
        self.emit(Op::Ext(Box::new(ExtBox::Comm { op, table, port })));
    }
}
