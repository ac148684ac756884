//! The C types of `fmi2FunctionTypes.h` and `fmi2TypesPlatform.h` ("default" platform).

use std::ffi::{c_char, c_int, c_void};

/// `fmi2Component`.
pub type Component = *mut c_void;
/// `fmi2ComponentEnvironment`.
pub type Env = *mut c_void;
/// `fmi2FMUstate`.
pub type FmuStatePtr = *mut c_void;
/// `fmi2ValueReference`.
pub type ValueReference = u32;
/// `fmi2Real`.
pub type Real = f64;
/// `fmi2Integer`.
pub type Integer = c_int;
/// `fmi2Boolean`.
pub type Boolean = c_int;
/// `fmi2String`.
pub type FmiString = *const c_char;

/// `fmi2Status`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// `fmi2OK`.
    Ok = 0,
    /// `fmi2Warning`.
    Warning = 1,
    /// `fmi2Discard`.
    Discard = 2,
    /// `fmi2Error`.
    Error = 3,
    /// `fmi2Fatal`.
    Fatal = 4,
    /// `fmi2Pending`.
    Pending = 5,
}

/// `fmi2StatusKind`.
pub type StatusKind = c_int;
/// `fmi2DoStepStatus`.
pub const DO_STEP_STATUS: StatusKind = 0;
/// `fmi2LastSuccessfulTime`.
pub const LAST_SUCCESSFUL_TIME: StatusKind = 2;
/// `fmi2Terminated`.
pub const TERMINATED: StatusKind = 3;

/// `fmi2CallbackLogger`: `(env, instanceName, status, category, message, ...)`.
pub type Logger = unsafe extern "C" fn(Env, FmiString, Status, FmiString, FmiString, ...);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct Callbacks {
    /// `logger`.
    pub logger: Option<Logger>,
    /// `allocateMemory` (unused: `canNotUseMemoryManagementFunctions`).
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// `freeMemory` (unused).
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// `stepFinished` (unused: steps are synchronous).
    pub step_finished: Option<unsafe extern "C" fn(Env, Status)>,
    /// `componentEnvironment`, passed back to the logger.
    pub component_environment: Env,
}
