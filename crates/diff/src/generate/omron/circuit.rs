//! Circuits: conditions (contacts with `@`/`%`/`!`, comparison contacts, NOT/UP/DOWN, nested
//! blocks joined by AND LD/OR LD), the bit outputs with AND continuation and TR branch points,
//! the multi-condition KEEP, DIFU/DIFD and rungs with many pending blocks.
//!
//! `pending` counts the blocks opened below the one being written; a condition never leaves
//! one open, and no more than 13 are ever pending (OMR-E041).

use super::OmronGen;
use stljit_core::ir::Address;
use stljit_core::omron::SystemBit;
use stljit_front_omron::mnemonics::{
    self, COMPARE_JOINS, COMPARE_OPTIONS, COMPARE_SUFFIXES, Group, Join, RELATIONS,
};
use stljit_front_omron::print_address;

/// Most blocks a condition may leave pending while it is written (E041 is above 13).
const MAX_PENDING: u32 = 12;

/// How an address is spelled: plain, or one of the forms the front end also accepts.
fn cio_spelling(word: u32, bit: Option<u32>, variant: u32) -> String {
    let w = match variant {
        1 => format!("CIO {word}"),
        2 => format!("CIO{word}"),
        3 => format!("{word:04}"),
        _ => word.to_string(),
    };
    match bit {
        Some(b) => format!("{w}.{b:02}"),
        None => w,
    }
}

impl OmronGen<'_, '_> {
    /// A CIO word or bit, now and then with a `CIO` prefix or leading zeros.
    pub(crate) fn cio(&mut self, word: u32, bit: Option<u32>) -> String {
        let v = if self.c.chance(1, 8) {
            self.c.range(1, 3)
        } else {
            0
        };
        cio_spelling(word, bit, v)
    }

    /// A timer (`T`) or counter (`C`) operand: `T0005`, `TIM0005`, `T5`.
    pub(crate) fn object_operand(&mut self, timer: bool, n: u32) -> String {
        let (short, long) = if timer { ("T", "TIM") } else { ("C", "CNT") };
        match self.c.weighted(&[6, 1, 1]) {
            0 => format!("{short}{n:04}"),
            1 => format!("{long}{n:04}"),
            _ => format!("{short}{n}"),
        }
    }

    fn system_bit(&mut self, bits: &[SystemBit]) -> String {
        let b = self.c.pick(bits);
        print_address(&Address::Bit(b.bit_loc()))
    }

    /// A condition flag (`P_EQ` … `P_AER`).
    pub(crate) fn condition_flag(&mut self) -> String {
        let n = SystemBit::CONDITION_FLAGS.count_ones() as usize;
        self.system_bit(&SystemBit::ALL[..n])
    }

    /// A bit to read.
    pub(crate) fn read_bit(&mut self) -> String {
        let dm_bits = self.p.omron.dm_bits;
        let w = [
            12,                          // input
            3,                           // output
            6,                           // W
            2,                           // H
            2,                           // CIO work
            2,                           // T flag
            2,                           // C flag
            2,                           // condition flag
            1,                           // P_On / P_Off
            1,                           // clock pulse
            1,                           // P_First_Cycle, A bits
            if dm_bits { 1 } else { 0 }, // D bit
        ];
        let bit = self.c.below(16);
        match self.c.weighted(&w) {
            0 => {
                let word = self.c.below(2);
                self.cio(word, Some(bit))
            }
            1 => {
                let word = 100 + self.c.below(2);
                self.cio(word, Some(bit))
            }
            2 => format!("W{}.{bit:02}", self.work_word()),
            3 => format!("H{}.{bit:02}", self.c.below(4)),
            4 => {
                let word = 2 + self.c.below(8);
                self.cio(word, Some(bit))
            }
            5 => {
                let n = self.some_object(true);
                self.object_operand(true, n)
            }
            6 => {
                let n = self.some_object(false);
                self.object_operand(false, n)
            }
            7 => self.condition_flag(),
            8 => self.system_bit(&[SystemBit::On, SystemBit::Off]),
            9 => {
                let pulses: Vec<SystemBit> = SystemBit::PULSES.iter().map(|p| p.0).collect();
                self.system_bit(&pulses)
            }
            10 => match self.c.below(4) {
                0 => "P_First_Cycle".into(),
                1 => format!("A448.{bit:02}"),
                // A step's bit, as a step's outputs would read it elsewhere.
                2 => self
                    .some_step_bit()
                    .unwrap_or_else(|| format!("A200.{bit:02}")),
                _ => format!("A200.{bit:02}"),
            },
            _ => format!("D{}.{bit:02}", self.c.below(16)),
        }
    }

    /// A work word, now and then the last one of the model.
    pub(crate) fn work_word(&mut self) -> u32 {
        if self.c.chance(1, 30) {
            self.p.omron.work - 1
        } else {
            self.c.below(8)
        }
    }

    /// A timer or counter number for reading: mostly one in use.
    pub(crate) fn some_object(&mut self, timer: bool) -> u32 {
        let used = if timer { &self.timers } else { &self.counters };
        let used: Vec<u32> = used.iter().copied().collect();
        if !used.is_empty() && self.c.chance(3, 4) {
            return self.c.pick(&used);
        }
        self.c.below(16)
    }

    /// A bit to write (a coil), mostly one no earlier coil writes (W020 is only a warning).
    pub(crate) fn write_bit(&mut self) -> String {
        let mut b = self.write_bit_once();
        for _ in 0..3 {
            if !self.coils.contains(&b) || self.c.chance(1, 10) {
                break;
            }
            b = self.write_bit_once();
        }
        self.coils.insert(b.clone());
        b
    }

    fn write_bit_once(&mut self) -> String {
        let dm_bits = self.p.omron.dm_bits;
        let bit = self.c.below(16);
        match self.c.weighted(&[5, 6, 2, 2, 1, u32::from(dm_bits), 1]) {
            0 => {
                let word = 100 + self.c.below(2);
                self.cio(word, Some(bit))
            }
            1 => format!("W{}.{bit:02}", self.work_word()),
            2 => {
                let h = if self.c.chance(1, 20) {
                    self.p.omron.holding - 1
                } else {
                    self.c.below(4)
                };
                format!("H{h}.{bit:02}")
            }
            3 => {
                let word = if self.c.chance(1, 20) {
                    self.p.omron.cio - 1
                } else {
                    2 + self.c.below(8)
                };
                self.cio(word, Some(bit))
            }
            4 => format!("A{}.{bit:02}", self.p.omron.aux_read_only + self.c.below(3)),
            5 => format!("D{}.{bit:02}", self.c.below(16)),
            // An input bit (W017: overwritten at the next input refresh).
            _ => {
                let word = self.c.below(2);
                self.cio(word, Some(bit))
            }
        }
    }

    /// One contact instruction joining the condition as `join`.
    pub(crate) fn contact(&mut self, join: Join) {
        if self.c.chance(1, 6) {
            self.compare_contact(join);
            return;
        }
        let negated = self.c.chance(1, 4);
        let group = Group::Contact(join, negated);
        let options = self.options(group);
        // `!` refreshes the word of an input bit: mostly read one then.
        let b = if options.contains('!') && self.c.chance(2, 3) {
            let (word, bit) = (self.c.below(2), self.c.below(16));
            self.cio(word, Some(bit))
        } else {
            self.read_bit()
        };
        self.op(&options, group, &[b]);
    }

    /// `LD|AND|OR` + relation + suffix, with word or constant operands (no indirect ones).
    pub(crate) fn compare_contact(&mut self, join: Join) {
        let Some(&(prefix, _)) = COMPARE_JOINS.iter().find(|j| j.1 == join) else {
            return;
        };
        let (rel, ..) = self.c.pick(&RELATIONS);
        let (suffix, double, ..) = self.c.pick(&COMPARE_SUFFIXES);
        let name = format!("{prefix}{rel}{suffix}");
        let Some(cc) = mnemonics::compare(&name) else {
            return;
        };
        let bang = if COMPARE_OPTIONS.immediate && !self.plain && self.c.chance(1, 8) {
            "!"
        } else {
            ""
        };
        let words = if double { 2 } else { 1 };
        let lhs = if bang == "!" && self.c.chance(2, 3) {
            self.io_word(true, words)
        } else {
            self.src(words, false)
        };
        let rhs = self.src(words, false);
        self.ins(bang, &name, Some(cc.code), &[lhs, rhs]);
    }

    /// A condition: a start contact and up to a few steps, nested blocks included; leaves one
    /// execution condition and no pending block.
    pub(crate) fn condition(&mut self, pending: u32, depth: u32) {
        self.contact(Join::Load);
        let steps = self.c.weighted(&[3, 4, 3, 2, 1]);
        for _ in 0..steps {
            self.combine(pending, depth);
        }
    }

    /// One step that combines into the current condition.
    fn combine(&mut self, pending: u32, depth: u32) {
        let nest = depth < 3 && pending < MAX_PENDING;
        let stack = depth < 2 && pending + 2 <= MAX_PENDING;
        match self.c.weighted(&[
            10,
            2,
            1,
            if nest { 3 } else { 0 },
            if stack { 1 } else { 0 },
        ]) {
            0 => {
                let join = if self.c.chance(1, 2) {
                    Join::And
                } else {
                    Join::Or
                };
                self.contact(join);
            }
            1 => self.op("", Group::Not, &[]),
            // UP/DOWN: not in a block program.
            2 if !self.block => {
                let falling = self.c.chance(1, 2);
                self.op("", Group::Edge(falling), &[]);
            }
            2 => self.op("", Group::Not, &[]),
            3 => {
                self.condition(pending + 1, depth + 1);
                self.join();
            }
            _ => {
                let k = self.c.range(2, 3.min(MAX_PENDING - pending));
                for j in 0..k {
                    self.condition(pending + 1 + j, depth + 1);
                }
                for _ in 0..k {
                    self.join();
                }
            }
        }
    }

    /// AND LD or OR LD.
    fn join(&mut self) {
        let j = if self.c.chance(1, 2) {
            Join::And
        } else {
            Join::Or
        };
        self.op("", Group::Block(j), &[]);
    }

    /// After an output: continue the circuit with a contact (and perhaps more, now that the
    /// rung is continued: an LD here would start a new circuit).
    pub(crate) fn continuation(&mut self) {
        match self.c.weighted(&[6, 1, 1]) {
            0 => {
                let join = if self.c.chance(2, 3) {
                    Join::And
                } else {
                    Join::Or
                };
                self.contact(join);
            }
            1 => self.op("", Group::Not, &[]),
            _ if self.block => self.op("", Group::Not, &[]),
            _ => {
                let falling = self.c.chance(1, 2);
                self.op("", Group::Edge(falling), &[]);
            }
        }
        if self.c.chance(1, 3) {
            self.combine(0, 1);
        }
    }

    /// A rung of contacts and coils: a condition, then one to four outputs with AND
    /// continuation and TR branch points between them.
    pub(crate) fn logic_rung(&mut self) {
        self.condition(0, 0);
        let n = self.c.range(1, 4);
        let mut saved: Vec<u32> = Vec::new();
        for k in 0..n {
            if k > 0 {
                match self
                    .c
                    .weighted(&[3, 3, if saved.is_empty() { 0 } else { 3 }])
                {
                    0 => {}
                    1 => self.continuation(),
                    _ => {
                        let tr = self.c.pick(&saved);
                        self.op("", Group::Contact(Join::Load, false), &[format!("TR{tr}")]);
                        if self.c.chance(1, 2) {
                            self.continuation();
                        }
                    }
                }
            }
            // OUT TRn is an OUT, which a block program may not hold.
            if !self.block && self.c.chance(1, 4) {
                let free: Vec<u32> = (0..16).filter(|t| self.trs & (1 << t) == 0).collect();
                if !free.is_empty() {
                    let tr = if self.c.chance(3, 4) {
                        free[0]
                    } else {
                        self.c.pick(&free)
                    };
                    self.trs |= 1 << tr;
                    saved.push(tr);
                    self.op("", Group::Out(false), &[format!("TR{tr}")]);
                    if self.c.chance(1, 2) {
                        self.continuation();
                    }
                }
            }
            self.bit_output();
        }
    }

    /// OUT, OUT NOT, SET, RSET (with their options) or DIFU/DIFD; in a block program SET or
    /// RSET only.
    pub(crate) fn bit_output(&mut self) {
        let out = u32::from(!self.block);
        let group = match self.c.weighted(&[10 * out, 3 * out, 4, 4, out, out]) {
            0 => Group::Out(false),
            1 => Group::Out(true),
            2 => Group::SetReset(true),
            3 => Group::SetReset(false),
            4 => Group::Differentiate(false),
            _ => Group::Differentiate(true),
        };
        let options = self.options(group);
        let b = self.refreshed_bit(&options);
        self.op(&options, group, &[b]);
    }

    /// A coil written with `options`: with `!`, mostly an output bit (whose word is refreshed).
    fn refreshed_bit(&mut self, options: &str) -> String {
        if options.contains('!') && self.c.chance(2, 3) {
            let (word, bit) = (100 + self.c.below(2), self.c.below(16));
            self.cio(word, Some(bit))
        } else {
            self.write_bit()
        }
    }

    /// KEEP(011): a set condition and a reset condition, each a whole block.
    pub(crate) fn keep_rung(&mut self) {
        self.condition(0, 0);
        self.condition(1, 1);
        let options = self.options(Group::Keep);
        let b = self.refreshed_bit(&options);
        self.op(&options, Group::Keep, &[b]);
    }

    /// DIFU(013)/DIFD(014) on a condition.
    pub(crate) fn differentiate_rung(&mut self) {
        self.condition(0, 0);
        let falling = self.c.chance(1, 2);
        let b = self.write_bit();
        self.op("", Group::Differentiate(falling), &[b]);
    }

    /// A rung that stacks 8 to 13 blocks before joining them (W040 above 8; E041 above 13
    /// is never generated).
    pub(crate) fn deep_rung(&mut self) {
        self.contact(Join::Load);
        let k = self.c.range(8, MAX_PENDING + 1);
        for _ in 0..k {
            self.contact(Join::Load);
            if self.c.chance(1, 2) {
                self.contact(Join::And);
            }
        }
        for _ in 0..k {
            self.join();
        }
        self.bit_output();
    }
}
