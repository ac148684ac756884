//! The pulse output instruction (s7-200-more §9.2): `PLS Q`, lowered to [`ExtBox::Pls`] (the
//! runtime's `pulse` module runs it). Q is a constant naming a channel of the selected CPU's
//! pulse output table (E072). The STL spelling for the printer is in `ext`.

use crate::classes::R;
use crate::lexer::Line;
use crate::program::{Lowerer, PouState};
use stljit_core::ir::{ExtBox, Op};
use stljit_source::Code;

impl Lowerer<'_> {
    /// Lowers `PLS Q`.
    pub(crate) fn pls(&mut self, ps: &mut PouState, line: &Line<'_>) -> R<()> {
        self.arity(line, 1, 1)?;
        let t = line.ops[0];
        let n = self
            .cx
            .number(t, 0, 255, "pulse output number", Code::PulseNumber)?;
        let profile = self.cx.profile;
        let Some(c) = u8::try_from(n).ok().and_then(|n| profile.pulse.get(n)) else {
            let list: Vec<String> = profile
                .pulse
                .channels
                .iter()
                .map(|c| format!("{} (Q{}.{})", c.number, c.output.0, c.output.1))
                .collect();
            return Err(self.cx.report(
                Code::PulseNumber,
                t,
                format!("pulse output {n} does not exist on the {}", profile.model),
                Some(format!(
                    "pulse outputs of the {}: {}",
                    profile.model,
                    list.join(", ")
                )),
            ));
        };
        let b = ExtBox::Pls { channel: c.number };
        self.emit(ps, Op::Ext(Box::new(b)));
        Ok(())
    }
}
