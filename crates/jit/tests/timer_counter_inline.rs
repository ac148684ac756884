//! The JIT emits the counter rules inline (`lower::rules`), and the timer rules too under rules
//! the timer fast shims are not specialised to (here: first-scan edges detected), and decodes
//! the objects' bytes itself; the interpreter decodes them in `Timer::decode`/`Counter::decode`.
//! Both go through the same `from_raw`, so even private bytes no scan ever writes (a restored
//! snapshot may carry any: a TOF phase byte of 9, a run byte of 0x80, a bit byte of 0xFE) must
//! leave the two engines' images equal, scan by scan and byte by byte, for every kind,
//! resolution and gate, under either rule set. The expected behaviour on clean bytes is spec §5.2/§5.3, checked by the runtime's
//! rule tables and the conformance cases; this test holds the engines to each other.

use stljit_core::ProfileId;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};
use stljit_runtime::rules::{FirstScanEdges, Rules};
use stljit_runtime::{Engine, Image};

/// Every timer and counter kind on I0.0/I0.1/I0.2, 100-ms and 10-ms timers, a negative and a
/// word preset, and a TON and a CTUD inside an SCR segment that I0.3 switches (a gate only
/// known at run time).
const PROGRAM: &str = "\
LD I0.0
TON T37, 3
LD I0.0
TON T33, 2
LD I0.1
TONR T5, 4
LDN I0.0
TOF T40, 2
LD I0.0
TOF T41, -1
LD I0.2
LD I0.0
CTU C0, 2
LD I0.2
LD I0.1
CTD C1, VW0
LD I0.2
LD I0.1
LD I0.0
CTUD C2, 1
LD I0.3
= S0.0
LSCR S0.0
LD I0.0
TON T38, 1
LD I0.2
LD I0.1
LD I0.0
CTUD C3, 2
SCRE
";

const TIMERS: [u16; 6] = [37, 33, 5, 40, 41, 38];
const COUNTERS: [u16; 4] = [0, 1, 2, 3];

/// Writes `fill` over every private byte and every value and bit byte of the program's timers
/// and counters (the value bytes too: a restored CV may be anything).
fn scribble(img: &mut Image, fill: u8) {
    let (buf, l) = img.split_mut();
    let objects = TIMERS
        .iter()
        .map(|&n| l.timer_bytes(n))
        .chain(COUNTERS.iter().map(|&n| l.counter_bytes(n)));
    for (k, ranges) in objects.enumerate() {
        for (off, len) in ranges {
            for i in 0..len {
                let at = (off + i) as usize;
                buf[at] = fill
                    .wrapping_mul(k as u8 + 1)
                    .wrapping_add((i as u8).wrapping_mul(37));
            }
        }
    }
}

#[test]
fn odd_timer_and_counter_bytes_run_alike_on_both_engines() {
    let c = stljit_front_s7::compile_str("inline.stl", PROGRAM, ProfileId::A5);
    let program = c.program.expect("compiles");
    let detect = Rules {
        first_scan_edges: FirstScanEdges::Detect,
    };
    for (rules, opt) in [Rules::IN_FORCE, detect]
        .into_iter()
        .flat_map(|r| [(r, OptLevel::None), (r, OptLevel::Speed)])
    {
        let mut interp = Interpreter::new(&program)
            .expect("interpreter accepts the program")
            .with_rules(rules);
        let mut jit = JitProgram::compile_with_rules(&program, &JitOptions::at(opt), rules)
            .expect("compiles");
        for fill in [0x00, 0x09, 0x80, 0xFE, 0x5B] {
            let (mut a, mut b) = (Image::cold_start(&program), Image::cold_start(&program));
            for scan in 0..24u64 {
                if scan == 0 || scan == 11 {
                    scribble(&mut a, fill);
                    scribble(&mut b, fill);
                }
                // Inputs walk through all 16 combinations of I0.0..I0.3 (and some twice).
                let inputs = [((scan * 7) % 16) as u8];
                a.set_inputs(&inputs);
                b.set_inputs(&inputs);
                let t = 40 * scan;
                let (sa, sb) = (interp.scan(&mut a, t), jit.scan(&mut b, t));
                assert_eq!(
                    sa, sb,
                    "{rules:?} {opt:?} fill {fill:#x} scan {scan}: status"
                );
                let diff = a.bytes().iter().zip(b.bytes()).position(|(x, y)| x != y);
                assert_eq!(
                    diff, None,
                    "{rules:?} {opt:?} fill {fill:#x} scan {scan}: first differing image byte"
                );
            }
        }
    }
}

/// The clock refresh of 1-ms and 10-ms timers at scan start: the JIT's inline scan path emits
/// `timer::refresh_rule` with the declared kind and resolution as constants where the timer's
/// kind and resolution bytes are the declaration's, and on the bytes otherwise (`scan_clock`).
/// Every pair of kind and resolution bytes, written after the first scans, must run alike on
/// both engines: unused (kind 0), a kind no timer has (7), a resolution the refresh skips (100,
/// 0) and the other clocked one (a 10-ms timer's bytes saying 1 ms).
#[test]
fn clock_timers_with_any_kind_and_resolution_bytes_run_alike_on_both_engines() {
    use stljit_core::layout::TimerState;
    // S7-200: T32 1-ms TON, T33 10-ms TON, T96 1-ms TOF, T1 10-ms TONR.
    const CLOCKED: &str = "\
LD I0.0
TON T32, 30
LD I0.0
TON T33, 5
LDN I0.0
TOF T96, 50
LD I0.1
TONR T1, 8
";
    let c = stljit_front_s7::compile_str("clock.stl", CLOCKED, ProfileId::S7_200);
    let program = c.program.expect("compiles");
    for opt in [OptLevel::None, OptLevel::Speed] {
        let mut interp = Interpreter::new(&program).expect("interpreter accepts the program");
        let mut jit = JitProgram::compile(&program, &JitOptions::at(opt)).expect("compiles");
        for kind in [0u8, 1, 2, 3, 7] {
            for res in [1u8, 10, 100, 0] {
                let (mut a, mut b) = (Image::cold_start(&program), Image::cold_start(&program));
                for scan in 0..16u64 {
                    if scan == 3 {
                        for img in [&mut a, &mut b] {
                            let (buf, l) = img.split_mut();
                            for n in [32, 33, 96, 1] {
                                let state = l.timer_state(n) as usize;
                                buf[state + TimerState::KIND as usize] = kind;
                                buf[state + TimerState::RES as usize] = res;
                            }
                        }
                    }
                    // I0.0 on for 6 scans, off for 6 (the TOF times), I0.1 in runs of 3.
                    let inputs = [u8::from(scan % 12 < 6) | u8::from(scan % 6 < 3) << 1];
                    a.set_inputs(&inputs);
                    b.set_inputs(&inputs);
                    let t = 7 * scan;
                    let (sa, sb) = (interp.scan(&mut a, t), jit.scan(&mut b, t));
                    assert_eq!(sa, sb, "{opt:?} kind {kind} res {res} scan {scan}: status");
                    let diff = a.bytes().iter().zip(b.bytes()).position(|(x, y)| x != y);
                    assert_eq!(
                        diff, None,
                        "{opt:?} kind {kind} res {res} scan {scan}: first differing image byte"
                    );
                }
            }
        }
    }
}
