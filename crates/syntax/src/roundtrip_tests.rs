//! Round trip: every spec §7 program and the all-instructions fixture, printed with
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
    "spec/T01.stl", "spec/T02.stl", "spec/T03.stl", "spec/T04.stl", "spec/T05.stl",
    "spec/T06.stl", "spec/T07.stl", "spec/T08.stl", "spec/T09.stl", "spec/T10.stl",
    "spec/T11.stl", "spec/T12.stl", "spec/T13.stl", "spec/T14.stl", "spec/T15.stl",
    "spec/X1.stl", "spec/X2.stl", "spec/X3.stl", "spec/X4.stl", "spec/X5.stl", "spec/X6.stl",
    "ok/all_instructions.stl"
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
    let i = |byte, bit| BitLoc { area: Area::I, byte, bit };
    let q = |byte, bit| BitLoc { area: Area::Q, byte, bit };
    assert_eq!(
        p.pous[0].ops,
        vec![
            Op::Load(Contact::Bit { bit: i(0, 0), negated: false }),
            Op::SetRange { start: q(0, 0), count: Operand::Const(3), value: true, immediate: false },
            Op::Load(Contact::Bit { bit: i(0, 1), negated: false }),
            Op::SetRange { start: q(0, 1), count: Operand::Const(1), value: false, immediate: false },
        ]
    );
    assert_eq!(p.pous[0].locs[1].line, 3);
}
