//! The round trips a generated program must survive, in two forms:
//!
//! - **IR text** ([`ir_text_roundtrip`]): `stljit_core::text::print`, then `text::parse`, must
//!   give back exactly the same program, source locations included. This is what makes a
//!   reproducer's `program.ir` and `tests/regressions/` trustworthy, whatever the dialect.
//! - **The dialect's front end** ([`front_end_roundtrip`]): the program printed in its
//!   dialect (S7 STL, or Omron mnemonics for an Omron profile), compiled again, must be
//!   accepted and give the same IR up to source locations. This is each printer's own test,
//!   and it keeps the shrinker within programs the front end can express.
//!
//! [`roundtrip`] checks both; campaigns, the shrinker's callers and the `roundtrip` fuzz target
//! use it.

use std::fmt;
use stljit_core::Family;
use stljit_core::ir::{Program, SrcLoc};
use stljit_core::text::{self, ParseError};

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
    /// The dialect's printer refused the program (an Omron op sequence no text lowers to).
    NotPrintable {
        /// Why.
        message: String,
    },
    /// The front end rejected the printed program.
    FrontEndRejected {
        /// The dialect (`s7`, `omron`).
        dialect: &'static str,
        /// The printed program.
        text: String,
        /// The error diagnostics, rendered.
        diagnostics: String,
    },
    /// The printed program compiled to a different program.
    FrontEndChanged {
        /// The dialect.
        dialect: &'static str,
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
            RoundTripError::NotPrintable { message } => {
                write!(f, "the printer refuses the program: {message}")
            }
            RoundTripError::FrontEndRejected {
                dialect,
                diagnostics,
                ..
            } => {
                write!(
                    f,
                    "the {dialect} front end rejects the printed program:\n{diagnostics}"
                )
            }
            RoundTripError::FrontEndChanged {
                dialect,
                difference,
                ..
            } => write!(f, "{dialect} print and compile: {difference}"),
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

/// Both round trips; returns the program the dialect's front end compiled back.
pub fn roundtrip(program: &Program) -> Result<Program, RoundTripError> {
    ir_text_roundtrip(program)?;
    front_end_roundtrip(program)
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

/// The program printed in the dialect of its profile (S7 STL or Omron mnemonics).
pub fn dialect_text(program: &Program) -> Result<String, RoundTripError> {
    match program.profile.profile().family {
        Family::S7 => Ok(stljit_front_s7::print_program(program)),
        Family::Omron => {
            stljit_front_omron::print_program(program).map_err(|e| RoundTripError::NotPrintable {
                message: e.to_string(),
            })
        }
    }
}

/// Compiles `text`, the dialect text of `like` or a cut of it, in the dialect of `like`'s
/// profile with the options its print needs (an Omron program with backward jumps compiles
/// with `allow_backward_jumps`): the program, or the rendered errors.
pub fn compile_dialect(text: &str, like: &Program) -> Result<Program, String> {
    let render = |errors: Vec<String>| errors.join("");
    let profile = like.profile;
    match profile.profile().family {
        Family::S7 => {
            let c = stljit_front_s7::compile_str("fuzz.stl", text, profile);
            c.program.ok_or_else(|| {
                render(
                    c.diagnostics
                        .iter()
                        .filter(|d| d.severity == stljit_front_s7::Severity::Error)
                        .map(|d| stljit_front_s7::render_human(d, &c.sources))
                        .collect(),
                )
            })
        }
        Family::Omron => {
            let file = stljit_front_omron::SourceFile::from_text("fuzz.omr", text);
            let options = stljit_front_omron::printed_options(like);
            let c = stljit_front_omron::compile_with(&[file], None, profile, options);
            c.program.ok_or_else(|| {
                render(
                    c.diagnostics
                        .iter()
                        .filter(|d| d.severity == stljit_front_omron::Severity::Error)
                        .map(|d| stljit_front_omron::render_human(d, &c.sources))
                        .collect(),
                )
            })
        }
    }
}

/// Prints `program` in its dialect, compiles the text for its profile, and returns the
/// compiled program when it equals the original up to source locations.
pub fn front_end_roundtrip(program: &Program) -> Result<Program, RoundTripError> {
    let dialect = match program.profile.profile().family {
        Family::S7 => "s7",
        Family::Omron => "omron",
    };
    let text = dialect_text(program)?;
    let back = compile_dialect(&text, program).map_err(|diagnostics| {
        RoundTripError::FrontEndRejected {
            dialect,
            text: text.clone(),
            diagnostics,
        }
    })?;
    let (a, b) = (normalized(program), normalized(&back));
    if a == b {
        return Ok(back);
    }
    Err(RoundTripError::FrontEndChanged {
        dialect,
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

    /// 3,000 generated Omron programs (text compiled by the front end) survive both round
    /// trips: IR text, and the Omron printer's text compiled again.
    #[test]
    fn generated_omron_programs_survive_both_round_trips() {
        let cfg = GenConfig::default();
        let mut failures = Vec::new();
        for seed in 0..3000 {
            let mut c = crate::rng::Choices::from_seed(seed);
            match crate::generate::omron::generate(&mut c, &cfg) {
                Err(e) => failures.push(format!("seed {seed}: {e}")),
                Ok(g) => {
                    if let Err(e) = roundtrip(&g.case.program) {
                        failures.push(format!("seed {seed}: {e}\n{}", g.source));
                    }
                }
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
