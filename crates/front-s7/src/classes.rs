//! Operand classes (spec §4.0): turns a written operand into an IR operand of the width the
//! instruction fixes, checking class, width, profile range and write access on the way.

use crate::lexer::Tok;
use crate::locals::Locals;
use crate::names::{ResolveError, Scope, Via};
use crate::operand::{Const, Syn};
use crate::spelling::{area_prefix, width_letter};
use crate::symbols::SymbolTable;
use stljit_core::ir::{BitLoc, Loc, Operand};
use stljit_core::{Area, CounterId, CpuProfile, FileId, TimerId, Width};
use stljit_source::Code;
use stljit_source::{Diagnostic, Span, clip};

/// The diagnostic for this operand has already been pushed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Reported;

/// Result of a checking step whose failure is already reported.
pub(crate) type R<T> = Result<T, Reported>;

/// Which bits an instruction accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BitClass {
    /// Any bit, read (contacts): I, Q, M, SM, T, C, V, S, L.
    Read,
    /// Any bit, written (coils, S/R): no SM0-SM29.
    Write,
    /// Input bits only (immediate contacts).
    Input,
    /// Output bits only (immediate coils).
    Output,
    /// S bits only (SCR).
    Seq,
    /// Bits of byte-addressable memory, read (SHRB data).
    MemRead,
    /// Bits of byte-addressable memory, written (SHRB register).
    MemWrite,
}

/// Read or write access to a value operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Access {
    /// Input.
    In,
    /// Output (also read when the instruction works in place).
    Out,
}

/// What a value operand may be.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Val {
    /// Width fixed by the instruction.
    pub(crate) width: Width,
    /// A real operand (constants are converted to IEEE bits).
    pub(crate) real: bool,
    /// Input or output.
    pub(crate) access: Access,
    /// `&x` allowed (MOVD input).
    pub(crate) addr_of: bool,
    /// `AQW` allowed as output (MOVW).
    pub(crate) aq_out: bool,
    /// Accumulators and constants allowed (not for block-move addresses).
    pub(crate) acc_const: bool,
}

impl Val {
    /// An input of `width`.
    pub(crate) const fn input(width: Width) -> Val {
        Val {
            width,
            real: false,
            access: Access::In,
            addr_of: false,
            aq_out: false,
            acc_const: true,
        }
    }

    /// An output of `width`.
    pub(crate) const fn output(width: Width) -> Val {
        Val {
            access: Access::Out,
            ..Val::input(width)
        }
    }

    /// A real input.
    pub(crate) const REAL_IN: Val = Val {
        real: true,
        ..Val::input(Width::DWord)
    };
    /// A real output.
    pub(crate) const REAL_OUT: Val = Val {
        real: true,
        ..Val::output(Width::DWord)
    };

    /// What the class allows, for help texts.
    fn allowed(&self) -> String {
        let mut s = String::from("allowed: ");
        s.push_str(match self.width {
            Width::Byte => "IB, QB, MB, SMB, VB, SB, LB",
            Width::Word => "IW, QW, MW, SMW, VW, SW, LW, T, C",
            Width::DWord => "ID, QD, MD, SMD, VD, SD, LD",
        });
        if self.acc_const {
            s.push_str(", AC");
        }
        if self.width == Width::Word && self.access == Access::In {
            s.push_str(", AIW");
        }
        if self.aq_out {
            s.push_str(", AQW");
        }
        if self.width == Width::DWord && self.access == Access::In && !self.real {
            s.push_str(", HC");
        }
        s.push_str(", *VD, *LD, *AC");
        if self.acc_const && self.access == Access::In {
            s.push_str(if self.real {
                ", real constant"
            } else {
                ", constant"
            });
        }
        if self.addr_of {
            s.push_str(", &VB/&IB/&QB/&MB/&SB/&SMB/&AIW/&AQW/&T/&C");
        }
        s
    }
}

fn width_name(w: Width) -> &'static str {
    match w {
        Width::Byte => "byte",
        Width::Word => "word",
        Width::DWord => "dword",
    }
}

/// Operand checking state: the profile, the symbols and the diagnostics so far.
pub(crate) struct Cx<'s> {
    /// The CPU profile.
    pub(crate) profile: &'static CpuProfile,
    /// The project symbol table, if any.
    pub(crate) symbols: Option<&'s SymbolTable>,
    /// The CPU's system symbols.
    pub(crate) system: &'static SymbolTable,
    /// The local variables of the block being lowered.
    pub(crate) locals: Option<std::rc::Rc<Locals>>,
    /// Every diagnostic so far.
    pub(crate) diags: Vec<Diagnostic>,
    /// File of the line being checked.
    pub(crate) file: FileId,
    /// Line being checked.
    pub(crate) line: u32,
    /// File names, for "first defined in …" notes.
    pub(crate) file_names: Vec<String>,
}

impl Cx<'_> {
    /// "line N" when `span` is in the current file, else "line N of FILE".
    pub(crate) fn place(&self, span: Span) -> String {
        if span.file == self.file {
            format!("line {}", span.line)
        } else {
            let name = self
                .file_names
                .get(span.file.index())
                .map_or("?", String::as_str);
            format!("line {} of {name}", span.line)
        }
    }

    /// The span of a token on the current line.
    pub(crate) fn span(&self, t: Tok<'_>) -> Span {
        Span {
            file: self.file,
            line: self.line,
            col: t.col,
            len: t.len,
        }
    }

    /// Pushes a diagnostic about token `t`.
    pub(crate) fn report(
        &mut self,
        code: Code,
        t: Tok<'_>,
        message: impl Into<String>,
        help: Option<String>,
    ) -> Reported {
        let mut d = Diagnostic::new(code, self.span(t), t.text, message);
        d.help = help;
        self.diags.push(d);
        Reported
    }

    /// What names are visible now.
    pub(crate) fn scope(&self) -> Scope<'_> {
        Scope {
            user: self.symbols,
            system: self.system,
            locals: self.locals.as_deref(),
        }
    }

    /// Resolves operand text (address, constant, local variable or symbol).
    pub(crate) fn syn(&mut self, t: Tok<'_>) -> R<Syn> {
        let result = self.scope().resolve(t.text);
        match result {
            Ok(r) => {
                self.resolved_via(t, r.via);
                Ok(r.syn)
            }
            Err(ResolveError::Malformed(why)) => Err(self.report(
                Code::Malformed,
                t,
                format!("malformed operand `{}`", clip(t.text)),
                Some(why.to_owned()),
            )),
            Err(ResolveError::UnknownSymbol(name)) => Err(self.report(
                Code::UnknownSymbol,
                t,
                format!("unknown symbol `{}`", clip(&name)),
                Some("define it in the symbol table (--symbols) or write an address".to_owned()),
            )),
            Err(ResolveError::UnknownLocal(name)) => {
                let help = match self.locals.as_deref().map(Locals::names) {
                    Some(names) if !names.is_empty() => {
                        format!("this block declares: {}", names.join(", "))
                    }
                    _ => "this block declares no local variables (VAR_INPUT … END_VAR)".to_owned(),
                };
                Err(self.report(
                    Code::UnknownSymbol,
                    t,
                    format!("unknown local variable `{}`", clip(&name)),
                    Some(help),
                ))
            }
            Err(ResolveError::LocalBit(name, absolute)) => {
                let help = match absolute {
                    Some(a) => format!("write the absolute L bit: `{a}`"),
                    None => "a local variable is addressed as a whole; write an absolute L bit"
                        .to_owned(),
                };
                Err(self.report(
                    Code::Malformed,
                    t,
                    format!("`{}` addresses a bit of a local variable", clip(&name)),
                    Some(help),
                ))
            }
            Err(ResolveError::Invalid) => Err(Reported),
            Err(ResolveError::PouSymbol(name)) => Err(self.report(
                Code::OperandClass,
                t,
                format!("symbol `{}` names a program block, not memory", clip(&name)),
                None,
            )),
            Err(ResolveError::Mismatch {
                symbol,
                names,
                written,
            }) => Err(self.report(
                Code::SymbolMismatch,
                t,
                format!(
                    "`{}` names {}, not {}",
                    clip(&symbol),
                    crate::operand::show(names),
                    crate::operand::show(written)
                ),
                Some("in `symbol:address` the address must be the one the symbol names".into()),
            )),
        }
    }

    /// The warnings a successful resolution may deserve.
    fn resolved_via(&mut self, t: Tok<'_>, via: Via) {
        let (code, message, help) = match via {
            Via::Plain => return,
            Via::BareLocal { hides } => (
                Code::UnprefixedLocal,
                format!("`{}` is taken as the local variable `#{0}`", clip(t.text)),
                if hides {
                    "it hides the global symbol of the same name in this block; write `#` to make it clear"
                } else {
                    "MicroWIN writes local variables with `#`"
                },
            ),
            Via::Unchecked => (
                Code::UncheckedSymbol,
                format!(
                    "`{}`: the symbol is not defined, so only the address is used",
                    clip(t.text)
                ),
                "give the project's symbol table (--symbols) to have the pair checked",
            ),
        };
        let mut d = Diagnostic::new(code, self.span(t), t.text, message);
        d.help = Some(help.to_owned());
        self.diags.push(d);
    }

    fn out_of_range(&mut self, t: Tok<'_>, what: String, allowed: String) -> Reported {
        let model = self.profile.model;
        self.report(
            Code::OutOfRange,
            t,
            format!("{what} is out of range for the {model}"),
            Some(format!("allowed: {allowed}")),
        )
    }

    /// Checks that `count` bytes from `offset` lie inside `area`.
    fn range(&mut self, t: Tok<'_>, area: Area, offset: u32, width: Width) -> R<()> {
        let size = self.profile.area_size(area);
        if offset
            .checked_add(width.bytes())
            .is_some_and(|end| end <= size)
        {
            return Ok(());
        }
        let prefix = match area {
            Area::AI => "AIW".to_owned(),
            Area::AQ => "AQW".to_owned(),
            a => format!("{}{}", area_prefix(a), width_letter(width)),
        };
        let last = size.saturating_sub(width.bytes());
        let mut allowed = format!("{prefix}0 - {prefix}{last}");
        if width != Width::Byte && offset < size {
            allowed.push_str(&format!(
                " ({prefix}{offset} needs {}B{})",
                area_prefix(area),
                offset + width.bytes() - 1
            ));
        }
        Err(self.out_of_range(t, format!("`{}`", clip(t.text)), allowed))
    }

    fn count_range(&mut self, t: Tok<'_>, prefix: &str, n: u32, count: u16) -> R<()> {
        if n < u32::from(count) {
            return Ok(());
        }
        let last = count.saturating_sub(1);
        Err(self.out_of_range(
            t,
            format!("`{}`", clip(t.text)),
            format!("{prefix}0 - {prefix}{last}"),
        ))
    }

    fn read_only(&mut self, t: Tok<'_>, what: &str) -> Reported {
        let ro = self.profile.special_memory_read_only;
        self.report(
            Code::ReadOnly,
            t,
            format!("`{}` is written here but {what} is read-only", clip(t.text)),
            Some(format!(
                "writable: I, Q, M, S, V, L, SMB{ro} and above, T, C, AC; read-only: SMB0-SMB{}, AIW, HC, constants",
                ro.saturating_sub(1)
            )),
        )
    }

    /// Resolves a bit operand.
    pub(crate) fn bit(&mut self, t: Tok<'_>, class: BitClass) -> R<BitLoc> {
        let syn = self.syn(t)?;
        let help = match class {
            BitClass::Read | BitClass::Write => "allowed: I, Q, M, SM, T, C, V, S, L bits",
            BitClass::Input => "allowed: I bits (e.g. I0.3)",
            BitClass::Output => "allowed: Q bits (e.g. Q0.1)",
            BitClass::Seq => "allowed: S bits (e.g. S0.1)",
            BitClass::MemRead | BitClass::MemWrite => "allowed: I, Q, M, SM, V, S, L bits",
        };
        let write = matches!(
            class,
            BitClass::Write | BitClass::Output | BitClass::MemWrite
        );
        let loc = match syn {
            Syn::Bit { area, byte, bit } => {
                let ok = match class {
                    BitClass::Input => area == Area::I,
                    BitClass::Output => area == Area::Q,
                    BitClass::Seq => area == Area::S,
                    _ => true,
                };
                if !ok {
                    return Err(self.report(
                        Code::OperandClass,
                        t,
                        format!("`{}` is not allowed here", clip(t.text)),
                        Some(help.to_owned()),
                    ));
                }
                let size = self.profile.area_size(area);
                if byte >= size {
                    let p = area_prefix(area);
                    return Err(self.out_of_range(
                        t,
                        format!("`{}`", clip(t.text)),
                        format!("{p}0.0 - {p}{}.7", size.saturating_sub(1)),
                    ));
                }
                BitLoc { area, byte, bit }
            }
            Syn::Timer(n) | Syn::Counter(n)
                if matches!(class, BitClass::Read | BitClass::Write) =>
            {
                let (area, prefix, count) = match syn {
                    Syn::Timer(_) => (Area::TimerBit, "T", self.profile.timers),
                    _ => (Area::CounterBit, "C", self.profile.counters),
                };
                self.count_range(t, prefix, n, count)?;
                BitLoc {
                    area,
                    byte: n,
                    bit: 0,
                }
            }
            Syn::Mem { width, .. } => {
                return Err(self.report(
                    Code::OperandWidth,
                    t,
                    format!(
                        "expected a bit, found {} address `{}`",
                        width_name(width),
                        clip(t.text)
                    ),
                    Some(help.to_owned()),
                ));
            }
            other => {
                return Err(self.report(
                    Code::OperandClass,
                    t,
                    format!(
                        "expected a bit, found {} `{}`",
                        other.describe(),
                        clip(t.text)
                    ),
                    Some(help.to_owned()),
                ));
            }
        };
        if write && loc.area == Area::SM && loc.byte < self.profile.special_memory_read_only {
            return Err(self.read_only(t, "this special-memory bit"));
        }
        Ok(loc)
    }

    /// Resolves a value operand of the class `v`.
    pub(crate) fn value(&mut self, t: Tok<'_>, v: Val) -> R<Operand> {
        let syn = self.syn(t)?;
        let wrong_class = |cx: &mut Self, what: &str| {
            cx.report(
                Code::OperandClass,
                t,
                format!(
                    "expected a {} operand, found {what} `{}`",
                    if v.real { "real" } else { width_name(v.width) },
                    clip(t.text)
                ),
                Some(v.allowed()),
            )
        };
        let out = v.access == Access::Out;
        match syn {
            Syn::Mem {
                area,
                width,
                offset,
            } => {
                if width != v.width {
                    return Err(self.report(
                        Code::OperandWidth,
                        t,
                        format!(
                            "expected a {} operand, found {} address `{}`",
                            width_name(v.width),
                            width_name(width),
                            clip(t.text)
                        ),
                        Some(v.allowed()),
                    ));
                }
                if area == Area::AI && out {
                    return Err(self.read_only(t, "AIW"));
                }
                if area == Area::AQ && !(out && v.aq_out) {
                    return Err(wrong_class(self, "analog output"));
                }
                if matches!(area, Area::AI | Area::AQ) && offset % 2 != 0 {
                    return Err(self.report(
                        Code::OddAnalog,
                        t,
                        format!("analog address `{}` is odd", clip(t.text)),
                        Some("AIW/AQW addresses are even byte offsets: AIW0, AIW2, ...".into()),
                    ));
                }
                self.range(t, area, offset, width)?;
                if out && area == Area::SM && offset < self.profile.special_memory_read_only {
                    return Err(self.read_only(t, "SMB0-SMB29"));
                }
                Ok(Operand::Mem(Loc { area, offset }))
            }
            Syn::Timer(n) | Syn::Counter(n) => {
                if v.width != Width::Word || v.real {
                    return Err(wrong_class(self, "a timer/counter (a word current value)"));
                }
                let (area, prefix, count) = match syn {
                    Syn::Timer(_) => (Area::TimerValue, "T", self.profile.timers),
                    _ => (Area::CounterValue, "C", self.profile.counters),
                };
                self.count_range(t, prefix, n, count)?;
                Ok(Operand::Mem(Loc {
                    area,
                    offset: 2 * n,
                }))
            }
            Syn::Acc(n) => {
                if !v.acc_const {
                    return Err(wrong_class(self, "an accumulator"));
                }
                self.count_range(t, "AC", n, self.profile.accumulators)?;
                Ok(Operand::Mem(Loc {
                    area: Area::AC,
                    offset: 4 * n + 4 - v.width.bytes(),
                }))
            }
            Syn::Hc(n) => {
                if out {
                    return Err(self.read_only(t, "HC"));
                }
                if v.width != Width::DWord || v.real || !v.acc_const {
                    return Err(wrong_class(self, "a high-speed counter (a dword)"));
                }
                self.count_range(t, "HC", n, self.profile.high_speed_counters)?;
                Ok(Operand::Mem(Loc {
                    area: Area::HC,
                    offset: 4 * n,
                }))
            }
            Syn::Const(c) => {
                if out {
                    return Err(self.read_only(t, "a constant"));
                }
                if !v.acc_const {
                    return Err(wrong_class(self, "a constant"));
                }
                self.constant(t, c, v)
            }
            Syn::Indirect { area, n } => {
                let loc = if area == Area::AC {
                    self.count_range(t, "AC", n, self.profile.accumulators)?;
                    Loc {
                        area,
                        offset: 4 * n,
                    }
                } else {
                    self.range(t, area, n, Width::DWord)?;
                    Loc { area, offset: n }
                };
                Ok(Operand::Indirect(loc))
            }
            Syn::AddressOf { area, n } => {
                if !v.addr_of {
                    return Err(self.report(
                        Code::OperandClass,
                        t,
                        format!("address-of `{}` is not allowed here", clip(t.text)),
                        Some("& is only allowed as the input of MOVD".into()),
                    ));
                }
                let offset = match area {
                    Area::TimerValue => {
                        self.count_range(t, "&T", n, self.profile.timers)?;
                        2 * n
                    }
                    Area::CounterValue => {
                        self.count_range(t, "&C", n, self.profile.counters)?;
                        2 * n
                    }
                    Area::AI | Area::AQ => {
                        if n % 2 != 0 {
                            return Err(self.report(
                                Code::OddAnalog,
                                t,
                                format!("analog address `{}` is odd", clip(t.text)),
                                Some("AIW/AQW addresses are even".into()),
                            ));
                        }
                        self.range(t, area, n, Width::Word)?;
                        n
                    }
                    _ => {
                        self.range(t, area, n, Width::Byte)?;
                        n
                    }
                };
                Ok(Operand::AddressOf(Loc { area, offset }))
            }
            Syn::Bit { .. } => Err(self.report(
                Code::OperandWidth,
                t,
                format!(
                    "expected a {} operand, found bit address `{}`",
                    width_name(v.width),
                    clip(t.text)
                ),
                Some(v.allowed()),
            )),
        }
    }

    /// Converts a constant to the bit pattern of the operand width.
    fn constant(&mut self, t: Tok<'_>, c: Const, v: Val) -> R<Operand> {
        let (lo, hi): (i64, i64) = match v.width {
            Width::Byte => (-128, 255),
            Width::Word => (-32768, 65535),
            Width::DWord => (i64::from(i32::MIN), i64::from(u32::MAX)),
        };
        let bits = match c {
            Const::Real(f) if v.real => Some(f.to_bits()),
            Const::Int(i) if v.real => Some((i as f32).to_bits()),
            Const::Real(_) => {
                return Err(self.report(
                    Code::OperandClass,
                    t,
                    format!(
                        "real constant `{}` where an integer {} is expected",
                        clip(t.text),
                        width_name(v.width)
                    ),
                    Some(v.allowed()),
                ));
            }
            Const::Int(i) => (lo..=hi).contains(&i).then(|| (i as u32) & v.width.mask()),
            Const::Bits(b) => u32::try_from(b).ok().filter(|&b| b <= v.width.mask()),
        };
        bits.map(Operand::Const).ok_or_else(|| {
            self.report(
                Code::NumberRange,
                t,
                format!(
                    "constant `{}` does not fit a {}",
                    clip(t.text),
                    if v.real { "real" } else { width_name(v.width) }
                ),
                Some(if v.real {
                    "allowed: a finite real".to_owned()
                } else {
                    format!("allowed: {lo} .. {hi}")
                }),
            )
        })
    }

    /// A timer object (`TON T37, ...`, `R T37, n`).
    pub(crate) fn timer(&mut self, t: Tok<'_>) -> R<TimerId> {
        match self.syn(t)? {
            Syn::Timer(n) => {
                self.count_range(t, "T", n, self.profile.timers)?;
                Ok(TimerId(u16::try_from(n).unwrap_or(u16::MAX)))
            }
            other => Err(self.report(
                Code::OperandClass,
                t,
                format!(
                    "expected a timer, found {} `{}`",
                    other.describe(),
                    clip(t.text)
                ),
                Some(format!(
                    "allowed: T0 - T{}",
                    self.profile.timers.saturating_sub(1)
                )),
            )),
        }
    }

    /// A counter object (`CTU C5, ...`).
    pub(crate) fn counter(&mut self, t: Tok<'_>) -> R<CounterId> {
        match self.syn(t)? {
            Syn::Counter(n) => {
                self.count_range(t, "C", n, self.profile.counters)?;
                Ok(CounterId(u16::try_from(n).unwrap_or(u16::MAX)))
            }
            other => Err(self.report(
                Code::OperandClass,
                t,
                format!(
                    "expected a counter, found {} `{}`",
                    other.describe(),
                    clip(t.text)
                ),
                Some(format!(
                    "allowed: C0 - C{}",
                    self.profile.counters.saturating_sub(1)
                )),
            )),
        }
    }

    /// A plain decimal number in `lo..=hi` (label, LDS level, NOP count); `code` on range errors.
    pub(crate) fn number(
        &mut self,
        t: Tok<'_>,
        lo: u32,
        hi: u32,
        what: &str,
        code: Code,
    ) -> R<u32> {
        match self.syn(t)? {
            Syn::Const(Const::Int(i)) if (i64::from(lo)..=i64::from(hi)).contains(&i) => {
                Ok(u32::try_from(i).unwrap_or(0))
            }
            Syn::Const(Const::Int(_) | Const::Bits(_)) => Err(self.report(
                code,
                t,
                format!("{what} `{}` is out of range", clip(t.text)),
                Some(format!("allowed: {lo} .. {hi}")),
            )),
            other => Err(self.report(
                Code::OperandClass,
                t,
                format!(
                    "expected {what}, found {} `{}`",
                    other.describe(),
                    clip(t.text)
                ),
                Some(format!("allowed: a number {lo} .. {hi}")),
            )),
        }
    }
}
