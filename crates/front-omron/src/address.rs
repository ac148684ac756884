//! Single addresses in Omron spelling for stimulus files and watch lists: [`parse_address`]
//! (an address or a symbol; `T0005`/`C0002` mean the completion flag) and its inverse
//! [`print_address`] (`0.00`, `100.02`, `W3.15`, `D10`, `T0005`, `A200.11`, `P_EQ`, `TR0`).

use crate::lexer::Tok;
use crate::operand::{FLAGS, Syn, area_prefix};
use crate::resolve::Cx;
use crate::symbols::SymbolTable;
use stljit_core::ir::{Address, Operand};
use stljit_core::omron::{word_bit, word_of};
use stljit_core::{Area, FileId, ProfileId, Width};

pub use stljit_source::AddressError;

/// Parses one address (or a symbol of `symbols`) against the Omron `profile`. Words are
/// `Address::Value` of width `Word`; `Tn`/`Cn` are the completion flags.
pub fn parse_address(
    text: &str,
    profile: ProfileId,
    symbols: Option<&SymbolTable>,
) -> Result<Address, AddressError> {
    let text = text.trim();
    let mut cx = Cx {
        profile: profile.profile(),
        symbols,
        diags: Vec::new(),
        file: FileId(0),
        line: 1,
        mn: "an address".into(),
        options: crate::Options::default(),
    };
    let tok = Tok {
        text: text.to_owned(),
        col: 1,
        len: u32::try_from(text.chars().count()).unwrap_or(u32::MAX),
    };
    let result = match cx.syn(&tok) {
        Ok(Syn::Word { .. }) => match cx.word(&tok, 1, false) {
            Ok(Operand::Mem(loc)) => Ok(Address::Value {
                loc,
                width: Width::Word,
            }),
            _ => Err(()),
        },
        Ok(Syn::Tr(n)) if n < 16 => Ok(Address::Bit(stljit_core::omron::tr_bit(n as u8))),
        Ok(Syn::Const(..)) => {
            return Err(AddressError {
                message: format!("`{text}` is a constant, not an address"),
            });
        }
        Ok(_) => cx.bit(&tok, false).map(Address::Bit).map_err(|_| ()),
        Err(_) => Err(()),
    };
    match (result, cx.diags.first()) {
        (Ok(a), None) => Ok(a),
        (_, Some(d)) => Err(AddressError {
            message: d.message.trim_start_matches("line 1: ").to_owned(),
        }),
        (Err(()), None) => Err(AddressError {
            message: format!("`{text}` is not an address"),
        }),
    }
}

/// The Omron spelling of `address` on the CP profiles (which share one I/O layout); the
/// inverse of [`parse_address`]. Locations no Omron operand names print as `?area+offset`.
pub fn print_address(address: &Address) -> String {
    let profile = ProfileId::Cp1h.profile();
    match *address {
        Address::Bit(b) => match b.area {
            Area::TimerBit => format!("T{:04}", b.byte),
            Area::CounterBit => format!("C{:04}", b.byte),
            Area::Flags => FLAGS
                .iter()
                .find(|(_, f)| f.bit_loc() == b)
                .map_or_else(|| unnamed(b.area, b.byte), |(n, _)| (*n).to_owned()),
            Area::Tr => format!("TR{}", b.byte * 8 + u32::from(b.bit)),
            _ => {
                let (loc, bit) = word_bit(b);
                match word_of(profile, loc) {
                    Some((area, w)) => format!("{}{w}.{bit:02}", area_prefix(area)),
                    None => unnamed(b.area, b.byte),
                }
            }
        },
        Address::Value { loc, .. } => match loc.area {
            Area::TimerValue => format!("T{:04}", loc.offset / 2),
            Area::CounterValue => format!("C{:04}", loc.offset / 2),
            _ => match word_of(profile, loc) {
                Some((area, w)) => format!("{}{w}", area_prefix(area)),
                None => unnamed(loc.area, loc.offset),
            },
        },
    }
}

fn unnamed(area: Area, offset: u32) -> String {
    format!("?{area:?}+{offset}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ir::{BitLoc, Loc};
    use stljit_core::omron::SystemBit;

    fn cp1h(t: &str) -> Result<Address, AddressError> {
        parse_address(t, ProfileId::Cp1h, None)
    }

    #[test]
    fn spellings_round_trip() {
        for t in [
            "0.00", "1.15", "100.02", "102.09", "W3.15", "H10.15", "A200.11", "D10", "100", "W5",
            "T0005", "C0002", "P_EQ", "P_On", "TR3",
        ] {
            let a = cp1h(t).unwrap_or_else(|e| panic!("{t}: {e}"));
            assert_eq!(print_address(&a), t);
        }
    }

    #[test]
    fn parsed_locations_follow_the_omron_mapping() {
        // CIO 0 is input word 0 (area I); bit 00 is the LSB, bit 0 of byte 1 (core::omron).
        assert_eq!(
            cp1h("0.00"),
            Ok(Address::Bit(BitLoc {
                area: Area::I,
                byte: 1,
                bit: 0
            }))
        );
        // CIO 100 is output word 0; bit 02.
        assert_eq!(
            cp1h("100.02"),
            Ok(Address::Bit(BitLoc {
                area: Area::Q,
                byte: 1,
                bit: 2
            }))
        );
        assert_eq!(
            cp1h("D10"),
            Ok(Address::Value {
                loc: Loc {
                    area: Area::Dm,
                    offset: 20
                },
                width: Width::Word
            })
        );
        assert_eq!(
            cp1h("T0005"),
            Ok(Address::Bit(BitLoc {
                area: Area::TimerBit,
                byte: 5,
                bit: 0
            }))
        );
        assert_eq!(cp1h("P_First_Cycle"), cp1h("A200.11"));
        assert_eq!(cp1h("P_EQ"), Ok(Address::Bit(SystemBit::Eq.bit_loc())));
        assert!(cp1h("W600").is_err());
        assert!(parse_address("D2048", ProfileId::Cp1e, None).is_err());
        assert!(cp1h("#0001").is_err());
        assert!(cp1h("Motor").is_err());
    }

    #[test]
    fn symbols_name_addresses() {
        let (t, d) = SymbolTable::parse("Start_PB\tBOOL\t0.00\tstart button\n", FileId(0));
        assert!(d.is_empty());
        assert_eq!(
            parse_address("Start_PB", ProfileId::Cp1h, Some(&t)),
            cp1h("0.00")
        );
    }
}
