//! Static logic-stack depth analysis (spec §3.3): warns when a contact or ALD/OLD/LPP/LRD
//! consumes a level nothing loaded, and when more than nine levels are live.
//!
//! The depth is tracked per straight-line stretch. A load that follows an output, box or
//! control instruction starts a new rung and resets the count: the CPU keeps old levels, but no
//! well-formed rung reads them. Labels and jumps make the depth unknown (no warnings) until the
//! next rung starts, so that jump targets never produce false alarms.

use stljit_core::ir::Op;
use stljit_source::Code;
use stljit_source::{Diagnostic, Span};

/// Depth tracker for one POU.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StackCheck {
    depth: Option<u8>,
    after_output: bool,
    levels: u8,
}

impl StackCheck {
    /// A tracker for a POU starting with `depth` known levels (0 for main, 1 for a subroutine,
    /// whose stack starts as S0 = 1).
    pub(crate) fn new(depth: u8, levels: u8) -> Self {
        StackCheck {
            depth: Some(depth),
            after_output: false,
            levels,
        }
    }

    fn need(&self, n: u8, op: &str, span: Span, text: &str, diags: &mut Vec<Diagnostic>) {
        if let Some(d) = self.depth.filter(|&d| d < n) {
            let loaded = match d {
                0 => "nothing was loaded".to_owned(),
                1 => "only 1 level was loaded".to_owned(),
                d => format!("only {d} levels were loaded"),
            };
            diags.push(
                Diagnostic::new(
                    Code::StackUnderflow,
                    span,
                    text,
                    format!("`{op}` reads {n} stack level(s) but {loaded} in this rung"),
                )
                .help("start the rung with LD/LDN (or LPS before the branch); the level read here holds an older rung's value"),
            );
        }
    }

    /// A line that produced no op (unknown, not supported or erroneous): what it did to the stack
    /// is unknown, so no warning follows until the next rung starts.
    pub(crate) fn lost_line(&mut self) {
        self.depth = None;
        self.after_output = true;
    }

    /// Accounts for `op` at `span` (the mnemonic); `text` is the mnemonic as written.
    pub(crate) fn step(&mut self, op: &Op, span: Span, text: &str, diags: &mut Vec<Diagnostic>) {
        let push = |s: &mut Self, new_rung: bool, diags: &mut Vec<Diagnostic>| {
            if new_rung && s.after_output {
                s.depth = Some(0);
            }
            if let Some(d) = s.depth {
                if d >= s.levels {
                    diags.push(
                        Diagnostic::new(
                            Code::StackOverflow,
                            span,
                            text,
                            format!(
                                "this push makes {} levels live; the bottom one is lost",
                                d + 1
                            ),
                        )
                        .help(format!(
                            "the logic stack has {} levels; combine branches (ALD/OLD) earlier",
                            s.levels
                        )),
                    );
                }
                s.depth = Some((d + 1).min(s.levels));
            }
        };
        // The levels come from the op's stack effect (core's one statement of it); which ops
        // are checked for underflow is this front end's rule (W001: contacts and the block ops).
        let effect = op.stack_effect();
        match op {
            Op::Label(_) | Op::Jump(_) | Op::Next { .. } => {
                self.depth = None;
                self.after_output = true;
                return;
            }
            Op::And(_) | Op::Or(_) | Op::AndBlock | Op::OrBlock | Op::Pop | Op::ReadSecond => {
                // The levels it reads, and a loaded level left as the top after its pops.
                let net_pops = effect.pops.saturating_sub(effect.pushes);
                let need = effect.levels_read().max(net_pops + 1);
                self.need(need, text, span, text, diags);
            }
            _ => {}
        }
        if effect.pushes == 0 && effect.pops == 0 {
            self.after_output = true;
            return;
        }
        if effect.pushes > effect.pops {
            for _ in effect.pops..effect.pushes {
                push(self, effect.pushes_fresh(), diags);
            }
        } else {
            self.depth = self
                .depth
                .map(|d| d.saturating_sub(effect.pops - effect.pushes));
        }
        self.after_output = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::Area;
    use stljit_core::ir::{BitLoc, Contact};

    fn ld() -> Op {
        Op::Load(Contact::Bit {
            bit: BitLoc {
                area: Area::I,
                byte: 0,
                bit: 0,
            },
            negated: false,
        })
    }

    fn run(ops: &[Op], start: u8) -> Vec<Code> {
        let mut s = StackCheck::new(start, 9);
        let mut d = Vec::new();
        for op in ops {
            s.step(op, Span::default(), "x", &mut d);
        }
        d.into_iter().map(|d| d.code).collect()
    }

    #[test]
    fn old_with_one_level_warns() {
        assert_eq!(run(&[ld(), Op::OrBlock], 0), vec![Code::StackUnderflow]);
        assert!(run(&[ld(), ld(), Op::OrBlock], 0).is_empty());
    }

    #[test]
    fn new_rung_resets_and_ten_pushes_warn_once() {
        let assign = Op::Assign {
            bit: BitLoc {
                area: Area::Q,
                byte: 0,
                bit: 0,
            },
            immediate: false,
        };
        let mut ops = vec![ld(), assign.clone()];
        ops.extend(std::iter::repeat_n(ld(), 9));
        assert!(run(&ops, 0).is_empty());
        ops.push(ld());
        assert_eq!(run(&ops, 0), vec![Code::StackOverflow]);
        // After an output, a contact still works on the unchanged stack.
        let and = Op::And(Contact::Bit {
            bit: BitLoc {
                area: Area::I,
                byte: 0,
                bit: 1,
            },
            negated: false,
        });
        assert!(run(&[ld(), assign, and.clone()], 0).is_empty());
        assert_eq!(
            run(std::slice::from_ref(&and), 0),
            vec![Code::StackUnderflow]
        );
        assert!(run(&[and], 1).is_empty());
    }

    #[test]
    fn label_makes_depth_unknown() {
        assert!(run(&[Op::Label(stljit_core::LabelId(0)), Op::OrBlock], 0).is_empty());
    }
}
