//! What every command that executes a program does first: print the diagnostics of the
//! compilation and hand back the program only when it has no errors.

use std::io::Write as _;
use stljit_core::ir::Program;
use stljit_front::{Compilation, render_human};

/// Prints every diagnostic to stderr; returns the program when there were no errors.
pub(crate) fn checked_program(c: &Compilation) -> Option<&Program> {
    let mut err = std::io::stderr().lock();
    for d in &c.diagnostics {
        let _ = writeln!(err, "{}", render_human(d, &c.sources));
    }
    if c.program.is_none() {
        let _ = writeln!(err, "{} error(s); nothing was run", c.error_count());
    }
    c.program.as_ref()
}
