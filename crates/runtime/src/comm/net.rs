//! Network jobs (s7-200-more §10.5): NETR/NETW over a PPI master port and GET/PUT over
//! Ethernet. The table is checked when the instruction runs; a valid job becomes active
//! (status byte 16#40) and completes [`NET_LATENCY_US`] later as a happening. The simulator
//! declares no remote stations, so every job ends "done with error": time-out (1) for
//! NETR/NETW, no connection (5) for GET/PUT [design: §10.5's unknown station]. No data is
//! copied and no interrupt is raised.

use super::{mode, regs};
use crate::block::Span;
use crate::interrupt::{
    self,
    sources::{Happening, SourceKind},
};
use crate::mem;
use crate::pointer;
use stljit_core::comm::{self, NET_LATENCY_US, Protocol};
use stljit_core::ir::CommOp;
use stljit_core::layout::{Block, Layout, NetJob};
use stljit_core::{Area, ErrorCode};

/// Status byte bits (§10.5): done, active, error; the code is bits 3–0.
const DONE: u8 = 0x80;
const ACTIVE: u8 = 0x40;
const ERROR: u8 = 0x20;

/// NETR/NETW codes.
const NET_TIMEOUT: u8 = 1;
const NET_QUEUE_FULL: u8 = 4;
const NET_PROTOCOL: u8 = 5;
const NET_PARAM: u8 = 6;
/// GET/PUT codes [SMART manual, recalled, §13 C2].
const GP_PARAM: u8 = 1;
const GP_TOO_MANY: u8 = 2;
const GP_NO_CONNECTION: u8 = 5;

/// The areas a remote or local data pointer may name (I, Q, M, V; DB1 is V).
fn data_area(ptr: u32) -> bool {
    matches!(
        pointer::decode(ptr).map(|(a, _)| a),
        Some(Area::I | Area::Q | Area::M | Area::V)
    )
}

/// The table's size and its check: `Err(code)` for an illegal parameter (§10.5 tables).
fn check(img: &[u8], layout: &Layout, op: CommOp, port: u8, t: &[u8]) -> Result<(), u8> {
    let be32 = |i: usize| u32::from_be_bytes([t[i], t[i + 1], t[i + 2], t[i + 3]]);
    match op {
        CommOp::NetRead | CommOp::NetWrite => {
            let p = regs(port).ok_or(NET_PARAM)?;
            if comm::protocol(mode(img, layout, p)) != Protocol::PpiMaster {
                return Err(NET_PROTOCOL);
            }
            let ok = (1..=16).contains(&t[6]) && data_area(be32(2));
            if ok { Ok(()) } else { Err(NET_PARAM) }
        }
        _ => {
            let max = if op == CommOp::Get { 222 } else { 212 };
            let ok = t[5] == 0
                && t[6] == 0
                && (1..=max).contains(&t[11])
                && data_area(be32(7))
                && data_area(be32(12));
            if ok { Ok(()) } else { Err(GP_PARAM) }
        }
    }
}

/// Starts NETR/NETW/GET/PUT on the table at `tbl` (§10.5).
pub(super) fn start(
    img: &mut [u8],
    layout: &Layout,
    op: CommOp,
    port: u8,
    tbl: Span,
) -> Result<bool, ErrorCode> {
    let net = matches!(op, CommOp::NetRead | CommOp::NetWrite);
    let size = if net { 23 } else { 16 };
    let r = tbl.bytes(size, img.len())?;
    let status = r.start;
    if let Err(code) = check(img, layout, op, port, &img[r]) {
        img[status] = ERROR | code;
        return Ok(false);
    }
    let free =
        (0..comm::MAX_NET_JOBS).find(|&s| mem::get_u8(img, layout.net_job(s, NetJob::ACTIVE)) == 0);
    let Some(slot) = free else {
        img[status] = ERROR | if net { NET_QUEUE_FULL } else { GP_TOO_MANY };
        return Ok(false);
    };
    img[status] = ACTIVE;
    let result = DONE | ERROR | if net { NET_TIMEOUT } else { GP_NO_CONNECTION };
    let done = interrupt::now(img, layout) + NET_LATENCY_US;
    mem::set_u8(img, layout.net_job(slot, NetJob::ACTIVE), 1);
    mem::set_u8(img, layout.net_job(slot, NetJob::RESULT), result);
    mem::set_u32_ne(img, layout.net_job(slot, NetJob::TABLE), status as u32);
    mem::set_u64_ne(img, layout.net_job(slot, NetJob::DONE), done);
    Ok(true)
}

/// The network jobs as one happening source (the last `source_rank`, §3.6.3): the active job
/// with the earliest completion (then the lowest slot) completes first.
pub struct NetJobs;

impl NetJobs {
    fn due(img: &[u8], layout: &Layout) -> Option<(u64, u32)> {
        if layout.block_size(Block::NetJobs) == 0 {
            return None;
        }
        (0..comm::MAX_NET_JOBS)
            .filter(|&s| mem::get_u8(img, layout.net_job(s, NetJob::ACTIVE)) != 0)
            .map(|s| (mem::get_u64_ne(img, layout.net_job(s, NetJob::DONE)), s))
            .min()
    }
}

impl Happening for NetJobs {
    fn kind(&self) -> SourceKind {
        SourceKind::Network
    }

    fn next(&self, img: &[u8], layout: &Layout) -> Option<u64> {
        Self::due(img, layout).map(|(t, _)| t)
    }

    fn apply(&self, img: &mut [u8], layout: &Layout, _tau: u64) {
        if let Some((_, slot)) = Self::due(img, layout) {
            mem::set_u8(img, layout.net_job(slot, NetJob::ACTIVE), 0);
            let table = mem::get_u32_ne(img, layout.net_job(slot, NetJob::TABLE));
            let result = mem::get_u8(img, layout.net_job(slot, NetJob::RESULT));
            if (table as usize) < img.len() {
                mem::set_u8(img, table, result);
            }
        }
    }
}
