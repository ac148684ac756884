//! Memory areas and access widths.
//!
//! Every operand of the IR names an [`Area`] and a byte offset inside it; the
//! [`crate::layout::Layout`] turns that pair into an offset in the flat image. Multi-byte values
//! are big-endian in every area, accumulators included, so that a byte write to an accumulator
//! (offset `4n + 3`) replaces only its low byte (spec §1.5, item A5).

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
}

impl Area {
    /// Every area, in image order.
    pub const ALL: [Area; 15] = [
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
