//! A call with parameters ([`Op::CallArgs`](super::Op::CallArgs)): the subroutine's formal
//! parameters are locations in the callee's L frame, each paired with the caller's actual
//! (s7-200-more §1.4–§1.5). The IR keeps no declaration: a call names every formal it copies,
//! so an engine needs nothing but the op.
//!
//! Execution, the same in every engine: without power flow ENO = 0 and nothing happens; a call
//! beyond the profile's nesting depth is error 0x0008; every actual is resolved in the caller's
//! frame first (a pointer that does not resolve is 0x0006); either error skips the call. Then IN
//! and IN_OUT actuals are copied into the frame one level deeper (in argument order), the callee
//! runs, IN_OUT and OUT formals are copied back to the places resolved before the call (in
//! argument order, so a later write wins), and ENO = 1. A BOOL copies one bit; a value copies
//! its width big-endian.

use super::operand::{BitLoc, Loc, Operand};
use super::uses::{Access, OperandUse};
use crate::area::{Area, Width};
use crate::index::PouId;

/// How a parameter is passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArgDir {
    /// Copied in before the call (`VAR_INPUT`).
    In,
    /// Copied in before and back after the call (`VAR_IN_OUT`).
    InOut,
    /// Copied back after the call (`VAR_OUTPUT`); the formal is not initialised.
    Out,
}

impl ArgDir {
    /// Every direction.
    pub const ALL: &'static [ArgDir] = &[ArgDir::In, ArgDir::InOut, ArgDir::Out];

    /// Whether the actual is copied into the callee's frame before the call.
    pub fn copies_in(self) -> bool {
        self != ArgDir::Out
    }

    /// Whether the formal is copied back to the actual after the call.
    pub fn copies_out(self) -> bool {
        self != ArgDir::In
    }

    /// How the call accesses the actual.
    pub fn access(self) -> Access {
        match self {
            ArgDir::In => Access::Read,
            ArgDir::InOut => Access::ReadWrite,
            ArgDir::Out => Access::Write,
        }
    }
}

/// A formal parameter and its actual.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArgValue {
    /// A BOOL: one bit of the callee's frame (area `L`) and a bit of the caller.
    Bit {
        /// The formal, in the callee's frame.
        formal: BitLoc,
        /// The actual, in the caller's context (an `L` bit is the caller's frame).
        actual: BitLoc,
    },
    /// A BYTE, WORD/INT or DWORD/DINT/REAL.
    Value {
        /// The width both sides have.
        width: Width,
        /// The formal's first byte, in the callee's frame (area `L`).
        formal: Loc,
        /// The actual: a location, a pointer resolved at call time, or (IN only) a constant.
        actual: Operand,
    },
}

/// One parameter of a call.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Arg {
    /// How it is passed.
    pub dir: ArgDir,
    /// The formal and the actual.
    pub value: ArgValue,
}

impl Arg {
    /// The actual as an operand use (values only), for the verifier's location rules.
    pub fn actual_use(&self) -> Option<OperandUse> {
        match self.value {
            ArgValue::Value { width, actual, .. } => Some(OperandUse {
                operand: actual,
                width,
                access: self.dir.access(),
            }),
            ArgValue::Bit { .. } => None,
        }
    }

    /// The formal as an operand use of the frame one level deeper (values only): written by the
    /// copy-in, read by the copy-back.
    pub fn formal_use(&self) -> Option<OperandUse> {
        match self.value {
            ArgValue::Value { width, formal, .. } => Some(OperandUse {
                operand: Operand::Mem(formal),
                width,
                access: Access::ReadWrite,
            }),
            ArgValue::Bit { .. } => None,
        }
    }

    /// The bits the argument names: the actual (with the call's access) and the formal.
    pub fn bit_uses(&self) -> Option<[(BitLoc, Access); 2]> {
        match self.value {
            ArgValue::Bit { formal, actual } => {
                Some([(actual, self.dir.access()), (formal, Access::ReadWrite)])
            }
            ArgValue::Value { .. } => None,
        }
    }

    /// Whether the formal lies in area `L` (the verifier's rule).
    pub fn formal_is_local(&self) -> bool {
        match self.value {
            ArgValue::Bit { formal, .. } => formal.area == Area::L,
            ArgValue::Value { formal, .. } => formal.area == Area::L,
        }
    }
}

/// The callee and the parameters of an [`Op::CallArgs`](super::Op::CallArgs), boxed so that
/// the op stays small.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct CallArgs {
    /// The subroutine.
    pub callee: PouId,
    /// The parameters in table order (IN, IN_OUT, OUT, declaration order inside each).
    pub args: Vec<Arg>,
}
