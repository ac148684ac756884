//! Watch specs: an address to observe plus how its value prints (`VD50:real`, `VW0:hex`).
//!
//! Defaults: bits print `0`/`1`, bytes unsigned, words and dwords signed decimal. Suffixes:
//! `:i` signed, `:u` unsigned, `:hex` (`16#` and the full width in upper-case digits), `:bin`
//! (`2#` and every bit), `:real` (dwords only, the bits read as an IEEE-754 binary32). A timer or
//! counter name (`T37`, `C5`) is its bit; with a numeric suffix (`T37:i`) it is its current value
//! — the only way to name the word of a timer outside a program.
//!
//! Omron programs (`Family::Omron`, spec omron-cp.md §6 "Watched values") print words unsigned
//! by default and `:hex` with Omron's `#` prefix (`#00AA`); [`WatchSpec::parse_for`] takes the
//! family.

use crate::Resolver;
use crate::value::read_address;
use std::fmt;
use stljit_core::ir::{Address, Loc};
use stljit_core::layout::Layout;
use stljit_core::{Area, Family, Width};
use stljit_runtime::image::{Image, bit_addr, loc_addr};

/// How a watched value prints.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Bits 0/1, bytes unsigned, words and dwords signed.
    Default,
    /// `:i` — two's complement.
    Signed,
    /// `:u` — unsigned.
    Unsigned,
    /// `:hex` — `16#` and width/4 digits.
    Hex,
    /// `:bin` — `2#` and every bit.
    Bin,
    /// `:real` — IEEE-754 binary32 (dwords only).
    Real,
}

impl Format {
    fn from_suffix(s: &str) -> Option<Format> {
        Some(match s {
            "i" => Format::Signed,
            "u" => Format::Unsigned,
            "hex" => Format::Hex,
            "bin" => Format::Bin,
            "real" => Format::Real,
            _ => return None,
        })
    }
}

/// Why a watch spec was rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WatchError {
    /// The resolver did not know the name.
    UnknownAddress {
        /// The spec as written.
        spec: String,
        /// The resolver's reason.
        reason: String,
    },
    /// The suffix is not one of `i`, `u`, `hex`, `bin`, `real`.
    UnknownFormat {
        /// The spec as written.
        spec: String,
    },
    /// The suffix does not apply to the address (`:real` on a word, `:hex` on an I bit).
    NotApplicable {
        /// The spec as written.
        spec: String,
        /// Why.
        reason: &'static str,
    },
    /// The address does not fit the image (checked by [`WatchSpec::check`]).
    OutOfRange {
        /// The spec as written.
        spec: String,
    },
}

impl fmt::Display for WatchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WatchError::UnknownAddress { spec, reason } => {
                write!(f, "watch `{spec}`: unknown address: {reason}")
            }
            WatchError::UnknownFormat { spec } => write!(
                f,
                "watch `{spec}`: unknown format (use :i, :u, :hex, :bin or :real)"
            ),
            WatchError::NotApplicable { spec, reason } => write!(f, "watch `{spec}`: {reason}"),
            WatchError::OutOfRange { spec } => {
                write!(f, "watch `{spec}`: address outside the memory image")
            }
        }
    }
}

impl std::error::Error for WatchError {}

/// An address to observe and its print format.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WatchSpec {
    /// The spec as written (`VD50:real`), used as the column title.
    pub text: String,
    /// What is read.
    pub address: Address,
    /// How it prints.
    pub format: Format,
    /// Whose notation it prints in.
    pub family: Family,
}

impl WatchSpec {
    /// Parses `ADDR` or `ADDR:FORMAT` in S7 notation.
    pub fn parse(text: &str, resolve: Resolver<'_>) -> Result<WatchSpec, WatchError> {
        WatchSpec::parse_for(text, resolve, Family::S7)
    }

    /// Parses `ADDR` or `ADDR:FORMAT`, printing in the notation of `family`.
    pub fn parse_for(
        text: &str,
        resolve: Resolver<'_>,
        family: Family,
    ) -> Result<WatchSpec, WatchError> {
        let spec = text.trim();
        let (name, format) = match spec.rsplit_once(':') {
            Some((name, suffix)) => {
                let f = Format::from_suffix(suffix.trim()).ok_or(WatchError::UnknownFormat {
                    spec: spec.to_string(),
                })?;
                (name.trim(), f)
            }
            None => (spec, Format::Default),
        };
        let mut address = resolve(name).map_err(|reason| WatchError::UnknownAddress {
            spec: spec.to_string(),
            reason,
        })?;
        let na = |reason| WatchError::NotApplicable {
            spec: spec.to_string(),
            reason,
        };
        match (address, format) {
            (_, Format::Default) => {}
            (Address::Bit(b), _) if matches!(b.area, Area::TimerBit | Area::CounterBit) => {
                if format == Format::Real {
                    return Err(na("a timer or counter value is a word, not a real"));
                }
                let area = if b.area == Area::TimerBit {
                    Area::TimerValue
                } else {
                    Area::CounterValue
                };
                address = Address::Value {
                    loc: Loc {
                        area,
                        offset: 2 * b.byte,
                    },
                    width: Width::Word,
                };
            }
            (Address::Bit(_), _) => return Err(na("a bit prints only as 0/1 (no format)")),
            (Address::Value { width, .. }, Format::Real) if width != Width::DWord => {
                return Err(na(":real needs a dword (VD, MD, AC, ...)"));
            }
            (Address::Value { .. }, _) => {}
        }
        Ok(WatchSpec {
            text: spec.to_string(),
            address,
            format,
            family,
        })
    }

    /// Checks that the address fits the image described by `layout`.
    pub fn check(&self, layout: &Layout) -> Result<(), WatchError> {
        let ok = match self.address {
            Address::Bit(b) => bit_addr(layout, b, 0).is_some(),
            Address::Value { loc, width } => loc_addr(layout, loc, width, 0).is_some(),
        };
        if ok {
            Ok(())
        } else {
            Err(WatchError::OutOfRange {
                spec: self.text.clone(),
            })
        }
    }

    /// Width in bits: 1 for a bit, 8/16/32 for values.
    pub fn bits(&self) -> u32 {
        match self.address {
            Address::Bit(_) => 1,
            Address::Value { width, .. } => width.bits(),
        }
    }

    /// The raw value in `image` (zero-extended), `None` when the address does not fit it.
    pub fn read(&self, image: &Image) -> Option<u32> {
        read_address(image, &self.address)
    }

    /// The image bytes [`WatchSpec::read`] reads, or `None` when the address does not fit.
    pub fn bytes(&self, layout: &Layout) -> Option<std::ops::Range<usize>> {
        crate::value::read_range(layout, &self.address)
    }

    /// Formats a raw value of this watch.
    pub fn format(&self, raw: u32) -> String {
        let bits = self.bits();
        let mask = if bits == 32 {
            u32::MAX
        } else {
            (1 << bits) - 1
        };
        let raw = raw & mask;
        let signed = || {
            let shift = 32 - bits;
            (((raw << shift) as i32) >> shift).to_string()
        };
        let omron = self.family == Family::Omron;
        match self.format {
            Format::Default if bits <= 8 || omron => raw.to_string(),
            Format::Default | Format::Signed => signed(),
            Format::Unsigned => raw.to_string(),
            Format::Hex if omron => format!("#{:0w$X}", raw, w = (bits as usize).div_ceil(4)),
            Format::Hex => format!("16#{:0w$X}", raw, w = (bits as usize).div_ceil(4)),
            Format::Bin => format!("2#{:0w$b}", raw, w = bits as usize),
            Format::Real => format!("{:?}", f32::from_bits(raw)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_resolver::resolve;
    use crate::value::write_address;
    use stljit_core::ProfileId;
    use stljit_core::ir::BitLoc;

    fn w(text: &str) -> WatchSpec {
        WatchSpec::parse(text, &resolve).unwrap()
    }

    #[test]
    fn default_formats_follow_the_width() {
        assert_eq!(w("I0.0").format(1), "1");
        assert_eq!(w("VB0").format(0xFF), "255");
        assert_eq!(w("VW0").format(0xFFFF), "-1");
        assert_eq!(w("VD0").format(0x8000_0000), "-2147483648");
        assert_eq!(w("T37").format(1), "1");
        assert_eq!(w("T37").bits(), 1);
    }

    #[test]
    fn suffixes() {
        assert_eq!(w("VW0:u").format(0xFFFF), "65535");
        assert_eq!(w("VB0:i").format(0x80), "-128");
        assert_eq!(w("VW0:hex").format(0xAB), "16#00AB");
        assert_eq!(w("VB0:hex").format(0x5), "16#05");
        assert_eq!(w("VD0:hex").format(0x1234_5678), "16#12345678");
        // Omron notation (omron-cp.md §6): words unsigned by default, `#` hex.
        let o = |t| WatchSpec::parse_for(t, &resolve, Family::Omron).unwrap();
        assert_eq!(o("VW0").format(0xFFED), "65517");
        assert_eq!(o("VW0:hex").format(0xAA), "#00AA");
        assert_eq!(o("VW0:i").format(0xFFED), "-19");
        assert_eq!(w("VB0:bin").format(5), "2#00000101");
        assert_eq!(w("VD50:real").format(1.5f32.to_bits()), "1.5");
        assert_eq!(w("VD50:real").format(100f32.to_bits()), "100.0");
        assert_eq!(w("VD50:real").format(0x7FC0_0000), "NaN");
        assert_eq!(w("VD50:real").bits(), 32);
    }

    #[test]
    fn timer_with_a_numeric_suffix_is_its_value() {
        let t = w("T37:i");
        assert_eq!(
            t.address,
            Address::Value {
                loc: Loc {
                    area: Area::TimerValue,
                    offset: 74
                },
                width: Width::Word
            }
        );
        let mut img = Image::blank(ProfileId::A5);
        assert!(write_address(&mut img, &t.address, 0xFFF6));
        assert_eq!(t.read(&img).map(|v| t.format(v)), Some("-10".to_string()));
        assert_eq!(
            w("C5:u").address,
            Address::Value {
                loc: Loc {
                    area: Area::CounterValue,
                    offset: 10
                },
                width: Width::Word
            }
        );
    }

    #[test]
    fn errors() {
        let e = |t| WatchSpec::parse(t, &resolve).unwrap_err();
        assert!(matches!(e("XY1"), WatchError::UnknownAddress { .. }));
        assert!(matches!(e("VW0:float"), WatchError::UnknownFormat { .. }));
        assert!(matches!(e("VW0:real"), WatchError::NotApplicable { .. }));
        assert!(matches!(e("I0.0:hex"), WatchError::NotApplicable { .. }));
        assert!(matches!(e("T37:real"), WatchError::NotApplicable { .. }));
        assert_eq!(
            e("VW0:float").to_string(),
            "watch `VW0:float`: unknown format (use :i, :u, :hex, :bin or :real)"
        );
        let layout = Layout::of(ProfileId::A5);
        assert!(w("VW2498").check(&layout).is_ok());
        assert!(matches!(
            w("VW2499").check(&layout),
            Err(WatchError::OutOfRange { .. })
        ));
        let bit = WatchSpec {
            text: "I16.0".into(),
            address: Address::Bit(BitLoc {
                area: Area::I,
                byte: 16,
                bit: 0,
            }),
            format: Format::Default,
            family: Family::S7,
        };
        assert!(bit.check(&layout).is_err());
    }
}
