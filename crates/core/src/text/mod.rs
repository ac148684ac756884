//! The IR's own text form, as CLIF is Cranelift's: [`print`] writes a whole [`Program`] and
//! [`parse`] reads it back, so that `parse(&print(p)) == Ok(p)` for every program, source
//! locations and file names included.
//!
//! The form is dialect-neutral: ops are spelled by their IR names (`load`, `set_range`,
//! `box int_arith`), areas by their [`crate::Area`] variant names (`V.100`, `TimerBit.37.0`),
//! indices by their `Display` (`pou1`, `op12`, `L0`, `edge3`, `T37`, `C5`, `file0`) and the small
//! enums by their variant names (`Int`, `Ge`, `DWord`, `Retentive`). No front end's mnemonics or
//! address prefixes appear, which is why fuzz reproducers and `tests/regressions/` are kept in
//! it: they do not depend on any one dialect's printer. The grammar is in `docs/ir-text.md`.
//!
//! ```text
//! stljit-ir 1
//! profile a5
//! logic_stack_depth 9
//! file file0 "main.stl"
//! timer T37 kind=On resolution=100ms
//! edge edge0 init=0
//!
//! pou pou0 main "MAIN" {
//!   target L0 op3
//!   op0 @file0:1:1 load bit I.0.3
//!   op1 @file0:2:1 edge slot=edge0 falling=0
//!   op2 @file0:3:1 jump L0
//!   op3 @file0:4:1 label L0
//!   op4 @file0:5:1 box move width=Word src=const(7) dst=V.10
//! }
//! ```
//!
//! The parser checks syntax and the positional indices (`op3` must be the fourth op, `edge2`
//! the third edge), not meaning: a text that names a label the POU does not have parses, and the
//! IR verifier is what rejects it. The parser never panics; every error names its line and
//! column ([`ParseError`]).

mod error;
mod ext;
mod lex;
mod parse;
mod print;
#[cfg(test)]
mod tests;

pub use error::{ParseError, ParseErrorKind};
pub use parse::parse;
pub use print::print;

use std::fmt;

/// The first word of every text; the version number follows it.
const MAGIC: &str = "stljit-ir";

/// The version of the format [`print`] writes and [`parse`] reads.
pub const VERSION: u32 = 1;

/// Whether `value`'s `Debug` form is exactly `word`, without allocating. Enum words in the text
/// are `Debug` names, so the enum declaration is the one place that spells them.
fn debug_is<T: fmt::Debug>(value: &T, word: &str) -> bool {
    struct Compare<'a> {
        rest: &'a str,
        equal: bool,
    }
    impl fmt::Write for Compare<'_> {
        fn write_str(&mut self, s: &str) -> fmt::Result {
            match self.rest.strip_prefix(s) {
                Some(rest) if self.equal => self.rest = rest,
                _ => self.equal = false,
            }
            Ok(())
        }
    }
    let mut c = Compare {
        rest: word,
        equal: true,
    };
    let _ = fmt::write(&mut c, format_args!("{value:?}"));
    c.equal && c.rest.is_empty()
}
