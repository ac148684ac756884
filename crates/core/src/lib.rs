//! The hub of stljit: the dialect-neutral IR ([`ir::Program`]), the CPU profiles that fix area
//! ranges, timer resolutions and interrupt events ([`profile::CpuProfile`], [`interrupt`]), the
//! flat memory-image layout every engine addresses ([`layout::Layout`]) and the status and
//! error codes engines report ([`codes`]).
//!
//! This crate has no dependencies and no behaviour beyond arithmetic on offsets, the structural
//! rules of the IR ([`ir::verify`], [`ir::Op::successors`], [`ir::Op::stack_effect`]) and the IR's
//! own text form ([`text`]): front ends build [`ir::Program`]s, engines execute them, and both
//! agree on bytes through [`layout::Layout`].

pub mod area;
pub mod codes;
pub mod comm;
pub mod hsc;
pub mod index;
pub mod instr_set;
pub mod interrupt;
pub mod ir;
pub mod layout;
pub mod omron;
pub mod profile;
pub mod pulse;
pub mod text;

pub use area::{Area, Width};
pub use codes::{ErrorCode, FatalCode, ScanStatus};
pub use index::{CounterId, EdgeSlot, FileId, LabelId, OpIdx, PouId, TimerId};
pub use instr_set::InstrSet;
pub use layout::Layout;
pub use profile::{CpuProfile, Family, GatePolicy, ProfileId};
