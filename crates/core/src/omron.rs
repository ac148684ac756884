//! Omron CP memory as the IR sees it: the CP1H and CP1E profiles, the mapping of Omron word and
//! bit addresses onto image areas, and the positions of the condition flags and system pulses.
//!
//! **Mapping** (ARCHITECTURE.md, "Omron memory"): every Omron word is 16 bits stored big-endian
//! at byte offset `2w` of its area, so bit `bb` of a word (bit 00 = least significant) is bit
//! `bb % 8` of byte `2w + 1 - bb / 8`. The CIO input words are the `I` area and the CIO output
//! words the `Q` area of the profile (so the scan cycle's input and output copy and the
//! simulator's stimulus work unchanged); every other CIO word is area `Cio` at its own number.
//! Timer and counter PVs are the `TimerValue`/`CounterValue` words and their completion flags
//! the `TimerBit`/`CounterBit` bytes, as for S7. Double words keep Omron's order (the
//! lower-numbered word holds the low 16 bits, spec §1.6); only Omron ops read them.

use crate::area::Area;
use crate::instr_set::InstrSet;
use crate::interrupt::InterruptProfile;
use crate::ir::{BitLoc, Loc};
use crate::profile::{CpuProfile, Family, OmronAreas, ProfileId, TimerRange};

/// The Omron areas a word address can name, as the programmer writes them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WordArea {
    /// CIO, written without prefix (`100`, `0.01`) or with `CIO`.
    Cio,
    /// `W`.
    Work,
    /// `H`.
    Holding,
    /// `A`.
    Aux,
    /// `D`.
    Dm,
}

impl WordArea {
    /// Every word area.
    pub const ALL: [WordArea; 5] = [
        WordArea::Cio,
        WordArea::Work,
        WordArea::Holding,
        WordArea::Aux,
        WordArea::Dm,
    ];

    /// Number of words of this area on `profile`.
    pub fn words(self, profile: &CpuProfile) -> u32 {
        let a = &profile.omron;
        match self {
            WordArea::Cio => a.cio,
            WordArea::Work => a.work,
            WordArea::Holding => a.holding,
            WordArea::Aux => a.aux,
            WordArea::Dm => a.dm,
        }
    }
}

/// The image location of word `word` of `area`, or `None` outside the profile's range.
pub fn word_loc(profile: &CpuProfile, area: WordArea, word: u32) -> Option<Loc> {
    if word >= area.words(profile) {
        return None;
    }
    let a = &profile.omron;
    let loc = |area, w: u32| {
        Some(Loc {
            area,
            offset: 2 * w,
        })
    };
    match area {
        WordArea::Cio => {
            let in_words = profile.inputs / 2;
            let out_words = profile.outputs / 2;
            if (a.first_input_word..a.first_input_word + in_words).contains(&word) {
                loc(Area::I, word - a.first_input_word)
            } else if (a.first_output_word..a.first_output_word + out_words).contains(&word) {
                loc(Area::Q, word - a.first_output_word)
            } else {
                loc(Area::Cio, word)
            }
        }
        WordArea::Work => loc(Area::Work, word),
        WordArea::Holding => loc(Area::Holding, word),
        WordArea::Aux => loc(Area::Aux, word),
        WordArea::Dm => loc(Area::Dm, word),
    }
}

/// The inverse of [`word_loc`]: which Omron word a word-aligned location is.
pub fn word_of(profile: &CpuProfile, loc: Loc) -> Option<(WordArea, u32)> {
    if !loc.offset.is_multiple_of(2) {
        return None;
    }
    let w = loc.offset / 2;
    let a = &profile.omron;
    let (area, word) = match loc.area {
        Area::I => (WordArea::Cio, a.first_input_word + w),
        Area::Q => (WordArea::Cio, a.first_output_word + w),
        Area::Cio => (WordArea::Cio, w),
        Area::Work => (WordArea::Work, w),
        Area::Holding => (WordArea::Holding, w),
        Area::Aux => (WordArea::Aux, w),
        Area::Dm => (WordArea::Dm, w),
        _ => return None,
    };
    (word_loc(profile, area, word) == Some(loc)).then_some((area, word))
}

/// Bit `bit` (0 = least significant, 0..=15) of the word at `word`.
pub fn bit_of_word(word: Loc, bit: u8) -> BitLoc {
    BitLoc {
        area: word.area,
        byte: word.offset + 1 - u32::from(bit / 8),
        bit: bit % 8,
    }
}

/// The inverse of [`bit_of_word`]: the word location and the bit number (0..=15).
pub fn word_bit(bit: BitLoc) -> (Loc, u8) {
    let word = bit.byte & !1;
    let high = bit.byte.is_multiple_of(2);
    (
        Loc {
            area: bit.area,
            offset: word,
        },
        bit.bit + if high { 8 } else { 0 },
    )
}

/// The flat "I/O memory effective address" space of spec §1.5 (the CS/CJ map, U8): the first
/// effective word address of each region. Index registers hold these addresses; a bit's
/// address is `16 · word address + bit`, above every word address (so a bit address used as a
/// word operand is an access error).
pub const EA_MAP: [(EaRegion, u32); 7] = [
    (EaRegion::Word(WordArea::Aux), 0x0B000),
    (EaRegion::Word(WordArea::Cio), 0x0C000),
    (EaRegion::Word(WordArea::Holding), 0x0D800),
    (EaRegion::Word(WordArea::Work), 0x0DE00),
    (EaRegion::TimerPv, 0x0E000),
    (EaRegion::CounterPv, 0x0F000),
    (EaRegion::Word(WordArea::Dm), 0x10000),
];

/// A region of the effective-address space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EaRegion {
    /// A word area.
    Word(WordArea),
    /// The timer PVs.
    TimerPv,
    /// The counter PVs.
    CounterPv,
}

/// Words reserved for each region in the map (the distance to the next region; D to the end).
fn ea_span(i: usize) -> u32 {
    match EA_MAP.get(i + 1) {
        Some((_, next)) => next - EA_MAP[i].1,
        None => 0x8000,
    }
}

fn region_words(profile: &CpuProfile, region: EaRegion) -> u32 {
    match region {
        EaRegion::Word(a) => a.words(profile),
        EaRegion::TimerPv => u32::from(profile.timers),
        EaRegion::CounterPv => u32::from(profile.counters),
    }
}

/// The effective address of word `word` of `region`, `None` outside the profile.
pub fn effective_address(profile: &CpuProfile, region: EaRegion, word: u32) -> Option<u32> {
    let (i, &(_, base)) = EA_MAP.iter().enumerate().find(|(_, r)| r.0 == region)?;
    (word < region_words(profile, region) && word < ea_span(i)).then_some(base + word)
}

/// The image location of the word at effective address `ea`, `None` for a hole, memory the
/// profile does not have, or a bit address.
pub fn ea_loc(profile: &CpuProfile, ea: u32) -> Option<Loc> {
    let (_, &(region, base)) = EA_MAP
        .iter()
        .enumerate()
        .find(|(i, (_, base))| (*base..*base + ea_span(*i)).contains(&ea))?;
    let word = ea - base;
    if word >= region_words(profile, region) {
        return None;
    }
    match region {
        EaRegion::Word(a) => word_loc(profile, a, word),
        EaRegion::TimerPv => Some(Loc {
            area: Area::TimerValue,
            offset: 2 * word,
        }),
        EaRegion::CounterPv => Some(Loc {
            area: Area::CounterValue,
            offset: 2 * word,
        }),
    }
}

/// Bytes of the [`Area::Flags`] area: the system bits (bytes 0–3, [`SystemBit`]) and the
/// condition flags saved by CCS(282) (bytes 4–5, [`SAVED_FLAGS`]).
pub const FLAG_BYTES: u32 = 6;

/// Offset in [`Area::Flags`] of the condition flags CCS(282) saved (two bytes, the order of
/// bytes 0–1); the scan does not clear them.
pub const SAVED_FLAGS: u32 = 4;

/// The read-only system bits of [`Area::Flags`]: the condition flags first (their order is the
/// bit order of the runtime's flag word, bytes 0–1 little-endian), then the constants and the
/// clock pulses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SystemBit {
    /// `P_ER`: instruction processing error.
    Er,
    /// `P_CY`: carry / borrow.
    Cy,
    /// `P_GT`.
    Gt,
    /// `P_EQ`.
    Eq,
    /// `P_LT`.
    Lt,
    /// `P_N`: negative.
    N,
    /// `P_OF`: overflow.
    Of,
    /// `P_UF`: underflow.
    Uf,
    /// `P_GE`.
    Ge,
    /// `P_NE`.
    Ne,
    /// `P_LE`.
    Le,
    /// `P_AER`: access error.
    Aer,
    /// `P_On`: always 1.
    On,
    /// `P_Off`: always 0.
    Off,
    /// `P_0_02s`: 20 ms clock pulse.
    Pulse20ms,
    /// `P_0_1s`.
    Pulse100ms,
    /// `P_0_2s`.
    Pulse200ms,
    /// `P_1s`.
    Pulse1s,
    /// `P_1min`.
    Pulse1min,
}

impl SystemBit {
    /// Every system bit, in bit order.
    pub const ALL: [SystemBit; 19] = [
        SystemBit::Er,
        SystemBit::Cy,
        SystemBit::Gt,
        SystemBit::Eq,
        SystemBit::Lt,
        SystemBit::N,
        SystemBit::Of,
        SystemBit::Uf,
        SystemBit::Ge,
        SystemBit::Ne,
        SystemBit::Le,
        SystemBit::Aer,
        SystemBit::On,
        SystemBit::Off,
        SystemBit::Pulse20ms,
        SystemBit::Pulse100ms,
        SystemBit::Pulse200ms,
        SystemBit::Pulse1s,
        SystemBit::Pulse1min,
    ];

    /// The condition flags: the bits cleared at every task start (spec §1.8 rule 2).
    pub const CONDITION_FLAGS: u16 = (1 << 12) - 1;

    /// Its position: bit `i % 8` of byte `i / 8` of [`Area::Flags`].
    pub fn index(self) -> u32 {
        self as u32
    }

    /// The value of a constant system bit at `bit` (`P_On` 1, `P_Off` 0), which every scan
    /// writes before the program runs and no program can write (the verifier rejects writes to
    /// [`Area::Flags`]), so compiled code may take it as a constant.
    pub fn constant_at(bit: BitLoc) -> Option<bool> {
        [(SystemBit::On, true), (SystemBit::Off, false)]
            .into_iter()
            .find(|(b, _)| b.bit_loc() == bit)
            .map(|(_, v)| v)
    }

    /// Its location in the image.
    pub fn bit_loc(self) -> BitLoc {
        BitLoc {
            area: Area::Flags,
            byte: self.index() / 8,
            bit: (self.index() % 8) as u8,
        }
    }

    /// The clock pulses with their period in ms (50 % duty, ON half first, spec §2.12).
    pub const PULSES: [(SystemBit, u64); 5] = [
        (SystemBit::Pulse20ms, 20),
        (SystemBit::Pulse100ms, 100),
        (SystemBit::Pulse200ms, 200),
        (SystemBit::Pulse1s, 1000),
        (SystemBit::Pulse1min, 60_000),
    ];
}

/// `A200.11` (`P_First_Cycle`): ON during the first cycle only (spec §1.8).
pub const FIRST_CYCLE: (u32, u8) = (200, 11);

/// Where [`FIRST_CYCLE`] sits in an image of `layout`: the byte's image offset and the bit, or
/// `None` on a profile whose Aux area does not reach it.
pub fn first_cycle_bit(layout: &crate::layout::Layout) -> Option<(u32, u8)> {
    let (word, bit) = FIRST_CYCLE;
    let at = bit_of_word(
        Loc {
            area: Area::Aux,
            offset: 2 * word,
        },
        bit,
    );
    (at.byte < layout.area_size(Area::Aux)).then(|| (layout.base(Area::Aux) + at.byte, at.bit))
}

/// The temporary relay `TRn` (0..=15).
pub fn tr_bit(n: u8) -> BitLoc {
    BitLoc {
        area: Area::Tr,
        byte: u32::from(n / 8),
        bit: n % 8,
    }
}

const OMRON_TIMERS: &[TimerRange] = &[];

/// The CP1H (and CP1L-M), spec omron-cp.md §1.1; built-in I/O only: input words CIO 0–1, output
/// words CIO 100–101.
pub static CP1H: CpuProfile = CP1H_DATA;

/// The CP1H's data, which the CP1E profile starts from (a `static` cannot be copied).
const CP1H_DATA: CpuProfile = CpuProfile {
    id: ProfileId::Cp1h,
    family: Family::Omron,
    omron: OmronAreas {
        cio: 6144,
        first_input_word: 0,
        first_output_word: 100,
        work: 512,
        holding: 512,
        aux: 960,
        aux_read_only: 448,
        dm: 32768,
        max_jump: 255,
        dm_bits: false,
        // CP Programming Manual §2-1-3: up to 32 cyclic tasks, numbers 0–31.
        cyclic_tasks: 32,
        // "20K steps" [uncertain: K read as 1024].
        program_steps: 20 * 1024,
        // BPRG(096) N: N = 0–127 (CS/CJ instruction list) [uncertain].
        block_programs: 128,
    },
    model: "CP1H",
    inputs: 4,
    outputs: 4,
    bit_memory: 0,
    sequence_relays: 0,
    special_memory: 0,
    special_memory_read_only: 0,
    variable_memory: 0,
    // Not an Omron area: the front end's private words (the FOR/NEXT loop counters, then the
    // saved gate of an interlock around a step area), one frame per call level like S7's L
    // memory; no Omron operand can name them.
    local_frame: 32,
    analog_inputs: 0,
    analog_outputs: 0,
    timers: 4096,
    counters: 4096,
    high_speed_counters: 0,
    accumulators: 0,
    max_edges: 8192,
    max_label: 1023,
    max_subroutine: 255,
    // SBS nesting: the image has `ISR_FRAME - 1` call frames below the main program (CS/CJ
    // allow 16 levels; the deeper ones are not modelled, a call beyond is skipped as on S7).
    max_call_depth: 8,
    max_for_depth: 15,
    timer_table: OMRON_TIMERS,
    lacks: InstrSet::ALL,
    interrupts: &InterruptProfile::NONE,
    hsc: &crate::hsc::HscProfile::NONE,
    pulse: &crate::pulse::PulseProfile::NONE,
    clock: crate::profile::RealTimeClock::Absent,
};

/// The CP1E (E type), with the smaller ranges of spec §1.1 (U9: the per-model table is
/// [uncertain]; these are the listed defaults).
pub static CP1E: CpuProfile = CpuProfile {
    id: ProfileId::Cp1e,
    omron: OmronAreas {
        work: 100,
        holding: 50,
        aux: 754,
        dm: 2048,
        // [uncertain] U9: the CP1E manuals allow `Dn.bb`.
        dm_bits: true,
        // [uncertain]: one cyclic task.
        cyclic_tasks: 1,
        // The N type's 8K steps (the E type has 2K) [uncertain].
        program_steps: 8 * 1024,
        ..CP1H_DATA.omron
    },
    model: "CP1E",
    timers: 256,
    counters: 256,
    max_edges: 4096,
    max_subroutine: 127,
    ..CP1H_DATA
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cio_routes_io_words_to_i_and_q() {
        let p = &CP1H;
        assert_eq!(
            word_loc(p, WordArea::Cio, 1),
            Some(Loc {
                area: Area::I,
                offset: 2
            })
        );
        assert_eq!(
            word_loc(p, WordArea::Cio, 101),
            Some(Loc {
                area: Area::Q,
                offset: 2
            })
        );
        assert_eq!(
            word_loc(p, WordArea::Cio, 102),
            Some(Loc {
                area: Area::Cio,
                offset: 204
            })
        );
        assert_eq!(word_loc(p, WordArea::Cio, 6144), None);
        assert_eq!(
            word_loc(p, WordArea::Dm, 32767).map(|l| l.offset),
            Some(65534)
        );
        for area in WordArea::ALL {
            for w in [0, 1, 2, 99, 100, 101, 102, 511] {
                if let Some(l) = word_loc(p, area, w) {
                    assert_eq!(word_of(p, l), Some((area, w)), "{area:?} {w}");
                }
            }
        }
    }

    #[test]
    fn bit_00_is_the_least_significant_bit_of_the_big_endian_word() {
        let w = Loc {
            area: Area::Work,
            offset: 10,
        };
        // Bit 00 is in the low byte, which big-endian storage puts second.
        assert_eq!(bit_of_word(w, 0).byte, 11);
        assert_eq!(bit_of_word(w, 7).bit, 7);
        assert_eq!(bit_of_word(w, 8).byte, 10);
        assert_eq!(bit_of_word(w, 15).bit, 7);
        for b in 0..16 {
            assert_eq!(word_bit(bit_of_word(w, b)), (w, b));
        }
    }

    #[test]
    fn effective_addresses_follow_the_cs_cj_map() {
        let p = &CP1H;
        // Spec §1.5: W500 is EA 0DFF4 and the word after W511 is T0000's PV.
        assert_eq!(
            effective_address(p, EaRegion::Word(WordArea::Work), 500),
            Some(0xDFF4)
        );
        assert_eq!(
            ea_loc(p, 0xDE00 + 512),
            Some(Loc {
                area: Area::TimerValue,
                offset: 0
            })
        );
        assert_eq!(
            ea_loc(p, 0x10000 + 400),
            Some(Loc {
                area: Area::Dm,
                offset: 800
            })
        );
        // CIO 100 is the first output word: area Q.
        assert_eq!(ea_loc(p, 0xC000 + 100).map(|l| l.area), Some(Area::Q));
        // A hole (A960.. below CIO) and bit addresses are no words.
        assert_eq!(ea_loc(p, 0xB000 + 960), None);
        assert_eq!(ea_loc(p, 0x10000 * 16), None);
        for (region, _) in EA_MAP {
            let ea = effective_address(p, region, 3).unwrap();
            assert!(ea_loc(p, ea).is_some());
        }
    }

    #[test]
    fn condition_flags_fill_the_first_twelve_bits() {
        assert_eq!(SystemBit::Aer.index(), 11);
        assert_eq!(SystemBit::CONDITION_FLAGS.count_ones(), 12);
        assert!(SystemBit::ALL.iter().all(|b| b.index() / 8 < FLAG_BYTES));
        for (i, b) in SystemBit::ALL.iter().enumerate() {
            assert_eq!(b.index() as usize, i);
        }
    }
}
