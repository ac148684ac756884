//! The condition-flag discipline of omron-cp.md §2.10 within a circuit: OMR-W033.
//!
//! A flag read on a branch should see the flags of the instruction that branch comes from (the
//! last flag-changing instruction before it on the same branch, §2.10 rule 1). Three ways it
//! does not, each a W033 at the read:
//!
//! 1. **Intervening instruction** (pitfall 2, §6.8 part A): the branch was saved with
//!    `OUT TRn` after instruction A and restored with `LD TRn` after another instruction W that
//!    changes the flag ran — the read sees W's flag, not A's.
//! 2. **Differentiated A** (pitfall 3, §6.8 part D): A is an `@`/`%` instruction, so it runs
//!    only in its edge cycle; in the other cycles the flag comes from earlier circuits.
//! 3. **Read by a differentiated instruction** (pitfall 3): no instruction on the branch
//!    changed the flag, and the read feeds a differentiated instruction (`@`/`%`, DIFU, DIFD,
//!    UP, DOWN) — the flag's accidental OFF→ON fires it.
//!
//! Which flags an instruction changes is read off the runtime's rules
//! (`stljit_runtime::omron_written`), from the ops the instruction lowered to. A flag read at
//! a circuit's start is W032 and one before any flag changed in the task W034, not W033.

use crate::lexer::Tok;
use stljit_core::omron::SystemBit;
use stljit_source::{Code, Diagnostic, Span, clip};

/// An instruction that changes condition flags.
#[derive(Clone, Debug)]
struct Writer {
    /// As messages name it (`MOV(021)`).
    what: String,
    line: u32,
    /// The flags it can change.
    mask: u16,
    /// `@`/`%`: it runs only in its edge cycle.
    differentiated: bool,
}

/// A branch point: the writer the branch comes from, and how many writers had run then.
#[derive(Clone, Copy, Debug, Default)]
struct Point {
    from: Option<usize>,
    seen: usize,
}

/// The flag state of the current circuit.
#[derive(Clone, Debug, Default)]
pub(crate) struct FlagBranches {
    /// The flag-changing instructions of the circuit, in execution order.
    writers: Vec<Writer>,
    /// The current branch.
    here: Point,
    /// The branch points saved by `OUT TRn`.
    tr: [Point; 16],
    /// Flag reads on the branch that no writer of the branch explains (case 3 candidates).
    orphan_reads: Vec<(Span, String)>,
}

impl FlagBranches {
    /// A new circuit starts.
    pub(crate) fn new_circuit(&mut self) {
        *self = FlagBranches::default();
    }

    /// An instruction that changes the flags in `mask` ran; the branch continues from it.
    pub(crate) fn wrote(&mut self, what: String, line: u32, mask: u16, differentiated: bool) {
        if mask == 0 {
            return;
        }
        self.writers.push(Writer {
            what,
            line,
            mask,
            differentiated,
        });
        self.here = Point {
            from: Some(self.writers.len() - 1),
            seen: self.writers.len(),
        };
    }

    /// `OUT TRn`.
    pub(crate) fn store_tr(&mut self, n: u8) {
        if let Some(p) = self.tr.get_mut(usize::from(n)) {
            *p = self.here;
        }
    }

    /// `LD TRn`: the branch saved there continues; reads after the earlier branch point are
    /// not on it.
    pub(crate) fn load_tr(&mut self, n: u8) {
        if let Some(p) = self.tr.get(usize::from(n)) {
            self.here = *p;
        }
        self.orphan_reads.clear();
    }

    /// A read of condition flag `flag` (written as `tok`, at `span`): W033 for cases 1 and 2.
    pub(crate) fn read(&mut self, flag: SystemBit, tok: &Tok, span: Span) -> Option<Diagnostic> {
        let bit = 1u16 << flag.index();
        let name = clip(&tok.text);
        let own = self.here.from.map(|i| &self.writers[i]);
        let intervening = self.writers[self.here.seen..]
            .iter()
            .rev()
            .find(|w| w.mask & bit != 0);
        let message = match (intervening, own) {
            (Some(w), Some(a)) => format!(
                "{name} was last changed by {} at line {}, not by {} at line {}; take both results of {} with OUT before anything else runs",
                w.what, w.line, a.what, a.line, a.what
            ),
            (Some(w), None) => format!(
                "{name} was last changed by {} at line {}, not by an instruction on this branch",
                w.what, w.line
            ),
            (None, Some(a)) if a.differentiated && a.mask & bit != 0 => format!(
                "{name} comes from {} at line {} only in the cycle it executes; in the other cycles an earlier instruction set it — run non-differentiated instructions from a DIFU(013)/DIFD(014) bit instead",
                a.what, a.line
            ),
            (None, Some(_)) => return None,
            (None, None) => {
                self.orphan_reads.push((span, name));
                return None;
            }
        };
        Some(Diagnostic::new(
            Code::OmrFlagOverwritten,
            span,
            &tok.text,
            format!("line {}: {message}", span.line),
        ))
    }

    /// A differentiated instruction `what` at `line` takes the branch's condition: W033 for
    /// each flag read on the branch that no instruction of the branch explains (case 3).
    pub(crate) fn differentiated(&mut self, what: &str, line: u32) -> Vec<Diagnostic> {
        std::mem::take(&mut self.orphan_reads)
            .into_iter()
            .map(|(span, name)| {
                Diagnostic::new(
                    Code::OmrFlagOverwritten,
                    span,
                    &name,
                    format!(
                        "line {}: {name} is read by the differentiated {what} at line {line}, but no instruction on this branch changed it: it comes from whichever instruction ran last and can fire {what} by accident",
                        span.line
                    ),
                )
            })
            .collect()
    }
}
