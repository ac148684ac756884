//! Communication (s7-200-more.md §10), once for both engines: the instructions XMT, RCV,
//! NETR, NETW, GET, PUT, GPA and SPA ([`execute`], which `ext::execute` runs for the
//! interpreter and for the JIT's `stljit_rt_ext`), and the simulated hardware that completes
//! them later in virtual time as happening sources of the interrupt machinery: the serial
//! ports ([`Port`]: transmit completion, received characters, receive timers) and the network
//! jobs ([`NetJobs`]). All state is in the image (`PortState`, `NetJob` records); the port
//! facts (registers, events, character time) are `stljit_core::comm`.
//!
//! **The simulated port.** Nothing leaves the simulator: a transmission takes
//! `count × C` µs (`C` the character time of the port's mode byte, §10.1) and then raises
//! its transmit-complete event; its bytes stay in the port's `TX_BUF` (the transmit log's
//! last entry). Received characters come from the harness ([`queue_rx`]: bytes that arrive
//! on a port during the next scan interval, back to back from the interval's start, §10.4).
//! Network jobs have no peer: after the fixed latency they complete with the "no answer"
//! error of their family (§10.5).
//!
//! Rules §10 leaves open, fixed here [design] (docs/semantics.md lists them):
//! * RCV with its enable bit clear while no message is in progress does nothing (ENO 1).
//! * The receive timer (SMW92) runs at least 1 µs, so a 0-ms timer ends the message in the
//!   next interval phase rather than at the RCV instant.
//! * A receive buffer running past its area's end loses the characters beyond it (the count
//!   byte still counts them).
//! * Switching a port to Freeport inside an interrupt routine (0x009A) is not checked: the
//!   mode byte is read whenever an instruction or a happening needs it.

mod net;
mod port;

pub use net::NetJobs;
pub(crate) use port::start_interval as start_rx;
pub use port::{Port, queue_rx};

use crate::interrupt;
use crate::mem;
use crate::operand;
use stljit_core::comm::{self, PortRegs, Protocol};
use stljit_core::ir::{CommOp, Operand};
use stljit_core::layout::{IntState, Layout, PortState};
use stljit_core::{Area, ErrorCode, Width};

/// The SM byte `smb` (0 if the profile's SM area does not have it).
pub(crate) fn sm(img: &[u8], layout: &Layout, smb: u32) -> u8 {
    if smb < layout.area_size(Area::SM) {
        mem::get_u8(img, layout.base(Area::SM) + smb)
    } else {
        0
    }
}

/// Writes SM byte `smb` (nothing if the profile's SM area does not have it).
pub(crate) fn set_sm(img: &mut [u8], layout: &Layout, smb: u32, v: u8) {
    if smb < layout.area_size(Area::SM) {
        mem::set_u8(img, layout.base(Area::SM) + smb, v);
    }
}

/// Port `n`'s registers (`None` for a port the simulator does not have).
fn regs(n: u8) -> Option<&'static PortRegs> {
    comm::PORTS.get(usize::from(n))
}

/// The mode byte of port `p`.
fn mode(img: &[u8], layout: &Layout, p: &PortRegs) -> u8 {
    sm(img, layout, p.mode_smb)
}

fn get(img: &[u8], layout: &Layout, port: u8, field: u32) -> u8 {
    mem::get_u8(img, layout.port_state(port, field))
}

fn set(img: &mut [u8], layout: &Layout, port: u8, field: u32, v: u8) {
    mem::set_u8(img, layout.port_state(port, field), v);
}

fn get_u64(img: &[u8], layout: &Layout, port: u8, field: u32) -> u64 {
    mem::get_u64_ne(img, layout.port_state(port, field))
}

fn set_u64(img: &mut [u8], layout: &Layout, port: u8, field: u32, v: u64) {
    mem::set_u64_ne(img, layout.port_state(port, field), v);
}

/// Sets the transmitter-idle bit (SM4.5 / SM4.6) of port `p`.
fn set_tx_idle(img: &mut [u8], layout: &Layout, p: &PortRegs, idle: bool) {
    let v = sm(img, layout, 4);
    let bit = 1 << p.tx_idle_bit;
    set_sm(img, layout, 4, if idle { v | bit } else { v & !bit });
}

/// The "simultaneous XMT/RCV" error of port `p` (0x0009 / 0x000B).
fn busy(p: &PortRegs) -> ErrorCode {
    if p.port == 0 {
        ErrorCode::PortBusy0
    } else {
        ErrorCode::PortBusy1
    }
}

/// Whether an interrupt routine is running.
fn in_isr(img: &[u8], layout: &Layout) -> bool {
    layout.block_size(stljit_core::layout::Block::Interrupts) != 0
        && interrupt::get(img, layout, IntState::IN_ISR) != 0
}

/// The scan instant (E2) of a program that communicates: the transmitter-idle bits show the
/// ports' state, so SM4.5/SM4.6 are 1 from the first scan until an XMT starts (§10.2).
pub fn instant(img: &mut [u8], layout: &Layout) {
    if layout.block_size(stljit_core::layout::Block::Ports) == 0 {
        return;
    }
    for p in &comm::PORTS {
        let idle = get(img, layout, p.port, PortState::TX_ACTIVE) == 0;
        set_tx_idle(img, layout, p, idle);
    }
}

/// Runs communication instruction `op` with power flow on, TBL `table` resolved in L frame
/// `frame`. Returns ENO, or the non-fatal error the engine records.
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    op: CommOp,
    table: &Operand,
    port: u8,
    frame: u32,
) -> Result<bool, ErrorCode> {
    if layout.block_size(stljit_core::layout::Block::Ports) == 0 {
        return Ok(false);
    }
    if op == CommOp::SetAddress {
        regs(port).ok_or(ErrorCode::OperandRange)?;
        if in_isr(img, layout) {
            return Err(ErrorCode::InInterrupt);
        }
        let a = operand::read(img, layout, table, Width::Byte, frame)? as u8;
        if a == 0 || a > comm::MAX_STATION {
            return Err(ErrorCode::OperandRange);
        }
        set(img, layout, port, PortState::STATION, a);
        return Ok(true);
    }
    let write = op != CommOp::Transmit;
    let span = operand::span(img, layout, table, Width::Byte, frame, write)?;
    match op {
        CommOp::Transmit | CommOp::Receive => {
            let p = regs(port).ok_or(ErrorCode::OperandRange)?;
            if comm::protocol(mode(img, layout, p)) != Protocol::Freeport {
                return Ok(false);
            }
            if op == CommOp::Transmit {
                port::transmit(img, layout, p, span)
            } else {
                port::receive(img, layout, p, span)
            }
        }
        CommOp::NetRead | CommOp::NetWrite | CommOp::Get | CommOp::Put => {
            net::start(img, layout, op, port, span)
        }
        CommOp::GetAddress => {
            regs(port).ok_or(ErrorCode::OperandRange)?;
            let r = span.bytes(1, img.len())?;
            img[r.start] = station(img, layout, port);
            Ok(true)
        }
        CommOp::SetAddress => Ok(false),
    }
}

/// Port `port`'s station address: the one SPA set, else the default (§10.6).
fn station(img: &[u8], layout: &Layout, port: u8) -> u8 {
    match get(img, layout, port, PortState::STATION) {
        0 => comm::DEFAULT_STATION,
        a => a,
    }
}
