//! Where the printed text needs a circuit boundary the IR does not show. IORF(097) is an
//! output that lowers to no op, so after `LD a / IORF(097) … / LD b` the IR holds two pushes and
//! nothing marks that `LD b` starts a new circuit instead of opening a block; printed without
//! the IORF, `LD b` would open a block the next output finds pending (E005), or an
//! unconditional instruction would find the rung unfinished (E009). [`separate`] runs the
//! block count of the circuit machine (§2.4) over the printed lines and puts an IORF (no op on
//! the built-in I/O, so the IR is unchanged) back where such a boundary must be, or, where an
//! unfolded `NOT / OUT b / NOT` (`NOT / CJP n / NOT`) stands just before, folds it into
//! `OUT NOT b` (`JMP n`), an output that ends the rung the same way.

use super::body::Line;
use crate::circuit::Class;
use crate::lexer::lex_line;
use crate::lower::class_of;
use crate::mnemonics::{self, Join};

/// The op-less output the printer puts back (CIO 0 is always there).
const BOUNDARY: &str = "IORF(097)  0 0\n";

/// The §2.4 class of a printed line.
fn class(line: &str) -> Option<Class> {
    let l = lex_line(line, 1)?;
    if let Some(m) = mnemonics::lookup(&l.mnemonic) {
        return Some(class_of(m.group));
    }
    mnemonics::compare(&l.mnemonic).map(|c| {
        if c.join == Join::Load {
            Class::Start
        } else {
            Class::Combine
        }
    })
}

/// Where a boundary is missing: the line to put an IORF before, if any.
fn missing_boundary(lines: &[Line]) -> Option<usize> {
    #[derive(PartialEq)]
    enum Pos {
        Fresh,
        InRung,
        After,
    }
    let mut pos = Pos::Fresh;
    // The lines whose LD opened a block that is still pending, oldest first.
    let mut pending: Vec<usize> = Vec::new();
    let classes = lines.iter().map(|l| class(&l.text));
    for (i, c) in classes
        .chain(std::iter::once(Some(Class::Unconditional)))
        .enumerate()
    {
        match c? {
            Class::Start | Class::LoadTr => {
                if pos == Pos::InRung {
                    pending.push(i);
                }
                pos = Pos::InRung;
            }
            Class::Combine | Class::Intermediate => pos = Pos::InRung,
            Class::Join => {
                pending.pop();
                pos = Pos::InRung;
            }
            Class::Output => {
                if let Some(&first) = pending.first() {
                    return Some(first);
                }
                pos = Pos::After;
            }
            Class::Multi(k) => {
                // k conditions: k - 1 pending blocks and the execution condition.
                if pending.len() + 1 > k as usize {
                    return Some(pending[0]);
                }
                pending.clear();
                pos = Pos::After;
            }
            Class::Unconditional => {
                if let Some(&first) = pending.first() {
                    return Some(first);
                }
                if pos == Pos::InRung {
                    return Some(i);
                }
                pos = Pos::Fresh;
            }
        }
    }
    None
}

/// Puts an IORF(097) before every line that must start a new circuit (see the module doc).
/// Each insertion ends one circuit, so this ends after at most one insertion per line.
pub(super) fn separate(lines: &mut Vec<Line>) {
    for _ in 0..=lines.len() {
        let Some(at) = missing_boundary(lines) else {
            return;
        };
        let fold = at
            .checked_sub(3)
            .and_then(|k| Some((k, lines[k].folded.clone()?)));
        match fold {
            Some((k, folded)) => {
                lines.splice(k..at, [Line::plain(folded)]);
            }
            None => lines.insert(at, Line::plain(BOUNDARY.to_owned())),
        }
    }
}
