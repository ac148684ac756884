//! The Omron pass of the shrinker: drop runs of source lines of the printed program, then runs
//! of two and three lines at every offset (an instruction with its conditions, which the
//! halving runs may straddle), then pairs of lines (a region's opening and closing lines, FOR …
//! NEXT, IL … ILC, `$TASK` and its END, which no single cut removes), keeping a candidate when
//! the Omron front end accepts the text and the case still fails the same way.

use super::Shrinker;
use crate::generate::Case;

/// The pair pass runs on texts of at most this many lines (it tries every pair).
const PAIRS_UP_TO: usize = 80;

impl Shrinker<'_> {
    /// Drops runs of lines of the program's Omron text, halving the run length down to one,
    /// then short runs at every offset, then pairs of lines.
    pub(super) fn drop_lines(&mut self) {
        let Ok(text) = stljit_front_omron::print_program(&self.best.program) else {
            return;
        };
        let mut lines: Vec<String> = text
            .lines()
            .filter(|l| !l.starts_with(';'))
            .map(str::to_owned)
            .collect();
        let mut chunk = (lines.len() / 2).max(1);
        loop {
            let mut start = 0;
            while start < lines.len() && self.budget > 0 {
                let end = (start + chunk).min(lines.len());
                if self.try_without(&lines, |k| (start..end).contains(&k)) {
                    lines.drain(start..end);
                } else {
                    start += chunk;
                }
            }
            if chunk == 1 {
                break;
            }
            chunk /= 2;
        }
        for run in [3, 2] {
            let mut start = 0;
            while start + run <= lines.len() && self.budget > 0 {
                if self.try_without(&lines, |k| (start..start + run).contains(&k)) {
                    lines.drain(start..start + run);
                } else {
                    start += 1;
                }
            }
        }
        if lines.len() > PAIRS_UP_TO {
            return;
        }
        let mut i = 0;
        while i < lines.len() && self.budget > 0 {
            let found =
                (i + 1..lines.len()).find(|&j| self.try_without(&lines, |k| k == i || k == j));
            match found {
                Some(j) => {
                    lines.remove(j);
                    lines.remove(i);
                }
                None => i += 1,
            }
        }
    }

    /// Whether the text of `lines` without the lines whose index is `cut` compiles and still
    /// fails (it is then the best case).
    fn try_without(&mut self, lines: &[String], cut: impl Fn(usize) -> bool) -> bool {
        if self.budget == 0 {
            return false;
        }
        let candidate: Vec<&str> = lines
            .iter()
            .enumerate()
            .filter(|&(k, _)| !cut(k))
            .map(|(_, l)| l.as_str())
            .collect();
        let compiled = crate::roundtrip::compile_dialect(&candidate.join("\n"), &self.best.program);
        compiled.is_ok_and(|program| {
            self.try_case(Case {
                program,
                stimulus: self.best.stimulus.clone(),
            })
        })
    }
}
