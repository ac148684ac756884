//! `PID TBL, LOOP` (s7-200-more §7): the loop-table algorithm of the S7-200 manual with its
//! bias (anti-windup) and bumpless-transfer rules, in the spec's exact f32 operation order
//! (each step one IEEE binary32 operation, no fused multiply-add), so both engines and every
//! host compute the same bits.
//!
//! The loop table is nine big-endian REALs in V ([`Field`]); the simulator reads and writes
//! its first 36 bytes only. Each loop number has a power-flow history bit in the image
//! ([`InstrState::PID_NO_FLOW`], stored inverted so that a cold start has it set): an
//! execution with power flow after one without does the bumpless transfer first.

use crate::block::Span;
use crate::flags::{OVERFLOW, SmFlags, apply_flags};
use crate::mem;
use stljit_core::layout::{InstrState, Layout};
use stljit_core::{ErrorCode, Width};

/// The fields of the loop table, in table order (offset `4 × index`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// PV_n, the process variable (0.0–1.0).
    Pv,
    /// SP_n, the setpoint (written by the bumpless transfer).
    Sp,
    /// M_n, the output.
    Out,
    /// K_C, the gain.
    Gain,
    /// T_S, the sample time in seconds.
    SampleTime,
    /// T_I, the integral time in minutes (+INF: no integral action).
    IntegralTime,
    /// T_D, the derivative time in minutes.
    DerivativeTime,
    /// MX, the bias (integral sum).
    Bias,
    /// PV_{n−1}, the previous process variable.
    PrevPv,
}

/// The bytes of the loop table the simulator uses.
pub const TABLE_BYTES: u32 = 36;

/// The nine fields of a loop table, indexed by [`Field`].
pub type Table = [f32; 9];

/// One PID calculation (§7.2) on `t`, after the bumpless transfer (§7.3: SP := PV,
/// PV_{n−1} := PV, MX := M) when `bumpless`. `None` when a term or input is NaN or infinite
/// (T_I may be +INF) or T_S ≤ 0: SM1.1 := 1 and nothing is written.
pub fn step(t: &Table, bumpless: bool) -> Option<Table> {
    let mut t = *t;
    if t.iter().any(|x| x.is_nan()) {
        return None;
    }
    if bumpless {
        t[Field::Sp as usize] = t[Field::Pv as usize];
        t[Field::PrevPv as usize] = t[Field::Pv as usize];
        t[Field::Bias as usize] = t[Field::Out as usize];
    }
    let [pv, sp, _, kc, ts, ti, td, mx, pv_prev] = t;
    if ts <= 0.0 {
        return None;
    }
    let e = sp - pv;
    let mp = kc * e;
    let kg = if kc == 0.0 { 1.0 } else { kc };
    let ki = kg * (ts / (ti * 60.0));
    let mi = (ki * e) + mx;
    let kd = kg * ((td * 60.0) / ts);
    let md = kd * (pv_prev - pv);
    let m = (mp + mi) + md;
    if ![e, mp, ki, mi, kd, md, m].iter().all(|x| x.is_finite()) {
        return None;
    }
    let (out, bias) = if m > 1.0 {
        (1.0, 1.0 - (mp + md))
    } else if m < 0.0 {
        (0.0, -(mp + md))
    } else {
        (m, mi)
    };
    t[Field::Out as usize] = out;
    t[Field::Bias as usize] = bias.clamp(0.0, 1.0);
    t[Field::PrevPv as usize] = pv;
    Some(t)
}

/// `PID TBL, LOOP` with power flow `pf`: updates loop `lp`'s history bit; with power flow runs
/// [`step`] on the table at `table` (36 bytes, else 0x0091) and writes M, MX, PV_{n−1} (and SP
/// after a bumpless transfer). Returns ENO: 0 without power flow or on a calculation error
/// (then SM1.1 := 1; SM1.1 is not cleared on success, §13 P2).
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    table: Span,
    lp: u8,
    pf: bool,
) -> Result<bool, ErrorCode> {
    let hist = layout.instr_state(InstrState::PID_NO_FLOW);
    let bits = mem::get_u8(img, hist);
    let mask = 1u8.checked_shl(u32::from(lp)).unwrap_or(0);
    if !pf {
        mem::set_u8(img, hist, bits | mask);
        return Ok(false);
    }
    let r = table.bytes(TABLE_BYTES, img.len())?;
    mem::set_u8(img, hist, bits & !mask);
    let at = |i: usize| r.start as u32 + 4 * i as u32;
    let mut t = [0f32; 9];
    for (i, x) in t.iter_mut().enumerate() {
        *x = f32::from_bits(mem::get_be(img, at(i), Width::DWord));
    }
    let Some(new) = step(&t, bits & mask != 0) else {
        apply_flags(img, layout, SmFlags::assign(OVERFLOW, OVERFLOW));
        return Ok(false);
    };
    for (i, (old, new)) in t.iter().zip(new).enumerate() {
        if old.to_bits() != new.to_bits() {
            mem::set_be(img, at(i), Width::DWord, new.to_bits());
        }
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(v: [f32; 9]) -> Table {
        v
    }

    /// s7-200-more §12 M11, computed there with numpy f32.
    #[test]
    fn m11() {
        // Loop 0: first execution after RUN (no bumpless).
        let t0 = table([0.4, 0.5, 0.25, 0.5, 0.1, 1.0, 0.0, 0.2, 0.4]);
        let r = step(&t0, false).unwrap();
        assert_eq!(r[Field::Out as usize].to_bits(), 0x3E80_0AEC);
        assert_eq!(r[Field::Bias as usize].to_bits(), 0x3E4C_E2A5);
        assert_eq!(r[Field::PrevPv as usize].to_bits(), 0x3ECC_CCCD);
        let e = 0.5f32 - 0.4f32;
        assert_eq!(e.to_bits(), 0x3DCC_CCCC);
        assert_eq!((0.5f32 * (0.1f32 / (1.0f32 * 60.0))).to_bits(), 0x3A5A_740E);
        // Loop 1: saturation; MX = 1.0 − mp with mp = 0.99999994.
        let mut t1 = t0;
        t1[Field::Gain as usize] = 10.0;
        let r = step(&t1, false).unwrap();
        assert_eq!(r[Field::Out as usize].to_bits(), 0x3F80_0000);
        assert_eq!(r[Field::Bias as usize].to_bits(), 0x3380_0000);
        // Loop 2: bumpless transfer, then e = 0.
        let t2 = table([0.3, 0.8, 0.6, 2.0, 1.0, 10.0, 0.5, 0.1, 0.0]);
        let r = step(&t2, true).unwrap();
        assert_eq!(r[Field::Out as usize].to_bits(), 0x3F19_999A);
        assert_eq!(r[Field::Bias as usize].to_bits(), 0x3F19_999A);
        assert_eq!(r[Field::Sp as usize].to_bits(), 0x3E99_999A);
        assert_eq!(r[Field::PrevPv as usize].to_bits(), 0x3E99_999A);
    }

    /// Loop types and errors (§7.2): no integral (T_I = +INF), no P (K_C = 0: gain 1 in I and
    /// D), the bias clamped to 0–1, and NaN, T_S ≤ 0 or T_I = 0 rejected.
    #[test]
    fn loop_types_and_errors() {
        let base = table([0.5, 0.5, 0.0, 1.0, 1.0, f32::INFINITY, 0.0, 0.3, 0.5]);
        let r = step(&base, false).unwrap();
        assert_eq!(
            (r[Field::Out as usize], r[Field::Bias as usize]),
            (0.3, 0.3)
        );
        let mut no_p = base;
        no_p[Field::Gain as usize] = 0.0;
        no_p[Field::IntegralTime as usize] = 1.0;
        no_p[Field::Sp as usize] = 0.56;
        // ki = 1 × (1 / 60): the integral acts with gain 1.
        let r = step(&no_p, false).unwrap();
        let ki = 1.0f32 * (1.0f32 / (1.0f32 * 60.0));
        let e = 0.56f32 - 0.5f32;
        assert_eq!(r[Field::Out as usize], ki * e + 0.3);
        // Output below 0: M = 0, MX = −(mp + md) clamped to 0.
        let mut low = base;
        low[Field::Sp as usize] = 0.0;
        let r = step(&low, false).unwrap();
        assert_eq!(
            (r[Field::Out as usize], r[Field::Bias as usize]),
            (0.0, 0.5)
        );
        let mut bad = base;
        bad[Field::SampleTime as usize] = 0.0;
        assert_eq!(step(&bad, false), None);
        bad[Field::SampleTime as usize] = f32::NAN;
        assert_eq!(step(&bad, false), None);
        let mut zero_ti = base;
        zero_ti[Field::IntegralTime as usize] = 0.0;
        assert_eq!(step(&zero_ti, false), None);
    }
}
