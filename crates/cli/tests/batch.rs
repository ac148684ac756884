//! `stljit run` batches: one result file per run, the same files whatever the job count or
//! sharding, each the same as the single run with `--trace`, and sweeps that reach the program.

use std::path::{Path, PathBuf};
use std::process::Command;

const PROGRAM: &str = "\
NETWORK 1 // Q0.0 once the scan counter VW0 reaches the setpoint VW100
LDW>= VW0, VW100
= Q0.0
NETWORK 2
LD SM0.0
INCW VW0
NETWORK 3 // I0.0 copied to Q0.1
LD I0.0
= Q0.1
";

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stljit-batch-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("count.stl"), PROGRAM).unwrap();
    std::fs::write(d.join("a.csv"), "scan,I0.0\n0,0\n3,1\n").unwrap();
    std::fs::write(d.join("b.csv"), "scan,I0.0\n0,1\n7,0\n").unwrap();
    d
}

fn stljit(cwd: &Path, args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_stljit"))
        .current_dir(cwd)
        .args(["run", "count.stl", "--dialect", "s7", "--scans", "12"])
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn files(d: &Path) -> Vec<(String, String)> {
    let mut v: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read_to_string(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

const BATCH: &[&str] = &[
    "--inputs",
    "a.csv",
    "b.csv",
    "--sweep",
    "VW100=5,10",
    "--watch",
    "Q0.0,Q0.1,VW0",
];

#[test]
fn results_do_not_depend_on_jobs_or_shards() {
    let d = dir("jobs");
    let one = stljit(&d, &[BATCH, &["--out-dir", "one", "--jobs", "1"]].concat());
    let two = stljit(&d, &[BATCH, &["--out-dir", "two", "--jobs", "3"]].concat());
    assert!(one.0 && two.0, "{}", one.2);
    assert_eq!(one.1, two.1, "the summary is printed in run order");
    let all = files(&d.join("one"));
    assert_eq!(
        all.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
        [
            "0_a__VW100=5.csv",
            "1_a__VW100=10.csv",
            "2_b__VW100=5.csv",
            "3_b__VW100=10.csv"
        ]
    );
    assert_eq!(files(&d.join("two")), all);
    for k in 0..2 {
        let shard = format!("{k}/2");
        assert!(
            stljit(
                &d,
                &[BATCH, &["--out-dir", "shards", "--shard", &shard]].concat()
            )
            .0
        );
    }
    assert_eq!(
        files(&d.join("shards")),
        all,
        "two shards make the whole batch"
    );
    // Each file is the single run of its stimulus with its sweep value written before scan 0.
    let single = stljit(
        &d,
        &[
            "--inputs",
            "b.csv",
            "--watch",
            "Q0.0,Q0.1,VW0",
            "--trace",
            "single.csv",
        ],
    );
    assert!(single.0);
    let single = std::fs::read_to_string(d.join("single.csv")).unwrap();
    // VW100 = 0 in the single run, so only the Q0.0 column differs from run 2 (VW100 = 5).
    let q01 = |t: &str| -> Vec<String> {
        t.lines()
            .map(|l| l.split(',').skip(3).collect::<Vec<_>>().join(","))
            .collect()
    };
    assert_eq!(q01(&single), q01(&all[2].1));
}

#[test]
fn a_sweep_value_reaches_the_program_before_the_first_scan() {
    let d = dir("sweep");
    let (ok, summary, err) = stljit(
        &d,
        &[
            "--sweep",
            "VW100=5,10",
            "--watch",
            "Q0.0",
            "--out-dir",
            "out",
        ],
    );
    assert!(ok, "{err}");
    assert_eq!(
        summary,
        "run,scans,outcome,Q0.0\n0_run__VW100=5,12,completed,1\n1_run__VW100=10,12,completed,1\n"
    );
    for (name, first_on) in [("0_run__VW100=5.csv", 5), ("1_run__VW100=10.csv", 10)] {
        let text = std::fs::read_to_string(d.join("out").join(name)).unwrap();
        // Scan k compares VW0 = k (incremented after the compare) with the setpoint.
        let on: Vec<usize> = text
            .lines()
            .skip(1)
            .enumerate()
            .filter(|(_, l)| l.ends_with(",1"))
            .map(|(k, _)| k)
            .collect();
        assert_eq!(on.first(), Some(&first_on), "{name}");
    }
}

#[test]
fn batch_mistakes_are_usage_errors() {
    let d = dir("errors");
    for (args, want) in [
        (&["--sweep", "VW100=5"][..], "--out-dir"),
        (&["--sweep", "VW100=x", "--out-dir", "o"], "value `x`"),
        (&["--sweep", "SMB0=1", "--out-dir", "o"], "not writable"),
        (&["--sweep", "VW100", "--out-dir", "o"], "ADDR=V1"),
        (
            &[
                "--inputs",
                "a.csv",
                "b.csv",
                "--out-dir",
                "o",
                "--trace",
                "t.csv",
            ],
            "--trace",
        ),
        (
            &["--inputs", "a.csv", "--out-dir", "o", "--shard", "2/2"],
            "K < N",
        ),
    ] {
        let (ok, _, err) = stljit(&d, args);
        assert!(!ok && err.contains(want), "{args:?}: {err}");
    }
}
