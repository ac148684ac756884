//! Per-scan stimulus: virtual time, input bytes, analog input words, HMI writes, high-speed
//! counter activity and, for programs that communicate, the bytes received on the serial ports.
//!
//! Inputs change the way a machine's do (a few bits per scan, now and then a whole byte); times
//! are regular, irregular (including repeated instants) or jump far ahead, so that every timer
//! resolution sees zero, one and many intervals per scan. Received bytes ([`for_program`]) come
//! in short messages built around the start and end characters the communication generator
//! configures, now and then as noise or as a burst that overflows the port's receive FIFO.
//!
//! Omron profiles ([`Family::Omron`]): the inputs are the CIO input words 0–1 (the profile's
//! input bytes), scan times are 1 to 200 ms (fixed, irregular, or fixed with a rare pause of
//! seconds), and HMI writes go to DM words (the `@D`/`*D` pointer words D100–D103 among them,
//! with values inside and outside the DM area), work, holding, CIO work and writable auxiliary
//! words and bits.

use crate::rng::Choices;
use stljit_core::comm::PORTS;
use stljit_core::ir::{Address, BitLoc, Loc, Program};
use stljit_core::omron::{WordArea, bit_of_word, word_loc};
use stljit_core::{Area, Family, ProfileId, Width};

/// A value written into the image before a scan, as an HMI or a debugger would.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HmiWrite {
    /// Where.
    pub addr: Address,
    /// The value (a bit uses bit 0).
    pub value: u32,
}

/// The bytes arriving on the serial ports in one scan interval (s7-200-more §10.4, §11.2 `rx`),
/// as `(port, bytes)`: ports ascending, each at most once, never an empty list.
pub type Received = Vec<(u8, Vec<u8>)>;

/// Everything the outside world supplies for one scan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScanInput {
    /// Virtual time of the scan in ms (non-decreasing).
    pub t_ms: u64,
    /// The physical input bytes (`IB0..`), one per profile input byte.
    pub inputs: Vec<u8>,
    /// The analog input words (`AIW0, AIW2, ..`).
    pub ai: Vec<u16>,
    /// Writes applied before the scan starts.
    pub writes: Vec<HmiWrite>,
    /// High-speed counter activity in the interval before the scan, by counter number
    /// (s7-200-more §8.4; missing counters: 0).
    pub hsc: Vec<i32>,
    /// The bytes arriving on the serial ports in the interval before the scan.
    pub rx: Received,
}

/// The stimulus of a whole run.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct Stimulus {
    /// One entry per scan.
    pub scans: Vec<ScanInput>,
}

impl Stimulus {
    /// Number of scans.
    pub fn len(&self) -> usize {
        self.scans.len()
    }

    /// Whether there are no scans.
    pub fn is_empty(&self) -> bool {
        self.scans.is_empty()
    }
}

/// Generates `scans` scans of stimulus for a profile.
pub fn generate(c: &mut Choices<'_>, profile: ProfileId, scans: u32) -> Stimulus {
    let p = profile.profile();
    let omron = p.family == Family::Omron;
    let mut inputs: Vec<u8> = (0..p.inputs)
        .map(|_| if c.chance(1, 3) { c.bits() as u8 } else { 0 })
        .collect();
    let mut ai: Vec<u16> = (0..p.analog_inputs / 2).map(|_| 0).collect();
    let mut hsc: Vec<i32> = vec![0; p.hsc.counters.len()];
    // Time modes: a fixed period, irregular steps, or a fixed period with rare long pauses.
    let mode = c.below(3);
    let periods: &[u32] = if omron {
        &[10, 1, 2, 5, 20, 50, 100, 150, 200]
    } else {
        &[10, 1, 5, 7, 20, 50, 100, 250, 1000]
    };
    let period = u64::from(c.pick(periods));
    let mut t = if c.chance(1, 4) {
        u64::from(c.below(100_000))
    } else {
        0
    };
    let mut out = Vec::with_capacity(scans as usize);
    for k in 0..scans {
        if k > 0 && omron {
            t += omron_step(c, mode, period);
        } else if k > 0 {
            t += match mode {
                0 => period,
                1 => u64::from(match c.weighted(&[2, 6, 3, 1]) {
                    0 => 0,
                    1 => c.range(1, 30),
                    2 => c.range(30, 300),
                    _ => c.range(300, 3000),
                }),
                _ => {
                    if c.chance(1, 20) {
                        u64::from(c.range(1000, 70_000))
                    } else {
                        period
                    }
                }
            };
        }
        for _ in 0..c.weighted(&[3, 4, 2, 1]) {
            let byte = if c.chance(3, 4) {
                c.below(2.min(p.inputs))
            } else {
                c.below(p.inputs)
            } as usize;
            inputs[byte] ^= 1 << c.below(8);
        }
        if c.chance(1, 30) {
            let byte = c.below(p.inputs) as usize;
            inputs[byte] = c.bits() as u8;
        }
        if !ai.is_empty() && c.chance(1, 5) {
            let w = c.below(ai.len() as u32) as usize;
            ai[w] = match c.below(3) {
                0 => c.below(32_001) as u16,
                1 => c.bits() as u16,
                _ => ai[w].wrapping_add(c.below(200) as u16),
            };
        }
        let mut writes = Vec::new();
        if c.chance(1, 12) {
            writes.push(if omron {
                omron_hmi_write(c, profile)
            } else {
                hmi_write(c, profile)
            });
        }
        // Counting activity: mostly a few steps either way, so CV meets small presets and
        // changes direction; now and then a burst.
        if c.chance(1, 4) {
            let n = c.below(p.hsc.counters.len().max(1) as u32) as usize;
            if n < hsc.len() {
                hsc[n] = match c.weighted(&[2, 6, 1]) {
                    0 => 0,
                    1 => c.range(0, 24) as i32 - 12,
                    _ => c.range(0, 400) as i32 - 200,
                };
            }
        }
        out.push(ScanInput {
            t_ms: t,
            inputs: inputs.clone(),
            ai: ai.clone(),
            writes,
            hsc: hsc.clone(),
            rx: Vec::new(),
        });
    }
    Stimulus { scans: out }
}

/// Generates `scans` scans of stimulus for `program`: [`generate`] for its profile, then, if the
/// program starts communication ([`Program::uses_ports`]), received bytes in about one scan in
/// three. A program without ports gets exactly [`generate`]'s stimulus.
pub fn for_program(c: &mut Choices<'_>, program: &Program, scans: u32) -> Stimulus {
    let mut stimulus = generate(c, program.profile, scans);
    if program.uses_ports() {
        for scan in &mut stimulus.scans {
            scan.rx = received(c);
        }
    }
    stimulus
}

/// One scan's received bytes: none in two scans of three, else mostly port 0, now and then
/// port 1 or both.
fn received(c: &mut Choices<'_>) -> Received {
    if !c.chance(1, 3) {
        return Vec::new();
    }
    let ports: &[u8] = match c.weighted(&[6, 2, 1]) {
        0 => &[PORTS[0].port],
        1 => &[PORTS[1].port],
        _ => &[PORTS[0].port, PORTS[1].port],
    };
    ports.iter().map(|&p| (p, message(c))).collect()
}

/// A message: a start character, a few characters, an end character (each part optional), or
/// noise, or a burst longer than the receive FIFO (s7-200-more §10.4: the excess is dropped).
fn message(c: &mut Choices<'_>) -> Vec<u8> {
    use super::comm::{END_CHARS, START_CHARS};
    let mut m = Vec::new();
    match c.weighted(&[8, 2, 1]) {
        0 => {
            if c.chance(2, 3) {
                m.push(c.pick(&START_CHARS));
            }
            for _ in 0..c.range(0, 6) {
                m.push(if c.chance(1, 6) {
                    c.pick(&END_CHARS)
                } else {
                    c.range(0x20, 0x7E) as u8
                });
            }
            if c.chance(2, 3) {
                m.push(c.pick(&END_CHARS));
            }
        }
        1 => m.extend((0..c.range(1, 40)).map(|_| c.bits() as u8)),
        _ => m.extend((0..c.range(200, 320)).map(|_| c.bits() as u8)),
    }
    if m.is_empty() {
        m.push(c.pick(&END_CHARS));
    }
    m
}

fn hmi_write(c: &mut Choices<'_>, profile: ProfileId) -> HmiWrite {
    let p = profile.profile();
    match c.below(4) {
        0 => HmiWrite {
            addr: Address::Bit(BitLoc {
                area: Area::M,
                byte: c.below(p.bit_memory.min(8)),
                bit: c.below(8) as u8,
            }),
            value: c.below(2),
        },
        1 => HmiWrite {
            addr: Address::Value {
                loc: Loc {
                    area: Area::V,
                    offset: 2 * c.below(32),
                },
                width: Width::Word,
            },
            value: c.bits() & 0xFFFF,
        },
        2 => HmiWrite {
            addr: Address::Value {
                loc: Loc {
                    area: Area::V,
                    offset: c.below(64),
                },
                width: Width::Byte,
            },
            value: c.bits() & 0xFF,
        },
        _ => HmiWrite {
            addr: Address::Value {
                loc: Loc {
                    area: Area::V,
                    offset: 100 + 4 * c.below(8),
                },
                width: Width::DWord,
            },
            value: (c.range(0, 2000) as f32 / 4.0 - 250.0).to_bits(),
        },
    }
}

/// The time from one Omron scan to the next: 1 to 200 ms, and in mode 2 a rare pause.
fn omron_step(c: &mut Choices<'_>, mode: u32, period: u64) -> u64 {
    match mode {
        0 => period,
        1 => u64::from(match c.weighted(&[6, 3, 1]) {
            0 => c.range(1, 10),
            1 => c.range(10, 50),
            _ => c.range(50, 200),
        }),
        _ => {
            if c.chance(1, 40) {
                u64::from(c.range(1000, 70_000))
            } else {
                period
            }
        }
    }
}

/// An HMI write on an Omron profile: a word or bit of D, W, H, CIO work or A448+.
fn omron_hmi_write(c: &mut Choices<'_>, profile: ProfileId) -> HmiWrite {
    let p = profile.profile();
    let (area, word) = match c.below(6) {
        0 | 1 => {
            let w = if c.chance(1, 2) {
                100 + c.below(4)
            } else {
                c.below(32)
            };
            (WordArea::Dm, w)
        }
        2 => (WordArea::Work, c.below(8)),
        3 => (WordArea::Holding, c.below(4)),
        4 => (WordArea::Cio, 2 + c.below(8)),
        _ => (WordArea::Aux, p.omron.aux_read_only + c.below(4)),
    };
    // Every word above exists on every Omron profile.
    let loc = word_loc(p, area, word).unwrap_or(Loc {
        area: Area::Dm,
        offset: 0,
    });
    if area != WordArea::Dm && c.chance(1, 2) {
        return HmiWrite {
            addr: Address::Bit(bit_of_word(loc, c.below(16) as u8)),
            value: c.below(2),
        };
    }
    let value = match c.below(4) {
        0 => c.below(40),
        1 => c.pick(&[
            0x12A4,
            0x9999,
            0x7FFF,
            0x8000,
            0xFFFF,
            p.omron.dm - 1,
            p.omron.dm,
        ]),
        _ => c.bits() & 0xFFFF,
    };
    HmiWrite {
        addr: Address::Value {
            loc,
            width: Width::Word,
        },
        value,
    }
}
