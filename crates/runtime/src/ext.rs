//! The instructions of s7-200-more §4–§7 on the image: [`execute`] runs one
//! [`ExtBox`] (tables, ASCII and number text, strings, the clock, PID; HDEF/HSC through
//! [`crate::hsc`]) and [`str_compare`] one
//! string compare contact. Both engines call exactly these (the interpreter directly, the JIT
//! through `ffi::stljit_rt_ext` and `ffi::stljit_rt_str_compare` with a pointer to the op), so
//! operand resolution, run checks and the rules of [`crate::table`], [`crate::text`],
//! [`crate::string`], [`crate::rtc`] and [`crate::pid`] exist once.
//!
//! Box rules (a5-stl §4.0, s7-200-more §0.5): every operand is resolved, and every input read,
//! before anything is written, in STL operand order; an operand error (a bad pointer 0x0006, a
//! run past its area or a string with length byte 255 0x0091, an index 0 0x009B) writes
//! nothing. A string is its length byte and that many characters, all inside its area.

use crate::block::Span;
use crate::flags::{NOT_HEX, OVERFLOW, SmFlags, apply_flags};
use crate::operand;
use crate::text::{self, NumText, ParseFail};
use crate::{hsc, pid, pulse, rtc, string, table};
use stljit_core::ir::{ClockOp, ExtBox, NumType, StrArg, StrCompare};
use stljit_core::layout::Layout;
use stljit_core::{ErrorCode, FatalCode, Width};

/// The characters of the string at `s` (length byte 255, or a string running past its area,
/// is 0x0091).
fn string_at(img: &[u8], s: Span) -> Result<Vec<u8>, ErrorCode> {
    let head = s.bytes(1, img.len())?;
    let len = img[head.start];
    if usize::from(len) > stljit_core::ir::MAX_STRING {
        return Err(ErrorCode::OperandRange);
    }
    let r = s.bytes(1 + u32::from(len), img.len())?;
    Ok(img[r.start + 1..r.end].to_vec())
}

/// The characters of a string input (a constant, or a string in memory).
fn read_string(
    img: &[u8],
    layout: &Layout,
    arg: &StrArg,
    frame: u32,
) -> Result<Vec<u8>, ErrorCode> {
    match arg {
        StrArg::Const(b) => Ok(b.clone()),
        StrArg::Mem(o) => string_at(
            img,
            operand::span(img, layout, o, Width::Byte, frame, false)?,
        ),
    }
}

/// Writes `bytes` at the start of `out` (all of them inside its area, else 0x0091).
fn put(img: &mut [u8], out: Span, bytes: &[u8]) -> Result<(), ErrorCode> {
    let r = out.bytes(bytes.len() as u32, img.len())?;
    img[r].copy_from_slice(bytes);
    Ok(())
}

/// Writes the string `chars` (length byte first) at `out`.
fn put_string(img: &mut [u8], out: Span, chars: &[u8]) -> Result<(), ErrorCode> {
    let mut b = Vec::with_capacity(chars.len() + 1);
    b.push(chars.len() as u8);
    b.extend_from_slice(chars);
    put(img, out, &b)
}

/// Sets SM1.1 to `v`.
fn overflow(img: &mut [u8], layout: &Layout, v: bool) {
    let bits = if v { OVERFLOW } else { 0 };
    apply_flags(img, layout, SmFlags::assign(OVERFLOW, bits));
}

/// Runs `b` in L frame `frame` with power flow `pf`. Returns ENO, or the non-fatal error the
/// engine records (ENO 0). Without power flow nothing happens and ENO is 0, except that PID
/// updates its loop's history bit.
pub fn execute(
    img: &mut [u8],
    layout: &Layout,
    b: &ExtBox,
    frame: u32,
    pf: bool,
) -> Result<bool, ErrorCode> {
    if let ExtBox::Pid { table, lp } = b {
        let t = operand::span(img, layout, table, Width::DWord, frame, true)?;
        return pid::execute(img, layout, t, *lp, pf);
    }
    if !pf {
        return Ok(false);
    }
    let span = |img: &[u8], o, w, write| operand::span(img, layout, o, w, frame, write);
    let read = |img: &[u8], o, w| operand::read(img, layout, o, w, frame);
    match b {
        ExtBox::TableAdd { data, table } => {
            let d = read(img, data, Width::Word)?;
            let t = span(img, table, Width::Word, true)?;
            table::add(img, layout, t, d as u16)
        }
        ExtBox::TableTake { lifo, table, data } => {
            let t = span(img, table, Width::Word, true)?;
            let d = operand::resolve(img, layout, data, Width::Word, frame, true)?;
            table::take(img, layout, t, d, *lifo)
        }
        ExtBox::TableFind {
            rel,
            table,
            pattern,
            index,
        } => {
            let t = span(img, table, Width::Word, false)?;
            let p = read(img, pattern, Width::Word)?;
            let i = operand::resolve(img, layout, index, Width::Word, frame, true)?;
            let start = operand::load(img, i, Width::Word) as u16 as i16;
            let found = table::find(img, t, p as u16 as i16, start, *rel)?;
            operand::store(img, i, Width::Word, u32::from(found));
            Ok(true)
        }
        ExtBox::AsciiToHex { src, dst, len } => {
            let s = span(img, src, Width::Byte, false)?;
            let d = span(img, dst, Width::Byte, true)?;
            let n = read(img, len, Width::Byte)?;
            let chars = img[s.bytes(n, img.len())?].to_vec();
            let out = d.bytes(n.div_ceil(2), img.len())?;
            if n == 0 {
                return Ok(true);
            }
            let ok = text::ascii_to_hex(&chars, &mut img[out]);
            apply_flags(
                img,
                layout,
                SmFlags::assign(NOT_HEX, if ok { 0 } else { NOT_HEX }),
            );
            Ok(ok)
        }
        ExtBox::HexToAscii { src, dst, len } => {
            let s = span(img, src, Width::Byte, false)?;
            let d = span(img, dst, Width::Byte, true)?;
            let n = read(img, len, Width::Byte)?;
            let digits = img[s.bytes(n.div_ceil(2), img.len())?].to_vec();
            put(img, d, &text::hex_to_ascii(&digits, n as usize))?;
            Ok(true)
        }
        ExtBox::NumToText {
            ty,
            string,
            src,
            dst,
            fmt,
        } => {
            let v = read(img, src, ty.width())?;
            let d = span(img, dst, Width::Byte, true)?;
            let f = read(img, fmt, Width::Byte)? as u8;
            let t = match ty {
                NumType::Int => text::int_text(i32::from(v as u16 as i16), f, text::INT_SIZE),
                NumType::DInt => text::int_text(v as i32, f, text::DINT_SIZE),
                NumType::Real => text::real_text(v, f),
            };
            let (chars, eno) = match t {
                NumText::Illegal => return Ok(false),
                NumText::Spaces(n) => (vec![b' '; n], false),
                NumText::Text(c) => (c, true),
            };
            if *string {
                put_string(img, d, &chars)?;
            } else {
                put(img, d, &chars)?;
            }
            Ok(eno)
        }
        ExtBox::TextToNum {
            ty,
            src,
            index,
            dst,
        } => {
            let s = read_string(img, layout, src, frame)?;
            let i = read(img, index, Width::Byte)?;
            let d = operand::resolve(img, layout, dst, ty.width(), frame, true)?;
            if i == 0 {
                return Err(ErrorCode::StringIndex);
            }
            let start = i as usize;
            let v = match ty {
                NumType::Int => text::parse_int(&s, start, -32768, 32767).map(|v| v as u32),
                NumType::DInt => {
                    text::parse_int(&s, start, i32::MIN.into(), i32::MAX.into()).map(|v| v as u32)
                }
                NumType::Real => text::parse_real(&s, start).map(f32::to_bits),
            };
            match v {
                Ok(v) => {
                    operand::store(img, d, ty.width(), v);
                    overflow(img, layout, false);
                    Ok(true)
                }
                Err(ParseFail::NoNumber | ParseFail::Overflow) => {
                    overflow(img, layout, true);
                    Ok(false)
                }
            }
        }
        ExtBox::StrLen { src, dst } => {
            let s = read_string(img, layout, src, frame)?;
            let d = operand::resolve(img, layout, dst, Width::Byte, frame, true)?;
            operand::store(img, d, Width::Byte, s.len() as u32);
            Ok(true)
        }
        ExtBox::StrCopy { src, dst } => {
            let s = read_string(img, layout, src, frame)?;
            let d = span(img, dst, Width::Byte, true)?;
            put_string(img, d, &s)?;
            Ok(true)
        }
        ExtBox::StrCat { src, dst } => {
            let s = read_string(img, layout, src, frame)?;
            let d = span(img, dst, Width::Byte, true)?;
            let joined = string::concat(&string_at(img, d)?, &s)?;
            put_string(img, d, &joined)?;
            Ok(true)
        }
        ExtBox::SubStr {
            src,
            index,
            count,
            dst,
        } => {
            let s = read_string(img, layout, src, frame)?;
            let i = read(img, index, Width::Byte)?;
            let n = read(img, count, Width::Byte)?;
            let d = span(img, dst, Width::Byte, true)?;
            put_string(img, d, &string::substring(&s, i as u8, n as u8)?)?;
            Ok(true)
        }
        ExtBox::StrFind {
            chars,
            src,
            pattern,
            pos,
        } => {
            let s = read_string(img, layout, src, frame)?;
            let p = read_string(img, layout, pattern, frame)?;
            let at = operand::resolve(img, layout, pos, Width::Byte, frame, true)?;
            let start = operand::load(img, at, Width::Byte) as u8;
            let found = string::find(&s, &p, start, *chars)?;
            operand::store(img, at, Width::Byte, u32::from(found));
            Ok(true)
        }
        ExtBox::Clock { op, buf } => {
            let write = matches!(op, ClockOp::Read | ClockOp::ReadExt);
            let t = span(img, buf, Width::Byte, write)?;
            match op {
                ClockOp::Read => rtc::read(img, layout, t, false),
                ClockOp::ReadExt => rtc::read(img, layout, t, true),
                ClockOp::Write => rtc::write(img, layout, t, false),
                ClockOp::WriteExt => rtc::write(img, layout, t, true),
            }?;
            Ok(true)
        }
        ExtBox::Pid { .. } => Ok(false),
        ExtBox::HscDefine { counter, mode } => {
            hsc::define(img, layout, *counter, *mode)?;
            Ok(true)
        }
        ExtBox::Hsc { counter } => {
            hsc::control(img, layout, *counter)?;
            Ok(true)
        }
        ExtBox::Pls { channel } => {
            pulse::execute(img, layout, *channel)?;
            Ok(true)
        }
        ExtBox::Comm { op, table, port } => {
            crate::comm::execute(img, layout, *op, table, *port, frame)
        }
    }
}

/// A string compare contact (§5.6): whether IN1 and IN2 are equal (same length, same bytes),
/// negated for `<>`. Evaluated regardless of power flow; an operand error is fatal like the
/// other compares: a bad pointer [`FatalCode::CompareIndirect`], a length byte of 255 or a
/// string past its area [`FatalCode::CompareString`].
pub fn str_compare(
    img: &[u8],
    layout: &Layout,
    c: &StrCompare,
    frame: u32,
) -> Result<bool, FatalCode> {
    let fatal = |e: ErrorCode| match e {
        ErrorCode::IndirectAddress => FatalCode::CompareIndirect,
        _ => FatalCode::CompareString,
    };
    let a = read_string(img, layout, &c.lhs, frame).map_err(fatal)?;
    let b = read_string(img, layout, &c.rhs, frame).map_err(fatal)?;
    Ok((a == b) != c.ne)
}
