//! Pulse outputs (s7-200-more.md §9), once for both engines: `PLS Q` ([`execute`], which
//! `ext::execute` runs for the interpreter and for the JIT's `stljit_rt_ext`), the PTO pulse
//! completions as a happening source of the interrupt machinery ([`Generator`], in
//! `interrupt::sources::HAPPENINGS` before the counters, the spec's `source_rank`), and the
//! override of the physical output at the end of the scan ([`override_outputs`], §9.5). The
//! channels per CPU and their registers are profile data (`stljit_core::pulse`); the state is
//! the SM registers plus the channel's `PulseState` record in the image.
//!
//! A PTO pulse is a happening at the end of its cycle (§9.3): it counts (total, segment, HSC
//! mode 12), then the next pulse, the next profile segment or the pipelined segment starts at
//! that instant, or the channel goes idle and raises its PTO-complete event. PWM has no
//! happenings: its level is a function of time (§9.4).
//!
//! Rules the spec leaves open, fixed here [design] (docs/semantics.md lists them):
//! * The registers hold time units; the cycle (and PWM width) last loaded by PLS stay the
//!   channel's values for a later PLS that does not update them (`LAST_CYCLE`, `WIDTH`), the
//!   cycle starting at 2 units, the width at 0, the PTO count at 1.
//! * PTO on a channel without PTO (`smart`, §9.1) is 0x0091 at run time, nothing changes.
//! * A profile segment with pulse count 0 counts 1 pulse (as the single-segment count); a
//!   profile table that does not fit in V is 0x0091.
//! * A delta calculation error (§9.3) stops the channel: idle (status .7 and .4), no event.
//! * Stopping with control bit 7 clear sets status .7 (idle) whatever ran.

use crate::interrupt::{
    self,
    sources::{Happening, SourceKind},
};
use crate::mem;
use stljit_core::interrupt::pulse_event;
use stljit_core::layout::{Layout, PulseState};
use stljit_core::pulse::PulseChannel;
use stljit_core::{Area, ErrorCode, Width};

/// Channel states (`PulseState::STATE`).
const IDLE: u8 = 0;
const PTO: u8 = 1;
const PWM: u8 = 2;

/// Status byte bits (§9.1).
const STATUS_DELTA_ERR: u8 = 1 << 4;
const STATUS_USER_ABORT: u8 = 1 << 5;
const STATUS_OVERFLOW: u8 = 1 << 6;
const STATUS_IDLE: u8 = 1 << 7;

/// Control byte bits (§9.1).
const CTRL_CYCLE: u8 = 1 << 0;
const CTRL_WIDTH: u8 = 1 << 1;
const CTRL_COUNT: u8 = 1 << 2;
const CTRL_MS: u8 = 1 << 3;
const CTRL_MULTI: u8 = 1 << 5;
const CTRL_PWM: u8 = 1 << 6;
const CTRL_ENABLE: u8 = 1 << 7;

/// The cycle time range in time units (§9.1, §9.3).
const MIN_CYCLE: u32 = 2;
const MAX_CYCLE: u32 = 65_535;

/// The status byte every channel has at RUN entry: idle (§9.2 [design]).
pub const STATUS_AT_RUN: u8 = STATUS_IDLE;

fn info(layout: &Layout, n: u8) -> Option<&'static PulseChannel> {
    layout.profile.profile().pulse.get(n)
}

fn sm(layout: &Layout, smb: u32) -> u32 {
    layout.base(Area::SM) + smb
}

fn get(img: &[u8], layout: &Layout, n: u8, f: u32) -> u8 {
    mem::get_u8(img, layout.pulse_state(n, f))
}

fn set(img: &mut [u8], layout: &Layout, n: u8, f: u32, v: u8) {
    mem::set_u8(img, layout.pulse_state(n, f), v);
}

fn get32(img: &[u8], layout: &Layout, n: u8, f: u32) -> u32 {
    mem::get_u32_ne(img, layout.pulse_state(n, f))
}

fn set32(img: &mut [u8], layout: &Layout, n: u8, f: u32, v: u32) {
    mem::set_u32_ne(img, layout.pulse_state(n, f), v);
}

fn start_of(img: &[u8], layout: &Layout, n: u8) -> u64 {
    mem::get_u64_ne(img, layout.pulse_state(n, PulseState::START))
}

fn set_start(img: &mut [u8], layout: &Layout, n: u8, t: u64) {
    mem::set_u64_ne(img, layout.pulse_state(n, PulseState::START), t);
}

/// Sets or clears `bits` of channel `c`'s status byte.
fn status(img: &mut [u8], layout: &Layout, c: &PulseChannel, bits: u8, on: bool) {
    let at = sm(layout, c.status_smb);
    let v = mem::get_u8(img, at);
    mem::set_u8(img, at, if on { v | bits } else { v & !bits });
}

/// RUN entry (§9.2): every channel's status byte is idle. The state records start zeroed.
pub fn run_entry(img: &mut [u8], layout: &Layout) {
    for c in layout.profile.profile().pulse.channels {
        mem::set_u8(img, sm(layout, c.status_smb), STATUS_AT_RUN);
    }
}

/// `v` units of `base` µs, or `None` outside the cycle range.
fn cycle_us(units: i64, base: u32) -> Option<u32> {
    let ok = (i64::from(MIN_CYCLE)..=i64::from(MAX_CYCLE)).contains(&units);
    ok.then(|| units as u32 * base)
}

/// `PLS channel` with power flow at the current virtual time (§9.2).
pub fn execute(img: &mut [u8], layout: &Layout, channel: u8) -> Result<(), ErrorCode> {
    let c = info(layout, channel).ok_or(ErrorCode::OperandRange)?;
    let n = channel;
    let now = interrupt::now(img, layout);
    let ctrl = mem::get_u8(img, sm(layout, c.control_smb()));
    let base = if ctrl & CTRL_MS != 0 { 1000 } else { 1 };
    let state = get(img, layout, n, PulseState::STATE);
    if ctrl & CTRL_ENABLE == 0 {
        if state == PTO {
            status(img, layout, c, STATUS_USER_ABORT, true);
        }
        stop(img, layout, c);
        return Ok(());
    }
    let want = if ctrl & CTRL_PWM != 0 { PWM } else { PTO };
    if want == PTO && !c.pto {
        return Err(ErrorCode::OperandRange);
    }
    let running_base = get32(img, layout, n, PulseState::BASE_US);
    if state != IDLE && (state != want || running_base != base) {
        return Err(ErrorCode::PulseRedefined);
    }
    let word = |img: &[u8], smw| mem::get_be(img, sm(layout, smw), Width::Word);
    if ctrl & CTRL_CYCLE != 0 {
        let units = word(img, c.cycle_smw()).max(MIN_CYCLE);
        set32(img, layout, n, PulseState::LAST_CYCLE, units);
    }
    let last_cycle = get32(img, layout, n, PulseState::LAST_CYCLE).max(MIN_CYCLE);
    if want == PWM {
        if ctrl & CTRL_WIDTH != 0 {
            let w = word(img, c.width_smw());
            set32(img, layout, n, PulseState::WIDTH, w);
        }
        set(img, layout, n, PulseState::STATE, PWM);
        set32(img, layout, n, PulseState::BASE_US, base);
        set32(img, layout, n, PulseState::CYCLE, last_cycle * base);
        set_start(img, layout, n, now);
        return Ok(());
    }
    if ctrl & CTRL_MULTI == 0 {
        if ctrl & CTRL_COUNT != 0 {
            let count = mem::get_be(img, sm(layout, c.count_smd()), Width::DWord).max(1);
            set32(img, layout, n, PulseState::LAST_COUNT, count);
        }
        let count = get32(img, layout, n, PulseState::LAST_COUNT).max(1);
        if state == IDLE {
            set(img, layout, n, PulseState::MULTI, 0);
            set(img, layout, n, PulseState::SEG_NO, 0);
            set32(img, layout, n, PulseState::BASE_US, base);
            begin_segment(img, layout, n, last_cycle * base, 0, count, now);
            status(img, layout, c, STATUS_IDLE, false);
        } else if get(img, layout, n, PulseState::PIPE_VALID) == 0 {
            set(img, layout, n, PulseState::PIPE_VALID, 1);
            set32(img, layout, n, PulseState::PIPE_CYCLE, last_cycle * base);
            set32(img, layout, n, PulseState::PIPE_COUNT, count);
        } else {
            status(img, layout, c, STATUS_OVERFLOW, true);
        }
        return Ok(());
    }
    if state != IDLE {
        return Err(ErrorCode::PulseRedefined);
    }
    let off = mem::get_be(img, sm(layout, c.table_smw()), Width::Word);
    let v_size = layout.area_size(Area::V);
    if off >= v_size {
        return Err(ErrorCode::OperandRange);
    }
    let nseg = mem::get_u8(img, layout.base(Area::V) + off);
    if nseg == 0 {
        return Err(ErrorCode::PulseNoSegments);
    }
    if off + 1 + 8 * u32::from(nseg) > v_size {
        return Err(ErrorCode::OperandRange);
    }
    set(img, layout, n, PulseState::MULTI, 1);
    set(img, layout, n, PulseState::NSEG, nseg);
    mem::set_u16_ne(
        img,
        layout.pulse_state(n, PulseState::PROFILE_OFF),
        off as u16,
    );
    set32(img, layout, n, PulseState::BASE_US, base);
    status(img, layout, c, STATUS_IDLE, false);
    profile_segment(img, layout, c, 1, now);
    Ok(())
}

/// Starts a segment at `t`: pulses of `cycle` µs changing by `delta` µs per pulse.
fn begin_segment(
    img: &mut [u8],
    layout: &Layout,
    n: u8,
    cycle: u32,
    delta: i32,
    count: u32,
    t: u64,
) {
    set(img, layout, n, PulseState::STATE, PTO);
    set32(img, layout, n, PulseState::CYCLE, cycle);
    set32(img, layout, n, PulseState::DELTA, delta as u32);
    set32(img, layout, n, PulseState::COUNT, count);
    set32(img, layout, n, PulseState::DONE_IN_SEG, 0);
    set_start(img, layout, n, t);
}

/// Starts profile segment `s` (1-based) of channel `c` at `t`, read from V now (§9.3); an
/// initial cycle outside the range is a delta calculation error.
fn profile_segment(img: &mut [u8], layout: &Layout, c: &PulseChannel, s: u8, t: u64) {
    let n = c.number;
    let off = u32::from(mem::get_u16_ne(
        img,
        layout.pulse_state(n, PulseState::PROFILE_OFF),
    ));
    let at = layout.base(Area::V) + off + 1 + 8 * (u32::from(s) - 1);
    let base = get32(img, layout, n, PulseState::BASE_US);
    let c0 = mem::get_be(img, at, Width::Word);
    let delta = i32::from(mem::get_i16_be(img, at + 2));
    let count = mem::get_be(img, at + 4, Width::DWord).max(1);
    set(img, layout, n, PulseState::SEG_NO, s);
    mem::set_u8(img, sm(layout, c.profile_smb), s);
    match cycle_us(i64::from(c0), base) {
        Some(cycle) => begin_segment(img, layout, n, cycle, delta * base as i32, count, t),
        None => delta_error(img, layout, c),
    }
}

/// The channel goes idle (status .7), its pipeline emptied.
fn stop(img: &mut [u8], layout: &Layout, c: &PulseChannel) {
    set(img, layout, c.number, PulseState::STATE, IDLE);
    set(img, layout, c.number, PulseState::PIPE_VALID, 0);
    status(img, layout, c, STATUS_IDLE, true);
}

fn delta_error(img: &mut [u8], layout: &Layout, c: &PulseChannel) {
    status(img, layout, c, STATUS_DELTA_ERR, true);
    stop(img, layout, c);
}

/// The level the generator of channel `n` drives at `t` (`None`: idle, the image drives).
fn level(img: &[u8], layout: &Layout, n: u8, t: u64) -> Option<bool> {
    let start = start_of(img, layout, n);
    let cycle = u64::from(get32(img, layout, n, PulseState::CYCLE));
    let phase = t.saturating_sub(start);
    match get(img, layout, n, PulseState::STATE) {
        PTO => Some(phase < cycle / 2),
        PWM => {
            let base = u64::from(get32(img, layout, n, PulseState::BASE_US));
            let width = u64::from(get32(img, layout, n, PulseState::WIDTH)) * base;
            Some(width >= cycle || (width > 0 && phase % cycle.max(1) < width))
        }
        _ => None,
    }
}

/// §9.5: after the output copy at `T_k` (`t_us`), the physical bit of each active channel's
/// output is the generator's level; the image bit is unchanged.
pub fn override_outputs(img: &mut [u8], layout: &Layout, t_us: u64) {
    for c in layout.profile.profile().pulse.channels {
        if let Some(high) = level(img, layout, c.number, t_us) {
            let (byte, bit) = c.output;
            if byte < layout.area_size(Area::Q) {
                mem::set_bit(img, layout.phys_out + byte, bit, high);
            }
        }
    }
}

/// Pulse channel `n` as a happening source: its PTO pulse completions.
pub(crate) struct Generator {
    /// The channel number.
    pub(crate) n: u8,
}

impl Happening for Generator {
    fn kind(&self) -> SourceKind {
        SourceKind::Pulse
    }

    fn next(&self, img: &[u8], layout: &Layout) -> Option<u64> {
        info(layout, self.n)?;
        (get(img, layout, self.n, PulseState::STATE) == PTO).then(|| {
            let cycle = get32(img, layout, self.n, PulseState::CYCLE);
            start_of(img, layout, self.n).saturating_add(u64::from(cycle))
        })
    }

    /// One pulse completes at `tau` (§9.3).
    fn apply(&self, img: &mut [u8], layout: &Layout, tau: u64) {
        let n = self.n;
        let Some(c) = info(layout, n) else {
            return;
        };
        let total = get32(img, layout, n, PulseState::TOTAL);
        set32(img, layout, n, PulseState::TOTAL, total.wrapping_add(1));
        let done = get32(img, layout, n, PulseState::DONE_IN_SEG).saturating_add(1);
        set32(img, layout, n, PulseState::DONE_IN_SEG, done);
        if let Some(h) = c.counter {
            crate::hsc::count_pulse(img, layout, h, tau);
        }
        if done < get32(img, layout, n, PulseState::COUNT) {
            let base = get32(img, layout, n, PulseState::BASE_US);
            let cycle = get32(img, layout, n, PulseState::CYCLE);
            let delta = get32(img, layout, n, PulseState::DELTA) as i32;
            let next = (i64::from(cycle) + i64::from(delta)) / i64::from(base.max(1));
            match cycle_us(next, base) {
                Some(us) => {
                    set32(img, layout, n, PulseState::CYCLE, us);
                    set_start(img, layout, n, tau);
                }
                None => delta_error(img, layout, c),
            }
            return;
        }
        let seg = get(img, layout, n, PulseState::SEG_NO);
        if get(img, layout, n, PulseState::MULTI) != 0
            && seg < get(img, layout, n, PulseState::NSEG)
        {
            profile_segment(img, layout, c, seg + 1, tau);
        } else if get(img, layout, n, PulseState::PIPE_VALID) != 0 {
            set(img, layout, n, PulseState::PIPE_VALID, 0);
            let cycle = get32(img, layout, n, PulseState::PIPE_CYCLE);
            let count = get32(img, layout, n, PulseState::PIPE_COUNT);
            begin_segment(img, layout, n, cycle, 0, count, tau);
        } else {
            stop(img, layout, c);
            if let Some(e) = pulse_event(n).filter(|&e| layout.profile.profile().interrupts.has(e))
            {
                interrupt::raise(img, layout, e, tau);
            }
        }
    }
}
