//! Fuzz target: the fuzzer's bytes drive the program generator; the generated IR must survive
//! both round trips: IR text (`stljit_core::text`) printed and parsed back gives exactly the same
//! program, and the dialect's printer (S7 STL or Omron mnemonics) compiled again gives the same
//! IR (and the front end must accept it). Bit 0 of the first byte picks the dialect; a
//! generated Omron text its front end rejects is a generator bug.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_core::Family;
use stljit_diff::generate::{GenConfig, generate_in};
use stljit_diff::rng::Choices;
use stljit_diff::roundtrip::roundtrip;

fuzz_target!(|data: &[u8]| {
    let family = match data.first() {
        Some(b) if b & 1 == 1 => Family::Omron,
        _ => Family::S7,
    };
    let mut c = Choices::from_bytes(data.get(1..).unwrap_or_default());
    let generated = match generate_in(family, &mut c, &GenConfig::default()) {
        Ok(g) => g,
        Err(e) => panic!("{e}\n{}", e.source),
    };
    if let Err(e) = roundtrip(&generated.case.program) {
        panic!("{e}");
    }
});
