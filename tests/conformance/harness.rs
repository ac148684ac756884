//! The conformance runner behind `tests/conformance.rs`: reads a case file, compiles its program,
//! drives every engine through `stljit_sim`, and turns every mismatch into a
//! [`Failure`] that names the case file, the scan, the address, the engine, and both values.
//!
//! Case format: see `README.md` in this directory. Parsing is strict (unknown keys, bad
//! addresses and values that do not fit are errors) so that a typo cannot turn a check off.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};
use stljit_core::ir::{Address, Program};
use stljit_core::layout::{Block, Layout};
use stljit_core::{Area, Family, FatalCode, ProfileId, ScanStatus};
use stljit_diff::engines::EngineKind;
use stljit_front::{Dialect, Severity, SourceFile, render_human};
use stljit_jit::OptLevel;
use stljit_runtime::{Engine, Image};
use stljit_sim::{
    FnObserver, Format, Outcome, ScanEvent, Simulation, Stimulus, TimeBase, Until, ValueKind,
    WatchSpec, parse_value,
};
use toml::{Table, Value};

/// Builds an engine for a program; the error is a message.
pub(crate) type EngineCtor = fn(&Program) -> Result<Box<dyn Engine>, String>;
/// An engine's report name and constructor.
pub(crate) type EngineEntry = (&'static str, EngineCtor);

/// Every engine a case runs on. All of them run every case; none is ever skipped.
pub(crate) const ENGINES: &[EngineEntry] =
    &[("interp", interp), ("jit", jit), ("jit-split", jit_split)];

fn build(kind: EngineKind, p: &Program) -> Result<Box<dyn Engine>, String> {
    kind.build(p).map_err(|e| e.to_string())
}

fn interp(p: &Program) -> Result<Box<dyn Engine>, String> {
    build(EngineKind::Interp, p)
}

fn jit(p: &Program) -> Result<Box<dyn Engine>, String> {
    build(EngineKind::Jit(OptLevel::None), p)
}

/// The JIT with every basic block in a chunk function of its own: the cases are far shorter than
/// the default chunk size, so this runs them through the chunk dispatcher as well.
fn jit_split(p: &Program) -> Result<Box<dyn Engine>, String> {
    build(EngineKind::JitSplit(OptLevel::None), p)
}

/// One mismatch or error.
#[derive(Debug)]
pub(crate) struct Failure {
    file: String,
    scan: Option<usize>,
    what: Option<String>,
    engine: Option<String>,
    detail: String,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.file)?;
        let mut parts = Vec::new();
        if let Some(k) = self.scan {
            parts.push(format!("scan {k}"));
        }
        if let Some(w) = &self.what {
            parts.push(w.clone());
        }
        if !parts.is_empty() {
            f.write_str(&parts.join(", "))?;
        }
        if let Some(e) = &self.engine {
            if parts.is_empty() {
                write!(f, "[{e}]")?;
            } else {
                write!(f, " [{e}]")?;
            }
        }
        if !parts.is_empty() || self.engine.is_some() {
            f.write_str(": ")?;
        }
        f.write_str(&self.detail)
    }
}

/// Why a directory could not be run at all.
#[derive(Debug)]
pub(crate) enum HarnessError {
    /// The directory could not be listed.
    Io(PathBuf, io::Error),
    /// No `*.toml` case in it: a harness that checks nothing must not pass.
    NoCases(PathBuf),
}

impl fmt::Display for HarnessError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HarnessError::Io(p, e) => write!(f, "cannot read {}: {e}", p.display()),
            HarnessError::NoCases(p) => {
                write!(f, "no conformance cases (*.toml) in {}", p.display())
            }
        }
    }
}

/// Result of one case.
pub(crate) struct CaseResult {
    /// Everything that went wrong.
    pub(crate) failures: Vec<Failure>,
    /// Scans checked (per engine).
    pub(crate) scans: usize,
    /// The case's `known_failure` reason.
    pub(crate) known_failure: Option<String>,
}

/// Result of a directory.
#[derive(Debug)]
pub(crate) struct Summary {
    /// Case files run.
    pub(crate) cases: usize,
    /// Scans checked over all cases (per engine).
    pub(crate) scans: usize,
    /// Failures of cases not marked `known_failure` (and known failures that now pass).
    pub(crate) failures: Vec<Failure>,
    /// Reports of cases marked `known_failure` that still fail.
    pub(crate) known: Vec<String>,
}

/// Runs every `*.toml` case in `dir` on `engines`.
pub(crate) fn run_dir(dir: &Path, engines: &[EngineEntry]) -> Result<Summary, HarnessError> {
    let entries = std::fs::read_dir(dir).map_err(|e| HarnessError::Io(dir.to_path_buf(), e))?;
    let mut files: Vec<PathBuf> = Vec::new();
    // The cases of a dialect other than S7 live one folder down (`omron/`).
    for path in entries.flatten().map(|e| e.path()) {
        if path.is_dir() {
            let sub =
                std::fs::read_dir(&path).map_err(|e| HarnessError::Io(path.to_path_buf(), e))?;
            files.extend(sub.flatten().map(|e| e.path()));
        } else {
            files.push(path);
        }
    }
    files.retain(|p| p.extension().is_some_and(|x| x == "toml"));
    files.sort();
    if files.is_empty() {
        return Err(HarnessError::NoCases(dir.to_path_buf()));
    }
    let mut summary = Summary {
        cases: files.len(),
        scans: 0,
        failures: Vec::new(),
        known: Vec::new(),
    };
    for path in files {
        let file = path
            .strip_prefix(dir)
            .unwrap_or(&path)
            .to_string_lossy()
            .into_owned();
        let result = match std::fs::read_to_string(&path) {
            Ok(text) => run_case_text(&file, &text, engines),
            Err(e) => CaseResult {
                failures: vec![case_failure(&file, format!("cannot read: {e}"))],
                scans: 0,
                known_failure: None,
            },
        };
        summary.scans += result.scans;
        match (result.known_failure, result.failures.is_empty()) {
            (Some(reason), false) => {
                let lines: Vec<String> = result.failures.iter().map(|f| f.to_string()).collect();
                summary
                    .known
                    .push(format!("{file}: {reason}\n  {}", lines.join("\n  ")));
            }
            (Some(reason), true) => summary.failures.push(case_failure(
                &file,
                format!(
                    "marked known_failure (\"{reason}\") but passes on every engine: remove the \
                     marker"
                ),
            )),
            (None, _) => summary.failures.extend(result.failures),
        }
    }
    Ok(summary)
}

fn case_failure(file: &str, detail: String) -> Failure {
    Failure {
        file: file.to_string(),
        scan: None,
        what: None,
        engine: None,
        detail,
    }
}

/// What a scan must show.
struct ScanSpec {
    /// `(name, address, raw)` of every driven address.
    inputs: Vec<(String, Address, u32)>,
    expect: Vec<(WatchSpec, Want)>,
    /// L memory of call levels (`frame = { 1 = { "LW9" = … } }`).
    frames: Vec<super::frames::FrameExpect>,
    status: ScanStatus,
    fatal: Option<FatalCode>,
    last_err: Option<u16>,
    /// Counter activity and received bytes before the scan (`hsc = …`, `rx = …`).
    feed: super::feeds::ScanFeed,
    /// Physical output bits after the scan (`phys_q = { "Q0.0" = 1 }`).
    phys_q: Vec<(String, u32, u8, bool)>,
}

/// An expected value: a raw bit pattern, or a real compared by value (NaN matches NaN).
#[derive(Clone, Copy)]
enum Want {
    Raw(u32),
    Real(f32),
}

struct Case {
    dialect: Dialect,
    profile: ProfileId,
    /// The front-end options (`tc_mode`, `allow_backward_jumps`: Omron's).
    options: stljit_front::Options,
    scan_ms: u64,
    /// The date the real-time clock shows at t = 0 (s7-200-more §6.2 `rtc_start`).
    rtc_start: Option<stljit_runtime::rtc::DateTime>,
    program: String,
    scans: Vec<ScanSpec>,
    known_failure: Option<String>,
}

/// The program, profile and front-end options of a case given as text ([`run_case_text`]'s).
pub(crate) fn case_program(
    text: &str,
) -> Result<(String, ProfileId, stljit_front::Options), String> {
    let case = parse_case(text)?;
    Ok((case.program, case.profile, case.options))
}

/// Runs one case given as text (`file` names it in reports).
pub(crate) fn run_case_text(file: &str, text: &str, engines: &[EngineEntry]) -> CaseResult {
    let fail = |detail: String| CaseResult {
        failures: vec![case_failure(file, detail)],
        scans: 0,
        known_failure: None,
    };
    let case = match parse_case(text) {
        Ok(c) => c,
        Err(e) => return fail(e),
    };
    let known_failure = case.known_failure.clone();
    let with_known = |mut r: CaseResult| {
        r.known_failure = known_failure.clone();
        r
    };
    let program = match compile(file, &case) {
        Ok(p) => p,
        Err(e) => return with_known(fail(e)),
    };
    let stimulus = match stimulus(&case) {
        Ok(s) => s,
        Err(e) => return with_known(fail(e)),
    };
    let mut failures = Vec::new();
    let mut runs: Vec<(&str, Vec<(ScanStatus, Image)>)> = Vec::new();
    for &(name, ctor) in engines {
        let at = |scan: Option<usize>, what: Option<String>, detail: String| Failure {
            file: file.to_string(),
            scan,
            what,
            engine: Some(name.to_string()),
            detail,
        };
        let mut engine = match ctor(&program) {
            Ok(e) => e,
            Err(e) => {
                failures.push(at(None, None, format!("engine refused the program: {e}")));
                continue;
            }
        };
        let (records, outcome) = match run(&mut *engine, &program, &case, &stimulus) {
            Ok(r) => r,
            Err(e) => {
                failures.push(at(None, None, e));
                continue;
            }
        };
        if records.len() < case.scans.len() {
            failures.push(at(
                records.len().checked_sub(1),
                None,
                format!(
                    "run ended early ({outcome}) but the case lists {} scans",
                    case.scans.len()
                ),
            ));
        }
        for (k, ((status, image), spec)) in records.iter().zip(&case.scans).enumerate() {
            for (what, detail) in check_scan(image, *status, spec) {
                failures.push(at(Some(k), Some(what), detail));
            }
        }
        runs.push((name, records));
    }
    if let Some(((first, base), rest)) = runs.split_first() {
        for (other, records) in rest {
            for (k, ((_, a), (_, b))) in base.iter().zip(records).enumerate() {
                if let Some(detail) = image_diff(a, b) {
                    failures.push(Failure {
                        file: file.to_string(),
                        scan: Some(k),
                        what: Some("images differ".to_string()),
                        engine: Some(format!("{first} vs {other}")),
                        detail,
                    });
                    break;
                }
            }
        }
    }
    CaseResult {
        failures,
        scans: case.scans.len(),
        known_failure,
    }
}

type Records = Vec<(ScanStatus, Image)>;

fn run(
    engine: &mut dyn Engine,
    program: &Program,
    case: &Case,
    stimulus: &Stimulus,
) -> Result<(Records, Outcome), String> {
    let mut records = Vec::new();
    let mut image = Image::cold_start(program);
    if let Some(start) = case.rtc_start {
        image.set_clock_start(start);
    }
    let mut feed = super::feeds::Feed {
        inner: engine,
        scans: case.scans.iter().map(|s| s.feed.clone()).collect(),
        k: 0,
    };
    let mut sim = Simulation::new(&mut feed, image, case.scan_ms).map_err(|e| e.to_string())?;
    let mut rec = FnObserver(|e: &ScanEvent<'_>| {
        records.push((e.status, e.image.clone()));
        Ok(())
    });
    let n = case.scans.len() as u64;
    let report = sim
        .run(Until::Scans(n), stimulus, &mut rec)
        .map_err(|e| e.to_string())?;
    Ok((records, report.outcome))
}

/// Every mismatch of one scan as `(what, detail)`.
fn check_scan(image: &Image, status: ScanStatus, spec: &ScanSpec) -> Vec<(String, String)> {
    let mut out = Vec::new();
    if status != spec.status {
        out.push((
            "status".to_string(),
            format!("expected {:?}, got {status:?}", spec.status),
        ));
    }
    if let Some(code) = spec.fatal
        && image.fatal() != code as u16
    {
        let got = FatalCode::try_from(image.fatal())
            .map_or_else(|raw| format!("16#{raw:04X}"), |c| format!("{c:?}"));
        out.push(("fatal".to_string(), format!("expected {code:?}, got {got}")));
    }
    if let Some(code) = spec.last_err
        && image.last_error() != code
    {
        out.push((
            "last_err".to_string(),
            format!("expected 16#{code:04X}, got 16#{:04X}", image.last_error()),
        ));
    }
    out.extend(super::frames::check(image, &spec.frames));
    out.extend(super::phys_out::check(image, &spec.phys_q));
    for (watch, want) in &spec.expect {
        let Some(raw) = watch.read(image) else {
            out.push((watch.text.clone(), "address outside the image".to_string()));
            continue;
        };
        let ok = match *want {
            Want::Raw(w) => w == raw,
            Want::Real(w) => {
                let got = f32::from_bits(raw);
                got.to_bits() == w.to_bits() || (got.is_nan() && w.is_nan())
            }
        };
        if !ok {
            let shown = match *want {
                Want::Raw(w) => watch.format(w),
                Want::Real(w) => format!("{w:?}"),
            };
            out.push((
                watch.text.clone(),
                format!("expected {shown}, got {}", watch.format(raw)),
            ));
        }
    }
    out
}

/// Names the first differing byte of two images and counts the rest.
fn image_diff(a: &Image, b: &Image) -> Option<String> {
    let (x, y) = (a.bytes(), b.bytes());
    let diffs: Vec<usize> = (0..x.len().max(y.len()))
        .filter(|&i| x.get(i) != y.get(i))
        .collect();
    let &first = diffs.first()?;
    let byte = |s: &[u8]| {
        s.get(first)
            .map_or("--".to_string(), |v| format!("{v:02X}"))
    };
    Some(format!(
        "{}: {} vs {} ({} differing byte(s) in all)",
        region(a.layout(), first as u32),
        byte(x),
        byte(y),
        diffs.len()
    ))
}

/// Names an image offset for a failure message: the area and offset, or the private block it is in
/// or pads (blocks and their names from core's layout).
fn region(l: &Layout, off: u32) -> String {
    if let Some((area, o)) = l.locate(off) {
        return format!("{area:?} offset {o}");
    }
    Block::ALL
        .into_iter()
        .map(|block| (block, l.block_start(block)))
        .filter(|&(_, start)| start <= off)
        .max_by_key(|&(_, start)| start)
        .map_or(format!("image offset {off}"), |(block, start)| {
            format!("{} +{} (image offset {off})", block.name(), off - start)
        })
}

/// A wrapper engine that corrupts VB2499 after every scan: proves the image comparison works.
pub(crate) struct Skew(pub(crate) Box<dyn Engine>);

impl Engine for Skew {
    fn name(&self) -> &'static str {
        "skewed"
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        let status = self.0.scan(image, t_ms);
        let at = image.layout().base(Area::V) as usize + 2499;
        if let Some(b) = image.bytes_mut().get_mut(at) {
            *b ^= 0xFF;
        }
        status
    }
}

// ---- case files ---------------------------------------------------------------------------

fn resolver(dialect: Dialect, profile: ProfileId) -> impl Fn(&str) -> Result<Address, String> {
    move |name: &str| {
        dialect
            .parse_address(name, profile, None)
            .map_err(|e| e.message)
    }
}

fn compile(file: &str, case: &Case) -> Result<Program, String> {
    let source = SourceFile {
        name: file.to_string(),
        bytes: case.program.as_bytes().to_vec(),
    };
    let c = case
        .dialect
        .compile_with(&[source], None, case.profile, case.options);
    match c.program {
        Some(p) => Ok(p),
        None => {
            let errors: Vec<String> = c
                .diagnostics
                .iter()
                .filter(|d| d.severity == Severity::Error)
                .map(|d| render_human(d, &c.sources))
                .collect();
            Err(format!("program does not compile:\n{}", errors.join("\n")))
        }
    }
}

/// The input rule: an S7 scan drives the whole input image (every I bit not listed is 0,
/// spec a5-stl.md §7); an Omron scan changes only the input bits and words it lists, the rest
/// keep the previous scan's value (omron-cp.md §6 "Stimulus"). Other inputs become their own
/// columns, set only in the scans that list them.
fn stimulus(case: &Case) -> Result<Stimulus, String> {
    let profile = case.profile.profile();
    let resolve = resolver(case.dialect, case.profile);
    let mut s = Stimulus::empty(TimeBase::Scan, profile);
    let bytes = profile.inputs as usize;
    let held = profile.family == Family::Omron;
    // One column per input byte (S7: `IB0` …) or per input word (Omron: CIO `0` …).
    let unit = if held { 2 } else { 1 };
    for i in 0..bytes / unit {
        let name = if held {
            format!("{}", profile.omron.first_input_word as usize + i)
        } else {
            format!("IB{i}")
        };
        s.add_column(&name, &resolve)
            .map_err(|e| format!("{e:?}"))?;
    }
    let mut image = vec![0u8; bytes];
    let mut extra: Vec<(String, Address)> = Vec::new();
    for spec in &case.scans {
        for (name, address, _) in &spec.inputs {
            if input_area(address).is_none() && !extra.iter().any(|(_, a)| a == address) {
                s.add_column(name, &resolve)
                    .map_err(|e| format!("inputs: {e:?}"))?;
                extra.push((name.clone(), *address));
            }
        }
    }
    for (k, spec) in case.scans.iter().enumerate() {
        if !held {
            image.iter_mut().for_each(|b| *b = 0);
        }
        let mut cells = vec![None; extra.len()];
        for (name, address, raw) in &spec.inputs {
            match (input_area(address), address) {
                (Some(_), Address::Bit(b)) => {
                    if let Some(byte) = image.get_mut(b.byte as usize) {
                        *byte = (*byte & !(1 << b.bit)) | u8::from(*raw != 0) << b.bit;
                    }
                }
                (Some(_), Address::Value { loc, width }) => {
                    let be = raw.to_be_bytes();
                    let n = width.bytes() as usize;
                    for (i, v) in be[4 - n..].iter().enumerate() {
                        if let Some(byte) = image.get_mut(loc.offset as usize + i) {
                            *byte = *v;
                        }
                    }
                }
                (None, _) => {
                    let i = extra.iter().position(|(_, a)| a == address);
                    if let Some(i) = i {
                        cells[i] = Some(*raw);
                    } else {
                        return Err(format!("inputs: `{name}` has no column"));
                    }
                }
            }
        }
        let mut row: Vec<Option<u32>> = image
            .chunks(unit)
            .map(|c| Some(c.iter().fold(0, |w, &b| w << 8 | u32::from(b))))
            .collect();
        row.extend(cells);
        s.push_row(k as u64, row).map_err(|e| e.to_string())?;
    }
    Ok(s)
}

fn input_area(address: &Address) -> Option<()> {
    let area = match address {
        Address::Bit(b) => b.area,
        Address::Value { loc, .. } => loc.area,
    };
    (area == Area::I).then_some(())
}

const CASE_KEYS: &[&str] = &[
    "name",
    "dialect",
    "spec",
    "cpu",
    "scan_ms",
    "program",
    "scan",
    "known_failure",
    "tc_mode",
    "allow_backward_jumps",
    "rtc_start",
];
const SCAN_KEYS: &[&str] = &[
    "scan", "t_ms", "inputs", "expect", "frame", "status", "fatal", "last_err", "phys_q",
];

fn check_keys(t: &Table, allowed: &[&str], what: &str) -> Result<(), String> {
    match t.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(format!(
            "{what}: unknown key `{k}` (allowed: {})",
            allowed.join(", ")
        )),
        None => Ok(()),
    }
}

fn string<'a>(t: &'a Table, key: &str) -> Result<Option<&'a str>, String> {
    match t.get(key) {
        None => Ok(None),
        Some(Value::String(s)) => Ok(Some(s)),
        Some(_) => Err(format!("`{key}` must be a string")),
    }
}

fn uint(t: &Table, key: &str, what: &str) -> Result<Option<u64>, String> {
    match t.get(key) {
        None => Ok(None),
        Some(Value::Integer(i)) if *i >= 0 => Ok(Some(*i as u64)),
        Some(_) => Err(format!("{what}: `{key}` must be a non-negative integer")),
    }
}

fn parse_case(text: &str) -> Result<Case, String> {
    let t: Table = text
        .parse()
        .map_err(|e: toml::de::Error| format!("not valid TOML: {e}"))?;
    check_keys(&t, CASE_KEYS, "case")?;
    for key in ["name", "spec", "program"] {
        if string(&t, key)?.is_none() {
            return Err(format!("missing `{key}`"));
        }
    }
    let dialect_name = string(&t, "dialect")?.unwrap_or("s7");
    let dialect =
        Dialect::from_name(dialect_name).ok_or(format!("unknown dialect `{dialect_name}`"))?;
    let profile = match string(&t, "cpu")? {
        None => dialect.default_profile(),
        Some(cpu) => ProfileId::from_name(cpu)
            .filter(|p| dialect.profiles().contains(p))
            .ok_or(format!("unknown cpu `{cpu}` for dialect `{dialect_name}`"))?,
    };
    let mut options = stljit_front::Options::default();
    if let Some(mode) = string(&t, "tc_mode")? {
        options.omron.tc_mode = stljit_front::TcMode::from_name(mode)
            .ok_or(format!("unknown tc_mode `{mode}` (bcd, binary)"))?;
    }
    match t.get("allow_backward_jumps") {
        None => {}
        Some(Value::Boolean(b)) => options.omron.allow_backward_jumps = *b,
        Some(_) => return Err("`allow_backward_jumps` must be true or false".to_string()),
    }
    if options != stljit_front::Options::default() && dialect != Dialect::Omron {
        return Err("`tc_mode` and `allow_backward_jumps` are options of the omron dialect".into());
    }
    let rtc_start = string(&t, "rtc_start")?
        .map(stljit_runtime::rtc::DateTime::parse)
        .transpose()
        .map_err(|e| format!("rtc_start: {e}"))?;
    let scan_ms = uint(&t, "scan_ms", "case")?.unwrap_or(10);
    if scan_ms == 0 {
        return Err("`scan_ms` must be at least 1".to_string());
    }
    let resolve = resolver(dialect, profile);
    let family = profile.profile().family;
    let Some(Value::Array(rows)) = t.get("scan") else {
        return Err("no `[[scan]]` entries".to_string());
    };
    if rows.is_empty() {
        return Err("no `[[scan]]` entries".to_string());
    }
    let mut scans = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        let Value::Table(row) = row else {
            return Err(format!("scan {k}: must be a table"));
        };
        let spec =
            parse_scan(row, k, scan_ms, &resolve, family).map_err(|e| format!("scan {k}: {e}"))?;
        if let Some(prev) = scans.last().map(|s: &ScanSpec| s.status)
            && prev != ScanStatus::Ok
        {
            return Err(format!(
                "scan {k}: listed after a scan that ends in {prev:?} (the run stops there)"
            ));
        }
        scans.push(spec);
    }
    Ok(Case {
        dialect,
        profile,
        options,
        scan_ms,
        rtc_start,
        program: string(&t, "program")?.unwrap_or_default().to_string(),
        scans,
        known_failure: string(&t, "known_failure")?.map(str::to_string),
    })
}

fn parse_scan(
    row: &Table,
    k: usize,
    scan_ms: u64,
    resolve: &dyn Fn(&str) -> Result<Address, String>,
    family: Family,
) -> Result<ScanSpec, String> {
    check_keys(row, &[SCAN_KEYS, super::feeds::KEYS].concat(), "scan")?;
    if let Some(n) = uint(row, "scan", "scan")?
        && n != k as u64
    {
        return Err(format!(
            "`scan = {n}` but this is entry {k} (list every scan in order)"
        ));
    }
    if let Some(t) = uint(row, "t_ms", "scan")?
        && t != k as u64 * scan_ms
    {
        return Err(format!(
            "`t_ms = {t}` but scan {k} starts at {} (scan_ms = {scan_ms})",
            k as u64 * scan_ms
        ));
    }
    let table = |key: &str| match row.get(key) {
        None => Ok(Table::new()),
        Some(Value::Table(t)) => Ok(t.clone()),
        Some(_) => Err(format!("`{key}` must be a table")),
    };
    let mut inputs = Vec::new();
    for (name, v) in &table("inputs")? {
        let address = resolve(name).map_err(|e| format!("inputs: `{name}`: {e}"))?;
        let raw =
            raw_value(v, ValueKind::of(&address)).map_err(|e| format!("inputs: `{name}`: {e}"))?;
        inputs.push((name.clone(), address, raw));
    }
    let mut expect = Vec::new();
    for (name, v) in &table("expect")? {
        let watch =
            WatchSpec::parse_for(name, resolve, family).map_err(|e| format!("expect: {e}"))?;
        let want = if watch.format == Format::Real {
            match v {
                Value::Float(f) => Want::Real(*f as f32),
                Value::Integer(i) => Want::Real(*i as f32),
                _ => Want::Raw(raw_value(v, ValueKind::of(&watch.address))?),
            }
        } else {
            Want::Raw(
                raw_value(v, ValueKind::of(&watch.address))
                    .map_err(|e| format!("expect: `{name}`: {e}"))?,
            )
        };
        expect.push((watch, want));
    }
    let frames = super::frames::parse(&table("frame")?, resolve, &raw_value)?;
    let status = match string(row, "status")? {
        None | Some("ok") => ScanStatus::Ok,
        Some("stopped") => ScanStatus::Stopped,
        Some("fatal") => ScanStatus::Fatal,
        Some(other) => return Err(format!("unknown status `{other}` (ok, stopped, fatal)")),
    };
    let fatal = match string(row, "fatal")? {
        None => None,
        Some(name) => Some(
            FatalCode::ALL
                .iter()
                .copied()
                .find(|c| format!("{c:?}") == name)
                .ok_or(format!("unknown fatal code `{name}`"))?,
        ),
    };
    if fatal.is_some() && status != ScanStatus::Fatal {
        return Err("`fatal` needs `status = \"fatal\"`".to_string());
    }
    let last_err = match uint(row, "last_err", "scan")? {
        None => None,
        Some(v) => Some(u16::try_from(v).map_err(|_| "`last_err` must fit 16 bits".to_string())?),
    };
    Ok(ScanSpec {
        feed: super::feeds::ScanFeed::parse(row)?,
        phys_q: super::phys_out::parse(&table("phys_q")?)?,
        inputs,
        expect,
        frames,
        status,
        fatal,
        last_err,
    })
}

fn raw_value(v: &Value, kind: ValueKind) -> Result<u32, String> {
    let text = match v {
        Value::Integer(i) => i.to_string(),
        Value::String(s) => s.clone(),
        Value::Boolean(b) if kind == ValueKind::Bit => u8::from(*b).to_string(),
        Value::Float(f) => format!("{f:?}"),
        _ => return Err(format!("unsupported value {v}")),
    };
    parse_value(&text, kind).map_err(|e| format!("`{text}`: {e}"))
}
