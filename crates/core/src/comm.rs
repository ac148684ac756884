//! The facts of the simulated communication ports (s7-200-more §10): each port's SM registers
//! and events, and the simulator's fixed choices where §10 leaves a value to the harness
//! (station address, network latency). The runtime's `comm` module is the semantics; the
//! front end and the fuzzer read the same table.

use crate::profile::{CpuProfile, Family};

/// The SM registers and events of one serial port (§10.1–§10.4, event table §3.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PortRegs {
    /// The port number (the PORT operand).
    pub port: u8,
    /// The mode byte: SMB30 / SMB130.
    pub mode_smb: u32,
    /// The bit of SMB4 that is 1 while the transmitter is idle: SM4.5 / SM4.6.
    pub tx_idle_bit: u8,
    /// The first receive register: SMB86 / SMB186 (status; +1 control, +2 start character,
    /// +3 end character, +4 idle time word, +6 timer word, +8 maximum count).
    pub rcv_smb: u32,
    /// Receive-character event (8 / 25).
    pub char_event: u8,
    /// Transmit-complete event (9 / 26).
    pub tx_event: u8,
    /// Receive-message-complete event (23 / 24).
    pub rcv_event: u8,
}

/// Ports 0 and 1. Every S7 profile has both register sets except the `a5`, whose SM area
/// ends below SMB186 (the front end rejects RCV on its port 1, Appendix A).
pub const PORTS: [PortRegs; 2] = [
    PortRegs {
        port: 0,
        mode_smb: 30,
        tx_idle_bit: 5,
        rcv_smb: 86,
        char_event: 8,
        tx_event: 9,
        rcv_event: 23,
    },
    PortRegs {
        port: 1,
        mode_smb: 130,
        tx_idle_bit: 6,
        rcv_smb: 186,
        char_event: 25,
        tx_event: 26,
        rcv_event: 24,
    },
];

/// The serial ports `profile` has: both of [`PORTS`] on every S7 profile (the `a5` too, whose
/// port 1 transmits and receives characters but has no receive registers for RCV), none on
/// the Omron profiles. The layout's port state and the stimulus's `PORTn` columns follow it.
pub fn ports(profile: &CpuProfile) -> &'static [PortRegs] {
    match profile.family {
        Family::S7 => &PORTS,
        Family::Omron => &[],
    }
}

/// Port `n` of `profile`, if it has it.
pub fn port(profile: &CpuProfile, n: u8) -> Option<&'static PortRegs> {
    ports(profile).get(usize::from(n))
}

/// The receive register offsets from [`PortRegs::rcv_smb`] (§10.3).
pub mod rcv {
    /// Status byte (SMB86): `n r e 0 0 t c p`.
    pub const STATUS: u32 = 0;
    /// Control byte (SMB87): `en sc ec il c/m tmr bk 0`.
    pub const CONTROL: u32 = 1;
    /// Start character (SMB88).
    pub const START_CHAR: u32 = 2;
    /// End character (SMB89).
    pub const END_CHAR: u32 = 3;
    /// Idle-line time in ms (SMW90).
    pub const IDLE_MS: u32 = 4;
    /// Inter-character or message timer in ms (SMW92).
    pub const TIMER_MS: u32 = 6;
    /// Maximum characters (SMB94).
    pub const MAX_COUNT: u32 = 8;
}

/// The SM byte a received character is written to (SMB2; both ports share it, §10.4).
pub const RX_CHAR_SMB: u32 = 2;

/// The station address GPA reads until SPA sets one (§10.6 "default 2").
pub const DEFAULT_STATION: u8 = 2;

/// The highest station address SPA accepts (§10.6: 1–126).
pub const MAX_STATION: u8 = 126;

/// Network jobs (NETR/NETW/GET/PUT) that can be active at once (§10.5: "more than 8 active").
pub const MAX_NET_JOBS: u32 = 8;

/// The time from a network job's start to its completion, µs (§10.5 default 10 ms).
pub const NET_LATENCY_US: u64 = 10_000;

/// Character time in µs for the mode byte `mode` (§10.1): 1 start + 8 or 7 data + parity
/// (if any) + 1 stop bit, `⌈bits · 10⁶ / baud⌉`.
pub fn char_time_us(mode: u8) -> u64 {
    bit_time(mode, 1 + data_bits(mode) + parity_bits(mode) + 1)
}

/// The duration in µs of a BREAK (XMT with count 0): 16 bit times (§10.2).
pub fn break_time_us(mode: u8) -> u64 {
    bit_time(mode, 16)
}

/// The baud rate of mode byte `mode` (bits 4–2).
pub fn baud(mode: u8) -> u64 {
    const BAUD: [u64; 8] = [38_400, 19_200, 9_600, 4_800, 2_400, 1_200, 115_200, 57_600];
    BAUD[usize::from((mode >> 2) & 7)]
}

fn data_bits(mode: u8) -> u64 {
    if mode & 0x20 != 0 { 7 } else { 8 }
}

/// Parity bits 7–6: 00 and 10 none, 01 even, 11 odd.
fn parity_bits(mode: u8) -> u64 {
    u64::from(mode & 0x40 != 0)
}

fn bit_time(mode: u8, bits: u64) -> u64 {
    (bits * 1_000_000).div_ceil(baud(mode))
}

/// The protocol of a mode byte (bits 1–0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Protocol {
    /// 00 and 11 (reserved, taken as PPI slave).
    PpiSlave,
    /// 01: XMT/RCV work.
    Freeport,
    /// 10: NETR/NETW work.
    PpiMaster,
}

/// The protocol of mode byte `mode`.
pub fn protocol(mode: u8) -> Protocol {
    match mode & 3 {
        1 => Protocol::Freeport,
        2 => Protocol::PpiMaster,
        _ => Protocol::PpiSlave,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// §10.1: 9 600 baud 8N1 is 10 bits, 1 042 µs; 16#09 is Freeport at 9 600.
    #[test]
    fn character_time() {
        assert_eq!(baud(0x09), 9_600);
        assert_eq!(char_time_us(0x09), 1_042);
        assert_eq!(protocol(0x09), Protocol::Freeport);
        // Even parity, 7 data bits, 19 200: 1 + 7 + 1 + 1 = 10 bits → 521 µs.
        assert_eq!(char_time_us(0b0110_0101), 521);
        assert_eq!(break_time_us(0x09), 1_667);
    }
}
