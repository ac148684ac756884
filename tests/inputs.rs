//! Hostile stimulus files: no text makes the stimulus parser or a run driven by it panic, and
//! every rejection names a place inside the text.
//!
//! The cases are the examples' `stimulus.csv` files with their symbol tables (the S7 traffic
//! light and the Omron conveyor, whose addresses are Omron's: `0.00`, `W3`, `D10`, `#hex`
//! values), and a stimulus of the S7 hardware columns (`HSCn`, `PORTn`), mutated by a fixed-seed
//! generator (byte flips, cuts, splices, duplicated lines), plus a few hand-made extremes. An
//! accepted stimulus is run for a few scans on every engine, which must agree.

use crate::conformance::harness::ENGINES;
use std::path::PathBuf;
use stljit_core::ir::{Address, Program};
use stljit_front::{Dialect, SourceFile, Symbols};
use stljit_runtime::Image;
use stljit_sim::{FnObserver, ScanEvent, Simulation, Stimulus, Until};

/// An example program with its dialect and symbols, which stimulus files are read against.
struct Subject {
    dir: PathBuf,
    dialect: Dialect,
    program: Program,
    symbols: Option<Symbols>,
}

fn subject(dir: &str, file: &str, dialect: Dialect) -> Subject {
    let dir = stljit_harness::repo_root().join("examples").join(dir);
    let read = |name: &str| SourceFile {
        name: name.into(),
        bytes: std::fs::read(dir.join(name)).expect("example is checked in"),
    };
    let c = dialect.compile(
        &[read(file)],
        Some(&read("symbols.txt")),
        dialect.default_profile(),
    );
    Subject {
        program: c.program.expect("example compiles"),
        symbols: c.symbols,
        dialect,
        dir,
    }
}

/// Parses `text`; checks an error's place; runs an accepted stimulus on every engine.
fn exercise(text: &str, s: &Subject) -> bool {
    let program = &s.program;
    let profile = program.profile.profile();
    let resolve = |name: &str| -> Result<Address, String> {
        s.dialect
            .parse_address(name, program.profile, s.symbols.as_ref())
            .map_err(|e| e.message)
    };
    let stimulus = match Stimulus::parse(text, profile, &resolve) {
        Ok(st) => st,
        Err(e) => {
            let lines = text.lines().count().max(1) as u32;
            assert!(
                (1..=lines).contains(&e.line) && e.col >= 1,
                "error {e} is outside the text ({lines} lines):\n{text}"
            );
            assert!(!e.to_string().is_empty());
            return false;
        }
    };
    let mut images = Vec::new();
    for (name, build) in ENGINES {
        let mut engine = build(program).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut sim = Simulation::new(engine.as_mut(), Image::cold_start(program), 10)
            .expect("non-zero scan time");
        let mut observer = FnObserver(|_: &ScanEvent<'_>| Ok(()));
        sim.run(Until::Scans(30), &stimulus, &mut observer)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        images.push((name, sim.into_image()));
    }
    for (name, img) in &images[1..] {
        assert!(
            img.bytes() == images[0].1.bytes(),
            "{name} differs from {} after a mutated stimulus:\n{text}",
            images[0].0
        );
    }
    true
}

/// 1,000 mutations of `base` (one or two edits each, from `alphabet` and pieces of the file):
/// every one is exercised; returns how many were accepted and rejected.
fn mutations(base: &str, s: &Subject, seed: u64, alphabet: &[u8]) -> (u32, u32) {
    let bytes = base.as_bytes();
    let mut next = crate::mutate::xorshift(seed);
    let (mut accepted, mut rejected) = (0, 0);
    for _ in 0..1000 {
        let mut m = bytes.to_vec();
        // One or two edits: more and nearly every file is rejected at its first bad row.
        for _ in 0..=(next() % 2) {
            let at = (next() as usize) % m.len().max(1);
            match next() % 4 {
                0 => {
                    if let Some(b) = m.get_mut(at) {
                        *b = alphabet[(next() % alphabet.len() as u64) as usize];
                    }
                }
                1 => m.truncate(at),
                2 => {
                    let from = (next() as usize) % bytes.len();
                    let len = (next() as usize) % 40;
                    let piece = bytes[from..(from + len).min(bytes.len())].to_vec();
                    let at = at.min(m.len());
                    m.splice(at..at, piece);
                }
                _ => {
                    if let Some(b) = m.get_mut(at) {
                        *b = next() as u8;
                    }
                }
            }
        }
        let text = String::from_utf8_lossy(&m);
        if exercise(&text, s) {
            accepted += 1;
        } else {
            rejected += 1;
        }
    }
    (accepted, rejected)
}

#[test]
fn no_stimulus_text_makes_the_tools_panic() {
    let s = subject("traffic_light", "traffic_light.awl", Dialect::S7);
    let base = std::fs::read_to_string(s.dir.join("stimulus.csv")).expect("example stimulus");
    assert!(exercise(&base, &s), "the example itself is accepted");
    let extremes = [
        String::new(),
        "\n\n# only a comment\n".to_string(),
        "scan".to_string(),
        "t_ms,I0.0\n18446744073709551615,1\n".to_string(),
        "scan,I0.0\n-1,1\n".to_string(),
        "scan,VD0\n0,1e40\n1,nan\n2,16#FFFFFFFFF\n".to_string(),
        "scan,I0.0,I0.0\n0,1,0\n".to_string(),
        format!("scan,{}\n0,1\n", "V".repeat(100_000)),
        "scan,I0.0\n5,1\n3,0\n".to_string(),
        "scan,\u{1F600}\n0,\u{0}\n".to_string(),
    ];
    for text in &extremes {
        exercise(text, &s);
    }
    let (accepted, rejected) = mutations(
        &base,
        &s,
        0x2545_F491_4F6C_DD1D,
        b"0123456789,.-#\n\r VIQMT+e",
    );
    // Both paths must be exercised, or the mutations are too weak (or too strong) to test much.
    assert!(
        accepted > 30 && rejected > 30,
        "{accepted} accepted, {rejected} rejected"
    );
}

/// The reserved columns of the simulated hardware (`HSCn` steps, `PORTn` bytes), on the traffic
/// light (an a5 program: HSC0, HSC1, ports 0 and 1; it defines no counter, so even a mutated
/// huge step count costs nothing, and nothing drains the ports' 256-byte FIFOs).
#[test]
fn no_hardware_column_makes_the_tools_panic() {
    let s = subject("traffic_light", "traffic_light.awl", Dialect::S7);
    let base = "t_ms,Ped_Button,HSC0,hsc1,PORT0,Port1\n0,0,5,-3,16#4F4B0D,\n2000,1,10,,,16#00FF\n\
                3000,0,0,16#FFFFFFFF,16#41,\n";
    assert!(exercise(base, &s), "the base is accepted");
    let extremes = [
        "scan,HSC0\n0,16#\n".to_string(),
        "scan,HSC0\n0,2147483648\n".to_string(),
        "scan,HSC0\n0,1.5\n".to_string(),
        "scan,HSC2\n0,1\n".to_string(),
        "scan,HSC99999999999999999999\n0,1\n".to_string(),
        "scan,PORT0\n0,16#4\n".to_string(),
        "scan,PORT0\n0,16#\n".to_string(),
        "scan,PORT0\n0,4F4B\n".to_string(),
        "scan,PORT2\n0,16#00\n".to_string(),
        "scan,PORT0,port0\n0,16#00,16#01\n".to_string(),
        format!("scan,PORT0\n0,16#{}\n1,16#00\n", "AB".repeat(5000)),
        "scan,HSC0\n0,-2147483648\n1,2147483647\n".to_string(),
    ];
    for text in &extremes {
        exercise(text, &s);
    }
    let (accepted, rejected) = mutations(
        base,
        &s,
        0x1B87_F491_4F6C_DD1D,
        b"0123456789ABCDEF#,-\n HSCPORT",
    );
    assert!(
        accepted > 30 && rejected > 30,
        "{accepted} accepted, {rejected} rejected"
    );
}

#[test]
fn no_omron_stimulus_text_makes_the_tools_panic() {
    let s = subject("omron_conveyor", "conveyor.omr", Dialect::Omron);
    let base = std::fs::read_to_string(s.dir.join("stimulus.csv")).expect("example stimulus");
    assert!(exercise(&base, &s), "the example itself is accepted");
    let extremes = [
        "scan,0.00,1,W3,D10,H0.15\n0,1,#FFFF,65535,#12A4,1\n1,0,0,,&5,0\n".to_string(),
        "scan,0\n0,65536\n".to_string(),
        "scan,D32768\n0,1\n".to_string(),
        "scan,P_EQ\n0,1\n".to_string(),
        "scan,T0000\n0,1\n".to_string(),
        "scan,TR0\n0,1\n".to_string(),
        "scan,A0\n0,1\n".to_string(),
        "scan,CIO 0.00,0.00\n0,1,0\n".to_string(),
        "t_ms,0.16\n0,1\n".to_string(),
        "scan,W3\n0,#\n1,#1FFFF\n2,-1\n".to_string(),
    ];
    for text in &extremes {
        exercise(text, &s);
    }
    let (accepted, rejected) = mutations(
        &base,
        &s,
        0x0E1D_F491_4F6C_DD1D,
        b"0123456789012345,,#&\n W.",
    );
    assert!(
        accepted > 30 && rejected > 30,
        "{accepted} accepted, {rejected} rejected"
    );
}
