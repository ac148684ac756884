//! JIT compile time on the corpus at both optimisation levels (targets: 10k instructions under
//! 100 ms and 100k under 1 s with `--opt none`; see docs/performance.md).

use criterion::{Criterion, criterion_group, criterion_main};
use stljit_core::ProfileId;
use stljit_jit::{JitOptions, JitProgram, OptLevel};

fn compile(c: &mut Criterion) {
    for name in ["bitlogic_10k.stl", "mixed_10k.stl", "mixed_100k.stl"] {
        let path = stljit_harness::repo_root()
            .join("benches/programs")
            .join(name);
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        let p = stljit_front_s7::compile_str(name, &text, ProfileId::A5)
            .program
            .unwrap_or_else(|| panic!("{name} does not compile"));
        // 100k at `speed` takes about a second per compile; `stljit bench` reports it.
        let levels: &[OptLevel] = if name.contains("100k") {
            &[OptLevel::None]
        } else {
            &[OptLevel::None, OptLevel::Speed]
        };
        for &opt in levels {
            c.bench_function(&format!("compile/{name}/{}", opt.name()), |b| {
                b.iter(|| JitProgram::compile(&p, &JitOptions::at(opt)).expect("compiles"))
            });
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = compile
}
criterion_main!(benches);
