//! High-speed counters (s7-200-more.md §8), once for both engines: HDEF and HSC
//! ([`define`], [`control`], which `ext::execute` runs for the interpreter and for the JIT's
//! `stljit_rt_ext`), the count steps as a happening source of the interrupt machinery
//! ([`Counter`], in `interrupt::sources::HAPPENINGS`), and the reset input at the scan instant
//! ([`instant`]). The state is in the image: the current value in the HC area (big-endian
//! DINT), the status byte in SM, the rest in the counter's `HscState` record.
//!
//! **The counting model (§8.4, normative).** The harness gives each counter a signed activity
//! `n` per scan interval ([`set_rate`]: the `RATE` field, held until it writes again). At the
//! start of the interval phase ([`start_interval`]) it becomes `s` unit steps (`|n|`, times 4
//! for a quadrature counter at 4x; none in mode 12, whose steps are the pulses of its pulse
//! output, [`count_pulse`]), step `j` at `T_{k−1} + ⌊j·D/s⌋`. Each step is a happening: the
//! interval phase applies the steps of every source in time order and services the queues
//! after each, so a CV = PV routine runs at the step that reached the preset, before the next.
//! Steps that raise no event and come before any other source's next happening are applied
//! together ([`Counter::apply_before`]): with nothing queued no routine can run between them,
//! so the result is the same, and a fast encoder costs a few happenings per scan.
//! A step counts only while the counter is enabled and not held by its reset input, and (modes
//! 2, 5, 8, 11) while its start input is active; the levels are those of the previous scan
//! instant, which is what the physical inputs hold while the interval phase runs.
//!
//! Rules the spec leaves open, fixed here [design]:
//! * HDEF sets the counting direction to up ([`DIRECTION_AT_HDEF`]); HSC with control bit 4
//!   sets it (modes 0–2) or its initial value (3–11).
//! * CV wraps at the ends of the DINT range (§8.4 [uncertain: wrap]).
//! * The status byte's bits 0–4 are kept; HSC with bit 7 clear only disables (§8.1).

use crate::interrupt::{
    self,
    sources::{Happening, SourceKind},
};
use crate::mem;
use stljit_core::hsc::{HscEvent, HscInfo, InputBit, Mode};
use stljit_core::interrupt::{EventSource, hsc_event};
use stljit_core::layout::{HscState, IntState, Layout};
use stljit_core::{Area, ErrorCode};

/// The counting direction HDEF gives a counter (1 = up) [design: the manual does not say;
/// HSC with control bit 4 sets it].
pub const DIRECTION_AT_HDEF: u8 = 1;

/// Status byte bits (§8.1): current direction up, CV = PV, CV > PV.
const STATUS_UP: u8 = 1 << 5;
const STATUS_EQ: u8 = 1 << 6;
const STATUS_GT: u8 = 1 << 7;

/// Control byte bits (§8.1).
const CTRL_RESET_LOW: u8 = 1 << 0;
const CTRL_START_LOW: u8 = 1 << 1;
const CTRL_RATE_1X: u8 = 1 << 2;
const CTRL_UP: u8 = 1 << 3;
const CTRL_WRITE_DIR: u8 = 1 << 4;
const CTRL_WRITE_PV: u8 = 1 << 5;
const CTRL_WRITE_CV: u8 = 1 << 6;
const CTRL_ENABLE: u8 = 1 << 7;

/// Counter `n` of the image's profile, if it has it.
fn info(layout: &Layout, n: u8) -> Option<&'static HscInfo> {
    layout.profile.profile().hsc.get(n)
}

fn get(img: &[u8], layout: &Layout, n: u8, field: u32) -> u8 {
    mem::get_u8(img, layout.hsc_state(n, field))
}

fn set(img: &mut [u8], layout: &Layout, n: u8, field: u32, v: u8) {
    mem::set_u8(img, layout.hsc_state(n, field), v);
}

fn get_u32(img: &[u8], layout: &Layout, n: u8, field: u32) -> u32 {
    mem::get_u32_ne(img, layout.hsc_state(n, field))
}

fn set_u32(img: &mut [u8], layout: &Layout, n: u8, field: u32, v: u32) {
    mem::set_u32_ne(img, layout.hsc_state(n, field), v);
}

/// The SM byte `smb`.
fn sm(layout: &Layout, smb: u32) -> u32 {
    layout.base(Area::SM) + smb
}

/// Image offset of `HCn`.
fn hc(layout: &Layout, n: u8) -> u32 {
    layout.base(Area::HC) + 4 * u32::from(n)
}

/// The current value `HCn`.
pub fn current(img: &[u8], layout: &Layout, n: u8) -> i32 {
    mem::get_be(img, hc(layout, n), stljit_core::Width::DWord) as i32
}

fn set_current(img: &mut [u8], layout: &Layout, n: u8, cv: i32) {
    mem::set_be(img, hc(layout, n), stljit_core::Width::DWord, cv as u32);
}

/// The mode of a defined counter (`None`: not defined).
fn mode(img: &[u8], layout: &Layout, n: u8) -> Option<Mode> {
    (get(img, layout, n, HscState::DEFINED) != 0).then(|| Mode(get(img, layout, n, HscState::MODE)))
}

/// Writes the status byte's direction, CV = PV and CV > PV bits from the counter's state.
fn update_status(img: &mut [u8], layout: &Layout, info: &HscInfo) {
    let n = info.number;
    let cv = current(img, layout, n);
    let pv = get_u32(img, layout, n, HscState::PV) as i32;
    let mut bits = 0;
    if get(img, layout, n, HscState::DIR) != 0 {
        bits |= STATUS_UP;
    }
    if cv == pv {
        bits |= STATUS_EQ;
    }
    if cv > pv {
        bits |= STATUS_GT;
    }
    let at = sm(layout, info.status_smb);
    let keep = mem::get_u8(img, at) & !(STATUS_UP | STATUS_EQ | STATUS_GT);
    mem::set_u8(img, at, keep | bits);
}

/// Whether input `bit` is used by a defined counter other than `except` (§8.3).
fn used_by_counter(img: &[u8], layout: &Layout, bit: InputBit, except: Option<u8>) -> bool {
    layout.profile.profile().hsc.iter().any(|c| {
        Some(c.number) != except
            && mode(img, layout, c.number).is_some_and(|m| c.inputs_used(m).any(|u| u == bit))
    })
}

/// Whether an ATCH of input-edge event source `source` conflicts with a defined counter
/// (§8.3: error 0x0002, the attachment is not made).
pub(crate) fn edge_conflict(img: &[u8], layout: &Layout, source: EventSource) -> bool {
    match source {
        EventSource::InputEdge { byte, bit, .. } => used_by_counter(img, layout, (byte, bit), None),
        _ => false,
    }
}

/// Whether an input-edge event on `bit` is attached.
fn edge_attached(img: &[u8], layout: &Layout, bit: InputBit) -> bool {
    layout.profile.profile().interrupts.infos().any(|e| {
        matches!(e.source, EventSource::InputEdge { byte, bit: b, .. } if (byte, b) == bit)
            && interrupt::attached(img, layout, e.number) != 0
    })
}

/// `HDEF counter, mode` with power flow (§8.1): defines the counter, disabled, reading bits
/// 0–2 of its control byte now. Errors (nothing changes): 0x0004 in an interrupt routine,
/// 0x000A already defined, 0x0003 an input of the mode used by another defined counter or by
/// an attached input-edge event; a counter or mode outside the profile's table (which the
/// verifier rejects) is 0x0091.
pub fn define(img: &mut [u8], layout: &Layout, counter: u8, m: u8) -> Result<(), ErrorCode> {
    let info = info(layout, counter)
        .filter(|c| c.has_mode(m))
        .ok_or(ErrorCode::OperandRange)?;
    if interrupt::get(img, layout, IntState::IN_ISR) != 0 {
        return Err(ErrorCode::InInterrupt);
    }
    if mode(img, layout, counter).is_some() {
        return Err(ErrorCode::HscRedefined);
    }
    let conflict = info.inputs_used(Mode(m)).any(|bit| {
        used_by_counter(img, layout, bit, Some(counter)) || edge_attached(img, layout, bit)
    });
    if conflict {
        return Err(ErrorCode::HscInputConflict);
    }
    let ctrl = mem::get_u8(img, sm(layout, info.control_smb()));
    let flag = |bit: u8| u8::from(ctrl & bit != 0);
    set(img, layout, counter, HscState::DEFINED, 1);
    set(img, layout, counter, HscState::MODE, m);
    set(img, layout, counter, HscState::ENABLED, 0);
    set(img, layout, counter, HscState::DIR, DIRECTION_AT_HDEF);
    set(
        img,
        layout,
        counter,
        HscState::RESET_LOW,
        flag(CTRL_RESET_LOW),
    );
    set(
        img,
        layout,
        counter,
        HscState::START_LOW,
        flag(CTRL_START_LOW),
    );
    set(img, layout, counter, HscState::RATE1X, flag(CTRL_RATE_1X));
    Ok(())
}

/// `HSC counter` with power flow (§8.1): applies the control byte. Bit 7 clear disables the
/// counter and nothing else; else it is enabled and bits 4–6 write the direction, the preset
/// (SMD 6 bytes after the status byte) and the current value (SMD 2 bytes after it), and the
/// status bits are updated. No CV = PV event comes from an update. Not defined: 0x0001.
pub fn control(img: &mut [u8], layout: &Layout, counter: u8) -> Result<(), ErrorCode> {
    let info = info(layout, counter).ok_or(ErrorCode::OperandRange)?;
    if mode(img, layout, counter).is_none() {
        return Err(ErrorCode::HscNotDefined);
    }
    let ctrl = mem::get_u8(img, sm(layout, info.control_smb()));
    if ctrl & CTRL_ENABLE == 0 {
        set(img, layout, counter, HscState::ENABLED, 0);
        return Ok(());
    }
    set(img, layout, counter, HscState::ENABLED, 1);
    if ctrl & CTRL_WRITE_DIR != 0 {
        set(
            img,
            layout,
            counter,
            HscState::DIR,
            u8::from(ctrl & CTRL_UP != 0),
        );
    }
    let dword = |img: &[u8], smb| mem::get_be(img, sm(layout, smb), stljit_core::Width::DWord);
    if ctrl & CTRL_WRITE_PV != 0 {
        let pv = dword(img, info.new_pv_smb());
        set_u32(img, layout, counter, HscState::PV, pv);
    }
    if ctrl & CTRL_WRITE_CV != 0 {
        let cv = dword(img, info.new_cv_smb());
        set_current(img, layout, counter, cv as i32);
    }
    update_status(img, layout, info);
    Ok(())
}

/// The harness's counting activity of counter `n` per scan interval (§11.2 `hsc_steps`):
/// held until set again. Nothing for a counter the profile does not have.
pub fn set_rate(img: &mut [u8], layout: &Layout, n: u8, steps: i32) {
    if info(layout, n).is_some() {
        set_u32(img, layout, n, HscState::RATE, steps as u32);
    }
}

/// The counting activity of counter `n` per scan interval (0 for a counter the profile lacks).
pub fn rate(img: &[u8], layout: &Layout, n: u8) -> i32 {
    if info(layout, n).is_some() {
        get_u32(img, layout, n, HscState::RATE) as i32
    } else {
        0
    }
}

/// The start of the interval `(ta, tb]` (µs): every defined counter turns its activity into
/// this interval's unit steps (module doc). An empty interval has none.
pub(crate) fn start_interval(img: &mut [u8], layout: &Layout, ta: u64, tb: u64) {
    for c in layout.profile.profile().hsc.iter() {
        let n = c.number;
        let activity = rate(img, layout, n);
        let steps = match mode(img, layout, n) {
            Some(m) if tb > ta && m.0 != stljit_core::hsc::PULSE_MODE => {
                let x4 = m.quadrature() && get(img, layout, n, HscState::RATE1X) == 0;
                activity
                    .unsigned_abs()
                    .saturating_mul(if x4 { 4 } else { 1 })
            }
            _ => 0,
        };
        set_u32(img, layout, n, HscState::STEPS, steps);
        set_u32(img, layout, n, HscState::DONE, 0);
        set(img, layout, n, HscState::STEP_UP, u8::from(activity > 0));
        mem::set_u64_ne(img, layout.hsc_state(n, HscState::T_START), ta);
        mem::set_u64_ne(
            img,
            layout.hsc_state(n, HscState::SPAN),
            tb.saturating_sub(ta),
        );
    }
}

/// Whether the input `bit` is at its active level (`low`: active low) in the physical inputs.
fn active(img: &[u8], layout: &Layout, bit: InputBit, low: bool) -> bool {
    mem::get_bit(img, layout.phys_in + bit.0, bit.1) != low
}

/// High-speed counter `n` as a happening source: its count steps.
pub(crate) struct Counter {
    /// The counter's number.
    pub(crate) n: u8,
}

impl Happening for Counter {
    fn kind(&self) -> SourceKind {
        SourceKind::Counter
    }

    fn next(&self, img: &[u8], layout: &Layout) -> Option<u64> {
        info(layout, self.n)?;
        let n = self.n;
        let steps = get_u32(img, layout, n, HscState::STEPS);
        let done = get_u32(img, layout, n, HscState::DONE);
        (done < steps).then(|| {
            let ta = mem::get_u64_ne(img, layout.hsc_state(n, HscState::T_START));
            let d = mem::get_u64_ne(img, layout.hsc_state(n, HscState::SPAN));
            let off = u128::from(done + 1) * u128::from(d) / u128::from(steps);
            ta.saturating_add(u64::try_from(off).unwrap_or(u64::MAX))
        })
    }

    /// One unit step (§8.4): only while it counts ([`counting`]); in modes with external
    /// direction a step against the current direction turns it first.
    fn apply(&self, img: &mut [u8], layout: &Layout, tau: u64) {
        let n = self.n;
        let done = get_u32(img, layout, n, HscState::DONE);
        set_u32(img, layout, n, HscState::DONE, done.saturating_add(1));
        let Some((info, m)) = counting(img, layout, n) else {
            return;
        };
        let mut up = get(img, layout, n, HscState::DIR) != 0;
        if !m.internal_direction() {
            let step_up = get(img, layout, n, HscState::STEP_UP) != 0;
            if step_up != up {
                up = step_up;
                set(img, layout, n, HscState::DIR, u8::from(up));
                raise(img, layout, n, HscEvent::Direction, tau);
            }
        }
        step(img, layout, info, up, tau);
    }

    /// The step due at `tau`, then at once every further step of the interval due before
    /// `before` that raises nothing: no direction change and no CV = PV on the way (the step
    /// reaching PV is left to [`Counter::apply`], so its routine runs at its own time). Between
    /// such steps only their count is observable (no routine can run: nothing is queued), so a
    /// fast encoder costs a few steps per scan instead of one happening per pulse.
    fn apply_before(&self, img: &mut [u8], layout: &Layout, tau: u64, before: u64) {
        self.apply(img, layout, tau);
        if !interrupt::nothing_queued(img, layout) {
            return;
        }
        let n = self.n;
        let due = steps_due_before(img, layout, n, before);
        let silent = match counting(img, layout, n) {
            // Steps that do not count change nothing but the interval's progress.
            None => due,
            Some((_, m)) => {
                let up = get(img, layout, n, HscState::DIR) != 0;
                let turns =
                    !m.internal_direction() && (get(img, layout, n, HscState::STEP_UP) != 0) != up;
                if turns {
                    0
                } else {
                    due.min(steps_before_preset(img, layout, n, up))
                }
            }
        };
        if silent == 0 {
            return;
        }
        let done = get_u32(img, layout, n, HscState::DONE);
        set_u32(img, layout, n, HscState::DONE, done.saturating_add(silent));
        if let Some((info, _)) = counting(img, layout, n) {
            let up = get(img, layout, n, HscState::DIR) != 0;
            let cv = current(img, layout, n);
            // CV wraps at the DINT ends (module doc): `silent` steps are `silent` mod 2^32.
            let cv = if up {
                cv.wrapping_add(silent as i32)
            } else {
                cv.wrapping_sub(silent as i32)
            };
            set_current(img, layout, n, cv);
            update_status(img, layout, info);
        }
    }
}

/// Counter `n`'s info and mode when a step counts now (§8.4): defined, enabled, not held by
/// its reset input and, in modes 2, 5, 8 and 11, started by its start input; the levels are
/// the physical inputs, which hold the previous scan instant's while the interval phase runs.
fn counting(img: &[u8], layout: &Layout, n: u8) -> Option<(&'static HscInfo, Mode)> {
    let (info, m) = (info(layout, n)?, mode(img, layout, n)?);
    if get(img, layout, n, HscState::ENABLED) == 0 {
        return None;
    }
    let low = |field| get(img, layout, n, field) != 0;
    if let Some(r) = info.reset_input(m)
        && active(img, layout, r, low(HscState::RESET_LOW))
    {
        return None;
    }
    if let Some(s) = info.start_input(m)
        && !active(img, layout, s, low(HscState::START_LOW))
    {
        return None;
    }
    Some((info, m))
}

/// How many of counter `n`'s remaining steps in this interval are due before `before`: step
/// `j` (1-based) is due at `T_START + ⌊j·SPAN/STEPS⌋`, which is before `before` exactly when
/// `j·SPAN < (before − T_START)·STEPS`.
fn steps_due_before(img: &[u8], layout: &Layout, n: u8, before: u64) -> u32 {
    let steps = get_u32(img, layout, n, HscState::STEPS);
    let done = get_u32(img, layout, n, HscState::DONE);
    if done >= steps {
        return 0;
    }
    let ta = mem::get_u64_ne(img, layout.hsc_state(n, HscState::T_START));
    let span = mem::get_u64_ne(img, layout.hsc_state(n, HscState::SPAN));
    let Some(room) = before.checked_sub(ta).filter(|&r| r > 0) else {
        return 0;
    };
    let last = if span == 0 {
        u128::from(steps)
    } else {
        // The largest j with j·SPAN < room·STEPS.
        (u128::from(room) * u128::from(steps) - 1) / u128::from(span)
    };
    let last = u32::try_from(last.min(u128::from(steps))).unwrap_or(steps);
    last.saturating_sub(done)
}

/// How many steps in direction `up` counter `n` can take before one makes CV = PV (that one
/// raises the event): the distance to PV less one, modulo 2^32 (at CV = PV already, the next
/// 2^32 − 1 steps are clear).
fn steps_before_preset(img: &[u8], layout: &Layout, n: u8, up: bool) -> u32 {
    let cv = current(img, layout, n) as u32;
    let pv = get_u32(img, layout, n, HscState::PV);
    let distance = if up {
        pv.wrapping_sub(cv)
    } else {
        cv.wrapping_sub(pv)
    };
    distance.wrapping_sub(1)
}

/// One unit step of counter `info` in direction `up` at `tau`: CV, status, CV = PV event.
fn step(img: &mut [u8], layout: &Layout, info: &HscInfo, up: bool, tau: u64) {
    let n = info.number;
    let cv = current(img, layout, n);
    let cv = if up {
        cv.wrapping_add(1)
    } else {
        cv.wrapping_sub(1)
    };
    set_current(img, layout, n, cv);
    update_status(img, layout, info);
    if cv == get_u32(img, layout, n, HscState::PV) as i32 {
        raise(img, layout, n, HscEvent::CvEqPv, tau);
    }
}

/// A PTO pulse of the channel counter `n` watches completed at `tau` (§8.4 mode 12, §9.3):
/// one step in the counter's direction, if it is defined in mode 12 and enabled.
pub(crate) fn count_pulse(img: &mut [u8], layout: &Layout, n: u8, tau: u64) {
    let Some(info) = info(layout, n) else {
        return;
    };
    let counting = mode(img, layout, n).is_some_and(|m| m.0 == stljit_core::hsc::PULSE_MODE)
        && get(img, layout, n, HscState::ENABLED) != 0;
    if counting {
        let up = get(img, layout, n, HscState::DIR) != 0;
        step(img, layout, info, up, tau);
    }
}

/// Raises counter `n`'s event `kind` at `tau`, if the counter has that event.
fn raise(img: &mut [u8], layout: &Layout, n: u8, kind: HscEvent, tau: u64) {
    if let Some(e) = hsc_event(n, kind).filter(|&e| layout.profile.profile().interrupts.has(e)) {
        interrupt::raise(img, layout, e, tau);
    }
}

/// The reset inputs at the scan instant `tau` (§8.4, E2): a defined counter whose reset input
/// became active since the last instant (`prev_in`: the physical inputs then) is cleared and
/// raises "external reset". Called before `prev_in` takes the new inputs.
pub(crate) fn instant(img: &mut [u8], layout: &Layout, prev_in: u32, tau: u64) {
    for c in layout.profile.profile().hsc.iter() {
        let n = c.number;
        let Some(r) = mode(img, layout, n).and_then(|m| c.reset_input(m)) else {
            continue;
        };
        let low = get(img, layout, n, HscState::RESET_LOW) != 0;
        let was = mem::get_bit(img, prev_in + r.0, r.1) != low;
        if !was && active(img, layout, r, low) {
            set_current(img, layout, n, 0);
            update_status(img, layout, c);
            raise(img, layout, n, HscEvent::Reset, tau);
        }
    }
}
