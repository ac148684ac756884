//! Round trip: every spec §7 program, the all-instructions fixture and a MicroWIN export with
//! subroutine parameters, printed with
//! [`crate::print_program`] and parsed again, give the same IR up to source locations.

use crate::{compile_str, print_program};
use stljit_core::ProfileId;
use stljit_core::ir::Program;

macro_rules! fixtures {
    ($($name:literal),*) => {
        &[$(($name, include_str!(concat!("../../../tests/diagnostics/", $name)))),*]
    };
}

const PROGRAMS: &[(&str, &str)] = fixtures!(
    "spec/T01.stl",
    "spec/T02.stl",
    "spec/T03.stl",
    "spec/T04.stl",
    "spec/T05.stl",
    "spec/T06.stl",
    "spec/T07.stl",
    "spec/T08.stl",
    "spec/T09.stl",
    "spec/T10.stl",
    "spec/T11.stl",
    "spec/T12.stl",
    "spec/T13.stl",
    "spec/T14.stl",
    "spec/T15.stl",
    "spec/X1.stl",
    "spec/X2.stl",
    "spec/X3.stl",
    "spec/X4.stl",
    "spec/X5.stl",
    "spec/X6.stl",
    "ok/all_instructions.stl",
    "ok/microwin_params.awl"
);

/// The program without source locations and file names.
fn strip(mut p: Program) -> Program {
    for pou in &mut p.pous {
        pou.locs.clear();
    }
    p.files.clear();
    p
}

#[test]
fn printed_programs_parse_back_to_the_same_ir() {
    for (name, text) in PROGRAMS {
        let first = compile_str(name, text, ProfileId::A5);
        let program = first
            .program
            .unwrap_or_else(|| panic!("{name}: {:?}", first.diagnostics));
        let printed = print_program(&program);
        let second = compile_str("printed.awl", &printed, ProfileId::A5);
        let again = second
            .program
            .unwrap_or_else(|| panic!("{name} printed:\n{printed}\n{:?}", second.diagnostics));
        assert_eq!(strip(again), strip(program), "{name} printed:\n{printed}");
    }
}

#[test]
fn t03_lowers_as_the_spec_describes() {
    use stljit_core::Area;
    use stljit_core::ir::{BitLoc, Contact, Op, Operand};
    let c = compile_str("t03", PROGRAMS[2].1, ProfileId::A5);
    let p = c.program.expect("T03 checks");
    let i = |byte, bit| BitLoc {
        area: Area::I,
        byte,
        bit,
    };
    let q = |byte, bit| BitLoc {
        area: Area::Q,
        byte,
        bit,
    };
    assert_eq!(
        p.pous[0].ops,
        vec![
            Op::Load(Contact::Bit {
                bit: i(0, 0),
                negated: false
            }),
            Op::SetRange {
                start: q(0, 0),
                count: Operand::Const(3),
                value: true,
                immediate: false
            },
            Op::Load(Contact::Bit {
                bit: i(0, 1),
                negated: false
            }),
            Op::SetRange {
                start: q(0, 1),
                count: Operand::Const(1),
                value: false,
                immediate: false
            },
        ]
    );
    assert_eq!(p.pous[0].locs[1].line, 3);
}

#[test]
fn operands_lower_to_areas_and_offsets() {
    use stljit_core::ir::{ArithOp, BitLoc, BoxOp, Contact, Conversion, Loc, Op, Operand};
    use stljit_core::{Area, TimerId, Width};
    let text = "LD T37\nMOVB AC1, VB0\nMOVW T37, C5\nMOVD &VB100, *VD4\n-I 3, AC2\n\
                R T3, 2\nBCDI VW0, VW2\nMOVW 16#FFFF, VW6\nMOVW -3, VW8\nMOVR -2.0E+3, VD10\n";
    let p = compile_str("ops", text, ProfileId::A5)
        .program
        .expect("checks");
    let mem = |area, offset| Operand::Mem(Loc { area, offset });
    let ops = &p.pous[0].ops;
    // Timer bits are byte n bit 0 of TimerBit; values are at 2n; AC1 as a byte is offset 7.
    let t37 = BitLoc {
        area: Area::TimerBit,
        byte: 37,
        bit: 0,
    };
    assert_eq!(
        ops[0],
        Op::Load(Contact::Bit {
            bit: t37,
            negated: false
        })
    );
    let mv = |width, src, dst| Op::Box(BoxOp::Move { width, src, dst });
    assert_eq!(ops[1], mv(Width::Byte, mem(Area::AC, 7), mem(Area::V, 0)));
    assert_eq!(
        ops[2],
        mv(
            Width::Word,
            mem(Area::TimerValue, 74),
            mem(Area::CounterValue, 10)
        )
    );
    let v100 = Operand::AddressOf(Loc {
        area: Area::V,
        offset: 100,
    });
    let vd4 = Operand::Indirect(Loc {
        area: Area::V,
        offset: 4,
    });
    assert_eq!(ops[3], mv(Width::DWord, v100, vd4));
    // STL two-operand form: `-I IN1, OUT` is OUT := OUT - IN1; AC2 as a word is offset 10.
    let sub = BoxOp::IntArith {
        op: ArithOp::Sub,
        width: Width::Word,
        src: Operand::Const(3),
        dst: mem(Area::AC, 10),
    };
    assert_eq!(ops[4], Op::Box(sub));
    assert_eq!(
        ops[5],
        Op::ResetTimers {
            first: TimerId(3),
            count: Operand::Const(2)
        }
    );
    // BCDI IN, OUT: a MOVW then the in-place conversion.
    assert_eq!(ops[6], mv(Width::Word, mem(Area::V, 0), mem(Area::V, 2)));
    let bcd = BoxOp::Convert {
        conv: Conversion::BcdToInt,
        src: mem(Area::V, 2),
        dst: mem(Area::V, 2),
    };
    assert_eq!(ops[7], Op::Box(bcd));
    assert_eq!(
        ops[8],
        mv(Width::Word, Operand::Const(0xFFFF), mem(Area::V, 6))
    );
    assert_eq!(
        ops[9],
        mv(Width::Word, Operand::Const(0xFFFD), mem(Area::V, 8))
    );
    assert_eq!(
        ops[10],
        mv(
            Width::DWord,
            Operand::Const((-2000.0f32).to_bits()),
            mem(Area::V, 10)
        )
    );
    assert_eq!(p.timers.len(), 0, "R alone declares no timer kind");
}
