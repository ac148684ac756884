//! Tests of the IR text form: every op and operand kind prints and parses back, the printed form
//! of a small program is what docs/ir-text.md shows, and no mutation or truncation of a text
//! makes the parser panic or name a place outside the text.

use super::{ParseErrorKind, parse, print};
use crate::area::{Area, Width};
use crate::index::{CounterId, EdgeSlot, FileId, LabelId, OpIdx, PouId, TimerId};
use crate::ir::{
    Arg, ArgDir, ArgValue, ArithOp, BitLoc, BoxOp, CallArgs, CmpOp, CmpType, Contact, Conversion,
    CounterDecl, CounterKind, EdgeDecl, Loc, LogicOp, Op, Operand, Pou, PouKind, Program, RealFn,
    SrcLoc, TimerDecl, TimerKind,
};
use crate::profile::{ProfileId, Resolution};

fn bit(area: Area, byte: u32, bit: u8) -> BitLoc {
    BitLoc { area, byte, bit }
}

fn mem(area: Area, offset: u32) -> Operand {
    Operand::Mem(Loc { area, offset })
}

/// Every operand kind, in every area.
fn operands() -> Vec<Operand> {
    let mut v = vec![Operand::Const(0), Operand::Const(u32::MAX)];
    for (i, &area) in Area::ALL.iter().enumerate() {
        let loc = Loc {
            area,
            offset: 7 * i as u32,
        };
        v.extend([
            Operand::Mem(loc),
            Operand::Indirect(loc),
            Operand::AddressOf(loc),
        ]);
    }
    v
}

/// One op of every variant, every box op and every value of the small enums.
fn every_op() -> Vec<Op> {
    let q = bit(Area::Q, 1, 7);
    let mut ops = Vec::new();
    let ops_of = |i: usize| operands()[i % operands().len()];
    for (i, &area) in Area::ALL.iter().enumerate() {
        let b = bit(area, i as u32, (i % 8) as u8);
        for negated in [false, true] {
            ops.push(Op::Load(Contact::Bit { bit: b, negated }));
            ops.push(Op::And(Contact::ImmediateInput { bit: b, negated }));
        }
    }
    for (i, &ty) in CmpType::ALL.iter().enumerate() {
        for &op in CmpOp::ALL {
            ops.push(Op::Or(Contact::Compare {
                ty,
                op,
                lhs: ops_of(i),
                rhs: ops_of(i + 5),
            }));
        }
    }
    ops.extend([
        Op::Not,
        Op::AndBlock,
        Op::OrBlock,
        Op::Dup,
        Op::ReadSecond,
        Op::Pop,
        Op::Pick(8),
        Op::Pick(255),
        Op::AndEno,
        Op::Edge {
            slot: EdgeSlot(0),
            falling: true,
        },
        Op::Edge {
            slot: EdgeSlot(u16::MAX),
            falling: false,
        },
        Op::Assign {
            bit: q,
            immediate: true,
        },
        Op::SetRange {
            start: q,
            count: Operand::Const(3),
            value: true,
            immediate: false,
        },
        Op::ResetTimers {
            first: TimerId(37),
            count: mem(Area::V, 3),
        },
        Op::ResetCounters {
            first: CounterId(5),
            count: Operand::Const(2),
        },
        Op::Jump(LabelId(0)),
        Op::Label(LabelId(0)),
        Op::Call(PouId(1)),
        Op::CallArgs(Box::new(CallArgs {
            callee: PouId(1),
            args: vec![
                Arg {
                    dir: ArgDir::In,
                    value: ArgValue::Bit {
                        formal: BitLoc {
                            area: Area::L,
                            byte: 0,
                            bit: 0,
                        },
                        actual: q,
                    },
                },
                Arg {
                    dir: ArgDir::In,
                    value: ArgValue::Value {
                        width: Width::Word,
                        formal: Loc {
                            area: Area::L,
                            offset: 1,
                        },
                        actual: Operand::Const(3),
                    },
                },
                Arg {
                    dir: ArgDir::InOut,
                    value: ArgValue::Value {
                        width: Width::DWord,
                        formal: Loc {
                            area: Area::L,
                            offset: 3,
                        },
                        actual: Operand::Indirect(Loc {
                            area: Area::V,
                            offset: 4,
                        }),
                    },
                },
                Arg {
                    dir: ArgDir::Out,
                    value: ArgValue::Value {
                        width: Width::Byte,
                        formal: Loc {
                            area: Area::L,
                            offset: 7,
                        },
                        actual: mem(Area::L, 9),
                    },
                },
            ],
        })),
        Op::CallArgs(Box::new(CallArgs {
            callee: PouId(1),
            args: vec![],
        })),
        Op::Return { conditional: true },
        Op::End { conditional: false },
        Op::Stop,
        Op::Wdr,
        Op::Nop,
        Op::For {
            index: mem(Area::V, 0),
            init: Operand::Const(1),
            limit: mem(Area::AC, 4),
            next: OpIdx(9),
        },
        Op::Next { head: OpIdx(3) },
        Op::ScrBegin {
            bit: bit(Area::S, 0, 1),
        },
        Op::ScrTransition {
            to: bit(Area::S, 0, 2),
            from: bit(Area::S, 0, 1),
        },
        Op::ScrCondEnd { end: OpIdx(12) },
        Op::ScrEnd,
        Op::Interlock,
        Op::InterlockEnd,
        Op::TaskStart,
    ]);
    for &kind in TimerKind::ALL {
        ops.push(Op::Timer {
            kind,
            timer: TimerId(37),
            preset: Operand::Const(100),
        });
    }
    for &kind in CounterKind::ALL {
        ops.push(Op::Counter {
            kind,
            counter: CounterId(u16::MAX),
            preset: mem(Area::CounterValue, 2),
        });
    }
    let (s, d) = (mem(Area::V, 10), mem(Area::L, 60));
    for width in Width::ALL {
        let left = width == Width::Word;
        ops.extend(
            [
                BoxOp::Move {
                    width,
                    src: s,
                    dst: d,
                },
                BoxOp::BlockMove {
                    width,
                    src: Operand::Indirect(Loc {
                        area: Area::AC,
                        offset: 0,
                    }),
                    dst: d,
                    count: Operand::Const(255),
                },
                BoxOp::Step {
                    width,
                    up: left,
                    dst: d,
                },
                BoxOp::Invert { width, dst: d },
                BoxOp::Shift {
                    left,
                    width,
                    dst: d,
                    count: s,
                },
                BoxOp::Rotate {
                    left: !left,
                    width,
                    dst: d,
                    count: s,
                },
            ]
            .map(Op::Box),
        );
        for &op in ArithOp::ALL {
            ops.push(Op::Box(BoxOp::IntArith {
                op,
                width,
                src: s,
                dst: d,
            }));
        }
        for &op in LogicOp::ALL {
            ops.push(Op::Box(BoxOp::Logic {
                op,
                width,
                src: s,
                dst: d,
            }));
        }
    }
    for &op in ArithOp::ALL {
        ops.push(Op::Box(BoxOp::RealArith { op, src: s, dst: d }));
    }
    for &func in RealFn::ALL {
        ops.push(Op::Box(BoxOp::RealFunc {
            func,
            src: s,
            dst: d,
        }));
    }
    for &conv in Conversion::ALL {
        ops.push(Op::Box(BoxOp::Convert {
            conv,
            src: s,
            dst: d,
        }));
    }
    ops.extend(
        [
            BoxOp::Swap { dst: d },
            BoxOp::Fill {
                src: Operand::Const(0xFFFF),
                dst: d,
                count: Operand::Const(1),
            },
            BoxOp::MulWide { src: s, dst: d },
            BoxOp::DivWide { src: s, dst: d },
            BoxOp::ShiftRegister {
                data: bit(Area::I, 0, 0),
                start: bit(Area::V, 100, 7),
                len: Operand::Const(0xF8),
            },
            BoxOp::ImmediateRead { input: 3, dst: d },
            BoxOp::ImmediateWrite {
                src: s,
                output: u32::MAX,
            },
        ]
        .map(Op::Box),
    );
    ops
}

fn pou(name: &str, kind: PouKind, ops: Vec<Op>) -> Pou {
    let locs = (0..ops.len())
        .map(|i| SrcLoc {
            file: FileId(i as u32 % 2),
            line: i as u32 + 1,
            col: 3,
        })
        .collect();
    Pou {
        name: name.to_owned(),
        kind,
        ops,
        locs,
        labels: vec![OpIdx(4), OpIdx(0)],
    }
}

/// A program with every op, every declaration kind and awkward names.
fn sample() -> Program {
    let mut sub = pou(
        "Motor \"Logic\"\t\\ 电机",
        PouKind::Subroutine(7),
        vec![Op::Nop; 3],
    );
    // Locations are a prefix of the ops: the last op has none.
    sub.locs.pop();
    let mut int = pou("INT0", PouKind::Interrupt(u16::MAX), vec![Op::Stop]);
    // A location past the last op.
    int.locs.push(SrcLoc::default());
    Program {
        profile: ProfileId::S7_200,
        pous: vec![
            pou("MAIN", PouKind::Main, every_op()),
            sub,
            int,
            pou("", PouKind::Subroutine(0), Vec::new()),
        ],
        timers: TimerKind::ALL
            .iter()
            .zip([Resolution::Ms1, Resolution::Ms10, Resolution::Ms100])
            .map(|(&kind, resolution)| TimerDecl {
                id: TimerId(32 + kind.code() as u16),
                kind,
                resolution,
            })
            .collect(),
        counters: CounterKind::ALL
            .iter()
            .map(|&kind| CounterDecl {
                id: CounterId(kind.code().into()),
                kind,
            })
            .collect(),
        edges: vec![EdgeDecl { init: false }, EdgeDecl { init: true }],
        logic_stack_depth: 9,
        files: vec!["main.stl".into(), "sub dir/b\"\n.awl".into()],
    }
}

#[test]
fn every_op_prints_and_parses_back() {
    let p = sample();
    let text = print(&p);
    match parse(&text) {
        Ok(back) => assert_eq!(back, p, "{text}"),
        Err(e) => panic!("{e}\n{text}"),
    }
}

#[test]
fn an_empty_program_parses_back() {
    let p = Program {
        profile: ProfileId::A5,
        pous: Vec::new(),
        timers: Vec::new(),
        counters: Vec::new(),
        edges: Vec::new(),
        logic_stack_depth: 0,
        files: Vec::new(),
    };
    assert_eq!(parse(&print(&p)), Ok(p));
}

/// The example of docs/ir-text.md; a change here is a change of the format.
#[test]
fn a_small_program_prints_as_documented() {
    let l = |line| SrcLoc {
        file: FileId(0),
        line,
        col: 1,
    };
    let p = Program {
        profile: ProfileId::A5,
        pous: vec![Pou {
            name: "MAIN".into(),
            kind: PouKind::Main,
            ops: vec![
                Op::Load(Contact::Bit {
                    bit: bit(Area::I, 0, 3),
                    negated: false,
                }),
                Op::Edge {
                    slot: EdgeSlot(0),
                    falling: false,
                },
                Op::Jump(LabelId(0)),
                Op::Label(LabelId(0)),
                Op::Box(BoxOp::Move {
                    width: Width::Word,
                    src: Operand::Const(7),
                    dst: mem(Area::V, 10),
                }),
            ],
            locs: (1..=5).map(l).collect(),
            labels: vec![OpIdx(3)],
        }],
        timers: vec![TimerDecl {
            id: TimerId(37),
            kind: TimerKind::On,
            resolution: Resolution::Ms100,
        }],
        counters: Vec::new(),
        edges: vec![EdgeDecl { init: false }],
        logic_stack_depth: 9,
        files: vec!["main.stl".into()],
    };
    let expected = "\
stljit-ir 1
profile a5
logic_stack_depth 9
file file0 \"main.stl\"
timer T37 kind=On resolution=100ms
edge edge0 init=0

pou pou0 main \"MAIN\" {
  target L0 op3
  op0    @file0:1:1       load bit I.0.3
  op1    @file0:2:1       edge slot=edge0 falling=0
  op2    @file0:3:1       jump L0
  op3    @file0:4:1       label L0
  op4    @file0:5:1       box move width=Word src=const(7) dst=V.10
}
";
    assert_eq!(print(&p), expected);
    assert_eq!(parse(expected), Ok(p));
}

#[test]
fn comments_blank_lines_hex_and_spacing_are_accepted() {
    let text = "; a comment\n\n  stljit-ir   1 ; the header\nprofile A5\nlogic_stack_depth 0x9\n\
                pou pou0 main \"M;A\\u{4e2d}\" {\n op0 load bit V.0x10.7 ;x\n}\n";
    let p = parse(text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.logic_stack_depth, 9);
    assert_eq!(p.pous[0].name, "M;A中");
    assert_eq!(
        p.pous[0].ops,
        vec![Op::Load(Contact::Bit {
            bit: bit(Area::V, 16, 7),
            negated: false,
        })]
    );
    assert!(p.pous[0].locs.is_empty());
}

/// Each error names the place of its cause.
#[test]
fn errors_name_line_column_and_cause() {
    let head = "stljit-ir 1\nprofile a5\nlogic_stack_depth 9\n";
    let cases: &[(&str, u32, u32, &str)] = &[
        ("", 1, 1, "missing the header"),
        ("stljit-ir 2\n", 1, 11, "format version `2`"),
        ("stljit-ir 1\n", 1, 12, "missing `profile`"),
        ("stljit-ir 1\nprofile z80\n", 2, 9, "unknown profile `z80`"),
        (
            "stljit-ir 1\nprofile a5\nprofile a5\n",
            3,
            1,
            "`profile` given twice",
        ),
        (
            "pou pou1 main \"M\" {\n}\n",
            4,
            5,
            "index `pou1` out of sequence",
        ),
        ("pou pou0 main \"M\" {\n", 4, 20, "missing the `}`"),
        ("pou pou0 main \"M {\n", 4, 15, "no closing `\"`"),
        (
            "pou pou0 main \"M\" {\n op0 load bit X.0.0\n}\n",
            5,
            15,
            "unknown area `X`",
        ),
        (
            "pou pou0 main \"M\" {\n op0 load bit V.0.300\n}\n",
            5,
            19,
            "not a valid bit number",
        ),
        (
            "pou pou0 main \"M\" {\n op0 assign bit=Q.0.0 immediate=2\n}\n",
            5,
            33,
            "expected 0 or 1, found `2`",
        ),
        (
            "pou pou0 main \"M\" {\n op0 assign immediate=0 bit=Q.0.0\n}\n",
            5,
            13,
            "expected the field `bit=...`, found `immediate=0`",
        ),
        (
            "pou pou0 main \"M\" {\n op0 box move width=Word src=V.0 dst=V.2 extra\n}\n",
            5,
            42,
            "expected end of line, found `extra`",
        ),
        (
            "pou pou0 main \"M\" {\n op0 frobnicate\n}\n",
            5,
            6,
            "unknown op `frobnicate`",
        ),
        (
            "pou pou0 main \"M\" {\n op0 nop\n op1 @file0:1:1 nop\n}\n",
            6,
            6,
            "follows one without",
        ),
        (
            "pou pou0 main \"M\" {\n op0 box move width=Word src=const(7 dst=V.2\n}\n",
            5,
            30,
            "`)` at the operand's end",
        ),
    ];
    for &(tail, line, col, cause) in cases {
        let text = if tail.starts_with("stljit-ir") || tail.is_empty() {
            tail.to_owned()
        } else {
            format!("{head}{tail}")
        };
        let e = parse(&text).expect_err(&text);
        let shown = e.to_string();
        assert!(
            e.line == line && e.col == col && shown.contains(cause),
            "{text:?}: got {shown}, want line {line}, column {col}: ...{cause}..."
        );
    }
    assert!(matches!(
        parse("").unwrap_err().kind,
        ParseErrorKind::Missing(_)
    ));
}

/// A tiny deterministic generator for the mutations (core has no dependencies).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self, n: usize) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 33) % n.max(1) as u64) as usize
    }
}

/// Parses `text`; any error must point into the text (or one past a line's end).
fn parse_checked(text: &str) {
    if let Err(e) = parse(text) {
        let lines: Vec<&str> = text.lines().collect();
        let n = lines.len().max(1);
        assert!(
            e.line >= 1 && e.line as usize <= n && e.col >= 1,
            "{e} outside the text:\n{text}"
        );
        let width = lines
            .get(e.line as usize - 1)
            .map_or(0, |l| l.chars().count());
        assert!(
            e.col as usize <= width + 1,
            "{e} past the line's end:\n{text}"
        );
    }
}

#[test]
fn truncated_and_mutated_texts_never_panic() {
    let text = print(&sample());
    let chars: Vec<char> = text.chars().collect();
    // Every prefix of the first 3,000 characters, then every 7th.
    for cut in (0..chars.len()).filter(|&c| c < 3000 || c % 7 == 0) {
        parse_checked(&chars[..cut].iter().collect::<String>());
    }
    let alphabet: Vec<char> = "\"\\{}()=.:;@ \n\t0123456789xopLTCVQI_-电\u{0}"
        .chars()
        .collect();
    let mut rng = Lcg(0x5EED);
    for _ in 0..3000 {
        let mut m = chars.clone();
        for _ in 0..=rng.next(4) {
            let at = rng.next(m.len());
            match rng.next(4) {
                0 => {
                    m.remove(at);
                }
                1 => m.insert(at, alphabet[rng.next(alphabet.len())]),
                2 => m[at] = alphabet[rng.next(alphabet.len())],
                _ => {
                    // Duplicate a run of characters (a line, part of one).
                    let len = rng.next(40).min(m.len() - at);
                    let run: Vec<char> = m[at..at + len].to_vec();
                    let to = rng.next(m.len());
                    m.splice(to..to, run);
                }
            }
        }
        parse_checked(&m.iter().collect::<String>());
    }
}
