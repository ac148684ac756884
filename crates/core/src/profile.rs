//! CPU profiles: the data that differs between PLC models.
//!
//! A profile is a plain value; nothing else in the code branches on the model. The front end reads
//! area sizes and the timer table from here, the layout sizes the image from here, the runtime reads
//! the timer resolution that the front end stored in the IR.

use crate::area::Area;
use crate::hsc::{self, HscProfile};
use crate::instr_set::InstrSet;
use crate::interrupt::{self, InterruptProfile};
use crate::ir::TimerKind;
use crate::layout::ISR_FRAME;
use crate::pulse::{self, PulseProfile};
use std::fmt;

/// Which built-in profile a program was compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ProfileId {
    /// The A5 series PLC (default).
    A5,
    /// A classic Siemens S7-200 CPU 226.
    S7_200,
    /// A Siemens S7-200 SMART (the largest standard CPU, ST60; s7-200-more.md §0.2).
    Smart,
    /// An Omron CP1H (and CP1L-M): the reference model of the Omron dialect.
    Cp1h,
    /// An Omron CP1E (its smaller ranges, spec omron-cp.md §1.1 / U9).
    Cp1e,
}

impl ProfileId {
    /// Every profile, for `--cpu` help texts.
    pub const ALL: [ProfileId; 5] = [
        ProfileId::A5,
        ProfileId::S7_200,
        ProfileId::Smart,
        ProfileId::Cp1h,
        ProfileId::Cp1e,
    ];

    /// The name used on the command line (`a5`, `s7-200`, `smart`, `cp1h`, `cp1e`).
    pub fn name(self) -> &'static str {
        match self {
            ProfileId::A5 => "a5",
            ProfileId::S7_200 => "s7-200",
            ProfileId::Smart => "smart",
            ProfileId::Cp1h => "cp1h",
            ProfileId::Cp1e => "cp1e",
        }
    }

    /// Parses a command-line name.
    pub fn from_name(name: &str) -> Option<ProfileId> {
        ProfileId::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(name))
    }

    /// The profile's data.
    #[inline]
    pub fn profile(self) -> &'static CpuProfile {
        match self {
            ProfileId::A5 => &A5,
            ProfileId::S7_200 => &S7_200,
            ProfileId::Smart => &SMART,
            ProfileId::Cp1h => &crate::omron::CP1H,
            ProfileId::Cp1e => &crate::omron::CP1E,
        }
    }
}

/// The PLC family a profile belongs to. The rules that differ between the families' execution
/// models (and not between models of one family) are methods here, so each is stated once.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    /// S7-200 / A5: SMB0 system bits, SCR gating, 1-ms and 10-ms timers refreshed at scan start.
    S7,
    /// Omron CP: condition flags cleared at every task start, A200.11 and the clock pulses,
    /// IL/ILC interlocks, timers updated only when they execute.
    Omron,
}

impl Family {
    /// What a closed power-flow gate does to timers, counters and edges: an inactive SCR segment
    /// (S7) or an active interlock (Omron).
    pub fn gate_policy(self) -> GatePolicy {
        match self {
            Family::S7 => GatePolicy::S7Scr,
            Family::Omron => GatePolicy::OmronInterlock,
        }
    }

    /// Whether the first scan only records edges (S7 spec TC7). Omron edge memories instead
    /// start at their instance's initial value (omron-cp.md §2.6) and detect from scan 0 on.
    pub fn first_scan_suppresses_edges(self) -> bool {
        self == Family::S7
    }

    /// Whether 1-ms and 10-ms timers are refreshed by the clock at scan start (S7 spec §5.2).
    /// Omron timers are updated only when their instruction executes (omron-cp.md §2.12).
    pub fn clock_refreshed_timers(self) -> bool {
        self == Family::S7
    }
}

/// What a closed gate does to the stateful instructions inside it (the rules themselves are in
/// `stljit_runtime::rules`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GatePolicy {
    /// S7 SCR segment not active (spec a5-stl.md §3.6): coils write 0, every timer, counter
    /// and edge detector runs with its inputs seen as 0 (TON resets, TONR holds, TOF is forced
    /// idle, counter inputs are 0, edge memories are updated with 0).
    S7Scr,
    /// Omron interlock active (omron-cp.md §2.7): OUT writes 0, an on-delay timer (TIM, here
    /// `TimerKind::On` and the Omron TIM family) resets, everything else is not executed:
    /// accumulating and off-delay timers, counters (value, bit and count-edge memories) and
    /// edge memories stay as they are, and an edge detector outputs 0.
    OmronInterlock,
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

/// The word areas of an Omron profile, in 16-bit words (all 0 on S7 profiles).
#[derive(Clone, Copy, Debug)]
pub struct OmronAreas {
    /// CIO words `0` … `cio - 1` (the input and output words among them are areas `I`/`Q`).
    pub cio: u32,
    /// First CIO input word; the profile's `inputs` bytes hold the input words from here.
    pub first_input_word: u32,
    /// First CIO output word; the profile's `outputs` bytes hold the output words from here.
    pub first_output_word: u32,
    /// `W` words.
    pub work: u32,
    /// `H` words.
    pub holding: u32,
    /// `A` words.
    pub aux: u32,
    /// `A0` up to (excluding) this word is read-only for the program.
    pub aux_read_only: u32,
    /// `D` words.
    pub dm: u32,
    /// Highest jump number (`JMP`/`CJP`/`JME`).
    pub max_jump: u16,
    /// Whether DM words are bit-addressable (`D10.03`; omron-cp.md §1.1, U9).
    pub dm_bits: bool,
    /// Cyclic tasks `0` … `cyclic_tasks - 1` (omron-cp.md §2.1).
    pub cyclic_tasks: u8,
    /// User-memory capacity in steps, all tasks together (seed §1-1-11, E035).
    pub program_steps: u32,
    /// Block programs `0` … `block_programs - 1` (`BPRG(096) N`).
    pub block_programs: u16,
}

impl OmronAreas {
    /// No Omron areas (the S7 profiles).
    pub const NONE: OmronAreas = OmronAreas {
        cio: 0,
        first_input_word: 0,
        first_output_word: 0,
        work: 0,
        holding: 0,
        aux: 0,
        aux_read_only: 0,
        dm: 0,
        max_jump: 0,
        dm_bits: false,
        cyclic_tasks: 0,
        program_steps: 0,
        block_programs: 0,
    };
}

/// Everything that differs between PLC models. Sizes are in bytes unless stated.
#[derive(Debug)]
pub struct CpuProfile {
    /// The profile's identity.
    pub id: ProfileId,
    /// The family, which fixes the execution model's rules ([`Family`]).
    pub family: Family,
    /// The Omron word areas ([`OmronAreas::NONE`] on S7 profiles).
    pub omron: OmronAreas,
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
    /// The optional instruction families the CPU does not have (s7-200-more Appendix A, its
    /// "rejected" entries; every family on Omron profiles, whose front end has its own table).
    pub lacks: &'static [InstrSet],
    /// Interrupt events, queues and the CALL depth of interrupt routines
    /// ([`InterruptProfile::NONE`] on Omron profiles).
    pub interrupts: &'static InterruptProfile,
    /// The high-speed counters with their inputs, modes and registers (s7-200-more §8.2;
    /// [`HscProfile::NONE`] on Omron profiles). The HC area has
    /// [`high_speed_counters`](Self::high_speed_counters) values whatever this table holds.
    pub hsc: &'static HscProfile,
    /// The pulse output channels with their outputs and registers (s7-200-more §9.1;
    /// [`PulseProfile::NONE`] where the CPU has none).
    pub pulse: &'static PulseProfile,
    /// The CPU's real-time clock (s7-200-more §6.2 `rtc_present`): without one,
    /// TODR/TODW/TODRX/TODWX fail at run time with 16#000C.
    pub clock: RealTimeClock,
}

/// The real-time clock of a CPU (s7-200-more §6): whether there is one, and the
/// daylight-saving modes its extended buffer (TODRX/TODWX) accepts in byte 8.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RealTimeClock {
    /// No clock: the clock instructions fail with 16#000C.
    Absent,
    /// The classic S7-200's: modes 00–03, 08, 10–13 and FF, a 19-byte extended buffer.
    Classic,
    /// The S7-200 SMART's: 12 is reserved; EE (a user rule by day of week) uses bytes 9–20, a
    /// 21-byte buffer.
    Smart,
}

impl RealTimeClock {
    /// The daylight-saving mode that makes the extended buffer 21 bytes long (SMART's EE).
    pub const DAY_OF_WEEK_RULE: u8 = 0xEE;

    /// Whether there is a clock.
    pub fn present(self) -> bool {
        self != RealTimeClock::Absent
    }

    /// The daylight-saving modes byte 8 of the extended buffer may hold.
    pub fn dst_modes(self) -> &'static [u8] {
        match self {
            RealTimeClock::Absent => &[],
            RealTimeClock::Classic => &[0x00, 0x01, 0x02, 0x03, 0x08, 0x10, 0x11, 0x12, 0x13, 0xFF],
            RealTimeClock::Smart => &[0x00, 0x01, 0x02, 0x03, 0x08, 0x10, 0x11, 0x13, 0xFF, 0xEE],
        }
    }

    /// The length of the extended buffer whose byte 8 is `mode`: 21 for SMART's EE, else 19.
    pub fn extended_len(self, mode: u8) -> u32 {
        if self == RealTimeClock::Smart && mode == Self::DAY_OF_WEEK_RULE {
            21
        } else {
            19
        }
    }
}

const ALL_TIMER_KINDS: &[TimerKind] = &[TimerKind::On, TimerKind::Retentive, TimerKind::Off];
const TON_TOF: &[TimerKind] = &[TimerKind::On, TimerKind::Off];
const TONR: &[TimerKind] = &[TimerKind::Retentive];

/// The A5 series (spec §1.1): every timer may be any kind; the number alone fixes the resolution.
pub static A5: CpuProfile = CpuProfile {
    id: ProfileId::A5,
    family: Family::S7,
    omron: OmronAreas::NONE,
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
    // No A5 document describes pulse outputs; Ethernet (GET/PUT, GIP/SIP) is the SMART's.
    lacks: &[
        InstrSet::PulseOutputs,
        InstrSet::GetPut,
        InstrSet::IpAddress,
    ],
    interrupts: &interrupt::A5_INTERRUPTS,
    hsc: &hsc::A5_COUNTERS,
    pulse: &PulseProfile::NONE,
    // "The seed does not mention a clock" (s7-200-more §6.2, Appendix A).
    clock: RealTimeClock::Absent,
};

/// The Siemens timer table (s7-200-more §3.5.3): the number fixes both the kind family and the
/// resolution; shared by the classic S7-200 and the S7-200 SMART.
const SIEMENS_TIMERS: &[TimerRange] = &[
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
];

/// A classic S7-200 CPU 226: the number fixes both the kind family and the resolution.
pub static S7_200: CpuProfile = CpuProfile {
    id: ProfileId::S7_200,
    family: Family::S7,
    omron: OmronAreas::NONE,
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
    timer_table: SIEMENS_TIMERS,
    lacks: &[InstrSet::GetPut, InstrSet::IpAddress],
    interrupts: &interrupt::S7_200_INTERRUPTS,
    hsc: &hsc::S7_200_COUNTERS,
    pulse: &pulse::S7_200_PULSE,
    clock: RealTimeClock::Classic,
};

/// A Siemens S7-200 SMART, sized as its largest standard CPU, the ST60 (s7-200-more §0.2; the
/// sizes are the SMART manual's, recalled: I/Q 256 bits each, V 20 kB, SM to SMB1535, AIW0 to
/// AIW110, HSC0–HSC5, SBR0–SBR127). A smaller CPU's program fits; the simulator does not check
/// the model's I/O count.
pub static SMART: CpuProfile = CpuProfile {
    id: ProfileId::Smart,
    family: Family::S7,
    omron: OmronAreas::NONE,
    model: "S7-200 SMART",
    inputs: 32,
    outputs: 32,
    bit_memory: 32,
    sequence_relays: 32,
    special_memory: 1536,
    special_memory_read_only: 30,
    variable_memory: 20480,
    local_frame: 64,
    analog_inputs: 112,
    analog_outputs: 112,
    timers: 256,
    counters: 256,
    high_speed_counters: 6,
    accumulators: 4,
    max_edges: 1024,
    max_label: 255,
    max_subroutine: 127,
    max_call_depth: 8,
    max_for_depth: 8,
    timer_table: SIEMENS_TIMERS,
    // Micro/WIN SMART rejects NETR/NETW (the corpus's instruction probe confirms it).
    lacks: &[InstrSet::NetReadWrite],
    interrupts: &interrupt::SMART_INTERRUPTS,
    hsc: &hsc::SMART_COUNTERS,
    pulse: &pulse::SMART_PULSE,
    clock: RealTimeClock::Smart,
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
            Area::Cio => 2 * self.omron.cio,
            Area::Work => 2 * self.omron.work,
            Area::Holding => 2 * self.omron.holding,
            Area::Aux => 2 * self.omron.aux,
            Area::Dm => 2 * self.omron.dm,
            Area::Flags => match self.family {
                Family::S7 => 0,
                Family::Omron => crate::omron::FLAG_BYTES,
            },
            Area::Tr => match self.family {
                Family::S7 => 0,
                Family::Omron => 2,
            },
            Area::IndexReg => match self.family {
                Family::S7 => 0,
                Family::Omron => 4 * 16,
            },
            Area::DataReg => match self.family {
                Family::S7 => 0,
                Family::Omron => 2 * 16,
            },
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

    /// Whether the CPU has the instruction family `set`.
    pub fn has(&self, set: InstrSet) -> bool {
        !self.lacks.contains(&set)
    }

    /// The bytes of a PID loop table that must fit in V (s7-200-more §7.1): 36, or 80 on the
    /// SMART, whose table has the auto-tuning area.
    pub fn pid_table_bytes(&self) -> u32 {
        if self.clock == RealTimeClock::Smart {
            80
        } else {
            36
        }
    }

    /// The deepest L frame a CALL made from frame `depth` may enter (the callee runs in frame
    /// `depth + 1`, allowed iff that is at most this): the main program's chain (frames 0 to
    /// [`ISR_FRAME`] − 1) nests `max_call_depth` levels, an interrupt routine runs in
    /// [`ISR_FRAME`] and its chain nests `interrupts.isr_call_depth` levels (s7-200-more §1.6).
    pub fn deepest_frame(&self, depth: u32) -> u32 {
        if depth >= ISR_FRAME {
            ISR_FRAME + u32::from(self.interrupts.isr_call_depth)
        } else {
            u32::from(self.max_call_depth)
        }
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
    fn smart_shares_the_siemens_timer_table_and_is_larger() {
        let (smart, s7) = (ProfileId::Smart.profile(), ProfileId::S7_200.profile());
        for n in 0..256 {
            assert_eq!(smart.timer_kinds(n), s7.timer_kinds(n), "T{n}");
        }
        assert_eq!(smart.area_size(Area::SM), 1536);
        assert_eq!(smart.area_size(Area::I), 32);
        assert!(smart.area_size(Area::V) > s7.area_size(Area::V));
    }

    /// Appendix A of s7-200-more.md: NETR/NETW only on the classic CPUs, GET/PUT only on the
    /// SMART, pulse outputs not on the A5.
    #[test]
    fn instruction_availability_follows_appendix_a() {
        use InstrSet::*;
        let has = |p: ProfileId, s| p.profile().has(s);
        assert!(has(ProfileId::A5, NetReadWrite) && has(ProfileId::S7_200, NetReadWrite));
        assert!(!has(ProfileId::Smart, NetReadWrite));
        assert!(has(ProfileId::Smart, GetPut));
        assert!(!has(ProfileId::A5, GetPut) && !has(ProfileId::S7_200, GetPut));
        assert!(!has(ProfileId::A5, PulseOutputs));
        assert!(has(ProfileId::S7_200, PulseOutputs) && has(ProfileId::Smart, PulseOutputs));
        for p in [ProfileId::A5, ProfileId::S7_200, ProfileId::Smart] {
            for s in [
                Interrupts,
                Tables,
                Ascii,
                Strings,
                Clock,
                Pid,
                HighSpeedCounters,
            ] {
                assert!(has(p, s), "{p} {s:?}");
            }
        }
        assert!(!ProfileId::Cp1h.profile().has(Interrupts));
    }

    #[test]
    fn profile_names_round_trip() {
        for id in ProfileId::ALL {
            assert_eq!(ProfileId::from_name(id.name()), Some(id));
        }
    }
}
