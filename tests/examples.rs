//! The programs under `examples/` run as tests on every engine.
//!
//! An example directory with an `expected.csv` is a case: its program files (`*.awl`, `*.stl`
//! for S7, `*.omr` for Omron CP; the dialect is detected from the content as the CLI does),
//! optional `symbols.txt` and `stimulus.csv` are compiled and run for as many scans as the
//! expectations need, on every engine of the conformance harness. Each expectation row names a
//! scan and the values (symbols or addresses in the header) after it; the rows are derived by
//! hand from the program and the spec (see the comment lines in each file). After every scan
//! all engines must hold byte-identical images.

use crate::conformance::harness::ENGINES;
use std::path::{Path, PathBuf};
use stljit_core::ir::{Address, Program};
use stljit_front::{Dialect, SourceFile, Symbols};
use stljit_runtime::Image;
use stljit_sim::{FnObserver, ScanEvent, Simulation, Stimulus, TimeBase, Until, read_address};

struct Example {
    dir: PathBuf,
    program: Program,
    symbols: Option<Symbols>,
    stimulus: Stimulus,
    columns: Vec<(String, Address)>,
    rows: Vec<(u64, Vec<u32>)>,
}

fn read(path: &Path) -> SourceFile {
    SourceFile {
        name: path.display().to_string(),
        bytes: std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    }
}

fn load(dir: &Path) -> Example {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.extension()
                .is_some_and(|e| e == "awl" || e == "stl" || e == "omr")
        })
        .collect();
    files.sort();
    let sources: Vec<SourceFile> = files.iter().map(|p| read(p)).collect();
    let symbols_path = dir.join("symbols.txt");
    let symbols = symbols_path.exists().then(|| read(&symbols_path));
    let text = String::from_utf8_lossy(&sources[0].bytes).into_owned();
    let dialect = Dialect::detect(&text)
        .unwrap_or_else(|| panic!("{}: cannot tell the dialect", dir.display()));
    let c = dialect.compile(&sources, symbols.as_ref(), dialect.default_profile());
    let program = c
        .program
        .unwrap_or_else(|| panic!("{}: does not compile: {:?}", dir.display(), c.diagnostics));
    let profile = program.profile.profile();
    let table = c.symbols;
    let resolve = |name: &str| {
        dialect
            .parse_address(name, program.profile, table.as_ref())
            .map_err(|e| e.message)
    };
    let stimulus_path = dir.join("stimulus.csv");
    let stimulus = if stimulus_path.exists() {
        let text = std::fs::read_to_string(&stimulus_path).unwrap();
        Stimulus::parse(&text, profile, &resolve).unwrap_or_else(|e| panic!("{e}"))
    } else {
        Stimulus::empty(TimeBase::Scan, profile)
    };
    let expected = std::fs::read_to_string(dir.join("expected.csv")).unwrap();
    let mut lines = expected
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header: Vec<&str> = lines
        .next()
        .expect("expected.csv has a header")
        .split(',')
        .collect();
    assert_eq!(
        header[0],
        "scan",
        "{}: first column must be `scan`",
        dir.display()
    );
    let columns = header[1..]
        .iter()
        .map(|n| {
            (
                n.to_string(),
                resolve(n).unwrap_or_else(|e| panic!("{n}: {e}")),
            )
        })
        .collect();
    let rows = lines
        .map(|l| {
            let cells: Vec<u32> = l.split(',').map(|c| c.trim().parse().unwrap()).collect();
            (u64::from(cells[0]), cells[1..].to_vec())
        })
        .collect();
    Example {
        dir: dir.to_path_buf(),
        program,
        symbols: table,
        stimulus,
        columns,
        rows,
    }
}

/// Runs the example on one engine; returns the image after every scan.
fn run(
    example: &Example,
    engine: &str,
    ctor: crate::conformance::harness::EngineCtor,
) -> Vec<Image> {
    let mut engine_box = ctor(&example.program).unwrap_or_else(|e| panic!("{engine}: {e}"));
    let scans = example.rows.last().map_or(0, |r| r.0 + 1);
    let mut images = Vec::new();
    let mut sim = Simulation::new(engine_box.as_mut(), Image::cold_start(&example.program), 10)
        .expect("10 ms scans");
    let mut record = FnObserver(|e: &ScanEvent<'_>| {
        images.push(e.image.clone());
        Ok(())
    });
    sim.run(Until::Scans(scans), &example.stimulus, &mut record)
        .expect("run");
    images
}

#[test]
fn examples_follow_their_hand_derived_timelines_on_every_engine() {
    let root = stljit_harness::repo_root().join("examples");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("expected.csv").exists())
        .collect();
    dirs.sort();
    assert!(!dirs.is_empty(), "no example has an expected.csv");
    for dir in dirs {
        let example = load(&dir);
        assert!(example.symbols.is_some() || !dir.join("symbols.txt").exists());
        let runs: Vec<(&str, Vec<Image>)> = ENGINES
            .iter()
            .map(|(name, ctor)| (*name, run(&example, name, *ctor)))
            .collect();
        let mut failures = Vec::new();
        for (name, images) in &runs {
            for (scan, values) in &example.rows {
                let image = &images[*scan as usize];
                for ((col, address), want) in example.columns.iter().zip(values) {
                    let got = read_address(image, address);
                    if got != Some(*want) {
                        failures.push(format!(
                            "{name}: scan {scan}, {col}: expected {want}, got {got:?}"
                        ));
                    }
                }
            }
        }
        let (first, rest) = runs.split_first().unwrap();
        for (name, images) in rest {
            for (scan, (a, b)) in first.1.iter().zip(images).enumerate() {
                if a.bytes() != b.bytes() {
                    failures.push(format!("scan {scan}: {} and {name} images differ", first.0));
                    break;
                }
            }
        }
        assert!(
            failures.is_empty(),
            "{}:\n{}",
            example.dir.display(),
            failures.join("\n")
        );
    }
}
