//! The exported `fmi2…` functions. Each one checks its pointers, turns them into Rust values and
//! calls an [`Instance`] method inside [`guard`], which catches panics and reports every problem
//! through the master's logger with the function's name. The only `unsafe` in the crate is here:
//! dereferencing the pointers the master passes (FMI 2.0 makes their validity the master's
//! contract, and each use says which pointer and why it is valid), calling the master's logger,
//! and moving the instance and saved states in and out of boxes.
//!
//! The functions are safe `extern "C"` functions, as FMI masters call them through C; the
//! validity of the pointers they receive is the FMI 2.0 contract with the master, which is why
//! clippy's `not_unsafe_ptr_arg_deref` is allowed here.
#![allow(clippy::not_unsafe_ptr_arg_deref)]

use crate::instance::{FmuState, Instance, Problem, resource_dir};
use crate::types::{
    Boolean, Callbacks, DO_STEP_STATUS, Env, FmiString, FmuStatePtr, Integer, LAST_SUCCESSFUL_TIME,
    Logger, Real, Status, StatusKind, TERMINATED, ValueReference,
};
use std::ffi::{CStr, CString, c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use stljit_api::Value;
use stljit_fmu::FmiType;

/// The master's handle of an instance.
type Component_ = crate::types::Component;

/// What a component pointer points to.
struct Component {
    name: CString,
    logger: Option<Logger>,
    env: Env,
    instance: Instance,
    /// A panic happened: the instance may be half-updated, only fmi2FreeInstance is allowed.
    poisoned: bool,
}

fn log_to(
    logger: Option<Logger>,
    env: Env,
    name: &CStr,
    status: Status,
    category: &str,
    msg: &str,
) {
    let Some(logger) = logger else { return };
    // Messages are printf formats for the master: `%` is escaped, NUL cannot occur in a C string.
    let msg = msg.replace('%', "%%").replace('\0', " ");
    let (Ok(category), Ok(msg)) = (CString::new(category), CString::new(msg)) else {
        return;
    };
    // SAFETY: `logger` is the master's fmi2CallbackLogger from fmi2Instantiate; every string
    // passed is a valid NUL-terminated C string that outlives the call, and no format arguments
    // are needed because `%` was escaped.
    unsafe { logger(env, name.as_ptr(), status, category.as_ptr(), msg.as_ptr()) }
}

impl Component {
    fn log(&self, status: Status, category: &str, msg: &str) {
        log_to(self.logger, self.env, &self.name, status, category, msg);
    }
}

/// Runs `f` on the component behind `c`, catching panics; every problem is logged.
fn guard(
    c: Component_,
    func: &str,
    f: impl FnOnce(&mut Component) -> Result<(), Problem>,
) -> Status {
    if c.is_null() {
        return Status::Error;
    }
    // SAFETY: a non-null component is a pointer fmi2Instantiate returned (Box<Component>) and
    // fmi2FreeInstance has not freed yet: FMI 2.0 §2.1.5 obliges the master to pass only those,
    // and calls on one instance are not concurrent.
    let comp = unsafe { &mut *c.cast::<Component>() };
    if comp.poisoned {
        comp.log(
            Status::Fatal,
            "logStatusFatal",
            &format!("{func}: the instance failed before"),
        );
        return Status::Fatal;
    }
    match catch_unwind(AssertUnwindSafe(|| f(comp))) {
        Ok(Ok(())) => Status::Ok,
        Ok(Err(Problem::Warning(m))) => {
            comp.log(Status::Warning, "logStatusWarning", &format!("{func}: {m}"));
            Status::Warning
        }
        Ok(Err(Problem::Error(m))) => {
            comp.log(Status::Error, "logStatusError", &format!("{func}: {m}"));
            Status::Error
        }
        Err(panic) => {
            comp.poisoned = true;
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| (*s).to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            comp.log(
                Status::Fatal,
                "logStatusFatal",
                &format!("{func}: internal error: {what}"),
            );
            Status::Fatal
        }
    }
}

/// A slice from a master's array pointer; an empty slice for `n == 0` (the pointer may then be
/// null), an error for a null pointer with `n > 0`.
fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Result<&'a [T], Problem> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(Problem::Error(format!("{what} is NULL")));
    }
    // SAFETY: the master passes arrays of `n` elements (FMI 2.0 §2.1.7), checked non-null.
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> Result<&'a mut [T], Problem> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(Problem::Error(format!("{what} is NULL")));
    }
    // SAFETY: as in `slice`; the master owns the array and lends it for the call.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

fn text<'a>(p: FmiString, what: &str) -> Result<&'a str, Problem> {
    if p.is_null() {
        return Err(Problem::Error(format!("{what} is NULL")));
    }
    // SAFETY: FMI strings are NUL-terminated and valid for the call; checked non-null.
    unsafe { CStr::from_ptr(p) }
        .to_str()
        .map_err(|_| Problem::Error(format!("{what} is not UTF-8")))
}

// ---- inquiry and life cycle ----------------------------------------------------------------

/// `fmi2GetTypesPlatform`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

/// `fmi2GetVersion`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2Instantiate`: compiles the FMU's program; NULL (after logging why) on failure.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2Instantiate(
    instance_name: FmiString,
    fmu_type: std::ffi::c_int,
    guid: FmiString,
    resource_location: FmiString,
    functions: *const Callbacks,
    _visible: Boolean,
    _logging_on: Boolean,
) -> Component_ {
    let (logger, env) = if functions.is_null() {
        (None, std::ptr::null_mut())
    } else {
        // SAFETY: a non-null `functions` points to the master's fmi2CallbackFunctions, valid
        // for the lifetime of the instance (FMI 2.0 §2.1.5).
        let f = unsafe { &*functions };
        (f.logger, f.component_environment)
    };
    let name =
        CString::new(text(instance_name, "instanceName").unwrap_or("stljit")).unwrap_or_default();
    let result = catch_unwind(|| -> Result<Instance, Problem> {
        if fmu_type != 1 {
            return Err(Problem::Error(
                "this FMU supports co-simulation only (fmi2CoSimulation)".into(),
            ));
        }
        let guid = text(guid, "fmuGUID")?;
        let location = text(resource_location, "fmuResourceLocation")?;
        let dir = resource_dir(location).map_err(Problem::Error)?;
        Instance::new(&dir, guid)
    });
    match result {
        Ok(Ok(instance)) => Box::into_raw(Box::new(Component {
            name,
            logger,
            env,
            instance,
            poisoned: false,
        }))
        .cast(),
        Ok(Err(Problem::Error(m) | Problem::Warning(m))) => {
            log_to(
                logger,
                env,
                &name,
                Status::Error,
                "logStatusError",
                &format!("fmi2Instantiate: {m}"),
            );
            std::ptr::null_mut()
        }
        Err(_) => {
            log_to(
                logger,
                env,
                &name,
                Status::Fatal,
                "logStatusFatal",
                "fmi2Instantiate: internal error",
            );
            std::ptr::null_mut()
        }
    }
}

/// `fmi2FreeInstance`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2FreeInstance(c: Component_) {
    if c.is_null() {
        return;
    }
    // SAFETY: `c` came from fmi2Instantiate's Box::into_raw and is freed once (the master's
    // contract); nothing uses it afterwards.
    let boxed = unsafe { Box::from_raw(c.cast::<Component>()) };
    let _ = catch_unwind(AssertUnwindSafe(move || drop(boxed)));
}

/// `fmi2SetDebugLogging`: warnings and errors are always logged; nothing else is.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetDebugLogging(
    c: Component_,
    _logging_on: Boolean,
    _n: usize,
    _categories: *const FmiString,
) -> Status {
    guard(c, "fmi2SetDebugLogging", |_| Ok(()))
}

/// `fmi2SetupExperiment`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetupExperiment(
    c: Component_,
    _tolerance_defined: Boolean,
    _tolerance: Real,
    start_time: Real,
    _stop_time_defined: Boolean,
    _stop_time: Real,
) -> Status {
    guard(c, "fmi2SetupExperiment", |comp| {
        comp.instance.setup(start_time)
    })
}

/// `fmi2EnterInitializationMode`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2EnterInitializationMode(c: Component_) -> Status {
    guard(c, "fmi2EnterInitializationMode", |comp| {
        comp.instance.enter_initialization()
    })
}

/// `fmi2ExitInitializationMode`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2ExitInitializationMode(c: Component_) -> Status {
    guard(c, "fmi2ExitInitializationMode", |comp| {
        comp.instance.exit_initialization()
    })
}

/// `fmi2Terminate`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2Terminate(c: Component_) -> Status {
    guard(c, "fmi2Terminate", |comp| comp.instance.terminate())
}

/// `fmi2Reset`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2Reset(c: Component_) -> Status {
    guard(c, "fmi2Reset", |comp| {
        comp.instance.reset();
        Ok(())
    })
}

// ---- variables -----------------------------------------------------------------------------

fn get_values<T>(
    c: Component_,
    func: &str,
    ty: FmiType,
    vr: *const ValueReference,
    n: usize,
    out: *mut T,
    convert: impl Fn(Value) -> T,
) -> Status {
    guard(c, func, |comp| {
        let vrs = slice(vr, n, "vr")?;
        let out = slice_mut(out, n, "value")?;
        for (v, o) in vrs.iter().zip(out) {
            *o = convert(comp.instance.get(*v, ty)?);
        }
        Ok(())
    })
}

fn set_values<T: Copy>(
    c: Component_,
    func: &str,
    ty: FmiType,
    vr: *const ValueReference,
    n: usize,
    values: *const T,
    convert: impl Fn(T) -> Value,
) -> Status {
    guard(c, func, |comp| {
        let vrs = slice(vr, n, "vr")?;
        let values = slice(values, n, "value")?;
        for (v, x) in vrs.iter().zip(values) {
            comp.instance.set(*v, ty, convert(*x))?;
        }
        Ok(())
    })
}

fn as_real(v: Value) -> Real {
    v.as_f64()
}

fn as_integer(v: Value) -> Integer {
    match v {
        // An unsigned dword travels as its two's-complement bits.
        Value::Int(i) => i as u32 as Integer,
        other => other.as_f64() as Integer,
    }
}

fn as_boolean(v: Value) -> Boolean {
    Boolean::from(v.as_f64() != 0.0)
}

/// `fmi2GetReal`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetReal(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    v: *mut Real,
) -> Status {
    get_values(c, "fmi2GetReal", FmiType::Real, vr, n, v, as_real)
}

/// `fmi2GetInteger`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetInteger(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    v: *mut Integer,
) -> Status {
    get_values(c, "fmi2GetInteger", FmiType::Integer, vr, n, v, as_integer)
}

/// `fmi2GetBoolean`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetBoolean(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    v: *mut Boolean,
) -> Status {
    get_values(c, "fmi2GetBoolean", FmiType::Boolean, vr, n, v, as_boolean)
}

/// `fmi2GetString`: the FMU has no string variables.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetString(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    _v: *mut FmiString,
) -> Status {
    guard(c, "fmi2GetString", |_| match slice(vr, n, "vr")?.first() {
        None => Ok(()),
        Some(v) => Err(Problem::Error(format!(
            "no String variable has value reference {v}"
        ))),
    })
}

/// `fmi2SetReal`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetReal(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    v: *const Real,
) -> Status {
    set_values(c, "fmi2SetReal", FmiType::Real, vr, n, v, Value::Real)
}

/// `fmi2SetInteger`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetInteger(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    v: *const Integer,
) -> Status {
    set_values(c, "fmi2SetInteger", FmiType::Integer, vr, n, v, |i| {
        Value::Int(i64::from(i))
    })
}

/// `fmi2SetBoolean`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetBoolean(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    v: *const Boolean,
) -> Status {
    set_values(c, "fmi2SetBoolean", FmiType::Boolean, vr, n, v, |b| {
        Value::Bool(b != 0)
    })
}

/// `fmi2SetString`: the FMU has no string variables.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetString(
    c: Component_,
    vr: *const ValueReference,
    n: usize,
    _v: *const FmiString,
) -> Status {
    fmi2GetString(c, vr, n, std::ptr::null_mut())
}

// ---- FMU state -----------------------------------------------------------------------------

/// `fmi2GetFMUstate`: a new saved state, or the one `*state` points to overwritten.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetFMUstate(c: Component_, state: *mut FmuStatePtr) -> Status {
    guard(c, "fmi2GetFMUstate", |comp| {
        let slot = slice_mut(state, 1, "FMUstate")?;
        let saved = comp.instance.save();
        if slot[0].is_null() {
            slot[0] = Box::into_raw(Box::new(saved)).cast();
        } else {
            // SAFETY: a non-null state is one this library made (Box<FmuState>) and has not
            // freed (the master's contract).
            unsafe { *slot[0].cast::<FmuState>() = saved };
        }
        Ok(())
    })
}

fn state_ref<'a>(state: FmuStatePtr) -> Result<&'a FmuState, Problem> {
    if state.is_null() {
        return Err(Problem::Error("FMUstate is NULL".into()));
    }
    // SAFETY: as in fmi2GetFMUstate: a state this library made and has not freed.
    Ok(unsafe { &*state.cast::<FmuState>() })
}

/// `fmi2SetFMUstate`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetFMUstate(c: Component_, state: FmuStatePtr) -> Status {
    guard(c, "fmi2SetFMUstate", |comp| {
        comp.instance.restore(state_ref(state)?)
    })
}

/// `fmi2FreeFMUstate`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2FreeFMUstate(c: Component_, state: *mut FmuStatePtr) -> Status {
    guard(c, "fmi2FreeFMUstate", |_| {
        let slot = slice_mut(state, 1, "FMUstate")?;
        if !slot[0].is_null() {
            // SAFETY: a state this library made with Box::into_raw, freed once, then cleared.
            drop(unsafe { Box::from_raw(slot[0].cast::<FmuState>()) });
            slot[0] = std::ptr::null_mut();
        }
        Ok(())
    })
}

/// `fmi2SerializedFMUstateSize`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SerializedFMUstateSize(
    c: Component_,
    state: FmuStatePtr,
    size: *mut usize,
) -> Status {
    guard(c, "fmi2SerializedFMUstateSize", |_| {
        slice_mut(size, 1, "size")?[0] = state_ref(state)?.to_bytes().len();
        Ok(())
    })
}

/// `fmi2SerializeFMUstate`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SerializeFMUstate(
    c: Component_,
    state: FmuStatePtr,
    out: *mut c_char,
    size: usize,
) -> Status {
    guard(c, "fmi2SerializeFMUstate", |_| {
        let bytes = state_ref(state)?.to_bytes();
        if size < bytes.len() {
            return Err(Problem::Error(format!(
                "the buffer holds {size} bytes, the state needs {}",
                bytes.len()
            )));
        }
        let out = slice_mut(out.cast::<u8>(), bytes.len(), "serializedState")?;
        out.copy_from_slice(&bytes);
        Ok(())
    })
}

/// `fmi2DeSerializeFMUstate`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2DeSerializeFMUstate(
    c: Component_,
    data: *const c_char,
    size: usize,
    state: *mut FmuStatePtr,
) -> Status {
    guard(c, "fmi2DeSerializeFMUstate", |_| {
        let bytes = slice(data.cast::<u8>(), size, "serializedState")?;
        let restored = FmuState::from_bytes(bytes)?;
        let slot = slice_mut(state, 1, "FMUstate")?;
        slot[0] = Box::into_raw(Box::new(restored)).cast::<c_void>();
        Ok(())
    })
}

/// `fmi2GetDirectionalDerivative`: not provided (no `providesDirectionalDerivative`).
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetDirectionalDerivative(
    c: Component_,
    _unknown: *const ValueReference,
    _n_unknown: usize,
    _known: *const ValueReference,
    _n_known: usize,
    _dv_known: *const Real,
    _dv_unknown: *mut Real,
) -> Status {
    unsupported(c, "fmi2GetDirectionalDerivative")
}

fn unsupported(c: Component_, func: &str) -> Status {
    guard(c, func, |_| {
        Err(Problem::Error("not supported by this FMU".into()))
    })
}

// ---- co-simulation -------------------------------------------------------------------------

/// `fmi2SetRealInputDerivatives`: not supported (`canInterpolateInputs="false"`).
#[unsafe(no_mangle)]
pub extern "C" fn fmi2SetRealInputDerivatives(
    c: Component_,
    _vr: *const ValueReference,
    _n: usize,
    _order: *const Integer,
    _value: *const Real,
) -> Status {
    unsupported(c, "fmi2SetRealInputDerivatives")
}

/// `fmi2GetRealOutputDerivatives`: not supported (`maxOutputDerivativeOrder` 0).
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetRealOutputDerivatives(
    c: Component_,
    _vr: *const ValueReference,
    _n: usize,
    _order: *const Integer,
    _value: *mut Real,
) -> Status {
    unsupported(c, "fmi2GetRealOutputDerivatives")
}

/// `fmi2DoStep`: the scans that start in `[t, t + h)`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2DoStep(c: Component_, t: Real, h: Real, _no_set_prior: Boolean) -> Status {
    guard(c, "fmi2DoStep", |comp| comp.instance.do_step(t, h))
}

/// `fmi2CancelStep`: steps are synchronous, there is nothing to cancel.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2CancelStep(c: Component_) -> Status {
    unsupported(c, "fmi2CancelStep")
}

/// `fmi2GetStatus`: `fmi2DoStepStatus` is always OK (steps are synchronous).
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetStatus(c: Component_, kind: StatusKind, value: *mut Status) -> Status {
    guard(c, "fmi2GetStatus", |_| {
        if kind != DO_STEP_STATUS {
            return Err(Problem::Error(format!(
                "status kind {kind} is not a Status"
            )));
        }
        slice_mut(value, 1, "value")?[0] = Status::Ok;
        Ok(())
    })
}

/// `fmi2GetRealStatus`: `fmi2LastSuccessfulTime` is the communication time.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetRealStatus(c: Component_, kind: StatusKind, value: *mut Real) -> Status {
    guard(c, "fmi2GetRealStatus", |comp| {
        if kind != LAST_SUCCESSFUL_TIME {
            return Err(Problem::Error(format!("status kind {kind} is not a Real")));
        }
        slice_mut(value, 1, "value")?[0] = comp.instance.time();
        Ok(())
    })
}

/// `fmi2GetIntegerStatus`: there is no Integer status kind.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetIntegerStatus(
    c: Component_,
    _kind: StatusKind,
    _value: *mut Integer,
) -> Status {
    unsupported(c, "fmi2GetIntegerStatus")
}

/// `fmi2GetBooleanStatus`: `fmi2Terminated` is false (the FMU never ends a simulation itself).
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetBooleanStatus(
    c: Component_,
    kind: StatusKind,
    value: *mut Boolean,
) -> Status {
    guard(c, "fmi2GetBooleanStatus", |_| {
        if kind != TERMINATED {
            return Err(Problem::Error(format!(
                "status kind {kind} is not a Boolean"
            )));
        }
        slice_mut(value, 1, "value")?[0] = 0;
        Ok(())
    })
}

/// `fmi2GetStringStatus`: there is no pending step to describe.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetStringStatus(
    c: Component_,
    _kind: StatusKind,
    _value: *mut FmiString,
) -> Status {
    unsupported(c, "fmi2GetStringStatus")
}
