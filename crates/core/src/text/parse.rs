//! The reader: [`parse`] turns IR text back into a [`Program`]. It works line by line (each
//! line split into words and strings by [`super::lex`]) and stops at the first error, which names
//! its line and column. No input makes it panic.

use super::error::{ParseErrorKind, Result, error};
use super::lex::{Line, Word, col_of};
use super::{MAGIC, VERSION};
use crate::area::Width;
use crate::index::{CounterId, EdgeSlot, FileId, LabelId, OpIdx, PouId, TimerId};
use crate::ir::{
    Arg, ArgDir, ArgValue, ArithOp, BoxOp, CallArgs, CmpOp, CmpType, Contact, Conversion,
    CounterDecl, CounterKind, EdgeDecl, LogicOp, OmronArith, OmronBox, OmronCounterKind,
    OmronTimerKind, Op, Operand, Pou, PouKind, Program, RealFn, TimerDecl, TimerKind,
};
use crate::profile::{ProfileId, Resolution};
use std::fmt;

/// Reads a program written by [`super::print`] (or by hand in the same grammar).
pub fn parse(text: &str) -> Result<Program> {
    let mut r = Reader::default();
    let mut last = (1, 1);
    for (i, raw) in text.lines().enumerate() {
        let no = u32::try_from(i + 1).unwrap_or(u32::MAX);
        last = (no, col_of(raw.chars().count()));
        let mut line = Line::split(raw, no)?;
        if !line.is_empty() {
            r.line(&mut line)?;
        }
    }
    r.finish(last)
}

/// The program being read.
#[derive(Default)]
struct Reader {
    header: bool,
    profile: Option<ProfileId>,
    depth: Option<u8>,
    files: Vec<String>,
    timers: Vec<TimerDecl>,
    counters: Vec<CounterDecl>,
    edges: Vec<EdgeDecl>,
    pous: Vec<Pou>,
    open: Option<OpenPou>,
}

/// A POU between its `{` and `}`.
struct OpenPou {
    pou: Pou,
    /// Set after the first op without a location or the first trailing `loc` line.
    locs_done: bool,
    /// Set after the first trailing `loc` line: no op may follow.
    ops_done: bool,
}

impl Reader {
    fn line(&mut self, line: &mut Line<'_>) -> Result<()> {
        if !self.header {
            let magic = line.word("the header `stljit-ir`")?;
            if magic.text != MAGIC {
                return Err(magic.err(ParseErrorKind::Expected {
                    expected: "the header `stljit-ir`",
                    found: format!("`{}`", magic.text),
                }));
            }
            let v = line.word("the format version")?;
            if v.text != VERSION.to_string() {
                return Err(v.err(ParseErrorKind::Version(v.text.to_owned())));
            }
            self.header = true;
            return line.finish();
        }
        if let Some(open) = &mut self.open {
            if open.body_line(line)?
                && let Some(done) = self.open.take()
            {
                self.pous.push(done.pou);
            }
            return Ok(());
        }
        let key = line.word("a declaration")?;
        match key.text {
            "profile" => {
                let w = line.word("a profile name")?;
                let p = ProfileId::from_name(w.text).ok_or_else(|| w.unknown("profile"))?;
                if self.profile.replace(p).is_some() {
                    return Err(key.err(ParseErrorKind::Duplicate("`profile`")));
                }
            }
            "logic_stack_depth" => {
                let d = line.word("the depth")?.number("logic stack depth")?;
                if self.depth.replace(d).is_some() {
                    return Err(key.err(ParseErrorKind::Duplicate("`logic_stack_depth`")));
                }
            }
            "file" => {
                positional(line.word("a file index")?, FileId(0), self.files.len())?;
                self.files.push(line.string("the file name")?);
            }
            "timer" => {
                let id = TimerId(line.word("a timer")?.index(TimerId(0), "timer")?);
                let kind = line.field("kind")?.choice(TimerKind::ALL, "timer kind")?;
                let res = line.field("resolution")?;
                let ms = res
                    .text
                    .strip_suffix("ms")
                    .ok_or_else(|| res.unknown("resolution"))?;
                let resolution = Word { text: ms, ..res }
                    .number("resolution")
                    .ok()
                    .and_then(Resolution::from_millis)
                    .ok_or_else(|| res.unknown("resolution"))?;
                self.timers.push(TimerDecl {
                    id,
                    kind,
                    resolution,
                });
            }
            "counter" => {
                let id = CounterId(line.word("a counter")?.index(CounterId(0), "counter")?);
                let kind = line
                    .field("kind")?
                    .choice(CounterKind::ALL, "counter kind")?;
                self.counters.push(CounterDecl { id, kind });
            }
            "edge" => {
                positional(line.word("an edge slot")?, EdgeSlot(0), self.edges.len())?;
                let init = line.field("init")?.flag()?;
                self.edges.push(EdgeDecl { init });
            }
            "pou" => {
                positional(line.word("a POU index")?, PouId(0), self.pous.len())?;
                let kind = pou_kind(line.word("`main`, `subroutine(n)` or `interrupt(n)`")?)?;
                let name = line.string("the POU name")?;
                let brace = line.word("`{`")?;
                if brace.text != "{" {
                    return Err(line.err(
                        brace.col,
                        ParseErrorKind::Expected {
                            expected: "`{`",
                            found: format!("`{}`", brace.text),
                        },
                    ));
                }
                self.open = Some(OpenPou {
                    pou: Pou {
                        name,
                        kind,
                        ops: Vec::new(),
                        locs: Vec::new(),
                        labels: Vec::new(),
                    },
                    locs_done: false,
                    ops_done: false,
                });
            }
            _ => return Err(key.unknown("declaration")),
        }
        line.finish()
    }

    fn finish(self, (line, col): (u32, u32)) -> Result<Program> {
        let missing = |what| Err(error(line, col, ParseErrorKind::Missing(what)));
        if !self.header {
            return missing("the header `stljit-ir 1`");
        }
        if self.open.is_some() {
            return missing("the `}` that closes the last POU");
        }
        let Some(profile) = self.profile else {
            return missing("`profile`");
        };
        let Some(logic_stack_depth) = self.depth else {
            return missing("`logic_stack_depth`");
        };
        Ok(Program {
            profile,
            pous: self.pous,
            timers: self.timers,
            counters: self.counters,
            edges: self.edges,
            logic_stack_depth,
            files: self.files,
        })
    }
}

/// Checks that a declaration's index is its position.
fn positional(w: Word<'_>, zero: impl fmt::Display + Copy, at: usize) -> Result<()> {
    let n: u64 = w.index(zero, "an index")?;
    if usize::try_from(n).ok() != Some(at) {
        let z = zero.to_string();
        let prefix = z.strip_suffix('0').unwrap_or(&z);
        return Err(w.err(ParseErrorKind::Index {
            expected: format!("{prefix}{at}"),
            found: w.text.to_owned(),
        }));
    }
    Ok(())
}

fn pou_kind(w: Word<'_>) -> Result<PouKind> {
    if w.text == "main" {
        return Ok(PouKind::Main);
    }
    for (head, make) in [
        ("subroutine(", PouKind::Subroutine as fn(u16) -> PouKind),
        ("interrupt(", PouKind::Interrupt as fn(u16) -> PouKind),
    ] {
        if w.text.starts_with(head) {
            let rest = w.tail(head.len());
            let inner = rest
                .text
                .strip_suffix(')')
                .ok_or_else(|| w.unknown("POU kind"))?;
            return Ok(make(
                Word {
                    text: inner,
                    ..rest
                }
                .number("POU number")?,
            ));
        }
    }
    Err(w.unknown("POU kind"))
}

impl OpenPou {
    /// Reads one line inside the POU; returns whether it was the closing `}`.
    fn body_line(&mut self, line: &mut Line<'_>) -> Result<bool> {
        let head = line.word("an op, `target`, `loc` or `}`")?;
        match head.text {
            "}" => {
                line.finish()?;
                return Ok(true);
            }
            "target" => {
                let label = line.word("a label")?;
                positional(label, LabelId(0), self.pou.labels.len())?;
                let at = line.word("an op index")?.index(OpIdx(0), "op index")?;
                self.pou.labels.push(OpIdx(at));
            }
            "loc" => {
                if self.pou.locs.len() < self.pou.ops.len() {
                    return Err(head.err(ParseErrorKind::LocationGap));
                }
                let loc = line.word("a source location")?.src_loc()?;
                self.pou.locs.push(loc);
                self.locs_done = true;
                self.ops_done = true;
            }
            _ => {
                if self.ops_done {
                    return Err(head.err(ParseErrorKind::Expected {
                        expected: "`loc` or `}` (no op follows a trailing location)",
                        found: format!("`{}`", head.text),
                    }));
                }
                positional(head, OpIdx(0), self.pou.ops.len())?;
                match line.word_starting('@') {
                    Some(w) if self.locs_done => return Err(w.err(ParseErrorKind::LocationGap)),
                    Some(w) => self.pou.locs.push(w.src_loc()?),
                    None => self.locs_done = true,
                }
                self.pou.ops.push(op(line)?);
            }
        }
        line.finish()?;
        Ok(false)
    }
}

/// One op, from its keyword to the line's end.
fn op(line: &mut Line<'_>) -> Result<Op> {
    let key = line.word("an op")?;
    Ok(match key.text {
        "load" => Op::Load(contact(line)?),
        "and" => Op::And(contact(line)?),
        "or" => Op::Or(contact(line)?),
        "not" => Op::Not,
        "and_block" => Op::AndBlock,
        "or_block" => Op::OrBlock,
        "dup" => Op::Dup,
        "read_second" => Op::ReadSecond,
        "pop" => Op::Pop,
        "pick" => Op::Pick(line.word("a stack level")?.number("stack level")?),
        "and_eno" => Op::AndEno,
        "edge" => Op::Edge {
            slot: EdgeSlot(line.field("slot")?.index(EdgeSlot(0), "edge slot")?),
            falling: line.field("falling")?.flag()?,
        },
        "assign" => Op::Assign {
            bit: line.field("bit")?.bit()?,
            immediate: line.field("immediate")?.flag()?,
        },
        "set_range" => Op::SetRange {
            start: line.field("start")?.bit()?,
            count: line.field("count")?.operand()?,
            value: line.field("value")?.flag()?,
            immediate: line.field("immediate")?.flag()?,
        },
        "reset_timers" => Op::ResetTimers {
            first: TimerId(line.field("first")?.index(TimerId(0), "timer")?),
            count: line.field("count")?.operand()?,
        },
        "reset_counters" => Op::ResetCounters {
            first: CounterId(line.field("first")?.index(CounterId(0), "counter")?),
            count: line.field("count")?.operand()?,
        },
        "timer" => Op::Timer {
            kind: line.field("kind")?.choice(TimerKind::ALL, "timer kind")?,
            timer: TimerId(line.field("timer")?.index(TimerId(0), "timer")?),
            preset: line.field("preset")?.operand()?,
        },
        "counter" => Op::Counter {
            kind: line
                .field("kind")?
                .choice(CounterKind::ALL, "counter kind")?,
            counter: CounterId(line.field("counter")?.index(CounterId(0), "counter")?),
            preset: line.field("preset")?.operand()?,
        },
        "box" => Op::Box(box_op(line)?),
        "jump" => Op::Jump(LabelId(line.word("a label")?.index(LabelId(0), "label")?)),
        "label" => Op::Label(LabelId(line.word("a label")?.index(LabelId(0), "label")?)),
        "call" => Op::Call(PouId(line.word("a POU")?.index(PouId(0), "POU index")?)),
        "call_args" => call_args(line)?,
        "return" => Op::Return {
            conditional: line.field("conditional")?.flag()?,
        },
        "end" => Op::End {
            conditional: line.field("conditional")?.flag()?,
        },
        "stop" => Op::Stop,
        "wdr" => Op::Wdr,
        "nop" => Op::Nop,
        "for" => Op::For {
            index: line.field("index")?.operand()?,
            init: line.field("init")?.operand()?,
            limit: line.field("limit")?.operand()?,
            next: op_index(line.field("next")?)?,
        },
        "next" => Op::Next {
            head: op_index(line.field("head")?)?,
        },
        "scr_begin" => Op::ScrBegin {
            bit: line.field("bit")?.bit()?,
        },
        "scr_transition" => Op::ScrTransition {
            to: line.field("to")?.bit()?,
            from: line.field("from")?.bit()?,
        },
        "scr_cond_end" => Op::ScrCondEnd {
            end: op_index(line.field("end")?)?,
        },
        "scr_end" => Op::ScrEnd,
        "interlock" => Op::Interlock,
        "interlock_end" => Op::InterlockEnd,
        "task_start" => Op::TaskStart,
        "omron_timer" => Op::OmronTimer {
            kind: line
                .field("kind")?
                .choice(OmronTimerKind::ALL, "Omron timer kind")?,
            timer: TimerId(line.field("timer")?.index(TimerId(0), "timer")?),
            set_value: line.field("set_value")?.operand()?,
        },
        "omron_counter" => Op::OmronCounter {
            kind: line
                .field("kind")?
                .choice(OmronCounterKind::ALL, "Omron counter kind")?,
            counter: CounterId(line.field("counter")?.index(CounterId(0), "counter")?),
            set_value: line.field("set_value")?.operand()?,
        },
        "omron" => Op::Omron(omron_box(line)?),
        _ => return Err(key.unknown("op")),
    })
}

fn omron_box(line: &mut Line<'_>) -> Result<OmronBox> {
    let key = line.word("an Omron box op")?;
    Ok(match key.text {
        "move" => {
            let double = line.field("double")?.flag()?;
            let (src, dst) = src_dst(line)?;
            OmronBox::Move { double, src, dst }
        }
        "compare" => OmronBox::Compare {
            double: line.field("double")?.flag()?,
            signed: line.field("signed")?.flag()?,
            lhs: line.field("lhs")?.operand()?,
            rhs: line.field("rhs")?.operand()?,
        },
        "flags" => OmronBox::Flags {
            save: line.field("save")?.flag()?,
        },
        "set_index" => OmronBox::SetIndex {
            ea: line.field("ea")?.number("effective address")?,
            ir: line.field("ir")?.number("index register")?,
        },
        "arith" => OmronBox::Arith {
            op: line
                .field("op")?
                .choice(OmronArith::ALL, "Omron arithmetic op")?,
            lhs: line.field("lhs")?.operand()?,
            rhs: line.field("rhs")?.operand()?,
            dst: line.field("dst")?.operand()?,
        },
        _ => return Err(key.unknown("Omron box op")),
    })
}

/// `call_args callee=POU arg=DIR,KIND,FORMAL,ACTUAL …` (KIND `Bit` or a `Width`).
fn call_args(line: &mut Line<'_>) -> Result<Op> {
    let callee = PouId(line.field("callee")?.index(PouId(0), "POU index")?);
    let mut args = Vec::new();
    while let Some(w) = line.optional_field("arg") {
        let [dir, kind, formal, actual] = w.split_n::<4>(',')?;
        let dir = dir.choice(ArgDir::ALL, "argument direction")?;
        let value = if kind.text == "Bit" {
            ArgValue::Bit {
                formal: formal.bit()?,
                actual: actual.bit()?,
            }
        } else {
            ArgValue::Value {
                width: kind.choice(&[Width::Byte, Width::Word, Width::DWord], "width")?,
                formal: formal.loc()?,
                actual: actual.operand()?,
            }
        };
        args.push(Arg { dir, value });
    }
    Ok(Op::CallArgs(Box::new(CallArgs { callee, args })))
}

fn op_index(w: Word<'_>) -> Result<OpIdx> {
    Ok(OpIdx(w.index(OpIdx(0), "op index")?))
}

fn contact(line: &mut Line<'_>) -> Result<Contact> {
    let kind = line.word("`bit`, `bit_not`, `input`, `input_not` or `compare`")?;
    Ok(match kind.text {
        "bit" | "bit_not" => Contact::Bit {
            bit: line.word("a bit")?.bit()?,
            negated: kind.text == "bit_not",
        },
        "input" | "input_not" => Contact::ImmediateInput {
            bit: line.word("a bit")?.bit()?,
            negated: kind.text == "input_not",
        },
        "compare" => Contact::Compare {
            ty: line.field("ty")?.choice(CmpType::ALL, "compare type")?,
            op: line.field("op")?.choice(CmpOp::ALL, "compare relation")?,
            lhs: line.field("lhs")?.operand()?,
            rhs: line.field("rhs")?.operand()?,
        },
        _ => return Err(kind.unknown("contact")),
    })
}

fn width(line: &mut Line<'_>) -> Result<Width> {
    line.field("width")?.choice(&Width::ALL, "width")
}

fn src_dst(line: &mut Line<'_>) -> Result<(Operand, Operand)> {
    Ok((line.field("src")?.operand()?, line.field("dst")?.operand()?))
}

fn box_op(line: &mut Line<'_>) -> Result<BoxOp> {
    let key = line.word("a box op")?;
    Ok(match key.text {
        "move" => {
            let width = width(line)?;
            let (src, dst) = src_dst(line)?;
            BoxOp::Move { width, src, dst }
        }
        "swap" => BoxOp::Swap {
            dst: line.field("dst")?.operand()?,
        },
        "block_move" => {
            let width = width(line)?;
            let (src, dst) = src_dst(line)?;
            let count = line.field("count")?.operand()?;
            BoxOp::BlockMove {
                width,
                src,
                dst,
                count,
            }
        }
        "fill" => {
            let (src, dst) = src_dst(line)?;
            let count = line.field("count")?.operand()?;
            BoxOp::Fill { src, dst, count }
        }
        "int_arith" => {
            let op = line.field("op")?.choice(ArithOp::ALL, "arithmetic op")?;
            let width = width(line)?;
            let (src, dst) = src_dst(line)?;
            BoxOp::IntArith {
                op,
                width,
                src,
                dst,
            }
        }
        "mul_wide" => {
            let (src, dst) = src_dst(line)?;
            BoxOp::MulWide { src, dst }
        }
        "div_wide" => {
            let (src, dst) = src_dst(line)?;
            BoxOp::DivWide { src, dst }
        }
        "real_arith" => {
            let op = line.field("op")?.choice(ArithOp::ALL, "arithmetic op")?;
            let (src, dst) = src_dst(line)?;
            BoxOp::RealArith { op, src, dst }
        }
        "real_func" => {
            let func = line.field("func")?.choice(RealFn::ALL, "real function")?;
            let (src, dst) = src_dst(line)?;
            BoxOp::RealFunc { func, src, dst }
        }
        "step" => BoxOp::Step {
            width: width(line)?,
            up: line.field("up")?.flag()?,
            dst: line.field("dst")?.operand()?,
        },
        "logic" => {
            let op = line.field("op")?.choice(LogicOp::ALL, "logic op")?;
            let width = width(line)?;
            let (src, dst) = src_dst(line)?;
            BoxOp::Logic {
                op,
                width,
                src,
                dst,
            }
        }
        "invert" => BoxOp::Invert {
            width: width(line)?,
            dst: line.field("dst")?.operand()?,
        },
        "shift" | "rotate" => {
            let left = line.field("left")?.flag()?;
            let width = width(line)?;
            let dst = line.field("dst")?.operand()?;
            let count = line.field("count")?.operand()?;
            BoxOp::shift_or_rotate(key.text == "rotate", left, width, dst, count)
        }
        "shift_register" => BoxOp::ShiftRegister {
            data: line.field("data")?.bit()?,
            start: line.field("start")?.bit()?,
            len: line.field("len")?.operand()?,
        },
        "convert" => {
            let conv = line.field("conv")?.choice(Conversion::ALL, "conversion")?;
            let (src, dst) = src_dst(line)?;
            BoxOp::Convert { conv, src, dst }
        }
        "immediate_read" => BoxOp::ImmediateRead {
            input: line.field("input")?.number("input byte")?,
            dst: line.field("dst")?.operand()?,
        },
        "immediate_write" => BoxOp::ImmediateWrite {
            src: line.field("src")?.operand()?,
            output: line.field("output")?.number("output byte")?,
        },
        _ => return Err(key.unknown("box op")),
    })
}
