//! The simulated hardware's stimulus through the API, on both engines: high-speed counter steps
//! (`Plc::set_hsc_steps`, s7-200-more §8.4) and bytes received on a serial port
//! (`Plc::queue_rx`, §10.4), and the errors for a counter or port the CPU does not have.

use stljit_api::{EngineKind, Error, Options, Plc, Project, Until, Value};

mod common;

use common::{ENGINES, plc};

fn int(plc: &Plc, name: &str) -> i64 {
    match plc.read(name).expect("readable") {
        Value::Int(i) => i,
        v => panic!("{name} is not an integer: {v:?}"),
    }
}

/// HSC0 in mode 0 (one clock input, internal direction), PV 25: the first scan writes the
/// control byte 16#F8 (.7 enable, .6 write CV = SMD38 = 0, .5 write PV = SMD42 = 25, .4 write
/// the direction, .3 up; s7-200-more §8.1), defines and applies it; every scan copies HC0 and
/// the status byte SMB36.
const COUNTER: &str = "\
Network 1
LD     SM0.1
MOVB   16#F8, SMB37
MOVD   +0, SMD38
MOVD   +25, SMD42
HDEF   0, 0
HSC    0
Network 2
LD     SM0.0
MOVD   HC0, VD100
MOVB   SMB36, VB104
";

/// §8.4: the steps set before scan k count in the interval (T_{k-1}, T_k], which the scan's
/// event phase runs before the program, and are held until set again; scan 0 has no interval.
/// Mode 0 counts every step in the counter's direction (up) whatever the sign. Status SMB36
/// (§8.1): .5 up, .6 CV = PV, .7 CV > PV.
#[test]
fn counter_steps_are_held_per_interval() {
    for e in ENGINES {
        let mut p = plc(COUNTER, e);
        p.set_hsc_steps(0, 10).unwrap();
        p.scan().unwrap();
        // Scan 0: no interval, CV = 0 < PV: up only.
        assert_eq!((int(&p, "VD100"), int(&p, "VB104")), (0, 0x20), "{e:?}");
        p.run(Until::Scans(2)).unwrap();
        // Scans 1, 2: 10 steps each: 20 < 25.
        assert_eq!((int(&p, "VD100"), int(&p, "VB104")), (20, 0x20), "{e:?}");
        p.scan().unwrap();
        // Scan 3: 30 > 25: up and CV > PV.
        assert_eq!((int(&p, "VD100"), int(&p, "VB104")), (30, 0xA0), "{e:?}");
        // The sign is ignored in mode 0: -5 is 5 steps up, in each of the next 3 scans.
        p.set_hsc_steps(0, -5).unwrap();
        p.run(Until::Scans(3)).unwrap();
        assert_eq!(int(&p, "VD100"), 45, "{e:?}");
        // Held in a snapshot (the activity is state in the image): 0 stops the counter.
        let saved = p.snapshot();
        p.set_hsc_steps(0, 0).unwrap();
        p.run(Until::Scans(4)).unwrap();
        assert_eq!(int(&p, "VD100"), 45, "{e:?}");
        p.restore(&saved).unwrap();
        p.scan().unwrap();
        assert_eq!(int(&p, "VD100"), 50, "{e:?}");
    }
}

/// RCV on port 0 (s7-200-more §12 M14 without the routine): Freeport at 9 600 baud (SMB30 =
/// 16#09), SMB87 = 16#B0 (en, ec, il), end character CR (SMB89), SMW90 = 0 with il and no sc is
/// "any response": the message starts at the RCV in scan 0 (§10.3).
const RECEIVER: &str = "\
Network 1
LD     SM0.1
MOVB   16#09, SMB30
MOVB   16#B0, SMB87
MOVB   16#0D, SMB89
MOVW   +0, SMW90
MOVB   20, SMB94
RCV    VB200, 0
";

/// §10.4: the bytes queued before scan 1 arrive back to back from T_0 = 0, one character time
/// C = 1 042 µs apart (9 600 baud 8N1, §10.1): at 1 042, 2 084 and 3 126 µs, all in the
/// interval before scan 1. Each is stored (count 1, 2, 3); the third is the end character, so
/// the receive ends with SMB86 = 16#20 (e). SMB2 holds the last character. Queued once, they
/// are received once: the count stays 3.
#[test]
fn received_bytes_arrive_before_the_next_scan() {
    for e in ENGINES {
        let mut p = plc(RECEIVER, e);
        p.scan().unwrap();
        assert_eq!(int(&p, "SMB86"), 0, "{e:?}: receiving");
        p.queue_rx(0, b"OK\r").unwrap();
        p.scan().unwrap();
        let buffer: Vec<i64> = (200..204).map(|b| int(&p, &format!("VB{b}"))).collect();
        assert_eq!(buffer, [3, 0x4F, 0x4B, 0x0D], "{e:?}");
        assert_eq!((int(&p, "SMB86"), int(&p, "SMB2")), (0x20, 0x0D), "{e:?}");
        p.run(Until::Scans(3)).unwrap();
        assert_eq!(int(&p, "VB200"), 3, "{e:?}");
    }
}

/// The a5 has HC0 and HC1 only (s7-200-more §8.2) and both ports; an Omron CP1H has neither
/// counters nor S7 ports.
#[test]
fn a_counter_or_port_the_cpu_lacks_is_an_error() {
    let mut p = plc(COUNTER, EngineKind::Interp);
    let e = p.set_hsc_steps(2, 1).unwrap_err();
    assert!(matches!(e, Error::NoCounter { counter: 2, .. }));
    assert_eq!(
        e.to_string(),
        "the A5 has no high-speed counter 2 (it has: HSC0, HSC1)"
    );
    p.set_hsc_steps(1, 1).unwrap();
    p.queue_rx(1, b"x").unwrap();
    let e = p.queue_rx(2, b"x").unwrap_err();
    assert_eq!(
        e.to_string(),
        "the A5 has no serial port 2 (it has: PORT0, PORT1)"
    );
    let project = Project::new().text("t.omr", "LD P_On\nOUT 100.00\nEND\n");
    let mut omron = Plc::compile(&project, &Options::default()).expect("compiles");
    let e = omron.queue_rx(0, b"x").unwrap_err();
    assert!(matches!(e, Error::NoPort { port: 0, .. }));
    assert_eq!(
        e.to_string(),
        "the CP1H has no serial port 0 (it has: none)"
    );
    assert!(matches!(
        omron.set_hsc_steps(0, 1),
        Err(Error::NoCounter { .. })
    ));
}
