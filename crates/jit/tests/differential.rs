//! The JIT against the reference interpreter: generated programs (the diff crate's generator of
//! valid programs) and hand-written programs per instruction group, whole image compared after
//! every scan.

mod common;

use common::{check, check_case, check_with, stimulus, stl};
use stljit_diff::generate::{GenConfig, case_from_seed};
use stljit_diff::oracle::RunOptions;

/// Generated cases per run (more in release builds, where each takes milliseconds).
const SEEDS: u64 = if cfg!(debug_assertions) { 60 } else { 400 };

#[test]
fn generated_programs_agree() {
    let cfg = GenConfig {
        scans: 30,
        ..GenConfig::default()
    };
    let mut compiled = 0u64;
    for seed in 0..SEEDS {
        let case = case_from_seed(seed, &cfg);
        if check_case(&case) {
            compiled += 1;
        }
    }
    // Every instruction the generator emits is compiled; nothing may be skipped.
    assert_eq!(compiled, SEEDS, "some generated programs were not compiled");
}

/// Plain programs (`GenConfig::plain`), whose M and V bits the JIT keeps resident: scan by
/// scan, each run finding its shadow current (the image is the one it left) or unpacking it
/// anew (the stimulus wrote the image).
#[test]
fn generated_plain_programs_agree() {
    let cfg = GenConfig {
        scans: 30,
        plain: true,
        ..GenConfig::default()
    };
    let mut resident = 0u64;
    for seed in 0..SEEDS {
        let case = case_from_seed(seed, &cfg);
        assert!(check_case(&case), "seed {seed} was not compiled");
        let jit = stljit_jit::JitProgram::compile(&case.program, &Default::default())
            .expect("JIT compiles");
        resident += u64::from(jit.resident_bytes() > 0);
    }
    assert!(
        resident > SEEDS * 3 / 4,
        "only {resident} with resident bits"
    );
}

/// Resident bits follow the image wherever it changes between runs (`Image::version`): a
/// write through the image's API, a second image run by the same program, a clone, and a
/// second program on the same image. Expected values: the program copies M0.0..M0.3 to
/// M1.0..M1.3, sets V2.0 while M0.0 is 1 and copies V2.0 to V2.1 (spec §4.1, `=` and `S`).
#[test]
fn resident_bits_follow_the_image() {
    use stljit_core::ir::BitLoc;
    use stljit_core::{Area, ScanStatus};
    use stljit_runtime::{Engine, Image};
    let p = stl(
        "LD M0.0\n= M1.0\nLD M0.1\n= M1.1\nLD M0.2\n= M1.2\nLD M0.3\n= M1.3\n\
                 LD M0.0\nS V2.0, 1\nLD V2.0\n= V2.1\n",
    );
    let mut jit = stljit_jit::JitProgram::compile(&p, &Default::default()).expect("compiles");
    assert!(jit.resident_bytes() >= 3, "M0, M1 and V2 are resident");
    let m = |byte, bit| BitLoc {
        area: Area::M,
        byte,
        bit,
    };
    let v20 = BitLoc {
        area: Area::V,
        byte: 2,
        bit: 0,
    };
    let mut a = Image::cold_start(&p);
    let mut b = Image::cold_start(&p);
    assert_eq!(jit.scan(&mut a, 0), ScanStatus::Ok);
    a.set_bit(m(0, 2), 0, true).unwrap();
    assert_eq!(jit.scan(&mut a, 10), ScanStatus::Ok);
    assert!(a.bit(m(1, 2), 0).unwrap(), "the write reached the shadow");
    // Another image in between: each run takes that image's bits.
    b.set_bit(m(0, 0), 0, true).unwrap();
    assert_eq!(jit.scan(&mut b, 0), ScanStatus::Ok);
    assert!(b.bit(m(1, 0), 0).unwrap() && b.bit(v20, 0).unwrap());
    assert!(!b.bit(m(1, 2), 0).unwrap(), "b never had M0.2");
    assert_eq!(jit.scan(&mut a, 20), ScanStatus::Ok);
    assert!(a.bit(m(1, 2), 0).unwrap() && !a.bit(m(1, 0), 0).unwrap());
    assert!(!a.bit(v20, 0).unwrap(), "a never had M0.0");
    // A clone, changed, then the original again.
    let mut c = a.clone();
    c.set_bit(m(0, 3), 0, true).unwrap();
    assert_eq!(jit.scan(&mut c, 30), ScanStatus::Ok);
    assert!(c.bit(m(1, 3), 0).unwrap());
    assert_eq!(jit.scan(&mut a, 30), ScanStatus::Ok);
    assert!(
        !a.bit(m(1, 3), 0).unwrap(),
        "the clone's bit stayed in the clone"
    );
    // A second program on the same image, then the first again.
    let q = stl("LD M0.1\n= M1.1\n");
    let mut other = stljit_jit::JitProgram::compile(&q, &Default::default()).expect("compiles");
    a.set_bit(m(0, 1), 0, true).unwrap();
    assert_eq!(other.scan(&mut a, 40), ScanStatus::Ok);
    a.set_bit(m(1, 1), 0, false).unwrap();
    a.set_bit(m(0, 1), 0, false).unwrap();
    assert_eq!(other.scan(&mut a, 50), ScanStatus::Ok);
    assert_eq!(jit.scan(&mut a, 60), ScanStatus::Ok);
    assert!(!a.bit(m(1, 1), 0).unwrap(), "M0.1 is 0 again");
    // The interpreter agrees with every one of these images.
    let mut interp = stljit_interp::Interpreter::new(&p).expect("accepts");
    let mut want = a.clone();
    want.set_bit(m(0, 0), 0, true).unwrap();
    let mut got = want.clone();
    assert_eq!(interp.scan(&mut want, 70), jit.scan(&mut got, 70));
    assert!(want == got);
}

#[test]
fn bit_logic_and_stack() {
    let p = stl(
        "LD I0.0\nA I0.1\nLDN I0.2\nO I0.3\nALD\n= Q0.0\nLD I1.0\nLPS\nA I1.1\n= Q0.1\nLRD\nAN I1.2\n= Q0.2\nLPP\nON I1.3\n= Q0.3\n\
         LD I0.4\nLD I0.5\nLD I0.6\nLD I0.7\nOLD\nALD\nNOT\n= M0.0\nLDS 2\n= M0.1\nLD M0.0\nEU\n= M1.0\nLD I0.0\nED\n= M1.1\n\
         LD I0.0\nS Q1.0, 3\nLD I0.1\nR Q1.1, 1\nLD SM0.5\n= V10.3\nLDI I0.3\n=I Q2.0\n",
    );
    for seed in 0..4 {
        check(&p, &stimulus(seed, 40));
    }
}

#[test]
fn nine_level_truncation() {
    let p = stl(
        "LD SM0.0\nLDN SM0.0\nLDN SM0.0\nLDN SM0.0\nLDN SM0.0\nLDN SM0.0\nLDN SM0.0\nLDN SM0.0\nLDN SM0.0\nLDN SM0.0\nOLD\nOLD\nOLD\nOLD\nOLD\nOLD\nOLD\nOLD\nOLD\n= Q0.0\n",
    );
    check(&p, &stimulus(1, 3));
}

#[test]
fn moves_compares_and_arithmetic() {
    let p = stl(
        "LD I0.0\nMOVW IW0, VW10\nMOVB IB1, VB20\nMOVD ID0, VD30\n+I IW2, VW10\n-I 1000, VW10\nAENO\n= Q0.0\n\
         LD SM0.0\n+D VD30, VD40\nINCW VW50\nDECB VB52\nANDW IW4, VW54\nORB 16#0F, VB56\nXORD ID4, VD60\nINVW VW64\n\
         *I IW6, VW70\n/I IW8, VW72\nMUL IW2, VD74\nDIV IW4, VD78\nSLW VW80, 3\nRRD VD82, 5\nSWAP VW86\n\
         LDW>= VW10, 100\n= Q0.1\nLDB< IB0, IB1\n= Q0.2\nAD<> VD30, 0\n= Q0.3\nMOVR 1.5, VD90\n+R VD90, VD94\nLDR> VD94, 2.0\n= Q0.4\n\
         ITD IW0, VD100\nDTR VD100, VD104\nROUND VD104, VD108\nBTI IB3, VW112\nSEG IB2, VB114\n",
    );
    for seed in 0..4 {
        check(&p, &stimulus(seed, 30));
    }
}

#[test]
fn timers_and_counters() {
    let p = stl(
        "LD I0.0\nTON T37, 5\nLD I0.1\nTONR T3, 20\nLD I0.2\nTOF T2, 8\nLD T37\n= Q0.0\nLD T3\n= Q0.1\nLD T2\n= Q0.2\n\
         LD I0.3\nLD I0.4\nCTU C1, 3\nLD I0.5\nLD I0.6\nCTD C2, 2\nLD I0.3\nLD I0.5\nLD I0.7\nCTUD C3, 2\n\
         LD C1\n= Q1.0\nLD I1.0\nR T3, 1\nLD I1.1\nR C1, 2\n",
    );
    for seed in 0..4 {
        check(&p, &stimulus(seed, 60));
    }
}

#[test]
fn control_flow_and_scr() {
    let p = stl(
        "LD I0.0\nJMP 1\nLD SM0.0\n= Q0.0\nLBL 1\nLD SM0.0\nFOR VW0, 1, IW2\nLD SM0.0\nINCW VW10\nNEXT\n\
         LD SM0.1\nS S0.0, 1\nLSCR S0.0\nLD I0.1\nSCRT S0.1\nLD SM0.0\n= Q0.5\nSCRE\nLSCR S0.1\nLD I0.2\nSCRT S0.0\nLD I0.3\nCSCRE\nLD SM0.0\n= Q0.6\nSCRE\n\
         LD I0.4\nCALL SBR_0\nLD I0.5\nSTOP\nMEND\nSUBROUTINE_BLOCK SBR_0:SBR0\nBEGIN\nLD SM0.0\nINCW VW20\nLD I1.0\nCRET\nLD SM0.0\n= Q1.0\nEND_SUBROUTINE_BLOCK\n",
    );
    for seed in 0..4 {
        check(&p, &stimulus(seed, 30));
    }
}

#[test]
fn watchdog_on_endless_loop() {
    let p = stl("LBL 0\nLD SM0.0\nINCW VW0\nJMP 0\n");
    check_with(
        &p,
        &stimulus(2, 3),
        RunOptions {
            loop_limit: 1000,
            max_diffs: 8,
        },
    );
    let p = stl("LD SM0.0\nFOR VW0, 1, 32767\nLD SM0.0\nNEXT\n");
    check_with(
        &p,
        &stimulus(3, 3),
        RunOptions {
            loop_limit: 500,
            max_diffs: 8,
        },
    );
}

#[test]
fn error_paths() {
    // Bad pointers (boxes: non-fatal 0x0006; compares: fatal), division by zero, overflow, NaN.
    let p = stl(
        "LD SM0.0\nMOVD 16#0B000000, VD0\nMOVW *VD0, VW10\nAENO\n= Q0.0\nMOVD &VB100, VD4\nMOVW 7, *VD4\n\
         /I 0, VW20\nMOVW 32767, VW22\n+I 1, VW22\nMOVD 16#7FC00000, VD30\nLD I0.0\nLDR= VD30, VD30\n= Q0.1\n",
    );
    for seed in 0..3 {
        check(&p, &stimulus(seed, 6));
    }
    let p = stl("LD SM0.0\nMOVD 16#06FFFFFF, VD0\nLD I0.1\nLDW= *VD0, 5\n= Q0.0\n");
    check(&p, &stimulus(5, 4));
}

#[test]
fn call_nesting_limit() {
    let p = stl(
        "LD SM0.0\nCALL SBR_0\nMEND\nSUBROUTINE_BLOCK SBR_0:SBR0\nBEGIN\nLD SM0.0\nINCW VW0\nCALL SBR_0\nEND_SUBROUTINE_BLOCK\n",
    );
    check(&p, &stimulus(1, 3));
}

/// A program longer than the default chunk size, with forward jumps between chunks, compiled
/// with the default options (several chunk functions and a dispatcher) and split at every block.
#[test]
fn long_program_split_into_chunks() {
    let p = benchmark("mixed_10k.stl");
    assert!(p.pous[0].ops.len() > 2 * stljit_jit::DEFAULT_CHUNK_OPS);
    check(&p, &stimulus(5, 12));
}

/// Logic-stack levels pushed before a jump and read after its label (LRD, LPP, ALD, OLD, LDS),
/// with the jump taken and not taken: the stack register carries exactly the live levels.
#[test]
fn stack_levels_across_jumps() {
    let p = stl(
        "LD I0.0\nLD I0.1\nLD I0.2\nLPS\nA I0.3\nJMP 1\nLBL 1\nLRD\n= Q0.0\nLPP\n= Q0.1\n\
         ALD\n= Q0.2\nLD I0.4\nLD I0.5\nLD I0.6\nLD I0.7\nJMP 2\nLBL 2\nLDS 3\n= Q0.3\nOLD\n\
         OLD\n= Q0.4\nLD I1.0\nJMP 3\nLPS\nLBL 3\nLPP\n= Q0.5\n\
         LD I1.1\nLPS\nAN I1.2\nJMP 4\nLBL 4\nLRD\n= Q0.6\n",
    );
    for seed in 0..6 {
        check(&p, &stimulus(seed, 40));
    }
}

/// The bit-logic benchmark with the default options: long runs without stores, where bit tests
/// and bit writes take 32-bit loads, next to bytes stored a few ops earlier, where they do not.
#[test]
fn long_bit_logic_program() {
    check(&benchmark("bitlogic_10k.stl"), &stimulus(7, 12));
}

/// A program of the benchmark corpus (`benches/programs/`).
fn benchmark(name: &str) -> stljit_core::ir::Program {
    let path = format!(
        "{}/../../benches/programs/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).expect("benchmark corpus is checked in");
    stl(&text)
}

/// Loops whose body and exit lie in different chunks: FOR/NEXT, a backward JMP counted by the
/// loop budget, and CSCRE jumping to the SCRE of its segment (run with every block split).
#[test]
fn loops_across_chunks() {
    let p = stl(
        "LD SM0.0\nMOVW 0, VW0\nLBL 1\nLD SM0.0\nINCW VW0\nLDW< VW0, 5\nJMP 1\n\
         LD SM0.0\nFOR VW2, 1, 3\nLD SM0.0\nINCW VW4\nLD I0.0\nJMP 2\nNEXT\nLBL 2\n\
         LD SM0.1\nS S0.0, 1\nLSCR S0.0\nLD I0.1\nCSCRE\nLD SM0.0\n= Q0.0\nSCRE\n",
    );
    for seed in 0..4 {
        check(&p, &stimulus(seed, 20));
    }
}

/// `JitProgram::run_scans`, the native N-scan loop for long simulations, equals the interpreter
/// run scan by scan: same number of scans, same last status (STOP and fatal errors end both at
/// the same scan) and the same image, for generated programs with their first scan's stimulus
/// held for the whole run.
#[test]
fn run_scans_equals_the_interpreter_scan_by_scan() {
    use stljit_core::ScanStatus;
    use stljit_diff::oracle::{apply_stimulus, start_image};
    use stljit_runtime::Engine;
    const N: u64 = 40;
    let cfg = GenConfig {
        scans: 1,
        ..GenConfig::default()
    };
    let run = RunOptions::default();
    let mut ended_early = 0;
    for seed in 0..SEEDS / 2 {
        let case = case_from_seed(seed, &cfg);
        let prepare = || {
            let mut img = start_image(&case.program, &run);
            apply_stimulus(&mut img, &case.stimulus.scans[0]);
            img
        };
        let mut interp =
            stljit_interp::Interpreter::new(&case.program).expect("interpreter accepts it");
        let mut want = prepare();
        let (mut done, mut status) = (0, ScanStatus::Ok);
        while done < N && status == ScanStatus::Ok {
            status = interp.scan(&mut want, done * 10);
            done += 1;
        }
        if status != ScanStatus::Ok {
            ended_early += 1;
        }
        for opt in [stljit_jit::OptLevel::None, stljit_jit::OptLevel::Speed] {
            let mut jit =
                stljit_jit::JitProgram::compile(&case.program, &stljit_jit::JitOptions::at(opt))
                    .expect("JIT compiles");
            let mut got = prepare();
            let (jdone, jstatus) = jit.run_scans(&mut got, 0, 10, N);
            assert_eq!((jdone, jstatus), (done, status), "seed {seed} at {opt:?}");
            assert!(
                got.bytes() == want.bytes(),
                "seed {seed} at {opt:?}: images differ after {done} scans"
            );
        }
    }
    assert!(
        ended_early > 0,
        "no program stopped early: the early exit is untested"
    );
}

/// The native loop in stretches, as the simulation driver calls it between stimulus rows:
/// stretches of 1–6 scans with a random scan time each, the stimulus of the stretch's first
/// scan applied before it (inputs, AI, HMI writes), and a stretch that starts before the
/// previous one's time (time running backwards), against the interpreter scan by scan. The
/// inline prologue/epilogue (`scan_loop`) and the runtime's `scan::begin`/`end` must leave the
/// same bytes whichever path each scan takes (first scan, STOP, fatal, clock timers).
#[test]
fn run_scans_in_stretches_equals_scan_by_scan() {
    let cfg = GenConfig {
        scans: 40,
        ..GenConfig::default()
    };
    let (stretches, watched) = generated_in_stretches(&cfg, 0x5EED);
    assert!(stretches > SEEDS, "{stretches} stretches");
    assert!(
        watched > SEEDS / 4,
        "only {watched} stretches ended at a watched change"
    );
}

/// The same for plain programs, whose M and V bits the native loop keeps resident: it packs
/// them before each watch compares and at every exit.
#[test]
fn plain_programs_in_stretches_equal_scan_by_scan() {
    let cfg = GenConfig {
        scans: 40,
        plain: true,
        ..GenConfig::default()
    };
    let (stretches, watched) = generated_in_stretches(&cfg, 0x91A1);
    assert!(stretches > SEEDS, "{stretches} stretches");
    assert!(
        watched > SEEDS / 4,
        "only {watched} ended at a watched change"
    );
}

/// The same for Omron programs, whose scans take the inline path too: the system bits (`P_On`,
/// the clock pulses at random scan times, `P_First_Cycle` OFF after the first cycle) and the
/// condition flags cleared at the cycle's start.
#[test]
fn omron_run_scans_in_stretches_equals_scan_by_scan() {
    use stljit_core::Family;
    use stljit_diff::generate::generate_in;
    use stljit_diff::rng::Choices;
    let cfg = GenConfig {
        scans: 40,
        ..GenConfig::default()
    };
    let (mut stretches, mut cases) = (0u64, 0u64);
    for seed in 0..SEEDS / 2 {
        let mut c = Choices::from_seed(seed ^ 0x0C01);
        // A program the front end rejects is the generator's business (its own tests).
        if let Ok(g) = generate_in(Family::Omron, &mut c, &cfg) {
            // Scan times up to 2 s, so that 40 scans pass the 1-minute pulse's edges too.
            stretches += stretches_agree(&g.case, seed, 2000).0;
            cases += 1;
        }
    }
    assert!(cases > SEEDS / 4, "only {cases} Omron programs generated");
    assert!(stretches > SEEDS / 2, "{stretches} stretches");
}

/// [`stretches_agree`] on `SEEDS / 2` programs generated with `cfg` (seeds salted with `salt`):
/// the stretches run and those a watched change ended.
fn generated_in_stretches(cfg: &GenConfig, salt: u64) -> (u64, u64) {
    let (mut stretches, mut watched) = (0u64, 0u64);
    for seed in 0..SEEDS / 2 {
        let (s, w) = stretches_agree(&case_from_seed(seed ^ salt, cfg), seed, 200);
        stretches += s;
        watched += w;
    }
    (stretches, watched)
}

/// Runs `case` in random stretches (scan times 1..=`max_dt` ms) on the JIT's native loop and
/// scan by scan on the interpreter, comparing the images after every stretch; the number of
/// stretches run, and of those that a watched change ended early.
fn stretches_agree(case: &stljit_diff::generate::Case, seed: u64, max_dt: u64) -> (u64, u64) {
    use stljit_core::{Area, ScanStatus};
    use stljit_diff::oracle::{apply_stimulus, start_image};
    use stljit_runtime::{ChangeWatch, Engine};
    let run = RunOptions::default();
    let (mut stretches, mut watched) = (0u64, 0u64);
    let mut interp =
        stljit_interp::Interpreter::new(&case.program).expect("interpreter accepts it");
    let opt = if seed.is_multiple_of(2) {
        stljit_jit::OptLevel::Speed
    } else {
        stljit_jit::OptLevel::None
    };
    let mut jit = stljit_jit::JitProgram::compile(&case.program, &stljit_jit::JitOptions::at(opt))
        .expect("JIT compiles");
    let (mut want, mut got) = (
        start_image(&case.program, &run),
        start_image(&case.program, &run),
    );
    let (mut k, mut t, mut rng) = (0usize, 0u64, seed.wrapping_mul(0x9E37_79B9) | 1);
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    while k < case.stimulus.scans.len() {
        let len = 1 + (next() % 6) as usize;
        let dt = 1 + next() % max_dt;
        // Now and then a stretch starts 50 ms before the last scan's time.
        let t0 = if next() % 11 == 0 {
            t.saturating_sub(50)
        } else {
            t
        };
        apply_stimulus(&mut want, &case.stimulus.scans[k]);
        apply_stimulus(&mut got, &case.stimulus.scans[k]);
        // Every other stretch also ends at the first scan that changes a byte of Q or of the
        // first bytes of M and V (`Engine::run_scans_watching`: the interpreter scan by scan,
        // the JIT in its native loop).
        let (done, status) = if next() % 2 == 0 {
            let l = want.layout().clone();
            let ranges = [Area::Q, Area::M, Area::V].map(|a| {
                let base = l.base(a) as usize;
                base..base + (l.area_size(a) as usize).min(8)
            });
            let mut wwant = ChangeWatch::new(&want, ranges.clone());
            let mut wgot = ChangeWatch::new(&got, ranges);
            let want_run = interp.run_scans_watching(&mut want, t0, dt, len as u64, &mut wwant);
            let got_run = jit.run_scans_watching(&mut got, t0, dt, len as u64, &mut wgot);
            assert_eq!(got_run, want_run, "seed {seed}, scan {k}: watching");
            assert_eq!(wgot, wwant, "seed {seed}, scan {k}: the watches' bytes");
            watched += u64::from(want_run.0 < len as u64 && want_run.1 == ScanStatus::Ok);
            want_run
        } else {
            let mut status = ScanStatus::Ok;
            let mut done = 0;
            while done < len as u64 && status == ScanStatus::Ok {
                status = interp.scan(&mut want, t0 + done * dt);
                done += 1;
            }
            // A call for no scans runs none and changes no byte (the loop tests its count
            // first).
            let before = got.bytes().to_vec();
            assert_eq!(jit.run_scans(&mut got, t0, dt, 0), (0, ScanStatus::Ok));
            assert!(
                got.bytes() == before.as_slice(),
                "seed {seed}: 0 scans wrote"
            );
            let (jdone, jstatus) = jit.run_scans(&mut got, t0, dt, len as u64);
            assert_eq!((jdone, jstatus), (done, status), "seed {seed}, scan {k}");
            (done, status)
        };
        assert!(
            got.bytes() == want.bytes(),
            "seed {seed}: images differ after the stretch starting at scan {k}"
        );
        stretches += 1;
        if status != ScanStatus::Ok {
            break;
        }
        k += done as usize;
        t = t0 + (done - 1) * dt;
    }
    (stretches, watched)
}

/// The native loop's time step at the ends of its ranges, against the interpreter: a scan
/// time above `u32::MAX` ms (the 1 ms delta saturates, spec §2.1 step 1; the 10 and 100 ms
/// deltas do not), a stretch whose time wraps past `u64::MAX` (every delta is 0 in the scan
/// after the wrap, as for any step back in time), and scans after it. Programs with event
/// sources are left out: their scans take the runtime's prologue anyway, and it would service
/// every timed event of the 58 days the first stretch spans.
#[test]
fn run_scans_time_step_at_the_range_ends() {
    use stljit_core::ScanStatus;
    use stljit_diff::oracle::{apply_stimulus, start_image};
    use stljit_runtime::Engine;
    let cfg = GenConfig {
        scans: 12,
        ..GenConfig::default()
    };
    // (t0, dt, scans): the images are compared after each stretch, so the second one ends
    // with the scan after the wrap (time 0).
    let stretches = [(0, 5_000_000_000, 3), (u64::MAX - 20, 7, 4), (3, 1, 2)];
    let mut cases = 0;
    for seed in 0..SEEDS / 8 {
        let case = case_from_seed(seed ^ 0x7173, &cfg);
        let p = &case.program;
        if p.has_interrupts() || p.defines_hsc() || p.uses_pulse() || p.uses_ports() {
            continue;
        }
        cases += 1;
        let run = RunOptions::default();
        let mut interp =
            stljit_interp::Interpreter::new(&case.program).expect("interpreter accepts it");
        for opt in [stljit_jit::OptLevel::None, stljit_jit::OptLevel::Speed] {
            let mut jit =
                stljit_jit::JitProgram::compile(&case.program, &stljit_jit::JitOptions::at(opt))
                    .expect("JIT compiles");
            let (mut want, mut got) = (
                start_image(&case.program, &run),
                start_image(&case.program, &run),
            );
            for (k, &(t0, dt, len)) in stretches.iter().enumerate() {
                apply_stimulus(&mut want, &case.stimulus.scans[k]);
                apply_stimulus(&mut got, &case.stimulus.scans[k]);
                let (mut done, mut status) = (0u64, ScanStatus::Ok);
                while done < len && status == ScanStatus::Ok {
                    let t = t0.wrapping_add(done.wrapping_mul(dt));
                    status = interp.scan(&mut want, t);
                    done += 1;
                }
                assert_eq!(
                    jit.run_scans(&mut got, t0, dt, len),
                    (done, status),
                    "seed {seed}, stretch {k}, {opt:?}"
                );
                assert!(
                    got.bytes() == want.bytes(),
                    "seed {seed}: images differ after stretch {k} ({opt:?})"
                );
                if status != ScanStatus::Ok {
                    break;
                }
            }
        }
    }
    assert!(
        cases > SEEDS / 16,
        "only {cases} programs without event sources"
    );
}
