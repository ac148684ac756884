//! The embedding API's behaviour, on both engines: addresses and values, time, forcing at the
//! documented points of the scan, snapshots that continue identically, observers, errors.

use stljit_api::{
    EngineKind, Error, FnObserver, Options, Outcome, Plc, Project, Snapshot, Type, Until, Value,
};

mod common;

use common::{ENGINES, plc};

/// I0.0 drives Q0.0; M0.1 reads Q0.0 back; the program sets M0.0 every scan and copies what it
/// reads of M0.0 to Q0.1; VW10 counts scans.
const FORCE_PROGRAM: &str = "\
NETWORK 1
LD I0.0
= Q0.0
NETWORK 2
LD Q0.0
= M0.1
NETWORK 3
LD SM0.0
= M0.0
NETWORK 4
LD M0.0
= Q0.1
NETWORK 5
LD SM0.0
INCW VW10
";

fn bit(plc: &Plc, name: &str) -> bool {
    match plc.read(name).expect("readable") {
        Value::Bool(b) => b,
        v => panic!("{name} is not a bit: {v:?}"),
    }
}

#[test]
fn values_follow_the_types_of_their_names() {
    for e in ENGINES {
        let mut p = plc(FORCE_PROGRAM, e);
        let vw = p.handle("VW20").unwrap();
        assert_eq!(vw.ty(), Type::Int16);
        p.set(&vw, -2).unwrap();
        assert_eq!(p.get(&vw).unwrap(), Value::Int(-2));
        assert_eq!(p.read("VW20:u").unwrap(), Value::Int(65534));
        p.set(&vw, 65535).unwrap();
        assert_eq!(p.get(&vw).unwrap(), Value::Int(-1));
        let real = p.handle("VD100:real").unwrap();
        assert_eq!(real.ty(), Type::Real);
        p.set(&real, 2.5).unwrap();
        assert_eq!(p.get(&real).unwrap(), Value::Real(2.5));
        assert_eq!(
            p.read("VD100:u").unwrap(),
            Value::Int(i64::from(2.5f32.to_bits()))
        );
        assert_eq!(p.handle("VB3").unwrap().ty(), Type::Byte);
        assert_eq!(p.handle("T37:i").unwrap().ty(), Type::Int16);
        assert_eq!(p.handle("T37").unwrap().ty(), Type::Bool);
        // Out of range, wrong kind, unknown, read-only: errors that name the address.
        let err = p.set(&vw, 70000).unwrap_err().to_string();
        assert!(err.contains("VW20") && err.contains("70000"), "{err}");
        assert!(matches!(p.set(&vw, 1.5), Err(Error::Value { .. })));
        assert!(matches!(p.write("Q0.0", 2), Err(Error::Value { .. })));
        assert!(matches!(p.handle("VW99999"), Err(Error::Address { .. })));
        assert!(matches!(p.handle("XYZ"), Err(Error::Address { .. })));
        assert!(matches!(p.handle("VW0:float"), Err(Error::Address { .. })));
        assert!(matches!(
            p.write("SM0.1", 1),
            Err(Error::NotWritable { .. })
        ));
    }
}

#[test]
fn inputs_reach_the_program_at_the_next_scan_and_time_is_virtual() {
    for e in ENGINES {
        let mut p = plc(FORCE_PROGRAM, e);
        assert_eq!((p.scan_no(), p.time_ms()), (0, 0));
        p.write("I0.0", true).unwrap();
        assert!(!bit(&p, "I0.0"), "the I image changes at the input refresh");
        let r = p.scan().unwrap();
        assert_eq!((r.scans, r.outcome), (1, Outcome::Completed));
        assert!(bit(&p, "I0.0") && bit(&p, "Q0.0") && bit(&p, "M0.1"));
        p.run(Until::Scans(9)).unwrap();
        assert_eq!(p.read("VW10").unwrap(), Value::Int(10));
        p.run_for(1000).unwrap();
        assert_eq!((p.scan_no(), p.time_ms()), (110, 1100));
        // run_until: every scan starting before 1125 ms (1100, 1110, 1120).
        assert_eq!(p.run_until(1125).unwrap().scans, 3);
        assert_eq!(p.run_until(1125).unwrap().scans, 0);
        assert_eq!(p.time_ms(), 1130);
        p.reset();
        assert_eq!((p.scan_no(), p.read("VW10").unwrap()), (0, Value::Int(0)));
    }
}

#[test]
fn forcing_acts_before_the_program_reads_and_after_it_writes() {
    let mut images = Vec::new();
    for e in ENGINES {
        let mut p = plc(FORCE_PROGRAM, e);
        let (i0, q0, m0) = (
            p.handle("I0.0").unwrap(),
            p.handle("Q0.0").unwrap(),
            p.handle("M0.0").unwrap(),
        );
        // A forced input: the program sees the forced value although the outside writes 0.
        p.set(&i0, false).unwrap();
        p.force(&i0, true).unwrap();
        p.scan().unwrap();
        assert!(bit(&p, "Q0.0") && bit(&p, "M0.1"));
        assert_eq!(p.forced(), vec![("I0.0".to_string(), Value::Bool(true))]);
        // Unforced, the outside value (0) comes back at the next input refresh.
        assert!(p.unforce(&i0));
        assert!(!p.unforce(&i0));
        p.scan().unwrap();
        assert!(!bit(&p, "I0.0") && !bit(&p, "Q0.0"));

        // A forced output: the program's write is seen inside the scan (M0.1 reads Q0.0 back),
        // the forced value wins after it, in the image and at the physical outputs.
        p.set(&i0, true).unwrap();
        p.force(&q0, false).unwrap();
        p.scan().unwrap();
        assert!(bit(&p, "M0.1"), "the program reads its own write of Q0.0");
        assert!(!bit(&p, "Q0.0"));
        assert_eq!(
            p.image().phys_out()[0] & 1,
            0,
            "forced output at the terminals"
        );
        assert_eq!(p.image().phys_out()[0] & 2, 2, "Q0.1 is not forced");
        // Writing a forced address does not move it.
        p.set(&q0, true).unwrap();
        assert!(!bit(&p, "Q0.0"));

        // Forced memory: the program starts from the forced 0, writes 1 and copies it to Q0.1;
        // after the scan M0.0 is 0 again.
        p.force(&m0, false).unwrap();
        p.scan().unwrap();
        assert!(!bit(&p, "M0.0") && bit(&p, "Q0.1"));
        assert!(matches!(p.force(&m0, 3), Err(Error::Value { .. })));
        assert!(matches!(
            p.force(&p.handle("SMB0").unwrap(), 0),
            Err(Error::NotWritable { .. })
        ));
        p.unforce_all();
        p.scan().unwrap();
        assert!(bit(&p, "M0.0") && bit(&p, "Q0.0"));
        images.push(p.image().clone());
    }
    assert_eq!(images[0], images[1], "forcing is the same on both engines");
}

/// A program with timers, a counter and edges: everything a snapshot must carry.
const STATEFUL: &str = "\
NETWORK 1
LD I0.0
TON T37, 20
NETWORK 2
LD I0.1
EU
LD I0.2
CTU C1, 3
NETWORK 3
LD T37
A C1
= Q0.0
NETWORK 4
LD SM0.5
EU
INCW VW0
";

fn drive(p: &mut Plc, k: u64) {
    p.write("I0.0", k % 7 < 5).unwrap();
    p.write("I0.1", k.is_multiple_of(3)).unwrap();
    p.write("I0.2", k % 97 == 50).unwrap();
}

#[test]
fn a_restored_snapshot_continues_identically_on_a_fresh_plc_of_either_engine() {
    let mut a = plc(STATEFUL, EngineKind::Jit);
    for k in 0..137 {
        drive(&mut a, k);
        a.scan().unwrap();
    }
    a.force(&a.handle("I0.2").unwrap(), false).unwrap();
    let snap = a.snapshot();
    let bytes = snap.to_bytes();
    let copy = Snapshot::from_bytes(&bytes).unwrap();
    assert_eq!(copy, snap);
    for engine in ENGINES {
        let mut a2 = plc(STATEFUL, EngineKind::Jit);
        a2.restore(&snap).unwrap();
        let mut b = plc(STATEFUL, engine);
        b.restore(&copy).unwrap();
        assert_eq!(b.scan_no(), 137);
        assert_eq!(b.time_ms(), 1370);
        assert_eq!(b.forced().len(), 1);
        for k in 137..400 {
            drive(&mut a2, k);
            drive(&mut b, k);
            a2.scan().unwrap();
            b.scan().unwrap();
            assert_eq!(a2.image(), b.image(), "scan {k} on {engine:?}");
        }
        assert!(b.read("C1").is_ok());
    }
    // Branching: the original goes on differently and is not affected by the copies.
    a.scan().unwrap();
    assert_eq!(a.scan_no(), 138);
}

#[test]
fn snapshots_are_refused_by_other_programs_and_garbage_is_refused() {
    let a = plc(STATEFUL, EngineKind::Jit);
    let mut other = plc(FORCE_PROGRAM, EngineKind::Jit);
    let before = other.image().clone();
    assert!(matches!(
        other.restore(&a.snapshot()),
        Err(Error::Foreign { .. })
    ));
    assert_eq!(other.image(), &before);
    let bytes = a.snapshot().to_bytes();
    for cut in [0, 7, 12, 30, bytes.len() - 1] {
        assert!(Snapshot::from_bytes(&bytes[..cut]).is_err(), "cut at {cut}");
    }
    let mut junk = bytes.clone();
    junk.push(0);
    assert!(Snapshot::from_bytes(&junk).is_err());
    assert!(Snapshot::from_bytes(b"not a snapshot at all").is_err());
}

#[test]
fn the_observer_hook_sees_every_scan_and_run_reports_a_stop() {
    let mut p = plc("NETWORK 1\nLD I0.0\nSTOP\n", EngineKind::Jit);
    let seen = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let log = seen.clone();
    p.set_observer(Some(Box::new(FnObserver(
        move |e: &stljit_api::ScanEvent<'_>| {
            log.lock().unwrap().push((e.scan, e.t_ms));
            Ok(())
        },
    ))));
    p.run(Until::Scans(3)).unwrap();
    p.write("I0.0", 1).unwrap();
    let r = p.run(Until::Scans(5)).unwrap();
    assert_eq!((r.scans, r.outcome), (1, Outcome::Stopped));
    assert!(p.is_stopped());
    assert_eq!(
        *seen.lock().unwrap(),
        vec![(0, 0), (1, 10), (2, 20), (3, 30)]
    );
}

#[test]
fn omron_programs_are_detected_and_read_by_symbol() {
    let project = Project::new()
        .file("../../examples/omron_conveyor/conveyor.omr")
        .unwrap()
        .symbols_file("../../examples/omron_conveyor/symbols.txt")
        .unwrap();
    for engine in ENGINES {
        let options = Options {
            engine,
            ..Options::default()
        };
        let mut p = Plc::compile(&project, &options).unwrap();
        assert_eq!(p.compiled().dialect(), stljit_api::Dialect::Omron);
        assert_eq!(p.handle("Batch_Left").unwrap().ty(), Type::UInt16);
        p.write("Stop_PB", true).unwrap();
        p.write("Start_PB", true).unwrap();
        p.scan().unwrap();
        assert_eq!(p.read("Run_Request").unwrap(), Value::Bool(true));
        assert!(matches!(p.read("100.16"), Err(Error::Address { .. })));
    }
}

#[test]
fn compile_errors_carry_the_rendered_diagnostics() {
    let project = Project::new().text("bad.stl", "NETWORK 1\nLD I0.0\n= Q99.0\n");
    let err = Plc::compile(&project, &Options::default()).unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, Error::Compile { errors: 1, .. }), "{text}");
    assert!(text.contains("bad.stl:3:"), "{text}");
    assert!(text.contains("Q99.0"), "{text}");
    let e = Plc::compile(&Project::new(), &Options::default()).unwrap_err();
    assert!(matches!(e, Error::NoSources));
    let e = Plc::compile(
        &Project::new().text("x.stl", "LD I0.0\n").cpu("cp1h"),
        &Options::default(),
    )
    .unwrap_err();
    // cp1h is an Omron profile: an S7 text names the S7 profiles (whatever they are) and not it.
    let text = e.to_string();
    assert!(
        text.starts_with("unknown cpu `cp1h` (known: a5, s7-200"),
        "{text}"
    );
    match &e {
        Error::UnknownCpu { known, .. } => {
            assert!(known.iter().all(|k| !k.starts_with("cp1")), "{known:?}")
        }
        other => panic!("{other}"),
    }
    let e = Plc::compile(&Project::new().text("x.stl", "NOP\n"), &Options::default()).unwrap_err();
    assert!(
        e.to_string().contains("cannot tell the dialect of x.stl"),
        "{e}"
    );
    let zero = Options {
        scan_ms: 0,
        ..Options::default()
    };
    let e = Plc::compile(&Project::new().text("x.stl", "LD I0.0\n= Q0.0\n"), &zero);
    assert!(matches!(e, Err(Error::ZeroScanTime)));
}
