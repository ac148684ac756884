//! Prints one digest per generated case: the images after every scan on the interpreter,
//! hashed. Run it on two commits and compare the outputs to check that a change to the shared
//! runtime (scan phases, event phases, shims used by both engines) left every image as it was:
//! the differential fuzzer compares the two engines, which share the runtime, so it cannot see
//! such a change.
//!
//! ```sh
//! cargo run --release -p stljit-diff --example image_digest -- FIRST_SEED COUNT > digests.txt
//! ```

use std::hash::{DefaultHasher, Hash, Hasher};
use stljit_diff::generate::{GenConfig, case_from_seed};
use stljit_diff::oracle::{RunOptions, apply_stimulus, start_image};
use stljit_interp::Interpreter;
use stljit_runtime::Engine;

fn main() -> std::process::ExitCode {
    let args: Result<Vec<u64>, _> = std::env::args().skip(1).map(|a| a.parse()).collect();
    let (first, count) = match args.as_deref() {
        Ok([f, c]) => (*f, *c),
        Ok([]) => (0, 1000),
        _ => {
            eprintln!("usage: image_digest [FIRST_SEED COUNT] (default: 0 1000)");
            return std::process::ExitCode::from(2);
        }
    };
    let cfg = GenConfig::default();
    let opts = RunOptions::default();
    for seed in first..first.saturating_add(count) {
        let case = case_from_seed(seed, &cfg);
        let Ok(mut engine) = Interpreter::new(&case.program) else {
            println!("{seed} rejected");
            continue;
        };
        let mut img = start_image(&case.program, &opts);
        let mut h = DefaultHasher::new();
        for s in &case.stimulus.scans {
            apply_stimulus(&mut img, s);
            let status = engine.scan(&mut img, s.t_ms);
            (status as u8).hash(&mut h);
            img.bytes().hash(&mut h);
        }
        println!("{seed} {:016x}", h.finish());
    }
    std::process::ExitCode::SUCCESS
}
