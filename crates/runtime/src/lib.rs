//! The runtime every stljit engine shares: the memory [`Image`], the scan cycle around the
//! program body ([`scan`]) with its interrupt event phases ([`interrupt`]), timers, counters
//! and edge detectors ([`timer`], [`counter`], [`edge`]), pointer resolution ([`pointer`]), the intricate instructions ([`arith`], [`bitops`],
//! [`block`], [`compare`], [`convert`], with the SMB1 rules in [`flags`]), the semantic switches
//! and the gate policy ([`rules`]) and the [`Engine`] trait. The Omron CP rules (BCD,
//! condition flags, moves, comparisons, arithmetic, timers and counters) are pure functions
//! over plain values in [`omron`], which the engines wire to the image ([`omron_image`]); which
//! flags each Omron op can change is read off those rules by [`omron_written`]. The
//! instructions of s7-200-more §4–§7 are [`ext`] over their rules: [`table`], [`text`] (ASCII
//! and number text), [`string`], [`rtc`] (the clock) and [`pid`]; [`operand`] resolves the
//! operands of every instruction the runtime runs whole.
//!
//! Everything is a function on the image bytes (`&mut [u8]` plus its [`Layout`]), so the
//! interpreter calls it directly and the Cranelift JIT calls the same code through the
//! `extern "C"` shims of [`ffi`]; the S7 timer and counter rules are written over
//! [`rule_ops::RuleOps`], so that the JIT can emit the same rule text inline. Semantics that both engines must agree on bit for bit exist once,
//! here. Tooling around the engines (stimulus files, traces, the simulation driver) is not
//! semantics and lives in the `stljit-sim` crate.

pub mod arith;
pub mod bitops;
pub mod block;
pub mod comm;
pub mod compare;
pub mod convert;
pub mod counter;
pub mod edge;
pub mod engine;
pub mod ext;
pub mod ffi;
pub mod flags;
pub mod hsc;
pub mod image;
pub mod interrupt;
pub mod mem;
pub mod omron;
pub mod omron_image;
pub mod omron_written;
pub mod operand;
pub mod pid;
pub mod pointer;
pub mod pulse;
pub mod rtc;
pub mod rule_ops;
pub mod rules;
pub mod scan;
pub mod string;
pub mod table;
pub mod text;
pub mod timer;

#[cfg(test)]
mod testutil;

pub use engine::{ChangeWatch, Engine};
pub use image::{Image, ImageError};
pub use stljit_core::layout::Layout;
