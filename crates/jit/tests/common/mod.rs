//! Shared helpers of the JIT's tests: compile with both engines and compare every scan.

use stljit_core::ProfileId;
use stljit_core::ir::Program;
use stljit_diff::generate::{Case, Stimulus};
use stljit_diff::oracle::{Finding, RunOptions, run_pair};
use stljit_diff::rng::Choices;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};

/// Compiles STL text for the A5 profile, panicking with the diagnostics on failure.
pub(crate) fn stl(text: &str) -> Program {
    let c = stljit_front_s7::compile_str("test.stl", text, ProfileId::A5);
    match c.program {
        Some(p) => p,
        None => panic!("program does not compile: {:#?}", c.diagnostics),
    }
}

/// A random stimulus of `scans` scans from `seed`.
pub(crate) fn stimulus(seed: u64, scans: u32) -> Stimulus {
    let bytes: Vec<u8> = (0..4096u64)
        .map(|i| {
            (seed
                .wrapping_mul(0x9E37_79B9_7F4A_7C15)
                .wrapping_add(i * 0x1234_5678_9ABC)
                >> 17) as u8
        })
        .collect();
    let mut c = Choices::from_bytes(&bytes);
    stljit_diff::generate::stimulus::generate(&mut c, ProfileId::A5, scans)
}

/// Runs `program` on the interpreter and the JIT (both opt levels) and asserts equal images
/// after every scan.
pub(crate) fn check(program: &Program, stim: &Stimulus) {
    check_with(program, stim, RunOptions::default());
}

/// [`check`] with explicit run options (loop limit).
pub(crate) fn check_with(program: &Program, stim: &Stimulus, opts: RunOptions) {
    for jo in jit_options() {
        let mut interp = Interpreter::new(program).expect("interpreter accepts the program");
        let mut jit = JitProgram::compile(program, &jo).expect("JIT compiles");
        if let Err(f) = run_pair(program, stim, &mut interp, &mut jit, &opts) {
            report(program, f, jo);
        }
    }
}

/// Every JIT configuration checked: both optimisation levels, and each basic block in a chunk
/// function of its own with 32-bit bit tests wherever valid (the test programs are shorter
/// than the default chunk size and store too often for the default wide-load heuristic).
fn jit_options() -> [JitOptions; 3] {
    [
        JitOptions::at(OptLevel::None),
        JitOptions::at(OptLevel::Speed),
        JitOptions {
            opt: OptLevel::None,
            chunk_ops: 1,
            hot_ops: 0,
        },
    ]
}

fn report(program: &Program, f: Finding, jo: JitOptions) -> ! {
    let text = stljit_front_s7::print_program(program);
    panic!("JIT ({jo:?}) differs from the interpreter: {f:#?}\nprogram:\n{text}");
}

/// Runs a generated case; `false` when the JIT does not support the program.
pub(crate) fn check_case(case: &Case) -> bool {
    let opts = RunOptions::default();
    for jo in jit_options() {
        let mut interp = Interpreter::new(&case.program).expect("interpreter accepts the program");
        let mut jit = match JitProgram::compile(&case.program, &jo) {
            Ok(j) => j,
            Err(stljit_jit::JitError::Unsupported(_)) => return false,
            Err(e) => panic!("JIT failed: {e}"),
        };
        if let Err(f) = run_pair(&case.program, &case.stimulus, &mut interp, &mut jit, &opts) {
            report(&case.program, f, jo);
        }
    }
    true
}
