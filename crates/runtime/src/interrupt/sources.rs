//! Event sources (s7-200-more §3.5, §3.6.3). Two kinds:
//!
//! * A **happening source** ([`Happening`]) is hardware that acts inside a scan interval: it
//!   knows the time of its next happening and applies it (updating its state in the image and
//!   raising events at that time). The interval phase applies the pending happening with the
//!   smallest `(τ, rank)` (rank = position in [`HAPPENINGS`], the spec's `source_rank`), then
//!   services the queues at `τ`, and repeats while a happening is due at or before `T_k`; a
//!   happening a routine schedules takes part if it is due in time. A source may apply its
//!   following happenings with the first when they raise nothing and no other source's comes
//!   between ([`Happening::apply_before`]: the high-speed counters' steps).
//! * An **instant source** raises the events of the scan instant `T_k` itself, in the order of
//!   §3.6.2 step 5 ([`instant`]): input edges, then the timers reaching their preset.
//!
//! **Adding a source.** A high-speed counter, a pulse output or a serial port is a
//! [`Happening`]: put its state in the image (a new `record_fields!` record in
//! `stljit_core::layout`), implement `kind` (a [`SourceKind`]; a new kind says in
//! [`Sources::new`] which instruction of a program sets it going), `next` (from that state)
//! and `apply` (step it, then `super::queue::raise` the events it causes, at `τ`), and insert it
//! into [`HAPPENINGS`] at its `source_rank` (§3.6.3: ports, pulse outputs, HSC0–HSC5, the timed
//! interrupts, then the network jobs). A source whose level changes at the scan instant (HSC reset/start inputs)
//! adds its check to [`instant`] between the edges and the timers.

use super::{attached, queue};
use crate::comm::{self, NetJobs, Port};
use crate::hsc::{self, Counter};
use crate::mem;
use crate::pulse::Generator;
use crate::timer::TofPhase;
use stljit_core::interrupt::{
    EventSource, INPUT_EDGE_EVENTS, TIMED_EVENTS, TIMER_REACHED_EVENTS, set_bits,
};
use stljit_core::ir::TimerKind;
use stljit_core::layout::{IntState, Layout, TimerState};
use stljit_core::{Area, TimerId};

/// What kind of hardware a [`Happening`] is: a program can only set some of them going (the
/// [`Sources`] of its scan plan), and the others stay idle without being asked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SourceKind {
    /// A serial port: characters arrive from the harness whatever the program does.
    Port,
    /// A pulse output: runs only after a `PLS`.
    Pulse,
    /// A high-speed counter: counts only once an `HDEF` has defined it.
    Counter,
    /// A timed interrupt: raises only while attached, which takes an `ATCH` to a routine.
    Timed,
    /// The network jobs: only after a `NETR`, `NETW`, `GET` or `PUT`.
    Network,
}

/// The [`HAPPENINGS`] that may act in a program's scans: every port, and the pulse outputs,
/// counters, timed interrupts and network jobs only where the program can set them going.
/// The others stay idle for the whole run, so the interval phase neither plans nor polls
/// them. Computed once per program (its scan plan).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sources {
    /// Bit `rank` for `HAPPENINGS[rank]`.
    ranks: u16,
    /// The counters are among them (they also plan their steps and watch reset inputs).
    counters: bool,
}

impl Sources {
    /// The sources of a program that has an `HDEF` (`counters`), a `PLS` (`pulses`),
    /// interrupt routines (`timed`) and starts communication (`network`).
    pub fn new(counters: bool, pulses: bool, timed: bool, network: bool) -> Sources {
        let may_act = |kind| match kind {
            SourceKind::Port => true,
            SourceKind::Pulse => pulses,
            SourceKind::Counter => counters,
            SourceKind::Timed => timed,
            SourceKind::Network => network,
        };
        let ranks = HAPPENINGS
            .iter()
            .enumerate()
            .filter(|(_, s)| may_act(s.kind()))
            .fold(0, |set, (rank, _)| set | 1 << rank);
        Sources { ranks, counters }
    }

    /// Whether the high-speed counters are among them.
    pub(crate) fn counters(self) -> bool {
        self.counters
    }

    /// The ranks of the sources that may act, ascending.
    fn ranks(self) -> impl Iterator<Item = usize> {
        set_bits(u64::from(self.ranks)).map(usize::from)
    }
}

/// Hardware that acts inside a scan interval (module doc).
pub trait Happening: Sync {
    /// What kind of hardware it is.
    fn kind(&self) -> SourceKind;
    /// The time in µs of the source's next happening, `None` while it is idle.
    fn next(&self, img: &[u8], layout: &Layout) -> Option<u64>;
    /// Applies the happening due at `tau` (== what `next` returned).
    fn apply(&self, img: &mut [u8], layout: &Layout, tau: u64);
    /// Applies the happening due at `tau` and, where the source can tell that its following
    /// happenings raise no event, those of them due before `before` as well: no other source's
    /// happening comes first, so only the service runs after each would come between them, and
    /// with nothing queued those do nothing. The default applies the one happening.
    fn apply_before(&self, img: &mut [u8], layout: &Layout, tau: u64, before: u64) {
        let _ = before;
        self.apply(img, layout, tau);
    }
}

/// Timed interrupt 0 or 1 (§3.5.1): while its event is attached with an interval of 1 ms or
/// more, one event every interval from the ATCH on.
struct TimedInterrupt {
    channel: u8,
}

impl TimedInterrupt {
    /// The event this channel raises (10, 11), from the event table.
    fn event(&self) -> Option<u8> {
        TIMED_EVENTS.get(usize::from(self.channel)).copied()
    }

    fn next_at(&self, layout: &Layout) -> u32 {
        layout.int_state(IntState::TIMED_NEXT) + 8 * u32::from(self.channel)
    }

    fn interval(&self, img: &[u8], layout: &Layout) -> u8 {
        super::get(
            img,
            layout,
            IntState::TIMED_INTERVAL + u32::from(self.channel),
        )
    }
}

impl Happening for TimedInterrupt {
    fn kind(&self) -> SourceKind {
        SourceKind::Timed
    }

    fn next(&self, img: &[u8], layout: &Layout) -> Option<u64> {
        let event = self.event()?;
        let live = attached(img, layout, event) != 0 && self.interval(img, layout) != 0;
        live.then(|| mem::get_u64_ne(img, self.next_at(layout)))
    }

    fn apply(&self, img: &mut [u8], layout: &Layout, tau: u64) {
        if let Some(event) = self.event() {
            queue::raise(img, layout, event, tau);
        }
        let step = 1000 * u64::from(self.interval(img, layout));
        mem::set_u64_ne(img, self.next_at(layout), tau.saturating_add(step));
    }
}

// `Sources` holds one bit per happening source.
const _: () = assert!(HAPPENINGS.len() <= 16);

/// The happening sources in `source_rank` order (§3.6.3): the serial ports 0 and 1
/// (`crate::comm`, each receive before transmit), the pulse outputs PTO0–PTO2
/// (`crate::pulse`), the high-speed counters HSC0–HSC5 (`crate::hsc`), the timed interrupts,
/// then the network jobs.
pub static HAPPENINGS: &[&dyn Happening] = &[
    &Port { n: 0 },
    &Port { n: 1 },
    &Generator { n: 0 },
    &Generator { n: 1 },
    &Generator { n: 2 },
    &Counter { n: 0 },
    &Counter { n: 1 },
    &Counter { n: 2 },
    &Counter { n: 3 },
    &Counter { n: 4 },
    &Counter { n: 5 },
    &TimedInterrupt { channel: 0 },
    &TimedInterrupt { channel: 1 },
    &NetJobs,
];

/// The pending happening with the smallest `(τ, rank)` due at or before `until`: its time, its
/// index in [`HAPPENINGS`], and the time before which no other source's happening is due
/// (`until + 1` when none is), for [`Happening::apply_before`].
pub(crate) fn next_due(
    img: &[u8],
    layout: &Layout,
    sources: Sources,
    until: u64,
) -> Option<(u64, usize, u64)> {
    let mut first: Option<(u64, usize)> = None;
    let mut second = until.saturating_add(1);
    for rank in sources.ranks() {
        let Some(t) = HAPPENINGS[rank].next(img, layout).filter(|&t| t <= until) else {
            continue;
        };
        // Ranks ascend, so at equal times the one found first keeps its place.
        match first {
            Some((f, _)) if t < f => {
                second = second.min(f);
                first = Some((t, rank));
            }
            Some(_) => second = second.min(t),
            None => first = Some((t, rank)),
        }
    }
    first.map(|(t, rank)| (t, rank, second))
}

/// The start of the interval `(ta, tb]` (µs): the sources whose happenings depend on the
/// harness's activity in it (the high-speed counters' steps, the received characters) plan
/// them (the counters only where the program defines one: see [`Sources`]).
pub(crate) fn start_interval(img: &mut [u8], layout: &Layout, sources: Sources, ta: u64, tb: u64) {
    if sources.counters {
        hsc::start_interval(img, layout, ta, tb);
    }
    comm::start_rx(img, layout, ta);
}

/// The instant sources at `T_k` (§3.6.2 step 5): input edges, the high-speed counters' reset
/// inputs, then T32/T96; `PREV_IN` takes the new inputs after the first two compared them.
pub(crate) fn instant(img: &mut [u8], layout: &Layout, sources: Sources, tau: u64) {
    // Inputs that did not change since the last instant have no edges and need no copy (the
    // usual case).
    let changed = inputs_changed(img, layout);
    if changed {
        input_edges(img, layout, tau);
    }
    if sources.counters {
        hsc::instant(img, layout, layout.int_state(IntState::PREV_IN), tau);
    }
    if changed {
        let n = layout.area_size(Area::I) as usize;
        let (from, to) = (
            layout.phys_in as usize,
            layout.int_state(IntState::PREV_IN) as usize,
        );
        if from + n <= img.len() && to + n <= img.len() {
            img.copy_within(from..from + n, to);
        }
    }
    poll_timers(img, layout, tau);
}

/// Whether the physical inputs differ from those of the last scan instant (`PREV_IN`).
fn inputs_changed(img: &[u8], layout: &Layout) -> bool {
    let (now, prev) = (layout.phys_in, layout.int_state(IntState::PREV_IN));
    let n = layout.area_size(Area::I) as usize;
    let (now, prev) = (now as usize, prev as usize);
    img.get(now..now + n) != img.get(prev..prev + n)
}

/// Input edges (§3.5.2): each edge event of the profile whose input bit differs between the
/// physical inputs and those of the last scan instant (`PREV_IN`) in its direction.
fn input_edges(img: &mut [u8], layout: &Layout, tau: u64) {
    let prev = layout.int_state(IntState::PREV_IN);
    let ints = layout.profile.profile().interrupts;
    for info in ints.infos_in(INPUT_EDGE_EVENTS) {
        if let EventSource::InputEdge { byte, bit, rising } = info.source {
            let old = mem::get_bit(img, prev + byte, bit);
            let new = mem::get_bit(img, layout.phys_in + byte, bit);
            if old != new && new == rising {
                queue::raise(img, layout, info.number, tau);
            }
        }
    }
}

/// Whether timer `n` is at its preset in the sense of its `CT = PT` event (§3.5.3): a TON's
/// bit (its CT reached PT), a TOF's phase Done.
fn reached(img: &[u8], layout: &Layout, n: TimerId) -> bool {
    if u32::from(n.0) >= layout.area_size(Area::TimerBit) {
        return false;
    }
    let state = layout.timer_state(n.0);
    let kind = mem::get_u8(img, state + TimerState::KIND);
    if kind == TimerKind::Off.code() {
        mem::get_u8(img, state + TimerState::TOF) == TofPhase::Done as u8
    } else if kind == 0 {
        false
    } else {
        mem::get_u8(img, layout.base(Area::TimerBit) + u32::from(n.0)) != 0
    }
}

/// The timer sources (T32, T96): an event when the `CT = PT` condition turned on since the
/// last poll (bit `i` of `TIMER_PREV` for the profile's `i`-th timer event). Polled at the
/// start of the interval phase, at `T_{k−1}` (what the previous scan's main program and E2
/// routines did, at the time they did it), and after the clock refresh (E2, at `T_k`: the
/// refresh, and what E1's routines did) [design: a routine's own execution is seen at the next
/// poll, so a routine cannot re-raise its event at its own instant].
#[inline]
pub(crate) fn poll_timers(img: &mut [u8], layout: &Layout, tau: u64) {
    // A CPU without these events (the A5) has no bit to keep; checked inline, since the poll
    // runs twice a scan.
    if layout
        .profile
        .profile()
        .interrupts
        .has_any(TIMER_REACHED_EVENTS)
    {
        poll_timer_events(img, layout, tau);
    }
}

/// [`poll_timers`] on a CPU with T32/T96 events.
#[inline(never)]
fn poll_timer_events(img: &mut [u8], layout: &Layout, tau: u64) {
    let ints = layout.profile.profile().interrupts;
    let mut prev = super::get(img, layout, IntState::TIMER_PREV);
    let timers = ints
        .infos_in(TIMER_REACHED_EVENTS)
        .filter_map(|info| match info.source {
            EventSource::TimerReached { timer } => Some((info.number, timer)),
            _ => None,
        });
    for (i, (event, timer)) in timers.enumerate().take(8) {
        let now = reached(img, layout, TimerId(timer));
        let mask = 1u8 << i;
        if now && prev & mask == 0 {
            queue::raise(img, layout, event, tau);
        }
        prev = if now { prev | mask } else { prev & !mask };
    }
    super::set(img, layout, IntState::TIMER_PREV, prev);
}
