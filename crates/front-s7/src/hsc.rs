//! The high-speed counter instructions (s7-200-more §8.1): `HDEF HSC, MODE` and `HSC N`,
//! lowered to [`ExtBox::HscDefine`]/[`ExtBox::Hsc`] (the runtime's `hsc` module runs them).
//! The counter is a constant the selected CPU has (E070) and HDEF's mode one that counter
//! accepts (E071), both read from the profile's counter table; HDEF directly in an interrupt
//! routine gets W070 (run-time error 0x0004). The STL spelling for the printer is in `ext`.

use crate::classes::R;
use crate::lexer::{Line, Tok};
use crate::program::{Lowerer, PouState};
use stljit_core::hsc::{HscInfo, MAX_MODE};
use stljit_core::ir::{ExtBox, Op, PouKind};
use stljit_source::Code;

impl Lowerer<'_> {
    /// Lowers `HDEF` or `HSC` (`m`, upper case).
    pub(crate) fn hsc(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        let o = line.ops;
        let b = if m == "HDEF" {
            self.arity(line, 2, 2)?;
            let counter = self.counter_operand(o[0]);
            let mode = self
                .cx
                .number(o[1], 0, 255, "HSC mode", Code::HscMode)
                .map(|n| n as u8);
            let (info, mode) = (counter?, mode?);
            if !info.has_mode(mode) {
                return Err(self.cx.report(
                    Code::HscMode,
                    o[1],
                    format!(
                        "HSC{} has no mode {mode} on the {}",
                        info.number, self.cx.profile.model
                    ),
                    Some(format!("modes of HSC{}: {}", info.number, modes(info))),
                ));
            }
            if matches!(ps.kind, PouKind::Interrupt(_)) {
                self.cx.report(
                    Code::HdefInInterrupt,
                    self.mnemonic,
                    "`HDEF` in an interrupt routine has no effect".to_string(),
                    Some(
                        "it records error 16#0004 when it runs; define the counter in the \
                         main program"
                            .into(),
                    ),
                );
            }
            ExtBox::HscDefine {
                counter: info.number,
                mode,
            }
        } else {
            self.arity(line, 1, 1)?;
            ExtBox::Hsc {
                counter: self.counter_operand(o[0])?.number,
            }
        };
        self.emit(ps, Op::Ext(Box::new(b)));
        Ok(())
    }

    /// A counter number operand: a constant naming a counter of the CPU (E070).
    fn counter_operand(&mut self, t: Tok<'_>) -> R<&'static HscInfo> {
        let n = self
            .cx
            .number(t, 0, 255, "high-speed counter number", Code::HscNumber)?;
        let profile = self.cx.profile;
        let found = u8::try_from(n).ok().and_then(|n| profile.hsc.get(n));
        found.ok_or_else(|| {
            let list: Vec<String> = profile.hsc.iter().map(|c| c.number.to_string()).collect();
            self.cx.report(
                Code::HscNumber,
                t,
                format!("HSC{n} does not exist on the {}", profile.model),
                Some(if list.is_empty() {
                    format!("the {} has no high-speed counters", profile.model)
                } else {
                    format!(
                        "high-speed counters of the {}: {}",
                        profile.model,
                        list.join(", ")
                    )
                }),
            )
        })
    }
}

/// The modes a counter accepts, for messages.
fn modes(info: &HscInfo) -> String {
    let list: Vec<String> = (0..=MAX_MODE)
        .filter(|&m| info.has_mode(m))
        .map(|m| m.to_string())
        .collect();
    list.join(", ")
}
