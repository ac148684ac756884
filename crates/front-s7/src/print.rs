//! IR → STL text. The output uses MicroWIN's block layout (so block names survive) and parses
//! back to the same IR, up to source locations; fuzz reproducers and the round-trip fuzz target
//! rely on that.

use crate::locals::Section;
use crate::spelling::{area_prefix, counter_mnemonic, timer_mnemonic, width_letter};
use std::fmt::Write as _;
use stljit_core::PouId;
use stljit_core::ir::{
    Address, ArgDir, ArgValue, ArithOp, BitLoc, BoxOp, CmpOp, CmpType, Contact, Conversion,
    LogicOp, Op, Operand, Pou, PouKind, Program, RealFn,
};
use stljit_core::{Area, Width};

/// Prints a bit operand (`I0.3`, `T37`).
fn bit(b: BitLoc) -> String {
    match b.area {
        Area::TimerBit => format!("T{}", b.byte),
        Area::CounterBit => format!("C{}", b.byte),
        a => format!("{}{}.{}", area_prefix(a), b.byte, b.bit),
    }
}

/// Prints a memory location read or written with `width`.
fn loc(area: Area, offset: u32, width: Width) -> String {
    match area {
        Area::AI => format!("AIW{offset}"),
        Area::AQ => format!("AQW{offset}"),
        Area::TimerValue => format!("T{}", offset / 2),
        Area::CounterValue => format!("C{}", offset / 2),
        Area::HC => format!("HC{}", offset / 4),
        Area::AC => format!("AC{}", offset / 4),
        a => format!("{}{}{offset}", area_prefix(a), width_letter(width)),
    }
}

/// Prints a value operand of `width`; `real` prints constants as real literals.
fn val(o: Operand, width: Width, real: bool) -> String {
    match o {
        Operand::Mem(l) => loc(l.area, l.offset, width),
        Operand::Const(c) if real => {
            let f = f32::from_bits(c);
            if f.is_finite() {
                format!("{f:?}")
            } else {
                format!("16#{c:08X}")
            }
        }
        Operand::Const(c) => match width {
            Width::Byte => format!("{}", c & 0xFF),
            Width::Word => format!("{}", c as u16 as i16),
            Width::DWord => format!("{}", c as i32),
        },
        Operand::Indirect(l) => format!("*{}", loc(l.area, l.offset, Width::DWord)),
        Operand::AddressOf(l) => format!("&{}", loc(l.area, l.offset, Width::Byte)),
        // The verifier rejects Omron operands in S7 programs.
        Operand::Omron(r) => format!("// not S7: {r:?}"),
    }
}

fn b(o: Operand) -> String {
    val(o, Width::Byte, false)
}
fn w(o: Operand) -> String {
    val(o, Width::Word, false)
}
fn d(o: Operand) -> String {
    val(o, Width::DWord, false)
}
fn r(o: Operand) -> String {
    val(o, Width::DWord, true)
}

fn contact(form: &str, c: &Contact) -> String {
    match c {
        Contact::Bit { bit: b, negated } => {
            format!("{form}{} {}", if *negated { "N" } else { "" }, bit(*b))
        }
        Contact::ImmediateInput { bit: b, negated } => {
            format!("{form}{}I {}", if *negated { "N" } else { "" }, bit(*b))
        }
        Contact::Compare { ty, op, lhs, rhs } => {
            let t = match ty {
                CmpType::Byte => 'B',
                CmpType::Int => 'W',
                CmpType::DInt => 'D',
                CmpType::Real => 'R',
            };
            let rel = match op {
                CmpOp::Eq => "=",
                CmpOp::Ne => "<>",
                CmpOp::Ge => ">=",
                CmpOp::Le => "<=",
                CmpOp::Gt => ">",
                CmpOp::Lt => "<",
            };
            let real = *ty == CmpType::Real;
            let wd = ty.width();
            format!(
                "{form}{t}{rel} {}, {}",
                val(*lhs, wd, real),
                val(*rhs, wd, real)
            )
        }
    }
}

fn arith(op: ArithOp) -> char {
    match op {
        ArithOp::Add => '+',
        ArithOp::Sub => '-',
        ArithOp::Mul => '*',
        ArithOp::Div => '/',
    }
}

fn box_op(x: &BoxOp) -> String {
    match *x {
        BoxOp::Move { width, src, dst } => {
            format!(
                "MOV{} {}, {}",
                width_letter(width),
                val(src, width, false),
                val(dst, width, false)
            )
        }
        BoxOp::Swap { dst } => format!("SWAP {}", w(dst)),
        BoxOp::BlockMove {
            width,
            src,
            dst,
            count,
        } => format!(
            "BM{} {}, {}, {}",
            width_letter(width),
            val(src, width, false),
            val(dst, width, false),
            b(count)
        ),
        BoxOp::Fill { src, dst, count } => format!("FILL {}, {}, {}", w(src), w(dst), b(count)),
        BoxOp::IntArith {
            op,
            width,
            src,
            dst,
        } => {
            let s = if width == Width::Word { 'I' } else { 'D' };
            format!(
                "{}{s} {}, {}",
                arith(op),
                val(src, width, false),
                val(dst, width, false)
            )
        }
        BoxOp::MulWide { src, dst } => format!("MUL {}, {}", w(src), d(dst)),
        BoxOp::DivWide { src, dst } => format!("DIV {}, {}", w(src), d(dst)),
        BoxOp::RealArith { op, src, dst } => format!("{}R {}, {}", arith(op), r(src), r(dst)),
        BoxOp::RealFunc { func, src, dst } => {
            let name = match func {
                RealFn::Sqrt => "SQRT",
                RealFn::Ln => "LN",
                RealFn::Exp => "EXP",
                RealFn::Sin => "SIN",
                RealFn::Cos => "COS",
                RealFn::Tan => "TAN",
            };
            format!("{name} {}, {}", r(src), r(dst))
        }
        BoxOp::Step { width, up, dst } => format!(
            "{}{} {}",
            if up { "INC" } else { "DEC" },
            width_letter(width),
            val(dst, width, false)
        ),
        BoxOp::Logic {
            op,
            width,
            src,
            dst,
        } => {
            let name = match op {
                LogicOp::And => "AND",
                LogicOp::Or => "OR",
                LogicOp::Xor => "XOR",
            };
            format!(
                "{name}{} {}, {}",
                width_letter(width),
                val(src, width, false),
                val(dst, width, false)
            )
        }
        BoxOp::Invert { width, dst } => {
            format!("INV{} {}", width_letter(width), val(dst, width, false))
        }
        BoxOp::Shift {
            left,
            width,
            dst,
            count,
        }
        | BoxOp::Rotate {
            left,
            width,
            dst,
            count,
        } => {
            let kind = if matches!(x, BoxOp::Shift { .. }) {
                'S'
            } else {
                'R'
            };
            let dir = if left { 'L' } else { 'R' };
            format!(
                "{kind}{dir}{} {}, {}",
                width_letter(width),
                val(dst, width, false),
                b(count)
            )
        }
        BoxOp::ShiftRegister { data, start, len } => {
            format!("SHRB {}, {}, {}", bit(data), bit(start), b(len))
        }
        BoxOp::Convert { conv, src, dst } => {
            let (name, iw, ow, ir, or) = match conv {
                Conversion::ByteToInt => ("BTI", Width::Byte, Width::Word, false, false),
                Conversion::IntToByte => ("ITB", Width::Word, Width::Byte, false, false),
                Conversion::IntToDInt => ("ITD", Width::Word, Width::DWord, false, false),
                Conversion::DIntToInt => ("DTI", Width::DWord, Width::Word, false, false),
                Conversion::DIntToReal => ("DTR", Width::DWord, Width::DWord, false, true),
                Conversion::Round => ("ROUND", Width::DWord, Width::DWord, true, false),
                Conversion::Trunc => ("TRUNC", Width::DWord, Width::DWord, true, false),
                Conversion::Decode => ("DECO", Width::Byte, Width::Word, false, false),
                Conversion::Encode => ("ENCO", Width::Word, Width::Byte, false, false),
                Conversion::Segment => ("SEG", Width::Byte, Width::Byte, false, false),
                Conversion::BcdToInt | Conversion::IntToBcd => {
                    let name = if conv == Conversion::BcdToInt {
                        "BCDI"
                    } else {
                        "IBCD"
                    };
                    return if src == dst {
                        format!("{name} {}", w(dst))
                    } else {
                        format!("{name} {}, {}", w(src), w(dst))
                    };
                }
            };
            format!("{name} {}, {}", val(src, iw, ir), val(dst, ow, or))
        }
        BoxOp::ImmediateRead { input, dst } => format!("BIR IB{input}, {}", b(dst)),
        BoxOp::ImmediateWrite { src, output } => format!("BIW {}, QB{output}", b(src)),
    }
}

/// An address the way STL text and `--watch` spell it (`Q0.1`, `VW100`, `AC0`, `T37`).
pub fn print_address(a: &Address) -> String {
    match *a {
        Address::Bit(b) => bit(b),
        Address::Value { loc: l, width } => loc(l.area, l.offset, width),
    }
}

/// Prints one op of `pou` as an STL line (without indentation).
pub fn print_op(program: &Program, pou: &Pou, op: &Op) -> String {
    match op {
        Op::Load(c) => contact("LD", c),
        Op::And(c) => contact("A", c),
        Op::Or(c) => contact("O", c),
        Op::Not => "NOT".into(),
        Op::AndBlock => "ALD".into(),
        Op::OrBlock => "OLD".into(),
        Op::Dup => "LPS".into(),
        Op::ReadSecond => "LRD".into(),
        Op::Pop => "LPP".into(),
        Op::Pick(n) => format!("LDS {n}"),
        Op::AndEno => "AENO".into(),
        Op::Edge { falling, .. } => if *falling { "ED" } else { "EU" }.into(),
        Op::Assign { bit: b, immediate } => {
            format!("={} {}", if *immediate { "I" } else { "" }, bit(*b))
        }
        Op::SetRange {
            start,
            count,
            value,
            immediate,
        } => format!(
            "{}{} {}, {}",
            if *value { "S" } else { "R" },
            if *immediate { "I" } else { "" },
            bit(*start),
            b(*count)
        ),
        Op::ResetTimers { first, count } => format!("R {first}, {}", b(*count)),
        Op::ResetCounters { first, count } => format!("R {first}, {}", b(*count)),
        Op::Timer {
            kind,
            timer,
            preset,
        } => format!("{} {timer}, {}", timer_mnemonic(*kind), w(*preset)),
        Op::Counter {
            kind,
            counter,
            preset,
        } => {
            format!("{} {counter}, {}", counter_mnemonic(*kind), w(*preset))
        }
        Op::Box(x) => box_op(x),
        Op::Jump(l) => format!("JMP {}", l.0),
        Op::Label(l) => format!("LBL {}", l.0),
        Op::Call(id) => format!("CALL {}", call_target(program, *id)),
        Op::CallArgs(c) => {
            let mut text = format!("CALL {}", call_target(program, c.callee));
            for a in &c.args {
                text.push_str(", ");
                text.push_str(&match a.value {
                    ArgValue::Bit { actual, .. } => bit(actual),
                    ArgValue::Value { width, actual, .. } => val(actual, width, false),
                });
            }
            text
        }
        Op::Return { conditional: true } => match pou.kind {
            PouKind::Interrupt(_) => "CRETI".into(),
            _ => "CRET".into(),
        },
        Op::Return { conditional: false } => match pou.kind {
            PouKind::Interrupt(_) => "RETI".into(),
            _ => "RET".into(),
        },
        Op::End { conditional } => if *conditional { "END" } else { "MEND" }.into(),
        Op::Stop => "STOP".into(),
        Op::Wdr => "WDR".into(),
        Op::Nop => "NOP".into(),
        Op::For {
            index, init, limit, ..
        } => format!("FOR {}, {}, {}", w(*index), w(*init), w(*limit)),
        Op::Next { .. } => "NEXT".into(),
        Op::ScrBegin { bit: b } => format!("LSCR {}", bit(*b)),
        Op::ScrTransition { to, .. } => format!("SCRT {}", bit(*to)),
        Op::ScrCondEnd { .. } => "CSCRE".into(),
        Op::ScrEnd => "SCRE".into(),
        // The verifier rejects these on S7 profiles, so no S7 program holds one.
        Op::Interlock
        | Op::InterlockEnd
        | Op::TaskStart
        | Op::OmronTimer { .. }
        | Op::OmronCounter { .. }
        | Op::Omron(_) => format!("// not S7: {op:?}"),
    }
}

fn call_target(program: &Program, id: PouId) -> String {
    match program.pous.get(id.index()).map(|p| p.kind) {
        Some(PouKind::Subroutine(n)) => format!("SBR{n}"),
        _ => program
            .pous
            .get(id.index())
            .map_or("?", |p| p.name.as_str())
            .to_owned(),
    }
}

/// The `VAR_…` sections of subroutine `id`, rebuilt from the first call with parameters that
/// targets it (the IR keeps no declarations): in the calls' argument order, which is table
/// order, so the front end allocates the same L addresses; BOOL, BYTE, WORD or DWORD by width.
fn declarations(program: &Program, id: PouId) -> String {
    let call = program
        .pous
        .iter()
        .flat_map(|p| &p.ops)
        .find_map(|op| match op {
            Op::CallArgs(c) if c.callee == id => Some(c),
            _ => None,
        });
    let mut out = String::new();
    let Some(call) = call else { return out };
    for dir in ArgDir::ALL {
        let section = match dir {
            ArgDir::In => Section::In,
            ArgDir::InOut => Section::InOut,
            ArgDir::Out => Section::Out,
        };
        let mut body = String::new();
        for (i, a) in call.args.iter().enumerate().filter(|(_, a)| a.dir == *dir) {
            let ty = match a.value {
                ArgValue::Bit { .. } => "BOOL",
                ArgValue::Value {
                    width: Width::Byte, ..
                } => "BYTE",
                ArgValue::Value {
                    width: Width::Word, ..
                } => "WORD",
                ArgValue::Value { .. } => "DWORD",
            };
            let _ = writeln!(body, "arg{i}:{ty};");
        }
        if !body.is_empty() {
            let _ = write!(out, "{}\n{body}END_VAR\n", section.keyword());
        }
    }
    out
}

/// Prints a whole program in MicroWIN block layout.
pub fn print_program(program: &Program) -> String {
    let mut out = String::new();
    for (i, pou) in program.pous.iter().enumerate() {
        let (kw, id) = match pou.kind {
            PouKind::Main => ("ORGANIZATION_BLOCK", "OB1".to_owned()),
            PouKind::Subroutine(n) => ("SUBROUTINE_BLOCK", format!("SBR{n}")),
            PouKind::Interrupt(n) => ("INTERRUPT_BLOCK", format!("INT{n}")),
        };
        let vars = declarations(program, PouId::new(i));
        let _ = writeln!(out, "{kw} {}:{id}\n{vars}BEGIN", pou.name);
        for op in &pou.ops {
            let _ = writeln!(out, "\t{}", print_op(program, pou, op));
        }
        let _ = writeln!(out, "END_{kw}");
    }
    out
}
