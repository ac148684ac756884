//! Timers, counters and the data instructions (MOV/MOVL/MOVR, the compares, the arithmetic,
//! CCS/CCL, IORF) with their operands: words of every area (multi-word ones inside their area),
//! constants in every form biased to boundaries and to valid and invalid BCD, and the indirect
//! forms `@D`/`*D`/IR whose pointers a setup rung aims inside and outside their areas.

use super::OmronGen;
use stljit_core::ir::OmronArith;
use stljit_front_omron::mnemonics::{self, Group, Join, Mnemonic, TABLE};

/// A random BCD number of up to `digits` digits, written as its hex pattern.
fn bcd_text(value: u32, digits: usize) -> String {
    let v = value % 10u32.pow(digits as u32);
    format!("#{v:0digits$}")
}

impl OmronGen<'_, '_> {
    /// Options for `m` (an entry of the table or an arithmetic instruction): none in a block
    /// program (`@`/`%`) or a function block (`!`).
    pub(crate) fn options_of(&mut self, m: &Mnemonic) -> String {
        let a = m.allowed;
        let edges = !self.block;
        let edge =
            match self
                .c
                .weighted(&[10, u32::from(a.up && edges) * 2, u32::from(a.down && edges)])
            {
                1 => "@",
                2 => "%",
                _ => "",
            };
        let bang = if a.immediate && !self.plain && self.c.chance(1, 6) {
            "!"
        } else {
            ""
        };
        format!("{bang}{edge}")
    }

    /// A direct location of `words` consecutive words in one area; `write` for a destination
    /// (never A0–A447; the input words rarely).
    pub(crate) fn loc_word(&mut self, words: u32, write: bool) -> String {
        let o = self.p.omron;
        let weights = [
            8,                         // D
            3,                         // W
            2,                         // H
            2,                         // CIO work words
            if write { 0 } else { 2 }, // CIO input words
            1,                         // CIO output words
            1,                         // A
            1,                         // T PV
            1,                         // C PV
            u32::from(words == 1),     // DR
        ];
        let edge = self.c.chance(1, 20);
        match self.c.weighted(&weights) {
            0 => {
                let w = if edge {
                    o.dm - words
                } else if self.c.chance(1, 6) {
                    100 + self.c.below(4)
                } else {
                    self.c.below(32)
                };
                format!("D{w}")
            }
            1 => format!(
                "W{}",
                if edge {
                    o.work - words
                } else {
                    self.c.below(8)
                }
            ),
            2 => format!(
                "H{}",
                if edge {
                    o.holding - words
                } else {
                    self.c.below(4)
                }
            ),
            3 => {
                let w = if edge {
                    o.cio - words
                } else {
                    2 + self.c.below(8)
                };
                self.cio(w, None)
            }
            4 if words <= 2 => {
                let w = if words == 1 { self.c.below(2) } else { 0 };
                self.cio(w, None)
            }
            5 if words <= 2 => {
                let w = if words == 1 {
                    100 + self.c.below(2)
                } else {
                    100
                };
                self.cio(w, None)
            }
            6 => {
                let w = if write || self.c.chance(1, 2) {
                    o.aux_read_only + self.c.below(4)
                } else {
                    [200, 0, 100, o.aux_read_only - 1][self.c.below(4) as usize]
                };
                format!("A{w}")
            }
            7 | 8 => {
                let timer = self.c.chance(1, 2);
                let count = u32::from(if timer {
                    self.p.timers
                } else {
                    self.p.counters
                });
                let n = self.some_object(timer).min(count - words);
                self.object_operand(timer, n)
            }
            9 => format!("DR{}", self.c.below(16)),
            _ => format!("D{}", self.c.below(32)),
        }
    }

    /// A constant of `words` words (1 or 2) in any form; `bcd` biases to valid BCD digits.
    pub(crate) fn constant(&mut self, words: u32, bcd: bool) -> String {
        let digits = 4 * words as usize;
        if bcd && self.c.chance(3, 4) {
            let v = if self.c.chance(1, 2) {
                self.c.below(100)
            } else {
                self.c.bits()
            };
            return bcd_text(
                v,
                if self.c.chance(1, 4) {
                    digits
                } else {
                    4.min(digits)
                },
            );
        }
        let bits = if words == 1 { 0xFFFF } else { u32::MAX };
        let boundary = [
            0,
            1,
            0x7FFF,
            0x8000,
            0xFFFF,
            0x9999,
            0x12A4,
            bits,
            bits >> 1,
        ];
        let v = match self.c.weighted(&[3, 3, 2]) {
            0 => self.c.below(300),
            1 => self.c.pick(&boundary) & bits,
            _ => self.c.bits() & bits,
        };
        match self.c.weighted(&[5, 2, 2]) {
            0 => format!("#{v:X}"),
            1 => format!("&{v}"),
            _ => {
                let signed = if words == 1 {
                    i64::from(v as u16 as i16)
                } else {
                    i64::from(v as i32)
                };
                format!("{signed:+}")
            }
        }
    }

    /// An indirect operand: `@Dn`, `*Dn` (pointer words D100–D103 mostly) or an IR form.
    pub(crate) fn indirect(&mut self) -> String {
        let pointer = if self.c.chance(4, 5) {
            100 + self.c.below(4)
        } else {
            self.c.below(self.p.omron.dm)
        };
        let ir = if self.c.chance(4, 5) {
            self.c.below(4)
        } else {
            self.c.below(16)
        };
        match self.c.weighted(&[3, 3, 2, 2, 1, 2, 1, 1, 1]) {
            0 => format!("@D{pointer}"),
            1 => format!("*D{pointer}"),
            2 => format!(",IR{ir}"),
            3 => {
                let off = match self.c.below(3) {
                    0 => self.c.range(0, 8) as i32 - 4,
                    1 => self.c.pick(&[2047, -2048, 512, -512]),
                    _ => self.c.range(0, 4095) as i32 - 2048,
                };
                format!("{off:+},IR{ir}")
            }
            4 => format!("DR{},IR{ir}", self.c.below(4)),
            5 => format!(",IR{ir}+"),
            6 => format!(",IR{ir}++"),
            7 => format!(",-IR{ir}"),
            _ => format!(",--IR{ir}"),
        }
    }

    /// A built-in input (`input`) or output word of `words` words, where `!` refreshes; a
    /// four-word result, which no I/O area holds, goes to the DM area.
    pub(crate) fn io_word(&mut self, input: bool, words: u32) -> String {
        let base = if input { 0 } else { 100 };
        match words {
            1 => {
                let w = base + self.c.below(2);
                self.cio(w, None)
            }
            2 => self.cio(base, None),
            _ => self.loc_word(words, !input),
        }
    }

    /// A source of a data instruction written with `options`: with `!`, half the time a
    /// built-in input word (refreshed before the instruction).
    fn refreshed_src(&mut self, options: &str, words: u32) -> String {
        if options.contains('!') && self.c.chance(1, 2) {
            self.io_word(true, words)
        } else {
            self.src(words, true)
        }
    }

    /// A destination of a data instruction written with `options`: with `!`, half the time a
    /// built-in output word (refreshed after it).
    fn refreshed_dst(&mut self, options: &str, words: u32) -> String {
        if options.contains('!') && self.c.chance(1, 2) {
            self.io_word(false, words)
        } else {
            self.dst(words, true)
        }
    }

    /// A source of `words` words: a location, a constant or (`indirect`) an indirect form.
    pub(crate) fn src(&mut self, words: u32, indirect: bool) -> String {
        self.src_bcd(words, indirect, false)
    }

    fn src_bcd(&mut self, words: u32, indirect: bool, bcd: bool) -> String {
        match self.c.weighted(&[6, 4, if indirect { 2 } else { 0 }]) {
            0 => self.loc_word(words, false),
            1 => self.constant(words.min(2), bcd),
            _ => self.indirect(),
        }
    }

    /// A destination of `words` words.
    pub(crate) fn dst(&mut self, words: u32, indirect: bool) -> String {
        if indirect && self.c.chance(1, 5) {
            self.indirect()
        } else {
            self.loc_word(words, true)
        }
    }

    /// A fresh timer or counter number (E021: each once), or `None` when none is left.
    fn new_object(&mut self, timer: bool) -> Option<u32> {
        let count = u32::from(if timer {
            self.p.timers
        } else {
            self.p.counters
        });
        for _ in 0..6 {
            let n = if self.c.chance(1, 15) {
                count - 1 - self.c.below(2)
            } else {
                self.c.below(24.min(count))
            };
            let used = if timer {
                &mut self.timers
            } else {
                &mut self.counters
            };
            if used.insert(n) {
                return Some(n);
            }
        }
        None
    }

    /// The number operand of a timer or counter instruction, in one of its spellings.
    fn number_operand(&mut self, timer: bool, n: u32) -> String {
        match self.c.weighted(&[6, 2, 1, 1, 1]) {
            0 => format!("{n:04}"),
            1 => self.object_operand(timer, n),
            2 => format!("&{n}"),
            3 => n.to_string(),
            _ => format!("#{n:04X}"),
        }
    }

    /// A set value: mostly a constant (BCD for the BCD kinds), else a word whose contents may
    /// be anything (so invalid BCD set values occur at run time).
    fn set_value(&mut self, bcd: bool) -> String {
        if self.c.chance(1, 3) {
            return self.loc_word(1, false);
        }
        if bcd {
            let v = if self.c.chance(1, 8) {
                self.c.below(10_000)
            } else {
                self.c.below(60)
            };
            return if v < 10 && self.c.chance(1, 4) {
                format!("&{v}")
            } else {
                bcd_text(v, 4)
            };
        }
        let v = if self.c.chance(1, 10) {
            self.c.pick(&[0, 0xFFFF, 0x8000])
        } else {
            self.c.below(600)
        };
        match self.c.below(3) {
            0 => format!("#{v:04X}"),
            1 => format!("&{v}"),
            _ => format!("{:+}", v as u16 as i16),
        }
    }

    /// A timer of any kind (TTIM with its reset condition), now and then its flag read after.
    pub(crate) fn timer_rung(&mut self) {
        let kinds: Vec<&Mnemonic> = TABLE
            .iter()
            .filter(|m| matches!(m.group, Group::Timer(_)))
            .collect();
        let m = self.c.pick(&kinds);
        let Group::Timer(kind) = m.group else { return };
        let Some(n) = self.new_object(true) else {
            return self.logic_rung();
        };
        self.condition(0, 0);
        if kind.totalizing() {
            self.condition(1, 1);
        }
        // In the binary mode the plain timers take binary set values (their X forms).
        let sv = self.set_value(self.options.tc_mode.timer(kind).bcd());
        let num = self.number_operand(true, n);
        self.ins("", m.name, m.code, &[num, sv]);
        if self.c.chance(1, 2) {
            let t = self.object_operand(true, n);
            self.op("", Group::Contact(Join::Load, false), &[t]);
            self.bit_output();
        }
    }

    /// A counter of any kind with its count, (decrement) and reset conditions.
    pub(crate) fn counter_rung(&mut self) {
        let kinds: Vec<&Mnemonic> = TABLE
            .iter()
            .filter(|m| matches!(m.group, Group::Counter(_)))
            .collect();
        let m = self.c.pick(&kinds);
        let Group::Counter(kind) = m.group else {
            return;
        };
        let Some(n) = self.new_object(false) else {
            return self.logic_rung();
        };
        for i in 0..u32::from(kind.conditions()) {
            self.condition(i, u32::from(i > 0));
        }
        let sv = self.set_value(self.options.tc_mode.counter(kind).bcd());
        let num = self.number_operand(false, n);
        self.ins("", m.name, m.code, &[num, sv]);
        if self.c.chance(1, 2) {
            let c = self.object_operand(false, n);
            self.op("", Group::Contact(Join::Load, false), &[c]);
            self.bit_output();
        }
    }

    /// A MOV into a timer's or counter's PV: valid and invalid BCD, binary values.
    pub(crate) fn pv_rewrite(&mut self) {
        self.condition(0, 0);
        let timer = self.c.chance(2, 3);
        let n = self.some_object(timer);
        let pv = self.object_operand(timer, n);
        let v = match self.c.below(4) {
            0 => bcd_text(self.c.below(30), 4),
            1 => self
                .c
                .pick(&["#12A4", "#FFFF", "#00A0", "#9999"])
                .to_owned(),
            2 => format!("&{}", self.c.below(100)),
            _ => "#0000".to_owned(),
        };
        let options = self.options(Group::Move(false));
        self.op(&options, Group::Move(false), &[v, pv]);
    }

    /// A rung of data instructions, their condition flags read on the rung as the manual
    /// recommends (`AND P_CY`, a TR branch for both outcomes of a compare).
    pub(crate) fn data_rung(&mut self) {
        self.condition(0, 0);
        for k in 0..self.c.range(1, 3) {
            if k > 0 && self.c.chance(1, 3) {
                self.continuation();
            }
            let compare = self.data_instruction();
            match self.c.weighted(&[3, 3, if compare { 3 } else { 0 }]) {
                0 => {}
                1 => {
                    let negated = self.c.chance(1, 3);
                    let f = self.condition_flag();
                    self.op("", Group::Contact(Join::And, negated), &[f]);
                    self.bit_output();
                }
                _ => {
                    // OUT TR0 is an OUT, which a block program may not hold.
                    if self.trs & 1 == 0 && !self.block {
                        self.trs |= 1;
                        self.op("", Group::Out(false), &["TR0".into()]);
                        for i in 0..2 {
                            if i > 0 {
                                self.op("", Group::Contact(Join::Load, false), &["TR0".into()]);
                            }
                            let f = self.condition_flag();
                            self.op("", Group::Contact(Join::And, false), &[f]);
                            self.bit_output();
                        }
                    }
                }
            }
        }
    }

    /// One data instruction; true for a compare.
    fn data_instruction(&mut self) -> bool {
        match self.c.weighted(&[6, 2, 3, 8]) {
            0 => {
                let double = self.c.chance(1, 3);
                let group = Group::Move(double);
                let options = self.options(group);
                let w = if double { 2 } else { 1 };
                let src = self.refreshed_src(&options, w);
                let dst = self.refreshed_dst(&options, w);
                self.op(&options, group, &[src, dst]);
                false
            }
            1 => {
                self.movr();
                false
            }
            2 => {
                let (double, signed) = (self.c.chance(1, 2), self.c.chance(1, 2));
                let group = Group::Compare(double, signed);
                let options = self.options(group);
                let w = if double { 2 } else { 1 };
                let lhs = self.refreshed_src(&options, w);
                let rhs = self.refreshed_src(&options, w);
                self.op(&options, group, &[lhs, rhs]);
                true
            }
            _ => {
                self.arith();
                false
            }
        }
    }

    /// One arithmetic instruction of §3.6, BCD ones biased to BCD constants.
    fn arith(&mut self) {
        let op = self.c.pick(OmronArith::ALL);
        let Some(m) = mnemonics::lookup(op.mnemonic()) else {
            return;
        };
        // Only a bias of the constants: the BCD family is the one whose name has a `B`.
        let bcd = op.mnemonic().contains('B');
        let options = self.options_of(&m);
        let w = op.operand_words();
        let (lhs, rhs, dst) = if options.contains('!') && self.c.chance(1, 2) {
            let lhs = self.io_word(true, w);
            let rhs = self.src_bcd(w, true, bcd);
            (lhs, rhs, self.io_word(false, op.result_words()))
        } else {
            let lhs = self.src_bcd(w, true, bcd);
            let rhs = self.src_bcd(w, true, bcd);
            (lhs, rhs, self.dst(op.result_words(), true))
        };
        self.ins(&options, m.name, m.code, &[lhs, rhs, dst]);
    }

    /// `MOVR(560) S IRn`: the address of a word, a bit (used as a word: an access error), a
    /// timer or counter PV, the last words of their areas (an IR stepped from there leaves).
    fn movr(&mut self) {
        let o = self.p.omron;
        let bit = self.c.below(16);
        let src = match self.c.weighted(&[5, 2, 2, 1, 1, 1, 2]) {
            0 => format!("D{}", self.c.below(40)),
            1 => format!("D{}", o.dm - 1 - self.c.below(3)),
            2 => format!("W{}", self.work_word()),
            3 => format!("W{}.{bit:02}", self.c.below(8)),
            4 => {
                let w = [0, 100, 2, o.cio - 1][self.c.below(4) as usize];
                self.cio(w, None)
            }
            5 => format!("H{}", self.c.below(4)),
            _ => {
                let timer = self.c.chance(1, 2);
                let n = self.some_object(timer);
                self.object_operand(timer, n)
            }
        };
        let ir = if self.c.chance(4, 5) {
            self.c.below(4)
        } else {
            self.c.below(16)
        };
        let options = self.options(Group::MoveAddress);
        self.op(&options, Group::MoveAddress, &[src, format!("IR{ir}")]);
    }

    /// CCS(282)/CCL(283) or IORF(097) on a condition.
    pub(crate) fn misc_rung(&mut self) {
        self.condition(0, 0);
        let group = match self.c.below(3) {
            0 => Group::SaveFlags(true),
            1 => Group::SaveFlags(false),
            _ => Group::Iorf,
        };
        let options = self.options(group);
        let operands = if group == Group::Iorf {
            let (st, e) = [(0, 1), (100, 101), (2, 5), (7, 7)][self.c.below(4) as usize];
            vec![self.cio(st, None), self.cio(e, None)]
        } else {
            Vec::new()
        };
        self.op(&options, group, &operands);
    }

    /// The program's first rung, half the time: pointers for `@D` (binary) and `*D` (BCD) in
    /// D100–D103 aimed inside and outside the DM area, IRs loaded by MOVR, DR offsets; every
    /// cycle (`P_On`) or once (`P_First_Cycle`, so post-increments walk on from scan to scan).
    pub(crate) fn setup(&mut self) {
        let first = if self.c.chance(1, 2) {
            "P_On"
        } else {
            "P_First_Cycle"
        };
        self.op("", Group::Contact(Join::Load, false), &[first.into()]);
        let dm = self.p.omron.dm;
        for _ in 0..self.c.range(2, 6) {
            let d = format!("D{}", 100 + self.c.below(4));
            match self.c.below(4) {
                0 => {
                    let v = match self.c.below(4) {
                        0 | 1 => self.c.below(40),
                        2 => dm - 1,
                        _ => self.c.pick(&[dm, 0x8000, 0xFFFF]),
                    };
                    self.op("", Group::Move(false), &[format!("&{v}"), d]);
                }
                1 => {
                    let v = match self.c.below(3) {
                        0 => bcd_text(self.c.below(40), 4),
                        1 => "#9999".to_owned(),
                        _ => self.c.pick(&["#12A4", "#0A00", "#FFFF"]).to_owned(),
                    };
                    self.op("", Group::Move(false), &[v, d]);
                }
                2 => self.movr(),
                _ => {
                    let v = match self.c.below(3) {
                        0 => self.c.range(0, 8) as i32 - 4,
                        1 => self.c.pick(&[2047, -2048, 32767, -32768]),
                        _ => self.c.range(0, 200) as i32 - 100,
                    };
                    let dr = format!("DR{}", self.c.below(4));
                    self.op("", Group::Move(false), &[format!("{v:+}"), dr]);
                }
            }
        }
    }
}
