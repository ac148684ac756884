//! Conversions between Python objects and the embedding API's types: values (`bool`, `int`,
//! `float`, NumPy scalars), durations (`"10ms"`, `"2m"`, or an `int` of milliseconds), file
//! arguments (a path or a list of paths) and errors (the exception classes of `lib.rs`).

use crate::{AddressError, CompileError, PlcValueError, SnapshotError, StljitError};
use pyo3::IntoPyObjectExt as _;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBool;
use std::path::PathBuf;
use stljit_api::{Error, Value};

/// The Python exception for an API error, with the API's message.
pub(crate) fn error(e: Error) -> PyErr {
    let message = e.to_string();
    match e {
        Error::Compile { .. } => CompileError::new_err(message),
        Error::Address { .. } | Error::NotWritable { .. } => AddressError::new_err(message),
        Error::Value { .. } => PlcValueError::new_err(message),
        Error::Foreign { .. } | Error::Snapshot { .. } => SnapshotError::new_err(message),
        _ => StljitError::new_err(message),
    }
}

/// A value from Python: `bool` (or `numpy.bool_`), `int` (or a NumPy integer), `float`.
pub(crate) fn value(obj: &Bound<'_, PyAny>) -> PyResult<Value> {
    if obj.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(obj.extract::<bool>()?));
    }
    if let Ok(i) = obj.extract::<i64>() {
        return Ok(Value::Int(i));
    }
    if let Ok(f) = obj.extract::<f64>() {
        return Ok(Value::Real(f));
    }
    if let Ok(b) = obj.extract::<bool>() {
        return Ok(Value::Bool(b));
    }
    Err(PyTypeError::new_err(format!(
        "a PLC value is a bool, an int or a float, not {}",
        obj.get_type().name()?
    )))
}

/// A value to Python: `bool`, `int` or `float`.
pub(crate) fn to_py(py: Python<'_>, v: Value) -> PyResult<Py<PyAny>> {
    match v {
        Value::Bool(b) => b.into_py_any(py),
        Value::Int(i) => i.into_py_any(py),
        Value::Real(f) => f.into_py_any(py),
    }
}

/// Milliseconds from `"10ms"`, `"1.5s"`, `"2m"`, `"24h"` or an `int` of milliseconds.
pub(crate) fn duration(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<u64> {
    if let Ok(ms) = obj.extract::<u64>() {
        return Ok(ms);
    }
    match obj.extract::<String>() {
        Ok(text) => stljit_api::duration::parse_duration(&text)
            .map_err(|m| PyValueError::new_err(format!("{what}: {m}"))),
        Err(_) => Err(PyTypeError::new_err(format!(
            "{what}: a duration is a string such as \"10ms\" or \"2m\", or an int of milliseconds"
        ))),
    }
}

/// One path or a sequence of paths.
pub(crate) fn paths(obj: &Bound<'_, PyAny>) -> PyResult<Vec<PathBuf>> {
    if let Ok(p) = obj.extract::<PathBuf>() {
        return Ok(vec![p]);
    }
    obj.extract::<Vec<PathBuf>>()
        .map_err(|_| PyTypeError::new_err("files: a path (str or os.PathLike) or a list of paths"))
}
