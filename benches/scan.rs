//! Scan speed of the JIT against the interpreter on the committed corpus (`benches/programs/`):
//! time per scan of each engine on the same program and the same inputs.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use stljit_core::ProfileId;
use stljit_core::ir::Program;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};
use stljit_runtime::{Engine, Image};

fn program(name: &str) -> Program {
    let path = stljit_harness::repo_root()
        .join("benches/programs")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    let c = stljit_front_s7::compile_str(name, &text, ProfileId::A5);
    c.program
        .unwrap_or_else(|| panic!("{name} does not compile"))
}

fn bench_engine(c: &mut Criterion, name: &str, label: &str, p: &Program, e: &mut dyn Engine) {
    let mut img = Image::cold_start(p);
    let mut t = 0u64;
    c.bench_function(&format!("scan/{name}/{label}"), |b| {
        b.iter(|| {
            t += 10;
            img.set_inputs(&[(t >> 4) as u8, (t >> 6) as u8, (t >> 8) as u8]);
            black_box(e.scan(&mut img, t))
        })
    });
}

fn scan(c: &mut Criterion) {
    for name in [
        "bitlogic_1k.stl",
        "bitlogic_10k.stl",
        "mixed_10k.stl",
        "timed_interrupt.stl",
    ] {
        let p = program(name);
        let mut interp = Interpreter::new(&p).expect("interpreter accepts the corpus");
        bench_engine(c, name, "interp", &p, &mut interp);
        let mut jit =
            JitProgram::compile(&p, &JitOptions::at(OptLevel::Speed)).expect("JIT compiles");
        bench_engine(c, name, "jit", &p, &mut jit);
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = scan
}
criterion_main!(benches);
