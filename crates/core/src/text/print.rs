//! The printer: [`print`] writes a [`Program`] in the IR text form, one declaration or op per
//! line, every field of every op spelled out.

use super::{MAGIC, VERSION};
use crate::index::{EdgeSlot, FileId, LabelId, OpIdx, PouId};
use crate::ir::{
    ArgValue, BitLoc, BoxOp, Contact, IndexOffset, Loc, OmronBox, OmronRef, Op, Operand, Pou,
    PouKind, Program, SrcLoc,
};
use std::fmt::{self, Write as _};

/// The whole program as IR text; [`super::parse`] reads it back to an equal program.
pub fn print(program: &Program) -> String {
    let mut out = String::with_capacity(64 + 48 * program.op_count());
    // Writing into a `String` cannot fail.
    let _ = write_program(&mut out, program);
    out
}

fn write_program(out: &mut String, p: &Program) -> fmt::Result {
    writeln!(out, "{MAGIC} {VERSION}")?;
    writeln!(out, "profile {}", p.profile.name())?;
    writeln!(out, "logic_stack_depth {}", p.logic_stack_depth)?;
    for (i, name) in p.files.iter().enumerate() {
        writeln!(out, "file {} {}", FileId::new(i), Quoted(name))?;
    }
    for t in &p.timers {
        writeln!(
            out,
            "timer {} kind={:?} resolution={}ms",
            t.id,
            t.kind,
            t.resolution.millis()
        )?;
    }
    for c in &p.counters {
        writeln!(out, "counter {} kind={:?}", c.id, c.kind)?;
    }
    for (i, e) in p.edges.iter().enumerate() {
        writeln!(out, "edge {} init={}", EdgeSlot::new(i), Flag(e.init))?;
    }
    for (i, pou) in p.pous.iter().enumerate() {
        out.push('\n');
        write_pou(out, i, pou)?;
    }
    Ok(())
}

fn write_pou(out: &mut String, index: usize, pou: &Pou) -> fmt::Result {
    let kind = match pou.kind {
        PouKind::Main => "main".to_owned(),
        PouKind::Subroutine(n) => format!("subroutine({n})"),
        PouKind::Interrupt(n) => format!("interrupt({n})"),
    };
    writeln!(
        out,
        "pou {} {kind} {} {{",
        PouId::new(index),
        Quoted(&pou.name)
    )?;
    for (l, at) in pou.labels.iter().enumerate() {
        writeln!(out, "  target {} {at}", LabelId::new(l))?;
    }
    for (i, op) in pou.ops.iter().enumerate() {
        let head = OpIdx::new(i).to_string();
        match pou.locs.get(i) {
            Some(loc) => write!(out, "  {head:<6} {:<16} ", At(*loc))?,
            None => write!(out, "  {head:<6} ")?,
        }
        write_op(out, op)?;
        out.push('\n');
    }
    // Locations past the last op (a malformed but representable program) keep their place.
    for loc in pou.locs.iter().skip(pou.ops.len()) {
        writeln!(out, "  loc {}", At(*loc))?;
    }
    writeln!(out, "}}")
}

fn write_op(out: &mut String, op: &Op) -> fmt::Result {
    match op {
        Op::Load(c) => write!(out, "load {}", ContactText(c)),
        Op::And(c) => write!(out, "and {}", ContactText(c)),
        Op::Or(c) => write!(out, "or {}", ContactText(c)),
        Op::Not => out.write_str("not"),
        Op::AndBlock => out.write_str("and_block"),
        Op::OrBlock => out.write_str("or_block"),
        Op::Dup => out.write_str("dup"),
        Op::ReadSecond => out.write_str("read_second"),
        Op::Pop => out.write_str("pop"),
        Op::Pick(n) => write!(out, "pick {n}"),
        Op::AndEno => out.write_str("and_eno"),
        Op::Edge { slot, falling } => {
            write!(out, "edge slot={slot} falling={}", Flag(*falling))
        }
        Op::Assign { bit, immediate } => {
            write!(
                out,
                "assign bit={} immediate={}",
                Bit(*bit),
                Flag(*immediate)
            )
        }
        Op::SetRange {
            start,
            count,
            value,
            immediate,
        } => write!(
            out,
            "set_range start={} count={} value={} immediate={}",
            Bit(*start),
            Opd(*count),
            Flag(*value),
            Flag(*immediate)
        ),
        Op::ResetTimers { first, count } => {
            write!(out, "reset_timers first={first} count={}", Opd(*count))
        }
        Op::ResetCounters { first, count } => {
            write!(out, "reset_counters first={first} count={}", Opd(*count))
        }
        Op::Timer {
            kind,
            timer,
            preset,
        } => write!(
            out,
            "timer kind={kind:?} timer={timer} preset={}",
            Opd(*preset)
        ),
        Op::Counter {
            kind,
            counter,
            preset,
        } => write!(
            out,
            "counter kind={kind:?} counter={counter} preset={}",
            Opd(*preset)
        ),
        Op::Box(b) => {
            out.write_str("box ")?;
            write_box(out, b)
        }
        Op::Jump(l) => write!(out, "jump {l}"),
        Op::Label(l) => write!(out, "label {l}"),
        Op::Call(p) => write!(out, "call {p}"),
        Op::CallArgs(c) => {
            write!(out, "call_args callee={}", c.callee)?;
            for a in &c.args {
                write!(out, " arg={:?},", a.dir)?;
                match a.value {
                    ArgValue::Bit { formal, actual } => {
                        write!(out, "Bit,{},{}", Bit(formal), Bit(actual))?;
                    }
                    ArgValue::Value {
                        width,
                        formal,
                        actual,
                    } => write!(out, "{width:?},{},{}", Place(formal), Opd(actual))?,
                }
            }
            Ok(())
        }
        Op::Return { conditional } => write!(out, "return conditional={}", Flag(*conditional)),
        Op::End { conditional } => write!(out, "end conditional={}", Flag(*conditional)),
        Op::Stop => out.write_str("stop"),
        Op::Wdr => out.write_str("wdr"),
        Op::Nop => out.write_str("nop"),
        Op::For {
            index,
            init,
            limit,
            next,
        } => write!(
            out,
            "for index={} init={} limit={} next={next}",
            Opd(*index),
            Opd(*init),
            Opd(*limit)
        ),
        Op::Next { head } => write!(out, "next head={head}"),
        Op::ScrBegin { bit } => write!(out, "scr_begin bit={}", Bit(*bit)),
        Op::ScrTransition { to, from } => {
            write!(out, "scr_transition to={} from={}", Bit(*to), Bit(*from))
        }
        Op::ScrCondEnd { end } => write!(out, "scr_cond_end end={end}"),
        Op::ScrEnd => out.write_str("scr_end"),
        Op::Interlock => out.write_str("interlock"),
        Op::InterlockEnd => out.write_str("interlock_end"),
        Op::TaskStart => out.write_str("task_start"),
        Op::OmronTimer {
            kind,
            timer,
            set_value,
        } => write!(
            out,
            "omron_timer kind={kind:?} timer={timer} set_value={}",
            Opd(*set_value)
        ),
        Op::OmronCounter {
            kind,
            counter,
            set_value,
        } => write!(
            out,
            "omron_counter kind={kind:?} counter={counter} set_value={}",
            Opd(*set_value)
        ),
        Op::Omron(b) => {
            out.write_str("omron ")?;
            write_omron(out, b)
        }
    }
}

fn write_omron(out: &mut String, b: &OmronBox) -> fmt::Result {
    match *b {
        OmronBox::Move { double, src, dst } => write!(
            out,
            "move double={} src={} dst={}",
            Flag(double),
            Opd(src),
            Opd(dst)
        ),
        OmronBox::Compare {
            double,
            signed,
            lhs,
            rhs,
        } => write!(
            out,
            "compare double={} signed={} lhs={} rhs={}",
            Flag(double),
            Flag(signed),
            Opd(lhs),
            Opd(rhs)
        ),
        OmronBox::SetIndex { ea, ir } => write!(out, "set_index ea={ea} ir={ir}"),
        OmronBox::Flags { save } => write!(out, "flags save={}", Flag(save)),
        OmronBox::Arith { op, lhs, rhs, dst } => write!(
            out,
            "arith op={op:?} lhs={} rhs={} dst={}",
            Opd(lhs),
            Opd(rhs),
            Opd(dst)
        ),
    }
}

fn write_box(out: &mut String, b: &BoxOp) -> fmt::Result {
    match *b {
        BoxOp::Move { width, src, dst } => write!(
            out,
            "move width={width:?} src={} dst={}",
            Opd(src),
            Opd(dst)
        ),
        BoxOp::Swap { dst } => write!(out, "swap dst={}", Opd(dst)),
        BoxOp::BlockMove {
            width,
            src,
            dst,
            count,
        } => write!(
            out,
            "block_move width={width:?} src={} dst={} count={}",
            Opd(src),
            Opd(dst),
            Opd(count)
        ),
        BoxOp::Fill { src, dst, count } => write!(
            out,
            "fill src={} dst={} count={}",
            Opd(src),
            Opd(dst),
            Opd(count)
        ),
        BoxOp::IntArith {
            op,
            width,
            src,
            dst,
        } => write!(
            out,
            "int_arith op={op:?} width={width:?} src={} dst={}",
            Opd(src),
            Opd(dst)
        ),
        BoxOp::MulWide { src, dst } => {
            write!(out, "mul_wide src={} dst={}", Opd(src), Opd(dst))
        }
        BoxOp::DivWide { src, dst } => {
            write!(out, "div_wide src={} dst={}", Opd(src), Opd(dst))
        }
        BoxOp::RealArith { op, src, dst } => write!(
            out,
            "real_arith op={op:?} src={} dst={}",
            Opd(src),
            Opd(dst)
        ),
        BoxOp::RealFunc { func, src, dst } => write!(
            out,
            "real_func func={func:?} src={} dst={}",
            Opd(src),
            Opd(dst)
        ),
        BoxOp::Step { width, up, dst } => {
            write!(out, "step width={width:?} up={} dst={}", Flag(up), Opd(dst))
        }
        BoxOp::Logic {
            op,
            width,
            src,
            dst,
        } => write!(
            out,
            "logic op={op:?} width={width:?} src={} dst={}",
            Opd(src),
            Opd(dst)
        ),
        BoxOp::Invert { width, dst } => write!(out, "invert width={width:?} dst={}", Opd(dst)),
        BoxOp::Shift {
            left,
            width,
            dst,
            count,
        } => write!(
            out,
            "shift left={} width={width:?} dst={} count={}",
            Flag(left),
            Opd(dst),
            Opd(count)
        ),
        BoxOp::Rotate {
            left,
            width,
            dst,
            count,
        } => write!(
            out,
            "rotate left={} width={width:?} dst={} count={}",
            Flag(left),
            Opd(dst),
            Opd(count)
        ),
        BoxOp::ShiftRegister { data, start, len } => write!(
            out,
            "shift_register data={} start={} len={}",
            Bit(data),
            Bit(start),
            Opd(len)
        ),
        BoxOp::Convert { conv, src, dst } => write!(
            out,
            "convert conv={conv:?} src={} dst={}",
            Opd(src),
            Opd(dst)
        ),
        BoxOp::ImmediateRead { input, dst } => {
            write!(out, "immediate_read input={input} dst={}", Opd(dst))
        }
        BoxOp::ImmediateWrite { src, output } => {
            write!(out, "immediate_write src={} output={output}", Opd(src))
        }
    }
}

/// A boolean field: `0` or `1`.
struct Flag(bool);

impl fmt::Display for Flag {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.0 { "1" } else { "0" })
    }
}

/// A bit: `Area.byte.bit`.
struct Bit(BitLoc);

impl fmt::Display for Bit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}.{}.{}", self.0.area, self.0.byte, self.0.bit)
    }
}

/// A location: `Area.offset`.
struct Place(Loc);

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}.{}", self.0.area, self.0.offset)
    }
}

/// A value operand: a location, `const(n)`, `deref(location)` or `addr(location)`.
struct Opd(Operand);

impl fmt::Display for Opd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Operand::Mem(l) => write!(f, "{}", Place(l)),
            Operand::Const(n) => write!(f, "const({n})"),
            Operand::Indirect(l) => write!(f, "deref({})", Place(l)),
            Operand::AddressOf(l) => write!(f, "addr({})", Place(l)),
            Operand::Omron(OmronRef::DmBinary(n)) => write!(f, "ind_bin({n})"),
            Operand::Omron(OmronRef::DmBcd(n)) => write!(f, "ind_bcd({n})"),
            Operand::Omron(OmronRef::Index { ir, offset, step }) => {
                let off = match offset {
                    IndexOffset::Const(c) => format!("{c:+}"),
                    IndexOffset::Dr(m) => format!("dr{m}"),
                };
                write!(f, "ind_ir({ir},{off},{})", step.name())
            }
        }
    }
}

/// A contact: `bit B`, `bit_not B`, `input B`, `input_not B` or `compare ty=.. op=.. lhs=.. rhs=..`.
struct ContactText<'a>(&'a Contact);

impl fmt::Display for ContactText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self.0 {
            Contact::Bit { bit, negated } => {
                let word = if negated { "bit_not" } else { "bit" };
                write!(f, "{word} {}", Bit(bit))
            }
            Contact::ImmediateInput { bit, negated } => {
                let word = if negated { "input_not" } else { "input" };
                write!(f, "{word} {}", Bit(bit))
            }
            Contact::Compare { ty, op, lhs, rhs } => write!(
                f,
                "compare ty={ty:?} op={op:?} lhs={} rhs={}",
                Opd(lhs),
                Opd(rhs)
            ),
        }
    }
}

/// A source location: `@file0:12:3`.
struct At(SrcLoc);

impl fmt::Display for At {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = format!("@{}:{}:{}", self.0.file, self.0.line, self.0.col);
        f.pad(&s)
    }
}

/// A string in double quotes; `"`, `\` and control characters are escaped (`\"`, `\\`, `\n`,
/// `\t`, `\r`, `\u{..}`), everything else is written as it is.
struct Quoted<'a>(&'a str);

impl fmt::Display for Quoted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_char('"')?;
        for c in self.0.chars() {
            match c {
                '"' => f.write_str("\\\"")?,
                '\\' => f.write_str("\\\\")?,
                '\n' => f.write_str("\\n")?,
                '\t' => f.write_str("\\t")?,
                '\r' => f.write_str("\\r")?,
                c if c.is_control() => write!(f, "\\u{{{:x}}}", u32::from(c))?,
                c => f.write_char(c)?,
            }
        }
        f.write_char('"')
    }
}
