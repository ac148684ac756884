//! `stljit.Plc` and its companions `Handle`, `Snapshot` and `RunReport`.
//!
//! A `Plc` wraps one [`stljit_api::Plc`] behind a mutex (Python objects may be shared between
//! threads). Names used with `plc[name]` are resolved once and cached, so a closed loop that
//! indexes by string pays a hash lookup, not an address parse, per access; a `Handle` skips
//! even that. Long runs (`run`, `trace`) release the GIL.

use crate::convert::{duration, error, paths, to_py, value};
use numpy::{IntoPyArray as _, PyArray1};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes, PyDict};
use std::collections::HashMap;
use std::sync::{Mutex, MutexGuard};
use stljit_api::{
    EngineKind, Handle, Options, Outcome, Plc, Project, Recorder, RunReport, Snapshot, Type, Until,
};

/// Names cached per PLC before the cache is cleared (a loop over ever new names stays bounded).
const NAME_CACHE: usize = 4096;

/// A resolved address (`plc.handle("VD50:real")`): reads and writes through it skip name lookup.
#[pyclass(frozen, module = "stljit", name = "Handle")]
pub(crate) struct PyHandle {
    inner: Handle,
}

#[pymethods]
impl PyHandle {
    /// The name as written.
    #[getter]
    fn name(&self) -> &str {
        self.inner.name()
    }

    /// The value type: `bool`, `byte`, `int16`, `uint16`, `int32`, `uint32` or `real`.
    #[getter]
    fn r#type(&self) -> &'static str {
        self.inner.ty().name()
    }

    fn __repr__(&self) -> String {
        format!(
            "Handle({:?}, {})",
            self.inner.name(),
            self.inner.ty().name()
        )
    }
}

/// The whole state of a PLC (image, timers, counters, edges, time, forces).
#[pyclass(frozen, module = "stljit", name = "Snapshot")]
pub(crate) struct PySnapshot {
    inner: Snapshot,
}

#[pymethods]
impl PySnapshot {
    /// The snapshot as bytes (restorable on the same machine architecture).
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.inner.to_bytes())
    }

    /// A snapshot from `to_bytes`' output.
    #[staticmethod]
    fn from_bytes(data: &[u8]) -> PyResult<PySnapshot> {
        Snapshot::from_bytes(data)
            .map(|inner| PySnapshot { inner })
            .map_err(error)
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Py<PyAny>, (Bound<'py, PyBytes>,))> {
        let ctor = py.get_type::<PySnapshot>().getattr("from_bytes")?.unbind();
        Ok((ctor, (self.to_bytes(py),)))
    }
}

/// What a run did.
#[pyclass(frozen, module = "stljit", name = "RunReport")]
pub(crate) struct PyRunReport {
    /// Scans run.
    #[pyo3(get)]
    scans: u64,
    /// `completed`, `stopped`, `fatal` or `cancelled`.
    #[pyo3(get)]
    outcome: &'static str,
    /// The outcome in words (the fatal error's name for `fatal`).
    #[pyo3(get)]
    message: String,
    /// Virtual time after the run (the start of the next scan).
    #[pyo3(get)]
    time_ms: u64,
}

#[pymethods]
impl PyRunReport {
    fn __repr__(&self) -> String {
        format!(
            "RunReport(scans={}, outcome={:?}, time_ms={})",
            self.scans, self.outcome, self.time_ms
        )
    }
}

fn report(r: &RunReport, time_ms: u64) -> PyRunReport {
    PyRunReport {
        scans: r.scans,
        outcome: match r.outcome {
            Outcome::Completed => "completed",
            Outcome::Stopped => "stopped",
            Outcome::Fatal { .. } => "fatal",
            Outcome::Cancelled => "cancelled",
        },
        message: r.outcome.to_string(),
        time_ms,
    }
}

struct Inner {
    plc: Plc,
    names: HashMap<String, Handle>,
}

impl Inner {
    fn handle(&mut self, name: &str) -> PyResult<Handle> {
        if let Some(h) = self.names.get(name) {
            return Ok(h.clone());
        }
        let h = self.plc.handle(name).map_err(error)?;
        if self.names.len() >= NAME_CACHE {
            self.names.clear();
        }
        self.names.insert(name.to_string(), h.clone());
        Ok(h)
    }

    /// The handle a key names: a `Handle`, or a name.
    fn key(&mut self, key: &Bound<'_, PyAny>) -> PyResult<Handle> {
        if let Ok(h) = key.cast::<PyHandle>() {
            return Ok(h.get().inner.clone());
        }
        match key.extract::<String>() {
            Ok(name) => self.handle(&name),
            Err(_) => Err(PyTypeError::new_err(
                "a PLC address is a name (\"I0.0\", \"VW10\", a symbol) or a Handle",
            )),
        }
    }
}

/// A compiled PLC program on an engine, driven scan by scan on virtual time.
#[pyclass(module = "stljit", name = "Plc")]
pub(crate) struct PyPlc {
    inner: Mutex<Inner>,
}

impl PyPlc {
    fn lock(&self) -> MutexGuard<'_, Inner> {
        // A panic cannot happen while the lock is held (the API does not panic); were it to,
        // the state is still a whole-scan state, so the poison is ignored.
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }
}

fn until(
    scans: Option<u64>,
    for_: Option<&Bound<'_, PyAny>>,
    until_ms: Option<u64>,
) -> PyResult<Option<Until>> {
    match (scans, for_, until_ms) {
        (Some(n), None, None) => Ok(Some(Until::Scans(n))),
        (None, Some(d), None) => Ok(Some(Until::Duration(duration(d, "for_")?))),
        (None, None, Some(_)) => Ok(None),
        _ => Err(PyValueError::new_err(
            "give exactly one of scans=, for_= and until_ms=",
        )),
    }
}

#[pymethods]
impl PyPlc {
    /// Compiles `files` (one program) and builds the PLC, cold-started.
    #[new]
    #[pyo3(signature = (files, dialect=None, cpu=None, symbols=None, engine="jit", scan_time=None))]
    fn new(
        py: Python<'_>,
        files: &Bound<'_, PyAny>,
        dialect: Option<&str>,
        cpu: Option<&str>,
        symbols: Option<std::path::PathBuf>,
        engine: &str,
        scan_time: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyPlc> {
        let files = paths(files)?;
        let engine = EngineKind::from_name(engine).ok_or_else(|| {
            PyValueError::new_err(format!("engine `{engine}`: use \"jit\" or \"interp\""))
        })?;
        let scan_ms = match scan_time {
            Some(t) => duration(t, "scan_time")?,
            None => 10,
        };
        let mut project = Project::new();
        for f in &files {
            project = project.file(f).map_err(error)?;
        }
        if let Some(s) = &symbols {
            project = project.symbols_file(s).map_err(error)?;
        }
        if let Some(d) = dialect {
            project = project.dialect(stljit_api::dialect_named(d).map_err(error)?);
        }
        if let Some(c) = cpu {
            project = project.cpu(c);
        }
        let options = Options {
            engine,
            scan_ms,
            ..Options::default()
        };
        let plc = py
            .detach(|| Plc::compile(&project, &options))
            .map_err(error)?;
        Ok(PyPlc {
            inner: Mutex::new(Inner {
                plc,
                names: HashMap::new(),
            }),
        })
    }

    /// Resolves a name once (`"I0.0"`, `"VW10"`, `"VD50:real"`, `"T37:i"`, a symbol).
    fn handle(&self, name: &str) -> PyResult<PyHandle> {
        let inner = self.lock().handle(name)?;
        Ok(PyHandle { inner })
    }

    fn __getitem__(&self, py: Python<'_>, key: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let mut g = self.lock();
        let h = g.key(key)?;
        let v = g.plc.get(&h).map_err(error)?;
        to_py(py, v)
    }

    fn __setitem__(&self, key: &Bound<'_, PyAny>, v: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = value(v)?;
        let mut g = self.lock();
        let h = g.key(key)?;
        g.plc.set(&h, v).map_err(error)
    }

    /// The value at a name or handle (as `plc[key]`).
    fn get(&self, py: Python<'_>, key: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.__getitem__(py, key)
    }

    /// Writes a name or handle (as `plc[key] = value`).
    fn set(&self, key: &Bound<'_, PyAny>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.__setitem__(key, value)
    }

    /// Runs one scan.
    fn scan(&self) -> PyResult<()> {
        self.lock().plc.scan().map(|_| ()).map_err(error)
    }

    /// Runs `scans` scans, `for_` virtual time (`"2m"`, or ms), or until virtual time
    /// `until_ms`; stops early on STOP or a fatal error (the report says which).
    #[pyo3(signature = (scans=None, for_=None, until_ms=None))]
    fn run(
        &self,
        py: Python<'_>,
        scans: Option<u64>,
        for_: Option<&Bound<'_, PyAny>>,
        until_ms: Option<u64>,
    ) -> PyResult<PyRunReport> {
        let span = until(scans, for_, until_ms)?;
        py.detach(|| {
            let mut g = self.lock();
            let r = match (span, until_ms) {
                (Some(u), _) => g.plc.run(u),
                (None, Some(t)) => g.plc.run_until(t),
                (None, None) => g.plc.run(Until::Scans(0)),
            }?;
            Ok(report(&r, g.plc.time_ms()))
        })
        .map_err(error)
    }

    /// Runs like `run` and returns the values of `names` after every scan as NumPy arrays: a
    /// dict with `"scan"` and `"t_ms"` (uint64) and one array per name (bool for bits, int64
    /// for integers, float64 for reals).
    #[pyo3(signature = (names, scans=None, for_=None, until_ms=None))]
    fn trace<'py>(
        &self,
        py: Python<'py>,
        names: Vec<String>,
        scans: Option<u64>,
        for_: Option<&Bound<'_, PyAny>>,
        until_ms: Option<u64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let span = until(scans, for_, until_ms)?;
        let handles = {
            let mut g = self.lock();
            names
                .iter()
                .map(|n| g.handle(n))
                .collect::<PyResult<Vec<_>>>()?
        };
        let rec = py
            .detach(|| {
                let mut g = self.lock();
                let scan_ms = g.plc.scan_ms();
                let span = match (span, until_ms) {
                    (Some(u), _) => u,
                    (None, t) => Until::Scans(
                        t.unwrap_or(0)
                            .div_ceil(scan_ms)
                            .saturating_sub(g.plc.scan_no()),
                    ),
                };
                let capacity = match span {
                    Until::Scans(n) => n,
                    Until::Duration(ms) => ms.div_ceil(scan_ms),
                };
                let mut rec = Recorder::new(handles, capacity.min(1 << 24) as usize);
                g.plc.run_observed(span, &mut rec).map(|_| rec)
            })
            .map_err(error)?;
        let out = PyDict::new(py);
        out.set_item("scan", rec.scans().to_vec().into_pyarray(py))?;
        out.set_item("t_ms", rec.times().to_vec().into_pyarray(py))?;
        for (i, (name, h)) in names.iter().zip(rec.handles()).enumerate() {
            let raw = rec.raw(i);
            match h.ty() {
                Type::Bool => {
                    let col: Vec<bool> = raw.iter().map(|&r| r & 1 != 0).collect();
                    out.set_item(name, PyArray1::from_vec(py, col))?;
                }
                Type::Real => {
                    let col: Vec<f64> = raw.iter().map(|&r| f64::from(f32::from_bits(r))).collect();
                    out.set_item(name, PyArray1::from_vec(py, col))?;
                }
                _ => {
                    let col: Vec<i64> = rec
                        .values(i)
                        .into_iter()
                        .map(|v| match v {
                            stljit_api::Value::Int(i) => i,
                            other => other.as_f64() as i64,
                        })
                        .collect();
                    out.set_item(name, PyArray1::from_vec(py, col))?;
                }
            }
        }
        Ok(out)
    }

    /// Gives high-speed counter `counter` `steps` signed unit steps in every scan interval from
    /// the next scan on, held until set again (s7-200-more §8.4).
    fn set_hsc_steps(&self, counter: i64, steps: i64) -> PyResult<()> {
        let counter = u8::try_from(counter).map_err(|_| {
            PyValueError::new_err(format!("counter {counter}: not a counter number (0…255)"))
        })?;
        let steps = i32::try_from(steps).map_err(|_| {
            PyValueError::new_err(format!(
                "steps {steps}: not a 32-bit integer (-2147483648…2147483647)"
            ))
        })?;
        self.lock().plc.set_hsc_steps(counter, steps).map_err(error)
    }

    /// Queues `data` (bytes or bytearray) to be received on serial port `port` in the interval
    /// before the next scan (s7-200-more §10.4).
    fn queue_rx(&self, port: i64, data: &Bound<'_, PyAny>) -> PyResult<()> {
        let port = u8::try_from(port).map_err(|_| {
            PyValueError::new_err(format!("port {port}: not a port number (0…255)"))
        })?;
        let bytes: Vec<u8> = if let Ok(b) = data.cast::<PyBytes>() {
            b.as_bytes().to_vec()
        } else if let Ok(b) = data.cast::<PyByteArray>() {
            b.to_vec()
        } else {
            return Err(PyTypeError::new_err(format!(
                "data: bytes or bytearray, not {}",
                data.get_type().name()?
            )));
        };
        self.lock().plc.queue_rx(port, &bytes).map_err(error)
    }

    /// Holds an address at `value` whatever the program or a write does (inputs before the
    /// program reads them, everything after the program writes it, before the output copy).
    fn force(&self, key: &Bound<'_, PyAny>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = crate::convert::value(value)?;
        let mut g = self.lock();
        let h = g.key(key)?;
        g.plc.force(&h, v).map_err(error)
    }

    /// Releases a force; False when the address was not forced.
    fn unforce(&self, key: &Bound<'_, PyAny>) -> PyResult<bool> {
        let mut g = self.lock();
        let h = g.key(key)?;
        Ok(g.plc.unforce(&h))
    }

    /// Releases every force.
    fn unforce_all(&self) {
        self.lock().plc.unforce_all();
    }

    /// The forced addresses and their values.
    #[getter]
    fn forced<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for (name, v) in self.lock().plc.forced() {
            out.set_item(name, to_py(py, v)?)?;
        }
        Ok(out)
    }

    /// The whole state, to `restore` later (on this PLC or another of the same program).
    fn snapshot(&self) -> PySnapshot {
        PySnapshot {
            inner: self.lock().plc.snapshot(),
        }
    }

    /// Continues from a snapshot of the same program.
    fn restore(&self, snapshot: &PySnapshot) -> PyResult<()> {
        self.lock().plc.restore(&snapshot.inner).map_err(error)
    }

    /// Back to the power-up state: scan 0, time 0, no forces.
    fn reset(&self) {
        self.lock().plc.reset();
    }

    /// Virtual time now (the start of the next scan), in ms.
    #[getter]
    fn time_ms(&self) -> u64 {
        self.lock().plc.time_ms()
    }

    /// Number of the next scan (scans since the cold start).
    #[getter]
    fn scan_no(&self) -> u64 {
        self.lock().plc.scan_no()
    }

    /// Virtual time per scan, in ms.
    #[getter]
    fn scan_ms(&self) -> u64 {
        self.lock().plc.scan_ms()
    }

    /// `jit` or `interp`.
    #[getter]
    fn engine(&self) -> &'static str {
        self.lock().plc.engine().name()
    }

    /// `s7` or `omron`.
    #[getter]
    fn dialect(&self) -> &'static str {
        self.lock().plc.compiled().dialect().name()
    }

    /// The CPU profile (`a5`, `cp1h`, ...).
    #[getter]
    fn cpu(&self) -> &'static str {
        self.lock().plc.compiled().profile().name()
    }

    /// Whether the PLC is in STOP (after a STOP instruction or a fatal error).
    #[getter]
    fn is_stopped(&self) -> bool {
        self.lock().plc.is_stopped()
    }

    fn __repr__(&self) -> String {
        let g = self.lock();
        format!(
            "Plc(dialect={:?}, cpu={:?}, engine={:?}, scan_no={}, time_ms={})",
            g.plc.compiled().dialect().name(),
            g.plc.compiled().profile().name(),
            g.plc.engine().name(),
            g.plc.scan_no(),
            g.plc.time_ms()
        )
    }
}
