//! Each rule switch of `stljit_runtime::rules::Rules`, flipped, is followed by both engines: the
//! interpreter (through the runtime's functions) and the JIT (whose inlined edges and counter
//! rules read the same value), scan by scan and byte by byte.

use stljit_core::ProfileId;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};
use stljit_runtime::rules::{FirstScanEdges, Rules};
use stljit_runtime::{Engine, Image};

/// An input on from the first scan: a rising edge only if the first scan detects edges. EU and
/// ED inline, a counter (its rule inline too), and one inside an SCR segment (dynamic gate).
const PROGRAM: &str = "\
LD I0.0
EU
= Q0.0
LDN I0.0
ED
= Q0.1
LD I0.0
LD I0.1
CTU C0, 5
LD SM0.1
S S0.0, 1
LSCR S0.0
LD I0.0
EU
= Q0.2
LD I0.0
LD I0.1
CTU C1, 5
SCRE
";

/// Q0.0 (EU), C0 and C1 after every scan, checking that both engines leave the same image.
fn run(rules: Rules, opt: OptLevel) -> Vec<(bool, i16, i16)> {
    let c = stljit_front_s7::compile_str("rules.stl", PROGRAM, ProfileId::A5);
    let program = c.program.expect("compiles");
    let mut interp = Interpreter::new(&program)
        .expect("interpreter accepts the program")
        .with_rules(rules);
    let mut jit =
        JitProgram::compile_with_rules(&program, &JitOptions::at(opt), rules).expect("compiles");
    let (mut a, mut b) = (Image::cold_start(&program), Image::cold_start(&program));
    let mut seen = Vec::new();
    for scan in 0..4u64 {
        let inputs = [u8::from(scan < 3)];
        a.set_inputs(&inputs);
        b.set_inputs(&inputs);
        let (sa, sb) = (interp.scan(&mut a, 10 * scan), jit.scan(&mut b, 10 * scan));
        assert_eq!(sa, sb, "{rules:?} scan {scan}: status");
        assert!(
            a.bytes() == b.bytes(),
            "{rules:?} {opt:?} scan {scan}: images differ"
        );
        let q0 = a.phys_out()[0];
        seen.push((q0 & 1 != 0, a.counter_value(0), a.counter_value(1)));
        assert_eq!(
            q0 & 4 != 0,
            q0 & 1 != 0,
            "the EU in the segment sees the same edge"
        );
    }
    seen
}

#[test]
fn first_scan_edge_switch_is_followed_by_both_engines() {
    let detect = Rules {
        first_scan_edges: FirstScanEdges::Detect,
    };
    for opt in [OptLevel::None, OptLevel::Speed] {
        let suppress = run(Rules::IN_FORCE, opt);
        let detected = run(detect, opt);
        // Suppress (spec TC7): the first scan only records the input; nothing ever rises.
        assert_eq!(suppress[0], (false, 0, 0), "{opt:?}");
        assert_eq!(suppress[2], (false, 0, 0), "{opt:?}");
        // Detect: the input that is on in the first scan is an edge there.
        assert_eq!(detected[0], (true, 1, 1), "{opt:?}");
        assert_eq!(detected[1], (false, 1, 1), "{opt:?}");
        assert_eq!(
            detected[3].1, 1,
            "{opt:?}: the falling input counts nothing"
        );
    }
}
