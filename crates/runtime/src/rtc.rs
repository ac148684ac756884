//! The simulated real-time clock (s7-200-more §6): a start date plus virtual time.
//!
//! The clock's state is in the image ([`InstrState`]): the seconds since 2000-01-01 00:00:00
//! it showed (`RTC_EPOCH`) at a virtual time (`RTC_REF_US`). A cold start leaves both 0 (the
//! clock at 2000-01-01 00:00:00 at t = 0, the SMART's value after a long power loss, §6.2);
//! [`set_start`] puts another start date there before the first scan (`stljit run
//! --start-time`). The clock at virtual time τ is `epoch + ⌊(τ − ref) / 10^6⌋` seconds on the
//! proleptic Gregorian calendar without leap seconds, and TODW sets `epoch` and `ref := τ`.
//! The date arithmetic is integer-only ([`DateTime`]).

use crate::mem;
use stljit_core::ErrorCode;
use stljit_core::layout::{InstrState, Layout, Sched};

/// The 8-byte buffer of TODR/TODW: year, month, day, hour, minute, second (BCD), reserved 0,
/// day of week (1 = Sunday … 7 = Saturday).
pub type ClockBuffer = [u8; 8];

/// Days from 0000-03-01 to 2000-01-01 in the civil-days algorithm below.
const DAYS_TO_2000: i64 = 730_425;

/// A date and time of day, year 2000–2099 (what the BCD buffer can hold).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DateTime {
    /// 2000..=2099.
    pub year: u16,
    /// 1..=12.
    pub month: u8,
    /// 1..=31 (checked against the month).
    pub day: u8,
    /// 0..=23.
    pub hour: u8,
    /// 0..=59.
    pub minute: u8,
    /// 0..=59.
    pub second: u8,
}

/// Why a date is rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DateError(pub String);

impl std::fmt::Display for DateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for DateError {}

fn is_leap(y: i64) -> bool {
    (y % 4 == 0 && y % 100 != 0) || y % 400 == 0
}

/// Days in `month` of `year`.
pub fn days_in_month(year: i64, month: u8) -> u8 {
    match month {
        2 if is_leap(year) => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Days since 2000-01-01 of a civil date (H. Hinnant's `days_from_civil`).
fn days_from_civil(y: i64, m: u8, d: u8) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let m = i64::from(m);
    let doy = (153 * (if m > 2 { m - 3 } else { m + 9 }) + 2) / 5 + i64::from(d) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - DAYS_TO_2000
}

/// The civil date `days` after 2000-01-01 (H. Hinnant's `civil_from_days`).
fn civil_from_days(days: i64) -> (i64, u8, u8) {
    let z = days + DAYS_TO_2000;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u8;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u8;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

impl DateTime {
    /// The date `secs` seconds after 2000-01-01 00:00:00, and its day of week (1 = Sunday …
    /// 7 = Saturday). Years past 2099 keep counting (the buffer shows the year modulo 100).
    pub fn from_epoch(secs: i64) -> (DateTime, u8) {
        let (days, s) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
        let (y, m, d) = civil_from_days(days);
        // 2000-01-01 was a Saturday (7).
        let dow = ((days + 6).rem_euclid(7) + 1) as u8;
        let t = DateTime {
            year: u16::try_from(y).unwrap_or(u16::MAX),
            month: m,
            day: d,
            hour: (s / 3600) as u8,
            minute: (s / 60 % 60) as u8,
            second: (s % 60) as u8,
        };
        (t, dow)
    }

    /// Seconds since 2000-01-01 00:00:00.
    pub fn epoch(&self) -> i64 {
        days_from_civil(i64::from(self.year), self.month, self.day) * 86_400
            + i64::from(self.hour) * 3600
            + i64::from(self.minute) * 60
            + i64::from(self.second)
    }

    /// A checked date: year 2000–2099, a real day of its month, a real time of day.
    pub fn new(
        year: u16,
        month: u8,
        day: u8,
        hour: u8,
        minute: u8,
        second: u8,
    ) -> Result<DateTime, DateError> {
        let ok = (2000..=2099).contains(&year)
            && (1..=12).contains(&month)
            && day >= 1
            && day <= days_in_month(i64::from(year), month)
            && hour <= 23
            && minute <= 59
            && second <= 59;
        if !ok {
            return Err(DateError(format!(
                "{year:04}-{month:02}-{day:02} {hour:02}:{minute:02}:{second:02} is no date and time of 2000-2099"
            )));
        }
        Ok(DateTime {
            year,
            month,
            day,
            hour,
            minute,
            second,
        })
    }

    /// Reads `YYYY-MM-DD`, `YYYY-MM-DD HH:MM:SS` or `YYYY-MM-DDTHH:MM:SS` (the `--start-time`
    /// option), year 2000–2099.
    pub fn parse(text: &str) -> Result<DateTime, DateError> {
        let bad = || {
            DateError(format!(
                "`{text}` is not a date `YYYY-MM-DD` or `YYYY-MM-DD HH:MM:SS`"
            ))
        };
        let t = text.trim();
        let (date, time) = match t.split_once([' ', 'T']) {
            Some((d, tm)) => (d, Some(tm.trim())),
            None => (t, None),
        };
        let nums = |s: &str, sep: char, lens: [usize; 3]| -> Option<[u16; 3]> {
            let parts: Vec<&str> = s.split(sep).collect();
            if parts.len() != 3 {
                return None;
            }
            let mut out = [0u16; 3];
            for ((o, p), len) in out.iter_mut().zip(&parts).zip(lens) {
                if p.len() != len || !p.bytes().all(|c| c.is_ascii_digit()) {
                    return None;
                }
                *o = p.parse().ok()?;
            }
            Some(out)
        };
        let [y, mo, d] = nums(date, '-', [4, 2, 2]).ok_or_else(bad)?;
        let [h, mi, s] = match time {
            Some(tm) => nums(tm, ':', [2, 2, 2]).ok_or_else(bad)?,
            None => [0, 0, 0],
        };
        let b = |v: u16| u8::try_from(v).unwrap_or(u8::MAX);
        DateTime::new(y, b(mo), b(d), b(h), b(mi), b(s))
    }
}

impl std::fmt::Display for DateTime {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:04}-{:02}-{:02} {:02}:{:02}:{:02}",
            self.year, self.month, self.day, self.hour, self.minute, self.second
        )
    }
}

fn bcd(v: u8) -> u8 {
    ((v / 10) << 4) | (v % 10)
}

fn from_bcd(b: u8) -> Option<u8> {
    let (hi, lo) = (b >> 4, b & 0x0F);
    (hi <= 9 && lo <= 9).then_some(hi * 10 + lo)
}

/// The TODR buffer of the clock showing `secs` (byte 6 is 0, byte 7 the day of week computed
/// from the date, the SMART's behaviour, §13 R1).
pub fn encode(secs: i64) -> ClockBuffer {
    let (t, dow) = DateTime::from_epoch(secs);
    [
        bcd((t.year % 100) as u8),
        bcd(t.month),
        bcd(t.day),
        bcd(t.hour),
        bcd(t.minute),
        bcd(t.second),
        0,
        dow,
    ]
}

/// The time a TODW buffer sets: every field BCD and in range, the day within its month; bytes
/// 6 and 7 are ignored. `None` is the data error 0x0007 (§13 R2).
pub fn decode(buf: &ClockBuffer) -> Option<i64> {
    let f = |i: usize| from_bcd(buf[i]);
    let t = DateTime::new(2000 + u16::from(f(0)?), f(1)?, f(2)?, f(3)?, f(4)?, f(5)?).ok()?;
    Some(t.epoch())
}

fn epoch_at(layout: &Layout) -> (u32, u32) {
    (
        layout.instr_state(InstrState::RTC_EPOCH),
        layout.instr_state(InstrState::RTC_REF_US),
    )
}

/// The virtual time in µs of the code running: the scan's `T_k` (s7-200-more §0.3).
pub fn now_us(img: &[u8], layout: &Layout) -> u64 {
    mem::get_u64_ne(img, layout.sched(Sched::T_NOW)).saturating_mul(1000)
}

/// The clock's seconds since 2000-01-01 at virtual time `now_us`.
pub fn seconds(img: &[u8], layout: &Layout, now_us: u64) -> i64 {
    let (e, r) = epoch_at(layout);
    let epoch = mem::get_u64_ne(img, e) as i64;
    let since = now_us.saturating_sub(mem::get_u64_ne(img, r)) / 1_000_000;
    epoch.saturating_add(i64::try_from(since).unwrap_or(i64::MAX))
}

/// Sets the clock to `secs` at virtual time `now_us` (TODW).
pub fn set(img: &mut [u8], layout: &Layout, secs: i64, now_us: u64) {
    let (e, r) = epoch_at(layout);
    mem::set_u64_ne(img, e, secs as u64);
    mem::set_u64_ne(img, r, now_us);
}

/// Puts the start date into a cold-started image: the clock shows `start` at t = 0.
pub fn set_start(img: &mut [u8], layout: &Layout, start: DateTime) {
    if layout.block_size(stljit_core::layout::Block::Instr) > 0 {
        set(img, layout, start.epoch(), 0);
    }
}

/// The extended buffer's daylight-saving bytes (8 onwards) last written by TODWX.
fn dst_at(layout: &Layout) -> u32 {
    layout.instr_state(InstrState::RTC_DST)
}

/// `TODR`/`TODRX` into the buffer `buf`: 8 bytes, or with
/// `extended` the 19 (SMART's day-of-week rule: 21) of §6.1. 0x000C without a clock, 0x0091
/// when the buffer does not fit.
pub fn read(
    img: &mut [u8],
    layout: &Layout,
    buf: crate::block::Span,
    extended: bool,
) -> Result<(), ErrorCode> {
    let clock = layout.profile.profile().clock;
    if !clock.present() {
        return Err(ErrorCode::NoClock);
    }
    let dst = dst_at(layout);
    let len = if extended {
        clock.extended_len(mem::get_u8(img, dst))
    } else {
        8
    };
    let r = buf.bytes(len, img.len())?;
    let now = now_us(img, layout);
    // The clock's 8 bytes, then the extended bytes TODWX stored (21 at most in all).
    let mut bytes = [0u8; 32];
    let out = bytes
        .get_mut(..len as usize)
        .ok_or(ErrorCode::OperandRange)?;
    out[..8].copy_from_slice(&encode(seconds(img, layout, now)));
    for (i, b) in (8..len).zip(&mut out[8..]) {
        *b = mem::get_u8(img, dst + i - 8);
    }
    img[r].copy_from_slice(out);
    Ok(())
}

/// `TODW`/`TODWX` from the buffer: the date and time checked ([`decode`]; with `extended` also
/// the daylight-saving mode in byte 8, §6.1), then the clock set at the scan's time and the
/// extended bytes stored for TODRX (no correction is applied, §13 R3). 0x0007 for bad data,
/// 0x000C without a clock, 0x0091 when the buffer does not fit.
pub fn write(
    img: &mut [u8],
    layout: &Layout,
    buf: crate::block::Span,
    extended: bool,
) -> Result<(), ErrorCode> {
    let clock = layout.profile.profile().clock;
    if !clock.present() {
        return Err(ErrorCode::NoClock);
    }
    let head = buf.bytes(if extended { 9 } else { 8 }, img.len())?;
    let mode = mem::get_u8(img, head.start as u32 + 8);
    let len = if extended {
        clock.extended_len(mode)
    } else {
        8
    };
    let r = buf.bytes(len, img.len())?;
    let bytes = img[r].to_vec();
    let mut b = [0u8; 8];
    b.copy_from_slice(&bytes[..8]);
    let secs = decode(&b).ok_or(ErrorCode::ClockData)?;
    if extended && !clock.dst_modes().contains(&mode) {
        return Err(ErrorCode::ClockData);
    }
    let now = now_us(img, layout);
    set(img, layout, secs, now);
    if extended {
        let dst = dst_at(layout);
        for i in 0..13u32 {
            let v = bytes.get(8 + i as usize).copied().unwrap_or(0);
            mem::set_u8(img, dst + i, v);
        }
    }
    Ok(())
}

/// The clock as the harness shows it (for tools): the date at the scan's time.
pub fn now(img: &[u8], layout: &Layout) -> DateTime {
    DateTime::from_epoch(seconds(img, layout, now_us(img, layout))).0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dt(s: &str) -> DateTime {
        DateTime::parse(s).unwrap()
    }

    #[test]
    fn calendar() {
        assert_eq!(dt("2000-01-01").epoch(), 0);
        assert_eq!(DateTime::from_epoch(0), (dt("2000-01-01 00:00:00"), 7));
        // §12 M10: 2024-02-28 is a Wednesday (4), 2024-02-29 a Thursday (5), 2025-01-01 a
        // Wednesday.
        let t = dt("2024-02-28 23:59:58");
        assert_eq!(
            encode(t.epoch()),
            [0x24, 0x02, 0x28, 0x23, 0x59, 0x58, 0, 4]
        );
        assert_eq!(encode(t.epoch() + 2), [0x24, 0x02, 0x29, 0, 0, 0, 0, 5]);
        let s = decode(&[0x24, 0x12, 0x31, 0x23, 0x59, 0x59, 0, 0]).unwrap();
        assert_eq!(encode(s + 1), [0x25, 0x01, 0x01, 0, 0, 0, 0, 4]);
        // Every day of 2000–2099 round-trips, and weekdays cycle.
        let end = dt("2099-12-31").epoch() / 86_400;
        for day in (0..=end).step_by(13) {
            let (t, dow) = DateTime::from_epoch(day * 86_400);
            assert_eq!(t.epoch(), day * 86_400);
            assert_eq!(i64::from(dow), (day + 6) % 7 + 1);
        }
        // 2100 is no leap year: the day before 2100-03-01 is February 28.
        let march = days_from_civil(2100, 3, 1) * 86_400;
        assert_eq!(DateTime::from_epoch(march - 1).0.day, 28);
    }

    #[test]
    fn todw_validation() {
        assert_eq!(
            decode(&[0x23, 0x02, 0x29, 0, 0, 0, 0, 0]),
            None,
            "2023 is no leap year"
        );
        assert!(decode(&[0x24, 0x02, 0x29, 0, 0, 0, 0, 0]).is_some());
        assert_eq!(decode(&[0x24, 0x13, 0x01, 0, 0, 0, 0, 0]), None, "month 13");
        assert_eq!(decode(&[0x24, 0x00, 0x01, 0, 0, 0, 0, 0]), None, "month 0");
        assert_eq!(decode(&[0x24, 0x04, 0x31, 0, 0, 0, 0, 0]), None, "April 31");
        assert_eq!(
            decode(&[0x24, 0x01, 0x01, 0x24, 0, 0, 0, 0]),
            None,
            "hour 24"
        );
        assert_eq!(decode(&[0x2A, 0x01, 0x01, 0, 0, 0, 0, 0]), None, "no BCD");
        assert_eq!(
            decode(&[0x24, 0x01, 0x01, 0, 0x60, 0, 0, 0]),
            None,
            "minute 60"
        );
        assert!(decode(&[0x99, 0x12, 0x31, 0x23, 0x59, 0x59, 0x77, 0x09]).is_some());
    }

    #[test]
    fn start_time_option() {
        assert_eq!(dt("2024-02-28T23:59:58"), dt("2024-02-28 23:59:58"));
        assert_eq!(dt(" 2024-02-28 ").hour, 0);
        for bad in [
            "1999-12-31",
            "2100-01-01",
            "2024-2-28",
            "2024-02-30",
            "x",
            "2024-02-28 25:00:00",
        ] {
            assert!(DateTime::parse(bad).is_err(), "{bad}");
        }
        assert_eq!(dt("2024-02-28 23:59:58").to_string(), "2024-02-28 23:59:58");
    }
}
