//! Fuzz target: the fuzzer's bytes drive the program generator; the generated IR must survive
//! both round trips: IR text (`stljit_core::text`) printed and parsed back gives exactly the same
//! program, and the S7 printer's STL compiled again gives the same IR (and the front end must
//! accept it).
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_diff::generate::{GenConfig, generate_program};
use stljit_diff::rng::Choices;
use stljit_diff::roundtrip::roundtrip;

fuzz_target!(|data: &[u8]| {
    let program = generate_program(&mut Choices::from_bytes(data), &GenConfig::default());
    if let Err(e) = roundtrip(&program) {
        panic!("{e}");
    }
});
