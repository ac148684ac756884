//! The round trips a generated program must survive, in two forms:
//!
//! - **IR text** ([`ir_text_roundtrip`]): `stljit_core::text::print`, then `text::parse`, must
//!   give back exactly the same program, source locations included. This is what makes a
//!   reproducer's `program.ir` and `tests/regressions/` trustworthy, whatever the dialect.
//! - **S7 front end** ([`s7_roundtrip`]): the S7 printer's STL, compiled again, must be accepted
//!   and give the same IR up to source locations. This is the S7 front end's own test, and it
//!   keeps the shrinker within programs that front end can express.
//!
//! [`roundtrip`] checks both; campaigns, the shrinker's callers and the `roundtrip` fuzz target
//! use it.

use std::fmt;
use stljit_core::ir::{Program, SrcLoc};
use stljit_core::text::{self, ParseError};
use stljit_front_s7::{compile_str, print_program, render_human};

/// Why a program did not survive a round trip.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RoundTripError {
    /// The IR text of the program does not parse.
    IrTextRejected {
        /// The printed IR text.
        text: String,
        /// Where and why it does not parse.
        error: ParseError,
    },
    /// The IR text parsed to a different program.
    IrTextChanged {
        /// The printed IR text.
        text: String,
        /// What differs.
        difference: Difference,
    },
    /// The S7 front end rejected the printed STL.
    S7Rejected {
        /// The printed program.
        text: String,
        /// The error diagnostics, rendered.
        diagnostics: String,
    },
    /// The printed STL compiled to a different program.
    S7Changed {
        /// The printed program.
        text: String,
        /// What differs (source locations aside).
        difference: Difference,
    },
}

/// The first difference between two programs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Difference {
    /// The first POU and op index that differ (`None`: a table differs).
    pub at: Option<(usize, usize)>,
    /// The two versions of what differs, debug-printed.
    pub detail: String,
}

impl fmt::Display for Difference {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.at {
            Some((pou, op)) => write!(f, "pou {pou} op {op} changed: {}", self.detail),
            None => write!(f, "program tables changed: {}", self.detail),
        }
    }
}

impl fmt::Display for RoundTripError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RoundTripError::IrTextRejected { error, .. } => {
                write!(f, "the IR text of the program does not parse: {error}")
            }
            RoundTripError::IrTextChanged { difference, .. } => {
                write!(f, "IR text round trip: {difference}")
            }
            RoundTripError::S7Rejected { diagnostics, .. } => {
                write!(
                    f,
                    "the front end rejects the printed program:\n{diagnostics}"
                )
            }
            RoundTripError::S7Changed { difference, .. } => write!(f, "{difference}"),
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

/// Both round trips; returns the program the S7 front end compiled back.
pub fn roundtrip(program: &Program) -> Result<Program, RoundTripError> {
    ir_text_roundtrip(program)?;
    s7_roundtrip(program)
}

/// Prints `program` as IR text and parses it again; the result must equal `program` exactly.
pub fn ir_text_roundtrip(program: &Program) -> Result<(), RoundTripError> {
    let text = text::print(program);
    match text::parse(&text) {
        Err(error) => Err(RoundTripError::IrTextRejected { text, error }),
        Ok(back) if back == *program => Ok(()),
        Ok(back) => Err(RoundTripError::IrTextChanged {
            difference: first_difference(program, &back),
            text,
        }),
    }
}

/// Prints `program` as S7 STL, compiles the text for its profile, and returns the compiled
/// program when it equals the original up to source locations.
pub fn s7_roundtrip(program: &Program) -> Result<Program, RoundTripError> {
    let text = print_program(program);
    let c = compile_str("fuzz.stl", &text, program.profile);
    let Some(back) = c.program else {
        let diagnostics = c
            .diagnostics
            .iter()
            .filter(|d| d.severity == stljit_front_s7::Severity::Error)
            .map(|d| render_human(d, &c.sources))
            .collect::<Vec<_>>()
            .join("");
        return Err(RoundTripError::S7Rejected { text, diagnostics });
    };
    let (a, b) = (normalized(program), normalized(&back));
    if a == b {
        return Ok(back);
    }
    Err(RoundTripError::S7Changed {
        text,
        difference: first_difference(&a, &b),
    })
}

/// Where `b` first differs from `a` (which must differ somewhere).
fn first_difference(a: &Program, b: &Program) -> Difference {
    for (i, (pa, pb)) in a.pous.iter().zip(&b.pous).enumerate() {
        for (j, (oa, ob)) in pa.ops.iter().zip(&pb.ops).enumerate() {
            if oa != ob {
                return Difference {
                    at: Some((i, j)),
                    detail: format!("{oa:?} became {ob:?}"),
                };
            }
        }
        if pa != pb {
            return Difference {
                at: Some((i, pa.ops.len().min(pb.ops.len()))),
                detail: format!(
                    "{} ops, labels {:?}, name {:?}, kind {:?} became {} ops, labels {:?}, \
                     name {:?}, kind {:?} (or the source locations differ)",
                    pa.ops.len(),
                    pa.labels,
                    pa.name,
                    pa.kind,
                    pb.ops.len(),
                    pb.labels,
                    pb.name,
                    pb.kind,
                ),
            };
        }
    }
    Difference {
        at: None,
        detail: format!(
            "pous {} timers {:?} counters {:?} edges {:?} depth {} files {:?} became \
             pous {} timers {:?} counters {:?} edges {:?} depth {} files {:?}",
            a.pous.len(),
            a.timers,
            a.counters,
            a.edges,
            a.logic_stack_depth,
            a.files,
            b.pous.len(),
            b.timers,
            b.counters,
            b.edges,
            b.logic_stack_depth,
            b.files,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{GenConfig, case_from_bytes, case_from_seed};

    fn assert_no_failures(failures: &[String]) {
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

    /// 3,000 generated programs survive both round trips.
    #[test]
    fn generated_programs_survive_both_round_trips() {
        let cfg = GenConfig::default();
        let mut failures = Vec::new();
        for seed in 0..3000 {
            let case = case_from_seed(seed, &cfg);
            if let Err(e) = roundtrip(&case.program) {
                failures.push(format!("seed {seed}: {e}"));
            }
        }
        assert_no_failures(&failures);
    }

    /// The IR text property `parse(print(p)) == p` on 3,000 more generated programs, larger
    /// ones (up to 40 networks, 8 subroutines) and ones built from raw fuzzer-like bytes.
    #[test]
    fn generated_programs_survive_the_ir_text_round_trip() {
        let big = GenConfig {
            max_networks: 40,
            max_subroutines: 8,
            max_ops_per_pou: 600,
            ..GenConfig::default()
        };
        let mut failures = Vec::new();
        for seed in 3000..5000 {
            let case = case_from_seed(seed, &big);
            if let Err(e) = ir_text_roundtrip(&case.program) {
                failures.push(format!("seed {seed}: {e}"));
            }
        }
        let mut state = 0x1234_5678_9ABC_DEF0u64;
        for i in 0..1000 {
            let bytes: Vec<u8> = (0..(i % 400))
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    state as u8
                })
                .collect();
            let case = case_from_bytes(&bytes, &GenConfig::default());
            if let Err(e) = ir_text_roundtrip(&case.program) {
                failures.push(format!("bytes #{i}: {e}"));
            }
        }
        assert_no_failures(&failures);
    }
}
