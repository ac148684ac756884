//! Instruction lowering (spec §4.1-§4.12): one arm per lowering routine, a [`Group`] of
//! `mnemonics::TABLE`, turning checked operands into IR ops. Program control (§4.13) is in
//! `control.rs`.

use crate::classes::{BitClass, R, Val};
use crate::lexer::{Line, Tok};
use crate::mnemonics::{self, Group};
use crate::operand::Syn;
use crate::program::{Lowerer, PouState};
use stljit_core::EdgeSlot;
use stljit_core::Width::{self, Byte, DWord, Word};
use stljit_core::ir::{ArithOp, BoxOp, CmpOp, CmpType, Contact, Conversion, LogicOp, Op, Operand};
use stljit_source::Code;
use stljit_source::clip;

fn width_of(c: u8) -> Width {
    match c {
        b'B' => Byte,
        b'W' => Word,
        _ => DWord,
    }
}

/// Splits a compare mnemonic (`LDW>=`) into its stack form, type and relation.
pub(crate) fn compare(m: &str) -> Option<(u8, CmpType, CmpOp)> {
    let (form, rest) = if let Some(r) = m.strip_prefix("LD") {
        (b'L', r)
    } else if let Some(r) = m.strip_prefix('A') {
        (b'A', r)
    } else {
        (b'O', m.strip_prefix('O')?)
    };
    let ty = match rest.as_bytes().first()? {
        b'B' => CmpType::Byte,
        b'W' => CmpType::Int,
        b'D' => CmpType::DInt,
        b'R' => CmpType::Real,
        _ => return None,
    };
    let op = match &rest[1..] {
        "=" | "==" => CmpOp::Eq,
        "<>" => CmpOp::Ne,
        ">=" => CmpOp::Ge,
        "<=" => CmpOp::Le,
        ">" => CmpOp::Gt,
        "<" => CmpOp::Lt,
        _ => return None,
    };
    Some((form, ty, op))
}

impl<'s> Lowerer<'s> {
    /// Checks the operand count.
    pub(crate) fn arity(&mut self, line: &Line<'_>, lo: usize, hi: usize) -> R<()> {
        if (lo..=hi).contains(&line.n_ops) && line.operands().iter().all(|t| !t.text.is_empty()) {
            return Ok(());
        }
        let want = if lo == hi {
            format!("{lo}")
        } else {
            format!("{lo} to {hi}")
        };
        let (t, msg) = if line.n_ops < lo {
            (
                self.mnemonic,
                format!(
                    "`{}` needs {want} operand(s), found {}",
                    self.mnemonic.text, line.n_ops
                ),
            )
        } else if line.n_ops > hi {
            (
                line.rest,
                format!(
                    "`{}` takes {want} operand(s), found {}",
                    self.mnemonic.text, line.n_ops
                ),
            )
        } else {
            let empty = line
                .operands()
                .iter()
                .position(|t| t.text.is_empty())
                .unwrap_or(0);
            let t = Tok {
                text: "",
                col: line.ops[empty].col,
                len: 1,
            };
            (
                t,
                format!(
                    "operand {} of `{}` is missing",
                    empty + 1,
                    self.mnemonic.text
                ),
            )
        };
        let help = format!("`{}` takes {want} operand(s)", self.mnemonic.text);
        Err(self.cx.report(Code::OperandCount, t, msg, Some(help)))
    }

    fn boxed(&mut self, ps: &mut PouState, b: BoxOp) -> R<()> {
        self.emit(ps, Op::Box(b));
        Ok(())
    }

    /// Both value operands of a two-operand box (`IN, OUT`).
    fn in_out(&mut self, line: &Line<'_>, src: Val, dst: Val) -> R<(Operand, Operand)> {
        self.arity(line, 2, 2)?;
        let a = self.cx.value(line.ops[0], src);
        let b = self.cx.value(line.ops[1], dst);
        Ok((a?, b?))
    }

    /// A single in-place operand.
    fn one_out(&mut self, line: &Line<'_>, w: Width) -> R<Operand> {
        self.arity(line, 1, 1)?;
        self.cx.value(line.ops[0], Val::output(w))
    }

    /// A constant count must lie in `lo..=hi` (variable counts are checked at run time).
    fn const_count(&mut self, t: Tok<'_>, count: Operand, lo: i64, hi: i64) -> R<()> {
        if let Operand::Const(c) = count {
            let v = i64::from(c as u8 as i8);
            let v = if lo < 0 { v } else { i64::from(c) };
            if !(lo..=hi).contains(&v) {
                return Err(self.cx.report(
                    Code::NumberRange,
                    t,
                    format!("count `{}` is out of range", clip(t.text)),
                    Some(format!("allowed: {lo} .. {hi}")),
                ));
            }
        }
        Ok(())
    }

    /// Lowers one instruction line whose upper-cased mnemonic is `m`, or reports an unknown or
    /// out-of-scope mnemonic.
    pub(crate) fn instr(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        let Some(group) = mnemonics::group(m) else {
            self.unknown(self.mnemonic);
            return Ok(());
        };
        let o = line.ops;
        let bytes = m.as_bytes();
        let op = match group {
            Group::Contact => {
                self.arity(line, 1, 1)?;
                let immediate = m.ends_with('I');
                let negated = m.contains('N');
                let bit = self.cx.bit(
                    o[0],
                    if immediate {
                        BitClass::Input
                    } else {
                        BitClass::Read
                    },
                )?;
                let c = if immediate {
                    Contact::ImmediateInput { bit, negated }
                } else {
                    Contact::Bit { bit, negated }
                };
                match bytes[0] {
                    b'L' => Op::Load(c),
                    b'A' => Op::And(c),
                    _ => Op::Or(c),
                }
            }
            Group::Coil => {
                self.arity(line, 1, 1)?;
                let immediate = m == "=I";
                let class = if immediate {
                    BitClass::Output
                } else {
                    BitClass::Write
                };
                Op::Assign {
                    bit: self.cx.bit(o[0], class)?,
                    immediate,
                }
            }
            Group::SetReset => return self.set_reset(ps, m, line),
            Group::StackOp => {
                self.arity(line, 0, 0)?;
                match m {
                    "NOT" => Op::Not,
                    "ALD" => Op::AndBlock,
                    "OLD" => Op::OrBlock,
                    "LPS" => Op::Dup,
                    "LRD" => Op::ReadSecond,
                    "LPP" => Op::Pop,
                    _ => Op::AndEno,
                }
            }
            Group::Edge => {
                self.arity(line, 0, 0)?;
                let slot = EdgeSlot(u16::try_from(self.edges).unwrap_or(u16::MAX));
                self.edges += 1;
                if self.edges == usize::from(self.cx.profile.max_edges) + 1 {
                    self.cx.report(
                        Code::TooManyEdges,
                        self.mnemonic,
                        format!("more than {} EU/ED instructions", self.cx.profile.max_edges),
                        Some(format!(
                            "the {} allows {} edge instructions per program",
                            self.cx.profile.model, self.cx.profile.max_edges
                        )),
                    );
                }
                Op::Edge {
                    slot,
                    falling: m == "ED",
                }
            }
            Group::Pick => {
                self.arity(line, 1, 1)?;
                Op::Pick(
                    u8::try_from(self.cx.number(o[0], 0, 8, "stack level", Code::LdsRange)?)
                        .unwrap_or(0),
                )
            }
            Group::Timer(kind) => {
                self.arity(line, 2, 2)?;
                let timer = self.cx.timer(o[0]);
                let preset = self.cx.value(o[1], Val::input(Word));
                let timer = timer?;
                self.use_timer(o[0], timer, kind);
                Op::Timer {
                    kind,
                    timer,
                    preset: preset?,
                }
            }
            Group::Counter(kind) => {
                self.arity(line, 2, 2)?;
                let counter = self.cx.counter(o[0]);
                let preset = self.cx.value(o[1], Val::input(Word));
                let counter = counter?;
                self.use_counter(o[0], counter, kind);
                Op::Counter {
                    kind,
                    counter,
                    preset: preset?,
                }
            }
            Group::Move => {
                let width = width_of(bytes[3]);
                let (src, dst) = match m {
                    "MOVR" => (Val::REAL_IN, Val::REAL_OUT),
                    "MOVD" => (
                        Val {
                            addr_of: true,
                            ..Val::input(DWord)
                        },
                        Val::output(DWord),
                    ),
                    "MOVW" => (
                        Val::input(Word),
                        Val {
                            aq_out: true,
                            ..Val::output(Word)
                        },
                    ),
                    _ => (Val::input(width), Val::output(width)),
                };
                let (src, dst) = self.in_out(line, src, dst)?;
                return self.boxed(ps, BoxOp::Move { width, src, dst });
            }
            Group::Swap => {
                let dst = self.one_out(line, Word)?;
                return self.boxed(ps, BoxOp::Swap { dst });
            }
            Group::BlockMove => {
                self.arity(line, 3, 3)?;
                let width = if m == "FILL" {
                    Word
                } else {
                    width_of(bytes[2])
                };
                let addr = |v: Val| Val {
                    acc_const: false,
                    ..v
                };
                let src = if m == "FILL" {
                    Val::input(Word)
                } else {
                    addr(Val::input(width))
                };
                let src = self.cx.value(o[0], src);
                let dst = self.cx.value(o[1], addr(Val::output(width)));
                let count = self.cx.value(o[2], Val::input(Byte));
                let (src, dst, count) = (src?, dst?, count?);
                self.const_count(o[2], count, 1, 255)?;
                let b = if m == "FILL" {
                    BoxOp::Fill { src, dst, count }
                } else {
                    BoxOp::BlockMove {
                        width,
                        src,
                        dst,
                        count,
                    }
                };
                return self.boxed(ps, b);
            }
            Group::Arith => {
                let op = match bytes[0] {
                    b'+' => ArithOp::Add,
                    b'-' => ArithOp::Sub,
                    b'*' => ArithOp::Mul,
                    _ => ArithOp::Div,
                };
                let b = match bytes[1] {
                    b'R' => {
                        let (src, dst) = self.in_out(line, Val::REAL_IN, Val::REAL_OUT)?;
                        BoxOp::RealArith { op, src, dst }
                    }
                    c => {
                        let width = if c == b'I' { Word } else { DWord };
                        let (src, dst) =
                            self.in_out(line, Val::input(width), Val::output(width))?;
                        BoxOp::IntArith {
                            op,
                            width,
                            src,
                            dst,
                        }
                    }
                };
                return self.boxed(ps, b);
            }
            Group::MulDiv => {
                let (src, dst) = self.in_out(line, Val::input(Word), Val::output(DWord))?;
                let b = if m == "MUL" {
                    BoxOp::MulWide { src, dst }
                } else {
                    BoxOp::DivWide { src, dst }
                };
                return self.boxed(ps, b);
            }
            Group::RealFunc(func) => {
                let (src, dst) = self.in_out(line, Val::REAL_IN, Val::REAL_OUT)?;
                return self.boxed(ps, BoxOp::RealFunc { func, src, dst });
            }
            Group::Step => {
                let width = width_of(bytes[3]);
                let dst = self.one_out(line, width)?;
                let up = bytes[0] == b'I';
                return self.boxed(ps, BoxOp::Step { width, up, dst });
            }
            Group::WordLogic => {
                let width = width_of(bytes[m.len() - 1]);
                let op = match bytes[0] {
                    b'A' => LogicOp::And,
                    b'O' => LogicOp::Or,
                    _ => LogicOp::Xor,
                };
                let (src, dst) = self.in_out(line, Val::input(width), Val::output(width))?;
                return self.boxed(
                    ps,
                    BoxOp::Logic {
                        op,
                        width,
                        src,
                        dst,
                    },
                );
            }
            Group::Invert => {
                let width = width_of(bytes[3]);
                let dst = self.one_out(line, width)?;
                return self.boxed(ps, BoxOp::Invert { width, dst });
            }
            Group::ShiftRotate => {
                let width = width_of(bytes[2]);
                let left = bytes[1] == b'L';
                let (dst, count) = {
                    self.arity(line, 2, 2)?;
                    let d = self.cx.value(o[0], Val::output(width));
                    let c = self.cx.value(o[1], Val::input(Byte));
                    (d?, c?)
                };
                let b = BoxOp::shift_or_rotate(bytes[0] == b'R', left, width, dst, count);
                return self.boxed(ps, b);
            }
            Group::ShiftRegister => {
                self.arity(line, 3, 3)?;
                let data = self.cx.bit(o[0], BitClass::MemRead);
                let start = self.cx.bit(o[1], BitClass::MemWrite);
                let len = self.cx.value(o[2], Val::input(Byte));
                let (data, start, len) = (data?, start?, len?);
                self.const_count(o[2], len, -64, 64)?;
                if len == Operand::Const(0) {
                    return Err(self.cx.report(
                        Code::NumberRange,
                        o[2],
                        "SHRB length 0".to_owned(),
                        Some("allowed: -64 .. -1, 1 .. 64".into()),
                    ));
                }
                return self.boxed(ps, BoxOp::ShiftRegister { data, start, len });
            }
            Group::Convert => {
                let (conv, src, dst) = match m {
                    "BTI" => (Conversion::ByteToInt, Val::input(Byte), Val::output(Word)),
                    "ITB" => (Conversion::IntToByte, Val::input(Word), Val::output(Byte)),
                    "ITD" => (Conversion::IntToDInt, Val::input(Word), Val::output(DWord)),
                    "DTI" => (Conversion::DIntToInt, Val::input(DWord), Val::output(Word)),
                    "DTR" => (Conversion::DIntToReal, Val::input(DWord), Val::REAL_OUT),
                    "ROUND" => (Conversion::Round, Val::REAL_IN, Val::output(DWord)),
                    "TRUNC" => (Conversion::Trunc, Val::REAL_IN, Val::output(DWord)),
                    "DECO" => (Conversion::Decode, Val::input(Byte), Val::output(Word)),
                    "ENCO" => (Conversion::Encode, Val::input(Word), Val::output(Byte)),
                    _ => (Conversion::Segment, Val::input(Byte), Val::output(Byte)),
                };
                let (src, dst) = self.in_out(line, src, dst)?;
                return self.boxed(ps, BoxOp::Convert { conv, src, dst });
            }
            Group::Bcd => {
                self.arity(line, 1, 2)?;
                let conv = if m == "BCDI" {
                    Conversion::BcdToInt
                } else {
                    Conversion::IntToBcd
                };
                let dst = if line.n_ops == 2 {
                    // The LAD box spelling `BCDI IN, OUT` is MOVW IN, OUT plus the in-place form.
                    let (src, dst) = self.in_out(line, Val::input(Word), Val::output(Word))?;
                    self.boxed(
                        ps,
                        BoxOp::Move {
                            width: Word,
                            src,
                            dst,
                        },
                    )?;
                    dst
                } else {
                    self.one_out(line, Word)?
                };
                return self.boxed(
                    ps,
                    BoxOp::Convert {
                        conv,
                        src: dst,
                        dst,
                    },
                );
            }
            Group::ImmediateByte => return self.immediate_byte(ps, m, line),
            Group::Nop => {
                self.arity(line, 0, 1)?;
                if line.n_ops == 1 {
                    self.cx
                        .number(o[0], 0, 255, "NOP count", Code::NumberRange)?;
                }
                Op::Nop
            }
            Group::Compare => {
                let Some((form, ty, rel)) = compare(m) else {
                    // Unreachable: a test checks that `compare` reads every `Compare` entry.
                    self.unknown(self.mnemonic);
                    return Ok(());
                };
                self.arity(line, 2, 2)?;
                let v = match ty {
                    CmpType::Real => Val::REAL_IN,
                    t => Val::input(t.width()),
                };
                let lhs = self.cx.value(o[0], v);
                let rhs = self.cx.value(o[1], v);
                let c = Contact::Compare {
                    ty,
                    op: rel,
                    lhs: lhs?,
                    rhs: rhs?,
                };
                match form {
                    b'L' => Op::Load(c),
                    b'A' => Op::And(c),
                    _ => Op::Or(c),
                }
            }
            Group::Control(flow) => return self.control(ps, flow, m, line),
            Group::Interrupt => return self.interrupt(ps, m, line),
            Group::Ext => return self.ext(ps, m, line),
            Group::Hsc => return self.hsc(ps, m, line),
            Group::Pls => return self.pls(ps, line),
            Group::Comm => return self.comm(ps, m, line),
            Group::StrCompare => return self.str_compare(ps, m, line),
        };
        self.emit(ps, op);
        Ok(())
    }

    /// `S`/`R`/`SI`/`RI bit, N`; `R` on a timer or counter is a full reset.
    fn set_reset(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        self.arity(line, 2, 2)?;
        let o = line.ops;
        let immediate = m.len() == 2;
        let value = m.starts_with('S');
        let count = self.cx.value(o[1], Val::input(Byte));
        if immediate {
            let start = self.cx.bit(o[0], BitClass::Output);
            let count = count?;
            self.const_count(o[1], count, 1, 128)?;
            self.emit(
                ps,
                Op::SetRange {
                    start: start?,
                    count,
                    value,
                    immediate,
                },
            );
            return Ok(());
        }
        let target = if value { None } else { self.cx.syn(o[0]).ok() };
        let op = match target {
            Some(Syn::Timer(_)) => Op::ResetTimers {
                first: self.cx.timer(o[0])?,
                count: count?,
            },
            Some(Syn::Counter(_)) => Op::ResetCounters {
                first: self.cx.counter(o[0])?,
                count: count?,
            },
            _ => {
                let start = self.cx.bit(o[0], BitClass::Write);
                Op::SetRange {
                    start: start?,
                    count: count?,
                    value,
                    immediate,
                }
            }
        };
        self.emit(ps, op);
        Ok(())
    }

    /// `BIR IB, OUT` / `BIW IN, QB`.
    fn immediate_byte(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        self.arity(line, 2, 2)?;
        let o = line.ops;
        let (phys, area, prefix) = if m == "BIR" {
            (o[0], stljit_core::Area::I, "IB")
        } else {
            (o[1], stljit_core::Area::Q, "QB")
        };
        let other = if m == "BIR" {
            self.cx.value(o[1], Val::output(Byte))
        } else {
            self.cx.value(o[0], Val::input(Byte))
        };
        let byte = match self.cx.syn(phys)? {
            Syn::Mem {
                area: a,
                width: Byte,
                offset,
            } if a == area => {
                if offset >= self.cx.profile.area_size(area) {
                    let last = self.cx.profile.area_size(area).saturating_sub(1);
                    return Err(self.cx.report(
                        Code::OutOfRange,
                        phys,
                        format!(
                            "`{}` is out of range for the {}",
                            clip(phys.text),
                            self.cx.profile.model
                        ),
                        Some(format!("allowed: {prefix}0 - {prefix}{last}")),
                    ));
                }
                offset
            }
            other_syn => {
                return Err(self.cx.report(
                    Code::OperandClass,
                    phys,
                    format!(
                        "expected a physical {prefix} byte, found {} `{}`",
                        other_syn.describe(),
                        clip(phys.text)
                    ),
                    Some(format!("allowed: {prefix}n")),
                ));
            }
        };
        let other = other?;
        let b = if m == "BIR" {
            BoxOp::ImmediateRead {
                input: byte,
                dst: other,
            }
        } else {
            BoxOp::ImmediateWrite {
                src: other,
                output: byte,
            }
        };
        self.boxed(ps, b)
    }
}
