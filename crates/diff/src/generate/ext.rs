//! The instructions of s7-200-more §4–§7: tables (ATT, FIFO, LIFO, FND), ASCII and number
//! text (ATH, HTA, ITA/DTA/RTA, ITS/DTS/RTS, STI/STD/STR), strings (SLEN, SCPY, SSCPY, SCAT,
//! SFND, CFND), the clock (TODR, TODW, TODRX, TODWX), PID and the string compare contacts,
//! each only on a profile that has its family ([`CpuProfile::has`]).
//!
//! Operands mostly name the slots of [`super::ext_data`] (initialised in the data block), so
//! a table fills up and empties, a string is copied, cut and searched, a clock is set and read
//! back. Now and then an operand is a pointer, sits at the end of V (the run passes its area:
//! 0x0091) or anywhere else of its class, and counts, indexes and formats are sometimes out
//! of range (0x009B, illegal formats): the error paths and the flags (SM1.1, SM1.4, SM1.5,
//! SM1.7, SM4.3) are what a network after the box reads.
//!
//! [`CpuProfile::has`]: stljit_core::CpuProfile::has

use super::Gen;
use super::ext_data::{
    BUF_BASE, BUF_SLOTS, BUF_STRIDE, CLOCK_BASE, CLOCK_STRIDE, PID_BASE, STRING_BASE, STRING_SLOTS,
    STRING_STRIDE, TABLE_BASE, TABLE_SLOTS, TABLE_STRIDE,
};
use super::operands::Class;
use super::programs::{on, sm};
use stljit_core::instr_set::InstrSet;
use stljit_core::ir::{
    BoxOp, ClockOp, ExtBox, FindRel, Loc, NumType, Op, Operand, StackForm, StrArg, StrCompare,
};
use stljit_core::{Area, Width};

/// The families of this module, in the order of [`Gen::ext_box`]'s weights.
const FAMILIES: [InstrSet; 5] = [
    InstrSet::Tables,
    InstrSet::Ascii,
    InstrSet::Strings,
    InstrSet::Clock,
    InstrSet::Pid,
];

fn v(offset: u32) -> Operand {
    Operand::Mem(Loc {
        area: Area::V,
        offset,
    })
}

impl Gen<'_, '_> {
    /// Whether the profile has any instruction of this module.
    pub(crate) fn has_ext(&self) -> bool {
        FAMILIES.iter().any(|&f| self.p.has(f))
    }

    /// A network with one or two boxes of §4–§7 under a condition, then now and then a network
    /// that reads the flags they set (SM1.1, SM1.4, SM1.5, SM1.7) or SM4.3.
    pub(crate) fn ext_network(&mut self) {
        self.expr(1);
        if self.c.chance(1, 4) {
            self.touch_slot();
        }
        for _ in 0..self.c.weighted(&[0, 5, 1]) {
            let Some(b) = self.ext_box() else { break };
            self.emit(Op::Ext(Box::new(b)));
            if self.c.chance(1, 4) {
                self.emit(Op::AndEno);
            }
        }
        if self.c.chance(1, 3) {
            self.assign_out();
        }
        if self.c.chance(1, 3) {
            let (byte, bit) = self.c.pick(&[(1, 1), (1, 4), (1, 5), (1, 7), (4, 3)]);
            self.emit(Op::Load(on(sm(byte, bit))));
            self.assign_out();
        }
    }

    /// A plain move into or out of a slot, as programs clear a table's EC, set a string's
    /// length or read a loop output: the boxes' memory is shared with ordinary instructions
    /// (and the JIT's view of it with the runtime's).
    fn touch_slot(&mut self) {
        let (at, w) = match self.c.below(5) {
            0 => (
                TABLE_BASE + TABLE_STRIDE * self.c.below(TABLE_SLOTS) + 2,
                Width::Word,
            ),
            1 => (
                TABLE_BASE + TABLE_STRIDE * self.c.below(TABLE_SLOTS),
                Width::Word,
            ),
            2 => (
                STRING_BASE + STRING_STRIDE * self.c.below(STRING_SLOTS),
                Width::Byte,
            ),
            3 => (CLOCK_BASE + self.c.below(8), Width::Byte),
            _ => (PID_BASE + 8 * self.c.below(2), Width::DWord),
        };
        let (src, dst) = if self.c.chance(1, 2) {
            (v(at), self.value(w, Class::OUT))
        } else {
            let src = if self.c.chance(1, 2) {
                Operand::Const(self.c.below(30))
            } else {
                self.value(w, Class::IN)
            };
            (src, v(at))
        };
        self.emit(Op::Box(BoxOp::Move { width: w, src, dst }));
    }

    /// A string compare contact of form `form` (`LDS=`, `AS<>`, …), when the profile has strings.
    pub(crate) fn str_compare(&mut self, form: StackForm) -> Option<Op> {
        if !self.p.has(InstrSet::Strings) {
            return None;
        }
        // An unreadable string is fatal in a compare: keep such operands rare here.
        let lhs = self.string_in(true);
        let rhs = self.string_in(true);
        Some(Op::StrCompare(Box::new(StrCompare {
            form,
            ne: self.c.chance(1, 2),
            lhs,
            rhs,
        })))
    }

    /// One box of a family the profile has; `None` when it has none, or when every PID loop
    /// number is taken and a PID was picked.
    pub(crate) fn ext_box(&mut self) -> Option<ExtBox> {
        let weights = FAMILIES.map(|f| u32::from(self.p.has(f)));
        let w = [4, 3, 5, 2, 1];
        let weights: Vec<u32> = weights.iter().zip(w).map(|(h, w)| h * w).collect();
        if weights.iter().all(|&w| w == 0) {
            return None;
        }
        match self.c.weighted(&weights) {
            0 => Some(self.table_box()),
            1 => Some(self.ascii_box()),
            2 => Some(self.string_box()),
            3 => Some(self.clock_box()),
            _ => self.pid_box(),
        }
    }

    fn table_box(&mut self) -> ExtBox {
        match self.c.weighted(&[4, 3, 2, 3]) {
            0 => ExtBox::TableAdd {
                data: self.value(Width::Word, Class::IN),
                table: self.table(0),
            },
            1 | 2 => ExtBox::TableTake {
                lifo: self.c.chance(1, 2),
                table: self.table(0),
                data: self.value(
                    Width::Word,
                    Class {
                        aq: true,
                        ..Class::OUT
                    },
                ),
            },
            _ => {
                let rel = self
                    .c
                    .pick(&[FindRel::Eq, FindRel::Ne, FindRel::Lt, FindRel::Gt]);
                // FND names the EC word, one word above the TL the other three name.
                let table = self.table(2);
                let pattern = if self.c.chance(2, 3) {
                    Operand::Const(self.c.below(10))
                } else {
                    self.value(Width::Word, Class::IN)
                };
                ExtBox::TableFind {
                    rel,
                    table,
                    pattern,
                    index: self.value(Width::Word, Class::OUT),
                }
            }
        }
    }

    /// A table operand `skip` bytes into the table (0: TL, 2: EC): mostly a slot, sometimes a
    /// pointer, the end of V, or another word area (M, L, a timer or counter value).
    fn table(&mut self, skip: u32) -> Operand {
        match self.c.weighted(&[14, 1, 1, 1, 1]) {
            0 => {
                let at = TABLE_BASE + TABLE_STRIDE * self.c.below(TABLE_SLOTS);
                if !self.has_data(at) {
                    self.init_table(at);
                }
                v(at + skip)
            }
            1 => Operand::Indirect(self.pointer_cell()),
            2 => {
                let at = self.p.variable_memory - 2 * self.c.range(2, 8);
                if !self.has_data(at) {
                    self.init_table(at);
                }
                v(at + skip)
            }
            3 => Operand::Mem(self.direct(Width::Word, true)),
            _ => {
                let (area, n) = if self.c.chance(1, 2) {
                    (Area::TimerValue, self.timer_no())
                } else {
                    (Area::CounterValue, self.counter_no())
                };
                Operand::Mem(Loc {
                    area,
                    offset: 2 * u32::from(n),
                })
            }
        }
    }

    /// A run of bytes (ASCII buffer): mostly a buffer slot, sometimes a pointer, the end of V
    /// or any byte of the class.
    fn buffer(&mut self, out: bool) -> Operand {
        match self.c.weighted(&[12, 1, 2, 2]) {
            0 => {
                let at = BUF_BASE + BUF_STRIDE * self.c.below(BUF_SLOTS);
                if !self.has_data(at) {
                    self.init_buffer(at);
                }
                v(at)
            }
            1 => Operand::Indirect(self.pointer_cell()),
            2 => v(self.p.variable_memory - self.c.range(1, 12)),
            _ => Operand::Mem(self.direct(Width::Byte, out)),
        }
    }

    /// A string in memory: mostly a string slot, sometimes L memory, a pointer or the end of V
    /// (rarely so when `safe`: an unreadable string is fatal in a compare).
    fn string_mem(&mut self, safe: bool) -> Operand {
        let rare = u32::from(!safe);
        match self.c.weighted(&[14, 2, 2 * rare, 2 * rare, rare]) {
            0 => {
                let at = STRING_BASE + STRING_STRIDE * self.c.below(STRING_SLOTS);
                if !self.has_data(at) {
                    self.init_string(at);
                }
                v(at)
            }
            1 => Operand::Mem(Loc {
                area: Area::L,
                offset: self.c.below(40),
            }),
            2 => Operand::Indirect(self.pointer_cell()),
            3 => {
                let at = self.p.variable_memory - self.c.range(1, 12);
                if !self.has_data(at) {
                    self.init_string(at);
                }
                v(at)
            }
            // A string slot's neighbour: the buffers and tables read as strings.
            _ => v(STRING_BASE - 2 + self.c.below(STRING_SLOTS * STRING_STRIDE + 8)),
        }
    }

    /// A string input: a string in memory, or a constant one time in four.
    fn string_in(&mut self, safe: bool) -> StrArg {
        if self.c.chance(1, 4) {
            StrArg::Const(self.string_text())
        } else {
            StrArg::Mem(self.string_mem(safe))
        }
    }

    /// A byte input that is mostly a constant from `lo..=hi`, sometimes 0, sometimes anything.
    fn byte_arg(&mut self, lo: u32, hi: u32) -> Operand {
        match self.c.weighted(&[10, 1, 1, 2]) {
            0 => Operand::Const(self.c.range(lo, hi)),
            1 => Operand::Const(0),
            2 => Operand::Const(self.c.range(hi, 255)),
            _ => self.variable(Width::Byte),
        }
    }

    /// A format byte: `nnn` 0–5 and the comma bit (and for RTA/RTS a size 3–15) mostly, else
    /// `nnn` above 5, a size out of range or the upper bits of an integer format set.
    fn format(&mut self, real: bool) -> Operand {
        if self.c.chance(1, 8) {
            return self.variable(Width::Byte);
        }
        let comma = self.c.pick(&[0, 0, 8]);
        let nnn = if self.c.chance(1, 10) {
            self.c.range(6, 7)
        } else {
            self.c.range(0, 5)
        };
        let high = match (real, self.c.chance(1, 10)) {
            (true, false) => self.c.range(3, 15),
            (true, true) => self.c.pick(&[0, 1, 2]),
            (false, false) => 0,
            (false, true) => self.c.range(1, 15),
        };
        Operand::Const((high << 4) | comma | nnn)
    }

    fn ascii_box(&mut self) -> ExtBox {
        match self.c.weighted(&[2, 2, 4]) {
            0 => ExtBox::AsciiToHex {
                src: self.buffer(false),
                dst: self.buffer(true),
                len: self.byte_arg(1, 12),
            },
            1 => ExtBox::HexToAscii {
                src: self.buffer(false),
                dst: self.buffer(true),
                len: self.byte_arg(1, 12),
            },
            _ => self.num_to_text(false),
        }
    }

    /// ITA/DTA/RTA into a buffer, or ITS/DTS/RTS into a string.
    fn num_to_text(&mut self, string: bool) -> ExtBox {
        let ty = self
            .c
            .pick(&[NumType::Int, NumType::Int, NumType::DInt, NumType::Real]);
        let src = if ty == NumType::Real {
            self.value(Width::DWord, Class::REAL_IN)
        } else {
            self.value(ty.width(), Class::IN)
        };
        let dst = if string {
            self.string_mem(false)
        } else {
            self.buffer(true)
        };
        ExtBox::NumToText {
            ty,
            string,
            src,
            dst,
            fmt: self.format(ty == NumType::Real),
        }
    }

    fn string_box(&mut self) -> ExtBox {
        match self.c.weighted(&[3, 3, 2, 3, 2, 3, 3]) {
            0 => self.num_to_text(true),
            1 => {
                let ty = self.c.pick(&[NumType::Int, NumType::DInt, NumType::Real]);
                let src = self.string_in(false);
                let index = self.byte_arg(1, 4);
                let dst = if ty == NumType::Real {
                    self.value(Width::DWord, Class::REAL_OUT)
                } else {
                    self.value(ty.width(), Class::OUT)
                };
                ExtBox::TextToNum {
                    ty,
                    src,
                    index,
                    dst,
                }
            }
            2 => ExtBox::StrLen {
                src: self.string_in(false),
                dst: self.value(Width::Byte, Class::OUT),
            },
            3 => ExtBox::StrCopy {
                src: self.string_in(false),
                dst: self.string_mem(false),
            },
            4 => ExtBox::StrCat {
                src: self.string_in(false),
                dst: self.string_mem(false),
            },
            5 => ExtBox::SubStr {
                src: self.string_in(false),
                index: self.byte_arg(1, 8),
                count: self.byte_arg(1, 6),
                dst: self.string_mem(false),
            },
            _ => self.string_find(),
        }
    }

    /// SFND/CFND, its start position usually set just before (OUT is in/out).
    fn string_find(&mut self) -> ExtBox {
        let pos = self.value(Width::Byte, Class::OUT);
        if self.c.chance(3, 4) {
            let start = self.c.weighted(&[2, 6, 1, 1]) as u32;
            let start = if start == 3 {
                self.c.range(20, 255)
            } else {
                start
            };
            self.emit(Op::Box(BoxOp::Move {
                width: Width::Byte,
                src: Operand::Const(start),
                dst: pos,
            }));
        }
        ExtBox::StrFind {
            chars: self.c.chance(1, 2),
            src: self.string_in(false),
            pattern: self.string_in(false),
            pos,
        }
    }

    fn clock_box(&mut self) -> ExtBox {
        let op = self.c.pick(&[
            ClockOp::Read,
            ClockOp::Read,
            ClockOp::Write,
            ClockOp::ReadExt,
            ClockOp::WriteExt,
        ]);
        let extended = matches!(op, ClockOp::ReadExt | ClockOp::WriteExt);
        let write = matches!(op, ClockOp::Write | ClockOp::WriteExt);
        let buf = match self.c.weighted(&[12, 1, 1, 1]) {
            0 => {
                let at = CLOCK_BASE + CLOCK_STRIDE * u32::from(extended);
                // A write sometimes gets a fresh date just before it, as a program setting
                // the clock would.
                if !self.has_data(at) || (write && self.c.chance(1, 3)) {
                    self.init_clock(at, extended);
                }
                v(at)
            }
            1 => Operand::Indirect(self.pointer_cell()),
            2 => v(self.p.variable_memory - self.c.range(1, 20)),
            _ => Operand::Mem(self.direct(Width::Byte, !write)),
        };
        ExtBox::Clock { op, buf }
    }

    /// PID on a loop number no other PID of the program uses, its loop table in the PID slots;
    /// now and then the process variable is moved in first (a real cell, NaN among them).
    fn pid_box(&mut self) -> Option<ExtBox> {
        let free: Vec<u8> = (0..8).filter(|l| self.pid_loops & (1 << l) == 0).collect();
        if free.is_empty() {
            return None;
        }
        let lp = self.c.pick(&free);
        self.pid_loops |= 1 << lp;
        let at = PID_BASE + self.p.pid_table_bytes() * u32::from(lp);
        self.init_pid(at);
        if self.c.chance(1, 3) {
            let src = self.value(Width::DWord, Class::REAL_IN);
            self.emit(Op::Box(BoxOp::Move {
                width: Width::DWord,
                src,
                dst: v(at),
            }));
        }
        Some(ExtBox::Pid { table: v(at), lp })
    }
}
