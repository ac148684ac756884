//! The `stljit` Python package's native module, `stljit._native` (pyo3): the embedding API's
//! [`stljit_api::Plc`] as the Python class `stljit.Plc`, with handles, snapshots, forcing, run
//! reports and NumPy traces. Every API error becomes a Python exception of the `StljitError`
//! family carrying the API's message (for a program with errors, the rendered diagnostics).
//!
//! The pure-Python part of the package (`python/stljit/`) re-exports these names and carries the
//! type hints (`_native.pyi`, `py.typed`).

mod convert;
mod plc;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    stljit,
    StljitError,
    PyException,
    "Base class of every error stljit raises."
);
create_exception!(
    stljit,
    CompileError,
    StljitError,
    "The program has errors; the message is every diagnostic as `stljit check` prints it."
);
create_exception!(
    stljit,
    AddressError,
    StljitError,
    "A name is neither an address of the program's dialect and CPU nor a symbol, or it may not \
     be written or forced."
);
create_exception!(
    stljit,
    PlcValueError,
    StljitError,
    "A value does not fit the address (a 2 for a bit, 70000 for a word, a real for a word)."
);
create_exception!(
    stljit,
    SnapshotError,
    StljitError,
    "A snapshot belongs to another program, or bytes are not a snapshot."
);

/// The native module.
#[pymodule]
#[pyo3(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<plc::PyPlc>()?;
    m.add_class::<plc::PyHandle>()?;
    m.add_class::<plc::PySnapshot>()?;
    m.add_class::<plc::PyRunReport>()?;
    m.add("StljitError", py.get_type::<StljitError>())?;
    m.add("CompileError", py.get_type::<CompileError>())?;
    m.add("AddressError", py.get_type::<AddressError>())?;
    m.add("PlcValueError", py.get_type::<PlcValueError>())?;
    m.add("SnapshotError", py.get_type::<SnapshotError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
