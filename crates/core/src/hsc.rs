//! High-speed counters as data (s7-200-more.md §8): each CPU's counters with their inputs, the
//! modes each accepts and the SM registers of their control and status, and what a mode
//! means (which inputs it uses, how a count step finds its direction).
//!
//! Nothing here runs: the counting model is `stljit_runtime::hsc`, which reads these tables,
//! the S7 front end checks HDEF/HSC operands against [`HscProfile`], and the events the
//! counters raise are in the event table ([`crate::interrupt::EVENTS`], source
//! [`EventSource::HighSpeedCounter`](crate::interrupt::EventSource::HighSpeedCounter)).

/// An input bit: `(byte, bit)` of the I area (`I1.0` is `(1, 0)`).
pub type InputBit = (u32, u8);

/// Which event of a counter (§8.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HscEvent {
    /// CV reached PV by a count step (every mode).
    CvEqPv,
    /// A count step in the other direction (modes 3–11).
    Direction,
    /// The reset input became active (modes with a reset input).
    Reset,
}

/// The highest mode number (§8.2: 0–12).
pub const MAX_MODE: u8 = 12;

/// Mode 12: the counter counts the pulses of a pulse output (§8.2, §9.3).
pub const PULSE_MODE: u8 = 12;

/// What a mode is made of (§8.2: three modes per counter type, the second adding a reset
/// input and the third a reset and a start input; mode 12 counts pulse-output pulses).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mode(pub u8);

impl Mode {
    /// Single phase with the direction from the control byte (modes 0–2) or from the pulse
    /// output (12): every step goes in the counter's own direction.
    pub fn internal_direction(self) -> bool {
        self.0 <= 2 || self.0 == PULSE_MODE
    }

    /// A/B quadrature (modes 9–11): the control byte's rate bit chooses 1x or 4x.
    pub fn quadrature(self) -> bool {
        (9..=11).contains(&self.0)
    }

    /// Uses the counter's reset input (modes 1, 2, 4, 5, 7, 8, 10, 11).
    pub fn has_reset(self) -> bool {
        self.0 < PULSE_MODE && !self.0.is_multiple_of(3)
    }

    /// Uses the counter's start input (modes 2, 5, 8, 11).
    pub fn has_start(self) -> bool {
        self.0 < PULSE_MODE && self.0 % 3 == 2
    }

    /// Uses the second counting input (direction, down clock or B: modes 3–11).
    pub fn has_second_input(self) -> bool {
        (3..PULSE_MODE).contains(&self.0)
    }

    /// Raises "direction changed" (§8.5: all modes except 0, 1 and 2; 12 has no inputs).
    pub fn raises_direction(self) -> bool {
        self.has_second_input()
    }
}

/// One high-speed counter of a CPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HscInfo {
    /// The counter's number (`HSC n`, `HCn`).
    pub number: u8,
    /// Bit `m`: the counter accepts mode `m`.
    pub modes: u16,
    /// The inputs in the manual's order: clock/up/A, direction/down/B, reset, start.
    pub inputs: [Option<InputBit>; 4],
    /// SMB of its status byte; the control byte is the next one, the new CV (SMD) starts
    /// 2 bytes after it and the new PV (SMD) 6 bytes after it (§8.1: SMB36, SMB37, SMD38,
    /// SMD42 for HSC0).
    pub status_smb: u32,
}

impl HscInfo {
    /// Whether the counter accepts `mode`.
    pub fn has_mode(&self, mode: u8) -> bool {
        mode <= MAX_MODE && self.modes & (1 << mode) != 0
    }

    /// The control byte's SMB (§8.1).
    pub fn control_smb(&self) -> u32 {
        self.status_smb + 1
    }

    /// The first SMB of the new current value (big-endian DINT).
    pub fn new_cv_smb(&self) -> u32 {
        self.status_smb + 2
    }

    /// The first SMB of the new preset (big-endian DINT).
    pub fn new_pv_smb(&self) -> u32 {
        self.status_smb + 6
    }

    /// The reset input, if `mode` uses one.
    pub fn reset_input(&self, mode: Mode) -> Option<InputBit> {
        self.inputs[2].filter(|_| mode.has_reset())
    }

    /// The start input, if `mode` uses one.
    pub fn start_input(&self, mode: Mode) -> Option<InputBit> {
        self.inputs[3].filter(|_| mode.has_start())
    }

    /// Every input the counter occupies in `mode` (§8.3: they cannot raise input-edge events
    /// nor belong to another counter).
    pub fn inputs_used(&self, mode: Mode) -> impl Iterator<Item = InputBit> {
        let counting = mode.0 != PULSE_MODE;
        [
            self.inputs[0].filter(|_| counting),
            self.inputs[1].filter(|_| mode.has_second_input()),
            self.reset_input(mode),
            self.start_input(mode),
        ]
        .into_iter()
        .flatten()
    }
}

/// The high-speed counters of a CPU, by number (a counter's index in `counters` is its
/// number; numbers the CPU lacks are `None`).
#[derive(Debug)]
pub struct HscProfile {
    /// Entry `n`: HSC `n`, if the CPU has it.
    pub counters: &'static [Option<HscInfo>],
}

impl HscProfile {
    /// No high-speed counters (the Omron profiles).
    pub const NONE: HscProfile = HscProfile { counters: &[] };

    /// Counter `n`, if the CPU has it.
    pub fn get(&self, n: u8) -> Option<&HscInfo> {
        self.counters.get(usize::from(n)).and_then(Option::as_ref)
    }

    /// The CPU's counters, ascending.
    pub fn iter(&self) -> impl Iterator<Item = &HscInfo> {
        self.counters.iter().flatten()
    }
}

/// Modes as a bit set.
const fn modes(list: &[u8]) -> u16 {
    let mut m = 0;
    let mut i = 0;
    while i < list.len() {
        m |= 1 << list[i];
        i += 1;
    }
    m
}

const fn i(byte: u32, bit: u8) -> Option<InputBit> {
    Some((byte, bit))
}

const fn hsc(number: u8, modes: u16, inputs: [Option<InputBit>; 4], status_smb: u32) -> HscInfo {
    HscInfo {
        number,
        modes,
        inputs,
        status_smb,
    }
}

/// The S7-200 CPU 224/226 table (§8.2 [S7-200 manual, recalled, §13 H1]).
const S7_200_HSC: [Option<HscInfo>; 6] = [
    Some(hsc(
        0,
        modes(&[0, 1, 3, 4, 6, 7, 9, 10, 12]),
        [i(0, 0), i(0, 1), i(0, 2), None],
        36,
    )),
    Some(hsc(
        1,
        modes(&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]),
        [i(0, 6), i(0, 7), i(1, 0), i(1, 1)],
        46,
    )),
    Some(hsc(
        2,
        modes(&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]),
        [i(1, 2), i(1, 3), i(1, 4), i(1, 5)],
        56,
    )),
    Some(hsc(3, modes(&[0, 12]), [i(0, 1), None, None, None], 136)),
    Some(hsc(
        4,
        modes(&[0, 1, 3, 4, 6, 7, 9, 10]),
        [i(0, 3), i(0, 4), i(0, 5), None],
        146,
    )),
    Some(hsc(5, modes(&[0]), [i(0, 4), None, None, None], 156)),
];

/// The S7-200's counters (HSC0–HSC5).
pub static S7_200_COUNTERS: HscProfile = HscProfile {
    counters: &S7_200_HSC,
};

/// The A5: HC0 and HC1 exist [seed]; their inputs and registers are not documented, so they
/// are HSC0 and HSC1 of the S7-200 table (§8.2 [uncertain, §13 H3]).
pub static A5_COUNTERS: HscProfile = HscProfile {
    counters: &[S7_200_HSC[0], S7_200_HSC[1]],
};

/// The S7-200 SMART (§8.2 [SMART manual, recalled, §13 H2]): HSC0 (I0.0, I0.1, reset I0.4),
/// HSC1 (I0.1), HSC2 (I0.2, I0.3, reset I0.5), HSC3 (I0.3); the two-input counters take modes
/// 0, 1, 3, 4, 6, 7, 9, 10 (no start input, no mode 12), the one-input counters mode 0. The
/// HSC4/HSC5 of some SMART CPUs are not modelled [uncertain, §0.2].
pub static SMART_COUNTERS: HscProfile = HscProfile {
    counters: &[
        Some(hsc(
            0,
            modes(&[0, 1, 3, 4, 6, 7, 9, 10]),
            [i(0, 0), i(0, 1), i(0, 4), None],
            36,
        )),
        Some(hsc(1, modes(&[0]), [i(0, 1), None, None, None], 46)),
        Some(hsc(
            2,
            modes(&[0, 1, 3, 4, 6, 7, 9, 10]),
            [i(0, 2), i(0, 3), i(0, 5), None],
            56,
        )),
        Some(hsc(3, modes(&[0]), [i(0, 3), None, None, None], 136)),
    ],
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mode_structure() {
        let reset: Vec<u8> = (0..=MAX_MODE).filter(|&m| Mode(m).has_reset()).collect();
        assert_eq!(reset, [1, 2, 4, 5, 7, 8, 10, 11]);
        let start: Vec<u8> = (0..=MAX_MODE).filter(|&m| Mode(m).has_start()).collect();
        assert_eq!(start, [2, 5, 8, 11]);
        let dir: Vec<u8> = (0..=MAX_MODE)
            .filter(|&m| Mode(m).raises_direction())
            .collect();
        assert_eq!(dir, (3..=11).collect::<Vec<u8>>());
    }

    #[test]
    fn tables_are_by_number_and_registers_follow_the_manual() {
        for p in [&S7_200_COUNTERS, &A5_COUNTERS, &SMART_COUNTERS] {
            for (n, c) in p.counters.iter().enumerate() {
                let c = c.expect("no holes");
                assert_eq!(usize::from(c.number), n);
                // A mode with a reset or start input needs the input.
                for m in 0..=MAX_MODE {
                    if c.has_mode(m) {
                        assert!(!Mode(m).has_reset() || c.inputs[2].is_some(), "{n} {m}");
                        assert!(!Mode(m).has_start() || c.inputs[3].is_some(), "{n} {m}");
                        assert!(!Mode(m).has_second_input() || c.inputs[1].is_some());
                    }
                }
            }
        }
        let h0 = S7_200_COUNTERS.get(0).unwrap();
        assert_eq!(
            (h0.control_smb(), h0.new_cv_smb(), h0.new_pv_smb()),
            (37, 38, 42)
        );
        assert_eq!(S7_200_COUNTERS.get(5).unwrap().control_smb(), 157);
        let used: Vec<_> = S7_200_COUNTERS
            .get(1)
            .unwrap()
            .inputs_used(Mode(2))
            .collect();
        assert_eq!(used, [(0, 6), (1, 0), (1, 1)]);
    }
}
