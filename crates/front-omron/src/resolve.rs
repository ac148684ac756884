//! Operands against the profile: bits, words and constants of one instruction line resolved to
//! IR locations and values, with the range, kind, read-only and multi-word checks of
//! omron-cp.md §5 (E013–E016, W017, E018, E019). [`Cx`] carries the profile, the symbol table
//! and the diagnostics of the line being lowered.

use crate::lexer::Tok;
use crate::operand::{ConstForm, Syn, SynError, area_name, area_prefix, parse_syn};
use crate::symbols::{SymTarget, SymbolTable};
use stljit_core::ir::{BitLoc, Loc, OmronRef, Operand};
use stljit_core::omron::{
    EaRegion, FIRST_CYCLE, WordArea, bit_of_word, effective_address, word_loc,
};
use stljit_core::{Area, CpuProfile, FileId};
use stljit_source::{Code, Diagnostic, Span, clip};

/// A diagnostic was reported; the caller skips the operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Reported;

/// The compilation context of one line.
pub(crate) struct Cx<'a> {
    /// The model.
    pub(crate) profile: &'static CpuProfile,
    /// The symbol table, if any.
    pub(crate) symbols: Option<&'a SymbolTable>,
    /// Every diagnostic so far.
    pub(crate) diags: Vec<Diagnostic>,
    /// The file of the current line.
    pub(crate) file: FileId,
    /// The current line.
    pub(crate) line: u32,
    /// The current mnemonic, as written, for messages.
    pub(crate) mn: String,
    /// The compilation's options.
    pub(crate) options: crate::Options,
}

impl Cx<'_> {
    /// The span of `tok` on the current line.
    pub(crate) fn span(&self, tok: &Tok) -> Span {
        Span {
            file: self.file,
            line: self.line,
            col: tok.col,
            len: tok.len,
        }
    }

    /// Reports `code` at `tok`.
    pub(crate) fn report(&mut self, code: Code, tok: &Tok, message: String) -> Reported {
        let d = Diagnostic::new(code, self.span(tok), &tok.text, message);
        self.diags.push(d);
        Reported
    }

    /// Reports `code` at `tok` with a help line.
    pub(crate) fn report_help(
        &mut self,
        code: Code,
        tok: &Tok,
        message: String,
        help: &str,
    ) -> Reported {
        let d = Diagnostic::new(code, self.span(tok), &tok.text, message).help(help);
        self.diags.push(d);
        Reported
    }

    /// The operand's syntax, through the symbol table for names.
    pub(crate) fn syn(&mut self, tok: &Tok) -> Result<Syn, Reported> {
        let line = self.line;
        let syn = match parse_syn(&tok.text) {
            Ok(s) => s,
            Err(SynError::Malformed(why)) => {
                return Err(self.report(
                    Code::OmrOperand,
                    tok,
                    format!("line {line}: `{}` is malformed: {why}", clip(&tok.text)),
                ));
            }
            Err(SynError::NotAddress) => match self.symbols.and_then(|s| s.get(&tok.text)) {
                Some(SymTarget::Operand(s)) => *s,
                Some(SymTarget::Invalid) => return Err(Reported),
                None => {
                    return Err(self.report_help(
                        Code::OmrOperand,
                        tok,
                        format!(
                            "line {line}: `{}` is neither an address nor a known symbol",
                            clip(&tok.text)
                        ),
                        "define it in the symbol table (Name<TAB>Type<TAB>Address)",
                    ));
                }
            },
        };
        if let Syn::Unsupported(what) = syn {
            let mn = self.mn.clone();
            return Err(self.report(
                Code::OmrInstruction,
                tok,
                format!("line {line}: {mn}: {what} are not supported yet"),
            ));
        }
        Ok(syn)
    }

    fn kind(&mut self, tok: &Tok, expected: &str) -> Reported {
        let (line, mn) = (self.line, self.mn.clone());
        self.report(
            Code::OmrOperand,
            tok,
            format!(
                "line {line}: {mn} expects {expected}, got `{}`",
                clip(&tok.text)
            ),
        )
    }

    fn outside(&mut self, tok: &Tok, area: &str, hi: u32) -> Reported {
        let (line, model) = (self.line, self.profile.model);
        self.report(
            Code::OmrRange,
            tok,
            format!(
                "line {line}: {} is outside {area} (0–{hi}) on {model}",
                clip(&tok.text)
            ),
        )
    }

    fn read_only(&mut self, tok: &Tok) -> Reported {
        let line = self.line;
        self.report(
            Code::OmrReadOnly,
            tok,
            format!("line {line}: {} is read-only", clip(&tok.text)),
        )
    }

    /// The location of word `word` of `area`, range-checked.
    fn word_loc(&mut self, tok: &Tok, area: WordArea, word: u32) -> Result<Loc, Reported> {
        let words = area.words(self.profile);
        word_loc(self.profile, area, word)
            .ok_or_else(|| self.outside(tok, area_name(area), words.saturating_sub(1)))
    }

    /// A timer (`TimerBit`) or counter (`CounterBit`) number, range-checked.
    pub(crate) fn object(&mut self, tok: &Tok, area: Area, n: u32) -> Result<u16, Reported> {
        let (count, name) = match area {
            Area::TimerBit => (self.profile.timers, "T"),
            _ => (self.profile.counters, "C"),
        };
        match u16::try_from(n) {
            Ok(v) if u32::from(v) < u32::from(count) => Ok(v),
            _ => Err(self.outside(tok, name, u32::from(count).saturating_sub(1))),
        }
    }

    /// A bit operand (not a TR bit: the caller handles TRs, §2.4); `write` for the outputs
    /// (OUT, SET, KEEP, DIFU …), which may not target read-only bits (E016) and should not
    /// target input bits (W017).
    pub(crate) fn bit(&mut self, tok: &Tok, write: bool) -> Result<BitLoc, Reported> {
        let syn = self.syn(tok)?;
        let b = match syn {
            Syn::Bit { area, word, bit } => {
                if bit > 15 {
                    return Err(self.outside(tok, "bit numbers", 15));
                }
                if area == WordArea::Dm && !self.profile.omron.dm_bits {
                    let (line, model) = (self.line, self.profile.model);
                    return Err(self.report(
                        Code::OmrDmBit,
                        tok,
                        format!("line {line}: bit access to D is not supported on {model}"),
                    ));
                }
                let loc = self.word_loc(tok, area, word)?;
                if write && area == WordArea::Aux && word < self.profile.omron.aux_read_only {
                    return Err(self.read_only(tok));
                }
                bit_of_word(loc, bit as u8)
            }
            Syn::Timer(n) | Syn::Counter(n) => {
                let area = if matches!(syn, Syn::Timer(_)) {
                    Area::TimerBit
                } else {
                    Area::CounterBit
                };
                let n = self.object(tok, area, n)?;
                if write {
                    return Err(self.read_only(tok));
                }
                BitLoc {
                    area,
                    byte: u32::from(n),
                    bit: 0,
                }
            }
            Syn::Flag(f) => {
                if write {
                    return Err(self.read_only(tok));
                }
                f.bit_loc()
            }
            Syn::FirstCycle => {
                if write {
                    return Err(self.read_only(tok));
                }
                let loc = self.word_loc(tok, WordArea::Aux, FIRST_CYCLE.0)?;
                bit_of_word(loc, FIRST_CYCLE.1)
            }
            Syn::Tr(n) => {
                let (line, mn) = (self.line, self.mn.clone());
                return Err(self.report(
                    Code::OmrTr,
                    tok,
                    format!("line {line}: TR{n} may only be used with OUT and LD, not {mn}"),
                ));
            }
            Syn::Word { .. } => return Err(self.kind(tok, "a bit (word.bit, e.g. 0.00 or W3.15)")),
            Syn::Indirect(_) => return Err(self.not_yet(tok, "indirect bit operands")),
            Syn::Const(..) | Syn::Unsupported(_) | Syn::IndexReg(_) | Syn::DataReg(_) => {
                return Err(self.kind(tok, "a bit"));
            }
        };
        if write && b.area == Area::I {
            let line = self.line;
            self.report(
                Code::OmrInputWrite,
                tok,
                format!("line {line}: {} is a physical input; it will be overwritten at the next I/O refresh", clip(&tok.text)),
            );
        }
        Ok(b)
    }

    /// A word operand of `words` consecutive words (1, 2 or 4); `write` for a destination.
    /// Constants are allowed as sources and fill `words.min(2)` words.
    pub(crate) fn word(&mut self, tok: &Tok, words: u32, write: bool) -> Result<Operand, Reported> {
        let syn = self.syn(tok)?;
        match syn {
            Syn::Word { area, word } => {
                let first = self.word_loc(tok, area, word)?;
                if write && area == WordArea::Aux && word < self.profile.omron.aux_read_only {
                    return Err(self.read_only(tok));
                }
                for i in 1..words {
                    let line = self.line;
                    let Some(loc) = word
                        .checked_add(i)
                        .and_then(|w| word_loc(self.profile, area, w))
                    else {
                        let mn = self.mn.clone();
                        return Err(self.report(
                            Code::OmrWords,
                            tok,
                            format!(
                                "line {line}: {mn} needs {words} consecutive words at {}",
                                clip(&tok.text)
                            ),
                        ));
                    };
                    if loc.area != first.area || loc.offset != first.offset + 2 * i {
                        let p = area_prefix(area);
                        let last = word.saturating_add(words - 1);
                        return Err(self.report(
                            Code::OmrAreaCross,
                            tok,
                            format!(
                                "line {line}: {p}{word}…{p}{last} crosses from {} into {}",
                                region(first.area),
                                region(loc.area)
                            ),
                        ));
                    }
                }
                Ok(Operand::Mem(first))
            }
            Syn::Timer(n) | Syn::Counter(n) => {
                let (bit_area, area) = if matches!(syn, Syn::Timer(_)) {
                    (Area::TimerBit, Area::TimerValue)
                } else {
                    (Area::CounterBit, Area::CounterValue)
                };
                let n = self.object(tok, bit_area, n)?;
                if words > 1
                    && self
                        .object(tok, bit_area, u32::from(n) + words - 1)
                        .is_err()
                {
                    return Err(Reported);
                }
                Ok(Operand::Mem(Loc {
                    area,
                    offset: 2 * u32::from(n),
                }))
            }
            Syn::Const(v, form) => {
                if write {
                    return Err(self.kind(tok, "a destination word, not a constant"));
                }
                self.constant(tok, v, form, words.min(2))
                    .map(Operand::Const)
            }
            Syn::Bit { .. } => Err(self.kind(tok, "a word (e.g. D100, W3, 100), not a bit")),
            Syn::Flag(_) | Syn::FirstCycle => Err(self.kind(tok, "a word, not a system bit")),
            Syn::Tr(n) => {
                let line = self.line;
                Err(self.report(
                    Code::OmrTr,
                    tok,
                    format!("line {line}: TR{n} may only be used with OUT and LD"),
                ))
            }
            Syn::DataReg(m) if words == 1 => Ok(Operand::Mem(Loc {
                area: Area::DataReg,
                offset: 2 * m,
            })),
            Syn::Indirect(_) => {
                Err(self.not_yet(tok, "indirect operands outside MOV, CMP and the arithmetic"))
            }
            Syn::Unsupported(_) | Syn::IndexReg(_) | Syn::DataReg(_) => {
                Err(self.kind(tok, "a word"))
            }
        }
    }

    /// A word operand of a data box (MOV, CMP, arithmetic): as [`Cx::word`], and also the
    /// indirect forms of §1.7 (their DM pointer word range-checked here; the address they
    /// name is resolved at run time, AER when illegal).
    pub(crate) fn data_word(
        &mut self,
        tok: &Tok,
        words: u32,
        write: bool,
    ) -> Result<Operand, Reported> {
        match parse_syn(&tok.text) {
            Ok(Syn::Indirect(r)) => {
                if let OmronRef::DmBinary(n) | OmronRef::DmBcd(n) = r {
                    self.word_loc(tok, WordArea::Dm, u32::from(n))?;
                }
                Ok(Operand::Omron(r))
            }
            _ => self.word(tok, words, write),
        }
    }

    /// The effective address of a word, bit, timer or counter operand (MOVR's source).
    pub(crate) fn effective_address(&mut self, tok: &Tok) -> Result<u32, Reported> {
        let syn = self.syn(tok)?;
        let (region, word, bit) = match syn {
            Syn::Word { area, word } => (EaRegion::Word(area), word, None),
            Syn::Bit { area, word, bit } if bit <= 15 => (EaRegion::Word(area), word, Some(bit)),
            Syn::Timer(n) => (EaRegion::TimerPv, n, None),
            Syn::Counter(n) => (EaRegion::CounterPv, n, None),
            _ => return Err(self.kind(tok, "a word, bit, timer or counter (its address)")),
        };
        let Some(ea) = effective_address(self.profile, region, word) else {
            return Err(self.kind(tok, "an address of this model's memory"));
        };
        Ok(match bit {
            Some(b) => 16 * ea + b,
            None => ea,
        })
    }

    /// An index register `IRn` (0..=15).
    pub(crate) fn index_register(&mut self, tok: &Tok) -> Result<u8, Reported> {
        match self.syn(tok)? {
            Syn::IndexReg(n) if n <= 15 => Ok(n as u8),
            Syn::IndexReg(_) => Err(self.outside(tok, "IR", 15)),
            _ => Err(self.kind(tok, "an index register (IR0 to IR15)")),
        }
    }

    /// "{what} are not supported yet" (OMR-E011).
    fn not_yet(&mut self, tok: &Tok, what: &str) -> Reported {
        let (line, mn) = (self.line, self.mn.clone());
        self.report(
            Code::OmrInstruction,
            tok,
            format!("line {line}: {mn}: {what} are not supported yet"),
        )
    }

    /// A constant of `words` words (1 or 2) as its bit pattern (§1.6 ranges).
    pub(crate) fn constant(
        &mut self,
        tok: &Tok,
        v: i64,
        form: ConstForm,
        words: u32,
    ) -> Result<u32, Reported> {
        let bits = 16 * words;
        let ok = match form {
            ConstForm::Hex(d) => d as u32 <= bits / 4,
            ConstForm::Unsigned => v >= 0 && v < (1i64 << bits),
            ConstForm::Signed => v >= -(1i64 << (bits - 1)) && v < (1i64 << (bits - 1)),
        };
        if !ok {
            let (line, mn) = (self.line, self.mn.clone());
            return Err(self.report(
                Code::OmrConstant,
                tok,
                format!(
                    "line {line}: {} is not a valid {bits}-bit constant for {mn}",
                    clip(&tok.text)
                ),
            ));
        }
        // Two's complement, truncated to the operand: the low word is the value's low 16 bits.
        Ok((v as u64 & ((1u64 << bits) - 1)) as u32)
    }

    /// A number operand (jump, subroutine, timer/counter number): `dec`, `&dec` or `#hex`, at
    /// most `max`.
    pub(crate) fn number(&mut self, tok: &Tok, max: u32, what: &str) -> Result<u32, Reported> {
        let t = tok.text.as_str();
        let parsed = if let Some(h) = t.strip_prefix('#') {
            u32::from_str_radix(h, 16)
                .ok()
                .filter(|_| !h.is_empty() && h.len() <= 4)
        } else {
            let d = t.strip_prefix('&').unwrap_or(t);
            d.bytes()
                .all(|b| b.is_ascii_digit())
                .then(|| d.parse().ok())
                .flatten()
        };
        match parsed {
            Some(n) if n <= max => Ok(n),
            _ => {
                let (line, mn) = (self.line, self.mn.clone());
                Err(self.report(
                    Code::OmrConstant,
                    tok,
                    format!(
                        "line {line}: {} is not a valid {what} (0–{max}) for {mn}",
                        clip(t)
                    ),
                ))
            }
        }
    }
}

/// The part of the Omron memory a routed area is, for E018 messages (CIO input and output
/// words are the image's `I`/`Q` areas, the other CIO words area `Cio`).
fn region(area: Area) -> &'static str {
    match area {
        Area::I => "the CIO input words",
        Area::Q => "the CIO output words",
        _ => "the CIO work words",
    }
}
