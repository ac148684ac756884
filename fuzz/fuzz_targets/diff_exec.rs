//! Fuzz target: the fuzzer's bytes drive the program and stimulus generator; the interpreter and
//! the JIT must agree on status and the whole image after every scan. The first byte picks the
//! JIT's optimisation level (bit 0), whether it is split into one function per basic block
//! (bit 1) and the dialect (bit 2: S7 or Omron; a generated Omron text its front end rejects is
//! a generator bug).
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_core::Family;
use stljit_diff::campaign::check_case;
use stljit_diff::engines::EngineKind;
use stljit_diff::generate::{GenConfig, generate_in};
use stljit_diff::oracle::RunOptions;
use stljit_diff::rng::Choices;
use stljit_jit::OptLevel;

fuzz_target!(|data: &[u8]| {
    let flags = data.first().copied().unwrap_or(0);
    let opt = if flags & 1 == 1 {
        OptLevel::Speed
    } else {
        OptLevel::None
    };
    let jit = if flags & 2 == 2 {
        EngineKind::JitSplit(opt)
    } else {
        EngineKind::Jit(opt)
    };
    let family = if flags & 4 == 4 {
        Family::Omron
    } else {
        Family::S7
    };
    let mut c = Choices::from_bytes(data.get(1..).unwrap_or_default());
    let case = match generate_in(family, &mut c, &GenConfig::default()) {
        Ok(g) => g.case,
        Err(e) => panic!("{e}\n{}", e.source),
    };
    let engines = [EngineKind::Interp, jit];
    if let Err(f) = check_case(&case, engines, &RunOptions::default(), false) {
        panic!("{f}");
    }
});
