//! The text form of the s7-200-more ops ([`Op::Ext`](crate::ir::Op::Ext),
//! [`Op::StrCompare`](crate::ir::Op::StrCompare)) and of byte strings (constant strings,
//! `data` lines): both directions side by side, so that the grammar of these ops is in one
//! file.
//!
//! A byte string is written as a quoted string whose characters are the bytes (U+0000–U+00FF,
//! Latin-1), so any bytes survive, GBK text included; a string input is an operand or
//! `name=` directly followed by such a string (`src="HELLO"`).

use super::error::{ParseErrorKind, Result};
use super::lex::{Line, Word};
use super::print::{Flag, Opd, Quoted};
use crate::ir::{ClockOp, CommOp, ExtBox, FindRel, NumType, StackForm, StrArg, StrCompare};
use std::fmt::{self, Write as _};

/// Bytes as a quoted string of Latin-1 characters.
pub(super) struct Bytes<'a>(pub(super) &'a [u8]);

impl fmt::Display for Bytes<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s: String = self.0.iter().map(|&b| char::from(b)).collect();
        write!(f, "{}", Quoted(&s))
    }
}

/// A string input: an operand, or a constant string right after the `=`.
struct Str<'a>(&'a StrArg);

impl fmt::Display for Str<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            StrArg::Mem(o) => write!(f, "{}", Opd(*o)),
            StrArg::Const(b) => write!(f, "{}", Bytes(b)),
        }
    }
}

/// Writes an [`ExtBox`] after its `ext ` keyword.
pub(super) fn write_ext(out: &mut String, b: &ExtBox) -> fmt::Result {
    match b {
        ExtBox::TableAdd { data, table } => {
            write!(out, "table_add data={} table={}", Opd(*data), Opd(*table))
        }
        ExtBox::TableTake { lifo, table, data } => write!(
            out,
            "table_take lifo={} table={} data={}",
            Flag(*lifo),
            Opd(*table),
            Opd(*data)
        ),
        ExtBox::TableFind {
            rel,
            table,
            pattern,
            index,
        } => write!(
            out,
            "table_find rel={rel:?} table={} pattern={} index={}",
            Opd(*table),
            Opd(*pattern),
            Opd(*index)
        ),
        ExtBox::AsciiToHex { src, dst, len } | ExtBox::HexToAscii { src, dst, len } => {
            let key = if matches!(b, ExtBox::AsciiToHex { .. }) {
                "ascii_to_hex"
            } else {
                "hex_to_ascii"
            };
            write!(
                out,
                "{key} src={} dst={} len={}",
                Opd(*src),
                Opd(*dst),
                Opd(*len)
            )
        }
        ExtBox::NumToText {
            ty,
            string,
            src,
            dst,
            fmt,
        } => write!(
            out,
            "num_to_text ty={ty:?} string={} src={} dst={} fmt={}",
            Flag(*string),
            Opd(*src),
            Opd(*dst),
            Opd(*fmt)
        ),
        ExtBox::TextToNum {
            ty,
            src,
            index,
            dst,
        } => write!(
            out,
            "text_to_num ty={ty:?} src={} index={} dst={}",
            Str(src),
            Opd(*index),
            Opd(*dst)
        ),
        ExtBox::StrLen { src, dst } => write!(out, "str_len src={} dst={}", Str(src), Opd(*dst)),
        ExtBox::StrCopy { src, dst } => {
            write!(out, "str_copy src={} dst={}", Str(src), Opd(*dst))
        }
        ExtBox::StrCat { src, dst } => write!(out, "str_cat src={} dst={}", Str(src), Opd(*dst)),
        ExtBox::SubStr {
            src,
            index,
            count,
            dst,
        } => write!(
            out,
            "sub_str src={} index={} count={} dst={}",
            Str(src),
            Opd(*index),
            Opd(*count),
            Opd(*dst)
        ),
        ExtBox::StrFind {
            chars,
            src,
            pattern,
            pos,
        } => write!(
            out,
            "str_find chars={} src={} pattern={} pos={}",
            Flag(*chars),
            Str(src),
            Str(pattern),
            Opd(*pos)
        ),
        ExtBox::Clock { op, buf } => write!(out, "clock op={op:?} buf={}", Opd(*buf)),
        ExtBox::Pid { table, lp } => write!(out, "pid table={} loop={lp}", Opd(*table)),
        ExtBox::HscDefine { counter, mode } => write!(out, "hsc_define hsc={counter} mode={mode}"),
        ExtBox::Hsc { counter } => write!(out, "hsc hsc={counter}"),
        ExtBox::Pls { channel } => write!(out, "pls q={channel}"),
        ExtBox::Comm { op, table, port } => {
            write!(out, "comm op={op:?} table={} port={port}", Opd(*table))
        }
    }
}

/// Writes a string compare op: `str_compare form=.. ne=.. lhs=.. rhs=..`.
pub(super) fn write_str_compare(out: &mut String, c: &StrCompare) -> fmt::Result {
    write!(
        out,
        "str_compare form={:?} ne={} lhs={} rhs={}",
        c.form,
        Flag(c.ne),
        Str(&c.lhs),
        Str(&c.rhs)
    )
}

/// The bytes of a string whose characters are all U+0000–U+00FF.
pub(super) fn bytes_of(s: &str, at: Word<'_>) -> Result<Vec<u8>> {
    s.chars()
        .map(|c| u8::try_from(u32::from(c)))
        .collect::<std::result::Result<Vec<u8>, _>>()
        .map_err(|_| {
            at.err(ParseErrorKind::String(
                "a byte string holds U+0000 to U+00FF only",
            ))
        })
}

/// The string input `key=`: an operand, or a constant string after the `=`.
fn str_arg(line: &mut Line<'_>, key: &'static str) -> Result<StrArg> {
    let w = line.field(key)?;
    if !w.text.is_empty() {
        return Ok(StrArg::Mem(w.operand()?));
    }
    let s = line.string("a constant string")?;
    Ok(StrArg::Const(bytes_of(&s, w)?))
}

/// Reads an [`ExtBox`] after its `ext` keyword.
pub(super) fn parse_ext(line: &mut Line<'_>) -> Result<ExtBox> {
    let key = line.word("an ext op")?;
    let opd = |line: &mut Line<'_>, k| line.field(k).and_then(|w| w.operand());
    let ty = |line: &mut Line<'_>| line.field("ty")?.choice(NumType::ALL, "number type");
    Ok(match key.text {
        "table_add" => ExtBox::TableAdd {
            data: opd(line, "data")?,
            table: opd(line, "table")?,
        },
        "table_take" => ExtBox::TableTake {
            lifo: line.field("lifo")?.flag()?,
            table: opd(line, "table")?,
            data: opd(line, "data")?,
        },
        "table_find" => ExtBox::TableFind {
            rel: line.field("rel")?.choice(FindRel::ALL, "find relation")?,
            table: opd(line, "table")?,
            pattern: opd(line, "pattern")?,
            index: opd(line, "index")?,
        },
        "ascii_to_hex" => ExtBox::AsciiToHex {
            src: opd(line, "src")?,
            dst: opd(line, "dst")?,
            len: opd(line, "len")?,
        },
        "hex_to_ascii" => ExtBox::HexToAscii {
            src: opd(line, "src")?,
            dst: opd(line, "dst")?,
            len: opd(line, "len")?,
        },
        "num_to_text" => ExtBox::NumToText {
            ty: ty(line)?,
            string: line.field("string")?.flag()?,
            src: opd(line, "src")?,
            dst: opd(line, "dst")?,
            fmt: opd(line, "fmt")?,
        },
        "text_to_num" => ExtBox::TextToNum {
            ty: ty(line)?,
            src: str_arg(line, "src")?,
            index: opd(line, "index")?,
            dst: opd(line, "dst")?,
        },
        "str_len" => ExtBox::StrLen {
            src: str_arg(line, "src")?,
            dst: opd(line, "dst")?,
        },
        "str_copy" => ExtBox::StrCopy {
            src: str_arg(line, "src")?,
            dst: opd(line, "dst")?,
        },
        "str_cat" => ExtBox::StrCat {
            src: str_arg(line, "src")?,
            dst: opd(line, "dst")?,
        },
        "sub_str" => ExtBox::SubStr {
            src: str_arg(line, "src")?,
            index: opd(line, "index")?,
            count: opd(line, "count")?,
            dst: opd(line, "dst")?,
        },
        "str_find" => ExtBox::StrFind {
            chars: line.field("chars")?.flag()?,
            src: str_arg(line, "src")?,
            pattern: str_arg(line, "pattern")?,
            pos: opd(line, "pos")?,
        },
        "clock" => ExtBox::Clock {
            op: line.field("op")?.choice(ClockOp::ALL, "clock op")?,
            buf: opd(line, "buf")?,
        },
        "pid" => ExtBox::Pid {
            table: opd(line, "table")?,
            lp: line.field("loop")?.number("PID loop")?,
        },
        "comm" => ExtBox::Comm {
            op: line.field("op")?.choice(&CommOp::ALL, "communication op")?,
            table: opd(line, "table")?,
            port: line.field("port")?.number("port")?,
        },
        "hsc_define" => ExtBox::HscDefine {
            counter: line.field("hsc")?.number("counter")?,
            mode: line.field("mode")?.number("HSC mode")?,
        },
        "hsc" => ExtBox::Hsc {
            counter: line.field("hsc")?.number("counter")?,
        },
        "pls" => ExtBox::Pls {
            channel: line.field("q")?.number("pulse channel")?,
        },
        _ => return Err(key.unknown("ext op")),
    })
}

/// Reads a string compare after its `str_compare` keyword.
pub(super) fn parse_str_compare(line: &mut Line<'_>) -> Result<StrCompare> {
    Ok(StrCompare {
        form: line.field("form")?.choice(StackForm::ALL, "stack form")?,
        ne: line.field("ne")?.flag()?,
        lhs: str_arg(line, "lhs")?,
        rhs: str_arg(line, "rhs")?,
    })
}
