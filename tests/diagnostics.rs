//! Diagnostics fixtures: every program under `tests/diagnostics/` is compiled and its rendered
//! diagnostics compared with the `.expected` file next to it. A case is a `.stl`/`.awl` file
//! (with an optional `<stem>.symbols.txt` or `<stem>.symbols.csv`), or a `<name>.project/`
//! directory whose program files form one project (with `symbols.txt`/`symbols.csv` and
//! `expected` inside). A stem containing `.s7-200` or `.smart` selects that CPU; the default is
//! the A5. Cases under `omron/` (`.omr` files) compile with the Omron dialect on the CP1H. A few
//! programs are too long to commit and are generated here ([`generated`]); their `.expected`
//! files are committed like any other.
//! `STLJIT_BLESS=1` rewrites the expectations (read them before committing).
//!
//! Also here: every diagnostic code has a fixture named after it and an entry in
//! `docs/diagnostics.md`, and no input (garbage, a 1 MB line, an empty file) makes the front end
//! panic.

use std::path::{Path, PathBuf};
use stljit_core::ProfileId;
use stljit_front::Dialect;
use stljit_front_s7::{Code, Severity, SourceFile, compile, render_human};

fn root() -> PathBuf {
    stljit_harness::repo_root().join("tests/diagnostics")
}

fn is_program(p: &Path) -> bool {
    p.extension()
        .is_some_and(|e| e == "stl" || e == "awl" || e == "omr")
}

struct Case {
    /// Name relative to `tests/diagnostics`.
    name: String,
    files: Vec<PathBuf>,
    symbols: Option<PathBuf>,
    expected: PathBuf,
    cpu: ProfileId,
    dialect: Dialect,
    /// The program text of a generated case (else `files` are read).
    text: Option<String>,
}

fn rel(p: &Path) -> String {
    p.strip_prefix(root())
        .unwrap_or(p)
        .to_string_lossy()
        .replace('\\', "/")
}

fn first_existing(candidates: [PathBuf; 2]) -> Option<PathBuf> {
    candidates.into_iter().find(|p| p.exists())
}

fn discover(dir: &Path, out: &mut Vec<Case>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .map(|r| r.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    entries.sort();
    for path in entries {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let omron = rel(&path).starts_with("omron/");
        let (dialect, cpu) = if omron {
            (Dialect::Omron, ProfileId::Cp1h)
        } else if name.contains(".s7-200") {
            (Dialect::S7, ProfileId::S7_200)
        } else if name.contains(".smart") {
            (Dialect::S7, ProfileId::Smart)
        } else {
            (Dialect::S7, ProfileId::A5)
        };
        if path.is_dir() && name.ends_with(".project") {
            let mut files: Vec<_> = std::fs::read_dir(&path)
                .map(|r| {
                    r.flatten()
                        .map(|e| e.path())
                        .filter(|p| is_program(p))
                        .collect()
                })
                .unwrap_or_default();
            files.sort();
            out.push(Case {
                name: rel(&path),
                files,
                symbols: first_existing([path.join("symbols.txt"), path.join("symbols.csv")]),
                expected: path.join("expected"),
                cpu,
                dialect,
                text: None,
            });
        } else if path.is_dir() {
            discover(&path, out);
        } else if is_program(&path) {
            let stem = path.with_extension("");
            let with = |ext: &str| PathBuf::from(format!("{}{ext}", stem.display()));
            out.push(Case {
                name: rel(&path),
                files: vec![path.clone()],
                symbols: first_existing([with(".symbols.txt"), with(".symbols.csv")]),
                expected: with(".expected"),
                cpu,
                dialect,
                text: None,
            });
        }
    }
}

/// The generated cases: OMR-E035 needs a program larger than the CP1H's 20K steps: an `LD`
/// and 4096 CMPLs of two double constants (3 steps and one per constant: 5 each) are 20481
/// steps before the END.
fn generated() -> Vec<Case> {
    let mut text =
        String::from("; generated: 4096 x CMPL with two constants (5 steps each)\nLD P_On\n");
    for _ in 0..4096 {
        text.push_str("CMPL(060) #00010002 #00030004\n");
    }
    text.push_str("END(001)\n");
    let name = "omron/OMR-E035_capacity.omr";
    vec![Case {
        name: name.into(),
        files: Vec::new(),
        symbols: None,
        expected: root().join("omron/OMR-E035_capacity.expected"),
        cpu: ProfileId::Cp1h,
        dialect: Dialect::Omron,
        text: Some(text),
    }]
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    discover(&root(), &mut out);
    out.extend(generated());
    assert!(out.len() > 20, "too few diagnostics fixtures found");
    out
}

fn load(p: &Path) -> SourceFile {
    SourceFile {
        name: rel(p),
        bytes: std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display())),
    }
}

/// The code a fixture is named after (`E003_out_of_range.stl` → `E003`).
fn named_code(name: &str) -> Option<Code> {
    let base = name.rsplit('/').next().unwrap_or(name);
    Code::ALL
        .iter()
        .copied()
        .find(|c| base.starts_with(c.name()))
}

#[test]
fn fixtures_match_expectations() {
    let bless = std::env::var_os("STLJIT_BLESS").is_some_and(|v| v == "1");
    let mut failures = Vec::new();
    for case in cases() {
        let files: Vec<_> = match &case.text {
            Some(text) => vec![SourceFile {
                name: case.name.clone(),
                bytes: text.clone().into_bytes(),
            }],
            None => case.files.iter().map(|p| load(p)).collect(),
        };
        let symbols = case.symbols.as_deref().map(load);
        let c = case.dialect.compile(&files, symbols.as_ref(), case.cpu);
        let rendered: Vec<_> = c
            .diagnostics
            .iter()
            .map(|d| render_human(d, &c.sources))
            .collect();
        let actual = rendered.join("\n");
        if let Some(code) = named_code(&case.name) {
            if !c.diagnostics.iter().any(|d| d.code == code) {
                failures.push(format!(
                    "{}: expected a {code} diagnostic, got:\n{actual}",
                    case.name
                ));
            }
        } else if c.error_count() > 0 {
            failures.push(format!("{}: expected no errors, got:\n{actual}", case.name));
        }
        assert_eq!(
            c.program.is_some(),
            c.diagnostics.iter().all(|d| d.severity != Severity::Error),
            "{}: program iff no error",
            case.name
        );
        if bless {
            std::fs::write(&case.expected, &actual).expect("write expectation");
            continue;
        }
        let expected = std::fs::read_to_string(&case.expected).unwrap_or_else(|_| {
            failures.push(format!(
                "{}: missing {}",
                case.name,
                case.expected.display()
            ));
            String::new()
        });
        if expected.replace("\r\n", "\n") != actual {
            failures.push(format!(
                "{}: diagnostics differ\n--- expected\n{expected}\n--- actual\n{actual}",
                case.name
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn every_code_has_a_fixture_and_a_doc_entry() {
    let names: Vec<_> = cases().into_iter().map(|c| c.name).collect();
    let doc = std::fs::read_to_string(stljit_harness::repo_root().join("docs/diagnostics.md"))
        .expect("docs/diagnostics.md");
    for code in Code::ALL {
        assert!(
            names.iter().any(|n| named_code(n) == Some(*code)),
            "no fixture named {code}_*"
        );
        assert!(
            doc.contains(&format!("## {code}")),
            "docs/diagnostics.md has no `## {code}` section"
        );
    }
}

fn compile_bytes(bytes: Vec<u8>) -> stljit_front_s7::Compilation {
    let file = SourceFile {
        name: "input.stl".into(),
        bytes,
    };
    let c = compile(std::slice::from_ref(&file), Some(&file), ProfileId::A5);
    for d in &c.diagnostics {
        let _ = render_human(d, &c.sources);
        let _ = stljit_front_s7::render_json(d, &c.sources);
    }
    c
}

#[test]
fn no_input_makes_the_front_end_panic() {
    assert!(
        compile_bytes(Vec::new()).program.is_some(),
        "an empty file is a valid program"
    );
    let garbage: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect();
    assert!(compile_bytes(garbage).error_count() > 0);
    let mut long = b"LD ".to_vec();
    long.extend(std::iter::repeat_n(b'V', 1 << 20));
    let c = compile_bytes(long);
    assert!(c.error_count() > 0);
    assert!(
        c.diagnostics
            .iter()
            .all(|d| d.text.len() < 200 && d.message.len() < 400)
    );
    // Mutations of a valid program: cut, byte flips and splices, from a fixed-seed generator.
    let base = std::fs::read(root().join("ok/all_instructions.stl")).expect("fixture");
    let mut next = crate::mutate::xorshift(0x9E37_79B9_7F4A_7C15_u64);
    for _ in 0..300 {
        let mut bytes = base.clone();
        for _ in 0..(next() % 16) {
            let at = (next() as usize) % bytes.len().max(1);
            match next() % 3 {
                0 => bytes[at] = next() as u8,
                1 => bytes.truncate(at),
                _ => {
                    let from = (next() as usize) % base.len();
                    let len = (next() as usize) % 64;
                    let piece = base[from..(from + len).min(base.len())].to_vec();
                    bytes.splice(at.min(bytes.len())..at.min(bytes.len()), piece);
                }
            }
            if bytes.is_empty() {
                break;
            }
        }
        compile_bytes(bytes);
    }
}

fn compile_case(program: &str, symbols: Option<&str>) -> stljit_core::ir::Program {
    let files = [load(&root().join(program))];
    let symbols = symbols.map(|s| load(&root().join(s)));
    let c = compile(&files, symbols.as_ref(), ProfileId::A5);
    c.program
        .unwrap_or_else(|| panic!("{program}: {:?}", c.diagnostics))
}

#[test]
fn microwin_export_resolves_blocks_by_symbol_and_number() {
    use stljit_core::PouId;
    use stljit_core::ir::{CounterKind, Op, PouKind};
    let p = compile_case(
        "ok/microwin_export.awl",
        Some("ok/microwin_export.symbols.txt"),
    );
    let names: Vec<_> = p.pous.iter().map(|p| (p.name.as_str(), p.kind)).collect();
    assert_eq!(
        names,
        [
            ("MAIN", PouKind::Main),
            ("Motor_Logic", PouKind::Subroutine(0)),
            ("Counter_Logic", PouKind::Subroutine(1)),
            ("Alarm_Logic", PouKind::Subroutine(2)),
            ("Timer_Int", PouKind::Interrupt(0)),
        ]
    );
    let calls: Vec<_> = p.pous[0]
        .ops
        .iter()
        .filter_map(|op| match op {
            Op::Call(id) => Some(*id),
            _ => None,
        })
        .collect();
    // CALL Motor_Logic (block name), CALL SBR1 (number), CALL "Alarm Handler" (symbol → SBR2).
    assert_eq!(calls, [PouId(1), PouId(2), PouId(3)]);
    assert_eq!(p.counters.len(), 1);
    assert_eq!(
        (p.counters[0].id.0, p.counters[0].kind),
        (3, CounterKind::Up)
    );
    assert_eq!(p.edges.len(), 1);
    // CRLF line ends and tab indentation: the first SBR0 instruction is on line 19, column 2.
    assert_eq!((p.pous[1].locs[0].line, p.pous[1].locs[0].col), (19, 2));
}

#[test]
fn gbk_program_with_chinese_symbols_lowers_like_its_addresses() {
    use stljit_core::Area;
    use stljit_core::ir::{BitLoc, Contact, Op};
    let p = compile_case("ok/gbk_crlf.stl", Some("ok/gbk_crlf.symbols.txt"));
    let bit = |area, byte, bit| BitLoc { area, byte, bit };
    let c = |b, negated| Contact::Bit { bit: b, negated };
    assert_eq!(
        p.pous[0].ops[..4],
        [
            Op::Load(c(bit(Area::I, 0, 0), false)),
            Op::Or(c(bit(Area::Q, 0, 0), false)),
            Op::And(c(bit(Area::I, 0, 1), true)),
            Op::Assign {
                bit: bit(Area::Q, 0, 0),
                immediate: false
            },
        ]
    );
    // Columns count characters, not GBK or UTF-8 bytes.
    assert_eq!(p.pous[0].locs[0].line, 3);
}
