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

fn main() {
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("usage: image_digest FIRST_SEED COUNT"))
        .collect();
    let (first, count) = match args[..] {
        [f, c] => (f, c),
        _ => (0, 1000),
    };
    let cfg = GenConfig::default();
    let opts = RunOptions::default();
    for seed in first..first + count {
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
}
