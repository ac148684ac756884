//! The private state records of the serial ports and network jobs (s7-200-more §10, §11.1),
//! laid out by [`super::Layout`] as the `Ports` and `NetJobs` blocks.

use super::{Block, Field, Layout};
use crate::profile::{CpuProfile, Family};

/// Bytes of private state per serial port (see [`PortState`]).
pub const PORT_STATE_SIZE: u32 = 576;
/// Bytes of one network job slot (see [`NetJob`]).
pub const NET_JOB_SIZE: u32 = 16;

/// Takes the `Ports` and `NetJobs` blocks (empty on Omron profiles) from the layout's allocator.
pub(super) fn take_blocks(
    profile: &CpuProfile,
    take: &mut impl FnMut(Block, u32) -> u32,
) -> (u32, u32) {
    let s7 = u32::from(profile.family == Family::S7);
    let ports = take(
        Block::Ports,
        PORT_STATE_SIZE * crate::comm::ports(profile).len() as u32,
    );
    let net_jobs = take(
        Block::NetJobs,
        s7 * NET_JOB_SIZE * crate::comm::MAX_NET_JOBS,
    );
    (ports, net_jobs)
}

impl Layout {
    /// Image offset of a field (a [`PortState`] constant) of serial port `port`'s state.
    #[inline]
    pub fn port_state(&self, port: u8, field: u32) -> u32 {
        self.ports + PORT_STATE_SIZE * u32::from(port) + field
    }

    /// Image offset of a field (a [`NetJob`] constant) of network job slot `slot`.
    #[inline]
    pub fn net_job(&self, slot: u32, field: u32) -> u32 {
        self.net_jobs + NET_JOB_SIZE * slot + field
    }
}

record_fields! {
    /// Field offsets inside one serial port's private state (s7-200-more §10, §11.1): ports 0
    /// and 1 on S7 profiles, read and written only by `stljit_runtime::comm`. Times are µs,
    /// native-endian.
    PortState {
        /// 1 while a transmission (XMT) is in progress.
        TX_ACTIVE: u8 = 0;
        /// The receive state: 0 idle, 1 waiting for the start of a message, 2 in a message.
        RX_STATE: u8 = 1;
        /// The station address SPA set (0: none yet, GPA reads the default).
        STATION: u8 = 2;
        /// The characters of the transmission in `TX_BUF` (0: a BREAK).
        TX_LEN: u8 = 3;
        /// Image offset of the receive buffer RCV resolved.
        RX_TBL: u32 = 4;
        /// When the transmission completes (after completion: when it completed).
        TX_DONE: u64 = 8;
        /// When RCV started waiting.
        RX_SINCE: u64 = 16;
        /// When the last character received ended.
        RX_LAST_END: u64 = 24;
        /// When the current message started.
        RX_MSG_START: u64 = 32;
        /// When the receive timer ends the message (0: no timer running).
        RX_TIMER: u64 = 40;
        /// When the character at the head of the receive FIFO completes (0: not scheduled).
        CHAR_END: u64 = 48;
        /// Index of the FIFO's head character.
        FIFO_HEAD: u8 = 56;
        /// Characters received into the buffer so far (its count byte).
        RX_COUNT: u8 = 57;
        /// Characters in the FIFO (0–256).
        FIFO_LEN: u16 = 58;
        /// Image offset one past the last byte the receive buffer may use (its area's end).
        RX_END: u32 = 60;
        /// The receive FIFO: stimulus characters not yet received (§10.4), a ring.
        FIFO: [u8; 256] = 64;
        /// The characters of the current or last transmission, copied at XMT (§10.2): with
        /// `TX_LEN` and `TX_DONE` the transmit log's last entry.
        TX_BUF: [u8; 256] = 320;
    }
}

record_fields! {
    /// Field offsets inside one network job slot (NETR/NETW/GET/PUT, s7-200-more §10.5).
    NetJob {
        /// 1 while the job runs.
        ACTIVE: u8 = 0;
        /// The byte its table's status gets at completion (done, error, code).
        RESULT: u8 = 1;
        /// Image offset of the table's status byte.
        TABLE: u32 = 4;
        /// When it completes, µs.
        DONE: u64 = 8;
    }
}
