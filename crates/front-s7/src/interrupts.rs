//! The interrupt instructions (s7-200-more §3.4): `ATCH INT, EVNT`, `DTCH EVNT`, `CEVNT EVNT`,
//! `ENI` and `DISI`, with their operand checks: the routine by number, `INTn`, MicroWIN's
//! default symbol `INT_n`, its block name or a symbol naming `INTn` (E050 for anything else);
//! the event a constant among the selected CPU's (E051, Appendix A); a warning for ENI/DISI
//! directly in an interrupt routine (W051: run-time error 0x0004). Every event source is
//! simulated, so any attached event can occur. `RETI`/`CRETI` are program control (`control.rs`).

use crate::classes::R;
use crate::lexer::{Line, Tok};
use crate::names::unquote;
use crate::program::{Lowerer, PouState};
use crate::symbols::{PouRef, SymTarget};
use stljit_core::interrupt::{self, MAX_ROUTINE};
use stljit_core::ir::{IntOp, Op, PouKind};
use stljit_core::{CpuProfile, PouId};
use stljit_source::{Code, clip};

impl Lowerer<'_> {
    /// Lowers the interrupt instruction `m` (upper case).
    pub(crate) fn interrupt(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        let o = line.ops;
        let op = match m {
            "ATCH" => {
                self.arity(line, 2, 2)?;
                let routine = self.routine_operand(o[0]);
                let event = self.event_operand(o[1]);
                IntOp::Attach {
                    routine: routine?,
                    event: event?,
                }
            }
            "DTCH" | "CEVNT" => {
                self.arity(line, 1, 1)?;
                let event = self.event_operand(o[0])?;
                if m == "DTCH" {
                    IntOp::Detach { event }
                } else {
                    IntOp::ClearEvent { event }
                }
            }
            _ => {
                self.arity(line, 0, 0)?;
                if matches!(ps.kind, PouKind::Interrupt(_)) {
                    self.cx.report(
                        Code::EnableInInterrupt,
                        self.mnemonic,
                        format!("`{m}` in an interrupt routine has no effect"),
                        Some(
                            "it records error 16#0004 when it runs; enable and disable \
                             interrupts in the main program"
                                .into(),
                        ),
                    );
                }
                if m == "ENI" {
                    IntOp::Enable
                } else {
                    IntOp::Disable
                }
            }
        };
        self.emit(ps, Op::Interrupt(op));
        Ok(())
    }

    /// An event number operand: a constant the CPU has (E051).
    fn event_operand(&mut self, t: Tok<'_>) -> R<u8> {
        let n = self
            .cx
            .number(t, 0, 255, "event number", Code::EventNumber)?;
        let n = u8::try_from(n).unwrap_or(u8::MAX);
        let profile = self.cx.profile;
        if interrupt::event(n).is_none() || !profile.interrupts.has(n) {
            return Err(self.cx.report(
                Code::EventNumber,
                t,
                format!("event {n} does not exist on the {}", profile.model),
                Some(format!(
                    "events of the {}: {}",
                    profile.model,
                    event_list(profile)
                )),
            ));
        }
        Ok(n)
    }

    /// The interrupt routine of `ATCH`: a number, `INTn`, `INT_n`, a block name or a symbol
    /// naming `INTn`.
    fn routine_operand(&mut self, t: Tok<'_>) -> R<PouId> {
        let text = unquote(t.text).unwrap_or(t.text);
        let upper = text.to_ascii_uppercase();
        let digits = |d: &str| {
            (!d.is_empty() && d.bytes().all(|c| c.is_ascii_digit()))
                .then(|| d.parse::<u32>().ok())
                .flatten()
        };
        let number = digits(text).or_else(|| upper.strip_prefix("INT").and_then(digits));
        let number = match number {
            Some(n) => n,
            None => match self.names.get(text) {
                Some(&(id, PouKind::Interrupt(_))) => return Ok(id),
                Some(_) => {
                    return Err(self.cx.report(
                        Code::UnknownInterrupt,
                        t,
                        format!("`{}` is not an interrupt routine", clip(text)),
                        Some("ATCH takes an interrupt routine (INTn or its name)".into()),
                    ));
                }
                None => match self.cx.symbols.and_then(|s| s.get(text)) {
                    Some(SymTarget::Pou(PouRef::Interrupt(n))) => u32::from(*n),
                    // `INT_n`: MicroWIN's default symbol of INTn.
                    _ => upper
                        .strip_prefix("INT_")
                        .and_then(digits)
                        .unwrap_or(u32::MAX),
                },
            },
        };
        if let Some(&id) = u16::try_from(number)
            .ok()
            .filter(|&n| n <= MAX_ROUTINE)
            .and_then(|n| self.ints.get(&n))
        {
            return Ok(id);
        }
        let mut known: Vec<u16> = self.ints.keys().copied().collect();
        known.sort_unstable();
        let help = if known.is_empty() {
            "no interrupt routine is defined (INT n … RETI, or an INTERRUPT_BLOCK)".to_owned()
        } else {
            let names: Vec<String> = known.iter().take(8).map(|n| format!("INT{n}")).collect();
            format!("defined: {}", names.join(", "))
        };
        Err(self.cx.report(
            Code::UnknownInterrupt,
            t,
            format!("unknown interrupt routine `{}`", clip(text)),
            Some(help),
        ))
    }
}

/// The CPU's event numbers as ranges (`0-15, 23, 25-28`).
fn event_list(profile: &CpuProfile) -> String {
    let mut parts: Vec<String> = Vec::new();
    let events = profile.interrupts.events;
    let mut i = 0;
    while i < events.len() {
        let mut j = i;
        while j + 1 < events.len() && events[j + 1] == events[j] + 1 {
            j += 1;
        }
        parts.push(if j > i + 1 {
            format!("{}-{}", events[i], events[j])
        } else if j == i + 1 {
            format!("{}, {}", events[i], events[j])
        } else {
            events[i].to_string()
        });
        i = j + 1;
    }
    parts.join(", ")
}
