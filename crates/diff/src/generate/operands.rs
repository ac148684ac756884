//! Operands per operand class (spec §4.0), weighted towards a few hot regions so that
//! instructions read what others wrote.
//!
//! V memory is split by purpose so that data flows stay meaningful: `VB0..64` is general data,
//! `VD100..132` holds reals, `VW200..232` loop counters and FOR indices, `VD300..332` pointers.
//! Everything else is still reachable (uniform picks and area-end picks) so stray writes happen,
//! just not all the time.

use super::Gen;
use stljit_core::ir::{BitLoc, Loc, Operand};
use stljit_core::{Area, Width};

/// First byte of the real-valued cells.
pub(crate) const REAL_BASE: u32 = 100;
/// Number of real cells (dwords).
pub(crate) const REAL_CELLS: u32 = 8;
/// First byte of the loop-counter and FOR-index words.
pub(crate) const LOOP_BASE: u32 = 200;
/// Number of loop-counter words: groups of four, backward loops use groups 0..4 by nesting depth,
/// FOR indices groups 4..12 by FOR depth.
pub(crate) const LOOP_CELLS: u32 = 48;
/// First byte of the pointer cells in V.
pub(crate) const PTR_BASE: u32 = 300;
/// Number of pointer cells in V.
pub(crate) const PTR_CELLS: u32 = 8;
/// First byte of the pointer cells in each L frame.
pub(crate) const L_PTR_BASE: u32 = 48;

/// What an operand may be, beyond its width and direction.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Class {
    /// Written (no constants, no read-only areas).
    pub(crate) out: bool,
    /// A real operand (no HC, no `&`; constants are finite floats).
    pub(crate) real: bool,
    /// MOVW destination: AQW allowed.
    pub(crate) aq: bool,
    /// MOVD source: `&` allowed.
    pub(crate) addr: bool,
    /// Constants not allowed even for an input (block-move sources, in-place operands).
    pub(crate) no_const: bool,
}

impl Class {
    /// An input operand.
    pub(crate) const IN: Class = Class {
        out: false,
        real: false,
        aq: false,
        addr: false,
        no_const: false,
    };
    /// An output operand.
    pub(crate) const OUT: Class = Class {
        out: true,
        real: false,
        aq: false,
        addr: false,
        no_const: true,
    };
    /// A real input.
    pub(crate) const REAL_IN: Class = Class {
        out: false,
        real: true,
        aq: false,
        addr: false,
        no_const: false,
    };
    /// A real output.
    pub(crate) const REAL_OUT: Class = Class {
        out: true,
        real: true,
        aq: false,
        addr: false,
        no_const: true,
    };
}

/// The byte-addressed areas a direct operand is drawn from, each with its weight.
const BYTE_AREAS: [(Area, u32); 7] = [
    (Area::I, 2),
    (Area::Q, 3),
    (Area::M, 5),
    (Area::S, 1),
    (Area::SM, 1),
    (Area::V, 8),
    (Area::L, 3),
];

/// Interesting finite reals (bit patterns); NaN and infinities arise at run time instead, because
/// a constant must print as a real literal.
const REALS: [f32; 16] = [
    0.0, 1.0, -1.0, 0.5, -2.5, 2.5, 3.5, 100.0, -0.001, 1.0e10, -3.0e38, 3.0e38, 1.0e-20, 7.25,
    1234.5, 65536.0,
];

impl Gen<'_, '_> {
    /// A byte offset for a `w`-wide value in an area of `size` bytes, from `lo`: mostly in a hot
    /// window, sometimes at the very end, sometimes anywhere.
    fn offset(&mut self, lo: u32, size: u32, w: u32, hot: u32) -> u32 {
        let last = size.saturating_sub(w);
        if last <= lo {
            return lo;
        }
        match self.c.weighted(&[14, 2, 3]) {
            0 => lo + self.c.below(hot.min(last - lo + 1)),
            1 => last - self.c.below(4.min(last - lo + 1)),
            _ => self.c.range(lo, last),
        }
    }

    /// An offset inside a byte-addressable area for a `w`-byte value; `out` keeps SM writes out
    /// of the read-only system bytes.
    pub(crate) fn area_offset(&mut self, area: Area, w: u32, out: bool) -> u32 {
        let size = self.p.area_size(area);
        match area {
            Area::SM if out => {
                let lo = self.p.special_memory_read_only;
                self.offset(lo, size, w, 12)
            }
            // SMB0 (system bits) and SMB1 (arithmetic flags) are what real programs read.
            Area::SM => match self.c.weighted(&[3, 3, 2]) {
                0 => 0,
                1 => 1,
                _ => self.offset(0, size, w, 40),
            },
            Area::V => self.offset(0, size, w, 64),
            Area::L => self.offset(0, size, w, 16),
            Area::AI | Area::AQ => self.offset(0, size, w, size) & !1,
            _ => self.offset(0, size, w, 8),
        }
    }

    /// A timer number, preferring a few so that instructions share timers.
    pub(crate) fn timer_no(&mut self) -> u16 {
        let n = self.p.timers;
        match self.c.weighted(&[3, 4, 4, 2]) {
            // Numbers already declared, so reads see a running timer.
            0 if !self.timers.is_empty() => {
                let keys: Vec<u16> = self.timers.keys().copied().collect();
                self.c.pick(&keys)
            }
            // One pick per resolution band of the A5 table (1, 10, 100 ms); on the S7-200 these
            // fall in TONR bands, the uniform pick reaches the TON/TOF ones.
            1 => self.c.range(0, 1) as u16,
            2 => self.c.range(2, 19) as u16,
            _ => self.c.below(u32::from(n)) as u16,
        }
    }

    /// A counter number, preferring a few.
    pub(crate) fn counter_no(&mut self) -> u16 {
        let n = u32::from(self.p.counters);
        if self.c.chance(3, 4) {
            self.c.below(n.min(6)) as u16
        } else {
            self.c.below(n) as u16
        }
    }

    /// A bit an instruction reads (class BIT).
    pub(crate) fn bit_in(&mut self) -> BitLoc {
        self.bit_read(true)
    }

    /// A bit an instruction reads; `tc` allows timer and counter bits (SHRB's DATA does not).
    pub(crate) fn bit_read(&mut self, tc: bool) -> BitLoc {
        let tc = u32::from(tc) * 2;
        match self.c.weighted(&[6, 3, 5, 1, 4, 3, 1, tc, tc]) {
            0 => self.plain_bit(Area::I, false),
            1 => self.plain_bit(Area::Q, false),
            2 => self.plain_bit(Area::M, false),
            3 => self.plain_bit(Area::S, false),
            4 => {
                // SM0.x clocks and first-scan bits, SM1.x arithmetic flags.
                let byte = self.c.weighted(&[4, 4, 1]) as u32;
                let byte = if byte == 2 {
                    self.area_offset(Area::SM, 1, false)
                } else {
                    byte
                };
                BitLoc {
                    area: Area::SM,
                    byte,
                    bit: self.c.below(8) as u8,
                }
            }
            5 => self.plain_bit(Area::V, false),
            6 => self.plain_bit(Area::L, false),
            7 => self.timer_bit(),
            _ => self.counter_bit(),
        }
    }

    /// A bit an instruction writes: no SM system bytes. `tc` allows timer and counter bits.
    pub(crate) fn bit_out(&mut self, tc: bool) -> BitLoc {
        let w: &[u32] = if tc {
            &[1, 6, 5, 1, 1, 3, 1, 1, 1]
        } else {
            &[1, 6, 5, 1, 1, 3, 1, 0, 0]
        };
        match self.c.weighted(w) {
            0 => self.plain_bit(Area::I, true),
            1 => self.plain_bit(Area::Q, true),
            2 => self.plain_bit(Area::M, true),
            3 => self.plain_bit(Area::S, true),
            4 => self.plain_bit(Area::SM, true),
            5 => self.plain_bit(Area::V, true),
            6 => self.plain_bit(Area::L, true),
            7 => self.timer_bit(),
            _ => self.counter_bit(),
        }
    }

    /// A bit of a byte-addressable area.
    pub(crate) fn plain_bit(&mut self, area: Area, out: bool) -> BitLoc {
        BitLoc {
            area,
            byte: self.area_offset(area, 1, out),
            bit: self.c.below(8) as u8,
        }
    }

    fn timer_bit(&mut self) -> BitLoc {
        BitLoc {
            area: Area::TimerBit,
            byte: u32::from(self.timer_no()),
            bit: 0,
        }
    }

    fn counter_bit(&mut self) -> BitLoc {
        BitLoc {
            area: Area::CounterBit,
            byte: u32::from(self.counter_no()),
            bit: 0,
        }
    }

    /// A constant of width `w`, biased to boundaries.
    pub(crate) fn constant(&mut self, w: Width, real: bool) -> u32 {
        if real {
            let f = if self.c.chance(3, 4) {
                self.c.pick(&REALS)
            } else {
                self.c.range(0, 2000) as f32 / 8.0 - 100.0
            };
            return f.to_bits();
        }
        let m = w.mask();
        let sign = 1u32 << (w.bits() - 1);
        let v = match self.c.weighted(&[8, 4, 2, 2, 2, 2, 3]) {
            0 => self.c.below(20),
            1 => self.c.range(20, 300),
            2 => 0,
            3 => m,
            4 => sign - 1,
            5 => sign,
            _ => self.c.bits(),
        };
        v & m
    }

    /// A pointer cell: where a `*` operand reads its pointer.
    pub(crate) fn pointer_cell(&mut self) -> Loc {
        match self.c.weighted(&[6, 2, 2]) {
            0 => Loc {
                area: Area::V,
                offset: PTR_BASE + 4 * self.c.below(PTR_CELLS),
            },
            1 => Loc {
                area: Area::L,
                offset: L_PTR_BASE + 4 * self.c.below(4),
            },
            // AC1..AC3: the classic S7-200 does not take AC0 as a pointer.
            _ => Loc {
                area: Area::AC,
                offset: 4 * self
                    .c
                    .range(1, u32::from(self.p.accumulators).saturating_sub(1)),
            },
        }
    }

    /// A real cell (a dword in the real region).
    pub(crate) fn real_cell(&mut self) -> Loc {
        Loc {
            area: Area::V,
            offset: REAL_BASE + 4 * self.c.below(REAL_CELLS),
        }
    }

    /// A loop-counter word of `group`: nested loops use different groups, so an inner loop does
    /// not reset the outer one's counter.
    pub(crate) fn loop_cell(&mut self, group: u32) -> Loc {
        let group = group % (LOOP_CELLS / 4);
        Loc {
            area: Area::V,
            offset: LOOP_BASE + 2 * (4 * group + self.c.below(4)),
        }
    }

    /// An accumulator as a value of width `w` (its low bytes).
    fn accumulator(&mut self, w: Width) -> Loc {
        let n = self.c.below(u32::from(self.p.accumulators));
        Loc {
            area: Area::AC,
            offset: 4 * n + 4 - w.bytes(),
        }
    }

    /// A value operand of width `w` and class `k`.
    pub(crate) fn value(&mut self, w: Width, k: Class) -> Operand {
        if k.real {
            return self.real_value(k);
        }
        let can_const = !k.out && !k.no_const;
        let pointers = !self.cfg.plain;
        // Weights: direct byte area, AC, T/C value, AI, AQ, HC, indirect, constant, address-of.
        let weights = [
            12,
            2,
            u32::from(w == Width::Word) * 2,
            u32::from(w == Width::Word && !k.out),
            u32::from(w == Width::Word && k.aq),
            u32::from(w == Width::DWord && !k.out),
            u32::from(pointers) * 2,
            if can_const { 6 } else { 0 },
            u32::from(k.addr && pointers) * 4,
        ];
        match self.c.weighted(&weights) {
            0 => Operand::Mem(self.direct(w, k.out)),
            1 => Operand::Mem(self.accumulator(w)),
            2 => {
                if self.c.chance(1, 2) {
                    let n = u32::from(self.timer_no());
                    Operand::Mem(Loc {
                        area: Area::TimerValue,
                        offset: 2 * n,
                    })
                } else {
                    let n = u32::from(self.counter_no());
                    Operand::Mem(Loc {
                        area: Area::CounterValue,
                        offset: 2 * n,
                    })
                }
            }
            3 => Operand::Mem(Loc {
                area: Area::AI,
                offset: self.area_offset(Area::AI, 2, false),
            }),
            4 => Operand::Mem(Loc {
                area: Area::AQ,
                offset: self.area_offset(Area::AQ, 2, true),
            }),
            5 => Operand::Mem(Loc {
                area: Area::HC,
                offset: 4 * self.c.below(u32::from(self.p.high_speed_counters)),
            }),
            6 => Operand::Indirect(self.pointer_cell()),
            7 => Operand::Const(self.constant(w, false)),
            _ => Operand::AddressOf(self.address_target()),
        }
    }

    /// A direct operand in a byte-addressable area.
    pub(crate) fn direct(&mut self, w: Width, out: bool) -> Loc {
        let area = BYTE_AREAS[self.c.weighted(&BYTE_AREAS.map(|(_, weight)| weight))].0;
        // Most V traffic stays in the general region; pointer and real cells are still reachable.
        Loc {
            area,
            offset: self.area_offset(area, w.bytes(), out),
        }
    }

    fn real_value(&mut self, k: Class) -> Operand {
        let can_const = !k.out && !k.no_const;
        match self.c.weighted(&[
            10,
            if can_const { 4 } else { 0 },
            2,
            u32::from(!self.cfg.plain),
            1,
        ]) {
            0 => Operand::Mem(self.real_cell()),
            1 => Operand::Const(self.constant(Width::DWord, true)),
            2 => Operand::Mem(self.accumulator(Width::DWord)),
            3 => Operand::Indirect(self.pointer_cell()),
            _ => Operand::Mem(self.direct(Width::DWord, k.out)),
        }
    }

    /// What `&` may point at (spec §1.6): I, Q, M, S, SM, V, AI, AQ and timer/counter values.
    pub(crate) fn address_target(&mut self) -> Loc {
        let area = [
            Area::V,
            Area::M,
            Area::I,
            Area::Q,
            Area::S,
            Area::SM,
            Area::AI,
            Area::AQ,
            Area::TimerValue,
            Area::CounterValue,
        ][self.c.weighted(&[10, 3, 1, 2, 1, 1, 1, 1, 2, 1])];
        let offset = match area {
            Area::TimerValue => 2 * u32::from(self.timer_no()),
            Area::CounterValue => 2 * u32::from(self.counter_no()),
            // Out-of-range dereferences come from pointers near the area end being stepped.
            _ => self.area_offset(area, 1, false),
        };
        Loc { area, offset }
    }

    /// A byte count operand (class BYTE_IN): a constant up to `max`, or a variable byte.
    pub(crate) fn count(&mut self, max: u32) -> Operand {
        if self.c.chance(5, 6) {
            Operand::Const(self.c.range(1.min(max), max.min(255)))
        } else {
            self.variable(Width::Byte)
        }
    }

    /// A variable input (no constant): counts read at run time, which may be out of range.
    pub(crate) fn variable(&mut self, w: Width) -> Operand {
        self.value(
            w,
            Class {
                no_const: true,
                ..Class::IN
            },
        )
    }
}
