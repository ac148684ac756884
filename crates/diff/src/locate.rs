//! Names for image offsets: the PLC areas, and the private blocks (edge memories, timer and
//! counter state, the scan bookkeeping, the physical I/O copies, the interrupt state and
//! queues, the clock and PID state) by field, so that a divergence
//! report says `Sched.LOOP_COUNT` or `T37.RUN` instead of a bare number. Which block and field a
//! byte belongs to comes from core's layout ([`Layout::region`]); this module only spells it.

use std::fmt;
use stljit_core::ir::{Address, Loc};
use stljit_core::layout::{Block, L_FRAMES, Layout, Region};
use stljit_core::{Area, Width};
use stljit_front_s7::spelling::area_prefix;

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
    /// A field of the interrupt machinery's state, and the byte inside it.
    Interrupts {
        /// Field name.
        field: &'static str,
        /// Byte inside the field.
        byte: u32,
    },
    /// A field of an interrupt queue entry.
    Queue {
        /// The queue slot.
        slot: u32,
        /// Field name.
        field: &'static str,
        /// Byte inside the field.
        byte: u32,
    },
    /// The physical input copy.
    PhysIn(u32),
    /// The physical output copy.
    PhysOut(u32),
    /// A field of the clock and PID state, and the byte inside it.
    Instr {
        /// Field name.
        field: &'static str,
        /// Byte inside the field.
        byte: u32,
    },
    /// A field of serial port `n`'s state or of network job slot `n`, and the byte inside it.
    Comm {
        /// Port or job slot number.
        n: u32,
        /// Field name.
        field: &'static str,
        /// Byte inside the field.
        byte: u32,
    },
    /// A field of high-speed counter `n`'s state, and the byte inside it.
    Hsc {
        /// Counter number.
        n: u32,
        /// Field name.
        field: &'static str,
        /// Byte inside the field.
        byte: u32,
    },
    /// A field of pulse output channel `n`'s state, and the byte inside it.
    Pulse {
        /// Channel number.
        n: u32,
        /// Field name.
        field: &'static str,
        /// Byte inside the field.
        byte: u32,
    },
    /// Alignment padding.
    Padding(u32),
}

impl Place {
    /// Names image offset `off` of `layout`, from the blocks and record fields the layout
    /// declares ([`Layout::region`], [`Block::field_at`]).
    pub fn of(layout: &Layout, off: u32) -> Place {
        let (block, offset) = match layout.region(off) {
            Region::Area { area, offset } => {
                return Place::Area {
                    area,
                    offset,
                    frame_size: layout.area_size(Area::L),
                };
            }
            Region::Block { block, offset } => (block, offset),
            Region::Padding => return Place::Padding(off),
        };
        match (block, block.field_at(offset)) {
            (Block::Edges, _) => Place::Edge(offset),
            (Block::TimerState, Some(at)) => Place::Timer {
                n: at.record,
                field: at.name.unwrap_or("(pad)"),
            },
            (Block::CounterState, Some(at)) => Place::Counter {
                n: at.record,
                field: at.name.unwrap_or("(pad)"),
            },
            (Block::Sched, Some(at)) => Place::Sched {
                field: at.name.unwrap_or("(unused)"),
                at: at.start,
                byte: at.byte,
            },
            (Block::Interrupts, Some(at)) => Place::Interrupts {
                field: at.name.unwrap_or("(unused)"),
                byte: at.byte,
            },
            (Block::Queue, Some(at)) => Place::Queue {
                slot: at.record,
                field: at.name.unwrap_or("(pad)"),
                byte: at.byte,
            },
            (Block::PhysIn, _) => Place::PhysIn(offset),
            (Block::PhysOut, _) => Place::PhysOut(offset),
            (Block::Instr, Some(at)) => Place::Instr {
                field: at.name.unwrap_or("(unused)"),
                byte: at.byte,
            },
            (Block::Hsc, Some(at)) => Place::Hsc {
                n: at.record,
                field: at.name.unwrap_or("(pad)"),
                byte: at.byte,
            },
            (Block::Pulse, Some(at)) => Place::Pulse {
                n: at.record,
                field: at.name.unwrap_or("(pad)"),
                byte: at.byte,
            },
            (Block::Ports | Block::NetJobs, Some(at)) => Place::Comm {
                n: at.record,
                field: at.name.unwrap_or("(pad)"),
                byte: at.byte,
            },
            // Record blocks always name their bytes; a block without fields is matched above.
            (
                Block::Hsc
                | Block::Pulse
                | Block::Ports
                | Block::NetJobs
                | Block::TimerState
                | Block::CounterState
                | Block::Sched
                | Block::Interrupts
                | Block::Queue
                | Block::Instr,
                None,
            ) => Place::Padding(off),
        }
    }

    /// For a scan bookkeeping field: its offset in the block and size, to show whole values.
    pub fn sched_field(&self) -> Option<(u32, u32)> {
        match *self {
            Place::Sched { at, .. } => Block::Sched.field_at(at).map(|f| (f.start, f.size)),
            _ => None,
        }
    }
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
                Area::AI | Area::AQ => write!(
                    f,
                    "{}W{} byte {}",
                    area_prefix(area),
                    offset & !1,
                    offset & 1
                ),
                Area::TimerValue => write!(f, "T{} value byte {}", offset / 2, offset % 2),
                Area::CounterValue => write!(f, "C{} value byte {}", offset / 2, offset % 2),
                Area::TimerBit => write!(f, "T{} bit", offset),
                Area::CounterBit => write!(f, "C{} bit", offset),
                Area::HC => write!(f, "HC{} byte {}", offset / 4, offset % 4),
                // The Omron word areas: the word as Omron spells it, and which half.
                Area::Cio | Area::Work | Area::Holding | Area::Aux | Area::Dm => {
                    let word = stljit_front_omron::print_address(&Address::Value {
                        loc: Loc {
                            area,
                            offset: offset & !1,
                        },
                        width: Width::Word,
                    });
                    let half = if offset % 2 == 0 { "15-08" } else { "07-00" };
                    write!(f, "{word} bits {half}")
                }
                Area::Flags => write!(f, "Omron flags byte {offset} (P_ER=0.0 … P_AER=1.3)"),
                Area::DataReg => write!(f, "DR{} byte {}", offset / 2, offset % 2),
                Area::IndexReg => write!(f, "IR{} byte {}", offset / 4, offset % 4),
                Area::AC => write!(f, "AC{} byte {}", offset / 4, offset % 4),
                _ => write!(f, "{}B{offset}", area_prefix(area)),
            },
            Place::Edge(n) => write!(f, "edge memory {n}"),
            Place::Timer { n, field } => write!(f, "T{n}.{field} (private)"),
            Place::Counter { n, field } => write!(f, "C{n}.{field} (private)"),
            Place::Sched { field, byte, .. } => write!(f, "Sched.{field} byte {byte}"),
            Place::Interrupts { field, byte } => write!(f, "Interrupts.{field} byte {byte}"),
            Place::Queue { slot, field, byte } => {
                write!(f, "interrupt queue slot {slot}.{field} byte {byte}")
            }
            Place::PhysIn(n) => write!(f, "physical input byte {n}"),
            Place::PhysOut(n) => write!(f, "physical output byte {n}"),
            Place::Instr { field, byte } => write!(f, "InstrState.{field} byte {byte}"),
            Place::Hsc { n, field, byte } => write!(f, "HSC{n} HscState.{field} byte {byte}"),
            Place::Pulse { n, field, byte } => {
                write!(f, "PLS{n} PulseState.{field} byte {byte}")
            }
            Place::Comm { n, field, byte } => write!(f, "port/job {n} {field} byte {byte}"),
            Place::Padding(o) => write!(f, "padding at {o:#x}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ProfileId;
    use stljit_core::layout::{Sched, TimerState};

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
        let o = Layout::of(ProfileId::Cp1h);
        assert_eq!(
            Place::of(&o, o.addr(Area::Work, 3, 0)).to_string(),
            "W1 bits 07-00"
        );
        assert_eq!(
            Place::of(&o, o.addr(Area::Dm, 20, 0)).to_string(),
            "D10 bits 15-08"
        );
        assert_eq!(Place::of(&l, l.phys_out + 2), Place::PhysOut(2));
        assert_eq!(
            Place::of(&l, l.sched(Sched::FATAL)).sched_field(),
            Some((Sched::FATAL, 2))
        );
    }
}
