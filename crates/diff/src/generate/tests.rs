//! Generator self-checks: determinism, structure, and that every mnemonic is reachable.

use super::*;
use crate::coverage::Coverage;
use stljit_core::ir::{BoxOp, Operand};

fn structure_ok(p: &Program) -> Result<(), String> {
    for pou in &p.pous {
        for (id, at) in pou.labels.iter().enumerate() {
            if pou.ops.get(at.index()) != Some(&Op::Label(LabelId::new(id))) {
                return Err(format!("{}: label {id} not at {at}", pou.name));
            }
        }
        let mut scr_open = false;
        for (i, op) in pou.ops.iter().enumerate() {
            match op {
                Op::For { .. } if scr_open => return Err("FOR inside SCR".into()),
                Op::For { next, .. }
                    if pou.ops.get(next.index())
                        != Some(&Op::Next {
                            head: OpIdx::new(i),
                        }) =>
                {
                    return Err(format!("{}: FOR at {i} has no NEXT", pou.name));
                }
                Op::ScrBegin { .. } if scr_open => return Err("nested LSCR".into()),
                Op::ScrBegin { .. } => scr_open = true,
                Op::ScrEnd => scr_open = false,
                Op::ScrCondEnd { end } if pou.ops.get(end.index()) != Some(&Op::ScrEnd) => {
                    return Err(format!("{}: CSCRE at {i} misses SCRE", pou.name));
                }
                Op::Jump(_) | Op::Label(_) | Op::End { conditional: true } if scr_open => {
                    return Err(format!("{}: control op {i} inside SCR", pou.name));
                }
                op if op.callee().is_some_and(|id| {
                    !matches!(
                        p.pous.get(id.index()).map(|q| q.kind),
                        Some(PouKind::Subroutine(_))
                    )
                }) =>
                {
                    return Err(format!("{}: call to a non-subroutine", pou.name));
                }
                Op::Wdr if pou.kind != PouKind::Main => return Err("WDR in a subroutine".into()),
                _ => {}
            }
        }
        if scr_open {
            return Err(format!("{}: LSCR without SCRE", pou.name));
        }
    }
    let mut kinds = BTreeMap::new();
    for pou in &p.pous {
        for op in &pou.ops {
            if let Op::Timer { kind, timer, .. } = op
                && *kinds.entry(timer.0).or_insert(*kind) != *kind
            {
                return Err(format!("{timer} used with two kinds"));
            }
        }
    }
    let edges = p
        .pous
        .iter()
        .flat_map(|q| &q.ops)
        .filter(|op| matches!(op, Op::Edge { .. }))
        .count();
    if edges != p.edges.len() {
        return Err("edge slots and declarations differ".into());
    }
    Ok(())
}

#[test]
fn same_seed_same_case() {
    let cfg = GenConfig::default();
    for seed in 0..20 {
        assert_eq!(case_from_seed(seed, &cfg), case_from_seed(seed, &cfg));
    }
    assert_ne!(case_from_seed(1, &cfg), case_from_seed(2, &cfg));
}

#[test]
fn programs_are_well_structured() {
    let cfg = GenConfig::default();
    for seed in 0..2000 {
        let case = case_from_seed(seed, &cfg);
        if let Err(e) = structure_ok(&case.program) {
            panic!("seed {seed}: {e}");
        }
        assert_eq!(case.stimulus.len(), 50);
        let times: Vec<u64> = case.stimulus.scans.iter().map(|s| s.t_ms).collect();
        assert!(
            times.windows(2).all(|w| w[0] <= w[1]),
            "seed {seed}: time goes back"
        );
    }
}

#[test]
fn generated_programs_pass_the_verifier() {
    let cfg = GenConfig::default();
    for seed in 0..2000 {
        let case = case_from_seed(seed, &cfg);
        if let Err(e) = stljit_core::ir::verify(&case.program) {
            panic!("seed {seed}: {e}");
        }
    }
}

/// Calls with parameters are generated, every call of a subroutine passes the same formals, and
/// such programs survive the S7 print → compile round trip (the printer rebuilds the callee's
/// `VAR_…` sections from its calls, so the formals must be the front end's own allocation).
#[test]
fn parameterised_calls_are_generated_and_round_trip() {
    let cfg = GenConfig::default();
    let mut with_args = 0;
    for seed in 0..400 {
        let p = case_from_seed(seed, &cfg).program;
        let mut formals = BTreeMap::new();
        let mut has = false;
        for op in p.pous.iter().flat_map(|q| &q.ops) {
            if let Op::CallArgs(c) = op {
                has = true;
                let f: Vec<_> = c
                    .args
                    .iter()
                    .map(|a| (a.dir, a.value))
                    .map(|(d, v)| match v {
                        stljit_core::ir::ArgValue::Bit { formal, .. } => (d, format!("{formal:?}")),
                        stljit_core::ir::ArgValue::Value { width, formal, .. } => {
                            (d, format!("{width:?}{formal:?}"))
                        }
                    })
                    .collect();
                let first = formals.entry(c.callee).or_insert_with(|| f.clone());
                assert_eq!(*first, f, "seed {seed}: two calls of {} differ", c.callee);
            }
        }
        if has {
            with_args += 1;
            if let Err(e) = crate::roundtrip::roundtrip(&p) {
                panic!("seed {seed}: {e}");
            }
        }
    }
    assert!(
        with_args > 40,
        "only {with_args} of 400 programs call with parameters"
    );
}

/// FOR loops whose INIT or FINAL overlaps INDX, and INDX written inside the body (issue 16: the
/// order INDX := INIT, then FINAL, must stay covered by the differential fuzzer).
#[test]
fn for_operands_overlapping_the_index_are_generated() {
    let overlaps = |a: &Operand, b: &Operand| match (a, b) {
        (Operand::Mem(x), Operand::Mem(y)) => x.area == y.area && x.offset.abs_diff(y.offset) < 2,
        _ => false,
    };
    let cfg = GenConfig::default();
    let (mut init, mut limit, mut written) = (0, 0, 0);
    for seed in 0..2000 {
        for pou in &case_from_seed(seed, &cfg).program.pous {
            for (i, op) in pou.ops.iter().enumerate() {
                let Op::For {
                    index,
                    init: first,
                    limit: last,
                    ..
                } = op
                else {
                    continue;
                };
                init += usize::from(overlaps(index, first));
                limit += usize::from(overlaps(index, last));
                let bumped = matches!(pou.ops.get(i + 2), Some(Op::Box(BoxOp::Step { dst, .. })) if dst == index);
                written += usize::from(bumped);
            }
        }
    }
    assert!(
        init > 0 && limit > 0 && written > 0,
        "overlapping INIT {init}, FINAL {limit}, INDX written {written}"
    );
}

#[test]
fn every_mnemonic_is_generated() {
    let cfg = GenConfig::default();
    let mut cov = Coverage::default();
    for seed in 0..3000 {
        cov.add_program(&case_from_seed(seed, &cfg).program);
    }
    let missing = cov.missing();
    assert!(missing.is_empty(), "never generated: {missing:?}");
    for kind in [
        "*V", "*L", "*AC", "&V", "&T", "const", "AC", "L", "HC", "AI", "AQ", "T", "C", "\"str\"",
    ] {
        assert!(
            cov.operands.contains_key(kind),
            "operand kind {kind} never generated"
        );
    }
}

#[test]
fn fuzzer_bytes_never_panic_and_run_out_small() {
    let cfg = GenConfig::default();
    let empty = case_from_bytes(&[], &cfg);
    assert!(empty.program.op_count() < 20, "{:?}", empty.program);
    let mut r = crate::rng::SplitMix64::new(3);
    for len in [1usize, 7, 64, 512, 4096] {
        for _ in 0..50 {
            let data: Vec<u8> = (0..len).map(|_| r.next_u64() as u8).collect();
            let case = case_from_bytes(&data, &cfg);
            structure_ok(&case.program).unwrap();
        }
    }
}

/// Runs the generated cases of seeds `seeds` whose program `wanted` on the interpreter, with
/// their stimulus, until a scan ends other than OK; `after_scan(image, before)` sees the image
/// after every OK scan and the bytes it had before it. Returns how many cases ran.
fn run_generated(
    seeds: std::ops::Range<u64>,
    wanted: impl Fn(&Program) -> bool,
    mut after_scan: impl FnMut(&stljit_runtime::Image, &[u8]),
    mut after_case: impl FnMut(&stljit_runtime::Image),
) -> usize {
    use crate::engines::EngineKind;
    use crate::oracle::{RunOptions, apply_stimulus, start_image};
    let cfg = GenConfig::default();
    let mut programs = 0;
    for seed in seeds {
        let case = case_from_seed(seed, &cfg);
        if !wanted(&case.program) {
            continue;
        }
        programs += 1;
        let mut e = EngineKind::Interp.build(&case.program).expect("builds");
        let mut img = start_image(&case.program, &RunOptions::default());
        for s in &case.stimulus.scans {
            apply_stimulus(&mut img, s);
            let before = img.bytes().to_vec();
            if e.scan(&mut img, s.t_ms) != stljit_core::ScanStatus::Ok {
                break;
            }
            after_scan(&img, &before);
        }
        after_case(&img);
    }
    programs
}

/// The stimulus raises the events the programs attach: most programs with interrupt routines
/// queue events (input edges, timed interrupts, T32/T96) and run routines.
#[test]
fn interrupt_routines_run() {
    use stljit_core::layout::IntState;
    let mut raised = 0;
    let programs = run_generated(
        0..300,
        Program::has_interrupts,
        |_, _| {},
        |img| {
            let seq = img.layout().int_state(IntState::SEQ) as usize;
            raised += usize::from(img.bytes()[seq..seq + 4] != [0; 4]);
        },
    );
    assert!(programs > 50, "{programs} programs with interrupt routines");
    assert!(
        2 * raised > programs,
        "{raised} of {programs} queued an event"
    );
}

/// The stimulus drives the counters the programs define: in many programs with HDEF some
/// counter's value moves.
#[test]
fn high_speed_counters_count() {
    use stljit_core::Area;
    let (mut counted, moved) = (0, std::cell::Cell::new(false));
    let programs = run_generated(
        0..400,
        Program::defines_hsc,
        |img, before| {
            let hc = img.layout().base(Area::HC) as usize;
            let n = img.layout().area_size(Area::HC) as usize;
            moved.set(moved.get() | (img.bytes()[hc..hc + n] != before[hc..hc + n]));
        },
        |_| counted += usize::from(moved.replace(false)),
    );
    assert!(
        programs > 30,
        "{programs} programs with high-speed counters"
    );
    assert!(3 * counted > programs, "{counted} of {programs} counted");
}

/// Programs that communicate get received bytes, and the ports take them in: in most of them
/// characters leave a receive FIFO (s7-200-more §10.4), and in some an RCV stores them.
#[test]
fn received_bytes_reach_the_ports() {
    use stljit_core::comm::PORTS;
    use stljit_core::layout::PortState;
    let (mut with_rx, mut consumed, mut stored) = (0, 0, 0);
    for seed in 0..600 {
        let case = case_from_seed(seed, &GenConfig::default());
        let has_rx = case.stimulus.scans.iter().any(|s| !s.rx.is_empty());
        assert!(
            case.program.uses_ports() || !has_rx,
            "seed {seed}: received bytes for a program without ports"
        );
        with_rx += usize::from(has_rx);
    }
    let field = |img: &stljit_runtime::Image, port: u8, f: u32| {
        img.bytes()[img.layout().port_state(port, f) as usize]
    };
    let any =
        |img: &stljit_runtime::Image, f: u32| PORTS.iter().any(|p| field(img, p.port, f) != 0);
    let stored_now = std::cell::Cell::new(false);
    let programs = run_generated(
        0..600,
        Program::uses_ports,
        |img, _| stored_now.set(stored_now.get() | any(img, PortState::RX_COUNT)),
        |img| {
            consumed += usize::from(any(img, PortState::FIFO_HEAD));
            stored += usize::from(stored_now.replace(false));
        },
    );
    assert!(programs > 40, "{programs} programs with ports");
    assert!(2 * with_rx > programs, "{with_rx} of {programs} got bytes");
    assert!(2 * consumed > programs, "{consumed} of {programs} received");
    assert!(
        5 * stored > programs,
        "{stored} of {programs} stored a character"
    );
}

/// The §4–§7 instructions reach their error paths in generated programs: a table or string
/// past its area (0x0091), an index 0 (0x009B), a clock write with a bad date (0x0007), a clock
/// on the A5, which has none (0x000C), and a bad pointer (0x0006).
#[test]
fn ext_error_paths_are_reached() {
    let mut codes = std::collections::BTreeSet::new();
    let ext = |p: &Program| {
        p.pous
            .iter()
            .flat_map(|q| &q.ops)
            .any(|op| matches!(op, Op::Ext(_)))
    };
    run_generated(
        0..3000,
        ext,
        |img, _| _ = codes.insert(img.last_error()),
        |_| {},
    );
    for code in [0x0006, 0x0007, 0x000C, 0x0091, 0x009B] {
        assert!(
            codes.contains(&code),
            "error {code:#06x} never raised: {codes:x?}"
        );
    }
}
