//! CPU profiles: the data that differs between PLC models.
//!
//! A profile is a plain value; nothing else in the code branches on the model. The front end reads
//! area sizes and the timer table from here, the layout sizes the image from here, the runtime reads
//! the timer resolution that the front end stored in the IR.

use crate::area::Area;
use crate::ir::TimerKind;
use std::fmt;

/// Which built-in profile a program was compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ProfileId {
    /// The A5 series PLC (default).
    A5,
    /// A classic Siemens S7-200 CPU 226.
    S7_200,
}

impl ProfileId {
    /// Every profile, for `--cpu` help texts.
    pub const ALL: [ProfileId; 2] = [ProfileId::A5, ProfileId::S7_200];

    /// The name used on the command line (`a5`, `s7-200`).
    pub fn name(self) -> &'static str {
        match self {
            ProfileId::A5 => "a5",
            ProfileId::S7_200 => "s7-200",
        }
    }

    /// Parses a command-line name.
    pub fn from_name(name: &str) -> Option<ProfileId> {
        ProfileId::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(name))
    }

    /// The profile's data.
    pub fn profile(self) -> &'static CpuProfile {
        match self {
            ProfileId::A5 => &A5,
            ProfileId::S7_200 => &S7_200,
        }
    }
}

impl fmt::Display for ProfileId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Timer resolution in milliseconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Resolution {
    /// 1 ms, refreshed at scan start.
    Ms1,
    /// 10 ms, refreshed at scan start.
    Ms10,
    /// 100 ms, refreshed when the timer instruction executes.
    Ms100,
}

impl Resolution {
    /// The resolution in ms.
    pub fn millis(self) -> u32 {
        match self {
            Resolution::Ms1 => 1,
            Resolution::Ms10 => 10,
            Resolution::Ms100 => 100,
        }
    }

    /// Inverse of [`Resolution::millis`].
    pub fn from_millis(ms: u32) -> Option<Resolution> {
        match ms {
            1 => Some(Resolution::Ms1),
            10 => Some(Resolution::Ms10),
            100 => Some(Resolution::Ms100),
            _ => None,
        }
    }
}

/// A run of timer numbers sharing a resolution, for the timer kinds listed.
#[derive(Clone, Copy, Debug)]
pub struct TimerRange {
    /// First timer number of the run.
    pub first: u16,
    /// Last timer number of the run (inclusive).
    pub last: u16,
    /// Kinds allowed on these numbers.
    pub kinds: &'static [TimerKind],
    /// Resolution of these timers.
    pub resolution: Resolution,
}

/// Everything that differs between PLC models. Sizes are in bytes unless stated.
#[derive(Debug)]
pub struct CpuProfile {
    /// The profile's identity.
    pub id: ProfileId,
    /// Human-readable model name for messages.
    pub model: &'static str,
    /// Input image bytes (`I0.0`–`I{n-1}.7`).
    pub inputs: u32,
    /// Output image bytes.
    pub outputs: u32,
    /// `M` bytes.
    pub bit_memory: u32,
    /// `S` bytes.
    pub sequence_relays: u32,
    /// `SM` bytes.
    pub special_memory: u32,
    /// `SMB0` up to (excluding) this byte is read-only for the program.
    pub special_memory_read_only: u32,
    /// `V` bytes.
    pub variable_memory: u32,
    /// `L` bytes per POU frame.
    pub local_frame: u32,
    /// `AI` bytes (`AIW0` … `AIW{n-2}`, even offsets).
    pub analog_inputs: u32,
    /// `AQ` bytes.
    pub analog_outputs: u32,
    /// Number of timers (`T0` … `T{n-1}`).
    pub timers: u16,
    /// Number of counters.
    pub counters: u16,
    /// Number of high-speed counters (`HC0` …).
    pub high_speed_counters: u16,
    /// Number of accumulators (`AC0` …).
    pub accumulators: u16,
    /// Maximum number of EU/ED instructions in a program.
    pub max_edges: u16,
    /// Labels and subroutine numbers run from 0 to this value.
    pub max_label: u16,
    /// Highest subroutine number.
    pub max_subroutine: u16,
    /// Maximum CALL nesting below the main program.
    pub max_call_depth: u8,
    /// Maximum FOR/NEXT nesting.
    pub max_for_depth: u8,
    /// Timer number → resolution table, per timer kind.
    pub timer_table: &'static [TimerRange],
}

const ALL_TIMER_KINDS: &[TimerKind] = &[TimerKind::On, TimerKind::Retentive, TimerKind::Off];
const TON_TOF: &[TimerKind] = &[TimerKind::On, TimerKind::Off];
const TONR: &[TimerKind] = &[TimerKind::Retentive];

/// The A5 series (spec §1.1): every timer may be any kind; the number alone fixes the resolution.
pub static A5: CpuProfile = CpuProfile {
    id: ProfileId::A5,
    model: "A5",
    inputs: 16,
    outputs: 16,
    bit_memory: 32,
    sequence_relays: 16,
    special_memory: 180,
    special_memory_read_only: 30,
    variable_memory: 2500,
    local_frame: 64,
    analog_inputs: 32,
    analog_outputs: 32,
    timers: 64,
    counters: 32,
    high_speed_counters: 2,
    accumulators: 4,
    max_edges: 256,
    max_label: 255,
    max_subroutine: 255,
    max_call_depth: 8,
    max_for_depth: 8,
    timer_table: &[
        TimerRange {
            first: 0,
            last: 1,
            kinds: ALL_TIMER_KINDS,
            resolution: Resolution::Ms1,
        },
        TimerRange {
            first: 2,
            last: 19,
            kinds: ALL_TIMER_KINDS,
            resolution: Resolution::Ms10,
        },
        TimerRange {
            first: 20,
            last: 63,
            kinds: ALL_TIMER_KINDS,
            resolution: Resolution::Ms100,
        },
    ],
};

/// A classic S7-200 CPU 226: the number fixes both the kind family and the resolution.
pub static S7_200: CpuProfile = CpuProfile {
    id: ProfileId::S7_200,
    model: "S7-200 CPU 226",
    inputs: 16,
    outputs: 16,
    bit_memory: 32,
    sequence_relays: 32,
    special_memory: 550,
    special_memory_read_only: 30,
    variable_memory: 10240,
    local_frame: 64,
    analog_inputs: 64,
    analog_outputs: 64,
    timers: 256,
    counters: 256,
    high_speed_counters: 6,
    accumulators: 4,
    max_edges: 256,
    max_label: 255,
    max_subroutine: 63,
    max_call_depth: 8,
    max_for_depth: 8,
    timer_table: &[
        TimerRange {
            first: 0,
            last: 0,
            kinds: TONR,
            resolution: Resolution::Ms1,
        },
        TimerRange {
            first: 1,
            last: 4,
            kinds: TONR,
            resolution: Resolution::Ms10,
        },
        TimerRange {
            first: 5,
            last: 31,
            kinds: TONR,
            resolution: Resolution::Ms100,
        },
        TimerRange {
            first: 32,
            last: 32,
            kinds: TON_TOF,
            resolution: Resolution::Ms1,
        },
        TimerRange {
            first: 33,
            last: 36,
            kinds: TON_TOF,
            resolution: Resolution::Ms10,
        },
        TimerRange {
            first: 37,
            last: 63,
            kinds: TON_TOF,
            resolution: Resolution::Ms100,
        },
        TimerRange {
            first: 64,
            last: 64,
            kinds: TONR,
            resolution: Resolution::Ms1,
        },
        TimerRange {
            first: 65,
            last: 68,
            kinds: TONR,
            resolution: Resolution::Ms10,
        },
        TimerRange {
            first: 69,
            last: 95,
            kinds: TONR,
            resolution: Resolution::Ms100,
        },
        TimerRange {
            first: 96,
            last: 96,
            kinds: TON_TOF,
            resolution: Resolution::Ms1,
        },
        TimerRange {
            first: 97,
            last: 100,
            kinds: TON_TOF,
            resolution: Resolution::Ms10,
        },
        TimerRange {
            first: 101,
            last: 255,
            kinds: TON_TOF,
            resolution: Resolution::Ms100,
        },
    ],
};

impl CpuProfile {
    /// Size in bytes of a byte-addressable area, or the element count times element size for
    /// the timer, counter, HC and accumulator areas. `L` is one frame.
    pub fn area_size(&self, area: Area) -> u32 {
        match area {
            Area::I => self.inputs,
            Area::Q => self.outputs,
            Area::M => self.bit_memory,
            Area::S => self.sequence_relays,
            Area::SM => self.special_memory,
            Area::V => self.variable_memory,
            Area::L => self.local_frame,
            Area::AI => self.analog_inputs,
            Area::AQ => self.analog_outputs,
            Area::TimerValue => 2 * u32::from(self.timers),
            Area::CounterValue => 2 * u32::from(self.counters),
            Area::TimerBit => u32::from(self.timers),
            Area::CounterBit => u32::from(self.counters),
            Area::HC => 4 * u32::from(self.high_speed_counters),
            Area::AC => 4 * u32::from(self.accumulators),
        }
    }

    /// The resolution of timer `n` when used as `kind`, or `None` when the number does not exist
    /// or does not allow that kind on this model.
    pub fn timer_resolution(&self, n: u16, kind: TimerKind) -> Option<Resolution> {
        self.timer_table
            .iter()
            .find(|r| (r.first..=r.last).contains(&n) && r.kinds.contains(&kind))
            .map(|r| r.resolution)
    }

    /// Timer kinds allowed on number `n` (empty when the number does not exist).
    pub fn timer_kinds(&self, n: u16) -> &'static [TimerKind] {
        self.timer_table
            .iter()
            .find(|r| (r.first..=r.last).contains(&n))
            .map_or(&[], |r| r.kinds)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a5_resolution_depends_on_number_only() {
        let p = ProfileId::A5.profile();
        for kind in [TimerKind::On, TimerKind::Off, TimerKind::Retentive] {
            assert_eq!(p.timer_resolution(1, kind), Some(Resolution::Ms1));
            assert_eq!(p.timer_resolution(2, kind), Some(Resolution::Ms10));
            assert_eq!(p.timer_resolution(19, kind), Some(Resolution::Ms10));
            assert_eq!(p.timer_resolution(37, kind), Some(Resolution::Ms100));
            assert_eq!(p.timer_resolution(64, kind), None);
        }
    }

    #[test]
    fn s7_200_table_fixes_kind_family() {
        let p = ProfileId::S7_200.profile();
        assert_eq!(
            p.timer_resolution(37, TimerKind::On),
            Some(Resolution::Ms100)
        );
        assert_eq!(p.timer_resolution(37, TimerKind::Retentive), None);
        assert_eq!(
            p.timer_resolution(0, TimerKind::Retentive),
            Some(Resolution::Ms1)
        );
        assert_eq!(
            p.timer_resolution(97, TimerKind::Off),
            Some(Resolution::Ms10)
        );
        assert_eq!(
            p.timer_resolution(255, TimerKind::On),
            Some(Resolution::Ms100)
        );
        for n in 0..256 {
            assert!(!p.timer_kinds(n).is_empty(), "T{n} has no kind");
        }
    }

    #[test]
    fn profile_names_round_trip() {
        for id in ProfileId::ALL {
            assert_eq!(ProfileId::from_name(id.name()), Some(id));
        }
    }
}
