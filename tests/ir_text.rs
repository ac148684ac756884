//! The IR text form round-trips every program the repository holds: `text::parse(text::print(p))`
//! gives back exactly `p` (source locations included) for the benchmark corpus
//! (`benches/programs/`), every conformance case's program, the front end's spec and `ok`
//! fixtures and the examples. The generated programs are covered in `stljit_diff::roundtrip`.

use std::path::{Path, PathBuf};
use stljit_core::ProfileId;
use stljit_core::ir::Program;
use stljit_core::text;
use stljit_front_s7::{SourceFile, compile};

fn files_in(dir: &Path, exts: &[&str]) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| exts.iter().any(|x| e == *x)))
        .collect();
    v.sort();
    v
}

fn source(path: &Path) -> SourceFile {
    SourceFile {
        name: path.display().to_string(),
        bytes: std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    }
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
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        let table: toml::Table = text
            .parse()
            .unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let Some(src) = table.get("program").and_then(|v| v.as_str()) else {
            panic!("{}: no program", f.display());
        };
        let cpu = table
            .get("cpu")
            .and_then(|v| v.as_str())
            .map_or(Some(ProfileId::A5), ProfileId::from_name)
            .unwrap_or_else(|| panic!("{}: unknown cpu", f.display()));
        let file = SourceFile {
            name: f.display().to_string(),
            bytes: src.as_bytes().to_vec(),
        };
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
