//! The circuit checks of omron-cp.md §2.4: the abstract machine's position and pending-block
//! count, advanced once per instruction by its class, reporting E003–E009, W040 and E041. The
//! TR bookkeeping of a circuit (E010) is here too, since a circuit's start clears it.

use stljit_source::Code;

/// Where an instruction may appear (§2.4's classes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Class {
    /// (a) LD-type; `LD TRn` is [`Class::LoadTr`].
    Start,
    /// (a) `LD TRn`: never starts a circuit.
    LoadTr,
    /// (b) AND/OR-type.
    Combine,
    /// (c) AND LD / OR LD.
    Join,
    /// (d) NOT, UP, DOWN.
    Intermediate,
    /// (e) single-condition output.
    Output,
    /// (f) an output with this many conditions.
    Multi(u32),
    /// (g) unconditional.
    Unconditional,
}

/// The machine's position.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
enum Pos {
    /// At a circuit start with nothing before it (task start, after a (g)).
    #[default]
    Fresh,
    /// Inside a rung.
    InRung,
    /// Directly after an (e): a new circuit may start, or the rung continues.
    AfterOutput,
    /// Directly after an (f): only (a) or (g) may follow.
    AfterMulti,
}

/// Pending blocks above this draw W040 (§2.4: "believed to be 8").
const WARN_BLOCKS: u32 = 8;
/// Pending blocks above this are OMR-E041: with at most two temporaries per IR push the
/// program's 16 stack levels then always suffice (lowering rule in the crate doc).
pub(crate) const MAX_BLOCKS: u32 = 13;

/// The abstract machine of one task region.
#[derive(Clone, Debug, Default)]
pub(crate) struct Circuit {
    pos: Pos,
    blocks: u32,
    /// TR bits stored in the current circuit.
    trs: u16,
}

/// A finding of [`Circuit::step`]: code and message (the caller adds line and place).
pub(crate) type Finding = (Code, String);

impl Circuit {
    /// Advances by one instruction of `class` named `mn`; returns the findings and whether this
    /// instruction started a new circuit.
    pub(crate) fn step(&mut self, class: Class, mn: &str) -> (Vec<Finding>, bool) {
        let mut out = Vec::new();
        let mut new_circuit = false;
        let after_multi = |out: &mut Vec<Finding>, pos: Pos| {
            if pos == Pos::AfterMulti {
                out.push((
                    Code::OmrAfterMulti,
                    "a circuit cannot continue after the multi-condition instruction; start a new circuit with LD".to_owned(),
                ));
            }
        };
        match class {
            Class::Start | Class::LoadTr => {
                if self.pos == Pos::InRung {
                    self.blocks += 1;
                    if self.blocks > MAX_BLOCKS {
                        out.push((Code::OmrTooDeep, format!("{} pending logic blocks; more than {MAX_BLOCKS} pending logic blocks are not supported", self.blocks)));
                    } else if self.blocks > WARN_BLOCKS {
                        out.push((Code::OmrDeepBlocks, format!("{} pending logic blocks; CX-Programmer may reject more than {WARN_BLOCKS}", self.blocks)));
                    }
                } else if class == Class::Start {
                    new_circuit = true;
                    self.trs = 0;
                }
                self.pos = Pos::InRung;
            }
            Class::Combine | Class::Intermediate => {
                if self.pos == Pos::Fresh {
                    out.push((Code::OmrNoLoad, format!("{mn} has no preceding LD/LD NOT")));
                }
                after_multi(&mut out, self.pos);
                self.pos = Pos::InRung;
            }
            Class::Join => {
                if self.blocks == 0 {
                    out.push((
                        Code::OmrNothingToCombine,
                        format!("{mn} has nothing to combine"),
                    ));
                } else {
                    self.blocks -= 1;
                }
                self.pos = Pos::InRung;
            }
            Class::Output => {
                if self.pos == Pos::Fresh {
                    out.push((Code::OmrNoCondition, format!("{mn} needs an execution condition; start the circuit with a contact (e.g. LD P_On)")));
                }
                after_multi(&mut out, self.pos);
                if self.blocks > 0 {
                    out.push((Code::OmrOpenBlock, format!("{} logic block(s) opened by LD are never combined — missing AND LD / OR LD (circuit not closed)", self.blocks)));
                    self.blocks = 0;
                }
                if self.pos != Pos::AfterMulti {
                    self.pos = Pos::AfterOutput;
                }
            }
            Class::Multi(k) => {
                let found = if self.pos == Pos::InRung {
                    self.blocks + 1
                } else {
                    0
                };
                if found != k {
                    out.push((
                        Code::OmrConditionCount,
                        format!("{mn} takes {k} execution conditions, found {found}"),
                    ));
                }
                self.blocks = 0;
                self.pos = Pos::AfterMulti;
            }
            Class::Unconditional => {
                if self.pos == Pos::InRung || self.blocks > 0 {
                    out.push((
                        Code::OmrNotOnBus,
                        format!("{mn} must connect directly to the left bus"),
                    ));
                }
                self.blocks = 0;
                self.trs = 0;
                self.pos = Pos::Fresh;
            }
        }
        (out, new_circuit)
    }

    /// Whether `TRn` was stored in this circuit.
    pub(crate) fn tr_set(&self, n: u8) -> bool {
        self.trs & (1 << n) != 0
    }

    /// Records `OUT TRn`; false when it was already stored in this circuit.
    pub(crate) fn store_tr(&mut self, n: u8) -> bool {
        let fresh = !self.tr_set(n);
        self.trs |= 1 << n;
        fresh
    }

    /// After a line whose class is unknown (an unknown instruction): any instruction may
    /// follow without a follow-on finding.
    pub(crate) fn recover(&mut self) {
        self.pos = Pos::AfterOutput;
        self.blocks = 0;
    }

    /// Back to the start of a task region (a new POU).
    pub(crate) fn reset(&mut self) {
        *self = Circuit::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codes(steps: &[Class]) -> Vec<Code> {
        let mut c = Circuit::default();
        steps
            .iter()
            .flat_map(|&s| c.step(s, "X").0)
            .map(|f| f.0)
            .collect()
    }

    #[test]
    fn the_machine_of_section_2_4() {
        use Class::*;
        // LD a / OUT x / AND b / OUT y: continuing after an output is legal.
        assert!(codes(&[Start, Output, Combine, Output, Unconditional]).is_empty());
        // LD 0.00 / LD 0.01 / OUT: E005 at the OUT.
        assert_eq!(codes(&[Start, Start, Output]), [Code::OmrOpenBlock]);
        assert_eq!(codes(&[Output]), [Code::OmrNoCondition]);
        assert_eq!(codes(&[Combine]), [Code::OmrNoLoad]);
        assert_eq!(codes(&[Start, Join]), [Code::OmrNothingToCombine]);
        assert_eq!(codes(&[Start, Multi(2)]), [Code::OmrConditionCount]);
        assert!(codes(&[Start, Start, Multi(2), Start, Output]).is_empty());
        assert_eq!(
            codes(&[Start, Start, Multi(2), Combine]),
            [Code::OmrAfterMulti]
        );
        assert_eq!(codes(&[Start, Unconditional]), [Code::OmrNotOnBus]);
        // 9 pending blocks warn, 14 are an error.
        let mut deep = vec![Start; 10];
        assert_eq!(codes(&deep), [Code::OmrDeepBlocks]);
        deep.extend([Start; 5]);
        assert!(codes(&deep).contains(&Code::OmrTooDeep));
    }
}
