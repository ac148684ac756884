//! Puts generated IR in the form the front end produces for the same text, so that
//! "print, parse again" gives back an equal program: label ids numbered by first appearance (the
//! front end assigns them when it first meets `JMP n` or `LBL n`, and the printer prints the id as
//! the label number), source locations cleared.

use stljit_core::ir::{Op, Program, SrcLoc};
use stljit_core::{LabelId, OpIdx};

/// Canonicalizes `program` in place.
pub fn canonicalize(program: &mut Program) {
    for pou in &mut program.pous {
        let mut rename: Vec<Option<LabelId>> = vec![None; pou.labels.len()];
        let mut labels: Vec<OpIdx> = Vec::with_capacity(pou.labels.len());
        for op in &mut pou.ops {
            if let Op::Jump(l) | Op::Label(l) = op {
                let Some(slot) = rename.get_mut(l.index()) else {
                    continue;
                };
                let new = *slot.get_or_insert_with(|| {
                    labels.push(pou.labels.get(l.index()).copied().unwrap_or(OpIdx(0)));
                    LabelId::new(labels.len() - 1)
                });
                *l = new;
            }
        }
        pou.labels = labels;
        pou.locs = vec![SrcLoc::default(); pou.ops.len()];
    }
}
