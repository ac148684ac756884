//! The lowering's state, grouped by how long it lives.
//!
//! [`Lower`](super::Lower) keeps what the whole program shares ([`Env`](super::Env)), the
//! function builder, and one value per lifetime below it: [`BoxState`] lives for one box
//! instruction and is replaced when the next box starts.

use super::cache::Addr;
use cranelift_codegen::ir::Value;
use stljit_core::Width;

/// The state of the box instruction being lowered (the default outside boxes).
#[derive(Debug, Default)]
pub(crate) struct BoxState {
    /// The box has no pointer operand and no static error: it is lowered branch-free.
    pub(crate) free: bool,
    /// While a branch-free box runs under a power flow that is not constant.
    pub(crate) pred: Option<Pred>,
}

impl BoxState {
    /// The state at the start of a box; `free`: lower it branch-free.
    pub(crate) fn new(free: bool) -> BoxState {
        BoxState { free, pred: None }
    }

    /// The power flow the current box's writes are predicated on, if any.
    pub(crate) fn pf(&self) -> Option<Value> {
        self.pred.as_ref().map(|p| p.pf)
    }
}

/// The predicate of a branch-free box: writes of OUT and SMB1 keep the old value where its
/// power flow is zero (see [`Lower::set_byte_pred`](super::Lower::set_byte_pred)).
#[derive(Debug)]
pub(crate) struct Pred {
    /// The box's power flow (non-zero = run).
    pub(crate) pf: Value,
    /// Multi-byte values read since the box's last write, reused as the "old" value of a
    /// predicated write (every write of such a box is a no-op when PF is 0, so any value read
    /// inside it is the value at its start).
    pub(crate) reads: Vec<(Addr, Width, Value)>,
}

impl Pred {
    /// A predicate on `pf` with nothing read yet.
    pub(crate) fn new(pf: Value) -> Pred {
        Pred {
            pf,
            reads: Vec::new(),
        }
    }
}
