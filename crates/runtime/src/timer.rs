//! Timers (spec §5.2), as functions on the image bytes.
//!
//! A timer's visible state is its current value (area `TimerValue`, big-endian `i16` at `2n`) and
//! its bit (area `TimerBit`, byte `n`); the private state ([`TimerState`]) holds `run`, the TOF
//! phase, the kind and resolution written at cold start, and the preset seen at the last
//! execution (used by the clock refresh of 1-ms and 10-ms timers at scan start).
//!
//! The rules of an execution live in [`timer_rule`], written once over [`RuleOps`]
//! ([`crate::rule_ops`]): the interpreter runs it on plain integers through [`execute`] and
//! [`Timer::step`] (layout lookups, range check), the JIT by emitting it inline on the timer's
//! bytes (offsets fixed at compile time). Both paths read the bytes
//! through [`TimerFields::from_raw`] and the byte positions of [`TimerState`], so both engines
//! run the same rules on the same bytes. The one exception is the resolution an execution
//! credits time by: both take it from the program's declaration ([`declared_resolutions`]; spec
//! §5.2: "compile time, from the timer number"), the JIT as a constant, and the stored byte
//! only for a timer the program does not declare. The clock refresh at scan start reads the
//! byte, which cold start writes from the same declaration.

use crate::rule_ops::{Native, RuleOps};
use crate::rules::{Gate, GatePolicy};
use crate::{block, mem};
use stljit_core::ir::{Program, TimerKind};
use stljit_core::layout::{Layout, Sched, TIMER_STATE_SIZE, TimerState};
use stljit_core::{Area, ErrorCode};

/// Phase of an off-delay timer (the `TOF` byte of [`TimerState`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum TofPhase {
    /// Never switched on, or reset.
    Idle = 0,
    /// Input on: bit 1, CV 0.
    On = 1,
    /// Input went off: counting towards PT.
    Timing = 2,
    /// Reached PT: bit 0, CV = PT.
    Done = 3,
}

/// Bytes of a timer's private state block.
pub const STATE_BYTES: usize = TIMER_STATE_SIZE as usize;

const RUN: usize = TimerState::RUN as usize;
const TOF: usize = TimerState::TOF as usize;
const RES: usize = TimerState::RES as usize;
const PT: usize = TimerState::PT_CACHE as usize;

/// The fields of one timer the rules read and write, decoded from its value, bit and private
/// state bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timer {
    /// Current value.
    pub cv: i16,
    /// Timer bit.
    pub bit: bool,
    /// TON/TONR: timing active.
    pub run: bool,
    /// The TOF phase byte: a [`TofPhase`] as its number. Only a TOF execution reads it (any
    /// other byte counts as [`TofPhase::Idle`] there); TON and TONR leave it as it is.
    pub tof: u8,
    /// Preset seen at the last execution (for the clock refresh).
    pub pt_cache: i16,
    /// Resolution in ms (1, 10, 100; 0 for an unused timer). Read only.
    pub res: u8,
}

impl Timer {
    /// Decodes the fields from the timer's value bytes (big-endian), bit byte and private state
    /// block ([`TimerFields::from_raw`]; no indexing that can fail: the arrays have fixed
    /// sizes).
    #[inline]
    pub fn decode(value: &[u8; 2], bit: u8, state: &[u8; STATE_BYTES]) -> Timer {
        let raw = TimerFields {
            cv: i64::from(i16::from_be_bytes(*value)),
            bit: i64::from(bit),
            run: i64::from(state[RUN]),
            tof: i64::from(state[TOF]),
            pt_cache: i64::from(i16::from_ne_bytes([state[PT], state[PT + 1]])),
            res: i64::from(state[RES]),
        };
        let t = TimerFields::from_raw(&mut Native, raw);
        Timer {
            cv: t.cv as i16,
            bit: t.bit != 0,
            run: t.run != 0,
            tof: t.tof as u8,
            pt_cache: t.pt_cache as i16,
            res: t.res as u8,
        }
    }

    /// Writes the fields back; only the run, TOF and PT-cache bytes of the state block are
    /// written (kind and resolution are read only).
    #[inline]
    pub fn encode(&self, value: &mut [u8; 2], bit: &mut u8, state: &mut [u8; STATE_BYTES]) {
        *value = self.cv.to_be_bytes();
        *bit = u8::from(self.bit);
        state[RUN] = u8::from(self.run);
        state[TOF] = self.tof;
        [state[PT], state[PT + 1]] = self.pt_cache.to_ne_bytes();
    }

    /// Offsets of timer `n`'s value, bit and private state ([`Layout::timer_bytes`]).
    fn offsets(layout: &Layout, n: u16) -> (u32, u32, u32) {
        let [(v, _), (b, _), (s, _)] = layout.timer_bytes(n);
        (v, b, s)
    }

    fn load(img: &[u8], layout: &Layout, n: u16) -> Timer {
        let (v, b, s) = Timer::offsets(layout, n);
        let state = mem::get_array(img, s);
        Timer::decode(&mem::get_array(img, v), mem::get_u8(img, b), &state)
    }

    fn store(&self, img: &mut [u8], layout: &Layout, n: u16) {
        let (v, b, s) = Timer::offsets(layout, n);
        // Start from the current block: `encode` leaves the read-only bytes as they are.
        let (mut value, mut bit, mut state) = ([0; 2], 0, mem::get_array(img, s));
        self.encode(&mut value, &mut bit, &mut state);
        mem::set_array(img, v, value);
        mem::set_u8(img, b, bit);
        mem::set_array(img, s, state);
    }

    /// The fields as [`RuleOps`] values on plain integers.
    fn fields(&self) -> TimerFields<i64> {
        TimerFields {
            cv: i64::from(self.cv),
            bit: i64::from(self.bit),
            run: i64::from(self.run),
            tof: i64::from(self.tof),
            pt_cache: i64::from(self.pt_cache),
            res: i64::from(self.res),
        }
    }

    /// Executes `TON`/`TONR`/`TOF` on this timer (spec §5.2) under `gate`: [`timer_rule`] on
    /// plain integers. `d100` is the scan's 100-ms delta, credited only by a 100-ms timer.
    #[inline]
    pub fn step(&mut self, kind: TimerKind, input: bool, gate: Gate, preset: i16, d100: u32) {
        let (open, policy) = match gate {
            // The policy only matters for a closed gate.
            Gate::Open => (true, GatePolicy::S7Scr),
            Gate::Closed(policy) => (false, policy),
        };
        let t = self;
        let fields = t.fields();
        let inputs = TimerInputs {
            input: i64::from(input),
            gate: i64::from(open),
            preset: i64::from(preset),
            d100: i64::from(d100),
        };
        let next = timer_rule(&mut Native, kind, policy, fields, inputs);
        // The rule keeps every field in its type's range (CV saturates, flags are 0/1, the
        // phase a byte).
        t.cv = next.cv as i16;
        t.bit = next.bit != 0;
        t.run = next.run != 0;
        t.tof = next.tof as u8;
        t.pt_cache = next.pt_cache as i16;
    }
}

/// The fields of one timer [`timer_rule`] reads and writes, as [`RuleOps`] values: CV (as
/// `i16`), the bit, `run` and the PT cache, the TOF phase ([`TofPhase`] as its number) and the
/// resolution byte (read only).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimerFields<V> {
    /// Current value.
    pub cv: V,
    /// Timer bit (0/1).
    pub bit: V,
    /// TON/TONR: timing active (0/1).
    pub run: V,
    /// The TOF phase byte (raw: see [`TimerFields::from_raw`]).
    pub tof: V,
    /// Preset seen at the last execution.
    pub pt_cache: V,
    /// Resolution in ms (1, 10, 100; 0 for an unused timer).
    pub res: V,
}

impl<V: Copy> TimerFields<V> {
    /// The fields of a timer from its raw bytes, each as a [`RuleOps`] value: CV and PT cache
    /// already sign-extended, the bit, run, TOF and resolution bytes as they are. The bit is
    /// bit 0 of its byte and `run` any non-zero byte; the TOF byte stays raw (only
    /// [`timer_rule`]'s TOF case reads it, as a phase). Both engines decode through here, so a
    /// snapshot with odd private bytes runs alike.
    pub fn from_raw<O: RuleOps<V = V>>(o: &mut O, raw: TimerFields<V>) -> TimerFields<V> {
        TimerFields {
            bit: o.bit0(raw.bit),
            run: o.ne0(raw.run),
            ..raw
        }
    }
}

/// The inputs of one timer execution: `IN` (`S0`, 0/1), the gate (1 open, 0 closed), the
/// preset (as `i16`) and the scan's 100-ms delta (as `u32`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimerInputs<V> {
    /// `S0`.
    pub input: V,
    /// The gate: 1 open.
    pub gate: V,
    /// `PT`.
    pub preset: V,
    /// The scan's 100-ms delta ([`Sched::D100`]).
    pub d100: V,
}

/// Executes `TON`/`TONR`/`TOF` (spec §5.2) on `t`: the rules of a timer execution, the one
/// text both engines run ([`crate::rule_ops`]). Open gate: `IN = input`. Closed under
/// [`GatePolicy::S7Scr`]: `IN = 0`, and a TOF is forced idle (inactive SCR rule). Closed
/// under [`GatePolicy::OmronInterlock`]: TON resets, TONR and TOF are not executed. Only a
/// 100-ms timer credits `d100` (1-ms and 10-ms timers count in the clock refresh at scan
/// start, [`refresh`]).
pub fn timer_rule<O: RuleOps>(
    o: &mut O,
    kind: TimerKind,
    policy: GatePolicy,
    t: TimerFields<O::V>,
    x: TimerInputs<O::V>,
) -> TimerFields<O::V> {
    let zero = o.k(0);
    let hundred = o.k(100);
    let is_100ms = o.eq(t.res, hundred);
    let d = o.select(is_100ms, x.d100, zero);
    let on = o.and(x.input, x.gate);
    let next = match kind {
        TimerKind::On | TimerKind::Retentive => {
            // With IN on a running timer, CV = sat(CV + d); otherwise (starting, or IN off) a
            // TON's CV is 0 and a TONR's is held. With IN the bit is CV >= PT and the PT cache
            // takes PT; without, a TON's bit is 0 and a TONR's held. `run` = IN.
            let timing = o.and(on, t.run);
            let counted = o.sat_add(t.cv, d);
            let held = match kind {
                TimerKind::On => zero,
                _ => t.cv,
            };
            let cv = o.select(timing, counted, held);
            let reached = o.ge(cv, x.preset);
            let bit = match kind {
                TimerKind::On => o.and(on, reached),
                _ => o.select(on, reached, t.bit),
            };
            TimerFields {
                cv,
                bit,
                run: on,
                tof: t.tof,
                pt_cache: o.select(on, x.preset, t.pt_cache),
                res: t.res,
            }
        }
        TimerKind::Off => tof_rule(o, t, x, on, d),
    };
    match policy {
        GatePolicy::S7Scr => next,
        GatePolicy::OmronInterlock => {
            // Closed: a TON resets (`run`, CV and bit cleared), the others keep every field.
            let closed = o.not(x.gate);
            let kept = match kind {
                TimerKind::On => TimerFields {
                    cv: zero,
                    bit: zero,
                    run: zero,
                    ..t
                },
                _ => t,
            };
            TimerFields {
                cv: o.select(closed, kept.cv, next.cv),
                bit: o.select(closed, kept.bit, next.bit),
                run: o.select(closed, kept.run, next.run),
                tof: o.select(closed, kept.tof, next.tof),
                pt_cache: o.select(closed, kept.pt_cache, next.pt_cache),
                res: t.res,
            }
        }
    }
}

/// A TOF execution (part of [`timer_rule`]). With the gate closed: idle, bit 0, CV 0. With IN
/// on: phase On, bit 1, CV 0. With IN off: a timer that was On starts timing (CV counts from
/// the next scan), a timing one counts; a timing timer takes PT into its cache, and on
/// reaching it stops at CV = PT with the bit off (Done).
fn tof_rule<O: RuleOps>(
    o: &mut O,
    t: TimerFields<O::V>,
    x: TimerInputs<O::V>,
    on: O::V,
    d: O::V,
) -> TimerFields<O::V> {
    let [idle, phase_on, timing, done] = [
        TofPhase::Idle,
        TofPhase::On,
        TofPhase::Timing,
        TofPhase::Done,
    ]
    .map(|p| o.k(p as i64));
    // A byte that is no phase reads as Idle.
    let beyond = o.k(TofPhase::Done as i64 + 1);
    let is_phase = o.lt(t.tof, beyond);
    let phase = o.select(is_phase, t.tof, idle);
    let was_on = o.eq(phase, phase_on);
    let was_timing = o.eq(phase, timing);
    let tof = o.select(was_on, timing, phase);
    let counted = o.sat_add(t.cv, d);
    let cv = o.select(was_timing, counted, t.cv);
    let is_timing = o.or(was_on, was_timing);
    let pt_cache = o.select(is_timing, x.preset, t.pt_cache);
    let reached = o.ge(cv, x.preset);
    let finished = o.and(is_timing, reached);
    let cv = o.select(finished, x.preset, cv);
    let zero = o.k(0);
    let bit = o.select(finished, zero, t.bit);
    let tof = o.select(finished, done, tof);
    // `falling`: gate open, IN off, the case above; otherwise the bit is IN (1 when on, 0
    // when the gate is closed), CV is 0 and the phase On or Idle.
    let off = o.not(on);
    let falling = o.and(x.gate, off);
    let forced = o.select(on, phase_on, idle);
    TimerFields {
        cv: o.select(falling, cv, zero),
        bit: o.select(falling, bit, on),
        run: t.run,
        tof: o.select(falling, tof, forced),
        pt_cache: o.select(falling, pt_cache, t.pt_cache),
        res: t.res,
    }
}

fn check(layout: &Layout, n: u16) -> Result<(), ErrorCode> {
    block::object_run(layout, Area::TimerBit, n, 1).map(drop)
}

/// The resolution in ms each timer number runs with, indexed by number: its declaration's
/// (`TimerDecl::resolution`; spec §5.2: "compile time, from the timer number"), `None` for a
/// number the program does not declare. Both engines take an execution's resolution from here,
/// the JIT as a constant, so a resolution byte a restored snapshot changed does not matter.
pub fn declared_resolutions(program: &Program) -> Vec<Option<u8>> {
    let mut res = Vec::new();
    for t in &program.timers {
        let n = usize::from(t.id.0);
        if res.len() <= n {
            res.resize(n + 1, None);
        }
        res[n] = Some(t.resolution.millis() as u8);
    }
    res
}

/// Executes `TON`/`TONR`/`TOF Tn, PT` (spec §5.2) on the image: [`Timer::step`] with the scan's
/// `d100`. `input` is `S0`; `gate` the gate it runs under; `res` the timer's resolution from
/// [`declared_resolutions`] (`None`: the resolution byte stored at cold start). Errors only for
/// a timer the profile lacks.
#[allow(clippy::too_many_arguments)]
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    n: u16,
    kind: TimerKind,
    input: bool,
    gate: Gate,
    preset: i16,
    res: Option<u8>,
) -> Result<(), ErrorCode> {
    check(layout, n)?;
    let mut t = Timer::load(img, layout, n);
    if let Some(res) = res {
        t.res = res;
    }
    let d100 = mem::sched_u32(img, layout, Sched::D100);
    t.step(kind, input, gate, preset, d100);
    t.store(img, layout, n);
    Ok(())
}

/// Clock refresh of a 1-ms or 10-ms timer at scan start (spec §5.2 `refresh`), using the kind
/// and resolution stored at cold start: [`refresh_applies`], then [`refresh_rule`] on plain
/// integers. 100-ms and unused timers are left alone.
pub fn refresh(img: &mut [u8], layout: &Layout, n: u16) {
    if check(layout, n).is_err() {
        return;
    }
    // Every scan visits every timer in use: decide on the kind and resolution bytes alone
    // before decoding the whole timer.
    let (_, _, s) = Timer::offsets(layout, n);
    let kind = i64::from(mem::get_u8(img, s + TimerState::KIND));
    let res = i64::from(mem::get_u8(img, s + TimerState::RES));
    if refresh_applies(&mut Native, kind, res) == 0 {
        return;
    }
    let d1 = i64::from(mem::sched_u32(img, layout, Sched::D1));
    let d10 = i64::from(mem::sched_u32(img, layout, Sched::D10));
    let mut t = Timer::load(img, layout, n);
    let next = refresh_rule(&mut Native, kind, t.fields(), d1, d10);
    // The rule keeps every field in its type's range (CV saturates or takes the PT cache,
    // flags are 0/1, the phase a byte).
    t.cv = next.cv as i16;
    t.bit = next.bit != 0;
    t.tof = next.tof as u8;
    t.store(img, layout, n);
}

/// Whether the clock refresh touches a timer whose kind byte ([`TimerState::KIND`]) is `kind`
/// and resolution byte `res`: one the program uses (kind not 0) at 1 or 10 ms. Written over
/// [`RuleOps`] for both engines, like [`refresh_rule`].
pub fn refresh_applies<O: RuleOps>(o: &mut O, kind: O::V, res: O::V) -> O::V {
    let used = o.ne0(kind);
    let one = o.k(1);
    let ten = o.k(10);
    let is_1 = o.eq(res, one);
    let is_10 = o.eq(res, ten);
    let clocked = o.or(is_1, is_10);
    o.and(used, clocked)
}

/// The clock refresh of one timer that [`refresh_applies`] to (spec §5.2 `refresh`), on its
/// decoded fields ([`TimerFields::from_raw`]) with the scan's 1-ms and 10-ms deltas: a
/// running TON or TONR counts and its bit is `CV >= PT cache`; a timing TOF counts and, on
/// reaching its PT cache, stops there with the bit off (Done). Anything else keeps its
/// fields. The one text both engines run ([`crate::rule_ops`]): the runtime through
/// [`refresh`], the JIT inline in its scan prologue.
pub fn refresh_rule<O: RuleOps>(
    o: &mut O,
    kind: O::V,
    t: TimerFields<O::V>,
    d1: O::V,
    d10: O::V,
) -> TimerFields<O::V> {
    let one = o.k(1);
    let is_1 = o.eq(t.res, one);
    let d = o.select(is_1, d1, d10);
    let [on, retentive, off] =
        [TimerKind::On, TimerKind::Retentive, TimerKind::Off].map(|k| o.k(i64::from(k.code())));
    let [timing, done] = [TofPhase::Timing, TofPhase::Done].map(|p| o.k(p as i64));
    let is_on = o.eq(kind, on);
    let is_retentive = o.eq(kind, retentive);
    let on_kind = o.or(is_on, is_retentive);
    let on_running = o.and(on_kind, t.run);
    let is_off = o.eq(kind, off);
    let was_timing = o.eq(t.tof, timing);
    let off_timing = o.and(is_off, was_timing);
    let counts = o.or(on_running, off_timing);
    let counted = o.sat_add(t.cv, d);
    let cv = o.select(counts, counted, t.cv);
    let reached = o.ge(cv, t.pt_cache);
    let finished = o.and(off_timing, reached);
    let zero = o.k(0);
    let bit = o.select(on_running, reached, t.bit);
    TimerFields {
        cv: o.select(finished, t.pt_cache, cv),
        bit: o.select(finished, zero, bit),
        run: t.run,
        tof: o.select(finished, done, t.tof),
        pt_cache: t.pt_cache,
        res: t.res,
    }
}

/// `R Tn, N`: full reset of `count` timers from `first`: CV 0, bit 0, timing stopped, TOF idle
/// (spec §5.2). Past the last timer: 0x0091, nothing reset (spec M11); `count = 0` is a no-op
/// (M12).
pub fn reset_range(
    img: &mut [u8],
    layout: &Layout,
    first: u16,
    count: u32,
) -> Result<(), ErrorCode> {
    for n in block::object_run(layout, Area::TimerBit, first, count)? {
        let mut t = Timer::load(img, layout, n);
        t.cv = 0;
        t.bit = false;
        t.run = false;
        t.tof = TofPhase::Idle as u8;
        t.store(img, layout, n);
    }
    Ok(())
}

#[cfg(test)]
#[path = "timer_tests.rs"]
mod tests;
