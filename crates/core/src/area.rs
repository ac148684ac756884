//! Memory areas and access widths.
//!
//! Every operand of the IR names an [`Area`] and a byte offset inside it; the
//! [`crate::layout::Layout`] turns that pair into an offset in the flat image. Multi-byte values
//! are big-endian in every area, accumulators included, so that a byte write to an accumulator
//! (offset `4n + 3`) replaces only its low byte (spec §1.5, item A5).
//!
//! The Omron CP areas (`Cio` … `Tr`) are 16-bit words stored big-endian at offset `2w`, so the
//! word and bit operations of the IR work on them unchanged; `crate::omron` maps Omron's
//! `word.bit` addresses (bit 00 = least significant) onto these bytes. S7 profiles give them
//! size 0, so they change nothing in an S7 image.

/// Access width of a value operand. Reals are `DWord`s whose bits are an IEEE-754 binary32.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Width {
    /// 8 bits.
    Byte,
    /// 16 bits.
    Word,
    /// 32 bits.
    DWord,
}

impl Width {
    /// Every width, narrowest first.
    pub const ALL: [Width; 3] = [Width::Byte, Width::Word, Width::DWord];

    /// Size in bytes.
    #[inline]
    pub fn bytes(self) -> u32 {
        match self {
            Width::Byte => 1,
            Width::Word => 2,
            Width::DWord => 4,
        }
    }

    /// Size in bits.
    #[inline]
    pub fn bits(self) -> u32 {
        self.bytes() * 8
    }

    /// Mask of the value bits (`0xFF`, `0xFFFF`, `0xFFFF_FFFF`).
    #[inline]
    pub fn mask(self) -> u32 {
        match self {
            Width::Byte => 0xFF,
            Width::Word => 0xFFFF,
            Width::DWord => 0xFFFF_FFFF,
        }
    }
}

/// A memory area of the PLC. The order is the order of the areas in the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Area {
    /// Input process image (`I`).
    I,
    /// Output process image (`Q`).
    Q,
    /// Bit memory (`M`).
    M,
    /// Sequence-control relays (`S`).
    S,
    /// Special memory (`SM`).
    SM,
    /// Variable memory (`V`).
    V,
    /// Local memory of the current POU frame (`L`); offsets are relative to the frame.
    L,
    /// Analog inputs (`AIW`), big-endian words at even offsets.
    AI,
    /// Analog outputs (`AQW`).
    AQ,
    /// Timer current values, big-endian `i16` at offset `2n` (`T37` as a word).
    TimerValue,
    /// Counter current values, big-endian `i16` at offset `2n`.
    CounterValue,
    /// Timer bits, one byte (0/1) per timer at offset `n` (`T37` as a bit).
    TimerBit,
    /// Counter bits, one byte per counter.
    CounterBit,
    /// High-speed counters, big-endian `i32` at offset `4n`.
    HC,
    /// Accumulators, big-endian `u32` at offset `4n`.
    AC,
    /// Omron CIO words (`100`, `100.01`) other than the input and output words, which are the
    /// `I` and `Q` areas of an Omron profile (`crate::omron::word_loc`).
    Cio,
    /// Omron work words (`W`).
    Work,
    /// Omron holding words (`H`).
    Holding,
    /// Omron auxiliary words (`A`); the low words are read-only (profile).
    Aux,
    /// Omron data memory (`D`).
    Dm,
    /// Omron condition flags and system pulses (`P_EQ`, `P_On`, `P_1s`), one bit each at the
    /// positions of `crate::omron::SystemBit`; read-only for the program.
    Flags,
    /// Omron temporary relays `TR0`–`TR15` (two bytes; a branch point, never retained).
    Tr,
    /// Omron index registers `IR0`–`IR15`, big-endian `u32` effective addresses at `4n`.
    IndexReg,
    /// Omron data registers `DR0`–`DR15`, big-endian `i16` at `2n`.
    DataReg,
}

impl Area {
    /// Every area, in image order.
    pub const ALL: [Area; 24] = [
        Area::I,
        Area::Q,
        Area::M,
        Area::S,
        Area::SM,
        Area::V,
        Area::L,
        Area::AI,
        Area::AQ,
        Area::TimerValue,
        Area::CounterValue,
        Area::TimerBit,
        Area::CounterBit,
        Area::HC,
        Area::AC,
        Area::Cio,
        Area::Work,
        Area::Holding,
        Area::Aux,
        Area::Dm,
        Area::Flags,
        Area::Tr,
        Area::IndexReg,
        Area::DataReg,
    ];

    /// The code a pointer (`&VB100`) carries in its top byte, for areas a pointer may address
    /// (spec §1.6: I, Q, M, S, SM, V, AI, AQ, T and C current values). The encoding is fixed here
    /// and nowhere else.
    pub fn pointer_code(self) -> Option<u8> {
        Some(match self {
            Area::I => 0x01,
            Area::Q => 0x02,
            Area::M => 0x03,
            Area::S => 0x04,
            Area::SM => 0x05,
            Area::V => 0x06,
            Area::AI => 0x07,
            Area::AQ => 0x08,
            Area::TimerValue => 0x09,
            Area::CounterValue => 0x0A,
            _ => return None,
        })
    }

    /// Inverse of [`Area::pointer_code`].
    pub fn from_pointer_code(code: u8) -> Option<Area> {
        Area::ALL
            .into_iter()
            .find(|a| a.pointer_code() == Some(code))
    }
}
