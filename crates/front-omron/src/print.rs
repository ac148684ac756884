//! IR → Omron mnemonic text: [`print_program`] reads the op patterns the lowering emits (the
//! crate doc lists them) back into instructions, so that the printed text compiles to the same
//! IR up to source locations (with the options [`printed_options`] gives). Fuzz reproducers
//! (`program.omr`), the dialect round trip of `stljit-diff` and the `parse`/`roundtrip` fuzz
//! targets rely on that.
//!
//! Where an op sequence is not one the front end emits (an S7 op, a lone `Pop`, a `For` that is
//! not the FOR pattern, labels in an order no text allocates …) the printer returns a
//! [`PrintError`] naming the POU and op instead of text that would compile to something else.
//!
//! Choices where several texts give the same IR: `LD b` + `UP` is printed `@LD b`, `NOT` +
//! `OUT b` + `NOT` is `OUT NOT b`, every jump is a numbered `JMP`/`CJP` (JMP0/JME0, CJPN and a
//! block program BPRG/BEND outside a step area lower to the same ops as JMP/JME; inside a step
//! area, where no jump may stand, they are BPRG/BEND), SNXT outside a step area is `SET` (the
//! same op), `!` is written only where it changes the IR (the refresh boxes of an operand in a
//! built-in input or output word), the plain timers and counters of a binary-mode program are
//! their `X` forms, constants are `#hex`, and IORF, which lowers to nothing, never appears.
//!
//! Program units ([`units`]): the main POU's tasks (split at `Op::TaskStart`) are printed as
//! `$TASK CYCLIC n` programs numbered in their run order, each with its subroutines and END, in
//! the source order the IR's edge slots and subroutine order fix; edge memories of units that
//! never run (standby tasks, unassigned programs, `$FB` bodies are not in the IR, but their
//! edge slots are) come back as `$TASK UNASSIGNED` programs of differentiated contacts.

use crate::Options;
use crate::mnemonics::{Flow, Group, TABLE};
use std::fmt;
use stljit_core::ir::{Op, Program};
use stljit_core::{Family, PouId};

/// Why a program cannot be printed as Omron text: it is not a program the Omron front end
/// produces (for example IR built by hand or cut by a shrinker).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PrintError {
    /// The POU (index into `Program::pous`).
    pub pou: usize,
    /// The op the pattern starts at, when the problem is an op.
    pub op: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl PrintError {
    fn at_pou(pou: usize, message: impl Into<String>) -> PrintError {
        PrintError {
            pou,
            op: None,
            message: message.into(),
        }
    }
}

impl fmt::Display for PrintError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.op {
            Some(op) => write!(f, "pou {} op {}: {}", self.pou, op, self.message),
            None => write!(f, "pou {}: {}", self.pou, self.message),
        }
    }
}

impl std::error::Error for PrintError {}

/// Prints `program` (one the Omron front end compiled, or equal to one up to source locations)
/// as Omron mnemonic text: each task's program (the main program, its subroutines `SBN(092)
/// n` … `RET(093)`, then `END(001)`), behind `$TASK` directives when there are several units.
pub fn print_program(program: &Program) -> Result<String, PrintError> {
    if program.profile.profile().family != Family::Omron {
        return Err(PrintError::at_pou(0, "not an Omron profile"));
    }
    let plan = units::plan(program)?;
    let mut out = format!(
        "; printed by stljit from IR (profile {}{})\n",
        program.profile.name(),
        if printed_options(program).allow_backward_jumps {
            "; compile with allow_backward_jumps"
        } else {
            ""
        }
    );
    let directives = plan.units.len() > 1;
    for unit in &plan.units {
        match unit {
            units::Unit::Task(k) => {
                if directives {
                    out.push_str(&format!("$TASK CYCLIC {k}\n"));
                }
                plan.print_task(program, *k, &mut out)?;
            }
            units::Unit::Unused(edges) => units::print_unused(edges, &mut out),
        }
    }
    Ok(out)
}

/// The front-end options the text [`print_program`] writes for `program` compiles back with:
/// `allow_backward_jumps` when a jump goes back to an earlier JME; `tc_mode` stays BCD (the
/// printer spells the timers and counters of a binary-mode program as their `X` forms).
pub fn printed_options(program: &Program) -> Options {
    let backward = program.pous.iter().any(|pou| {
        pou.ops.iter().enumerate().any(|(i, op)| {
            matches!(op, Op::Jump(l) if pou.labels.get(l.index()).is_some_and(|at| at.index() <= i))
        })
    });
    Options {
        allow_backward_jumps: backward,
        ..Options::default()
    }
}

/// One instruction line.
fn line(head: &str, operands: &[String]) -> String {
    if operands.is_empty() {
        format!("{head}\n")
    } else {
        format!("{head:<10} {}\n", operands.join(" "))
    }
}

/// `options` + the table name of `group` + its function code.
fn head(options: &str, group: Group) -> Result<String, String> {
    let m = TABLE
        .iter()
        .find(|m| m.group == group)
        .ok_or_else(|| format!("no mnemonic for {group:?}"))?;
    let allowed = match options.trim_start_matches('!') {
        "@" => m.allowed.up,
        "%" => m.allowed.down,
        _ => true,
    } && (!options.starts_with('!') || m.allowed.immediate);
    if !allowed {
        return Err(format!("{options}{} is not allowed", m.name));
    }
    Ok(with_code(options, m.name, m.code))
}

/// The line of a program-control instruction without options.
fn control(flow: Flow, operands: &[String]) -> Result<String, String> {
    Ok(line(&head("", Group::Control(flow))?, operands))
}

fn with_code(options: &str, name: &str, code: Option<u16>) -> String {
    match code {
        Some(c) => format!("{options}{name}({c:03})"),
        None => format!("{options}{name}"),
    }
}

/// `@` or `%` for a rising or falling edge.
fn edge_option(falling: bool) -> &'static str {
    if falling { "%" } else { "@" }
}

/// The callee of a call op, if it is a plain `CALL` (SBS).
fn callee(op: &Op) -> Option<PouId> {
    match op {
        Op::Call(p) => Some(*p),
        _ => None,
    }
}

mod body;
mod circuits;
mod control;
mod operands;
mod refresh;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_units;
mod units;
