//! The event phases and the service loop (s7-200-more §3.6.3, §3.6.4), and [`Isr`], the one
//! thing an engine supplies: running a routine's body.

use super::sources::{self, HAPPENINGS, Sources};
use super::{attached, queue, set, set_now};
use crate::{mem, scan};
use stljit_core::layout::{IntState, Layout, Sched};
use stljit_core::{Area, PouId, ScanStatus};

/// Runs interrupt routine bodies: the engine-specific part of the machinery. The interpreter
/// interprets the routine's POU; the JIT calls its compiled function.
pub trait Isr {
    /// Runs interrupt routine `pou` to its end on the image: in L frame
    /// [`ISR_FRAME`](stljit_core::layout::ISR_FRAME) (its
    /// calls in the frames after it, with the profile's depth), with a zero logic stack and its
    /// own FOR stack. Returns `Ok` when the routine ended (RETI, CRETI, its last op),
    /// `Stopped` when a STOP ended it (and the routine chain) at once, `Fatal` when a fatal
    /// error aborted it (recorded in the image). The entry and exit context (gate, ENO, saved
    /// registers) is the machinery's.
    fn run(&mut self, img: &mut [u8], layout: &Layout, pou: PouId) -> ScanStatus;
}

/// An engine without interrupt routines: every run returns at once.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoIsr;

impl Isr for NoIsr {
    fn run(&mut self, _: &mut [u8], _: &Layout, _: PouId) -> ScanStatus {
        ScanStatus::Ok
    }
}

/// An event phase ended in a fatal error (recorded in the image): the scan is aborted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PhaseFatal;

/// What the event phases need of the program: its interrupt routines by number and the
/// sources it can set going (from its scan plan).
#[derive(Clone, Copy, Debug)]
pub struct Events<'a> {
    /// The interrupt routines by number.
    pub routines: &'a [Option<PouId>],
    /// The happening sources that may act.
    pub sources: Sources,
}

/// The routines of a program by interrupt number, the engine that runs them, and which
/// physical inputs the image holds for them.
struct Service<'a> {
    routines: &'a [Option<PouId>],
    isr: &'a mut dyn Isr,
    inputs: Inputs,
}

/// Which physical inputs the image holds while a phase runs. Routines of the interval phase
/// see those of the previous scan instant (`PREV_IN`), the harness having already written this
/// scan's; the exchange costs two copies of the inputs, so it waits for the first routine, and
/// most intervals run none.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Inputs {
    /// The instant phase: this scan's inputs, which its routines see.
    Instant,
    /// The interval phase before its first routine: still this scan's inputs.
    Deferred,
    /// The interval phase: the previous instant's inputs, exchanged back at its end.
    Previous,
}

/// Exchanges the physical inputs with those of the last scan instant (`PREV_IN`).
fn swap_inputs(img: &mut [u8], layout: &Layout) {
    let n = layout.area_size(Area::I) as usize;
    let (a, b) = (
        layout.phys_in as usize,
        layout.int_state(IntState::PREV_IN) as usize,
    );
    let (lo, hi) = (a.min(b), a.max(b));
    if lo + n <= hi && hi + n <= img.len() {
        let (first, second) = img.split_at_mut(hi);
        first[lo..lo + n].swap_with_slice(&mut second[..n]);
    }
}

/// Phase E1 (§3.6.3 `run_interval(Ta, Tb)`) for the interval `(ta, tb]` in µs: the entries
/// left queued are serviced at `ta` (after the T32/T96 poll of what the previous scan's main
/// program did), then every happening due in the interval is applied in time order, each
/// followed by a service run at its time. Routines see the physical inputs of the previous
/// scan instant, as the harness already wrote this scan's; so do the high-speed counters'
/// inputs, the only source that reads them.
pub fn interval_phase(
    img: &mut [u8],
    layout: &Layout,
    events: Events<'_>,
    isr: &mut dyn Isr,
    ta: u64,
    tb: u64,
) -> Result<(), PhaseFatal> {
    let mut s = Service {
        routines: events.routines,
        isr,
        inputs: Inputs::Deferred,
    };
    if events.sources.counters() {
        s.previous_inputs(img, layout);
    }
    sources::start_interval(img, layout, events.sources, ta, tb);
    let r = (|| {
        sources::poll_timers(img, layout, ta);
        s.service(img, layout, ta)?;
        while let Some((tau, rank, before)) = sources::next_due(img, layout, events.sources, tb) {
            HAPPENINGS[rank].apply_before(img, layout, tau, before);
            s.service(img, layout, tau)?;
        }
        Ok(())
    })();
    if s.inputs == Inputs::Previous {
        swap_inputs(img, layout);
    }
    r
}

/// Phase E2 (§3.6.2 step 5) at the scan instant `tk` in µs, after the inputs are read and the
/// timers refreshed: the instant sources raise their events, the queues are serviced at `tk`,
/// and the main program runs "at" `tk`.
pub fn instant_phase(
    img: &mut [u8],
    layout: &Layout,
    events: Events<'_>,
    isr: &mut dyn Isr,
    tk: u64,
) -> Result<(), PhaseFatal> {
    let mut s = Service {
        routines: events.routines,
        isr,
        inputs: Inputs::Instant,
    };
    set_now(img, layout, tk);
    sources::instant(img, layout, events.sources, tk);
    s.service(img, layout, tk)?;
    set_now(img, layout, tk);
    Ok(())
}

/// Whether service runs are blocked: interrupts disabled, a routine running or a STOP pending.
fn blocked(img: &[u8], layout: &Layout) -> bool {
    super::get(img, layout, IntState::ENABLED) == 0
        || super::get(img, layout, IntState::IN_ISR) != 0
        || mem::sched_u8(img, layout, Sched::STOP_REQ) != 0
}

impl Service<'_> {
    /// In the interval phase, puts the previous instant's inputs in place if they are not yet.
    fn previous_inputs(&mut self, img: &mut [u8], layout: &Layout) {
        if self.inputs == Inputs::Deferred {
            swap_inputs(img, layout);
            self.inputs = Inputs::Previous;
        }
    }

    /// A service run at `tau` (§3.6.3 `service`): nothing while interrupts are disabled, a
    /// routine runs or a STOP is pending; else the queued entry with the smallest key runs its
    /// routine, until the queues are empty; then SM4.0–SM4.2 are cleared. Most runs find the
    /// queues empty: that case is checked inline.
    #[inline]
    fn service(&mut self, img: &mut [u8], layout: &Layout, tau: u64) -> Result<(), PhaseFatal> {
        if blocked(img, layout) {
            return Ok(());
        }
        if queue::is_empty(img, layout) {
            queue::clear_overflow(img, layout);
            return Ok(());
        }
        self.service_queued(img, layout, tau)
    }

    /// [`Service::service`] with entries queued and nothing blocking.
    #[inline(never)]
    fn service_queued(
        &mut self,
        img: &mut [u8],
        layout: &Layout,
        tau: u64,
    ) -> Result<(), PhaseFatal> {
        while let Some(e) = queue::pop_next(img, layout) {
            let routine = attached(img, layout, e.event);
            if let Some(n) = routine.checked_sub(1) {
                self.run_isr(img, layout, usize::from(n), tau)?;
            }
            if blocked(img, layout) {
                return Ok(());
            }
        }
        queue::clear_overflow(img, layout);
        Ok(())
    }

    /// Runs interrupt routine `number` at `tau` (§3.6.4): the logic stack (the engine's),
    /// AC0–AC3, ENO and SMB1 are saved and restored around it, the gate is open at entry and
    /// after it; a STOP in it discards every queued entry.
    fn run_isr(
        &mut self,
        img: &mut [u8],
        layout: &Layout,
        number: usize,
        tau: u64,
    ) -> Result<(), PhaseFatal> {
        let Some(pou) = self.routines.get(number).copied().flatten() else {
            return Ok(());
        };
        self.previous_inputs(img, layout);
        // AC0–AC3: 16 bytes on every S7 profile.
        let ac = layout.base(Area::AC);
        let saved_ac: [u8; 16] = mem::get_array(img, ac);
        let smb1 = layout.base(Area::SM) + 1;
        let saved_smb1 = mem::get_u8(img, smb1);
        let saved_eno = mem::sched_u8(img, layout, Sched::ENO);
        set(img, layout, IntState::IN_ISR, 1);
        set_now(img, layout, tau);
        mem::set_sched_u8(img, layout, Sched::ENO, 0);
        let (gate, open) = scan::GATE_OPEN;
        mem::set_sched_u8(img, layout, gate, open);
        let status = self.isr.run(img, layout, pou);
        set(img, layout, IntState::IN_ISR, 0);
        if status == ScanStatus::Fatal {
            return Err(PhaseFatal);
        }
        if layout.area_size(Area::AC) == 16 {
            mem::set_array(img, ac, saved_ac);
        }
        mem::set_u8(img, smb1, saved_smb1);
        mem::set_sched_u8(img, layout, Sched::ENO, saved_eno);
        mem::set_sched_u8(img, layout, gate, open);
        if status == ScanStatus::Stopped {
            queue::clear(img, layout);
        }
        Ok(())
    }
}
