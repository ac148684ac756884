//! Front-end throughput: `stljit_front_s7::compile` on a generated 100,000-line program mixing every
//! instruction group (bit logic, stack, timers, counters, compares, moves, arithmetic, word logic,
//! shifts, conversions, program control, SCR), reported in lines per second.
//!
//! The program is also written to the system temp dir (`stljit-parse-100k.stl`) so that
//! `time stljit check` can be measured on exactly the same input.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::fmt::Write as _;
use stljit_core::ProfileId;
use stljit_front_s7::{SourceFile, compile};

/// One network per group; `i` varies the addresses so that lines are not all identical.
fn network(out: &mut String, i: usize) {
    let v = (i * 4) % 2000;
    let b = i % 16;
    let t = 20 + i % 40;
    let c = i % 32;
    let _ = write!(
        out,
        "Network {i}\n\
         LD     I{b}.0\nAN     M{m}.1\nLD     Q{b}.2\nO      V{v}.3\nALD\n=      Q{b}.4\n\
         LDW>=  VW{v}, +100\nAD<    VD{v}, 16#7FFF\nTON    T{t}, 50\n\
         LD     I0.1\nLD     I0.2\nCTU    C{c}, 10\n\
         LD     SM0.0\nLPS\nMOVW   VW{v}, VW{v2}\nLRD\n+I     1, VW{v}\nLPP\n*D     AC0, VD{v}\n\
         ANDW   16#00FF, VW{v}\nSLW    VW{v}, 2\nBTI    VB{v}, VW{v2}\nMOVR   1.5, VD{v}\n\
         +R     VD{v}, VD{v2}\nS      Q{b}.0, 3\nR      M{m}.0, 2\nLDS    1\nNOT\n",
        m = i % 32,
        v2 = v + 100,
    );
}

/// A program of about `lines` lines, in the linear layout, that checks clean on the A5.
fn program(lines: usize) -> String {
    let mut out = String::with_capacity(lines * 16);
    let mut i = 0;
    while out.bytes().filter(|&c| c == b'\n').count() < lines.saturating_sub(40) {
        network(&mut out, i);
        if i < 200 {
            // Labels, edges, FOR and SCR are limited per program; use them in the first networks.
            let _ = write!(
                out,
                "LD     I0.0\nEU\nJMP    {i}\nFOR    VW2400, 1, 3\nINCW   VW2402\nNEXT\nLBL    {i}\n"
            );
        }
        i += 1;
    }
    out.push_str("LSCR   S0.0\nLD     SM0.0\n=      Q0.0\nSCRT   S0.1\nSCRE\nMEND\nSBR    0\nLD     SM0.0\nCRET\nRET\n");
    out
}

fn bench(c: &mut Criterion) {
    let text = program(100_000);
    let lines = text.lines().count();
    let path = std::env::temp_dir().join("stljit-parse-100k.stl");
    let _ = std::fs::write(&path, &text);
    let files = [SourceFile {
        name: "generated.stl".into(),
        bytes: text.into_bytes(),
    }];
    let first = compile(&files, None, ProfileId::A5);
    assert!(
        first.program.is_some(),
        "generated program must check clean: {:?}",
        first.diagnostics.first()
    );
    eprintln!("parse bench: {lines} lines, written to {}", path.display());
    let mut g = c.benchmark_group("parse");
    g.throughput(Throughput::Elements(lines as u64));
    g.sample_size(20);
    g.bench_function("compile_100k_lines", |b| {
        b.iter(|| compile(std::hint::black_box(&files), None, ProfileId::A5))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
