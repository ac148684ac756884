//! Hostile stimulus files: no text makes the stimulus parser or a run driven by it panic, and
//! every rejection names a place inside the text.
//!
//! The cases are the traffic-light example's `stimulus.csv` and its symbol table, mutated by a
//! fixed-seed generator (byte flips, cuts, splices, duplicated lines), plus a few hand-made
//! extremes. An accepted stimulus is run for a few scans on every engine, which must agree.

use crate::conformance::harness::ENGINES;
use std::path::PathBuf;
use stljit_core::ir::{Address, Program};
use stljit_front_s7::{SourceFile, SymbolTable};
use stljit_runtime::Image;
use stljit_sim::{FnObserver, ScanEvent, Simulation, Stimulus, Until};

fn example(name: &str) -> PathBuf {
    stljit_harness::repo_root()
        .join("examples/traffic_light")
        .join(name)
}

fn traffic_light() -> (Program, Option<SymbolTable>) {
    let read = |name: &str| SourceFile {
        name: name.into(),
        bytes: std::fs::read(example(name)).expect("example is checked in"),
    };
    let c = stljit_front_s7::compile(
        &[read("traffic_light.awl")],
        Some(&read("symbols.txt")),
        stljit_core::ProfileId::A5,
    );
    (c.program.expect("example compiles"), c.symbols)
}

/// Parses `text`; checks an error's place; runs an accepted stimulus on every engine.
fn exercise(text: &str, program: &Program, symbols: Option<&SymbolTable>) -> bool {
    let profile = program.profile.profile();
    let resolve = |name: &str| -> Result<Address, String> {
        stljit_front_s7::parse_address(name, profile, symbols).map_err(|e| e.message)
    };
    let stimulus = match Stimulus::parse(text, profile, &resolve) {
        Ok(s) => s,
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

#[test]
fn no_stimulus_text_makes_the_tools_panic() {
    let (program, symbols) = traffic_light();
    let base = std::fs::read_to_string(example("stimulus.csv")).expect("example stimulus");
    assert!(
        exercise(&base, &program, symbols.as_ref()),
        "the example itself is accepted"
    );
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
        exercise(text, &program, symbols.as_ref());
    }
    let bytes = base.as_bytes();
    let mut next = crate::mutate::xorshift(0x2545_F491_4F6C_DD1D_u64);
    let (mut accepted, mut rejected) = (0, 0);
    for _ in 0..1000 {
        let mut m = bytes.to_vec();
        // One or two edits: more and nearly every file is rejected at its first bad row.
        for _ in 0..=(next() % 2) {
            let at = (next() as usize) % m.len().max(1);
            match next() % 4 {
                0 => {
                    if let Some(b) = m.get_mut(at) {
                        *b = b"0123456789,.-#\n\r VIQMT+e"[(next() % 24) as usize];
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
        if exercise(&text, &program, symbols.as_ref()) {
            accepted += 1;
        } else {
            rejected += 1;
        }
    }
    // Both paths must be exercised, or the mutations are too weak (or too strong) to test much.
    assert!(
        accepted > 30 && rejected > 30,
        "{accepted} accepted, {rejected} rejected"
    );
}
