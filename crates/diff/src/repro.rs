//! Reproducer directories: what a divergence leaves behind, and what `tests/regressions/` holds.
//!
//! ```text
//! program.ir     the program in the IR text form (`stljit_core::text`); what is read back
//! program.stl    the same program printed as S7 STL, for reading only (never read back);
//! program.omr    for an Omron profile instead: the program printed as Omron mnemonics
//! stimulus.csv   inputs, analog inputs, HMI writes, high-speed counter steps (`HSCn`) and
//!                received bytes (`PORTn`) per scan, in stljit_sim's CSV format, addresses spelled in the program's dialect
//!                (Omron: input words `0`, `1`)
//! meta           key = value lines: profile, seed, engines, loop limit, the time of every scan
//! README.txt     what failed: the scan, the first differing bytes with both values, the seed
//! ```
//! `stimulus.csv` uses scan numbers; scan times need not be regular, so they are listed in
//! `meta` (`times = ...`), which is what [`read_case`] uses to replay a case exactly.

use crate::generate::{Case, HmiWrite, Received, ScanInput, Stimulus};
use crate::oracle::{FUZZ_LOOP_LIMIT, Finding};
use std::collections::BTreeMap;
use std::fmt::{self, Write as _};
use std::path::Path;
use stljit_core::ir::{Address, BitLoc, Loc};
use stljit_core::text::{self, ParseError};
use stljit_core::{Area, Family, ProfileId, Width};
use stljit_sim as sim;

/// Facts about a case that are not in the program or the stimulus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Meta {
    /// The CPU profile.
    pub profile: ProfileId,
    /// The program seed, when the case came from the generator.
    pub seed: Option<u64>,
    /// The two engines compared, by name.
    pub engines: String,
    /// The loop budget per scan.
    pub loop_limit: u32,
}

impl Meta {
    /// Meta for a generated case.
    pub fn new(profile: ProfileId, seed: Option<u64>, engines: &str) -> Meta {
        Meta {
            profile,
            seed,
            engines: engines.to_owned(),
            loop_limit: FUZZ_LOOP_LIMIT,
        }
    }
}

/// Why a reproducer directory could not be read.
#[derive(Debug)]
pub enum ReproError {
    /// A file could not be read or written.
    Io(std::path::PathBuf, std::io::Error),
    /// `meta` is malformed.
    Meta(String),
    /// `program.ir` does not parse.
    Program(ParseError),
    /// `stimulus.csv` is malformed.
    Stimulus(String),
}

impl fmt::Display for ReproError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReproError::Io(p, e) => write!(f, "{}: {e}", p.display()),
            ReproError::Meta(m) => write!(f, "meta: {m}"),
            ReproError::Program(e) => write!(f, "program.ir: {e}"),
            ReproError::Stimulus(m) => write!(f, "stimulus.csv: {m}"),
        }
    }
}

impl std::error::Error for ReproError {}

/// `a` spelled in the dialect of `profile`.
fn name(profile: ProfileId, a: &Address) -> String {
    match profile.profile().family {
        Family::S7 => stljit_front_s7::print_address(a),
        Family::Omron => stljit_front_omron::print_address(a),
    }
}

/// The name of a program's text in its dialect: `program.stl` or `program.omr`.
pub fn dialect_file(profile: ProfileId) -> &'static str {
    match profile.profile().family {
        Family::S7 => "program.stl",
        Family::Omron => "program.omr",
    }
}

/// The input unit of a dialect's stimulus columns: S7 input bytes (`IB0`), Omron input words
/// (CIO `0`, `1`).
fn input_width(profile: ProfileId) -> Width {
    match profile.profile().family {
        Family::S7 => Width::Byte,
        Family::Omron => Width::Word,
    }
}

/// The stimulus as stljit_sim CSV: one column per input byte (Omron: input word), analog word
/// or HMI address that is ever non-zero or written, one row per scan where something changes.
pub fn stimulus_csv(profile: ProfileId, s: &Stimulus) -> String {
    let p = profile.profile();
    let width = input_width(profile);
    let unit = width.bytes() as usize;
    let mut cols: Vec<Address> = Vec::new();
    let input = |x: &ScanInput, i: usize| -> Option<u32> {
        let bytes = x.inputs.get(i..i + unit)?;
        Some(bytes.iter().fold(0, |v, &b| v << 8 | u32::from(b)))
    };
    let nonzero_in = |i: usize| s.scans.iter().any(|x| input(x, i).is_some_and(|v| v != 0));
    let nonzero_ai = |i: usize| s.scans.iter().any(|x| x.ai.get(i).is_some_and(|&w| w != 0));
    for i in (0..p.inputs as usize).step_by(unit) {
        if nonzero_in(i) {
            cols.push(Address::Value {
                loc: Loc {
                    area: Area::I,
                    offset: i as u32,
                },
                width,
            });
        }
    }
    for i in 0..(p.analog_inputs / 2) as usize {
        if nonzero_ai(i) {
            cols.push(Address::Value {
                loc: Loc {
                    area: Area::AI,
                    offset: 2 * i as u32,
                },
                width: Width::Word,
            });
        }
    }
    for w in s.scans.iter().flat_map(|x| &x.writes) {
        if !cols.contains(&w.addr) {
            cols.push(w.addr);
        }
    }
    // High-speed counters with any activity: `HSCn` columns, held like the inputs.
    let counters = s.scans.iter().map(|x| x.hsc.len()).max().unwrap_or(0);
    let hsc: Vec<usize> = (0..counters)
        .filter(|&n| {
            s.scans
                .iter()
                .any(|x| x.hsc.get(n).is_some_and(|&v| v != 0))
        })
        .collect();
    let mut out = String::from("scan");
    for c in &cols {
        let _ = write!(out, ",{}", name(profile, c));
    }
    for n in &hsc {
        let _ = write!(out, ",HSC{n}");
    }
    // Serial ports that receive anything: `PORTn` columns, one-shot per scan.
    let mut ports: Vec<u8> = s
        .scans
        .iter()
        .flat_map(|x| x.rx.iter().filter(|r| !r.1.is_empty()).map(|r| r.0))
        .collect();
    ports.sort_unstable();
    ports.dedup();
    for n in &ports {
        let _ = write!(out, ",PORT{n}");
    }
    out.push('\n');
    let mut prev: Vec<Option<u32>> = vec![Some(0); cols.len()];
    let mut prev_hsc = vec![0; hsc.len()];
    for (k, x) in s.scans.iter().enumerate() {
        let cells: Vec<Option<u32>> = cols
            .iter()
            .map(|c| match *c {
                Address::Value { loc, .. } if loc.area == Area::I => input(x, loc.offset as usize),
                Address::Value { loc, .. } if loc.area == Area::AI => {
                    x.ai.get(loc.offset as usize / 2).map(|&w| u32::from(w))
                }
                _ => x
                    .writes
                    .iter()
                    .rev()
                    .find(|w| w.addr == *c)
                    .map(|w| w.value),
            })
            .collect();
        let changed: Vec<Option<u32>> = cells
            .iter()
            .zip(&cols)
            .enumerate()
            .map(|(i, (v, c))| {
                let held = matches!(c, Address::Value { loc, .. } if matches!(loc.area, Area::I | Area::AI));
                if held && *v == prev[i] { None } else { *v }
            })
            .collect();
        let steps: Vec<i32> = hsc
            .iter()
            .map(|&n| x.hsc.get(n).copied().unwrap_or(0))
            .collect();
        let changed_hsc: Vec<Option<i32>> = steps
            .iter()
            .zip(&prev_hsc)
            .map(|(&v, &p)| (v != p).then_some(v))
            .collect();
        let received: Vec<Option<&[u8]>> = ports
            .iter()
            .map(|&n| {
                x.rx.iter()
                    .find(|r| r.0 == n && !r.1.is_empty())
                    .map(|r| r.1.as_slice())
            })
            .collect();
        if k == 0
            || changed.iter().any(Option::is_some)
            || changed_hsc.iter().any(Option::is_some)
            || received.iter().any(Option::is_some)
        {
            let _ = write!(out, "{k}");
            for v in &changed {
                match v {
                    Some(v) => {
                        let _ = write!(out, ",{v}");
                    }
                    None => out.push(','),
                }
            }
            for v in &changed_hsc {
                match v {
                    Some(v) => {
                        let _ = write!(out, ",{v}");
                    }
                    None => out.push(','),
                }
            }
            for bytes in &received {
                out.push(',');
                if let Some(bytes) = bytes {
                    out.push_str("16#");
                    for b in *bytes {
                        let _ = write!(out, "{b:02X}");
                    }
                }
            }
            out.push('\n');
        }
        prev_hsc = steps;
        for (i, v) in cells.into_iter().enumerate() {
            if v.is_some() {
                prev[i] = v;
            }
        }
    }
    out
}

/// The `meta` file.
pub fn meta_text(meta: &Meta, s: &Stimulus) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "profile = {}", meta.profile.name());
    if let Some(seed) = meta.seed {
        let _ = writeln!(out, "seed = {seed}");
    }
    let _ = writeln!(out, "engines = {}", meta.engines);
    let _ = writeln!(out, "loop_limit = {}", meta.loop_limit);
    let _ = writeln!(out, "scans = {}", s.len());
    let times: Vec<String> = s.scans.iter().map(|x| x.t_ms.to_string()).collect();
    let _ = writeln!(out, "times = {}", times.join(" "));
    out
}

/// Writes a reproducer directory (created if missing).
pub fn write_repro(
    dir: &Path,
    case: &Case,
    meta: &Meta,
    finding: Option<&Finding>,
) -> Result<(), ReproError> {
    let io = |e| ReproError::Io(dir.to_path_buf(), e);
    std::fs::create_dir_all(dir).map_err(io)?;
    let put = |file: &str, text: String| {
        std::fs::write(dir.join(file), text).map_err(|e| ReproError::Io(dir.join(file), e))
    };
    put("program.ir", text::print(&case.program))?;
    let dialect_text = crate::roundtrip::dialect_text(&case.program)
        .unwrap_or_else(|e| format!("; no text in this dialect: {e}\n"));
    put(dialect_file(meta.profile), dialect_text)?;
    put("stimulus.csv", stimulus_csv(meta.profile, &case.stimulus))?;
    put("meta", meta_text(meta, &case.stimulus))?;
    let mut readme = String::new();
    let _ = writeln!(
        readme,
        "stljit differential fuzzing reproducer ({} ops, {} scans, profile {}).\n",
        case.program.op_count(),
        case.stimulus.len(),
        meta.profile.name()
    );
    match finding {
        Some(f) => {
            let _ = writeln!(readme, "{f}");
        }
        None => readme.push_str("No failure recorded: the engines agreed.\n"),
    }
    if let Some(seed) = meta.seed {
        let _ = writeln!(
            readme,
            "Program seed: {seed} (stljit_diff::generate::generate_in({:?}, \
             Choices::from_seed(seed)); `stljit fuzz` prints the campaign seed and index).",
            meta.profile.profile().family
        );
    }
    if meta.profile.profile().family == Family::Omron
        && stljit_front_omron::printed_options(&case.program).allow_backward_jumps
    {
        let _ = writeln!(
            readme,
            "`program.omr` jumps backward: compile it with --allow-backward-jumps."
        );
    }
    let _ = writeln!(
        readme,
        "Engines: {}; loop budget per scan: {}.\nThe program is `program.ir` (IR text, \
         docs/ir-text.md); `{}` is the same program in its dialect, for reading.\nScan times \
         (ms) are listed in `meta`; `stimulus.csv` gives inputs per scan number.\nReplay: `cargo test --release -p \
         stljit-harness regressions` once this directory is in tests/regressions/.",
        meta.engines,
        meta.loop_limit,
        dialect_file(meta.profile)
    );
    put("README.txt", readme)
}

fn read(dir: &Path, file: &str) -> Result<String, ReproError> {
    std::fs::read_to_string(dir.join(file)).map_err(|e| ReproError::Io(dir.join(file), e))
}

/// Parses a `meta` file into its fields and the scan times.
pub fn parse_meta(text: &str) -> Result<(Meta, Vec<u64>), ReproError> {
    let kv: BTreeMap<&str, &str> = text
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .filter_map(|l| l.split_once('='))
        .map(|(k, v)| (k.trim(), v.trim()))
        .collect();
    let profile = kv
        .get("profile")
        .and_then(|p| ProfileId::from_name(p))
        .ok_or_else(|| ReproError::Meta("missing or unknown `profile`".into()))?;
    let num = |k: &str| -> Result<Option<u64>, ReproError> {
        kv.get(k)
            .map(|v| {
                v.parse()
                    .map_err(|_| ReproError::Meta(format!("bad `{k}`")))
            })
            .transpose()
    };
    let times: Vec<u64> = match kv.get("times") {
        Some(t) => t
            .split_whitespace()
            .map(|x| {
                x.parse()
                    .map_err(|_| ReproError::Meta(format!("bad time `{x}`")))
            })
            .collect::<Result<_, _>>()?,
        None => {
            let n =
                num("scans")?.ok_or_else(|| ReproError::Meta("no `scans` or `times`".into()))?;
            (0..n).map(|k| 10 * k).collect()
        }
    };
    let meta = Meta {
        profile,
        seed: num("seed")?,
        engines: kv.get("engines").copied().unwrap_or("").to_owned(),
        loop_limit: num("loop_limit")?.map_or(FUZZ_LOOP_LIMIT, |v| v as u32),
    };
    Ok((meta, times))
}

/// Builds a per-scan stimulus from stljit_sim CSV text and the scan times.
pub fn parse_stimulus(
    profile: ProfileId,
    csv: &str,
    times: &[u64],
) -> Result<Stimulus, ReproError> {
    let p = profile.profile();
    let resolve = |s: &str| -> Result<Address, String> {
        match p.family {
            Family::S7 => stljit_front_s7::parse_address(s, p, None).map_err(|e| e.to_string()),
            Family::Omron => {
                stljit_front_omron::parse_address(s, profile, None).map_err(|e| e.to_string())
            }
        }
    };
    let st =
        sim::Stimulus::parse(csv, p, &resolve).map_err(|e| ReproError::Stimulus(e.to_string()))?;
    if st.time_base() != sim::TimeBase::Scan {
        return Err(ReproError::Stimulus("reproducers use scan numbers".into()));
    }
    let mut inputs = vec![0u8; p.inputs as usize];
    let mut ai = vec![0u16; (p.analog_inputs / 2) as usize];
    let mut hsc = vec![0i32; p.hsc.counters.len()];
    let mut rows = st.rows().iter().peekable();
    let mut scans = Vec::with_capacity(times.len());
    for (k, &t) in times.iter().enumerate() {
        let mut writes = Vec::new();
        let mut rx: Received = Vec::new();
        while let Some(row) = rows.next_if(|r| r.at <= k as u64) {
            for (col, cell) in st.columns().iter().zip(&row.cells) {
                let (address, v) = match (col.target, cell.as_ref()) {
                    (_, None) => continue,
                    (sim::Target::Address(a), Some(&sim::Cell::Value(v))) => (a, v),
                    (sim::Target::HscSteps(n), Some(&sim::Cell::Steps(v))) => {
                        if let Some(h) = hsc.get_mut(usize::from(n)) {
                            *h = v;
                        }
                        continue;
                    }
                    (sim::Target::Receive(n), Some(sim::Cell::Bytes(b))) => {
                        if !b.is_empty() && rx.iter().all(|r| r.0 != n) {
                            rx.push((n, b.clone()));
                        }
                        continue;
                    }
                    (_, Some(_)) => {
                        return Err(ReproError::Stimulus(format!(
                            "line {}: a `{}` cell of the wrong kind",
                            row.line, col.name
                        )));
                    }
                };
                match address {
                    Address::Value { loc, width } if loc.area == Area::I => {
                        for i in 0..width.bytes() {
                            if let Some(b) = inputs.get_mut((loc.offset + i) as usize) {
                                *b = (v >> (8 * (width.bytes() - 1 - i))) as u8;
                            }
                        }
                    }
                    Address::Bit(BitLoc {
                        area: Area::I,
                        byte,
                        bit,
                    }) => {
                        if let Some(b) = inputs.get_mut(byte as usize) {
                            *b = (*b & !(1 << bit)) | (((v & 1) as u8) << bit);
                        }
                    }
                    Address::Value { loc, .. } if loc.area == Area::AI => {
                        if let Some(w) = ai.get_mut(loc.offset as usize / 2) {
                            *w = v as u16;
                        }
                    }
                    addr => writes.push(HmiWrite { addr, value: v }),
                }
            }
        }
        scans.push(ScanInput {
            t_ms: t,
            inputs: inputs.clone(),
            ai: ai.clone(),
            writes,
            hsc: hsc.clone(),
            rx,
        });
    }
    Ok(Stimulus { scans })
}

/// Reads a reproducer directory back into a case.
pub fn read_case(dir: &Path) -> Result<(Case, Meta), ReproError> {
    let (meta, times) = parse_meta(&read(dir, "meta")?)?;
    let program = text::parse(&read(dir, "program.ir")?).map_err(ReproError::Program)?;
    if program.profile != meta.profile {
        return Err(ReproError::Meta(format!(
            "profile {} but program.ir is for {}",
            meta.profile.name(),
            program.profile.name()
        )));
    }
    let stimulus = parse_stimulus(meta.profile, &read(dir, "stimulus.csv")?, &times)?;
    Ok((Case { program, stimulus }, meta))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{GenConfig, case_from_seed};

    /// Writes `case` as a reproducer in `dir` and reads it back: the same meta, program and
    /// stimulus.
    fn reads_back(dir: &Path, case: &Case, seed: u64) {
        let meta = Meta::new(case.program.profile, Some(seed), "interp jit(none)");
        write_repro(dir, case, &meta, None).unwrap();
        let (back, m) = read_case(dir).unwrap();
        assert_eq!(m, meta);
        assert_eq!(back.program, case.program, "seed {seed}");
        assert_eq!(back.stimulus, case.stimulus, "seed {seed}");
    }

    /// High-speed counter activity travels as `HSCn` columns of `stimulus.csv` and reads back
    /// per scan, held from row to row like the inputs.
    #[test]
    fn repro_directory_reads_back_the_same_case() {
        let dir = std::env::temp_dir().join(format!("stljit-repro-test-{}", std::process::id()));
        let mut hsc_columns = 0;
        for seed in 0..40 {
            reads_back(&dir, &case_from_seed(seed, &GenConfig::default()), seed);
            let csv = std::fs::read_to_string(dir.join("stimulus.csv")).unwrap();
            hsc_columns += csv.lines().next().unwrap().matches(",HSC").count();
        }
        assert!(
            hsc_columns > 0,
            "no generated case drove a high-speed counter"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Received bytes travel as `PORTn` columns of `stimulus.csv` (one-shot per scan) and read
    /// back exactly, in the generator's shape.
    #[test]
    fn received_bytes_read_back() {
        let dir = std::env::temp_dir().join(format!("stljit-repro-rx-{}", std::process::id()));
        let mut cases = 0;
        for seed in 0..400 {
            let case = case_from_seed(seed, &GenConfig::default());
            if case.stimulus.scans.iter().any(|s| !s.rx.is_empty()) {
                cases += 1;
                reads_back(&dir, &case, seed);
            }
        }
        assert!(cases > 10, "only {cases} cases with received bytes");
        let _ = std::fs::remove_dir_all(&dir);
        let st = parse_stimulus(
            ProfileId::A5,
            "scan,PORT0,PORT1\n0,,16#41\n1,16#0D0A,\n",
            &[0, 10, 20],
        )
        .unwrap();
        let rx: Vec<_> = st.scans.iter().map(|s| s.rx.clone()).collect();
        assert_eq!(
            rx,
            vec![vec![(1, vec![0x41])], vec![(0, vec![0x0D, 0x0A])], vec![]]
        );
    }

    /// Omron cases too: the stimulus in Omron spelling (input words, D/W/H addresses) reads
    /// back to the same per-scan inputs and writes, and `program.omr` compiles to the program.
    #[test]
    fn omron_repro_directory_reads_back_the_same_case() {
        let dir = std::env::temp_dir().join(format!("stljit-repro-omron-{}", std::process::id()));
        let mut writes = 0;
        for seed in 0..40 {
            let mut c = crate::rng::Choices::from_seed(seed);
            let case = crate::generate::omron::generate(&mut c, &GenConfig::default())
                .expect("generated programs compile")
                .case;
            writes += case
                .stimulus
                .scans
                .iter()
                .map(|s| s.writes.len())
                .sum::<usize>();
            reads_back(&dir, &case, seed);
            let omr = std::fs::read_to_string(dir.join("program.omr")).unwrap();
            let compiled = crate::roundtrip::compile_dialect(&omr, &case.program).unwrap();
            assert_eq!(
                crate::roundtrip::normalized(&compiled),
                crate::roundtrip::normalized(&case.program)
            );
        }
        assert!(writes > 20, "only {writes} HMI writes");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
