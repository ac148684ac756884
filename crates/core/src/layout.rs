//! The flat memory image: one contiguous byte buffer holding every area, the private state of
//! timers, counters and edges, and the scan bookkeeping.
//!
//! Offsets are computed from a [`CpuProfile`] in a fixed order, each block aligned to 16 bytes.
//! Multi-byte values in PLC areas (I, Q, M, S, SM, V, L, AI, AQ, T/C values, HC, AC) are big-endian;
//! the private blocks below ([`TimerState`], [`CounterState`], [`Sched`], [`IntState`],
//! [`QueueEntry`]) use native-endian fields because only the engines and the runtime read them. Both engines must leave identical bytes in
//! every block after every scan; the differential oracle compares the whole image.
//!
//! Each private record's field offsets, types and names are declared once (`record_fields!`), so
//! the constants the engines use and the `FIELDS` tables that name bytes in reports cannot drift
//! apart; [`Layout::region`] and [`Block::field_at`] name any image offset from them.

use crate::area::Area;
use crate::profile::{CpuProfile, Family, ProfileId};

/// Bytes of private state per timer (see [`TimerState`]).
pub const TIMER_STATE_SIZE: u32 = 16;
/// Bytes of private state per counter (see [`CounterState`]).
pub const COUNTER_STATE_SIZE: u32 = 4;
/// Bytes of the scan bookkeeping block (see [`Sched`]).
pub const SCHED_SIZE: u32 = 64;
/// Bytes of the interrupt machinery's state (see [`IntState`]; 0 on profiles without
/// interrupts).
pub const INT_STATE_SIZE: u32 = 144;
/// Bytes of one interrupt queue entry (see [`QueueEntry`]).
pub const QUEUE_ENTRY_SIZE: u32 = 16;
/// Bytes of private state per high-speed counter (see [`HscState`]).
pub const HSC_STATE_SIZE: u32 = 40;
/// Bytes of private state per pulse output channel (see [`PulseState`]).
pub const PULSE_STATE_SIZE: u32 = 64;
/// Number of `L` frames: the main program and eight subroutine levels (frames 0–8), the
/// running interrupt routine ([`ISR_FRAME`]) and four levels of its calls (frames 10–13),
/// s7-200-more §1.6.
pub const L_FRAMES: u32 = 14;
/// The L frame of the running interrupt routine; frames below it are the main program's call
/// chain, frames above it the routine's (only one routine runs at a time).
pub const ISR_FRAME: u32 = 9;
/// Bytes of the state of the s7-200-more instructions (see [`InstrState`]; 0 on Omron
/// profiles).
pub const INSTR_STATE_SIZE: u32 = 32;

/// One named field of a private record ([`TimerState`], [`CounterState`], [`Sched`]): its name,
/// its offset in the record and its size in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// The field's name, as its constant is spelled (`LOOP_COUNT`).
    pub name: &'static str,
    /// Byte offset inside the record.
    pub offset: u32,
    /// Size in bytes.
    pub size: u32,
}

/// Declares a private record's field offsets as `u32` constants and, from the same lines, its
/// `FIELDS` table, so that a field's offset, type and name are written once.
macro_rules! record_fields {
    (
        $(#[$doc:meta])*
        $record:ident {
            $( $(#[$field_doc:meta])* $field:ident: $ty:ty = $offset:literal; )*
        }
    ) => {
        $(#[$doc])*
        pub struct $record;
        impl $record {
            $(
                $(#[$field_doc])*
                #[doc = ""]
                #[doc = concat!("Type `", stringify!($ty), "`.")]
                pub const $field: u32 = $offset;
            )*
            /// Every field in offset order; bytes between fields are spare.
            pub const FIELDS: &'static [Field] = &[$(Field {
                name: stringify!($field),
                offset: $offset,
                size: std::mem::size_of::<$ty>() as u32,
            }),*];
        }
    };
}

// The peripherals' records (s7-200-more §8, §9) and the communication records (§10), beside
// this file to keep it short.
mod comm_records;
mod periph;
pub use comm_records::{NET_JOB_SIZE, NetJob, PORT_STATE_SIZE, PortState};
pub use periph::{HscState, PulseState};

record_fields! {
    /// Field offsets inside one timer's private state block.
    TimerState {
        /// TON/TONR timing active.
        RUN: u8 = 0;
        /// TOF phase, see `TofPhase` in the runtime (0 idle, 1 on, 2 timing, 3 done); Omron
        /// timers: the milliseconds not yet converted into PV units (below the unit).
        TOF: u8 = 1;
        /// The timer's kind (0 unused, 1 TON, 2 TONR, 3 TOF), written at cold start.
        KIND: u8 = 2;
        /// Resolution in ms (1, 10, 100), written at cold start.
        RES: u8 = 3;
        /// Native-endian: the preset seen at the last execution, used by the clock refresh.
        PT_CACHE: i16 = 4;
        /// Native-endian: Omron timers only, the virtual time (ms) of the last execution.
        LAST: u64 = 8;
    }
}

record_fields! {
    /// Field offsets inside one counter's private state block.
    CounterState {
        /// Count-up input at the last execution.
        PREV_UP: u8 = 0;
        /// Count-down input at the last execution.
        PREV_DOWN: u8 = 1;
        /// The counter's kind (0 unused, 1 CTU, 2 CTD, 3 CTUD), written at cold start.
        KIND: u8 = 2;
    }
}

record_fields! {
    /// Field offsets inside the scan bookkeeping block (spec §1.8 "scheduler").
    Sched {
        /// Number of the current scan (0 for the first).
        SCAN_NO: u64 = 0;
        /// Virtual time in ms at the start of the current scan.
        T_NOW: u64 = 8;
        /// Virtual time of the previous scan.
        T_PREV: u64 = 16;
        /// Ms elapsed since the previous scan.
        D1: u32 = 24;
        /// 10-ms intervals elapsed since the previous scan.
        D10: u32 = 28;
        /// 100-ms intervals elapsed since the previous scan.
        D100: u32 = 32;
        /// Loop-budget events counted in this scan (taken back-edges, NEXT loop-backs).
        LOOP_COUNT: u32 = 36;
        /// ENO of the last box instruction.
        ENO: u8 = 40;
        /// 1 during the first scan.
        FIRST_SCAN: u8 = 41;
        /// SCR power-flow gate (1 outside segments).
        SCR_ENABLE: u8 = 42;
        /// A STOP instruction executed in this scan.
        STOP_REQ: u8 = 43;
        /// 0 RUN, 1 STOP (entered by STOP or a fatal error).
        MODE: u8 = 44;
        /// 1 when the harness declares retentive data lost (SM0.2 in the first scan).
        RETENTIVE_LOST: u8 = 45;
        /// Code of the last non-fatal error (0 none).
        LAST_ERR: u16 = 46;
        /// Fatal error code (0 none).
        FATAL: u16 = 48;
        /// POU of the instruction that raised the last error.
        ERR_POU: u16 = 50;
        /// Instruction index that raised the last error.
        ERR_OP: u32 = 52;
        /// Loop budget per scan (watchdog), written at cold start.
        LOOP_LIMIT: u32 = 56;
    }
}

record_fields! {
    /// Field offsets inside the interrupt machinery's state (s7-200-more §3, §11.1): one record
    /// per image, read and written only by `stljit_runtime::interrupt`.
    IntState {
        /// Interrupts globally enabled (ENI); mirrored in SM4.4.
        ENABLED: u8 = 0;
        /// 1 while an interrupt routine runs.
        IN_ISR: u8 = 1;
        /// Bit `i`: the `CT = PT` condition of the `i`-th timer event source of the profile at
        /// the last poll (T32, T96).
        TIMER_PREV: u8 = 2;
        /// Sequence number of the next queued entry (counts every entry ever queued).
        SEQ: u32 = 4;
        /// Virtual time in µs of the code running: the event time in a routine, `T_k` in the
        /// main program (what ATCH of a timed interrupt starts its schedule from).
        NOW: u64 = 8;
        /// Entries queued, per group (communication, discrete, timed).
        QUEUE_LEN: [u8; 3] = 16;
        /// Timed interrupts 0 and 1: the interval in ms captured from SMB34/SMB35 at ATCH.
        TIMED_INTERVAL: [u8; 2] = 20;
        /// Timed interrupts 0 and 1: the time in µs of the next due event.
        TIMED_NEXT: [u64; 2] = 24;
        /// Per event number: 0 when detached, else the interrupt routine's number + 1.
        ATTACH: [u8; 64] = 40;
        /// The physical inputs at the last scan instant (input edges are found against them;
        /// the interval phase runs with them in place of the new ones).
        PREV_IN: [u8; 32] = 104;
    }
}

record_fields! {
    /// Field offsets inside one interrupt queue entry (s7-200-more §3.3). The entries of the
    /// three queues follow each other (communication, discrete, timed, each its profile's
    /// depth); a queue's entries are kept in the order they were queued.
    QueueEntry {
        /// Time in µs the event occurred.
        TAU: u64 = 0;
        /// Its sequence number ([`IntState::SEQ`] when it was queued).
        SEQ: u32 = 8;
        /// The event number.
        EVENT: u8 = 12;
    }
}

record_fields! {
    /// Field offsets inside the state of the s7-200-more instructions (§11.1): the real-time
    /// clock (§6.2) and the PID loops' power-flow history (§7.3). One record per image, read and
    /// written only by `stljit_runtime::rtc` and `stljit_runtime::pid`.
    InstrState {
        /// Native-endian: seconds since 2000-01-01 00:00:00 that the clock showed at
        /// `RTC_REF_US` (the start date at cold start, then the last TODW/TODWX).
        RTC_EPOCH: i64 = 0;
        /// Native-endian: the virtual time in µs at which the clock showed `RTC_EPOCH`.
        RTC_REF_US: u64 = 8;
        /// The daylight-saving bytes 8–20 of the last TODWX, which TODRX returns.
        RTC_DST: [u8; 13] = 16;
        /// Bit `n`: PID loop `n` ran without power flow at its last execution. 0 at cold start,
        /// which is the manual's history bit *set*: no bumpless transfer on a first execution
        /// with power flow.
        PID_NO_FLOW: u8 = 29;
    }
}

/// Default loop budget per scan (spec §2.5).
pub const DEFAULT_LOOP_LIMIT: u32 = 65_536;

/// Byte offsets of every block of the image for one profile.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The profile the layout was computed for.
    pub profile: ProfileId,
    area_base: [u32; Area::ALL.len()],
    area_size: [u32; Area::ALL.len()],
    /// Edge memories, one byte per EU/ED slot.
    pub edges: u32,
    /// Timer private state, [`TIMER_STATE_SIZE`] bytes per timer.
    pub timer_state: u32,
    /// Counter private state, [`COUNTER_STATE_SIZE`] bytes per counter.
    pub counter_state: u32,
    /// Scan bookkeeping block, see [`Sched`].
    pub sched: u32,
    /// Physical input copy (what the harness drives; LDI/BIR read it).
    pub phys_in: u32,
    /// Physical output copy (written at scan end and by `=I`, `SI`, `RI`, `BIW`).
    pub phys_out: u32,
    /// The interrupt machinery's state, see [`IntState`].
    pub interrupts: u32,
    /// The interrupt queues' entries, see [`QueueEntry`].
    pub queue: u32,
    /// The state of the s7-200-more instructions, see [`InstrState`].
    pub instr: u32,
    /// The high-speed counters' private state, see [`HscState`].
    pub hsc: u32,
    /// The pulse output channels' private state, see [`PulseState`].
    pub pulse: u32,
    /// The serial ports' state, one [`PortState`] per port.
    pub ports: u32,
    /// The network job slots ([`NetJob`]).
    pub net_jobs: u32,
    /// Total image size in bytes.
    pub size: u32,
    block_size: [u32; Block::ALL.len()],
}

fn align16(x: u32) -> u32 {
    (x + 15) & !15
}

impl Layout {
    /// Computes the layout of a profile's image.
    pub fn new(profile: &CpuProfile) -> Layout {
        let mut area_base = [0; Area::ALL.len()];
        let mut area_size = [0; Area::ALL.len()];
        let mut next = 0;
        for area in Area::ALL {
            let size = match area {
                Area::L => profile.local_frame * L_FRAMES,
                _ => profile.area_size(area),
            };
            area_base[area as usize] = next;
            area_size[area as usize] = profile.area_size(area);
            next = align16(next + size);
        }
        let mut block_size = [0; Block::ALL.len()];
        let mut take = |block: Block, size: u32| {
            block_size[block as usize] = size;
            let at = next;
            next = align16(next + size);
            at
        };
        let edges = take(Block::Edges, u32::from(profile.max_edges));
        let timer_state = take(
            Block::TimerState,
            TIMER_STATE_SIZE * u32::from(profile.timers),
        );
        let counter_state = take(
            Block::CounterState,
            COUNTER_STATE_SIZE * u32::from(profile.counters),
        );
        let sched = take(Block::Sched, SCHED_SIZE);
        let phys_in = take(Block::PhysIn, profile.inputs);
        let phys_out = take(Block::PhysOut, profile.outputs);
        let ints = profile.interrupts;
        let interrupts = take(
            Block::Interrupts,
            if ints.any() { INT_STATE_SIZE } else { 0 },
        );
        let queue = take(Block::Queue, QUEUE_ENTRY_SIZE * ints.slots());
        let instr = take(
            Block::Instr,
            match profile.family {
                Family::S7 => INSTR_STATE_SIZE,
                Family::Omron => 0,
            },
        );
        let hsc = take(
            Block::Hsc,
            HSC_STATE_SIZE * profile.hsc.counters.len() as u32,
        );
        let pulse = take(
            Block::Pulse,
            PULSE_STATE_SIZE * profile.pulse.channels.len() as u32,
        );
        let (ports, net_jobs) = comm_records::take_blocks(profile, &mut take);
        Layout {
            profile: profile.id,
            area_base,
            area_size,
            edges,
            timer_state,
            counter_state,
            sched,
            phys_in,
            phys_out,
            interrupts,
            queue,
            instr,
            hsc,
            pulse,
            ports,
            net_jobs,
            size: next,
            block_size,
        }
    }

    /// The layout of a built-in profile.
    pub fn of(id: ProfileId) -> Layout {
        Layout::new(id.profile())
    }

    /// Image offset of the first byte of `area` (for `L`, of frame 0).
    #[inline]
    pub fn base(&self, area: Area) -> u32 {
        self.area_base[area as usize]
    }

    /// Size of `area` in bytes (for `L`, one frame).
    #[inline]
    pub fn area_size(&self, area: Area) -> u32 {
        self.area_size[area as usize]
    }

    /// Image offset of byte `offset` of `area`; `L` offsets are in frame `frame`.
    #[inline]
    pub fn addr(&self, area: Area, offset: u32, frame: u32) -> u32 {
        let base = self.base(area);
        if area == Area::L {
            base + frame * self.area_size(Area::L) + offset
        } else {
            base + offset
        }
    }

    /// Image offset of timer `n`'s private state block.
    #[inline]
    pub fn timer_state(&self, n: u16) -> u32 {
        self.timer_state + TIMER_STATE_SIZE * u32::from(n)
    }

    /// Image offset of counter `n`'s private state block.
    #[inline]
    pub fn counter_state(&self, n: u16) -> u32 {
        self.counter_state + COUNTER_STATE_SIZE * u32::from(n)
    }

    /// Image offset of a scan bookkeeping field (a [`Sched`] constant).
    #[inline]
    pub fn sched(&self, field: u32) -> u32 {
        self.sched + field
    }

    /// Image offset of an interrupt-state field (an [`IntState`] constant).
    #[inline]
    pub fn int_state(&self, field: u32) -> u32 {
        self.interrupts + field
    }

    /// Image offset of queue entry `slot` (see [`crate::interrupt::InterruptProfile::queue`]).
    #[inline]
    pub fn queue_entry(&self, slot: u32) -> u32 {
        self.queue + QUEUE_ENTRY_SIZE * slot
    }

    /// Image offset of a field of the s7-200-more instructions' state (an [`InstrState`]
    /// constant).
    #[inline]
    pub fn instr_state(&self, field: u32) -> u32 {
        self.instr + field
    }

    /// Image offset of a field (an [`HscState`] constant) of high-speed counter `n`'s private
    /// state.
    #[inline]
    pub fn hsc_state(&self, n: u8, field: u32) -> u32 {
        self.hsc + HSC_STATE_SIZE * u32::from(n) + field
    }

    /// Image offset of a field (a [`PulseState`] constant) of pulse channel `n`'s private
    /// state.
    #[inline]
    pub fn pulse_state(&self, n: u8, field: u32) -> u32 {
        self.pulse + PULSE_STATE_SIZE * u32::from(n) + field
    }

    /// The area and in-area offset an image offset belongs to, for naming differing bytes.
    pub fn locate(&self, image_offset: u32) -> Option<(Area, u32)> {
        Area::ALL.into_iter().find_map(|area| {
            let base = self.base(area);
            let size = match area {
                Area::L => self.area_size(area) * L_FRAMES,
                _ => self.area_size(area),
            };
            (base..base + size)
                .contains(&image_offset)
                .then(|| (area, image_offset - base))
        })
    }

    /// Image offset of the first byte of a private block.
    #[inline]
    pub fn block_start(&self, block: Block) -> u32 {
        match block {
            Block::Edges => self.edges,
            Block::TimerState => self.timer_state,
            Block::CounterState => self.counter_state,
            Block::Sched => self.sched,
            Block::PhysIn => self.phys_in,
            Block::PhysOut => self.phys_out,
            Block::Interrupts => self.interrupts,
            Block::Queue => self.queue,
            Block::Instr => self.instr,
            Block::Hsc => self.hsc,
            Block::Pulse => self.pulse,
            Block::Ports => self.ports,
            Block::NetJobs => self.net_jobs,
        }
    }

    /// Size of a private block in bytes (without its alignment padding).
    #[inline]
    pub fn block_size(&self, block: Block) -> u32 {
        self.block_size[block as usize]
    }

    /// Names image offset `image_offset`: a PLC area byte ([`Layout::locate`]), a byte of a
    /// private block (whose field [`Block::field_at`] names), or alignment padding.
    pub fn region(&self, image_offset: u32) -> Region {
        if let Some((area, offset)) = self.locate(image_offset) {
            return Region::Area { area, offset };
        }
        Block::ALL
            .into_iter()
            .find_map(|block| {
                let start = self.block_start(block);
                (start..start + self.block_size(block))
                    .contains(&image_offset)
                    .then(|| Region::Block {
                        block,
                        offset: image_offset - start,
                    })
            })
            .unwrap_or(Region::Padding)
    }

    /// The image bytes `(offset, length)` one execution of timer `n` reads and writes: its
    /// value (2 bytes, big-endian), its bit (1 byte) and its private state
    /// ([`TIMER_STATE_SIZE`]). The runtime's timer rules and the JIT's cache invalidation both
    /// use it.
    pub fn timer_bytes(&self, n: u16) -> [(u32, u32); 3] {
        [
            (self.base(Area::TimerValue) + 2 * u32::from(n), 2),
            (self.base(Area::TimerBit) + u32::from(n), 1),
            (self.timer_state(n), TIMER_STATE_SIZE),
        ]
    }

    /// The image bytes `(offset, length)` one execution of counter `n` reads and writes: its
    /// value (2 bytes, big-endian), its bit (1 byte) and its private state
    /// ([`COUNTER_STATE_SIZE`]).
    pub fn counter_bytes(&self, n: u16) -> [(u32, u32); 3] {
        [
            (self.base(Area::CounterValue) + 2 * u32::from(n), 2),
            (self.base(Area::CounterBit) + u32::from(n), 1),
            (self.counter_state(n), COUNTER_STATE_SIZE),
        ]
    }
}

/// The blocks of the image after the PLC areas, in layout order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Block {
    /// Edge memories, one byte per EU/ED slot.
    Edges,
    /// Timer private state, one [`TimerState`] record per timer.
    TimerState,
    /// Counter private state, one [`CounterState`] record per counter.
    CounterState,
    /// Scan bookkeeping, one [`Sched`] record.
    Sched,
    /// The physical input copy.
    PhysIn,
    /// The physical output copy.
    PhysOut,
    /// The interrupt machinery's state, one [`IntState`] record (none on profiles without
    /// interrupts).
    Interrupts,
    /// The interrupt queues, one [`QueueEntry`] record per slot.
    Queue,
    /// The state of the s7-200-more instructions, one [`InstrState`] record (none on Omron
    /// profiles).
    Instr,
    /// The high-speed counters' private state, one [`HscState`] record per counter of the
    /// profile's table.
    Hsc,
    /// The pulse output channels' private state, one [`PulseState`] record per channel of
    /// the profile's table.
    Pulse,
    /// The serial ports' private state, one [`PortState`] record per port (none on Omron
    /// profiles).
    Ports,
    /// The network job slots, one [`NetJob`] record each (none on Omron profiles).
    NetJobs,
}

impl Block {
    /// Every block, in layout order.
    pub const ALL: [Block; 13] = [
        Block::Edges,
        Block::TimerState,
        Block::CounterState,
        Block::Sched,
        Block::PhysIn,
        Block::PhysOut,
        Block::Interrupts,
        Block::Queue,
        Block::Instr,
        Block::Hsc,
        Block::Pulse,
        Block::Ports,
        Block::NetJobs,
    ];

    /// A short name for reports (`timer state`).
    pub fn name(self) -> &'static str {
        match self {
            Block::Edges => "edge memory",
            Block::TimerState => "timer state",
            Block::CounterState => "counter state",
            Block::Sched => "scheduler",
            Block::PhysIn => "physical inputs",
            Block::PhysOut => "physical outputs",
            Block::Interrupts => "interrupt state",
            Block::Queue => "interrupt queue",
            Block::Instr => "clock and PID state",
            Block::Hsc => "high-speed counter state",
            Block::Pulse => "pulse output state",
            Block::Ports => "serial port state",
            Block::NetJobs => "network jobs",
        }
    }

    /// For a block of records with named fields: the bytes per record and the fields.
    pub fn record(self) -> Option<(u32, &'static [Field])> {
        match self {
            Block::TimerState => Some((TIMER_STATE_SIZE, TimerState::FIELDS)),
            Block::CounterState => Some((COUNTER_STATE_SIZE, CounterState::FIELDS)),
            Block::Sched => Some((SCHED_SIZE, Sched::FIELDS)),
            Block::Interrupts => Some((INT_STATE_SIZE, IntState::FIELDS)),
            Block::Queue => Some((QUEUE_ENTRY_SIZE, QueueEntry::FIELDS)),
            Block::Instr => Some((INSTR_STATE_SIZE, InstrState::FIELDS)),
            Block::Hsc => Some((HSC_STATE_SIZE, HscState::FIELDS)),
            Block::Pulse => Some((PULSE_STATE_SIZE, PulseState::FIELDS)),
            Block::Ports => Some((PORT_STATE_SIZE, PortState::FIELDS)),
            Block::NetJobs => Some((NET_JOB_SIZE, NetJob::FIELDS)),
            Block::Edges | Block::PhysIn | Block::PhysOut => None,
        }
    }

    /// The record and the field (or run of spare bytes) holding byte `offset` of this block;
    /// `None` for a block without fields.
    pub fn field_at(self, offset: u32) -> Option<FieldAt> {
        let (record_size, fields) = self.record()?;
        let (record, rel) = (offset / record_size, offset % record_size);
        let at = |name, start: u32, size| FieldAt {
            record,
            name,
            start,
            size,
            byte: rel - start,
        };
        let mut spare_start = 0;
        for f in fields {
            if rel < f.offset {
                return Some(at(None, spare_start, f.offset - spare_start));
            }
            if rel < f.offset + f.size {
                return Some(at(Some(f.name), f.offset, f.size));
            }
            spare_start = f.offset + f.size;
        }
        Some(at(None, spare_start, record_size - spare_start))
    }
}

/// Where a byte of a record block falls (see [`Block::field_at`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FieldAt {
    /// Record number: the timer or counter number, the queue slot (0 for [`Sched`] and
    /// [`IntState`]).
    pub record: u32,
    /// The field's name, or `None` for spare bytes.
    pub name: Option<&'static str>,
    /// Offset in the record of the field or the run of spare bytes.
    pub start: u32,
    /// Size of the field or the run of spare bytes.
    pub size: u32,
    /// Index of the byte inside it.
    pub byte: u32,
}

/// What an image byte belongs to (see [`Layout::region`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// Byte `offset` of a PLC area (for `L`, counted from frame 0).
    Area {
        /// The area.
        area: Area,
        /// Byte offset inside the area.
        offset: u32,
    },
    /// Byte `offset` of a private block.
    Block {
        /// The block.
        block: Block,
        /// Byte offset inside the block.
        offset: u32,
    },
    /// Alignment padding between blocks, or an offset past the end of the image.
    Padding,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_do_not_overlap() {
        for id in ProfileId::ALL {
            let l = Layout::of(id);
            let p = id.profile();
            let mut blocks: Vec<(u32, u32)> = Area::ALL
                .iter()
                .map(|&a| {
                    let n = if a == Area::L { L_FRAMES } else { 1 };
                    (l.base(a), l.area_size(a) * n)
                })
                .collect();
            blocks.push((l.edges, u32::from(p.max_edges)));
            blocks.push((l.timer_state, TIMER_STATE_SIZE * u32::from(p.timers)));
            blocks.push((l.counter_state, COUNTER_STATE_SIZE * u32::from(p.counters)));
            blocks.push((l.sched, SCHED_SIZE));
            blocks.push((l.phys_in, p.inputs));
            blocks.push((l.phys_out, p.outputs));
            blocks.push((l.interrupts, l.block_size(Block::Interrupts)));
            blocks.push((l.queue, l.block_size(Block::Queue)));
            blocks.push((l.instr, l.block_size(Block::Instr)));
            blocks.sort();
            for w in blocks.windows(2) {
                assert!(
                    w[0].0 + w[0].1 <= w[1].0,
                    "{id}: {:?} overlaps {:?}",
                    w[0],
                    w[1]
                );
            }
            let last = blocks.last().unwrap();
            assert!(last.0 + last.1 <= l.size);
        }
    }

    #[test]
    fn locate_inverts_addr() {
        let l = Layout::of(ProfileId::A5);
        assert_eq!(l.locate(l.addr(Area::V, 100, 0)), Some((Area::V, 100)));
        assert_eq!(l.locate(l.addr(Area::L, 3, 2)), Some((Area::L, 131)));
        assert_eq!(l.locate(l.sched), None);
    }

    #[test]
    fn record_fields_are_ordered_and_fit() {
        for block in Block::ALL {
            let Some((size, fields)) = block.record() else {
                continue;
            };
            let mut end = 0;
            for f in fields {
                assert!(f.offset >= end, "{block:?}.{} overlaps", f.name);
                end = f.offset + f.size;
            }
            assert!(end <= size, "{block:?} fields exceed {size} bytes");
        }
        // The saved physical inputs hold every profile's input image.
        let prev_in = IntState::FIELDS
            .iter()
            .find(|f| f.name == "PREV_IN")
            .unwrap();
        for id in ProfileId::ALL {
            assert!(id.profile().inputs <= prev_in.size, "{id}");
        }
        assert_eq!(Sched::FIELDS[6].name, "LOOP_COUNT");
        assert_eq!(Sched::FIELDS[6].offset, Sched::LOOP_COUNT);
        assert_eq!(TimerState::FIELDS[4].size, 2);
    }

    #[test]
    fn region_names_fields_and_spare_bytes() {
        let l = Layout::of(ProfileId::A5);
        assert_eq!(
            l.region(l.addr(Area::V, 7, 0)),
            Region::Area {
                area: Area::V,
                offset: 7
            }
        );
        let Region::Block { block, offset } =
            l.region(l.timer_state(37) + TimerState::PT_CACHE + 1)
        else {
            panic!("not a block")
        };
        assert_eq!(block, Block::TimerState);
        let at = block.field_at(offset).unwrap();
        assert_eq!((at.record, at.name, at.byte), (37, Some("PT_CACHE"), 1));
        let spare = Block::Sched.field_at(61).unwrap();
        assert_eq!(
            (spare.name, spare.start, spare.size, spare.byte),
            (None, 60, 4, 1)
        );
        assert_eq!(Block::Edges.field_at(0), None);
        // The A5's SM area (180 bytes) is padded to 192.
        assert_eq!(
            l.region(l.base(Area::SM) + l.area_size(Area::SM)),
            Region::Padding
        );
        assert_eq!(l.region(l.size), Region::Padding);
        let Region::Block { block, offset } = l.region(l.queue_entry(9) + QueueEntry::EVENT) else {
            panic!("not a block")
        };
        let at = block.field_at(offset).unwrap();
        assert_eq!(
            (block, at.record, at.name),
            (Block::Queue, 9, Some("EVENT"))
        );
        let Region::Block { block, offset } = l.region(l.int_state(IntState::ATTACH) + 10) else {
            panic!("not a block")
        };
        let at = block.field_at(offset).unwrap();
        assert_eq!((at.name, at.byte), (Some("ATTACH"), 10));
        let Region::Block { block, offset } = l.region(l.instr_state(InstrState::PID_NO_FLOW))
        else {
            panic!("not a block")
        };
        let at = block.field_at(offset).unwrap();
        assert_eq!((block, at.name), (Block::Instr, Some("PID_NO_FLOW")));
        let omron = Layout::of(ProfileId::Cp1h);
        assert_eq!(omron.block_size(Block::Instr), 0);
    }
}
