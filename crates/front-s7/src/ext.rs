//! The instructions of s7-200-more §4–§7 (tables, ASCII and number text, strings, the clock,
//! PID and the string compare contacts): their operand classes, lowered to
//! [`Op::Ext`]/[`Op::StrCompare`], and their STL spelling for the printer. Both directions
//! live here so that a mnemonic's operands are written down once.

use crate::classes::{R, Val};
use crate::lexer::{Line, Tok};
use crate::operand::Syn;
use crate::print::{b, d, r, w};
use crate::program::{Lowerer, PouState};
use stljit_core::Area;
use stljit_core::Width::{Byte, Word};
use stljit_core::ir::{
    ClockOp, ExtBox, FindRel, MAX_STRING, NumType, Op, Operand, StackForm, StrArg, StrCompare,
};
use stljit_source::{Code, clip};

/// A byte address starting a run (buffer, clock buffer): no constants or accumulators.
pub(crate) const fn run(out: bool) -> Val {
    let v = if out {
        Val::output(Byte)
    } else {
        Val::input(Byte)
    };
    Val {
        acc_const: false,
        ..v
    }
}

/// A table's word address (`VW200`, `T37`, `*VD4`): no constants or accumulators.
const TABLE: Val = Val {
    acc_const: false,
    ..Val::output(Word)
};

impl<'s> Lowerer<'s> {
    /// A string operand: a string in V or L memory (`VB100`, `LB4`, `*VD8`), or for an input
    /// (`out` false) a constant string `"…"`, stored in the bytes of its file's encoding.
    fn string(&mut self, t: Tok<'_>, out: bool) -> R<StrArg> {
        if let Some(inner) = t.text.strip_prefix('"') {
            let Some(inner) = inner.strip_suffix('"').filter(|s| !s.contains('"')) else {
                return Err(self.cx.report(
                    Code::Malformed,
                    t,
                    format!("malformed constant string `{}`", clip(t.text)),
                    Some("a constant string is text in double quotes, without `\"` inside".into()),
                ));
            };
            if out {
                return Err(self.cx.report(
                    Code::ReadOnly,
                    t,
                    format!("the constant string `{}` is written here", clip(t.text)),
                    Some("the output string must be in V or L memory".into()),
                ));
            }
            let encoding = self
                .cx
                .encodings
                .get(self.cx.file.index())
                .copied()
                .unwrap_or(stljit_source::Encoding::Utf8);
            let bytes = stljit_source::decode::encode(inner, encoding);
            if bytes.len() > MAX_STRING {
                return Err(self.cx.report(
                    Code::NumberRange,
                    t,
                    format!("the constant string has {} bytes", bytes.len()),
                    Some(format!("a string holds at most {MAX_STRING} bytes")),
                ));
            }
            return Ok(StrArg::Const(bytes));
        }
        // A peek without diagnostics: `value` reports everything else, once.
        let found = match self.cx.scope().resolve(t.text).map(|r| r.syn) {
            Ok(Syn::Mem {
                area: Area::V | Area::L,
                width: Byte,
                ..
            })
            | Ok(Syn::Indirect { .. })
            | Err(_) => None,
            Ok(other) => Some(other.describe()),
        };
        if let Some(found) = found {
            let constant = if out {
                ""
            } else {
                ", a constant string \"…\""
            };
            return Err(self.cx.report(
                Code::OperandClass,
                t,
                format!("expected a string, found {found} `{}`", clip(t.text)),
                Some(format!(
                    "a string is named by its first byte: allowed VB, LB, *VD, *LD, *AC{constant}"
                )),
            ));
        }
        Ok(StrArg::Mem(self.cx.value(t, run(out))?))
    }

    /// A string output (`OUT` of SCPY, ITS, …).
    fn string_out(&mut self, t: Tok<'_>) -> R<Operand> {
        match self.string(t, true)? {
            StrArg::Mem(o) => Ok(o),
            // `string(.., true)` rejects constants.
            StrArg::Const(_) => Err(crate::classes::Reported),
        }
    }

    /// Lowers one box of §4–§7 (mnemonic `m`, upper case).
    pub(crate) fn ext(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        let o = line.ops;
        let n = match m {
            "ATT" | "FIFO" | "LIFO" | "SLEN" | "SCPY" | "SCAT" | "PID" => 2,
            "TODR" | "TODW" | "TODRX" | "TODWX" => 1,
            "SSCPY" => 4,
            _ => 3,
        };
        self.arity(line, n, n)?;
        let num = |m: &str| match m.as_bytes()[0] {
            b'I' => NumType::Int,
            b'D' => NumType::DInt,
            _ => NumType::Real,
        };
        let to_num = |m: &str| match m.as_bytes()[2] {
            b'I' => NumType::Int,
            b'D' => NumType::DInt,
            _ => NumType::Real,
        };
        let b = match m {
            "ATT" => {
                let data = self.cx.value(o[0], Val::input(Word));
                let table = self.cx.value(o[1], TABLE);
                ExtBox::TableAdd {
                    data: data?,
                    table: self.table(o[1], table?)?,
                }
            }
            "FIFO" | "LIFO" => {
                let table = self.cx.value(o[0], TABLE);
                let data = self.cx.value(
                    o[1],
                    Val {
                        aq_out: true,
                        ..Val::output(Word)
                    },
                );
                ExtBox::TableTake {
                    lifo: m == "LIFO",
                    table: self.table(o[0], table?)?,
                    data: data?,
                }
            }
            "FND=" | "FND<>" | "FND<" | "FND>" => {
                let rel = match &m[3..] {
                    "=" => FindRel::Eq,
                    "<>" => FindRel::Ne,
                    "<" => FindRel::Lt,
                    _ => FindRel::Gt,
                };
                let table = self.cx.value(o[0], TABLE);
                let pattern = self.cx.value(o[1], Val::input(Word));
                let index = self.cx.value(o[2], Val::output(Word));
                ExtBox::TableFind {
                    rel,
                    table: self.table(o[0], table?)?,
                    pattern: pattern?,
                    index: index?,
                }
            }
            "ATH" | "HTA" => {
                let src = self.cx.value(o[0], run(false));
                let dst = self.cx.value(o[1], run(true));
                let len = self.cx.value(o[2], Val::input(Byte));
                let (src, dst, len) = (src?, dst?, len?);
                if m == "ATH" {
                    ExtBox::AsciiToHex { src, dst, len }
                } else {
                    ExtBox::HexToAscii { src, dst, len }
                }
            }
            "ITA" | "DTA" | "RTA" | "ITS" | "DTS" | "RTS" => {
                let ty = num(m);
                let string = m.ends_with('S');
                let src = self.cx.value(o[0], number(ty, false));
                let dst = if string {
                    self.string_out(o[1])
                } else {
                    self.cx.value(o[1], run(true))
                };
                let fmt = self.cx.value(o[2], Val::input(Byte));
                ExtBox::NumToText {
                    ty,
                    string,
                    src: src?,
                    dst: dst?,
                    fmt: fmt?,
                }
            }
            "STI" | "STD" | "STR" => {
                let ty = to_num(m);
                let src = self.string(o[0], false);
                let index = self.cx.value(o[1], Val::input(Byte));
                let dst = self.cx.value(o[2], number(ty, true));
                ExtBox::TextToNum {
                    ty,
                    src: src?,
                    index: index?,
                    dst: dst?,
                }
            }
            "SLEN" => {
                let src = self.string(o[0], false);
                let dst = self.cx.value(o[1], Val::output(Byte));
                ExtBox::StrLen {
                    src: src?,
                    dst: dst?,
                }
            }
            "SCPY" | "SCAT" => {
                let src = self.string(o[0], false);
                let dst = self.string_out(o[1]);
                let (src, dst) = (src?, dst?);
                if m == "SCPY" {
                    ExtBox::StrCopy { src, dst }
                } else {
                    ExtBox::StrCat { src, dst }
                }
            }
            "SSCPY" => {
                let src = self.string(o[0], false);
                let index = self.cx.value(o[1], Val::input(Byte));
                let count = self.cx.value(o[2], Val::input(Byte));
                let dst = self.string_out(o[3]);
                ExtBox::SubStr {
                    src: src?,
                    index: index?,
                    count: count?,
                    dst: dst?,
                }
            }
            "SFND" | "CFND" => {
                let src = self.string(o[0], false);
                let pattern = self.string(o[1], false);
                let pos = self.cx.value(o[2], Val::output(Byte));
                ExtBox::StrFind {
                    chars: m == "CFND",
                    src: src?,
                    pattern: pattern?,
                    pos: pos?,
                }
            }
            "TODR" | "TODW" | "TODRX" | "TODWX" => {
                let op = match m {
                    "TODR" => ClockOp::Read,
                    "TODW" => ClockOp::Write,
                    "TODRX" => ClockOp::ReadExt,
                    _ => ClockOp::WriteExt,
                };
                let read = matches!(op, ClockOp::Read | ClockOp::ReadExt);
                let buf = self.cx.value(o[0], run(read))?;
                if !self.cx.profile.clock.present() {
                    self.cx.report(
                        Code::NoClock,
                        self.mnemonic,
                        format!("the {} has no real-time clock", self.cx.profile.model),
                        Some(format!(
                            "`{m}` fails with 16#000C (and ENO = 0) at run time; choose --cpu s7-200 or --cpu smart for a CPU with a clock"
                        )),
                    );
                }
                ExtBox::Clock { op, buf }
            }
            _ => return self.pid(ps, line),
        };
        self.emit(ps, Op::Ext(Box::new(b)));
        Ok(())
    }

    /// A table operand: any word address but the analog areas.
    fn table(&mut self, t: Tok<'_>, o: Operand) -> R<Operand> {
        if let Operand::Mem(l) = o
            && matches!(l.area, Area::AI | Area::AQ)
        {
            return Err(self.cx.report(
                Code::OperandClass,
                t,
                format!("`{}` cannot hold a table", clip(t.text)),
                Some("allowed: VW, IW, QW, MW, SW, SMW, LW, T, C, *VD, *LD, *AC".into()),
            ));
        }
        Ok(o)
    }

    /// `PID TBL, LOOP` (§7.1): TBL a constant VB address whose loop table fits in V, LOOP a
    /// constant 0–7 used by no other PID of the program.
    fn pid(&mut self, ps: &mut PouState, line: &Line<'_>) -> R<()> {
        let o = line.ops;
        let lp = self
            .cx
            .number(o[1], 0, 7, "PID loop number", Code::NumberRange);
        let table = match self.cx.syn(o[0]) {
            Ok(Syn::Mem {
                area: Area::V,
                width: Byte,
                offset,
            }) => {
                let need = self.cx.profile.pid_table_bytes();
                let size = self.cx.profile.area_size(Area::V);
                if offset.saturating_add(need) > size {
                    return Err(self.cx.report(
                        Code::OutOfRange,
                        o[0],
                        format!(
                            "the loop table at `{}` runs past the end of V",
                            clip(o[0].text)
                        ),
                        Some(format!(
                            "the {} needs {need} bytes of loop table: allowed VB0 - VB{}",
                            self.cx.profile.model,
                            size - need
                        )),
                    ));
                }
                Operand::Mem(stljit_core::ir::Loc {
                    area: Area::V,
                    offset,
                })
            }
            Ok(other) => {
                return Err(self.cx.report(
                    Code::OperandClass,
                    o[0],
                    format!(
                        "expected the loop table's VB address, found {} `{}`",
                        other.describe(),
                        clip(o[0].text)
                    ),
                    Some("allowed: a constant V byte address (VB100)".into()),
                ));
            }
            Err(e) => return Err(e),
        };
        let lp = lp? as u8;
        let span = self.cx.span(o[1]);
        if let Some(first) = self.pid_loops.get(&lp) {
            let place = self.cx.place(*first);
            return Err(self.cx.report(
                Code::PidLoopTwice,
                o[1],
                format!("PID loop {lp} is already used on {place}"),
                Some("each PID loop number (0-7) belongs to one PID instruction".into()),
            ));
        }
        self.pid_loops.insert(lp, span);
        self.emit(ps, Op::Ext(Box::new(ExtBox::Pid { table, lp })));
        Ok(())
    }

    /// `LDS=`, `AS<>`, `OS=`, … (§5.6).
    pub(crate) fn str_compare(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        self.arity(line, 2, 2)?;
        let form = match m.as_bytes()[0] {
            b'L' => StackForm::Load,
            b'A' => StackForm::And,
            _ => StackForm::Or,
        };
        let lhs = self.string(line.ops[0], false);
        let rhs = self.string(line.ops[1], false);
        let c = StrCompare {
            form,
            ne: m.ends_with("<>"),
            lhs: lhs?,
            rhs: rhs?,
        };
        self.emit(ps, Op::StrCompare(Box::new(c)));
        Ok(())
    }
}

/// The operand class of a number of type `ty`, an input or an output.
fn number(ty: NumType, out: bool) -> Val {
    match (ty, out) {
        (NumType::Real, false) => Val::REAL_IN,
        (NumType::Real, true) => Val::REAL_OUT,
        (t, false) => Val::input(t.width()),
        (t, true) => Val::output(t.width()),
    }
}

/// A string input as STL writes it (a constant string in quotes: its bytes as UTF-8 text, or
/// Latin-1 where they are not UTF-8, which only a generated program has).
fn string_text(s: &StrArg) -> String {
    match s {
        StrArg::Mem(o) => b(*o),
        StrArg::Const(bytes) => {
            let text = String::from_utf8(bytes.clone())
                .unwrap_or_else(|_| bytes.iter().map(|&c| char::from(c)).collect());
            format!("\"{text}\"")
        }
    }
}

fn num_text(o: Operand, ty: NumType) -> String {
    match ty {
        NumType::Int => w(o),
        NumType::DInt => d(o),
        NumType::Real => r(o),
    }
}

/// The STL text of an [`ExtBox`].
pub(crate) fn print_ext(x: &ExtBox) -> String {
    match x {
        ExtBox::TableAdd { data, table } => format!("ATT {}, {}", w(*data), w(*table)),
        ExtBox::TableTake { lifo, table, data } => format!(
            "{} {}, {}",
            if *lifo { "LIFO" } else { "FIFO" },
            w(*table),
            w(*data)
        ),
        ExtBox::TableFind {
            rel,
            table,
            pattern,
            index,
        } => {
            let rel = match rel {
                FindRel::Eq => "=",
                FindRel::Ne => "<>",
                FindRel::Lt => "<",
                FindRel::Gt => ">",
            };
            format!("FND{rel} {}, {}, {}", w(*table), w(*pattern), w(*index))
        }
        ExtBox::AsciiToHex { src, dst, len } => {
            format!("ATH {}, {}, {}", b(*src), b(*dst), b(*len))
        }
        ExtBox::HexToAscii { src, dst, len } => {
            format!("HTA {}, {}, {}", b(*src), b(*dst), b(*len))
        }
        ExtBox::NumToText {
            ty,
            string,
            src,
            dst,
            fmt,
        } => {
            let t = match ty {
                NumType::Int => 'I',
                NumType::DInt => 'D',
                NumType::Real => 'R',
            };
            let k = if *string { 'S' } else { 'A' };
            format!("{t}T{k} {}, {}, {}", num_text(*src, *ty), b(*dst), b(*fmt))
        }
        ExtBox::TextToNum {
            ty,
            src,
            index,
            dst,
        } => {
            let t = match ty {
                NumType::Int => 'I',
                NumType::DInt => 'D',
                NumType::Real => 'R',
            };
            format!(
                "ST{t} {}, {}, {}",
                string_text(src),
                b(*index),
                num_text(*dst, *ty)
            )
        }
        ExtBox::StrLen { src, dst } => format!("SLEN {}, {}", string_text(src), b(*dst)),
        ExtBox::StrCopy { src, dst } => format!("SCPY {}, {}", string_text(src), b(*dst)),
        ExtBox::StrCat { src, dst } => format!("SCAT {}, {}", string_text(src), b(*dst)),
        ExtBox::SubStr {
            src,
            index,
            count,
            dst,
        } => format!(
            "SSCPY {}, {}, {}, {}",
            string_text(src),
            b(*index),
            b(*count),
            b(*dst)
        ),
        ExtBox::StrFind {
            chars,
            src,
            pattern,
            pos,
        } => format!(
            "{} {}, {}, {}",
            if *chars { "CFND" } else { "SFND" },
            string_text(src),
            string_text(pattern),
            b(*pos)
        ),
        ExtBox::Clock { op, buf } => {
            let m = match op {
                ClockOp::Read => "TODR",
                ClockOp::Write => "TODW",
                ClockOp::ReadExt => "TODRX",
                ClockOp::WriteExt => "TODWX",
            };
            format!("{m} {}", b(*buf))
        }
        ExtBox::Pid { table, lp } => format!("PID {}, {lp}", b(*table)),
        ExtBox::HscDefine { counter, mode } => format!("HDEF {counter}, {mode}"),
        ExtBox::Hsc { counter } => format!("HSC {counter}"),
        ExtBox::Pls { channel } => format!("PLS {channel}"),
        ExtBox::Comm { op, table, port } if op.has_port() => {
            format!("{} {}, {port}", op.mnemonic(), b(*table))
        }
        ExtBox::Comm { op, table, .. } => format!("{} {}", op.mnemonic(), b(*table)),
    }
}

/// The STL text of a string compare contact.
pub(crate) fn print_str_compare(c: &StrCompare) -> String {
    let form = match c.form {
        StackForm::Load => "LD",
        StackForm::And => "A",
        StackForm::Or => "O",
    };
    let rel = if c.ne { "<>" } else { "=" };
    format!(
        "{form}S{rel} {}, {}",
        string_text(&c.lhs),
        string_text(&c.rhs)
    )
}
