//! The interrupt machinery (s7-200-more.md §3), once for both engines: attachments, the three
//! queues with their overflow bits, the schedules of the timed interrupts, input-edge and
//! T32/T96 detection, and the service loop. Its state lives in the image (`IntState` and the
//! `QueueEntry` records of `stljit_core::layout`), so the differential oracle compares it.
//!
//! **The model (spec §3.6, normative).** Interrupt routines run only in the two *event phases*
//! at the start of a scan, never inside the main program ([`crate::scan::begin`] calls them):
//! * **E1, the interval phase** ([`interval_phase`]) replays the scan's interval
//!   `(T_{k−1}, T_k]` in time order: first the entries left queued (by DISI or by the previous
//!   scan's main program) are serviced at `T_{k−1}`, then every *happening* (a timed
//!   interrupt's due time; later an HSC count step, a pulse, a character) is applied at its
//!   own time `τ` and the queues are serviced at `τ`, before the next happening.
//! * **E2, the instant phase** ([`instant_phase`]) raises the events of the scan instant `T_k`
//!   after the inputs are read: input edges, then T32/T96 reaching their preset; then services.
//!
//! A routine runs in zero virtual time at its service time. Servicing takes the queued entry
//! with the smallest key `(group, τ, pri, seq)`, runs the routine attached to its event and
//! repeats until the queues are empty (then SM4.0–SM4.2 are cleared); nothing is serviced while
//! interrupts are disabled, while a routine runs, or after a STOP. The only engine-specific
//! part is running a routine's body: the engine passes an [`Isr`].
//!
//! Times are µs (`T_k = 1000 · t_k`), as the spec's §0.3. The work of a scan is bounded
//! without a budget of its own: every happening advances its source's time by at least 1 ms,
//! edges occur only at scan instants, and the timer sources are polled only at the two phase
//! starts (not after each routine), so no routine can raise events for its own instant without
//! end. Back-edges inside routines count toward the scan's loop budget (§3.6.4).
//!
//! **Adding a source** (HSC, pulse outputs, communication): see [`sources`].

mod queue;
mod service;
pub mod sources;

#[cfg(test)]
mod tests;

pub(crate) use queue::raise;
pub use service::{Events, Isr, NoIsr, PhaseFatal, instant_phase, interval_phase};

use crate::mem;
use stljit_core::interrupt::{self, EVENT_SLOTS, EventSource, TIMED_INTERVAL_SMB};
use stljit_core::ir::{IntOp, Program};
use stljit_core::layout::{IntState, Layout};
use stljit_core::{Area, ErrorCode};

/// SMB4: the overflow bits SM4.0–SM4.2 (bit = the group's index) and SM4.4.
pub const SMB4: u32 = 4;
/// SM4.4 mirrors the global enable (§3.3).
pub const SM4_ENABLED: u8 = 4;

/// An interrupt instruction with its routine resolved to the routine's number: what both
/// engines hand [`execute`] (the JIT through `stljit_rt_interrupt`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// `ATCH`: attach INT `routine` to `event`.
    Attach {
        /// The interrupt routine's number.
        routine: u16,
        /// The event.
        event: u8,
    },
    /// `DTCH`.
    Detach(u8),
    /// `ENI`.
    Enable,
    /// `DISI`.
    Disable,
    /// `CEVNT`.
    Clear(u8),
}

impl Action {
    /// The action of `op` in `program` (`None` for an ATCH whose routine is not an interrupt
    /// routine, which the verifier rejects).
    pub fn of(op: IntOp, program: &Program) -> Option<Action> {
        Some(match op {
            IntOp::Attach { routine, event } => Action::Attach {
                routine: program.pous.get(routine.index())?.kind.interrupt()?,
                event,
            },
            IntOp::Detach { event } => Action::Detach(event),
            IntOp::Enable => Action::Enable,
            IntOp::Disable => Action::Disable,
            IntOp::ClearEvent { event } => Action::Clear(event),
        })
    }

    /// The action as the three integers of `stljit_rt_interrupt`: `(kind, event, routine)`.
    pub fn encode(self) -> (u32, u32, u32) {
        match self {
            Action::Attach { routine, event } => (0, u32::from(event), u32::from(routine)),
            Action::Detach(e) => (1, u32::from(e), 0),
            Action::Enable => (2, 0, 0),
            Action::Disable => (3, 0, 0),
            Action::Clear(e) => (4, u32::from(e), 0),
        }
    }

    /// Inverse of [`Action::encode`]; `None` for integers no action encodes to.
    pub fn decode(kind: u32, event: u32, routine: u32) -> Option<Action> {
        let event = u8::try_from(event).ok()?;
        Some(match kind {
            0 => Action::Attach {
                routine: u16::try_from(routine).ok()?,
                event,
            },
            1 => Action::Detach(event),
            2 => Action::Enable,
            3 => Action::Disable,
            4 => Action::Clear(event),
            _ => return None,
        })
    }
}

/// Executes an interrupt instruction whose power flow is on (§3.4). ENI and DISI in an
/// interrupt routine are error 0x0004 and change nothing; ATCH of an input-edge event on an
/// input of a defined high-speed counter is 0x0002 and attaches nothing (§8.3); the others
/// cannot fail.
pub fn execute(img: &mut [u8], layout: &Layout, action: Action) -> Result<(), ErrorCode> {
    match action {
        Action::Attach { routine, event } => {
            let Some(slot) = attach_slot(layout, event) else {
                return Ok(());
            };
            if interrupt::event(event)
                .is_some_and(|e| crate::hsc::edge_conflict(img, layout, e.source))
            {
                return Err(ErrorCode::HscEdgeConflict);
            }
            mem::set_u8(img, slot, u8::try_from(routine + 1).unwrap_or(0));
            if let Some(EventSource::Timed { channel }) = interrupt::event(event).map(|e| e.source)
            {
                start_timed(img, layout, channel);
            }
        }
        Action::Detach(event) => {
            if let Some(slot) = attach_slot(layout, event) {
                mem::set_u8(img, slot, 0);
            }
            queue::remove_event(img, layout, event);
        }
        Action::Enable | Action::Disable => {
            if get(img, layout, IntState::IN_ISR) != 0 {
                return Err(ErrorCode::InInterrupt);
            }
            set_enabled(img, layout, action == Action::Enable);
        }
        Action::Clear(event) => queue::remove_event(img, layout, event),
    }
    Ok(())
}

/// Image offset of event `event`'s attachment byte (`None` beyond the table).
fn attach_slot(layout: &Layout, event: u8) -> Option<u32> {
    (usize::from(event) < EVENT_SLOTS)
        .then(|| layout.int_state(IntState::ATTACH) + u32::from(event))
}

/// Whether no event waits in any queue.
pub(crate) fn nothing_queued(img: &[u8], layout: &Layout) -> bool {
    queue::is_empty(img, layout)
}

/// The routine number + 1 attached to `event` (0: detached).
pub(crate) fn attached(img: &[u8], layout: &Layout, event: u8) -> u8 {
    attach_slot(layout, event).map_or(0, |at| mem::get_u8(img, at))
}

/// A one-byte field of the interrupt state.
pub(crate) fn get(img: &[u8], layout: &Layout, field: u32) -> u8 {
    mem::get_u8(img, layout.int_state(field))
}

/// Writes a one-byte field of the interrupt state.
pub(crate) fn set(img: &mut [u8], layout: &Layout, field: u32, v: u8) {
    mem::set_u8(img, layout.int_state(field), v);
}

/// The virtual time in µs of the code running.
pub(crate) fn now(img: &[u8], layout: &Layout) -> u64 {
    mem::get_u64_ne(img, layout.int_state(IntState::NOW))
}

/// Sets the virtual time of the code about to run.
pub(crate) fn set_now(img: &mut [u8], layout: &Layout, tau: u64) {
    mem::set_u64_ne(img, layout.int_state(IntState::NOW), tau);
}

/// The global enable and its mirror SM4.4.
fn set_enabled(img: &mut [u8], layout: &Layout, on: bool) {
    set(img, layout, IntState::ENABLED, u8::from(on));
    let smb4 = layout.base(Area::SM) + SMB4;
    mem::set_bit(img, smb4, SM4_ENABLED, on);
}

/// ATCH of timed interrupt `channel` (§3.5.1): the interval is captured from SMB34/SMB35 and
/// the schedule restarts from now; interval 0 attaches without ever firing [uncertain I4].
fn start_timed(img: &mut [u8], layout: &Layout, channel: u8) {
    let ch = u32::from(channel);
    let Some(&smb) = TIMED_INTERVAL_SMB.get(channel as usize) else {
        return;
    };
    let interval = mem::get_u8(img, layout.base(Area::SM) + smb);
    set(img, layout, IntState::TIMED_INTERVAL + ch, interval);
    let next = now(img, layout).saturating_add(1000 * u64::from(interval));
    mem::set_u64_ne(img, layout.int_state(IntState::TIMED_NEXT) + 8 * ch, next);
}
