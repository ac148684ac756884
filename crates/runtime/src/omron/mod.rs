//! The Omron CP rules of omron-cp.md as pure functions over plain values: BCD ([`bcd`]), the
//! condition flags as a value and the flag writes every instruction returns ([`flags`]), moves
//! and comparisons ([`data`]), the arithmetic of §3.6 ([`arith`]), the TIM family and TTIM
//! ([`timer`]) and CNT/CNTR ([`counter`]).
//!
//! Nothing here touches the image: an engine reads the operands, calls the rule and writes what
//! it returns. Every rule returns a [`flags::FlagWrites`] (which condition flags it assigns and
//! to what), so "flags not listed are unchanged" (spec §3) is data, applied by one function.
//! The instruction kinds are core's enums ([`stljit_core::ir::OmronArith`],
//! [`stljit_core::ir::OmronTimerKind`], [`stljit_core::ir::OmronCounterKind`]), the ones the IR
//! carries, so no engine maps between two lists.

pub mod arith;
pub mod bcd;
pub mod counter;
pub mod data;
pub mod flags;
pub mod timer;

pub use arith::ArithOutcome;
pub use counter::OmronCounter;
pub use flags::{CondFlags, Flag, FlagWrites};
pub use timer::OmronTimer;
