//! The scan cycle around the program body (spec §2.1): [`begin`] does steps 1–4 and the per-scan
//! resets of step 5, [`end`] does steps 6–8. Both engines call exactly these two functions, so
//! time, SMB0, the clock-driven timer refresh and the output copy exist once.
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

use crate::mem;
use crate::timer;
use stljit_core::ir::Loc;
use stljit_core::layout::{Layout, Sched, TimerState};
use stljit_core::omron::{self, SystemBit};
use stljit_core::{Area, ErrorCode, Family, FatalCode, ScanStatus};

/// Steps 1–4 of a scan plus the resets of step 5. Returns `false` (and does only the STOP rule
/// of the module doc) when the image is in STOP; the program must then not run.
pub fn begin(img: &mut [u8], layout: &Layout, t_ms: u64) -> bool {
    if mem::sched_u8(img, layout, Sched::MODE) != 0 {
        let out = layout.phys_out;
        for i in 0..layout.area_size(Area::Q) {
            mem::set_u8(img, out + i, 0);
        }
        return false;
    }
    let first = mem::sched_u8(img, layout, Sched::FIRST_SCAN) != 0;

    // Step 1: time. Scan 0 has t_prev = 0 and no deltas (spec §2.1).
    let (t_prev, d1, d10, d100) = if first {
        (0, 0, 0, 0)
    } else {
        let prev = mem::get_u64_ne(img, layout.sched(Sched::T_NOW));
        let delta = |div: u64| {
            let d = (t_ms / div).saturating_sub(prev / div);
            u32::try_from(d).unwrap_or(u32::MAX)
        };
        (prev, delta(1), delta(10), delta(100))
    };
    mem::set_u64_ne(img, layout.sched(Sched::T_PREV), t_prev);
    mem::set_u64_ne(img, layout.sched(Sched::T_NOW), t_ms);
    mem::set_sched_u32(img, layout, Sched::D1, d1);
    mem::set_sched_u32(img, layout, Sched::D10, d10);
    mem::set_sched_u32(img, layout, Sched::D100, d100);

    // Step 2: the I image is overwritten from the physical inputs (AI is latched by the harness
    // writing the AI area directly).
    let (src, dst) = (layout.phys_in, layout.base(Area::I));
    for i in 0..layout.area_size(Area::I) {
        let b = mem::get_u8(img, src + i);
        mem::set_u8(img, dst + i, b);
    }

    let profile = layout.profile.profile();
    match profile.family {
        Family::S7 => {
            // Step 3: SMB0 (spec §2.3). SMB1 keeps its bits.
            let scan_no = mem::get_u64_ne(img, layout.sched(Sched::SCAN_NO));
            let lost = mem::sched_u8(img, layout, Sched::RETENTIVE_LOST) != 0;
            let smb0 = 1
                | u8::from(first) << 1
                | u8::from(first && lost) << 2
                | u8::from(first) << 3
                | u8::from(t_ms % 60_000 < 30_000) << 4
                | u8::from(t_ms % 1000 < 500) << 5
                | u8::from(scan_no.is_multiple_of(2)) << 6
                | 1 << 7;
            mem::set_u8(img, layout.base(Area::SM), smb0);
        }
        Family::Omron => omron_system_bits(img, layout, t_ms, first),
    }

    // Step 4: clock-driven refresh of the 1-ms and 10-ms timers in use.
    if profile.family.clock_refreshed_timers() {
        let timers = layout.area_size(Area::TimerBit);
        for n in 0..timers {
            let n = n as u16;
            if mem::get_u8(img, layout.timer_state(n) + TimerState::KIND) != 0 {
                timer::refresh(img, layout, n);
            }
        }
    }

    // Step 5 resets.
    mem::set_sched_u8(img, layout, Sched::ENO, 0);
    mem::set_sched_u8(img, layout, Sched::SCR_ENABLE, 1);
    mem::set_sched_u8(img, layout, Sched::STOP_REQ, 0);
    mem::set_sched_u32(img, layout, Sched::LOOP_COUNT, 0);
    true
}

/// The Omron system bits at the start of the (single cyclic) task, omron-cp.md §2.2 step 3 and
/// §2.3: every condition flag cleared, `P_On` = 1, `P_Off` = 0, the clock pulses from `t_ms`
/// (50 % duty, ON half first, §2.12) and `A200.11` (`P_First_Cycle`) ON in the first cycle only.
fn omron_system_bits(img: &mut [u8], layout: &Layout, t_ms: u64, first: bool) {
    let mut bits: u32 = 1 << SystemBit::On.index();
    for (pulse, period) in SystemBit::PULSES {
        if t_ms % period < period / 2 {
            bits |= 1 << pulse.index();
        }
    }
    let base = layout.base(Area::Flags);
    for (i, b) in bits.to_le_bytes().into_iter().enumerate() {
        mem::set_u8(img, base + i as u32, b);
    }
    let (word, bit) = omron::FIRST_CYCLE;
    let at = omron::bit_of_word(
        Loc {
            area: Area::Aux,
            offset: 2 * word,
        },
        bit,
    );
    if at.byte < layout.area_size(Area::Aux) {
        let a = layout.base(Area::Aux) + at.byte;
        let old = mem::get_u8(img, a);
        let mask = 1 << at.bit;
        mem::set_u8(img, a, if first { old | mask } else { old & !mask });
    }
}

/// Steps 6–8: unless `status` is [`ScanStatus::Fatal`], copy Q to the physical outputs; a STOP
/// request or a fatal error puts the PLC in STOP. Returns the scan's final status (`Stopped` when
/// a STOP executed).
pub fn end(img: &mut [u8], layout: &Layout, status: ScanStatus) -> ScanStatus {
    let status = if status == ScanStatus::Fatal {
        mem::set_sched_u8(img, layout, Sched::MODE, 1);
        ScanStatus::Fatal
    } else {
        let (src, dst) = (layout.base(Area::Q), layout.phys_out);
        for i in 0..layout.area_size(Area::Q) {
            let b = mem::get_u8(img, src + i);
            mem::set_u8(img, dst + i, b);
        }
        if mem::sched_u8(img, layout, Sched::STOP_REQ) != 0 || status == ScanStatus::Stopped {
            mem::set_sched_u8(img, layout, Sched::MODE, 1);
            ScanStatus::Stopped
        } else {
            ScanStatus::Ok
        }
    };
    mem::set_sched_u8(img, layout, Sched::FIRST_SCAN, 0);
    let k = mem::get_u64_ne(img, layout.sched(Sched::SCAN_NO));
    mem::set_u64_ne(img, layout.sched(Sched::SCAN_NO), k.wrapping_add(1));
    status
}

/// One whole scan around `body` (which executes the program and returns `Ok` or `Fatal`).
pub fn run(
    img: &mut [u8],
    layout: &Layout,
    t_ms: u64,
    body: impl FnOnce(&mut [u8], &Layout) -> ScanStatus,
) -> ScanStatus {
    if !begin(img, layout, t_ms) {
        return ScanStatus::Stopped;
    }
    let status = body(img, layout);
    end(img, layout, status)
}

/// Records a non-fatal error (spec §2.5): `LAST_ERR`, `ERR_POU`, `ERR_OP`. ENO is the caller's.
pub fn record_error(img: &mut [u8], layout: &Layout, code: ErrorCode, pou: u32, op: u32) {
    mem::set_u16_ne(img, layout.sched(Sched::LAST_ERR), code as u16);
    mem::set_u16_ne(img, layout.sched(Sched::ERR_POU), pou as u16);
    mem::set_u32_ne(img, layout.sched(Sched::ERR_OP), op);
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
    use stljit_core::ProfileId;

    fn smb0(img: &Image) -> u8 {
        img.bytes()[img.layout().base(Area::SM) as usize]
    }

    fn scan(img: &mut Image, t: u64) -> ScanStatus {
        let (b, l) = img.split_mut();
        run(b, l, t, |_, _| ScanStatus::Ok)
    }

    #[test]
    fn x5_clock_bits() {
        // Spec §7 X5 with scan_ms = 250: (SM0.5, SM0.6, SM0.1) per scan.
        let want = [(1, 1, 1), (1, 0, 0), (0, 1, 0), (0, 0, 0), (1, 1, 0)];
        let mut img = Image::blank(ProfileId::A5);
        for (k, w) in want.into_iter().enumerate() {
            let (b, l) = img.split_mut();
            assert!(begin(b, l, 250 * k as u64));
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
        let (b, l) = img.split_mut();
        assert!(begin(b, l, 0));
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
        let st = {
            let (b, l) = img.split_mut();
            run(b, l, 0, |b, l| {
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
        let st = {
            let (b, l) = img.split_mut();
            run(b, l, 0, |b, l| {
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
