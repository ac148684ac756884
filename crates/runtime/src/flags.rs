//! SMB1 status flags (spec §2.3) and the outcome of a box computation.
//!
//! Every value helper returns an [`Outcome`]: the value to write (or `None`: nothing is written
//! and ENO = 0) and the flag effect as set/clear masks on SMB1. Engines apply the masks with
//! [`apply_flags`] (or inline `smb1 = smb1 & !clear | set`), so a flag rule exists only in the
//! helper that computes it.

use crate::mem;
use stljit_core::Area;
use stljit_core::layout::Layout;

/// SM1.0: result zero.
pub const ZERO: u8 = 1 << 0;
/// SM1.1: overflow or illegal value.
pub const OVERFLOW: u8 = 1 << 1;
/// SM1.2: result negative.
pub const NEGATIVE: u8 = 1 << 2;
/// SM1.3: division by zero.
pub const DIV_ZERO: u8 = 1 << 3;
/// SM1.4: ATT into a full table (s7-200-more §4.2).
pub const TABLE_FULL: u8 = 1 << 4;
/// SM1.5: FIFO or LIFO from an empty table.
pub const TABLE_EMPTY: u8 = 1 << 5;
/// SM1.6: not a BCD value.
pub const BCD: u8 = 1 << 6;
/// SM1.7: ATH met a character that is no hex digit (s7-200-more §5.2).
pub const NOT_HEX: u8 = 1 << 7;
/// The bits every integer and real result assigns (OK and OVF rules of spec §4.8): SM1.0,
/// SM1.1, SM1.2.
pub const RESULT: u8 = ZERO | OVERFLOW | NEGATIVE;

/// An effect on SMB1: bits in `set` become 1, bits in `clear` become 0, the rest keep their value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SmFlags {
    /// Bits to set.
    pub set: u8,
    /// Bits to clear.
    pub clear: u8,
}

impl SmFlags {
    /// No effect.
    pub const NONE: SmFlags = SmFlags { set: 0, clear: 0 };

    /// Writes exactly the bits of `mask` to the values in `values`.
    pub const fn assign(mask: u8, values: u8) -> SmFlags {
        SmFlags {
            set: values & mask,
            clear: !values & mask,
        }
    }

    /// The new SMB1.
    #[inline]
    pub fn apply(self, smb1: u8) -> u8 {
        (smb1 & !self.clear) | self.set
    }
}

/// Applies `f` to SMB1 in the image.
#[inline]
pub fn apply_flags(img: &mut [u8], layout: &Layout, f: SmFlags) {
    if f != SmFlags::NONE {
        let at = layout.base(Area::SM) + 1;
        let v = f.apply(mem::get_u8(img, at));
        mem::set_u8(img, at, v);
    }
}

/// What a box computation produced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// The value to write to OUT (low bits of the width), or `None`: OUT unchanged, ENO = 0.
    pub value: Option<u32>,
    /// The SMB1 effect.
    pub flags: SmFlags,
}

impl Outcome {
    /// A value with no flag effect.
    pub const fn plain(v: u32) -> Outcome {
        Outcome {
            value: Some(v),
            flags: SmFlags::NONE,
        }
    }

    /// Whether ENO is 1 (the value is written).
    pub fn ok(self) -> bool {
        self.value.is_some()
    }
}
