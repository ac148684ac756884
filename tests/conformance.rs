//! Conformance cases as data, run on every engine.
//!
//! Each `tests/conformance/*.toml` file is one case: a program, a CPU profile, a scan time and a
//! list of scans with inputs and expected values (format in `tests/conformance/README.md`). The
//! harness compiles the program with `stljit_front_s7`, runs it on **every** engine in [`ENGINES`]
//! through the runtime's simulation driver, checks the expectations after each listed scan, and
//! checks that all engines leave byte-identical images after every scan.
//!
//! **Input rule (spec §7):** the `inputs` of a scan are the *whole* input image for that scan —
//! an I bit or byte not listed is 0. Other addresses in `inputs` (`VW0`, `AIW0`, `M1.0`) are
//! written before that scan like an HMI write and hold until the program changes them.
//!
//! A case may carry `known_failure = "reason"`: its failures are printed loudly but do not fail
//! the test; a known failure that starts passing *does* fail, so the marker cannot go stale.

pub(crate) mod feeds;
pub(crate) mod frames;
pub(crate) mod harness;
pub(crate) mod phys_out;

use harness::{ENGINES, Failure, HarnessError, run_case_text, run_dir};
use std::path::PathBuf;

fn cases_dir() -> PathBuf {
    stljit_harness::repo_root().join("tests/conformance")
}

#[test]
fn every_case_passes_on_every_engine() {
    let summary = match run_dir(&cases_dir(), ENGINES) {
        Ok(s) => s,
        Err(e) => panic!("{e}"),
    };
    for line in &summary.known {
        eprintln!("KNOWN FAILURE {line}");
    }
    eprintln!(
        "conformance: {} cases, {} scans checked on {} engines ({}), {} known failures",
        summary.cases,
        summary.scans,
        ENGINES.len(),
        ENGINES.iter().map(|e| e.0).collect::<Vec<_>>().join(", "),
        summary.known.len()
    );
    let report: Vec<String> = summary.failures.iter().map(Failure::to_string).collect();
    assert!(
        report.is_empty(),
        "{} conformance failure(s):\n{}",
        report.len(),
        report.join("\n")
    );
}

#[test]
fn an_empty_directory_fails() {
    let dir = std::env::temp_dir().join(format!("stljit-conformance-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("README.md"), "not a case").expect("write");
    let got = run_dir(&dir, ENGINES);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(matches!(got, Err(HarnessError::NoCases(_))), "{got:?}");
}

#[test]
fn a_missing_directory_fails() {
    let got = run_dir(&cases_dir().join("no-such-dir"), ENGINES);
    assert!(matches!(got, Err(HarnessError::Io(..))), "{got:?}");
}

const WRONG: &str = r#"
name = "deliberately wrong"
spec = "harness self-test"
program = """
LD   I0.0
=    Q0.0
"""
[[scan]]
inputs = { "I0.0" = 1 }
expect = { "Q0.0" = 0, "VW0" = "16#0001" }
"#;

#[test]
fn a_wrong_expectation_is_reported_per_engine() {
    let failures = run_case_text("wrong.toml", WRONG, ENGINES).failures;
    let text: Vec<String> = failures.iter().map(Failure::to_string).collect();
    for (engine, _) in ENGINES {
        assert!(
            text.contains(&format!(
                "wrong.toml: scan 0, Q0.0 [{engine}]: expected 0, got 1"
            )),
            "{text:#?}"
        );
        assert!(
            text.contains(&format!(
                "wrong.toml: scan 0, VW0 [{engine}]: expected 1, got 0"
            )),
            "{text:#?}"
        );
    }
}

#[test]
fn diverging_engines_are_reported() {
    use stljit_runtime::Engine;
    fn skewed(p: &stljit_core::ir::Program) -> Result<Box<dyn Engine>, String> {
        let inner = (ENGINES[0].1)(p)?;
        Ok(Box::new(harness::Skew(inner)))
    }
    let engines: &[harness::EngineEntry] = &[ENGINES[0], ("skewed", skewed)];
    let case = WRONG.replace(
        "expect = { \"Q0.0\" = 0, \"VW0\" = \"16#0001\" }",
        "expect = {}",
    );
    let failures = run_case_text("skew.toml", &case, engines).failures;
    let text: Vec<String> = failures.iter().map(Failure::to_string).collect();
    assert!(
        text.iter().any(|t| t.starts_with(&format!(
            "skew.toml: scan 0, images differ [{} vs skewed]: V offset 2499",
            ENGINES[0].0
        ))),
        "{text:#?}"
    );
}

#[test]
fn malformed_cases_are_rejected_with_the_file_name() {
    let bad = [
        ("typo.toml", WRONG.replace("expect =", "expects =")),
        ("addr.toml", WRONG.replace("\"Q0.0\" = 0", "\"Q99.0\" = 0")),
        ("value.toml", WRONG.replace("\"Q0.0\" = 0", "\"Q0.0\" = 2")),
        ("prog.toml", WRONG.replace("LD   I0.0", "LDX  I0.0")),
        ("time.toml", WRONG.replace("[[scan]]", "[[scan]]\nt_ms = 5")),
    ];
    for (file, text) in bad {
        let failures = run_case_text(file, &text, ENGINES).failures;
        assert!(
            !failures.is_empty() && failures.iter().all(|f| f.to_string().starts_with(file)),
            "{file}: {failures:#?}"
        );
    }
}

#[test]
fn known_failure_markers_are_strict() {
    let dir = std::env::temp_dir().join(format!("stljit-conformance-known-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let still_failing = format!("known_failure = \"reason A\"\n{WRONG}");
    let now_passing = still_failing.replace("reason A", "reason B").replace(
        "expect = { \"Q0.0\" = 0, \"VW0\" = \"16#0001\" }",
        "expect = { \"Q0.0\" = 1 }",
    );
    std::fs::write(dir.join("a.toml"), still_failing).expect("write");
    std::fs::write(dir.join("b.toml"), now_passing).expect("write");
    let got = run_dir(&dir, ENGINES);
    let _ = std::fs::remove_dir_all(&dir);
    let summary = got.expect("two cases");
    assert_eq!(summary.cases, 2);
    assert_eq!(summary.known.len(), 1, "{:?}", summary.known);
    assert!(summary.known[0].starts_with("a.toml: reason A\n"));
    let failures: Vec<String> = summary.failures.iter().map(Failure::to_string).collect();
    assert_eq!(
        failures,
        vec![
            "b.toml: marked known_failure (\"reason B\") but passes on every engine: remove the \
             marker"
                .to_string()
        ]
    );
}
