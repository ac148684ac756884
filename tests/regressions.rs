//! Every fuzz finding stays fixed: each directory under `tests/regressions/` (written by
//! `stljit fuzz`: program.ir in the IR text form, stimulus.csv, meta) is replayed on the
//! interpreter and on the JIT at both optimisation levels, whole and split into one function per
//! basic block, with the whole image compared after every scan. The program is read as IR text,
//! so a case does not depend on any dialect's printer; `check_case` also runs both round trips
//! (IR text, and the front end of the program's dialect) on it.

use stljit_diff::campaign::check_case;
use stljit_diff::engines::EngineKind;
use stljit_diff::oracle::RunOptions;
use stljit_diff::repro::read_case;
use stljit_jit::OptLevel;

#[test]
fn every_regression_case_agrees_on_both_engines() {
    let root = stljit_harness::repo_root().join("tests/regressions");
    let mut dirs: Vec<_> = std::fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("program.ir").is_file())
        .collect();
    dirs.sort();
    assert!(!dirs.is_empty(), "no cases under {}", root.display());
    let mut failures = Vec::new();
    for dir in &dirs {
        let (case, meta) = match read_case(dir) {
            Ok(x) => x,
            Err(e) => {
                failures.push(format!("{}: {e}", dir.display()));
                continue;
            }
        };
        let run = RunOptions {
            loop_limit: meta.loop_limit,
            ..RunOptions::default()
        };
        for opt in [OptLevel::None, OptLevel::Speed] {
            for jit in [EngineKind::Jit(opt), EngineKind::JitSplit(opt)] {
                if let Err(f) = check_case(&case, [EngineKind::Interp, jit], &run, true) {
                    failures.push(format!("{} ({jit}): {f}", dir.display()));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
