//! The printer against the lowering: every instruction form compiles, prints and compiles
//! back to the same IR (up to source locations), and IR no text produces is refused.

use super::operands::ea_operand;
use super::*;
use crate::SourceFile;
use crate::mnemonics::{RELATIONS, relation_flag};
use stljit_core::ir::{BitLoc, Contact, Operand, SrcLoc};
use stljit_core::omron::{EaRegion, effective_address};
use stljit_core::{Area, LabelId, ProfileId};

pub(super) fn compiled(text: &str, profile: ProfileId) -> Program {
    compiled_with(text, profile, Options::default())
}

pub(super) fn compiled_with(text: &str, profile: ProfileId, options: Options) -> Program {
    let c = crate::compile_with(
        &[SourceFile::from_text("t.omr", text)],
        None,
        profile,
        options,
    );
    match c.program {
        Some(p) => p,
        None => panic!("does not compile: {:#?}\n{text}", c.diagnostics),
    }
}

fn normalized(mut p: Program) -> Program {
    p.files.clear();
    for pou in &mut p.pous {
        pou.locs = vec![SrcLoc::default(); pou.ops.len()];
    }
    p
}

/// Compiles `text`, prints the IR, compiles the print: both IRs must be equal.
pub(super) fn round_trip(text: &str, profile: ProfileId) -> String {
    round_trip_with(text, profile, Options::default())
}

/// [`round_trip`] of a text compiled with `options`; the print is compiled with the options
/// [`printed_options`] names.
pub(super) fn round_trip_with(text: &str, profile: ProfileId, options: Options) -> String {
    let p = compiled_with(text, profile, options);
    let printed = print_program(&p).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let back = compiled_with(&printed, profile, printed_options(&p));
    assert_eq!(
        normalized(p),
        normalized(back),
        "\n--- source\n{text}\n--- printed\n{printed}"
    );
    printed
}

#[test]
fn every_instruction_form_round_trips() {
    let text = "
LD 0.00
AND NOT 0.01
OR W3.15
OR NOT H10.02
LD 1.03
!AND 1.04
AND LD
LD NOT T0001
OR C0002
OR LD
NOT(520)
UP(521)
DOWN(522)
OUT 100.00
!OUT 100.01
OUT NOT W0.01
!OUT NOT 101.15
AND P_1s
SET W1.00
!@SET 100.02
%RSET W1.01
RSET A448.00
LD 0.02
@AND 0.03
%OR 0.04
!%LD 1.05
AND LD
OUT TR0
AND 0.06
DIFU(013) W2.00
LD TR0
DIFD(014) W2.01
LD 0.07
LD 0.08
KEEP(011) W2.02
LD 0.09
LD 0.10
!KEEP(011) 100.03
LD>=S(327) D0 -5
AND<>L(306) D2 #00010000
OR=(300) T0001 C0002
OUT W2.03
LD 0.11
TIM 0001 #0100
TIMX(550) 0002 &300
TIMH(015) 0003 D10
TIMHX(551) 0004 #FFFF
TMHH(540) 0005 #0005
TMHHX(552) 0006 W5
LD 0.12
LD 0.13
TTIM(087) 0007 #0030
LD 0.12
LD 0.13
TTIMX(555) 0008 DR3
LD 0.14
LD 0.15
CNT 0001 #0005
LD 0.14
LD 0.15
CNTX(546) 0002 &9
LD 1.00
LD 1.01
LD 1.02
CNTR(012) 0003 #0002
LD 1.00
LD 1.01
LD 1.02
CNTRX(548) 0004 D11
LD P_On
MOV(021) #1234 D20
@MOV(021) D20 D21
MOVL(498) #89ABCDEF D22
!MOVL(498) D22 W10
CMP(020) D20 D21
AND P_EQ
OUT W3.00
CMPL(060) D22 #00000001
CPS(114) DR1 -3
CPSL(115) W10 D22
+(400) D0 #0001 D30
@+BCL(407) D0 D2 D32
-C(412) D0 D1 D34
*U(422) D0 D1 D36
/BL(435) D40 D42 D44
MOVR(560) D400 IR0
@MOVR(560) W3.05 IR1
MOVR(560) T0003 IR2
MOVR(560) C0004 IR3
MOVR(560) 100 IR4
MOV(021) #1111 @D20
MOV(021) #2222 *D21
MOV(021) #3333 ,IR0+
MOV(021) ,IR0++ D50
MOV(021) ,-IR0 D51
MOV(021) ,--IR0 D52
MOV(021) +2,IR0 D53
MOV(021) -7,IR1 D54
MOV(021) DR2,IR0 D55
MOV(021) ,IR5 D56
+(400) @D20 *D21 ,IR0
CCS(282)
@CCL(283)
IORF(097) 10 12
NOT(520)
OUT TR1
NOT(520)
OUT W0.04
LD TR1
OUT W0.05
LD 0.00
JMP(004) &1
LD 0.01
CJP(510) 2
LD 0.02
CJPN(511) #3
JME(005) 2
JME(005) 3
LD 0.03
OUT 100.04
JME(005) 1
LD 0.04
JMP0(515)
LD 0.05
JMP0(515)
OUT 100.05
JME0(516)
LD 0.00
IL(002)
LD 0.01
TIM 0010 #0003
ILC(003)
FOR(503) &3
LD 0.01
BREAK(514)
FOR(503) D60
LD 0.02
JMP(004) 7
LD 0.03
BREAK(514)
JME(005) 7
NEXT(504)
NEXT(504)
LD P_First_Cycle
@SBS(091) 5
LD 0.06
SBS(091) 6
SBN(092) 5
LD 0.00
JMP(004) 1
LD 0.01
OUT W8.00
JME(005) 1
RET(093)
SBN(092) 6
RET(093)
END(001)
";
    let printed = round_trip(text, ProfileId::Cp1h);
    // The print writes what changes the IR and nothing else: `!%LD 1.05` / `AND LD` is one
    // `!%AND`, jumps are numbered, IORF is gone.
    assert!(printed.contains("!%AND      1.05"), "{printed}");
    assert!(
        !printed.contains("JMP0") && !printed.contains("IORF"),
        "{printed}"
    );
}

#[test]
fn iorf_boundaries_are_put_back() {
    // IORF lowers to nothing, but the LD after it starts a new circuit.
    let printed = round_trip(
        "LD 0.04\nIORF(097) 7 7\n@LD 1.10\nOR 3.10\nMOV(021) #FFFF D0\nLD 0.00\nIORF(097) 0 1\nEND(001)\n",
        ProfileId::Cp1h,
    );
    assert_eq!(printed.matches("IORF").count(), 2, "{printed}");
    // Where the LD after it opens a block anyway, nothing is added.
    let printed = round_trip(
        "LD 0.04\nIORF(097) 7 7\nAND 0.01\nLD 0.02\nAND LD\nOUT 100.00\nEND(001)\n",
        ProfileId::Cp1h,
    );
    assert!(!printed.contains("IORF"), "{printed}");
}

#[test]
fn out_not_and_jmp_fold_only_where_the_circuit_allows() {
    // `NOT / OUT b / NOT` followed by an LD opening a block: folding it into OUT NOT would end
    // the rung there and make the LD start a new circuit.
    round_trip(
        "LD 0.00\nNOT(520)\nOUT W0.00\nNOT(520)\nLD 0.01\nOR LD\nOUT W0.01\nEND(001)\n",
        ProfileId::Cp1h,
    );
    round_trip(
        "LD 0.00\nNOT(520)\nCJP(510) 1\nNOT(520)\nLD 0.01\nAND LD\nOUT W0.01\nJME(005) 1\nEND(001)\n",
        ProfileId::Cp1h,
    );
    // And an OUT NOT followed by a new circuit, or by FOR, stays OUT NOT.
    let printed = round_trip(
        "LD 0.00\nOUT NOT W0.00\nLD 0.01\nOUT W0.01\nLD 0.02\nOUT NOT W0.02\nFOR(503) &2\nNEXT(504)\nEND(001)\n",
        ProfileId::Cp1h,
    );
    assert_eq!(printed.matches("OUT NOT").count(), 2, "{printed}");
}

#[test]
fn cp1e_dm_bits_and_profile_limits_round_trip() {
    round_trip(
        "LD D10.05\nOUT D11.00\nLD P_On\nMOVR(560) D12.03 IR0\nEND(001)\n",
        ProfileId::Cp1e,
    );
}

#[test]
fn the_spec_programs_round_trip() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/spec");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).expect("tests/spec") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "omr") {
            let text = std::fs::read_to_string(&path).expect("readable");
            round_trip(&text, ProfileId::Cp1h);
            n += 1;
        }
    }
    assert!(n >= 10, "only {n} spec programs");
}

#[test]
fn compare_contacts_read_their_relation() {
    for &(rel, op, _) in &RELATIONS {
        let p = compiled(
            &format!("LD{rel} D0 D1\nOUT W0.00\nEND(001)\n"),
            ProfileId::Cp1h,
        );
        let want = Op::Load(Contact::Bit {
            bit: relation_flag(op).bit_loc(),
            negated: false,
        });
        assert_eq!(p.pous[0].ops[3], want, "{rel}");
    }
}

#[test]
fn ir_no_text_produces_is_refused() {
    let base = compiled(
        "LD 0.00\nOUT 100.00\nLD 0.01\nJMP(004) 1\nLD 0.02\nOUT 100.01\nJME(005) 1\nEND(001)\n",
        ProfileId::Cp1h,
    );
    assert!(print_program(&base).is_ok());
    let refused = |edit: &dyn Fn(&mut Program)| {
        let mut p = base.clone();
        edit(&mut p);
        print_program(&p).expect_err("refused")
    };
    // An S7 op, a lone Pop, a missing END, a cut JMP pattern, an S7 profile.
    let e = refused(&|p| p.pous[0].ops[1] = Op::Stop);
    assert_eq!(e.op, Some(1), "{e}");
    let e = refused(&|p| p.pous[0].ops[1] = Op::Pop);
    assert!(e.message.contains("Pop"), "{e}");
    refused(&|p| {
        p.pous[0].ops.pop();
    });
    refused(&|p| p.profile = ProfileId::A5);
    let e = refused(&|p| p.pous[0].ops.insert(0, Op::Dup));
    assert!(e.message.contains("Dup"), "{e}");
    // A set of two bits has no Omron spelling.
    refused(&|p| {
        p.pous[0].ops[1] = Op::SetRange {
            start: BitLoc {
                area: Area::Work,
                byte: 1,
                bit: 0,
            },
            count: Operand::Const(2),
            value: true,
            immediate: false,
        }
    });
}

#[test]
fn labels_out_of_text_order_are_refused() {
    let p = compiled(
        "LD 0.00\nJMP(004) 1\nLD 0.01\nJMP(004) 2\nJME(005) 1\nJME(005) 2\nEND(001)\n",
        ProfileId::Cp1h,
    );
    assert!(print_program(&p).is_ok());
    let mut q = p.clone();
    for op in &mut q.pous[0].ops {
        if let Op::Jump(l) | Op::Label(l) = op {
            *l = LabelId::new(1 - l.index());
        }
    }
    q.pous[0].labels.swap(0, 1);
    let e = print_program(&q).expect_err("label 1 is mentioned first");
    assert!(e.message.contains("label"), "{e}");
}

#[test]
fn effective_addresses_name_their_operands() {
    let p = ProfileId::Cp1h.profile();
    for (region, word, bit, text) in [
        (
            EaRegion::Word(stljit_core::omron::WordArea::Dm),
            400,
            None,
            "D400",
        ),
        (
            EaRegion::Word(stljit_core::omron::WordArea::Cio),
            100,
            None,
            "100",
        ),
        (
            EaRegion::Word(stljit_core::omron::WordArea::Work),
            3,
            Some(5),
            "W3.05",
        ),
        (EaRegion::TimerPv, 7, None, "T0007"),
        (EaRegion::CounterPv, 4095, None, "C4095"),
    ] {
        let ea = effective_address(p, region, word).unwrap();
        let ea = bit.map_or(ea, |b| 16 * ea + b);
        assert_eq!(ea_operand(p, ea).as_deref(), Some(text));
    }
    assert_eq!(ea_operand(p, 0xB000 + 960), None);
}
