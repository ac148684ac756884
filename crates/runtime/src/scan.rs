//! The scan cycle around the program body (spec §2.1): [`begin`] does steps 1–4 and the per-scan
//! resets of step 5, [`end`] does steps 6–8. Both engines call these functions, so time, SMB0,
//! the clock-driven timer refresh and the output copy exist once; the JIT's inline scan path
//! writes the stores of [`begin`] and [`end`] from the facts exported here, emits the clock
//! refresh from its rule ([`timer::refresh_rule`]) and calls [`interval_events`] and
//! [`instant_events`], the parts of `begin` that are more.
//!
//! A program with interrupt routines, high-speed counters, pulse outputs or communication runs
//! the event phases of s7-200-more §3.6.2 inside [`begin`] ([`crate::interrupt`]): E1 after the
//! time step and the resets (before the inputs are read), E2 after the clock refresh. The
//! engine passes an [`Isr`] that runs a routine's body; a fatal error in a routine aborts the
//! scan ([`Begin::Fatal`]).
//!
//! Rules fixed here (spec leaves them open):
//! * **STOP.** A scan on an image already in STOP (`Sched::MODE = 1`) runs nothing: [`begin`]
//!   forces the physical outputs to 0 (spec §2.5 "outputs forced to 0") and returns `false`; the
//!   engine then reports [`ScanStatus::Stopped`] without calling [`end`]. Time, SMB0 and the scan
//!   number do not move while stopped.
//! * **SMW22/24/26** (scan times) stay 0: a scan takes zero virtual time, so any other value
//!   would be invented.
//! * **Time running backwards** (`t_ms` below the previous scan's time) credits no time: the
//!   deltas saturate at 0 and `T_PREV` records the previous time as is.
//! * **Watchdog.** Every loop-budget event increments `LOOP_COUNT`; the event that makes it
//!   exceed `LOOP_LIMIT` is fatal (so a limit of N allows exactly N back-edges per scan).
//!
//! What the prologue and epilogue touch is proportional to the program, not to the profile: a
//! [`ScanPlan`] computed once per program lists the timers the clock refreshes (only the 1-ms
//! and 10-ms timers the program declares can change at a scan start), and the I/O images are
//! copied as whole blocks. A program-agnostic caller uses [`ScanPlan::every_timer`], which
//! visits every timer as the rule is written; both plans give the same bytes for any image a
//! program's cold start produced, because only declared timers have a kind (`Image::cold_start`).

use crate::interrupt::sources::Sources;
use crate::interrupt::{self, Isr};
use crate::mem;
use crate::timer;
use stljit_core::interrupt::MAX_ROUTINE;
use stljit_core::ir::Program;
use stljit_core::layout::{Layout, SCHED_SIZE, Sched};
use stljit_core::omron::{self, SystemBit};
use stljit_core::profile::Resolution;
use stljit_core::{Area, ErrorCode, Family, FatalCode, PouId, ScanStatus};

/// The time-step fields besides `T_PREV`/`T_NOW` (spec §2.1 step 1): `(field, div)`, each
/// `t / div − t_prev / div` saturated to `u32`, 0 in the first scan.
pub const DELTAS: [(u32, u64); 3] = [(Sched::D1, 1), (Sched::D10, 10), (Sched::D100, 100)];

/// The gate (SCR enable, Omron interlock and step) at the start of every task: open.
pub const GATE_OPEN: (u32, u8) = (Sched::SCR_ENABLE, 1);

/// The one-byte resets of step 5, `(field, value)`; the `u32` `LOOP_COUNT` is reset to 0 too.
pub const RESETS: [(u32, u8); 3] = [(Sched::ENO, 0), GATE_OPEN, (Sched::STOP_REQ, 0)];

/// SMB0 (spec §2.3): the bits always ON (SM0.0, SM0.7).
pub const SMB0_ALWAYS: u8 = 0x81;
/// SMB0's clock bits `(bit, period in ms)`: ON in the first half of each period (SM0.4, SM0.5),
/// that is while `t / (period / 2)` is even.
pub const SMB0_CLOCKS: [(u8, u64); 2] = [(4, 60_000), (5, 1000)];
/// SMB0's scan-parity bit (SM0.6): ON on even scan numbers.
pub const SMB0_EVEN_SCAN: u8 = 6;
/// SMB0's first-scan bits (SM0.1, SM0.3); SM0.2 ([`SMB0_LOST`]) also when retentive data was
/// lost.
pub const SMB0_FIRST: u8 = 0b1010;
/// SM0.2: retentive data lost, in the first scan only.
pub const SMB0_LOST: u8 = 0b100;

/// SMB0 for a scan at `t_ms` with number `scan_no`.
fn smb0(t_ms: u64, scan_no: u64, first: bool, lost: bool) -> u8 {
    let mut v = SMB0_ALWAYS;
    if first {
        v |= SMB0_FIRST | if lost { SMB0_LOST } else { 0 };
    }
    for (bit, period) in SMB0_CLOCKS {
        v |= u8::from((t_ms / (period / 2)).is_multiple_of(2)) << bit;
    }
    v | u8::from(scan_no.is_multiple_of(2)) << SMB0_EVEN_SCAN
}

/// What one program's scan prologue touches (module doc): computed once, read every scan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScanPlan {
    /// The profile's family (which system bits step 3 writes).
    family: Family,
    /// The timers step 4 refreshes from the clock, in ascending number.
    clock_timers: Box<[u16]>,
    /// The interrupt routines by number (empty: the program has none).
    routines: Box<[Option<PouId>]>,
    /// The program defines a high-speed counter, whose steps the event phases apply.
    hsc: bool,
    /// The program has a PLS, whose pulse trains the event phases advance.
    pulse: bool,
    /// The program starts communication (XMT, RCV, network jobs), which the event phases
    /// complete.
    ports: bool,
    /// The happening sources the event phases visit (from the four fields above).
    sources: Sources,
}

impl ScanPlan {
    /// The plan of `program`: its 1-ms and 10-ms timers, where the profile's family refreshes
    /// timers from the clock (S7; Omron timers update only when they execute).
    pub fn of(program: &Program) -> ScanPlan {
        let profile = program.profile.profile();
        let mut clock_timers: Vec<u16> = if profile.family.clock_refreshed_timers() {
            program
                .timers
                .iter()
                .filter(|t| t.id.0 < profile.timers)
                .filter(|t| matches!(t.resolution, Resolution::Ms1 | Resolution::Ms10))
                .map(|t| t.id.0)
                .collect()
        } else {
            Vec::new()
        };
        clock_timers.sort_unstable();
        clock_timers.dedup();
        let mut routines = Vec::new();
        if program.has_interrupts() {
            routines.resize(usize::from(MAX_ROUTINE) + 1, None);
            for (i, pou) in program.pous.iter().enumerate() {
                if let Some(slot) = pou
                    .kind
                    .interrupt()
                    .and_then(|n| routines.get_mut(usize::from(n)))
                {
                    *slot = Some(PouId::new(i));
                }
            }
        }
        let (hsc, pulse, ports) = (
            program.defines_hsc(),
            program.uses_pulse(),
            program.uses_ports(),
        );
        ScanPlan {
            family: profile.family,
            clock_timers: clock_timers.into(),
            sources: Sources::new(hsc, pulse, !routines.is_empty(), ports),
            routines: routines.into(),
            hsc,
            pulse,
            ports,
        }
    }

    /// Whether the program has interrupt routines.
    pub fn has_interrupts(&self) -> bool {
        !self.routines.is_empty()
    }

    /// Whether [`begin`] runs the event phases: the program has interrupt routines,
    /// high-speed counters, pulse outputs or communication. An engine's inline scan path must
    /// then call [`interval_events`] and [`instant_events`] where `begin` does.
    pub fn has_events(&self) -> bool {
        self.has_interrupts() || self.hsc || self.pulse || self.ports
    }

    /// What the event phases need: the routines, and the happening sources the program can
    /// set going (a counter without `HDEF`, a pulse output without `PLS`, ... stays idle).
    pub fn events(&self) -> interrupt::Events<'_> {
        interrupt::Events {
            routines: &self.routines,
            sources: self.sources,
        }
    }

    /// Whether the program has a PLS, whose active generators [`end`] lets drive their
    /// outputs (an engine's inline epilogue has no such step).
    pub fn has_pulse_outputs(&self) -> bool {
        self.pulse
    }

    /// The timers step 4 refreshes from the clock.
    pub fn clock_timers(&self) -> &[u16] {
        &self.clock_timers
    }

    /// The profile family the plan is for.
    pub fn family(&self) -> Family {
        self.family
    }

    /// Every timer of `layout`'s profile: the rule as written, for callers that run an image
    /// without its program (tests, tools).
    pub fn every_timer(layout: &Layout) -> ScanPlan {
        let family = layout.profile.profile().family;
        let n = if family.clock_refreshed_timers() {
            layout.area_size(Area::TimerBit).min(u32::from(u16::MAX)) as u16
        } else {
            0
        };
        ScanPlan {
            family,
            clock_timers: (0..n).collect(),
            routines: Box::new([]),
            hsc: false,
            pulse: false,
            ports: false,
            sources: Sources::new(false, false, false, false),
        }
    }
}

/// What [`begin`] leaves the engine to do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum Begin {
    /// The PLC is in STOP: run nothing, do not call [`end`]; the scan is `Stopped`.
    Stopped = 0,
    /// Run the main program, then call [`end`] with its status.
    Run = 1,
    /// An interrupt routine (or the event phase) ended in a fatal error, recorded in the
    /// image: skip the main program and call [`end`] with `Fatal` (spec §3.6.4).
    Fatal = 2,
}

/// The scheduler block of an image (`Sched`), bounds-checked once: every field is at a
/// constant offset inside the fixed-size array, so the accessors' own checks fold away.
struct SchedBlock<'a>(&'a mut [u8; SCHED_SIZE as usize]);

impl<'a> SchedBlock<'a> {
    /// The block of `img`, or `None` if the image is too short for its layout (never for an
    /// image of that layout).
    fn of(img: &'a mut [u8], layout: &Layout) -> Option<SchedBlock<'a>> {
        let at = layout.sched as usize;
        let bytes = img.get_mut(at..at.checked_add(SCHED_SIZE as usize)?)?;
        bytes.try_into().ok().map(SchedBlock)
    }

    fn u8(&self, field: u32) -> u8 {
        mem::get_u8(self.0, field)
    }

    fn set_u8(&mut self, field: u32, v: u8) {
        mem::set_u8(self.0, field, v);
    }

    fn u64(&self, field: u32) -> u64 {
        mem::get_u64_ne(self.0, field)
    }

    fn set_u64(&mut self, field: u32, v: u64) {
        mem::set_u64_ne(self.0, field, v);
    }

    fn set_u32(&mut self, field: u32, v: u32) {
        mem::set_u32_ne(self.0, field, v);
    }
}

/// Copies `len` image bytes from `src` to `dst` as one block (nothing when either range is
/// outside the image; the layout's ranges never are).
fn copy_block(img: &mut [u8], src: u32, dst: u32, len: u32) {
    let (src, dst, len) = (src as usize, dst as usize, len as usize);
    if src.saturating_add(len) <= img.len() && dst.saturating_add(len) <= img.len() {
        img.copy_within(src..src + len, dst);
    }
}

/// Steps 1–4 of a scan plus the resets of step 5, for the program whose plan is `plan`; with
/// interrupt routines, also the event phases E1 and E2 (module doc), whose routines `isr` runs.
/// Returns [`Begin::Stopped`] (having done only the STOP rule of the module doc) when the image
/// is in STOP.
pub fn begin(
    img: &mut [u8],
    layout: &Layout,
    plan: &ScanPlan,
    t_ms: u64,
    isr: &mut dyn Isr,
) -> Begin {
    let Some(mut sched) = SchedBlock::of(img, layout) else {
        return Begin::Stopped;
    };
    if sched.u8(Sched::MODE) != 0 {
        let out = layout.phys_out as usize;
        let len = layout.area_size(Area::Q) as usize;
        if let Some(q) = img.get_mut(out..out.saturating_add(len)) {
            q.fill(0);
        }
        return Begin::Stopped;
    }
    let first = sched.u8(Sched::FIRST_SCAN) != 0;

    // Step 1: time. Scan 0 has t_prev = 0 and no deltas (spec §2.1).
    let t_prev = if first { 0 } else { sched.u64(Sched::T_NOW) };
    for (field, div) in DELTAS {
        let d = if first {
            0
        } else {
            (t_ms / div).saturating_sub(t_prev / div)
        };
        sched.set_u32(field, u32::try_from(d).unwrap_or(u32::MAX));
    }
    sched.set_u64(Sched::T_PREV, t_prev);
    sched.set_u64(Sched::T_NOW, t_ms);
    // Step 5 resets (nothing below reads them but the interrupt routines, which count against
    // the scan's loop budget and may request STOP).
    for (field, v) in RESETS {
        sched.set_u8(field, v);
    }
    sched.set_u32(Sched::LOOP_COUNT, 0);
    let scan_no = sched.u64(Sched::SCAN_NO);
    let lost = sched.u8(Sched::RETENTIVE_LOST) != 0;

    if first && plan.family == Family::S7 {
        // RUN entry (s7-200-more §9.2): the pulse outputs are idle.
        crate::pulse::run_entry(img, layout);
    }
    // E1 (s7-200-more §3.6.2 step 2): the interval since the previous scan; none in scan 0.
    if !first && interval_events(img, layout, plan, isr, t_prev, t_ms).is_err() {
        return Begin::Fatal;
    }

    // Step 2: the I image is overwritten from the physical inputs (AI is latched by the harness
    // writing the AI area directly).
    copy_block(
        img,
        layout.phys_in,
        layout.base(Area::I),
        layout.area_size(Area::I),
    );

    match plan.family {
        Family::S7 => {
            // Step 3: SMB0 (spec §2.3). SMB1 keeps its bits.
            let v = smb0(t_ms, scan_no, first, lost);
            mem::set_u8(img, layout.base(Area::SM), v);
        }
        Family::Omron => {
            omron_system_bits(img, layout, t_ms, first);
            clear_condition_flags(img, layout);
        }
    }

    // Step 4, then E2 (§3.6.2 step 5).
    refresh_clock_timers(img, layout, plan);
    if instant_events(img, layout, plan, isr, t_ms).is_err() {
        return Begin::Fatal;
    }
    Begin::Run
}

/// [`begin`]'s phase E1 in a scan after the first (s7-200-more §3.6.2 step 2), after the
/// time step and the resets, before the inputs are read: the events of the interval since the
/// previous scan at `t_prev_ms`, for a program with events ([`ScanPlan::has_events`]). Public
/// for an engine that does the rest of [`begin`] itself (the JIT's inline scan path).
#[inline]
pub fn interval_events(
    img: &mut [u8],
    layout: &Layout,
    plan: &ScanPlan,
    isr: &mut dyn Isr,
    t_prev_ms: u64,
    t_ms: u64,
) -> Result<(), interrupt::PhaseFatal> {
    if !plan.has_events() {
        return Ok(());
    }
    let (ta, tb) = (micros(t_prev_ms), micros(t_ms));
    interrupt::interval_phase(img, layout, plan.events(), isr, ta, tb)
}

/// Step 4 of [`begin`]: the clock-driven refresh of the 1-ms and 10-ms timers the program
/// declares ([`timer::refresh`], whose rule the JIT's inline scan path emits itself).
#[inline]
pub fn refresh_clock_timers(img: &mut [u8], layout: &Layout, plan: &ScanPlan) {
    for &n in plan.clock_timers.iter() {
        timer::refresh(img, layout, n);
    }
}

/// The events of the scan instant `t_ms` (s7-200-more §3.6.2 step 5), after step 4: the
/// serial ports' instant (§10) and phase E2. Public like [`interval_events`].
#[inline]
pub fn instant_events(
    img: &mut [u8],
    layout: &Layout,
    plan: &ScanPlan,
    isr: &mut dyn Isr,
    t_ms: u64,
) -> Result<(), interrupt::PhaseFatal> {
    if plan.ports {
        crate::comm::instant(img, layout);
    }
    if !plan.has_events() {
        return Ok(());
    }
    interrupt::instant_phase(img, layout, plan.events(), isr, micros(t_ms))
}

/// A virtual time in ms as the µs of the event machinery (s7-200-more §0.3).
fn micros(t_ms: u64) -> u64 {
    t_ms.saturating_mul(1000)
}

/// What is reset at the start of every task (omron-cp.md §2.3): the instruction conditions
/// are released (the gate, which an S7 SCR segment or an Omron interlock or step closes, is
/// [`GATE_OPEN`]) and the condition flags cleared. [`begin`] does both for the scan's first task
/// (the gate among its [`RESETS`]); `Op::TaskStart` runs this before every later cyclic task
/// of an Omron program.
pub fn task_start(img: &mut [u8], layout: &Layout) {
    let (gate, open) = GATE_OPEN;
    mem::set_sched_u8(img, layout, gate, open);
    clear_condition_flags(img, layout);
}

/// The Omron condition flags (§1.8 rule 2: cleared at every task start) OFF; the system bits
/// sharing their bytes are kept. Nothing on a profile without the `Flags` area.
fn clear_condition_flags(img: &mut [u8], layout: &Layout) {
    if layout.area_size(Area::Flags) >= 2 {
        let at = layout.base(Area::Flags);
        let word = u16::from_le_bytes([mem::get_u8(img, at), mem::get_u8(img, at + 1)]);
        let [lo, hi] = (word & !SystemBit::CONDITION_FLAGS).to_le_bytes();
        mem::set_u8(img, at, lo);
        mem::set_u8(img, at + 1, hi);
    }
}

/// The Omron system bits of the cycle, omron-cp.md §2.2 step 3: `P_On` = 1, `P_Off` = 0, the
/// clock pulses from `t_ms` (50 % duty, ON half first, §2.12) and `A200.11`
/// (`P_First_Cycle`) ON in the first cycle only. The condition flags that share their bytes
/// are kept here; `clear_condition_flags` clears them.
fn omron_system_bits(img: &mut [u8], layout: &Layout, t_ms: u64, first: bool) {
    let mut bits: u32 = 1 << SystemBit::On.index();
    for (pulse, period) in SystemBit::PULSES {
        if t_ms % period < period / 2 {
            bits |= 1 << pulse.index();
        }
    }
    let base = layout.base(Area::Flags);
    let flags = u32::from(SystemBit::CONDITION_FLAGS);
    for (i, (b, keep)) in bits
        .to_le_bytes()
        .into_iter()
        .zip(flags.to_le_bytes())
        .enumerate()
    {
        let at = base + i as u32;
        mem::set_u8(img, at, (mem::get_u8(img, at) & keep) | b);
    }
    if let Some((a, bit)) = omron::first_cycle_bit(layout) {
        let old = mem::get_u8(img, a);
        let mask = 1 << bit;
        mem::set_u8(img, a, if first { old | mask } else { old & !mask });
    }
}

/// Steps 6–8: unless `status` is [`ScanStatus::Fatal`], copy Q to the physical outputs; a STOP
/// request or a fatal error puts the PLC in STOP. Returns the scan's final status (`Stopped` when
/// a STOP executed).
pub fn end(img: &mut [u8], layout: &Layout, status: ScanStatus) -> ScanStatus {
    if status != ScanStatus::Fatal {
        copy_block(
            img,
            layout.base(Area::Q),
            layout.phys_out,
            layout.area_size(Area::Q),
        );
        // §3.6.2 step 7: active pulse generators drive their outputs (§9.5).
        let t_us = micros(mem::get_u64_ne(img, layout.sched(Sched::T_NOW)));
        crate::pulse::override_outputs(img, layout, t_us);
    }
    let Some(mut sched) = SchedBlock::of(img, layout) else {
        return ScanStatus::Fatal;
    };
    let status = if status == ScanStatus::Fatal {
        sched.set_u8(Sched::MODE, 1);
        ScanStatus::Fatal
    } else if sched.u8(Sched::STOP_REQ) != 0 || status == ScanStatus::Stopped {
        sched.set_u8(Sched::MODE, 1);
        ScanStatus::Stopped
    } else {
        ScanStatus::Ok
    };
    sched.set_u8(Sched::FIRST_SCAN, 0);
    let k = sched.u64(Sched::SCAN_NO);
    sched.set_u64(Sched::SCAN_NO, k.wrapping_add(1));
    status
}

/// One whole scan around `body` (which executes the main program and returns `Ok` or
/// `Fatal`), with `isr` running the interrupt routines.
pub fn run(
    img: &mut [u8],
    layout: &Layout,
    plan: &ScanPlan,
    t_ms: u64,
    isr: &mut dyn Isr,
    body: impl FnOnce(&mut [u8], &Layout) -> ScanStatus,
) -> ScanStatus {
    let status = match begin(img, layout, plan, t_ms, isr) {
        Begin::Stopped => return ScanStatus::Stopped,
        Begin::Fatal => ScanStatus::Fatal,
        Begin::Run => body(img, layout),
    };
    end(img, layout, status)
}

/// SM4.3 (`RUN_Err`), `(SM byte, bit)`: set by every non-fatal run-time error, cleared only
/// at RUN entry, that is at cold start (s7-200-more §0.4).
pub const RUN_ERR: (u32, u8) = (4, 3);

/// The image offset and bit of SM4.3 in `layout`, if its profile has an SM area that holds it
/// (the Omron profiles have none). The JIT inlines the same bit from here.
pub fn run_err_bit(layout: &Layout) -> Option<(u32, u8)> {
    let (byte, bit) = RUN_ERR;
    (byte < layout.area_size(Area::SM)).then(|| (layout.base(Area::SM) + byte, bit))
}

/// Records a non-fatal error (spec §2.5): `LAST_ERR`, `ERR_POU`, `ERR_OP`, and SM4.3 := 1.
/// ENO is the caller's.
pub fn record_error(img: &mut [u8], layout: &Layout, code: ErrorCode, pou: u32, op: u32) {
    mem::set_u16_ne(img, layout.sched(Sched::LAST_ERR), code as u16);
    mem::set_u16_ne(img, layout.sched(Sched::ERR_POU), pou as u16);
    mem::set_u32_ne(img, layout.sched(Sched::ERR_OP), op);
    if let Some((at, bit)) = run_err_bit(layout) {
        mem::set_bit(img, at, bit, true);
    }
}

/// Records a fatal error: `FATAL`, `ERR_POU`, `ERR_OP`. The engine then aborts the scan and
/// passes [`ScanStatus::Fatal`] to [`end`].
pub fn record_fatal(img: &mut [u8], layout: &Layout, code: FatalCode, pou: u32, op: u32) {
    mem::set_u16_ne(img, layout.sched(Sched::FATAL), code as u16);
    mem::set_u16_ne(img, layout.sched(Sched::ERR_POU), pou as u16);
    mem::set_u32_ne(img, layout.sched(Sched::ERR_OP), op);
}

/// Counts one loop-budget event (a taken backward jump or a NEXT that loops back). Returns
/// `false` when the budget is exhausted: the caller must raise [`FatalCode::Watchdog`].
#[inline]
pub fn loop_tick(img: &mut [u8], layout: &Layout) -> bool {
    let n = mem::sched_u32(img, layout, Sched::LOOP_COUNT).saturating_add(1);
    mem::set_sched_u32(img, layout, Sched::LOOP_COUNT, n);
    n <= mem::sched_u32(img, layout, Sched::LOOP_LIMIT)
}

/// `WDR`: restarts the loop budget.
#[inline]
pub fn watchdog_reset(img: &mut [u8], layout: &Layout) {
    mem::set_sched_u32(img, layout, Sched::LOOP_COUNT, 0);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::Image;
    use crate::interrupt::NoIsr;
    use stljit_core::ProfileId;

    fn smb0(img: &Image) -> u8 {
        img.bytes()[img.layout().base(Area::SM) as usize]
    }

    fn scan(img: &mut Image, t: u64) -> ScanStatus {
        let plan = ScanPlan::every_timer(img.layout());
        let (b, l) = img.split_mut();
        run(b, l, &plan, t, &mut NoIsr, |_, _| ScanStatus::Ok)
    }

    #[test]
    fn x5_clock_bits() {
        // Spec §7 X5 with scan_ms = 250: (SM0.5, SM0.6, SM0.1) per scan.
        let want = [(1, 1, 1), (1, 0, 0), (0, 1, 0), (0, 0, 0), (1, 1, 0)];
        let mut img = Image::blank(ProfileId::A5);
        for (k, w) in want.into_iter().enumerate() {
            let plan = ScanPlan::every_timer(img.layout());
            let (b, l) = img.split_mut();
            assert_eq!(begin(b, l, &plan, 250 * k as u64, &mut NoIsr), Begin::Run);
            let s = smb0(&img);
            assert_eq!((s >> 5 & 1, s >> 6 & 1, s >> 1 & 1), w, "scan {k}");
            assert_eq!(s & 0x81, 0x81, "SM0.0 and SM0.7 always on");
            let (b, l) = img.split_mut();
            end(b, l, ScanStatus::Ok);
        }
    }

    #[test]
    fn sm0_2_only_in_first_scan_when_declared() {
        let mut img = Image::blank(ProfileId::A5);
        img.set_retentive_lost(true);
        let plan = ScanPlan::every_timer(img.layout());
        let (b, l) = img.split_mut();
        assert_eq!(begin(b, l, &plan, 0, &mut NoIsr), Begin::Run);
        assert_eq!(smb0(&img) >> 2 & 1, 1);
        let (b, l) = img.split_mut();
        end(b, l, ScanStatus::Ok);
        scan(&mut img, 10);
        assert_eq!(smb0(&img) >> 2 & 1, 0);
        // SM0.4: on for the first 30 s of each minute (spec §2.3).
        scan(&mut img, 30_000);
        assert_eq!(smb0(&img) >> 4 & 1, 0);
        scan(&mut img, 60_010);
        assert_eq!(smb0(&img) >> 4 & 1, 1);
    }

    #[test]
    fn time_deltas() {
        let mut img = Image::blank(ProfileId::A5);
        let get = |img: &Image, f| mem::sched_u32(img.bytes(), img.layout(), f);
        scan(&mut img, 95); // first scan: no deltas whatever t is
        assert_eq!(get(&img, Sched::D1), 0);
        scan(&mut img, 205);
        assert_eq!(
            (
                get(&img, Sched::D1),
                get(&img, Sched::D10),
                get(&img, Sched::D100)
            ),
            (110, 11, 2)
        );
        scan(&mut img, 100); // backwards: nothing credited
        assert_eq!(get(&img, Sched::D1), 0);
        assert_eq!(img.scan_no(), 3);
    }

    #[test]
    fn inputs_copied_outputs_written_and_stop() {
        let mut img = Image::blank(ProfileId::A5);
        img.set_inputs(&[0xA5, 1]);
        let q = img.layout().base(Area::Q) as usize;
        let plan = ScanPlan::every_timer(img.layout());
        let st = {
            let (b, l) = img.split_mut();
            run(b, l, &plan, 0, &mut NoIsr, |b, l| {
                assert_eq!(b[l.base(Area::I) as usize], 0xA5);
                b[q] = 0x3C;
                mem::set_sched_u8(b, l, Sched::STOP_REQ, 1);
                ScanStatus::Ok
            })
        };
        assert_eq!(st, ScanStatus::Stopped);
        assert_eq!(img.phys_out()[0], 0x3C, "STOP completes the scan (spec P1)");
        assert!(img.is_stopped());
        assert_eq!(scan(&mut img, 10), ScanStatus::Stopped);
        assert_eq!(
            img.phys_out()[0],
            0,
            "outputs forced to 0 in STOP (spec §2.5)"
        );
        assert_eq!(img.scan_no(), 1);
    }

    #[test]
    fn fatal_skips_output_copy() {
        let mut img = Image::blank(ProfileId::A5);
        let q = img.layout().base(Area::Q) as usize;
        let plan = ScanPlan::every_timer(img.layout());
        let st = {
            let (b, l) = img.split_mut();
            run(b, l, &plan, 0, &mut NoIsr, |b, l| {
                b[q] = 1;
                record_fatal(b, l, FatalCode::Watchdog, 0, 7);
                ScanStatus::Fatal
            })
        };
        assert_eq!(st, ScanStatus::Fatal);
        assert_eq!(img.phys_out()[0], 0);
        assert!(img.is_stopped());
        assert_eq!(img.fatal(), FatalCode::Watchdog as u16);
        assert_eq!(img.error_site(), (0, 7));
    }

    #[test]
    fn a_task_start_clears_the_condition_flags_and_opens_the_gate() {
        // omron-cp.md §2.3: every condition flag is cleared; P_On and the pulses stay.
        let mut img = Image::blank(ProfileId::Cp1h);
        scan(&mut img, 0);
        let (b, l) = img.split_mut();
        let at = l.base(Area::Flags) as usize;
        let on = 1u16 << SystemBit::On.index();
        let [lo, hi] = (on | SystemBit::CONDITION_FLAGS).to_le_bytes();
        (b[at], b[at + 1]) = (lo, hi);
        mem::set_sched_u8(b, l, Sched::SCR_ENABLE, 0);
        task_start(b, l);
        assert_eq!(u16::from_le_bytes([b[at], b[at + 1]]), on);
        assert_eq!(mem::sched_u8(b, l, Sched::SCR_ENABLE), 1);
    }

    #[test]
    fn loop_budget_allows_exactly_the_limit() {
        let mut img = Image::blank(ProfileId::A5);
        img.set_loop_limit(3);
        let (b, l) = img.split_mut();
        assert!(loop_tick(b, l) && loop_tick(b, l) && loop_tick(b, l));
        assert!(!loop_tick(b, l));
        watchdog_reset(b, l);
        assert!(loop_tick(b, l));
    }
}
