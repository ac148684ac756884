//! Timers, counters and the data boxes (omron-cp.md §3.3, §3.5, §3.6): their operands (timer
//! and counter numbers, set values with the BCD check E015, single and double words) and the
//! number-reuse check E021.

use crate::circuit::Class;
use crate::immediate::{Refresh, data_refresh};
use crate::lexer::{Line, Tok};
use crate::lower::{DataBox, Lowerer, Written};
use crate::resolve::Reported;
use stljit_core::ir::{OmronBox, OmronCounterKind, OmronTimerKind, Op, Operand};
use stljit_core::{Area, CounterId, TimerId};
use stljit_source::{Code, clip};

impl Lowerer<'_> {
    /// A timer or counter number: `0000`, `T0000` / `C0000` or `&0` (§1.2), range-checked
    /// (E014) and unique per area (E021).
    fn object_number(&mut self, tok: &Tok, area: Area) -> Result<u16, Reported> {
        let up = tok.text.to_ascii_uppercase();
        let prefixes: &[&str] = if area == Area::TimerBit {
            &["TIM", "T"]
        } else {
            &["CNT", "C"]
        };
        let bare = prefixes
            .iter()
            .find_map(|p| up.strip_prefix(p))
            .filter(|r| r.starts_with(|c: char| c.is_ascii_digit()))
            .unwrap_or(&up);
        let plain = Tok {
            text: bare.to_owned(),
            ..tok.clone()
        };
        let n = self
            .cx
            .number(&plain, u32::from(u16::MAX), "timer/counter number")?;
        let n = self.cx.object(tok, area, n)?;
        let line = self.cx.line;
        if let Some(first) = self.objects.get(&(area, n)) {
            let name = if area == Area::TimerBit { "T" } else { "C" };
            let first = *first;
            return Err(self.cx.report(
                Code::OmrNumberTwice,
                tok,
                format!(
                    "line {line}: {name}{n:04} already used by a {} instruction at line {first}",
                    if area == Area::TimerBit {
                        "timer"
                    } else {
                        "counter"
                    }
                ),
            ));
        }
        self.objects.insert((area, n), line);
        Ok(n)
    }

    /// A set value: a word, or a constant that must be BCD for the BCD kinds (E015).
    fn set_value(&mut self, tok: &Tok, bcd: bool) -> Result<Operand, Reported> {
        let sv = self.cx.word(tok, 1, false)?;
        if let Operand::Const(v) = sv {
            let is_bcd = (0..4).all(|i| (v >> (4 * i)) & 0xF <= 9);
            if bcd && !is_bcd {
                let (line, mn) = (self.cx.line, self.cx.mn.clone());
                return Err(self.cx.report(
                    Code::OmrConstant,
                    tok,
                    format!(
                        "line {line}: {} is not a valid BCD constant for {mn} operand 2",
                        clip(&tok.text)
                    ),
                ));
            }
        }
        Ok(sv)
    }

    /// The TIM family and TTIM: `OmronTimer{kind, timer, set_value}`.
    pub(crate) fn timer(&mut self, l: &Line, kind: OmronTimerKind) -> Result<(), Reported> {
        let kind = self.cx.options.tc_mode.timer(kind);
        let ops = self.operands(l, 2)?;
        let n = self.object_number(&ops[0], Area::TimerBit);
        let sv = self.set_value(&ops[1], kind.bcd());
        let (n, sv) = (n?, sv?);
        let class = if kind.totalizing() {
            Class::Multi(2)
        } else {
            Class::Output
        };
        self.flags_changed = true;
        self.class(l, class);
        self.emit(Op::OmronTimer {
            kind,
            timer: TimerId(n),
            set_value: sv,
        });
        Ok(())
    }

    /// CNT (2 conditions) and CNTR (3): `OmronCounter{kind, counter, set_value}`.
    pub(crate) fn counter(&mut self, l: &Line, kind: OmronCounterKind) -> Result<(), Reported> {
        let kind = self.cx.options.tc_mode.counter(kind);
        let ops = self.operands(l, 2)?;
        let n = self.object_number(&ops[0], Area::CounterBit);
        let sv = self.set_value(&ops[1], kind.bcd());
        let (n, sv) = (n?, sv?);
        self.flags_changed = true;
        self.class(l, Class::Multi(u32::from(kind.conditions())));
        self.emit(Op::OmronCounter {
            kind,
            counter: CounterId(n),
            set_value: sv,
        });
        Ok(())
    }

    /// MOV/MOVL, CMP/CMPL/CPS/CPSL and the arithmetic, with `@`/`%`.
    pub(crate) fn data(&mut self, l: &Line, what: DataBox) -> Result<(), Reported> {
        let n = if matches!(what, DataBox::Arith(_)) {
            3
        } else {
            2
        };
        let ops = self.operands(l, n)?;
        let op = match what {
            DataBox::Move(double) => {
                let w = if double { 2 } else { 1 };
                let src = self.cx.data_word(&ops[0], w, false);
                let dst = self.cx.data_word(&ops[1], w, true);
                OmronBox::Move {
                    double,
                    src: src?,
                    dst: dst?,
                }
            }
            DataBox::Compare(double, signed) => {
                let w = if double { 2 } else { 1 };
                let lhs = self.cx.data_word(&ops[0], w, false);
                let rhs = self.cx.data_word(&ops[1], w, false);
                OmronBox::Compare {
                    double,
                    signed,
                    lhs: lhs?,
                    rhs: rhs?,
                }
            }
            DataBox::Arith(op) => {
                let w = op.operand_words();
                let lhs = self.cx.data_word(&ops[0], w, false);
                let rhs = self.cx.data_word(&ops[1], w, false);
                let dst = self.cx.data_word(&ops[2], op.result_words(), true);
                OmronBox::Arith {
                    op,
                    lhs: lhs?,
                    rhs: rhs?,
                    dst: dst?,
                }
            }
        };
        if let (OmronBox::Move { dst, .. } | OmronBox::Arith { dst, .. }, Some(tok)) =
            (op, ops.last())
            && let Operand::Mem(loc) = dst
        {
            self.note_write(tok, Written::Word(loc));
        }
        self.flags_changed = true;
        self.class(l, Class::Output);
        let immediate = l.options.immediate;
        let (reads, writes) = if immediate {
            data_refresh(&op)
        } else {
            (Vec::new(), Vec::new())
        };
        self.edged(l.options, |s| {
            s.refresh_inputs(reads, Refresh::WhenExecuted);
            s.emit(Op::Omron(op));
            s.refresh_outputs(writes, Refresh::WhenExecuted);
        });
        Ok(())
    }

    /// `MOVR(560) S IRn`: `IRn :=` the effective address of `S` (core::omron's §1.5 map; a
    /// bit's address is `16 · word address + bit`).
    pub(crate) fn move_address(&mut self, l: &Line) -> Result<(), Reported> {
        let ops = self.operands(l, 2)?;
        let ea = self.cx.effective_address(&ops[0]);
        let ir = self.cx.index_register(&ops[1]);
        let (ea, ir) = (ea?, ir?);
        self.class(l, Class::Output);
        self.edged(l.options, |s| {
            s.emit(Op::Omron(OmronBox::SetIndex { ea, ir }))
        });
        Ok(())
    }

    /// `IORF(097) St E`: refreshes expansion I/O words St…E immediately (§3.4). The model has
    /// only the built-in I/O, on which IORF has no effect, so it lowers to nothing once its
    /// operands (two CIO words, St ≤ E) are checked.
    pub(crate) fn iorf(&mut self, l: &Line) -> Result<(), Reported> {
        let ops = self.operands(l, 2)?;
        let st = self.cx.word(&ops[0], 1, false);
        let e = self.cx.word(&ops[1], 1, false);
        let (st, e) = (st?, e?);
        let cio = |o: &Operand| match o {
            Operand::Mem(loc) => stljit_core::omron::word_of(self.cx.profile, *loc)
                .filter(|(a, _)| *a == stljit_core::omron::WordArea::Cio)
                .map(|(_, w)| w),
            _ => None,
        };
        match (cio(&st), cio(&e)) {
            (Some(a), Some(b)) if a <= b => {}
            _ => {
                let (line, mn) = (self.cx.line, self.cx.mn.clone());
                return Err(self.cx.report(
                    Code::OmrOperand,
                    &ops[0],
                    format!("line {line}: {mn} expects two CIO words St ≤ E"),
                ));
            }
        }
        self.class(l, Class::Output);
        Ok(())
    }
}
