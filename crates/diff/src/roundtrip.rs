//! The front-end check of a generated program: print it as STL, compile the text, and require no
//! error and the same IR back (up to source locations). This is what makes a reproducer's
//! `program.stl` trustworthy, what the shrinker uses to stay within valid programs, and what the
//! `roundtrip` fuzz target checks.

use std::fmt;
use stljit_core::ir::{Program, SrcLoc};
use stljit_syntax::{compile_str, print_program, render_human};

/// Why a program did not survive print → compile.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RoundTripError {
    /// The front end rejected the printed text.
    Rejected {
        /// The printed program.
        text: String,
        /// The error diagnostics, rendered.
        diagnostics: String,
    },
    /// The text compiled to a different program.
    Changed {
        /// The printed program.
        text: String,
        /// The first POU and op index that differ (`None`: a table differs).
        at: Option<(usize, usize)>,
        /// The two versions of what differs, debug-printed.
        detail: String,
    },
}

impl fmt::Display for RoundTripError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RoundTripError::Rejected { diagnostics, .. } => {
                write!(
                    f,
                    "the front end rejects the printed program:\n{diagnostics}"
                )
            }
            RoundTripError::Changed { at, detail, .. } => match at {
                Some((pou, op)) => write!(f, "pou {pou} op {op} changed: {detail}"),
                None => write!(f, "program tables changed: {detail}"),
            },
        }
    }
}

impl std::error::Error for RoundTripError {}

/// The program with source locations and file names cleared, for comparison.
pub fn normalized(p: &Program) -> Program {
    let mut p = p.clone();
    p.files.clear();
    for pou in &mut p.pous {
        pou.locs = vec![SrcLoc::default(); pou.ops.len()];
    }
    p
}

/// Prints `program`, compiles the text for its profile, and returns the compiled program when it
/// equals the original up to source locations.
pub fn roundtrip(program: &Program) -> Result<Program, RoundTripError> {
    let text = print_program(program);
    let c = compile_str("fuzz.stl", &text, program.profile);
    let Some(back) = c.program else {
        let diagnostics = c
            .diagnostics
            .iter()
            .filter(|d| d.severity == stljit_syntax::Severity::Error)
            .map(|d| render_human(d, &c.sources))
            .collect::<Vec<_>>()
            .join("");
        return Err(RoundTripError::Rejected { text, diagnostics });
    };
    let (a, b) = (normalized(program), normalized(&back));
    if a == b {
        return Ok(back);
    }
    for (i, (pa, pb)) in a.pous.iter().zip(&b.pous).enumerate() {
        for (j, (oa, ob)) in pa.ops.iter().zip(&pb.ops).enumerate() {
            if oa != ob {
                return Err(RoundTripError::Changed {
                    text,
                    at: Some((i, j)),
                    detail: format!("{oa:?} became {ob:?}"),
                });
            }
        }
        if pa != pb {
            return Err(RoundTripError::Changed {
                text,
                at: Some((i, pa.ops.len().min(pb.ops.len()))),
                detail: format!(
                    "{} ops, labels {:?} became {} ops, labels {:?}",
                    pa.ops.len(),
                    pa.labels,
                    pb.ops.len(),
                    pb.labels
                ),
            });
        }
    }
    Err(RoundTripError::Changed {
        text,
        at: None,
        detail: format!(
            "pous {} timers {:?} counters {:?} edges {} became pous {} timers {:?} counters {:?} edges {}",
            a.pous.len(),
            a.timers,
            a.counters,
            a.edges.len(),
            b.pous.len(),
            b.timers,
            b.counters,
            b.edges.len()
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{GenConfig, case_from_seed};

    #[test]
    fn generated_programs_survive_print_and_compile() {
        let cfg = GenConfig::default();
        let mut failures = Vec::new();
        for seed in 0..3000 {
            let case = case_from_seed(seed, &cfg);
            if let Err(e) = roundtrip(&case.program) {
                failures.push(format!("seed {seed}: {e}"));
            }
        }
        assert!(
            failures.is_empty(),
            "{} failures:\n{}",
            failures.len(),
            failures
                .iter()
                .take(12)
                .cloned()
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}
