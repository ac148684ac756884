//! The printer against what the front end gained with tasks: several `$TASK` programs (run
//! order, source order, units that never run), step areas and block programs, the whole-word
//! `!` refresh, the binary timer mode and backward jumps.

use super::tests::{compiled, compiled_with, round_trip, round_trip_with};
use super::*;
use crate::TcMode;
use stljit_core::ProfileId;
use stljit_core::ir::OmronTimerKind;

const CP1H: ProfileId = ProfileId::Cp1h;

#[test]
fn tasks_print_in_run_order_with_their_subroutines() {
    // Source order 2, 0, 1: the IR runs 0, 1, 2; the subroutines belong to tasks 2 and 1 and
    // come in source order. An `@` contact in each task fixes the edge slots' source order.
    let text = "
$TASK CYCLIC 2
@LD 0.00
SBS(091) 3
SBN(092) 3
LD 0.04
OUT W0.03
RET(093)
END(001)
$TASK CYCLIC 0
LD P_On
MOV(021) #0007 D0
@LD 0.01
OUT W0.00
END(001)
$TASK CYCLIC 1
LD 0.02
SBS(091) 1
%LD 0.03
OUT W0.01
SBN(092) 1
LD P_On
+(400) D0 #0001 D1
RET(093)
END(001)
$task cyclic 3 standby
LD 0.05
OUT W1.00
END(001)
";
    let p = compiled(text, CP1H);
    assert_eq!(
        p.pous[0]
            .ops
            .iter()
            .filter(|o| **o == Op::TaskStart)
            .count(),
        2
    );
    let printed = round_trip(text, CP1H);
    assert_eq!(printed.matches("$TASK CYCLIC").count(), 3, "{printed}");
    assert_eq!(printed.matches("END(001)").count(), 3, "{printed}");
    // The task running third is printed first, as its source was.
    let first = printed.find("$TASK CYCLIC 2").unwrap();
    assert!(first < printed.find("$TASK CYCLIC 0").unwrap(), "{printed}");
}

#[test]
fn a_single_task_has_no_directive() {
    let printed = round_trip("$TASK CYCLIC 4\nLD 0.00\nOUT W0.00\nEND(001)\n", CP1H);
    assert!(!printed.contains('$'), "{printed}");
}

#[test]
fn edges_of_units_that_never_run_come_back() {
    // The standby task, the unassigned program and the function block are not in the IR, but
    // their edge memories are: printed as unassigned programs where they stood.
    let text = "
$TASK CYCLIC 0
@LD 0.00
OUT W0.00
END(001)
$TASK CYCLIC 1 STANDBY
%LD 0.01
@AND 0.02
OUT W0.01
END(001)
$TASK CYCLIC 2
LD 0.03
UP(521)
AND 0.06
DOWN(522)
OUT W0.02
END(001)
$TASK UNASSIGNED
LD 0.04
UP(521)
OUT W0.03
END(001)
$FB valve
@LD 0.05
OUT W0.04
END(001)
";
    let p = compiled(text, CP1H);
    assert_eq!(p.edges.len(), 7);
    let printed = round_trip(text, CP1H);
    // The standby task's two edges between tasks 0 and 2; the unassigned program's and the
    // function block's together at the end.
    assert_eq!(printed.matches("$TASK UNASSIGNED").count(), 2, "{printed}");
}

#[test]
fn subroutines_called_from_two_tasks_are_refused() {
    let mut p = compiled(
        "$TASK CYCLIC 0\nLD 0.00\nSBS(091) 1\nSBN(092) 1\nRET(093)\nEND(001)\n$TASK CYCLIC 1\nLD 0.01\nOUT W0.00\nEND(001)\n",
        CP1H,
    );
    let call = p.pous[0].ops[1].clone();
    let last = p.pous[0].ops.len() - 1;
    p.pous[0].ops.insert(last, call);
    p.pous[0].ops.insert(last, Op::Load(p_on()));
    p.pous[0].locs = vec![Default::default(); p.pous[0].ops.len()];
    let e = print_program(&p).expect_err("refused");
    assert!(e.message.contains("two tasks"), "{e}");
}

fn p_on() -> stljit_core::ir::Contact {
    stljit_core::ir::Contact::Bit {
        bit: stljit_core::omron::SystemBit::On.bit_loc(),
        negated: false,
    }
}

#[test]
fn step_areas_and_block_programs_round_trip() {
    let text = "
LD P_First_Cycle
SNXT(009) W0.00
STEP(008) W0.00
LD 0.00
OUT 100.00
TIM 0001 #0010
LD T0001
SNXT(009) W0.01
STEP(008) W0.01
LD 0.01
BPRG(096) 5
LD 0.02
MOV(021) #0001 D0
BEND(801)
LD 0.03
SNXT(009) W0.00
STEP(008)
LD 0.04
BPRG(096) 6
LD 0.05
MOV(021) #0002 D1
LD 0.06
JMP(004) 3
LD P_On
+(400) D0 #0001 D0
JME(005) 3
BEND(801)
LD 0.07
IL(002)
LD 0.08
SNXT(009) W1.00
STEP(008) W1.00
LD 0.09
OUT 100.01
LD 0.10
SNXT(009) W1.01
STEP(008) W1.01
LD 0.11
SNXT(009) W1.00
STEP(008)
LD 0.12
OUT 100.02
ILC(003)
END(001)
";
    let printed = round_trip(text, CP1H);
    assert_eq!(printed.matches("STEP(008)").count(), 6, "{printed}");
    assert!(
        printed.contains("BPRG(096)") && printed.contains("BEND(801)"),
        "{printed}"
    );
    assert!(printed.contains("SNXT(009)  W0.01"), "{printed}");
}

#[test]
fn whole_word_refresh_round_trips() {
    // Every `!` form on operands in the built-in input words (CIO 0–1), output words (100–101)
    // and elsewhere (no refresh at all, so no `!` in the print).
    let text = "
!LD 0.00
!AND NOT 1.03
!OR W0.00
!@AND 0.05
OUT W1.00
!LD>(320) 0 1
!AND<>L(306) 0 D0
OUT W1.01
LD 0.01
!OUT 100.00
!OUT NOT 101.15
LD 0.03
LD 0.04
!KEEP(011) 101.03
LD 0.02
!SET 100.01
!@RSET 100.02
!%SET W2.00
!MOV(021) 0 100
!@MOVL(498) D4 100
!MOV(021) 1 D10
!+(400) 0 #0001 101
!CMP(020) 1 D10
!CMPL(060) 0 D12
!@+L(401) 0 D20 D30
!MOVL(498) 2 102
END(001)
";
    let p = compiled(text, CP1H);
    let boxes = p.pous[0]
        .ops
        .iter()
        .filter(|o| matches!(o, Op::Box(_)))
        .count();
    assert!(boxes > 30, "{boxes} refresh boxes");
    let printed = round_trip(text, CP1H);
    assert!(!printed.contains("!OR"), "{printed}");
    assert!(!printed.contains("!%SET"), "{printed}");
    assert!(printed.contains("!OUT NOT"), "{printed}");
    assert!(
        printed.contains("!@MOVL") && printed.contains("!KEEP"),
        "{printed}"
    );
    assert!(
        printed.contains("!AND<>L") && !printed.contains("!MOVL"),
        "{printed}"
    );
}

#[test]
fn refresh_boxes_that_no_instruction_writes_are_refused() {
    let mut p = compiled("LD 0.00\n!OUT 100.00\nEND(001)\n", CP1H);
    // `Assign; Load(P_On); Write(byte 0); Write(byte 1); Pop`: drop one byte's box.
    p.pous[0].ops.remove(3);
    p.pous[0].locs.pop();
    let e = print_program(&p).expect_err("refused");
    assert!(e.message.contains("refresh"), "{e}");
}

#[test]
fn binary_mode_timers_print_as_their_x_forms() {
    let text = "LD 0.00\nTIM 0000 &12\nLD 0.01\nLD 0.02\nCNT 0001 &3\nLD 0.03\nTIMH(015) 0002 #0100\nEND(001)\n";
    let binary = Options {
        tc_mode: TcMode::Binary,
        ..Options::default()
    };
    let p = compiled_with(text, CP1H, binary);
    assert!(matches!(
        p.pous[0].ops[1],
        Op::OmronTimer {
            kind: OmronTimerKind::TimX,
            ..
        }
    ));
    let printed = round_trip_with(text, CP1H, binary);
    assert!(
        printed.contains("TIMX(550)") && printed.contains("CNTX(546)"),
        "{printed}"
    );
    assert_eq!(printed_options(&p), Options::default());
}

#[test]
fn backward_jumps_print_and_name_their_option() {
    let text = "
LD P_On
MOV(021) #0000 D0
JME(005) &1
LD P_On
+(400) D0 #0001 D0
LD< D0 #0005
CJP(510) &1
LD 0.00
JMP(004) 2
JME(005) 2
END(001)
";
    let options = Options {
        allow_backward_jumps: true,
        ..Options::default()
    };
    let p = compiled_with(text, CP1H, options);
    assert!(printed_options(&p).allow_backward_jumps);
    let printed = round_trip_with(text, CP1H, options);
    assert!(printed.contains("allow_backward_jumps"), "{printed}");
    // Forward jumps only: no option needed.
    let forward = compiled("LD 0.00\nJMP(004) 1\nJME(005) 1\nEND(001)\n", CP1H);
    assert_eq!(printed_options(&forward), Options::default());
}

#[test]
fn a_refreshed_out_not_takes_the_not_it_shares() {
    // `NOT; OUT a; NOT; OUT b; NOT; <refresh>`: folding the first three into OUT NOT a would
    // leave the refresh behind a plain OUT b (found by the fuzzer's round trip, seed 1518).
    round_trip(
        "LD 0.00\nNOT(520)\nOUT W14.00\n!OUT NOT 100.04\nLD 0.01\nNOT(520)\nCJP(510) 1\n!OUT NOT 101.00\nJME(005) 1\nEND(001)\n",
        CP1H,
    );
}

#[test]
fn an_uncalled_subroutine_goes_to_the_task_its_edges_need() {
    // SBN 2 is called by no task. Its neighbour before it (SBN 1) is task 0's, but there its
    // `@` would come after task 1's in the slot order: only task 1 gives these edge slots.
    round_trip(
        "LD 0.00\nSBS(091) 1\nSBN(092) 1\nLD 0.01\nOUT W0.00\nRET(093)\nEND(001)\n$TASK CYCLIC 1\n@LD 0.02\nSBS(091) 3\nSBN(092) 2\n@LD 0.03\nOUT W0.01\nRET(093)\nSBN(092) 3\nRET(093)\nEND(001)\n",
        CP1H,
    );
}
