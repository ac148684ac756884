//! The IR text form round-trips every program the repository holds: `text::parse(text::print(p))`
//! gives back exactly `p` (source locations included) for the benchmark corpus
//! (`benches/programs/`), every conformance case's program, the front end's spec and `ok`
//! fixtures and the examples. The generated programs are covered in `stljit_diff::roundtrip`.

use std::path::{Path, PathBuf};
use stljit_core::ProfileId;
use stljit_core::ir::Program;
use stljit_core::text;
use stljit_front_s7::{SourceFile, compile};

pub(crate) fn files_in(dir: &Path, exts: &[&str]) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| exts.iter().any(|x| e == *x)))
        .collect();
    v.sort();
    v
}

pub(crate) fn source(path: &Path) -> SourceFile {
    SourceFile {
        name: path.display().to_string(),
        bytes: std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    }
}

/// The program of conformance case `f`, its CPU and its front-end options.
pub(crate) fn conformance_program(f: &Path) -> (SourceFile, ProfileId, stljit_front::Options) {
    let text = std::fs::read_to_string(f).unwrap_or_default();
    let (src, cpu, options) = crate::conformance::harness::case_program(&text)
        .unwrap_or_else(|e| panic!("{}: {e}", f.display()));
    let file = SourceFile {
        name: f.display().to_string(),
        bytes: src.into_bytes(),
    };
    (file, cpu, options)
}

/// Compiles `files` (with an optional symbol table); `None` when the front end rejects them.
fn program(files: &[SourceFile], symbols: Option<&SourceFile>, cpu: ProfileId) -> Option<Program> {
    compile(files, symbols, cpu).program
}

/// The round trip of one program; the error names it.
fn check(name: &str, p: &Program) -> Result<(), String> {
    let printed = text::print(p);
    match text::parse(&printed) {
        Ok(back) if back == *p => Ok(()),
        Ok(_) => Err(format!("{name}: parses back to a different program")),
        Err(e) => Err(format!("{name}: {e}")),
    }
}

/// Every program of the corpus, conformance cases, fixtures and examples, by name.
fn corpus() -> Vec<(String, Program)> {
    let root = stljit_harness::repo_root();
    let mut out = Vec::new();
    for f in files_in(&root.join("benches/programs"), &["stl"]) {
        let p = program(&[source(&f)], None, ProfileId::A5)
            .unwrap_or_else(|| panic!("{} does not compile", f.display()));
        out.push((f.display().to_string(), p));
    }
    for f in files_in(&root.join("tests/conformance"), &["toml"]) {
        let (file, cpu, _) = conformance_program(&f);
        let p = program(&[file], None, cpu)
            .unwrap_or_else(|| panic!("{} does not compile", f.display()));
        out.push((f.display().to_string(), p));
    }
    for dir in ["tests/diagnostics/spec", "tests/diagnostics/ok"] {
        for f in files_in(&root.join(dir), &["stl", "awl"]) {
            let stem = f.with_extension("");
            let symbols = ["symbols.txt", "symbols.csv"]
                .iter()
                .map(|ext| PathBuf::from(format!("{}.{ext}", stem.display())))
                .find(|p| p.is_file())
                .map(|p| source(&p));
            // Spec programs that are meant to be rejected have no IR to print.
            if let Some(p) = program(&[source(&f)], symbols.as_ref(), ProfileId::A5) {
                out.push((f.display().to_string(), p));
            }
        }
    }
    let mut examples: Vec<PathBuf> = std::fs::read_dir(root.join("examples"))
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    examples.sort();
    for dir in examples {
        let files: Vec<SourceFile> = files_in(&dir, &["stl", "awl"])
            .iter()
            .map(|f| source(f))
            .collect();
        let symbols = dir.join("symbols.txt");
        let symbols = symbols.is_file().then(|| source(&symbols));
        if let Some(p) = program(&files, symbols.as_ref(), ProfileId::A5) {
            out.push((dir.display().to_string(), p));
        }
    }
    out
}

#[test]
fn every_repository_program_round_trips_through_ir_text() {
    let corpus = corpus();
    let failures: Vec<String> = corpus
        .iter()
        .filter_map(|(name, p)| check(name, p).err())
        .collect();
    let ops: usize = corpus.iter().map(|(_, p)| p.op_count()).sum();
    eprintln!(
        "ir text: {} programs, {ops} ops round-tripped",
        corpus.len()
    );
    // The corpus (4), the conformance cases (over 40), the fixtures and the example.
    assert!(corpus.len() >= 60, "only {} programs found", corpus.len());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// An IR text that parses but breaks a verifier rule (here a word one byte past the end of V) is
/// rejected by both engines before anything runs: the text form is an input like any other.
#[test]
fn engines_reject_a_parsed_ir_that_breaks_the_verifier() {
    let text = "LD SM0.0\nMOVW 7, VW2498\n";
    let p = stljit_front_s7::compile_str("t.stl", text, ProfileId::A5)
        .program
        .expect("compiles");
    let printed = text::print(&p);
    assert!(printed.contains("V.2498"), "{printed}");
    let bad = text::parse(&printed.replace("V.2498", "V.2499")).expect("still parses");
    let interp = stljit_interp::Interpreter::new(&bad)
        .map(|_| ())
        .unwrap_err();
    let jit = stljit_jit::JitProgram::compile(&bad, &stljit_jit::JitOptions::default())
        .map(|_| ())
        .unwrap_err();
    let rule = "2 byte(s) at V 2499 run past the area";
    assert!(interp.to_string().contains(rule), "{interp}");
    assert!(jit.to_string().contains(rule), "{jit}");
}

/// The IR text form is an input like program text: a mutated text (a number replaced by a
/// boundary value, a line dropped or repeated) either fails to parse, fails the verifier, or runs
/// on the interpreter and the JIT without a panic and with identical images after every scan
/// (1,530 mutations of 40 generated programs; 689 of them pass the verifier and run).
#[test]
fn mutated_ir_texts_never_crash_and_both_engines_agree() {
    use stljit_diff::engines::EngineKind;
    use stljit_diff::generate::{GenConfig, case_from_seed};
    use stljit_diff::oracle::{RunOptions, run_pair};
    const BOUNDARIES: &[u64] = &[
        0,
        1,
        2,
        7,
        8,
        9,
        15,
        16,
        31,
        32,
        63,
        64,
        255,
        256,
        2047,
        2048,
        2498,
        2499,
        2500,
        32767,
        65535,
        65536,
        4_294_967_295,
    ];
    let mut next = crate::mutate::xorshift(0x9E37_79B9_7F4A_7C15);
    let (mut tried, mut ran) = (0, 0);
    for seed in 0..40 {
        let case = case_from_seed(seed, &GenConfig::default());
        let printed = text::print(&case.program);
        let lines: Vec<&str> = printed.lines().collect();
        let mut stimulus = case.stimulus.clone();
        stimulus.scans.truncate(8);
        for _ in 0..40 {
            let mut lines: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            let i = next() as usize % lines.len();
            match next() % 8 {
                0 => {
                    lines.remove(i);
                }
                1 => lines.insert(i, lines[i].clone()),
                _ => {
                    // Replace one run of digits on the line with a boundary value.
                    let line = &lines[i];
                    let starts: Vec<usize> = line
                        .char_indices()
                        .filter(|&(k, c)| {
                            c.is_ascii_digit() && !line[..k].ends_with(|p: char| p.is_ascii_digit())
                        })
                        .map(|(k, _)| k)
                        .collect();
                    if starts.is_empty() {
                        continue;
                    }
                    let at = starts[next() as usize % starts.len()];
                    let end = line[at..]
                        .find(|c: char| !c.is_ascii_digit())
                        .map_or(line.len(), |e| at + e);
                    let value = BOUNDARIES[next() as usize % BOUNDARIES.len()];
                    lines[i] = format!("{}{value}{}", &line[..at], &line[end..]);
                }
            }
            tried += 1;
            let Ok(p) = text::parse(&lines.join("\n")) else {
                continue;
            };
            if stljit_core::ir::verify(&p).is_err() {
                continue;
            }
            ran += 1;
            let build = |k: EngineKind| {
                k.build(&p)
                    .unwrap_or_else(|e| panic!("seed {seed}: a verified IR does not build: {e}"))
            };
            let (mut a, mut b) = (
                build(EngineKind::Interp),
                build(EngineKind::Jit(stljit_jit::OptLevel::None)),
            );
            if let Err(f) = run_pair(&p, &stimulus, &mut *a, &mut *b, &RunOptions::default()) {
                panic!("seed {seed}, mutated line {i}:\n{f}\n{}", lines.join("\n"));
            }
        }
    }
    assert!(
        ran > 200,
        "only {ran} of {tried} mutated texts passed the verifier"
    );
}
