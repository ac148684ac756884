//! The Omron pass of the shrinker: drop runs of source lines of the printed program, keeping a
//! candidate when the Omron front end accepts the text and the case still fails the same way.

use super::Shrinker;
use crate::generate::Case;

impl Shrinker<'_> {
    /// Drops runs of lines of the program's Omron text, halving the run length down to one.
    pub(super) fn drop_lines(&mut self) {
        let Ok(text) = stljit_front_omron::print_program(&self.best.program) else {
            return;
        };
        let mut lines: Vec<&str> = text.lines().filter(|l| !l.starts_with(';')).collect();
        let mut chunk = (lines.len() / 2).max(1);
        loop {
            let mut start = 0;
            while start < lines.len() && self.budget > 0 {
                let end = (start + chunk).min(lines.len());
                let candidate = [&lines[..start], &lines[end..]].concat().join("\n");
                let compiled = crate::roundtrip::compile_dialect(&candidate, &self.best.program);
                let kept = compiled.is_ok_and(|program| {
                    self.try_case(Case {
                        program,
                        stimulus: self.best.stimulus.clone(),
                    })
                });
                if kept {
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
    }
}
