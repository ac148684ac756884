//! The serial port model (s7-200-more §10.2–§10.4): XMT and RCV, the received characters of
//! the harness's stimulus, and the port as a happening source (transmit completion, one
//! received character, the receive timer), each raising its event of the port's table.

use super::{get, get_u64, mode, regs, set, set_tx_idle, set_u64, sm};
use crate::block::Span;
use crate::interrupt::{
    self,
    sources::{Happening, SourceKind},
};
use crate::mem;
use stljit_core::ErrorCode;
use stljit_core::comm::{self, PortRegs, Protocol, rcv};
use stljit_core::layout::{Block, Layout, PortState};

/// Receive states (`PortState::RX_STATE`).
const IDLE: u8 = 0;
const WAITING: u8 = 1;
const IN_MESSAGE: u8 = 2;

/// SMB86 bits (§10.3): `n r e 0 0 t c p`.
const ST_USER_DISABLE: u8 = 0x80;
const ST_BAD_PARAMS: u8 = 0x40;
const ST_END_CHAR: u8 = 0x20;
const ST_TIMER: u8 = 0x04;
const ST_MAX_COUNT: u8 = 0x02;

/// SMB87 bits (§10.3): `en sc ec il c/m tmr bk 0`.
const CT_EN: u8 = 0x80;
const CT_SC: u8 = 0x40;
const CT_EC: u8 = 0x20;
const CT_IL: u8 = 0x10;
const CT_MSG_TIMER: u8 = 0x08;
const CT_TMR: u8 = 0x04;
const CT_BK: u8 = 0x02;

fn now(img: &[u8], layout: &Layout) -> u64 {
    interrupt::now(img, layout)
}

fn rcv_reg(img: &[u8], layout: &Layout, p: &PortRegs, off: u32) -> u8 {
    sm(img, layout, p.rcv_smb + off)
}

fn rcv_word(img: &[u8], layout: &Layout, p: &PortRegs, off: u32) -> u64 {
    u64::from(rcv_reg(img, layout, p, off)) << 8 | u64::from(rcv_reg(img, layout, p, off + 1))
}

/// `XMT TBL, P` in Freeport mode (§10.2): copies the buffer now and schedules the completion.
pub(super) fn transmit(
    img: &mut [u8],
    layout: &Layout,
    p: &PortRegs,
    tbl: Span,
) -> Result<bool, ErrorCode> {
    let n = p.port;
    if get(img, layout, n, PortState::TX_ACTIVE) != 0
        || get(img, layout, n, PortState::RX_STATE) != IDLE
    {
        return Err(super::busy(p));
    }
    let head = tbl.bytes(1, img.len())?;
    let count = img[head.start];
    let all = tbl.bytes(1 + u32::from(count), img.len())?;
    let bytes = img[all.start + 1..all.end].to_vec();
    let buf = layout.port_state(n, PortState::TX_BUF) as usize;
    img[buf..buf + bytes.len()].copy_from_slice(&bytes);
    let m = mode(img, layout, p);
    let span = if count == 0 {
        comm::break_time_us(m)
    } else {
        u64::from(count) * comm::char_time_us(m)
    };
    set(img, layout, n, PortState::TX_LEN, count);
    set(img, layout, n, PortState::TX_ACTIVE, 1);
    set_u64(img, layout, n, PortState::TX_DONE, now(img, layout) + span);
    set_tx_idle(img, layout, p, false);
    Ok(true)
}

/// `RCV TBL, P` in Freeport mode (§10.3 model).
pub(super) fn receive(
    img: &mut [u8],
    layout: &Layout,
    p: &PortRegs,
    tbl: Span,
) -> Result<bool, ErrorCode> {
    let n = p.port;
    if get(img, layout, n, PortState::TX_ACTIVE) != 0 {
        return Err(super::busy(p));
    }
    let ctl = rcv_reg(img, layout, p, rcv::CONTROL);
    if ctl & CT_EN == 0 {
        if get(img, layout, n, PortState::RX_STATE) != IDLE {
            end(img, layout, p, ST_USER_DISABLE, false);
        }
        return Ok(true);
    }
    if ctl & (CT_IL | CT_SC | CT_BK) == 0 || rcv_reg(img, layout, p, rcv::MAX_COUNT) == 0 {
        super::set_sm(img, layout, p.rcv_smb + rcv::STATUS, ST_BAD_PARAMS);
        return Ok(false);
    }
    let head = tbl.bytes(1, img.len())?;
    img[head.start] = 0;
    let t = now(img, layout);
    mem::set_u32_ne(img, layout.port_state(n, PortState::RX_TBL), tbl.start);
    mem::set_u32_ne(img, layout.port_state(n, PortState::RX_END), tbl.end);
    set(img, layout, n, PortState::RX_COUNT, 0);
    set(img, layout, n, PortState::RX_STATE, WAITING);
    set_u64(img, layout, n, PortState::RX_SINCE, t);
    set_u64(img, layout, n, PortState::RX_TIMER, 0);
    super::set_sm(img, layout, p.rcv_smb + rcv::STATUS, 0);
    let any_response =
        ctl & CT_IL != 0 && ctl & CT_SC == 0 && rcv_word(img, layout, p, rcv::IDLE_MS) == 0;
    if any_response {
        start_message(img, layout, p, t);
    }
    Ok(true)
}

/// The message starts at `t`: the message timer (c/m = 1) runs from here; the
/// inter-character timer (c/m = 0) too, until the first character restarts it.
fn start_message(img: &mut [u8], layout: &Layout, p: &PortRegs, t: u64) {
    set(img, layout, p.port, PortState::RX_STATE, IN_MESSAGE);
    set_u64(img, layout, p.port, PortState::RX_MSG_START, t);
    arm_timer(img, layout, p, t);
}

/// Starts the receive timer from `t` if the control byte asks for one.
fn arm_timer(img: &mut [u8], layout: &Layout, p: &PortRegs, t: u64) {
    if rcv_reg(img, layout, p, rcv::CONTROL) & CT_TMR != 0 {
        let span = (1000 * rcv_word(img, layout, p, rcv::TIMER_MS)).max(1);
        set_u64(img, layout, p.port, PortState::RX_TIMER, t + span);
    }
}

/// Ends the receive with status `bit`, raising the message-complete event unless `quiet`.
fn end(img: &mut [u8], layout: &Layout, p: &PortRegs, bit: u8, quiet: bool) {
    set(img, layout, p.port, PortState::RX_STATE, IDLE);
    set_u64(img, layout, p.port, PortState::RX_TIMER, 0);
    super::set_sm(img, layout, p.rcv_smb + rcv::STATUS, bit);
    if !quiet {
        let tau = now(img, layout);
        interrupt::raise(img, layout, p.rcv_event, tau);
    }
}

/// Appends `bytes` to port `port`'s receive FIFO: they arrive during the next scan interval
/// (§10.4, the harness's `rx` stimulus). Bytes beyond the FIFO's 256 are dropped.
pub fn queue_rx(img: &mut [u8], layout: &Layout, port: u8, bytes: &[u8]) {
    if regs(port).is_none() || layout.block_size(Block::Ports) == 0 {
        return;
    }
    let head = get(img, layout, port, PortState::FIFO_HEAD);
    let len_at = layout.port_state(port, PortState::FIFO_LEN);
    let mut len = mem::get_u16_ne(img, len_at);
    let fifo = layout.port_state(port, PortState::FIFO);
    for &b in bytes {
        if len >= 256 {
            break;
        }
        let i = (u16::from(head) + len) % 256;
        mem::set_u8(img, fifo + u32::from(i), b);
        len += 1;
    }
    mem::set_u16_ne(img, len_at, len);
}

/// The start of the interval `(ta, …]`: a FIFO whose head has no time yet starts it at
/// `max(ta, end of the previous character)` (§10.4).
pub(crate) fn start_interval(img: &mut [u8], layout: &Layout, ta: u64) {
    if layout.block_size(Block::Ports) == 0 {
        return;
    }
    for p in &comm::PORTS {
        let n = p.port;
        let len = mem::get_u16_ne(img, layout.port_state(n, PortState::FIFO_LEN));
        if len > 0 && get_u64(img, layout, n, PortState::CHAR_END) == 0 {
            let from = ta.max(get_u64(img, layout, n, PortState::RX_LAST_END));
            let c = comm::char_time_us(mode(img, layout, p));
            set_u64(img, layout, n, PortState::CHAR_END, from + c);
        }
    }
}

/// Serial port `n` as a happening source (§3.6.3 `source_rank`: receive before transmit).
pub struct Port {
    /// The port number.
    pub n: u8,
}

impl Port {
    fn pending(&self, img: &[u8], layout: &Layout) -> [Option<u64>; 3] {
        let n = self.n;
        let nonzero = |v: u64| (v != 0).then_some(v);
        let char_end = nonzero(get_u64(img, layout, n, PortState::CHAR_END));
        let timer = (get(img, layout, n, PortState::RX_STATE) == IN_MESSAGE)
            .then(|| nonzero(get_u64(img, layout, n, PortState::RX_TIMER)))
            .flatten();
        let tx = (get(img, layout, n, PortState::TX_ACTIVE) != 0)
            .then(|| get_u64(img, layout, n, PortState::TX_DONE));
        [char_end, timer, tx]
    }
}

impl Happening for Port {
    fn kind(&self) -> SourceKind {
        SourceKind::Port
    }

    fn next(&self, img: &[u8], layout: &Layout) -> Option<u64> {
        if layout.block_size(Block::Ports) == 0 {
            return None;
        }
        let [char_end, timer, tx] = self.pending(img, layout);
        // `min` over the three `Option`s, written out: the iterator form cost a third of a
        // scan's polls of an idle port.
        let earlier = |a: Option<u64>, b: Option<u64>| match (a, b) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        earlier(earlier(char_end, timer), tx)
    }

    fn apply(&self, img: &mut [u8], layout: &Layout, tau: u64) {
        let Some(p) = regs(self.n) else { return };
        interrupt::set_now(img, layout, tau);
        match self.pending(img, layout) {
            [Some(t), ..] if t == tau => character(img, layout, p, tau),
            [_, Some(t), _] if t == tau => end(img, layout, p, ST_TIMER, false),
            [.., Some(t)] if t == tau => {
                set(img, layout, p.port, PortState::TX_ACTIVE, 0);
                set_tx_idle(img, layout, p, true);
                interrupt::raise(img, layout, p.tx_event, tau);
            }
            _ => {}
        }
    }
}

/// The character at the FIFO's head completes at `tau` (§10.4): in Freeport mode it goes to
/// SMB2 with the receive-character event, then to the receive state machine (§10.3).
fn character(img: &mut [u8], layout: &Layout, p: &PortRegs, tau: u64) {
    let n = p.port;
    let head = get(img, layout, n, PortState::FIFO_HEAD);
    let ch = mem::get_u8(img, layout.port_state(n, PortState::FIFO) + u32::from(head));
    let len_at = layout.port_state(n, PortState::FIFO_LEN);
    let len = mem::get_u16_ne(img, len_at) - 1;
    mem::set_u16_ne(img, len_at, len);
    set(img, layout, n, PortState::FIFO_HEAD, head.wrapping_add(1));
    let m = mode(img, layout, p);
    let c = comm::char_time_us(m);
    set_u64(
        img,
        layout,
        n,
        PortState::CHAR_END,
        if len > 0 { tau + c } else { 0 },
    );
    let prev_end = get_u64(img, layout, n, PortState::RX_LAST_END);
    set_u64(img, layout, n, PortState::RX_LAST_END, tau);
    if comm::protocol(m) != Protocol::Freeport {
        return;
    }
    super::set_sm(img, layout, comm::RX_CHAR_SMB, ch);
    let sm3 = super::sm(img, layout, 3);
    super::set_sm(img, layout, 3, sm3 & !1);
    interrupt::raise(img, layout, p.char_event, tau);
    let ctl = rcv_reg(img, layout, p, rcv::CONTROL);
    let state = get(img, layout, n, PortState::RX_STATE);
    if state == WAITING {
        let since = get_u64(img, layout, n, PortState::RX_SINCE).max(prev_end);
        let idle_ok = ctl & CT_IL == 0
            || tau.saturating_sub(c).saturating_sub(since)
                >= 1000 * rcv_word(img, layout, p, rcv::IDLE_MS);
        let sc = ctl & CT_SC != 0;
        let sc_ok = !sc || ch == rcv_reg(img, layout, p, rcv::START_CHAR);
        // A start needs idle line or a start character; breaks are not simulated (§10.3).
        let starts = (ctl & (CT_IL | CT_SC) != 0) && idle_ok && sc_ok;
        if !starts {
            return;
        }
        start_message(img, layout, p, tau.saturating_sub(c));
        store(img, layout, p, ch, tau, sc);
    } else if state == IN_MESSAGE {
        store(img, layout, p, ch, tau, false);
    }
}

/// Stores `ch` in the receive buffer and applies the end conditions (`start`: it is the start
/// character, which cannot also end the message).
fn store(img: &mut [u8], layout: &Layout, p: &PortRegs, ch: u8, tau: u64, start: bool) {
    let n = p.port;
    let count = get(img, layout, n, PortState::RX_COUNT).saturating_add(1);
    set(img, layout, n, PortState::RX_COUNT, count);
    let tbl = mem::get_u32_ne(img, layout.port_state(n, PortState::RX_TBL));
    let end_at = mem::get_u32_ne(img, layout.port_state(n, PortState::RX_END));
    if tbl < end_at {
        mem::set_u8(img, tbl, count);
    }
    let at = tbl + u32::from(count);
    if at < end_at {
        mem::set_u8(img, at, ch);
    }
    let ctl = rcv_reg(img, layout, p, rcv::CONTROL);
    if ctl & CT_MSG_TIMER == 0 {
        arm_timer(img, layout, p, tau);
    }
    if !start && ctl & CT_EC != 0 && ch == rcv_reg(img, layout, p, rcv::END_CHAR) {
        end(img, layout, p, ST_END_CHAR, false);
    } else if count >= rcv_reg(img, layout, p, rcv::MAX_COUNT) {
        end(img, layout, p, ST_MAX_COUNT, false);
    }
}
