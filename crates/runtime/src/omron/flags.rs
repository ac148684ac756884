//! The condition flags (spec §1.8) as a value, and what an instruction writes to them.
//!
//! [`CondFlags`] holds the twelve flags as bits; bit `i` is the flag at position `i` of
//! [`Flag::ALL`], which is also its bit in the image's `Flags` area (bytes 0–1 read
//! little-endian, `stljit_core::omron::SystemBit`): [`Flag`]'s discriminants are taken from
//! `SystemBit`, so the two orders cannot drift apart. [`FlagWrites`] says which flags an
//! instruction assigns and to what; every other flag keeps its value (spec §3: "flags not
//! listed are unchanged"), and [`FlagWrites::apply`] is the one place that rule is carried out.

use std::cmp::Ordering;
use stljit_core::omron::SystemBit;

/// One condition flag.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Flag {
    /// `P_ER`: the instruction was not executed (invalid operand data).
    Er = SystemBit::Er as u8,
    /// `P_CY`: carry or borrow.
    Cy = SystemBit::Cy as u8,
    /// `P_GT`: `>`.
    Gt = SystemBit::Gt as u8,
    /// `P_EQ`: `=` (also "result zero").
    Eq = SystemBit::Eq as u8,
    /// `P_LT`: `<`.
    Lt = SystemBit::Lt as u8,
    /// `P_N`: the result's most significant bit.
    N = SystemBit::N as u8,
    /// `P_OF`: signed overflow.
    Of = SystemBit::Of as u8,
    /// `P_UF`: signed underflow.
    Uf = SystemBit::Uf as u8,
    /// `P_GE`: `>=`.
    Ge = SystemBit::Ge as u8,
    /// `P_NE`: `<>`.
    Ne = SystemBit::Ne as u8,
    /// `P_LE`: `<=`.
    Le = SystemBit::Le as u8,
    /// `P_AER`: illegal memory access.
    Aer = SystemBit::Aer as u8,
}

impl Flag {
    /// Every flag, in bit order.
    pub const ALL: [Flag; 12] = [
        Flag::Er,
        Flag::Cy,
        Flag::Gt,
        Flag::Eq,
        Flag::Lt,
        Flag::N,
        Flag::Of,
        Flag::Uf,
        Flag::Ge,
        Flag::Ne,
        Flag::Le,
        Flag::Aer,
    ];

    /// The bits of every condition flag.
    pub const MASK: u16 = SystemBit::CONDITION_FLAGS;

    /// The six comparison flags (`>` `>=` `=` `<=` `<` `<>`).
    pub const COMPARISON: [Flag; 6] = [Flag::Gt, Flag::Ge, Flag::Eq, Flag::Le, Flag::Lt, Flag::Ne];

    /// This flag's bit.
    #[inline]
    pub const fn bit(self) -> u16 {
        1 << self as u16
    }

    /// The same flag as a system bit of the `Flags` area.
    pub fn system_bit(self) -> SystemBit {
        SystemBit::ALL[self as usize]
    }
}

/// The condition flags as one value (bit `i` = [`Flag::ALL`]`[i]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct CondFlags {
    bits: u16,
}

impl CondFlags {
    /// The flags in `bits` (the `Flags` area's bytes 0–1 read little-endian); the bits above
    /// the condition flags (`P_On`, clock pulses) are dropped.
    #[inline]
    pub const fn from_bits(bits: u16) -> CondFlags {
        CondFlags {
            bits: bits & Flag::MASK,
        }
    }

    /// The flags as bits.
    #[inline]
    pub const fn bits(self) -> u16 {
        self.bits
    }

    /// Whether `flag` is ON.
    #[inline]
    pub fn get(self, flag: Flag) -> bool {
        self.bits & flag.bit() != 0
    }

    /// Sets `flag` to `on`.
    #[inline]
    pub fn set(&mut self, flag: Flag, on: bool) {
        if on {
            self.bits |= flag.bit();
        } else {
            self.bits &= !flag.bit();
        }
    }
}

/// Which flags an instruction writes (`mask`) and the values it writes (`value`, only bits of
/// `mask` count). Build it with [`FlagWrites::write`]; apply it with [`FlagWrites::apply`] or,
/// on the raw flag word, [`FlagWrites::apply_bits`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FlagWrites {
    /// The flags written.
    pub mask: u16,
    /// Their new values (bits outside `mask` are 0).
    pub value: u16,
}

impl FlagWrites {
    /// No flag is written (an instruction that did not run, or one without flags).
    pub const NONE: FlagWrites = FlagWrites { mask: 0, value: 0 };

    /// ER ON and every other flag unchanged: the error outcome of spec §1.8 rule 3 and §2.11.
    pub const ERROR: FlagWrites = FlagWrites::NONE.write(Flag::Er, true);

    /// ER OFF and every other flag unchanged: a normal execution of an instruction whose only
    /// flag is ER (timers, counters).
    pub const OK: FlagWrites = FlagWrites::NONE.write(Flag::Er, false);

    /// These writes plus `flag := on` (a later write of the same flag wins).
    #[inline]
    pub const fn write(self, flag: Flag, on: bool) -> FlagWrites {
        let b = flag.bit();
        FlagWrites {
            mask: self.mask | b,
            value: if on { self.value | b } else { self.value & !b },
        }
    }

    /// Whether these writes set `flag` to ON (`false` if they write it OFF or not at all).
    #[inline]
    pub fn sets(self, flag: Flag) -> bool {
        self.value & self.mask & flag.bit() != 0
    }

    /// Whether these writes assign `flag` at all.
    #[inline]
    pub fn writes(self, flag: Flag) -> bool {
        self.mask & flag.bit() != 0
    }

    /// The flags after these writes: the written ones take their new value, the rest keep it.
    #[inline]
    pub fn apply(self, flags: CondFlags) -> CondFlags {
        CondFlags::from_bits(self.apply_bits(flags.bits()))
    }

    /// [`FlagWrites::apply`] on a raw flag word; bits outside [`Flag::MASK`] are kept as they are
    /// (the `Flags` area's system bits share the word).
    #[inline]
    pub const fn apply_bits(self, word: u16) -> u16 {
        let mask = self.mask & Flag::MASK;
        (word & !mask) | (self.value & mask)
    }
}

/// CMP's flags (spec §3.5): `>` `>=` `=` `<=` `<` `<>` from `ord` (first operand against the
/// second), ER OFF; N, CY and the rest unchanged.
pub const fn compare_writes(ord: Ordering) -> FlagWrites {
    let (lt, eq, gt) = (
        matches!(ord, Ordering::Less),
        matches!(ord, Ordering::Equal),
        matches!(ord, Ordering::Greater),
    );
    FlagWrites::OK
        .write(Flag::Gt, gt)
        .write(Flag::Ge, !lt)
        .write(Flag::Eq, eq)
        .write(Flag::Le, !gt)
        .write(Flag::Lt, lt)
        .write(Flag::Ne, !eq)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flag_bits_are_the_system_bits() {
        for (i, f) in Flag::ALL.iter().enumerate() {
            assert_eq!(*f as usize, i, "{f:?}: ALL is in bit order");
            assert_eq!(f.system_bit().index(), i as u32, "{f:?}");
        }
        let all = Flag::ALL.iter().fold(0, |m, f| m | f.bit());
        assert_eq!(all, Flag::MASK);
    }

    #[test]
    fn get_set_and_from_bits() {
        let mut f = CondFlags::default();
        assert!(Flag::ALL.iter().all(|&x| !f.get(x)), "cold start: all OFF");
        f.set(Flag::Cy, true);
        f.set(Flag::Aer, true);
        assert!(f.get(Flag::Cy) && f.get(Flag::Aer) && !f.get(Flag::Er));
        f.set(Flag::Cy, false);
        assert_eq!(f.bits(), Flag::Aer.bit());
        // P_On (bit 12) and the pulses are not condition flags.
        assert_eq!(CondFlags::from_bits(0xFFFF).bits(), Flag::MASK);
    }

    #[test]
    fn unlisted_flags_are_unchanged() {
        // Spec §3: a write touches only its listed flags.
        let before = CondFlags::from_bits(Flag::Cy.bit() | Flag::Er.bit() | Flag::N.bit());
        let after = FlagWrites::OK.write(Flag::Eq, true).apply(before);
        assert_eq!(
            after.bits(),
            Flag::Cy.bit() | Flag::N.bit() | Flag::Eq.bit()
        );
        assert_eq!(FlagWrites::NONE.apply(before), before);
        assert_eq!(
            FlagWrites::ERROR.apply(CondFlags::default()).bits(),
            Flag::Er.bit()
        );
        // The raw word keeps the system bits above the flags (P_On = bit 12).
        assert_eq!(FlagWrites::ERROR.apply_bits(1 << 12), (1 << 12) | 1);
        // The later write of one flag wins.
        let w = FlagWrites::NONE
            .write(Flag::Eq, true)
            .write(Flag::Eq, false);
        assert!(w.writes(Flag::Eq) && !w.sets(Flag::Eq));
    }

    #[test]
    fn compare_sets_the_six_and_clears_er() {
        // Spec §3.5 CMP: > >= = <= < <> from the result, ER OFF, N unchanged.
        use Flag::*;
        let start = CondFlags::from_bits(Er.bit() | N.bit() | Cy.bit());
        let on = |o| {
            let f = compare_writes(o).apply(start);
            Flag::ALL
                .iter()
                .filter(|&&x| f.get(x))
                .copied()
                .collect::<Vec<_>>()
        };
        assert_eq!(on(Ordering::Less), [Cy, Lt, N, Ne, Le]);
        assert_eq!(on(Ordering::Equal), [Cy, Eq, N, Ge, Le]);
        assert_eq!(on(Ordering::Greater), [Cy, Gt, N, Ge, Ne]);
    }
}
