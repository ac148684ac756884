//! Omron program text as an input: the Omron printer round-trips every Omron program the
//! repository holds (the conformance cases, the spec programs, the diagnostics fixtures that
//! compile, the example and the benchmark program): printed and compiled again it gives the
//! same IR, and its IR text parses back exactly. Mutated Omron texts (lines dropped, repeated,
//! swapped or garbled, bytes flipped) never panic the front end, and every one it accepts
//! prints, compiles back to the same IR and runs alike on the interpreter and the JIT.

use crate::ir_text::{files_in, source};
use std::path::PathBuf;
use stljit_core::ProfileId;
use stljit_core::ir::Program;
use stljit_diff::campaign::check_case;
use stljit_diff::engines::EngineKind;
use stljit_diff::generate::{Case, stimulus};
use stljit_diff::oracle::RunOptions;
use stljit_diff::rng::Choices;
use stljit_diff::roundtrip::roundtrip;
use stljit_front::{Dialect, Options, SourceFile};
use stljit_jit::OptLevel;

/// One Omron program text of the repository: its name, the text, its symbol table, profile
/// and front-end options.
type Text = (String, SourceFile, Option<SourceFile>, ProfileId, Options);

/// Every Omron program text of the repository.
fn texts() -> Vec<Text> {
    let root = stljit_harness::repo_root();
    let mut out = Vec::new();
    for f in files_in(&root.join("tests/conformance/omron"), &["toml"]) {
        let (file, cpu, options) = crate::ir_text::conformance_program(&f);
        out.push((f.display().to_string(), file, None, cpu, options));
    }
    for dir in [
        "crates/front-omron/tests/spec",
        "tests/diagnostics/omron",
        "examples/omron_conveyor",
        "benches/programs",
    ] {
        for f in files_in(&root.join(dir), &["omr"]) {
            let stem = f.with_extension("");
            let symbols = [
                format!("{}.symbols.txt", stem.display()),
                format!("{}/symbols.txt", root.join(dir).display()),
            ]
            .into_iter()
            .map(PathBuf::from)
            .find(|p| p.is_file())
            .map(|p| source(&p));
            out.push((
                f.display().to_string(),
                source(&f),
                symbols,
                ProfileId::Cp1h,
                Options::default(),
            ));
        }
    }
    out
}

fn compile(
    file: &SourceFile,
    symbols: Option<&SourceFile>,
    cpu: ProfileId,
    options: Options,
) -> Option<Program> {
    Dialect::Omron
        .compile_with(std::slice::from_ref(file), symbols, cpu, options)
        .program
}

#[test]
fn every_repository_omron_program_round_trips_through_the_printer() {
    let texts = texts();
    let mut compiled = 0;
    let mut failures = Vec::new();
    for (name, file, symbols, cpu, options) in &texts {
        // Diagnostics fixtures that are meant to be rejected have no IR to print.
        let Some(p) = compile(file, symbols.as_ref(), *cpu, *options) else {
            assert!(!name.contains("conformance"), "{name} does not compile");
            continue;
        };
        compiled += 1;
        if let Err(e) = roundtrip(&p) {
            failures.push(format!("{name}: {e}"));
        }
    }
    // 44 conformance cases (tasks, steps, blocks, `!` words, binary mode and backward jumps
    // among them), 10 spec programs, 13 fixtures that compile (warnings only), the example and
    // the benchmark program: 69 today.
    assert!(compiled >= 69, "only {compiled} of {} compile", texts.len());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// One mutation of `lines` (or of its bytes) from the fixed-seed stream.
fn mutate(lines: &[&str], next: &mut impl FnMut() -> u64) -> String {
    let mut v: Vec<String> = lines.iter().map(|l| (*l).to_owned()).collect();
    for _ in 0..=(next() % 2) {
        let n = v.len().max(1);
        let (i, j) = ((next() as usize) % n, (next() as usize) % n);
        match next() % 6 {
            0 if !v.is_empty() => {
                v.remove(i);
            }
            1 if !v.is_empty() => {
                let l = v[i].clone();
                v.insert(j, l);
            }
            2 if !v.is_empty() => v.swap(i, j),
            3 if !v.is_empty() => {
                // A token replaced by another line's token.
                let words: Vec<String> = v[j].split_whitespace().map(String::from).collect();
                let mut mine: Vec<String> = v[i].split_whitespace().map(String::from).collect();
                if let (Some(w), false) = (words.last(), mine.is_empty()) {
                    let k = (next() as usize) % mine.len();
                    mine[k] = w.clone();
                    v[i] = mine.join(" ");
                }
            }
            _ => {
                let mut bytes = v.join("\n").into_bytes();
                let at = (next() as usize) % bytes.len().max(1);
                if let Some(b) = bytes.get_mut(at) {
                    *b = b"0123456789.#&+-@%!,;ILDTRCNOW() "[(next() % 32) as usize];
                }
                return String::from_utf8_lossy(&bytes).into_owned();
            }
        }
    }
    v.join("\n")
}

#[test]
fn mutated_omron_texts_never_panic_and_what_compiles_round_trips_and_runs_alike() {
    let mut bases: Vec<(String, ProfileId, Options)> = texts()
        .into_iter()
        .filter(|(name, ..)| !name.ends_with("omron_mixed_10k.omr"))
        .filter_map(|(_, f, s, cpu, options)| {
            compile(&f, s.as_ref(), cpu, options)?;
            let text = String::from_utf8_lossy(&f.bytes).into_owned();
            (s.is_none()).then_some((text, cpu, options))
        })
        .collect();
    for seed in 0..10 {
        let mut c = Choices::from_seed(seed);
        let g = stljit_diff::generate::omron::generate(&mut c, &Default::default())
            .expect("generated programs compile");
        bases.push((
            g.source,
            g.case.program.profile,
            Options { omron: g.options },
        ));
    }
    let mut next = crate::mutate::xorshift(0x51A7_E0F0_1234_5678);
    let (mut accepted, mut tried) = (0, 0);
    for k in 0..1200 {
        let (base, cpu, options) = &bases[k % bases.len()];
        let lines: Vec<&str> = base.lines().collect();
        let text = mutate(&lines, &mut next);
        let file = SourceFile {
            name: "mutant.omr".into(),
            bytes: text.clone().into_bytes(),
        };
        tried += 1;
        let c = Dialect::Omron.compile_with(std::slice::from_ref(&file), None, *cpu, *options);
        assert_eq!(c.program.is_some(), c.error_count() == 0, "{text}");
        for d in &c.diagnostics {
            let _ = stljit_front::render_human(d, &c.sources);
        }
        let Some(program) = c.program else { continue };
        accepted += 1;
        let case = Case {
            stimulus: stimulus::generate(&mut Choices::from_seed(k as u64), *cpu, 8),
            program,
        };
        let engines = [EngineKind::Interp, EngineKind::Jit(OptLevel::None)];
        if let Err(f) = check_case(&case, engines, &RunOptions::default(), true) {
            panic!("mutant {k}: {f}\n{text}");
        }
    }
    // Both outcomes must be common, or the mutations test little.
    eprintln!("omron text mutations: {accepted} of {tried} accepted, printed, run");
    assert!(
        accepted > 200 && tried - accepted > 200,
        "{accepted} of {tried} accepted"
    );
}
