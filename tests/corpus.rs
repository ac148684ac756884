//! The corpus of real MicroWIN / MicroWIN SMART exports (`tests/corpus/`, provenance in each
//! source's `PROVENANCE.md`): every file is compiled with the project it belongs to, as listed in
//! `tests/corpus/status.toml`, and how it checks must match the status recorded there:
//!
//! * `clean` — no error in the file;
//! * `gap M1 M2 …` — every error is E027 "not supported yet", for exactly these mnemonics (the
//!   later parts of issue 13 turn these clean and update the line);
//! * `rejected E015 …` — errors with these codes (plus `+ gap …` if unsupported mnemonics remain),
//!   for files that the vendor's own software rejects too (the status file says why).
//!
//! A project whose files are all clean also runs: both engines, 200 scans of random stimulus,
//! compared byte for byte after every scan, after the IR-text and S7 print → compile round
//! trips. On a mismatch the test prints the whole actual table,
//! ready to paste into `status.toml` after review.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use stljit_core::ProfileId;
use stljit_diff::campaign::check_case;
use stljit_diff::engines::EngineKind;
use stljit_diff::generate::{Case, stimulus};
use stljit_diff::oracle::RunOptions;
use stljit_diff::rng::Choices;
use stljit_front::{Code, Dialect, Severity, SourceFile};
use stljit_jit::OptLevel;
use toml::{Table, Value};

fn root() -> PathBuf {
    stljit_harness::repo_root().join("tests/corpus")
}

/// One project of `status.toml`.
struct Project {
    name: String,
    cpu: ProfileId,
    files: Vec<String>,
    symbols: Option<String>,
    /// Expected status per file (paths relative to `tests/corpus`).
    status: Vec<(String, String)>,
}

fn strings(t: &Table, key: &str) -> Vec<String> {
    match t.get(key) {
        Some(Value::Array(a)) => a
            .iter()
            .filter_map(|v| v.as_str().map(str::to_owned))
            .collect(),
        _ => Vec::new(),
    }
}

fn projects() -> Vec<Project> {
    let text = std::fs::read_to_string(root().join("status.toml")).expect("status.toml");
    let t: Table = text.parse().expect("status.toml is TOML");
    let Some(Value::Array(list)) = t.get("project") else {
        panic!("status.toml has no [[project]]");
    };
    list.iter()
        .map(|p| {
            let p = p.as_table().expect("a [[project]] is a table");
            let name = p["name"].as_str().expect("name").to_owned();
            let cpu = p
                .get("cpu")
                .and_then(Value::as_str)
                .map_or(ProfileId::Smart, |c| {
                    ProfileId::from_name(c).unwrap_or_else(|| panic!("{name}: cpu `{c}`"))
                });
            let mut files = strings(p, "files");
            if let Some(dir) = p.get("dir").and_then(Value::as_str) {
                let mut in_dir: Vec<String> = std::fs::read_dir(root().join(dir))
                    .unwrap_or_else(|e| panic!("{name}: {dir}: {e}"))
                    .flatten()
                    .map(|e| e.path())
                    .filter(|f| f.extension().is_some_and(|x| x == "awl"))
                    .map(|f| rel(&f))
                    .collect();
                in_dir.sort();
                files.extend(in_dir);
            }
            let status = match p.get("status") {
                Some(Value::Table(s)) => s
                    .iter()
                    .map(|(k, v)| (k.clone(), v.as_str().unwrap_or_default().to_owned()))
                    .collect(),
                _ => Vec::new(),
            };
            Project {
                name,
                cpu,
                files,
                symbols: p.get("symbols").and_then(Value::as_str).map(str::to_owned),
                status,
            }
        })
        .collect()
}

fn rel(p: &Path) -> String {
    p.strip_prefix(root())
        .unwrap_or(p)
        .to_string_lossy()
        .replace('\\', "/")
}

fn load(rel: &str) -> SourceFile {
    let path = root().join(rel);
    SourceFile {
        name: rel.to_owned(),
        bytes: std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    }
}

/// The status of one file from its errors: `clean`, `gap …` or `rejected … [+ gap …]`.
fn status_of(errors: &[(Code, String)]) -> String {
    let gaps: BTreeSet<String> = errors
        .iter()
        .filter(|(c, _)| *c == Code::Unsupported)
        .map(|(_, text)| text.to_ascii_uppercase())
        .collect();
    let codes: BTreeSet<&str> = errors
        .iter()
        .filter(|(c, _)| *c != Code::Unsupported)
        .map(|(c, _)| c.name())
        .collect();
    let gap = gaps.into_iter().collect::<Vec<_>>().join(" ");
    match (codes.is_empty(), gap.is_empty()) {
        (true, true) => "clean".to_owned(),
        (true, false) => format!("gap {gap}"),
        (false, true) => format!(
            "rejected {}",
            codes.into_iter().collect::<Vec<_>>().join(" ")
        ),
        (false, false) => format!(
            "rejected {} + gap {gap}",
            codes.into_iter().collect::<Vec<_>>().join(" ")
        ),
    }
}

#[test]
fn every_corpus_file_checks_as_recorded() {
    let mut mismatches = Vec::new();
    let mut table = Vec::new();
    let mut listed = BTreeSet::new();
    for p in projects() {
        let files: Vec<SourceFile> = p.files.iter().map(|f| load(f)).collect();
        let symbols = p.symbols.as_deref().map(load);
        let c = Dialect::S7.compile(&files, symbols.as_ref(), p.cpu);
        let mut all_clean = true;
        for (i, f) in p.files.iter().enumerate() {
            listed.insert(f.clone());
            let errors: Vec<(Code, String)> = c
                .diagnostics
                .iter()
                .filter(|d| d.severity == Severity::Error && d.file.index() == i)
                .map(|d| (d.code, d.text.clone()))
                .collect();
            let actual = status_of(&errors);
            all_clean &= actual == "clean";
            let expected = p
                .status
                .iter()
                .find(|(k, _)| k == f)
                .map(|(_, v)| v.as_str());
            if expected != Some(actual.as_str()) {
                mismatches.push(format!(
                    "{}: {f}: recorded {expected:?}, checks as {actual:?}",
                    p.name
                ));
            }
            table.push(format!("\"{f}\" = \"{actual}\""));
        }
        for (k, _) in &p.status {
            if !p.files.contains(k) {
                mismatches.push(format!(
                    "{}: status for {k}, which is not in the project",
                    p.name
                ));
            }
        }
        // Symbol-table errors are not any file's: they must not exist.
        let table_errors = c
            .diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Error && d.file.index() >= p.files.len())
            .count();
        if table_errors > 0 {
            mismatches.push(format!("{}: {table_errors} symbol-table error(s)", p.name));
        }
        if all_clean {
            run_both_engines(&p.name, c.program.as_ref(), &mut mismatches);
        }
    }
    // Every program file of the corpus is in some project.
    for f in corpus_files(&root()) {
        if !listed.contains(&f) {
            mismatches.push(format!("{f} is in no [[project]] of status.toml"));
        }
    }
    assert!(
        mismatches.is_empty(),
        "{}\n\nactual statuses:\n{}",
        mismatches.join("\n"),
        table.join("\n")
    );
}

/// Runs a clean project on the interpreter and the JIT with random stimulus.
fn run_both_engines(
    name: &str,
    program: Option<&stljit_core::ir::Program>,
    mismatches: &mut Vec<String>,
) {
    let Some(program) = program else {
        mismatches.push(format!(
            "{name}: every file is clean but there is no program"
        ));
        return;
    };
    let mut choices = Choices::from_seed(13);
    let case = Case {
        stimulus: stimulus::for_program(&mut choices, program, 200),
        program: program.clone(),
    };
    let engines = [EngineKind::Interp, EngineKind::Jit(OptLevel::None)];
    if let Err(finding) = check_case(&case, engines, &RunOptions::default(), true) {
        mismatches.push(format!("{name}: the engines disagree: {finding}"));
    }
}

/// Every `.awl` file under `dir`, relative to the corpus root.
fn corpus_files(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(corpus_files(&p));
        } else if p.extension().is_some_and(|x| x == "awl") {
            out.push(rel(&p));
        }
    }
    out.sort();
    out
}
