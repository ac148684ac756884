//! The flat memory image: one contiguous byte buffer holding every area, the private state of
//! timers, counters and edges, and the scan bookkeeping.
//!
//! Offsets are computed from a [`CpuProfile`] in a fixed order, each block aligned to 16 bytes.
//! Multi-byte values in PLC areas (I, Q, M, S, SM, V, L, AI, AQ, T/C values, HC, AC) are big-endian;
//! the private blocks below ([`TimerState`], [`CounterState`], [`Sched`]) use native-endian fields
//! because only the engines and the runtime read them. Both engines must leave identical bytes in
//! every block after every scan; the differential oracle compares the whole image.

use crate::area::Area;
use crate::profile::{CpuProfile, ProfileId};

/// Bytes of private state per timer (see [`TimerState`]).
pub const TIMER_STATE_SIZE: u32 = 8;
/// Bytes of private state per counter (see [`CounterState`]).
pub const COUNTER_STATE_SIZE: u32 = 4;
/// Bytes of the scan bookkeeping block (see [`Sched`]).
pub const SCHED_SIZE: u32 = 64;
/// Number of `L` frames: the main program plus eight subroutine levels.
pub const L_FRAMES: u32 = 9;

/// Field offsets inside one timer's private state block.
pub struct TimerState;
impl TimerState {
    /// `u8`: TON/TONR timing active.
    pub const RUN: u32 = 0;
    /// `u8`: TOF phase, see `TofPhase` in the runtime (0 idle, 1 on, 2 timing, 3 done).
    pub const TOF: u32 = 1;
    /// `u8`: the timer's kind (0 unused, 1 TON, 2 TONR, 3 TOF), written at cold start.
    pub const KIND: u32 = 2;
    /// `u8`: resolution in ms (1, 10, 100), written at cold start.
    pub const RES: u32 = 3;
    /// `i16` native-endian: the preset seen at the last execution, used by the clock refresh.
    pub const PT_CACHE: u32 = 4;
}

/// Field offsets inside one counter's private state block.
pub struct CounterState;
impl CounterState {
    /// `u8`: count-up input at the last execution.
    pub const PREV_UP: u32 = 0;
    /// `u8`: count-down input at the last execution.
    pub const PREV_DOWN: u32 = 1;
    /// `u8`: the counter's kind (0 unused, 1 CTU, 2 CTD, 3 CTUD), written at cold start.
    pub const KIND: u32 = 2;
}

/// Field offsets inside the scan bookkeeping block (spec §1.8 "scheduler").
pub struct Sched;
impl Sched {
    /// `u64`: number of the current scan (0 for the first).
    pub const SCAN_NO: u32 = 0;
    /// `u64`: virtual time in ms at the start of the current scan.
    pub const T_NOW: u32 = 8;
    /// `u64`: virtual time of the previous scan.
    pub const T_PREV: u32 = 16;
    /// `u32`: ms elapsed since the previous scan.
    pub const D1: u32 = 24;
    /// `u32`: 10-ms intervals elapsed since the previous scan.
    pub const D10: u32 = 28;
    /// `u32`: 100-ms intervals elapsed since the previous scan.
    pub const D100: u32 = 32;
    /// `u32`: loop-budget events counted in this scan (taken back-edges, NEXT loop-backs).
    pub const LOOP_COUNT: u32 = 36;
    /// `u8`: ENO of the last box instruction.
    pub const ENO: u32 = 40;
    /// `u8`: 1 during the first scan.
    pub const FIRST_SCAN: u32 = 41;
    /// `u8`: SCR power-flow gate (1 outside segments).
    pub const SCR_ENABLE: u32 = 42;
    /// `u8`: a STOP instruction executed in this scan.
    pub const STOP_REQ: u32 = 43;
    /// `u8`: 0 RUN, 1 STOP (entered by STOP or a fatal error).
    pub const MODE: u32 = 44;
    /// `u8`: 1 when the harness declares retentive data lost (SM0.2 in the first scan).
    pub const RETENTIVE_LOST: u32 = 45;
    /// `u16`: code of the last non-fatal error (0 none).
    pub const LAST_ERR: u32 = 46;
    /// `u16`: fatal error code (0 none).
    pub const FATAL: u32 = 48;
    /// `u16`: POU of the instruction that raised the last error.
    pub const ERR_POU: u32 = 50;
    /// `u32`: instruction index that raised the last error.
    pub const ERR_OP: u32 = 52;
    /// `u32`: loop budget per scan (watchdog), written at cold start.
    pub const LOOP_LIMIT: u32 = 56;
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
    /// Total image size in bytes.
    pub size: u32,
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
        let mut take = |size: u32| {
            let at = next;
            next = align16(next + size);
            at
        };
        let edges = take(u32::from(profile.max_edges));
        let timer_state = take(TIMER_STATE_SIZE * u32::from(profile.timers));
        let counter_state = take(COUNTER_STATE_SIZE * u32::from(profile.counters));
        let sched = take(SCHED_SIZE);
        let phys_in = take(profile.inputs);
        let phys_out = take(profile.outputs);
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
            size: next,
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
}
