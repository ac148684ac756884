//! The contacts (omron-cp.md §3.1): `LD`/`AND`/`OR` and their `NOT` forms with the `@`, `%`
//! and `!` options, `LD TRn`, and the comparison contacts; with the flag checks of a contact
//! on a condition flag (W032 at a circuit's start, W034 before anything set it, W033 through
//! `discipline`).

use crate::circuit::Class;
use crate::immediate::{Refresh, reads_of_bit, reads_of_words};
use crate::lexer::{Line, Options, Tok};
use crate::lower::Lowerer;
use crate::mnemonics::{self, Join};
use crate::operand::Syn;
use crate::resolve::Reported;
use stljit_core::ir::{Contact, OmronBox, Op};
use stljit_core::omron::{SystemBit, tr_bit};
use stljit_source::{Code, clip};

impl Lowerer<'_> {
    /// `LD`/`AND`/`OR` (and `NOT` forms, `@`/`%`/`!` options), `LD TRn`.
    pub(crate) fn contact(&mut self, l: &Line, join: Join, negated: bool) -> Result<(), Reported> {
        let ops = self.operands(l, 1)?;
        let tok = &ops[0];
        let syn = self.cx.syn(tok)?;
        if let Syn::Tr(n) = syn {
            let n = self.tr_number(tok, n)?;
            if join != Join::Load || negated || l.options != Options::default() {
                let (line, mn) = (l.line, self.cx.mn.clone());
                return Err(self.cx.report(
                    Code::OmrTr,
                    tok,
                    format!("line {line}: TR{n} may only be used with OUT and LD, not {mn}"),
                ));
            }
            self.class(l, Class::LoadTr);
            self.flag_branches.load_tr(n);
            if !self.circuit.tr_set(n) {
                let line = l.line;
                self.cx.report(
                    Code::OmrTr,
                    tok,
                    format!("line {line}: TR{n} is not set in this circuit"),
                );
            }
            self.emit(Op::Load(Contact::Bit {
                bit: tr_bit(n),
                negated: false,
            }));
            return Ok(());
        }
        let bit = self.cx.bit(tok, false)?;
        let constant = match syn {
            Syn::Flag(SystemBit::On) | Syn::FirstCycle => Some(true),
            Syn::Flag(SystemBit::Off) => Some(false),
            _ => None,
        };
        if let (Some(falling), Some(on)) = (l.options.edge, constant) {
            self.never_fires(l, falling, on);
        }
        if join == Join::Load && !negated && l.options.edge.is_none() {
            self.constant_ec = constant;
        }
        let class = if join == Join::Load {
            Class::Start
        } else {
            Class::Combine
        };
        let new_circuit = self.class(l, class);
        if let Syn::Flag(f) = syn
            && f.index() < SystemBit::CONDITION_FLAGS.count_ones()
            && !self.flags_changed
        {
            let line = l.line;
            self.cx.report(
                Code::OmrFlagNeverSet,
                tok,
                format!(
                    "line {line}: condition flags are cleared at task start; {} is always OFF here",
                    clip(&tok.text)
                ),
            );
        }
        if let (false, true, Syn::Flag(f)) = (new_circuit, self.flags_changed, syn)
            && f.index() < SystemBit::CONDITION_FLAGS.count_ones()
        {
            let span = self.cx.span(tok);
            let mut found: Vec<_> = self.flag_branches.read(f, tok, span).into_iter().collect();
            if l.options.edge.is_some() && found.is_empty() {
                // A differentiated contact on a flag: the read itself is differentiated.
                let what = format!("{}{}", l.options.text(), l.mnemonic);
                found = self.flag_branches.differentiated(&what, l.line);
            }
            self.cx.diags.extend(found);
        }
        if let (true, Syn::Flag(f)) = (new_circuit, syn)
            && f.index() < SystemBit::CONDITION_FLAGS.count_ones()
        {
            let line = l.line;
            self.cx.report(
                    Code::OmrFlagAtStart,
                    tok,
                    format!("line {line}: {} at circuit start reflects whichever instruction ran last; branch from the instruction's own condition instead", clip(&tok.text)),
                );
        }
        if l.options.immediate {
            self.refresh_inputs(reads_of_bit(bit), Refresh::Always);
        }
        let contact = Contact::Bit { bit, negated };
        match (l.options.edge, join) {
            (None, Join::Load) => self.emit(Op::Load(contact)),
            (None, Join::And) => self.emit(Op::And(contact)),
            (None, Join::Or) => self.emit(Op::Or(contact)),
            (Some(falling), _) => {
                self.emit(Op::Load(contact));
                let e = self.edge(falling);
                self.emit(e);
                match join {
                    Join::Load => {}
                    Join::And => self.emit(Op::AndBlock),
                    Join::Or => self.emit(Op::OrBlock),
                }
            }
        }
        Ok(())
    }

    /// A comparison contact: the flags from an `Omron(Compare)` run on a pushed `P_On`, then
    /// the flag of the relation as the contact (U2's default).
    pub(crate) fn compare_contact(
        &mut self,
        l: &Line,
        c: mnemonics::CompareContact,
    ) -> Result<(), Reported> {
        let ops = self.operands(l, 2)?;
        let words = if c.double { 2 } else { 1 };
        let lhs = self.cx.word(&ops[0], words, false);
        let rhs = self.cx.word(&ops[1], words, false);
        let (lhs, rhs) = (lhs?, rhs?);
        self.class(
            l,
            if c.join == Join::Load {
                Class::Start
            } else {
                Class::Combine
            },
        );
        let flag = mnemonics::relation_flag(c.op);
        let on = Contact::Bit {
            bit: SystemBit::On.bit_loc(),
            negated: false,
        };
        if l.options.immediate {
            self.refresh_inputs(reads_of_words(&[lhs, rhs], words), Refresh::Always);
        }
        self.emit(Op::Load(on));
        self.flags_changed = true;
        self.emit(Op::Omron(OmronBox::Compare {
            double: c.double,
            signed: c.signed,
            lhs,
            rhs,
        }));
        self.emit(Op::Pop);
        let contact = Contact::Bit {
            bit: flag.bit_loc(),
            negated: false,
        };
        self.emit(match c.join {
            Join::Load => Op::Load(contact),
            Join::And => Op::And(contact),
            Join::Or => Op::Or(contact),
        });
        Ok(())
    }

    /// A TR number, 0..=15 (E014).
    pub(crate) fn tr_number(&mut self, tok: &Tok, n: u32) -> Result<u8, Reported> {
        match u8::try_from(n) {
            Ok(v) if v < 16 => Ok(v),
            _ => {
                let (line, model) = (self.cx.line, self.cx.profile.model);
                Err(self.cx.report(
                    Code::OmrRange,
                    tok,
                    format!(
                        "line {line}: {} is outside TR (0–15) on {model}",
                        clip(&tok.text)
                    ),
                ))
            }
        }
    }
}
