//! Fuzz target: arbitrary bytes as a stimulus CSV (`--inputs`) must never panic the parser, an
//! error must name a line inside the text, and an accepted stimulus must drive a short run on
//! the interpreter without a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_core::ProfileId;
use stljit_core::ir::Address;
use stljit_runtime::Image;
use stljit_sim::{FnObserver, ScanEvent, Simulation, Stimulus, Until};

const PROGRAM: &str = "LD I0.0\nTON T37, 10\nLD T37\n= Q0.0\nLD I0.1\nMOVW AIW0, VW0\n";

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let c = stljit_front_s7::compile_str("p.stl", PROGRAM, ProfileId::A5);
    let program = c.program.expect("the fixed program compiles");
    let profile = program.profile.profile();
    let resolve = |name: &str| -> Result<Address, String> {
        stljit_front_s7::parse_address(name, profile, None).map_err(|e| e.message)
    };
    match Stimulus::parse(&text, profile, &resolve) {
        Err(e) => {
            let lines = text.lines().count().max(1) as u32;
            assert!((1..=lines).contains(&e.line) && e.col >= 1, "{e}");
        }
        Ok(stimulus) => {
            let mut engine = stljit_interp::Interpreter::new(&program).expect("interpreter");
            let mut sim = Simulation::new(&mut engine, Image::cold_start(&program), 10)
                .expect("non-zero scan time");
            let mut observer = FnObserver(|_: &ScanEvent<'_>| Ok(()));
            sim.run(Until::Scans(20), &stimulus, &mut observer)
                .expect("an accepted stimulus runs");
        }
    }
});
