//! The V regions the s7-200-more §4–§7 instructions work on, and their initial contents.
//!
//! Tables, strings, ASCII buffers, clock buffers and PID loop tables live in their own slots
//! above the regions of [`super::operands`] (`VB400` up), so that the instructions mostly read
//! what they or their neighbours wrote. A slot gets its initial contents in the program's data
//! block the first time an instruction names it: mostly valid (a table header with TL ≤ 100 and
//! EC ≤ TL, strings with a length that fits, BCD dates, loop tables with real gains), now and
//! then not (TL above 100, EC above TL, a length byte of 255, a month 13, NaN in a loop table),
//! which is where the error paths, SM4.3 and the SMB1 flags of these instructions show.

use super::Gen;
use std::collections::BTreeMap;
use stljit_core::ir::DataInit;

/// First byte of the table slots.
pub(crate) const TABLE_BASE: u32 = 400;
/// Number of table slots.
pub(crate) const TABLE_SLOTS: u32 = 3;
/// Bytes per table slot: a header and up to 28 entries.
pub(crate) const TABLE_STRIDE: u32 = 60;
/// First byte of the string slots.
pub(crate) const STRING_BASE: u32 = TABLE_BASE + TABLE_SLOTS * TABLE_STRIDE;
/// Number of string slots.
pub(crate) const STRING_SLOTS: u32 = 4;
/// Bytes per string slot; longer strings run into the next slot (and past the last one into
/// the buffers), which is allowed and happens.
pub(crate) const STRING_STRIDE: u32 = 40;
/// First byte of the ASCII buffer slots (ATH, HTA, ITA, DTA, RTA).
pub(crate) const BUF_BASE: u32 = STRING_BASE + STRING_SLOTS * STRING_STRIDE;
/// Number of ASCII buffer slots.
pub(crate) const BUF_SLOTS: u32 = 4;
/// Bytes per buffer slot: RTA writes up to 15.
pub(crate) const BUF_STRIDE: u32 = 24;
/// First byte of the clock buffers: the 8-byte one, then the extended one (19 or 21 bytes).
pub(crate) const CLOCK_BASE: u32 = BUF_BASE + BUF_SLOTS * BUF_STRIDE;
/// Bytes per clock buffer.
pub(crate) const CLOCK_STRIDE: u32 = 24;
/// First byte of the PID loop tables, one per loop number.
pub(crate) const PID_BASE: u32 = CLOCK_BASE + 2 * CLOCK_STRIDE;

/// Text pieces strings are made of: numbers in the forms STI/STD/STR accept and reject, hex
/// digits, words the find instructions look for. No `"` (a constant string cannot hold one).
const PIECES: [&str; 24] = [
    "123",
    "-00456",
    "+2345",
    "  -12",
    "123.45",
    "1,5",
    "-0.5",
    "32767",
    "-32768",
    "32768",
    "2147483648",
    "A123",
    "++1",
    "+ 1",
    "3E",
    "a1",
    "FF",
    "HELLO",
    "LO",
    " ",
    "ABC",
    "x",
    "000000123ABCD",
    "9.9999e9",
];

/// Interesting real values of a loop table that make the PID fail (SM1.1, nothing written).
const PID_POISON: [f32; 6] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    0.0,
    -1.0,
    3.0e38,
];

impl Gen<'_, '_> {
    /// Sets initial V bytes (a later setting wins, as in the data block).
    pub(crate) fn set_data(&mut self, offset: u32, bytes: &[u8]) {
        let v = self.p.variable_memory;
        for (i, &b) in bytes.iter().enumerate() {
            let at = offset + i as u32;
            if at < v {
                self.data.insert(at, b);
            }
        }
    }

    /// Whether the data block already sets byte `offset` (the slot there is initialised).
    pub(crate) fn has_data(&self, offset: u32) -> bool {
        self.data.contains_key(&offset)
    }

    /// Text for a string: a few pieces, now and then a long run (SCAT past 254 characters).
    pub(crate) fn string_text(&mut self) -> Vec<u8> {
        let mut s = Vec::new();
        if self.c.chance(1, 20) {
            let piece = self.c.pick(&PIECES).as_bytes();
            let n = self.c.range(100, 254) as usize;
            while s.len() < n {
                s.extend_from_slice(piece);
            }
            s.truncate(n);
            return s;
        }
        for _ in 0..self.c.weighted(&[1, 6, 3, 2]) {
            s.extend_from_slice(self.c.pick(&PIECES).as_bytes());
        }
        s
    }

    /// The initial table at `offset` (its TL word): TL 1–24 and EC ≤ TL most of the time.
    pub(crate) fn init_table(&mut self, offset: u32) {
        let tl = match self.c.weighted(&[12, 1, 1, 1]) {
            0 => self.c.range(1, 24),
            1 => 0,
            2 => self.c.range(101, 0x7FFF),
            _ => self.c.range(25, 100),
        };
        let ec = match self.c.weighted(&[10, 1, 1]) {
            0 => self.c.range(0, tl.min(24)),
            1 => tl + self.c.range(1, 3),
            _ => self.c.bits() & 0xFFFF,
        };
        let mut bytes = Vec::new();
        bytes.extend_from_slice(&(tl as u16).to_be_bytes());
        bytes.extend_from_slice(&(ec as u16).to_be_bytes());
        for _ in 0..ec.min(tl).min(24) {
            let d = if self.c.chance(3, 4) {
                self.c.below(10) as u16
            } else {
                self.c.bits() as u16
            };
            bytes.extend_from_slice(&d.to_be_bytes());
        }
        self.set_data(offset, &bytes);
    }

    /// The initial string at `offset`: a length byte and the characters, rarely length 255.
    pub(crate) fn init_string(&mut self, offset: u32) {
        if self.c.chance(1, 30) {
            self.set_data(offset, &[255]);
            return;
        }
        let text = self.string_text();
        let mut bytes = vec![text.len() as u8];
        bytes.extend_from_slice(&text);
        self.set_data(offset, &bytes);
    }

    /// The initial ASCII buffer at `offset`: hex digits, sometimes with a character ATH
    /// rejects (lower case, a space).
    pub(crate) fn init_buffer(&mut self, offset: u32) {
        const HEX: &[u8] = b"0123456789ABCDEF";
        let mut bytes: Vec<u8> = (0..BUF_STRIDE)
            .map(|_| HEX[self.c.below(16) as usize])
            .collect();
        if self.c.chance(1, 4) {
            let at = self.c.below(BUF_STRIDE) as usize;
            bytes[at] = self.c.pick(b"a fG/:@");
        }
        self.set_data(offset, &bytes);
    }

    /// The initial clock buffer at `offset`: a BCD date (sometimes an invalid one) and, for the
    /// extended buffer, a daylight-saving mode of the profile (sometimes one it lacks).
    pub(crate) fn init_clock(&mut self, offset: u32, extended: bool) {
        let bcd = |v: u32| (((v / 10) << 4) | (v % 10)) as u8;
        let month = self.c.range(1, 12);
        let days = [31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31][month as usize - 1];
        let mut b = vec![
            bcd(self.c.below(100)),
            bcd(month),
            bcd(self.c.range(1, days)),
            bcd(self.c.below(24)),
            bcd(self.c.below(60)),
            bcd(self.c.below(60)),
            0,
            self.c.range(1, 7) as u8,
        ];
        if self.c.chance(1, 4) {
            // One bad field: a non-BCD digit, month 13, day 30 of February, hour 24, day 0.
            match self.c.below(5) {
                0 => b[self.c.below(6) as usize] |= 0x0A,
                1 => b[1] = 0x13,
                2 => (b[1], b[2]) = (0x02, 0x30),
                3 => b[3] = 0x24,
                _ => b[2] = 0,
            }
        }
        if extended {
            let modes = self.p.clock.dst_modes();
            let mode = if modes.is_empty() || self.c.chance(1, 8) {
                self.c.pick(&[0x04, 0x12, 0x20, 0xEE, 0xFE])
            } else {
                self.c.pick(modes)
            };
            b.push(mode);
            for _ in 9..21 {
                b.push(bcd(self.c.below(60)));
            }
        }
        self.set_data(offset, &b);
    }

    /// The initial loop table at `offset`: normalised PV, SP, M and bias, real gains and times
    /// (T_I +INF now and then: no integral action), one poisoned field in one table of ten.
    pub(crate) fn init_pid(&mut self, offset: u32) {
        let unit = |c: &mut crate::rng::Choices<'_>| c.below(101) as f32 / 100.0;
        let mut f = [
            unit(self.c),
            unit(self.c),
            unit(self.c),
            self.c.pick(&[0.0, 0.5, 1.0, 2.5, -1.0, 10.0]),
            self.c.pick(&[0.1, 0.5, 1.0, 0.01]),
            self.c.pick(&[f32::INFINITY, 0.5, 1.0, 10.0, 0.01]),
            self.c.pick(&[0.0, 0.0, 0.01, 0.1]),
            unit(self.c),
            unit(self.c),
        ];
        if self.c.chance(1, 10) {
            f[self.c.below(9) as usize] = self.c.pick(&PID_POISON);
        }
        let bytes: Vec<u8> = f.iter().flat_map(|x| x.to_bits().to_be_bytes()).collect();
        self.set_data(offset, &bytes);
    }
}

/// The data block of the initial bytes: one run per stretch of consecutive bytes (the front
/// end joins values that follow each other into one run, so adjacent runs would not survive
/// the round trip).
pub(crate) fn data_runs(data: &BTreeMap<u32, u8>) -> Vec<DataInit> {
    let mut out: Vec<DataInit> = Vec::new();
    for (&at, &b) in data {
        match out.last_mut() {
            Some(last) if last.offset + last.bytes.len() as u32 == at => last.bytes.push(b),
            _ => out.push(DataInit {
                offset: at,
                bytes: vec![b],
            }),
        }
    }
    out
}
