//! The front-end options (omron-cp.md §1.9 `omron.tc_mode`, §2.8 `allow_backward_jumps`).

use stljit_core::ProfileId;
use stljit_core::ir::{OmronCounterKind, OmronTimerKind, Op, verify};
use stljit_front_omron::{Code, Options, SourceFile, TcMode, compile_with};

fn compile(text: &str, options: Options) -> stljit_front_omron::Compilation {
    let file = SourceFile::from_text("t.omr", text);
    compile_with(&[file], None, ProfileId::Cp1h, options)
}

fn codes(text: &str, options: Options) -> Vec<(Code, u32)> {
    compile(text, options)
        .diagnostics
        .iter()
        .map(|d| (d.code, d.line))
        .collect()
}

#[test]
fn binary_mode_runs_the_plain_timers_and_counters_as_their_x_forms() {
    let text = "LD 0.00\nTIM 0 &12\nLD 0.01\nLD 0.02\nCNT 1 &10\nLD 0.03\nLD 0.04\nLD 0.05\nCNTR(012) 2 #00FF\nEND(001)\n";
    // BCD mode: &12 (#000C), &10 (#000A) and #00FF are no BCD set values.
    assert_eq!(
        codes(text, Options::default()),
        [
            (Code::OmrConstant, 2),
            (Code::OmrConstant, 5),
            (Code::OmrConstant, 9)
        ]
    );
    let binary = Options {
        tc_mode: TcMode::Binary,
        ..Options::default()
    };
    let c = compile(text, binary);
    let p = c.program.expect("binary set values are fine");
    verify(&p).expect("verifies");
    let kinds: Vec<String> = p.pous[0]
        .ops
        .iter()
        .filter_map(|op| match op {
            Op::OmronTimer { kind, .. } => Some(format!("{kind:?}")),
            Op::OmronCounter { kind, .. } => Some(format!("{kind:?}")),
            _ => None,
        })
        .collect();
    let want = [
        format!("{:?}", OmronTimerKind::TimX),
        format!("{:?}", OmronCounterKind::CntX),
        format!("{:?}", OmronCounterKind::CntrX),
    ];
    assert_eq!(kinds, want);
    assert_eq!(TcMode::from_name("binary"), Some(TcMode::Binary));
    assert_eq!(TcMode::from_name("hex"), None);
}

#[test]
fn backward_jumps_need_the_option_and_stay_in_their_regions() {
    let back = "JME(005) &1\nLD 0.00\nJMP(004) &1\nEND(001)\n";
    assert_eq!(codes(back, Options::default()), [(Code::OmrJump, 3)]);
    let allow = Options {
        allow_backward_jumps: true,
        ..Options::default()
    };
    let c = compile(back, allow);
    let p = c.program.expect("allowed");
    verify(&p).expect("verifies");
    // Into an interlock region, into a block program, into a FOR loop: rejected.
    let into_il = "LD 0.00\nIL(002)\nJME(005) &1\nILC(003)\nLD 0.01\nJMP(004) &1\nEND(001)\n";
    assert_eq!(codes(into_il, allow), [(Code::OmrJump, 6)]);
    let into_block =
        "LD 0.00\nBPRG(096) &0\nJME(005) &1\nBEND(801)\nLD 0.01\nJMP(004) &1\nEND(001)\n";
    assert_eq!(codes(into_block, allow), [(Code::OmrJump, 6)]);
    let into_loop = "FOR(503) &2\nJME(005) &1\nNEXT(504)\nLD 0.01\nJMP(004) &1\nEND(001)\n";
    assert_eq!(codes(into_loop, allow), [(Code::OmrInRegion, 5)]);
    // Within one loop body it is fine.
    let in_loop = "FOR(503) &2\nJME(005) &1\nLD 0.01\nJMP(004) &1\nNEXT(504)\nEND(001)\n";
    let c = compile(in_loop, allow);
    verify(&c.program.expect("a jump within the loop body")).expect("verifies");
}
