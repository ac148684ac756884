//! Interrupt events as data (s7-200-more.md §3.1–§3.5): every event number with its queue
//! group, its priority inside the group and its source, and what a CPU profile offers
//! ([`InterruptProfile`]: its events, queue depths, the CALL depth below an interrupt routine).
//!
//! Nothing here runs: the event machinery (queues, attachments, schedules, the service loop)
//! is `stljit_runtime::interrupt`, which reads these tables, and the S7 front end checks event
//! numbers against [`InterruptProfile::has`].

use crate::hsc::HscEvent;

/// The three interrupt queues, highest priority first (§3.3: communication > discrete >
/// timed). The discriminant is the group's index in [`EventGroup::ALL`] and the bit of its
/// overflow flag in SMB4 (SM4.0–SM4.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum EventGroup {
    /// Serial communication: receive character, transmit complete, message complete.
    Communication = 0,
    /// Discrete I/O: input edges, pulse outputs, high-speed counters.
    Discrete = 1,
    /// Time based: timed interrupts 0/1 and the T32/T96 timer interrupts.
    Timed = 2,
}

impl EventGroup {
    /// Every group, in priority order.
    pub const ALL: [EventGroup; 3] = [
        EventGroup::Communication,
        EventGroup::Discrete,
        EventGroup::Timed,
    ];

    /// The group's index (its position in [`EventGroup::ALL`] and its SMB4 overflow bit).
    #[inline]
    pub fn index(self) -> usize {
        self as usize
    }

    /// A name for messages.
    pub fn name(self) -> &'static str {
        match self {
            EventGroup::Communication => "communication",
            EventGroup::Discrete => "discrete",
            EventGroup::Timed => "timed",
        }
    }
}

/// Where an event comes from; says which part of the simulation raises it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EventSource {
    /// An edge of a physical input bit, seen at a scan instant (§3.5.2).
    InputEdge {
        /// The input byte (`I0.3` is byte 0).
        byte: u32,
        /// The bit in it.
        bit: u8,
        /// A 0→1 edge (else 1→0).
        rising: bool,
    },
    /// Timed interrupt `channel` (0 or 1), its interval in ms captured from SMB
    /// [`TIMED_INTERVAL_SMB`]`[channel]` when the event is attached (§3.5.1).
    Timed {
        /// 0 or 1.
        channel: u8,
    },
    /// A 1-ms timer reaching its preset, `CT = PT` (§3.5.3).
    TimerReached {
        /// The timer number (T32, T96).
        timer: u16,
    },
    /// A high-speed counter (§8.5).
    HighSpeedCounter {
        /// The counter's number.
        counter: u8,
        /// Which of its events.
        kind: HscEvent,
    },
    /// A pulse output's PTO completing (§9.3).
    PulseOutput {
        /// The channel number (`PLS Q`).
        channel: u8,
    },
    /// A serial port (§10).
    Communication,
}

/// One interrupt event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EventInfo {
    /// The event number (the `EVNT` operand of ATCH/DTCH/CEVNT).
    pub number: u8,
    /// Its queue.
    pub group: EventGroup,
    /// Its priority inside the group (0 = highest).
    pub pri: u8,
    /// Where it comes from.
    pub source: EventSource,
    /// What it is, for messages.
    pub what: &'static str,
}

/// The SMB bytes holding the intervals of timed interrupts 0 and 1 (SMB34, SMB35).
pub const TIMED_INTERVAL_SMB: [u32; 2] = [34, 35];

/// The highest interrupt routine number (INT0–INT127 on every S7 CPU, §0.2).
pub const MAX_ROUTINE: u16 = 127;

/// Attachment slots: events 0 … `EVENT_SLOTS - 1` (the image's attach table, one byte each).
pub const EVENT_SLOTS: usize = 64;

const fn ev(
    number: u8,
    group: EventGroup,
    pri: u8,
    source: EventSource,
    what: &'static str,
) -> EventInfo {
    EventInfo {
        number,
        group,
        pri,
        source,
        what,
    }
}

const fn edge(number: u8, pri: u8, bit: u8, rising: bool, what: &'static str) -> EventInfo {
    ev(
        number,
        EventGroup::Discrete,
        pri,
        EventSource::InputEdge {
            byte: if bit < 8 { 0 } else { 7 },
            bit: bit % 8,
            rising,
        },
        what,
    )
}

/// Timed interrupt `channel`: the timed group, its priority the channel.
const fn timed(number: u8, channel: u8, what: &'static str) -> EventInfo {
    ev(
        number,
        EventGroup::Timed,
        channel,
        EventSource::Timed { channel },
        what,
    )
}

/// A timer reaching its preset: the timed group after the timed interrupts.
const fn timer(number: u8, pri: u8, timer: u16, what: &'static str) -> EventInfo {
    ev(
        number,
        EventGroup::Timed,
        pri,
        EventSource::TimerReached { timer },
        what,
    )
}

/// An event of high-speed counter `counter`: the discrete group.
const fn hsc(number: u8, pri: u8, counter: u8, kind: HscEvent, what: &'static str) -> EventInfo {
    ev(
        number,
        EventGroup::Discrete,
        pri,
        EventSource::HighSpeedCounter { counter, kind },
        what,
    )
}

use EventGroup::{Communication as COMM, Discrete as IO};
use EventSource::Communication as PORT;
use EventSource::PulseOutput as PLS;
use HscEvent::{CvEqPv as CV, Direction as DIR, Reset as RST};

/// Every event of every S7 profile, entry `n` for event `n`: the S7-200 table 6-50 (§3.1) and
/// the S7-200 SMART additions 34–38 (§3.2, in the discrete group after the S7-200's entries,
/// ascending). Which of them a CPU has is its [`InterruptProfile::events`]. The SMART's
/// signal-board inputs I7.0/I7.1 are bits 8 and 9 of [`edge`]'s numbering (byte 7).
pub const EVENTS: &[EventInfo] = &[
    edge(0, 2, 0, true, "I0.0 rising edge"),
    edge(1, 6, 0, false, "I0.0 falling edge"),
    edge(2, 3, 1, true, "I0.1 rising edge"),
    edge(3, 7, 1, false, "I0.1 falling edge"),
    edge(4, 4, 2, true, "I0.2 rising edge"),
    edge(5, 8, 2, false, "I0.2 falling edge"),
    edge(6, 5, 3, true, "I0.3 rising edge"),
    edge(7, 9, 3, false, "I0.3 falling edge"),
    ev(8, COMM, 0, PORT, "port 0 receive character"),
    ev(9, COMM, 0, PORT, "port 0 transmit complete"),
    timed(10, 0, "timed interrupt 0 (SMB34)"),
    timed(11, 1, "timed interrupt 1 (SMB35)"),
    hsc(12, 10, 0, CV, "HSC0 CV = PV"),
    hsc(13, 13, 1, CV, "HSC1 CV = PV"),
    hsc(14, 14, 1, DIR, "HSC1 direction changed"),
    hsc(15, 15, 1, RST, "HSC1 external reset"),
    hsc(16, 16, 2, CV, "HSC2 CV = PV"),
    hsc(17, 17, 2, DIR, "HSC2 direction changed"),
    hsc(18, 18, 2, RST, "HSC2 external reset"),
    ev(
        19,
        IO,
        0,
        PLS { channel: 0 },
        "PLS0 (Q0.0) pulse count complete",
    ),
    ev(
        20,
        IO,
        1,
        PLS { channel: 1 },
        "PLS1 (Q0.1) pulse count complete",
    ),
    timer(21, 2, 32, "timer T32 CT = PT"),
    timer(22, 3, 96, "timer T96 CT = PT"),
    ev(23, COMM, 0, PORT, "port 0 receive message complete"),
    ev(24, COMM, 1, PORT, "port 1 receive message complete"),
    ev(25, COMM, 1, PORT, "port 1 receive character"),
    ev(26, COMM, 1, PORT, "port 1 transmit complete"),
    hsc(27, 11, 0, DIR, "HSC0 direction changed"),
    hsc(28, 12, 0, RST, "HSC0 external reset"),
    hsc(29, 20, 4, CV, "HSC4 CV = PV"),
    hsc(30, 21, 4, DIR, "HSC4 direction changed"),
    hsc(31, 22, 4, RST, "HSC4 external reset"),
    hsc(32, 19, 3, CV, "HSC3 CV = PV"),
    hsc(33, 23, 5, CV, "HSC5 CV = PV"),
    ev(
        34,
        IO,
        24,
        PLS { channel: 2 },
        "PLS2 (Q0.3) pulse count complete",
    ),
    edge(35, 25, 8, true, "I7.0 rising edge"),
    edge(36, 26, 8, false, "I7.0 falling edge"),
    edge(37, 27, 9, true, "I7.1 rising edge"),
    edge(38, 28, 9, false, "I7.1 falling edge"),
];

/// The event with number `n`, whatever the profile.
#[inline]
pub fn event(n: u8) -> Option<&'static EventInfo> {
    EVENTS.get(usize::from(n)).filter(|e| e.number == n)
}

/// The event `kind` of high-speed counter `counter` (none: the counter has no such event,
/// §8.5), whatever the profile.
pub fn hsc_event(counter: u8, kind: HscEvent) -> Option<u8> {
    EVENTS
        .iter()
        .find(|e| e.source == EventSource::HighSpeedCounter { counter, kind })
        .map(|e| e.number)
}

/// The PTO-complete event of pulse channel `channel` (§9.3), whatever the profile.
pub fn pulse_event(channel: u8) -> Option<u8> {
    EVENTS
        .iter()
        .find(|e| e.source == EventSource::PulseOutput { channel })
        .map(|e| e.number)
}

/// The event timed interrupt `channel` raises, read off [`EVENTS`] at compile time.
const fn timed_event(channel: u8) -> u8 {
    let mut i = 0;
    while i < EVENTS.len() {
        if let EventSource::Timed { channel: c } = EVENTS[i].source
            && c == channel
        {
            return EVENTS[i].number;
        }
        i += 1;
    }
    panic!("no timed interrupt event for the channel")
}

/// The events of timed interrupts 0 and 1 (10, 11).
pub const TIMED_EVENTS: [u8; 2] = [timed_event(0), timed_event(1)];

/// The positions of the bits set in `bits`, ascending (the walk over a bit set: [`EventSet`],
/// and the runtime's happening sources).
pub fn set_bits(bits: u64) -> impl Iterator<Item = u8> {
    let mut rest = bits;
    std::iter::from_fn(move || {
        let n = rest.trailing_zeros();
        (rest != 0).then(|| {
            rest &= rest - 1;
            n as u8
        })
    })
}

/// A set of event numbers: bit `n` for event `n` (every number is below [`EVENT_SLOTS`], 64).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EventSet(pub u64);

impl EventSet {
    /// The numbers in the set, ascending.
    pub fn numbers(self) -> impl Iterator<Item = u8> {
        set_bits(self.0)
    }
}

/// The events of [`EVENTS`] whose source is an input edge (`by_edge`) or a timer reaching its
/// preset (otherwise), read off the table at compile time.
const fn events_of_source(by_edge: bool) -> EventSet {
    let mut set = 0u64;
    let mut i = 0;
    while i < EVENTS.len() {
        let hit = match EVENTS[i].source {
            EventSource::InputEdge { .. } => by_edge,
            EventSource::TimerReached { .. } => !by_edge,
            _ => false,
        };
        if hit {
            set |= 1 << EVENTS[i].number;
        }
        i += 1;
    }
    EventSet(set)
}

/// The input-edge events (§3.5.2), whatever the profile.
pub const INPUT_EDGE_EVENTS: EventSet = events_of_source(true);

/// The timer events T32/T96 `CT = PT` (§3.5.3), whatever the profile.
pub const TIMER_REACHED_EVENTS: EventSet = events_of_source(false);

/// What a CPU offers for interrupts.
#[derive(Debug)]
pub struct InterruptProfile {
    /// The event numbers the CPU has, ascending (empty: no interrupts at all).
    pub events: &'static [u8],
    /// Entries each queue holds, by [`EventGroup::index`] (§3.3).
    pub queue_depth: [u8; 3],
    /// CALL nesting levels an interrupt routine may use (§1.6).
    pub isr_call_depth: u8,
    /// `events` as a set, for the runtime's per-scan walks over one kind of event.
    set: EventSet,
}

impl InterruptProfile {
    /// No interrupts (the Omron profiles).
    pub const NONE: InterruptProfile = InterruptProfile::new(&[], [0; 3], 0);

    /// A CPU with `events` (ascending, each below [`EVENT_SLOTS`]), `queue_depth` entries per
    /// queue and `isr_call_depth` CALL levels below a routine.
    pub const fn new(events: &'static [u8], queue_depth: [u8; 3], isr_call_depth: u8) -> Self {
        let mut set = 0u64;
        let mut i = 0;
        while i < events.len() {
            set |= 1 << events[i];
            i += 1;
        }
        InterruptProfile {
            events,
            queue_depth,
            isr_call_depth,
            set: EventSet(set),
        }
    }

    /// The CPU's events in `of` (a set of [`EVENTS`] by source, such as
    /// [`INPUT_EDGE_EVENTS`]), ascending: a walk over those alone, not over the whole table.
    pub fn infos_in(&self, of: EventSet) -> impl Iterator<Item = &'static EventInfo> + use<> {
        EventSet(self.set.0 & of.0).numbers().filter_map(event)
    }

    /// Whether the CPU has any of the events in `of`.
    #[inline]
    pub fn has_any(&self, of: EventSet) -> bool {
        self.set.0 & of.0 != 0
    }

    /// Whether the CPU has event `n`.
    pub fn has(&self, n: u8) -> bool {
        self.events.contains(&n)
    }

    /// Whether the CPU has interrupts at all.
    pub fn any(&self) -> bool {
        !self.events.is_empty()
    }

    /// The CPU's events with their data, ascending.
    pub fn infos(&self) -> impl Iterator<Item = &'static EventInfo> + '_ {
        self.events.iter().filter_map(|&n| event(n))
    }

    /// Queue slots in all: the image holds one entry per slot.
    pub fn slots(&self) -> u32 {
        self.queue_depth.iter().map(|&d| u32::from(d)).sum()
    }

    /// The first slot of `group`'s queue and its depth.
    #[inline]
    pub fn queue(&self, group: EventGroup) -> (u32, u32) {
        let g = group.index();
        let first = self.queue_depth[..g].iter().map(|&d| u32::from(d)).sum();
        (first, u32::from(self.queue_depth[g]))
    }
}

/// The A5 (Appendix A, `a5` profile default [design]): events 0–15, 23, 25–28; no T32/T96
/// events (its timer table differs). Queue depths as the S7-200 CPU 221–224 [design: the seed
/// is silent]; one CALL level from a routine, as the classic S7-200.
pub static A5_INTERRUPTS: InterruptProfile = InterruptProfile::new(
    &[
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 23, 25, 26, 27, 28,
    ],
    [4, 16, 8],
    1,
);

/// The S7-200 CPU 226: events 0–33, a communication queue of 8 (§3.3 [S7-200 help]), one CALL
/// level from a routine [S7-200 manual].
pub static S7_200_INTERRUPTS: InterruptProfile = InterruptProfile::new(
    &[
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24,
        25, 26, 27, 28, 29, 30, 31, 32, 33,
    ],
    [8, 16, 8],
    1,
);

/// The S7-200 SMART (§3.2 [SMART manual, recalled; uncertain I1]): events 0–13 and 16–38
/// (14, 15 reserved; 29–33 for HSC3–HSC5, which the profile has; 34 PLS2; 35–38 the signal
/// board's I7.0/I7.1 edges), the queue depths of all SMART CPUs, four CALL levels from a
/// routine [SMART manual 7.10.3].
pub static SMART_INTERRUPTS: InterruptProfile = InterruptProfile::new(
    &[
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26,
        27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38,
    ],
    [4, 16, 8],
    4,
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_unique_and_priorities_distinct_within_a_group() {
        for (i, e) in EVENTS.iter().enumerate() {
            assert_eq!(usize::from(e.number), i, "EVENTS[n] is event n");
            assert!(usize::from(e.number) < EVENT_SLOTS);
            for o in &EVENTS[..i] {
                assert_ne!(o.number, e.number, "event {} twice", e.number);
                // Port 0's events share priority 0, port 1's priority 1 (§3.1).
                if o.group == e.group && o.group != EventGroup::Communication {
                    assert_ne!(o.pri, e.pri, "events {} and {}", o.number, e.number);
                }
            }
        }
    }

    #[test]
    fn profiles_list_known_events_ascending() {
        for p in [&A5_INTERRUPTS, &S7_200_INTERRUPTS, &SMART_INTERRUPTS] {
            assert!(p.events.windows(2).all(|w| w[0] < w[1]));
            assert_eq!(p.infos().count(), p.events.len());
        }
        assert!(!A5_INTERRUPTS.has(21) && !A5_INTERRUPTS.has(22));
        assert!(S7_200_INTERRUPTS.has(21));
        assert_eq!(S7_200_INTERRUPTS.queue(EventGroup::Timed), (24, 8));
        assert_eq!(S7_200_INTERRUPTS.slots(), 32);
        assert!(!SMART_INTERRUPTS.has(14) && SMART_INTERRUPTS.has(38));
        assert_eq!(TIMED_EVENTS, [10, 11]);
        // Each set holds exactly the profile's events of its source, ascending.
        for p in [&A5_INTERRUPTS, &S7_200_INTERRUPTS, &SMART_INTERRUPTS] {
            for (set, edges) in [(INPUT_EDGE_EVENTS, true), (TIMER_REACHED_EVENTS, false)] {
                let walked: Vec<u8> = p.infos_in(set).map(|e| e.number).collect();
                let by_table: Vec<u8> = p
                    .infos()
                    .filter(|e| match e.source {
                        EventSource::InputEdge { .. } => edges,
                        EventSource::TimerReached { .. } => !edges,
                        _ => false,
                    })
                    .map(|e| e.number)
                    .collect();
                assert_eq!(walked, by_table);
            }
        }
        assert_eq!(
            S7_200_INTERRUPTS
                .infos_in(TIMER_REACHED_EVENTS)
                .map(|e| e.number)
                .collect::<Vec<_>>(),
            [21, 22]
        );
        assert_eq!(SMART_INTERRUPTS.infos_in(INPUT_EDGE_EVENTS).count(), 12);
        assert_eq!(EventSet(0b1010).numbers().collect::<Vec<_>>(), [1, 3]);
        assert_eq!(set_bits(1 << 63 | 1).collect::<Vec<_>>(), [0, 63]);
    }

    #[test]
    fn the_manual_order_of_the_discrete_group() {
        // §3.1: PLS0, PLS1, then the rising edges I0.0 … I0.3, then the falling ones.
        let order: Vec<u8> = {
            let mut d: Vec<_> = EVENTS
                .iter()
                .filter(|e| e.group == EventGroup::Discrete)
                .collect();
            d.sort_by_key(|e| e.pri);
            d.iter().take(10).map(|e| e.number).collect()
        };
        assert_eq!(order, [19, 20, 0, 2, 4, 6, 1, 3, 5, 7]);
    }
}
