//! One FMU instance in safe Rust: the PLC built from the FMU's resources, its variables by value
//! reference, the communication time and the FMI 2.0 co-simulation state machine. The C
//! functions (`exports`) only translate pointers and statuses around these methods.
//!
//! Time: FMU time `t` maps to virtual time `(t - startTime) · 1000` ms, rounded to the ms.
//! `fmi2DoStep(t, h)` runs every scan that starts in `[t, t + h)`, so a step shorter than the scan
//! time may run no scan and a longer one several. Inputs set before a step reach the program at
//! the step's first scan (an input bit or word goes to the physical input copy, read by the scan's
//! input refresh); outputs read after a step are the image after its last scan.

use std::path::{Path, PathBuf};
use stljit_api::{Handle, Options, Outcome, Plc, Project, Snapshot, Value};
use stljit_fmu::{Causality, FmiType, Manifest, Variable};

/// Where an instance is in the FMI 2.0 co-simulation state machine (§4.2.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum State {
    /// After `fmi2Instantiate` or `fmi2Reset`.
    Instantiated,
    /// Between `fmi2EnterInitializationMode` and `fmi2ExitInitializationMode`.
    Initialization,
    /// Stepping.
    StepComplete,
    /// After `fmi2Terminate`.
    Terminated,
}

/// What an FMI call reports besides success.
#[derive(Debug, PartialEq, Eq)]
pub enum Problem {
    /// Worth a warning; the call did its work (a PLC that stopped on a fatal error).
    Warning(String),
    /// The call was refused or failed; nothing (more) was done.
    Error(String),
}

fn error<T>(message: impl Into<String>) -> Result<T, Problem> {
    Err(Problem::Error(message.into()))
}

/// A saved FMU state: the PLC's snapshot and the communication time.
#[derive(Clone, Debug)]
pub struct FmuState {
    snapshot: Snapshot,
    time: f64,
}

impl FmuState {
    /// The state as bytes (FMI's serialized state): the time, then the snapshot.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = self.time.to_le_bytes().to_vec();
        out.extend_from_slice(&self.snapshot.to_bytes());
        out
    }

    /// Reads `to_bytes`' output.
    pub fn from_bytes(bytes: &[u8]) -> Result<FmuState, Problem> {
        let (time, rest) = bytes
            .split_first_chunk::<8>()
            .ok_or_else(|| Problem::Error("serialized FMU state is truncated".into()))?;
        let snapshot = Snapshot::from_bytes(rest).map_err(|e| Problem::Error(e.to_string()))?;
        Ok(FmuState {
            snapshot,
            time: f64::from_le_bytes(*time),
        })
    }
}

/// One instantiated FMU.
pub struct Instance {
    plc: Plc,
    variables: Vec<(Variable, Handle)>,
    state: State,
    start: f64,
    time: f64,
    stopped_reported: bool,
}

impl std::fmt::Debug for Instance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Instance")
            .field("state", &self.state)
            .field("time", &self.time)
            .finish_non_exhaustive()
    }
}

/// The directory a `fmuResourceLocation` URI names (`file:///path`, `file:/path`,
/// `file://localhost/path`, percent-encoded).
pub fn resource_dir(uri: &str) -> Result<PathBuf, String> {
    let rest = uri
        .strip_prefix("file://localhost/")
        .map(|r| format!("/{r}"))
        .or_else(|| uri.strip_prefix("file:///").map(|r| format!("/{r}")))
        .or_else(|| uri.strip_prefix("file:/").map(|r| format!("/{r}")))
        .ok_or_else(|| format!("resource location `{uri}` is not a file: URI"))?;
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%'
            && let Some(h) = rest.get(i + 1..i + 3)
            && let Ok(b) = u8::from_str_radix(h, 16)
        {
            out.push(b);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    let path =
        String::from_utf8(out).map_err(|_| format!("resource location `{uri}` is not UTF-8"))?;
    // Windows: `file:///C:/dir` names `C:/dir`.
    let path = match path.as_bytes() {
        [b'/', d, b':', ..] if d.is_ascii_alphabetic() => path[1..].to_string(),
        _ => path,
    };
    Ok(PathBuf::from(path))
}

impl Instance {
    /// Builds the PLC from the FMU's resources, checking the GUID.
    pub fn new(resources: &Path, guid: &str) -> Result<Instance, Problem> {
        let manifest_path = resources.join("stljit.txt");
        let text = std::fs::read_to_string(&manifest_path)
            .map_err(|e| Problem::Error(format!("cannot read {}: {e}", manifest_path.display())))?;
        let m = Manifest::parse(&text).map_err(|e| Problem::Error(e.to_string()))?;
        if m.guid != guid {
            return error(format!(
                "GUID mismatch: the master gave {guid}, this FMU is {}",
                m.guid
            ));
        }
        let api = |e: stljit_api::Error| Problem::Error(e.to_string());
        let mut project = Project::new()
            .dialect(stljit_api::dialect_named(&m.dialect).map_err(api)?)
            .cpu(&m.cpu);
        for f in &m.files {
            project = project.file(resources.join(f)).map_err(api)?;
        }
        if let Some(s) = &m.symbols {
            project = project.symbols_file(resources.join(s)).map_err(api)?;
        }
        let options = Options {
            scan_ms: m.scan_ms,
            ..Options::default()
        };
        let plc = Plc::compile(&project, &options).map_err(api)?;
        let mut variables = Vec::with_capacity(m.variables.len());
        for v in m.variables {
            let h = plc.handle(&v.spec).map_err(api)?;
            if FmiType::of(h.ty()) != v.ty {
                return error(format!(
                    "variable {} ({}) is {} in the manifest but {} in the program",
                    v.name,
                    v.spec,
                    v.ty.name(),
                    h.ty().name()
                ));
            }
            variables.push((v, h));
        }
        Ok(Instance {
            plc,
            variables,
            state: State::Instantiated,
            start: 0.0,
            time: 0.0,
            stopped_reported: false,
        })
    }

    /// The state machine's state.
    pub fn state(&self) -> State {
        self.state
    }

    /// The communication time.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The PLC.
    pub fn plc(&self) -> &Plc {
        &self.plc
    }

    /// `fmi2SetupExperiment`.
    pub fn setup(&mut self, start: f64) -> Result<(), Problem> {
        if self.state != State::Instantiated {
            return error("fmi2SetupExperiment is allowed only after fmi2Instantiate or fmi2Reset");
        }
        if !start.is_finite() {
            return error(format!("start time {start} is not finite"));
        }
        self.start = start;
        self.time = start;
        Ok(())
    }

    /// `fmi2EnterInitializationMode`.
    pub fn enter_initialization(&mut self) -> Result<(), Problem> {
        if self.state != State::Instantiated {
            return error("fmi2EnterInitializationMode is allowed only once, after instantiation");
        }
        self.state = State::Initialization;
        Ok(())
    }

    /// `fmi2ExitInitializationMode`.
    pub fn exit_initialization(&mut self) -> Result<(), Problem> {
        if self.state != State::Initialization {
            return error("fmi2ExitInitializationMode without fmi2EnterInitializationMode");
        }
        self.state = State::StepComplete;
        Ok(())
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Result<(), Problem> {
        if self.state != State::StepComplete {
            return error("fmi2Terminate is allowed only after initialization");
        }
        self.state = State::Terminated;
        Ok(())
    }

    /// `fmi2Reset`: the cold-start PLC, back to the instantiated state.
    pub fn reset(&mut self) {
        self.plc.reset();
        self.state = State::Instantiated;
        self.start = 0.0;
        self.time = 0.0;
        self.stopped_reported = false;
    }

    fn variable(&self, vr: u32, ty: FmiType) -> Result<&(Variable, Handle), Problem> {
        let found = (vr as usize)
            .checked_sub(1)
            .and_then(|i| self.variables.get(i))
            .ok_or_else(|| Problem::Error(format!("no variable has value reference {vr}")))?;
        if found.0.ty != ty {
            return error(format!(
                "variable {} (value reference {vr}) is {}, not {}",
                found.0.name,
                found.0.ty.name(),
                ty.name()
            ));
        }
        Ok(found)
    }

    /// `fmi2Get{Real,Integer,Boolean}` of one variable: an input reads back the value set, an
    /// output or local the image.
    pub fn get(&self, vr: u32, ty: FmiType) -> Result<Value, Problem> {
        let (v, h) = self.variable(vr, ty)?;
        let read = if v.causality == Causality::Input {
            self.plc.get_written(h)
        } else {
            self.plc.get(h)
        };
        read.map_err(|e| Problem::Error(e.to_string()))
    }

    /// `fmi2Set{Real,Integer,Boolean}` of one variable (inputs only).
    pub fn set(&mut self, vr: u32, ty: FmiType, value: Value) -> Result<(), Problem> {
        if self.state == State::Terminated {
            return error("variables cannot be set after fmi2Terminate");
        }
        let (v, h) = self.variable(vr, ty)?;
        if v.causality != Causality::Input {
            return error(format!(
                "variable {} is an {}, only inputs can be set",
                v.name,
                v.causality.name()
            ));
        }
        let h = h.clone();
        self.plc
            .set(&h, value)
            .map_err(|e| Problem::Error(e.to_string()))
    }

    /// `fmi2DoStep`: every scan that starts in `[t, t + h)`.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<(), Problem> {
        if self.state != State::StepComplete {
            return error("fmi2DoStep is allowed only after fmi2ExitInitializationMode");
        }
        if !(h.is_finite() && h >= 0.0 && t.is_finite()) {
            return error(format!(
                "step [{t}, {t} + {h}) is not a finite forward step"
            ));
        }
        if (t - self.time).abs() > 1e-9 + 1e-12 * t.abs() {
            return error(format!(
                "fmi2DoStep at t = {t}, but the FMU is at t = {} (restore an FMU state to go back)",
                self.time
            ));
        }
        let end_ms = ((t + h - self.start) * 1000.0).round();
        if !(0.0..=1e15).contains(&end_ms) {
            return error(format!("t = {} is outside the simulated time", t + h));
        }
        let report = self
            .plc
            .run_until(end_ms as u64)
            .map_err(|e| Problem::Error(e.to_string()))?;
        self.time = t + h;
        match report.outcome {
            Outcome::Fatal { .. } if !self.stopped_reported => {
                self.stopped_reported = true;
                Err(Problem::Warning(format!(
                    "the PLC stopped at t = {:.3} s: {}",
                    report.t_ms as f64 / 1000.0,
                    report.outcome
                )))
            }
            _ => Ok(()),
        }
    }

    /// `fmi2GetFMUstate`.
    pub fn save(&self) -> FmuState {
        FmuState {
            snapshot: self.plc.snapshot(),
            time: self.time,
        }
    }

    /// `fmi2SetFMUstate`.
    pub fn restore(&mut self, state: &FmuState) -> Result<(), Problem> {
        self.plc
            .restore(&state.snapshot)
            .map_err(|e| Problem::Error(e.to_string()))?;
        self.time = state.time;
        Ok(())
    }
}
