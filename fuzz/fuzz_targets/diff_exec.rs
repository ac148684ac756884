//! Fuzz target: the fuzzer's bytes drive the program and stimulus generator; the interpreter and
//! the JIT must agree on status and the whole image after every scan (the first byte picks the
//! JIT's optimisation level and whether it is split into one function per basic block).
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_diff::campaign::check_case;
use stljit_diff::engines::EngineKind;
use stljit_diff::generate::{GenConfig, case_from_bytes};
use stljit_diff::oracle::RunOptions;
use stljit_jit::OptLevel;

fuzz_target!(|data: &[u8]| {
    let opt = match data.first() {
        Some(b) if b & 1 == 1 => OptLevel::Speed,
        _ => OptLevel::None,
    };
    let case = case_from_bytes(data.get(1..).unwrap_or_default(), &GenConfig::default());
    let jit = match data.first() {
        Some(b) if b & 2 == 2 => EngineKind::JitSplit(opt),
        _ => EngineKind::Jit(opt),
    };
    let engines = [EngineKind::Interp, jit];
    if let Err(f) = check_case(&case, engines, &RunOptions::default(), false) {
        panic!("{f}");
    }
});
