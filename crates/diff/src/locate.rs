//! Names for image offsets: [`Layout::locate`] for the PLC areas, and the private blocks (edge
//! memories, timer and counter state, the scan bookkeeping, the physical I/O copies) by field, so
//! that a divergence report says `Sched.LOOP_COUNT` or `T37.RUN` instead of a bare number.

use std::fmt;
use stljit_core::layout::{
    COUNTER_STATE_SIZE, CounterState, L_FRAMES, Layout, SCHED_SIZE, Sched, TIMER_STATE_SIZE,
    TimerState,
};
use stljit_core::{Area, ProfileId};

/// What an image byte belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// A PLC area byte (for `L`, `offset` counts from frame 0: frame = offset / frame size).
    Area {
        /// The area.
        area: Area,
        /// Byte offset inside the area.
        offset: u32,
        /// Bytes per L frame (only meaningful for `L`).
        frame_size: u32,
    },
    /// An edge memory.
    Edge(u32),
    /// A timer's private state.
    Timer {
        /// Timer number.
        n: u32,
        /// Field name.
        field: &'static str,
    },
    /// A counter's private state.
    Counter {
        /// Counter number.
        n: u32,
        /// Field name.
        field: &'static str,
    },
    /// A scan bookkeeping field, and the byte inside it.
    Sched {
        /// Field name.
        field: &'static str,
        /// Byte offset of the field in the block.
        at: u32,
        /// Byte inside the field.
        byte: u32,
    },
    /// The physical input copy.
    PhysIn(u32),
    /// The physical output copy.
    PhysOut(u32),
    /// Alignment padding.
    Padding(u32),
}

/// Scan bookkeeping fields: offset, size, name.
const SCHED_FIELDS: [(u32, u32, &str); 20] = [
    (Sched::SCAN_NO, 8, "SCAN_NO"),
    (Sched::T_NOW, 8, "T_NOW"),
    (Sched::T_PREV, 8, "T_PREV"),
    (Sched::D1, 4, "D1"),
    (Sched::D10, 4, "D10"),
    (Sched::D100, 4, "D100"),
    (Sched::LOOP_COUNT, 4, "LOOP_COUNT"),
    (Sched::ENO, 1, "ENO"),
    (Sched::FIRST_SCAN, 1, "FIRST_SCAN"),
    (Sched::SCR_ENABLE, 1, "SCR_ENABLE"),
    (Sched::STOP_REQ, 1, "STOP_REQ"),
    (Sched::MODE, 1, "MODE"),
    (Sched::RETENTIVE_LOST, 1, "RETENTIVE_LOST"),
    (Sched::LAST_ERR, 2, "LAST_ERR"),
    (Sched::FATAL, 2, "FATAL"),
    (Sched::ERR_POU, 2, "ERR_POU"),
    (Sched::ERR_OP, 4, "ERR_OP"),
    (Sched::LOOP_LIMIT, 4, "LOOP_LIMIT"),
    (60, 4, "(unused)"),
    (64, 0, ""),
];

impl Place {
    /// Names image offset `off` of `layout`.
    pub fn of(layout: &Layout, off: u32) -> Place {
        if let Some((area, offset)) = layout.locate(off) {
            return Place::Area {
                area,
                offset,
                frame_size: layout.area_size(Area::L),
            };
        }
        let p = profile_of(layout.profile);
        let within = |base: u32, len: u32| off >= base && off < base + len;
        if within(layout.edges, u32::from(p.max_edges)) {
            return Place::Edge(off - layout.edges);
        }
        if within(layout.timer_state, TIMER_STATE_SIZE * u32::from(p.timers)) {
            let rel = off - layout.timer_state;
            let field = match rel % TIMER_STATE_SIZE {
                TimerState::RUN => "RUN",
                TimerState::TOF => "TOF",
                TimerState::KIND => "KIND",
                TimerState::RES => "RES",
                4 | 5 => "PT_CACHE",
                _ => "(pad)",
            };
            return Place::Timer {
                n: rel / TIMER_STATE_SIZE,
                field,
            };
        }
        if within(
            layout.counter_state,
            COUNTER_STATE_SIZE * u32::from(p.counters),
        ) {
            let rel = off - layout.counter_state;
            let field = match rel % COUNTER_STATE_SIZE {
                CounterState::PREV_UP => "PREV_UP",
                CounterState::PREV_DOWN => "PREV_DOWN",
                CounterState::KIND => "KIND",
                _ => "(pad)",
            };
            return Place::Counter {
                n: rel / COUNTER_STATE_SIZE,
                field,
            };
        }
        if within(layout.sched, SCHED_SIZE) {
            let rel = off - layout.sched;
            let (at, _, field) = SCHED_FIELDS
                .windows(2)
                .find(|w| rel >= w[0].0 && rel < w[1].0)
                .map_or((0, 0, "?"), |w| w[0]);
            return Place::Sched {
                field,
                at,
                byte: rel - at,
            };
        }
        if within(layout.phys_in, layout.area_size(Area::I)) {
            return Place::PhysIn(off - layout.phys_in);
        }
        if within(layout.phys_out, layout.area_size(Area::Q)) {
            return Place::PhysOut(off - layout.phys_out);
        }
        Place::Padding(off)
    }

    /// For a scan bookkeeping field: its offset in the block and size, to show whole values.
    pub fn sched_field(&self) -> Option<(u32, u32)> {
        match *self {
            Place::Sched { at, .. } => SCHED_FIELDS
                .iter()
                .find(|f| f.0 == at)
                .map(|&(at, size, _)| (at, size)),
            _ => None,
        }
    }
}

fn profile_of(id: ProfileId) -> &'static stljit_core::CpuProfile {
    id.profile()
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Place::Area {
                area: Area::L,
                offset,
                frame_size,
            } if frame_size > 0 && offset >= frame_size && offset / frame_size < L_FRAMES => {
                write!(
                    f,
                    "LB{} (frame {})",
                    offset % frame_size,
                    offset / frame_size
                )
            }
            Place::Area { area, offset, .. } => match area {
                Area::AI | Area::AQ => write!(f, "{area}W{} byte {}", offset & !1, offset & 1),
                Area::TimerValue => write!(f, "T{} value byte {}", offset / 2, offset % 2),
                Area::CounterValue => write!(f, "C{} value byte {}", offset / 2, offset % 2),
                Area::TimerBit => write!(f, "T{} bit", offset),
                Area::CounterBit => write!(f, "C{} bit", offset),
                Area::HC => write!(f, "HC{} byte {}", offset / 4, offset % 4),
                Area::AC => write!(f, "AC{} byte {}", offset / 4, offset % 4),
                _ => write!(f, "{}B{offset}", area.prefix()),
            },
            Place::Edge(n) => write!(f, "edge memory {n}"),
            Place::Timer { n, field } => write!(f, "T{n}.{field} (private)"),
            Place::Counter { n, field } => write!(f, "C{n}.{field} (private)"),
            Place::Sched { field, byte, .. } => write!(f, "Sched.{field} byte {byte}"),
            Place::PhysIn(n) => write!(f, "physical input byte {n}"),
            Place::PhysOut(n) => write!(f, "physical output byte {n}"),
            Place::Padding(o) => write!(f, "padding at {o:#x}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_every_block() {
        let l = Layout::of(ProfileId::A5);
        assert_eq!(Place::of(&l, l.addr(Area::V, 7, 0)).to_string(), "VB7");
        assert_eq!(
            Place::of(&l, l.addr(Area::L, 3, 2)).to_string(),
            "LB3 (frame 2)"
        );
        assert_eq!(
            Place::of(&l, l.timer_state(37) + TimerState::RUN).to_string(),
            "T37.RUN (private)"
        );
        assert_eq!(
            Place::of(&l, l.sched(Sched::LOOP_COUNT) + 1).to_string(),
            "Sched.LOOP_COUNT byte 1"
        );
        assert_eq!(Place::of(&l, l.edges + 3), Place::Edge(3));
        assert_eq!(Place::of(&l, l.phys_out + 2), Place::PhysOut(2));
        assert_eq!(
            Place::of(&l, l.sched(Sched::FATAL)).sched_field(),
            Some((Sched::FATAL, 2))
        );
    }
}
