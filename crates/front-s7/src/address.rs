//! Single addresses for the CLI's stimulus and watch options (`I0.3`, `VW100`, `T37`, a symbol
//! of the project table or of the CPU's system symbols, `Always_On`).

use crate::classes::{BitClass, Cx, Val};
use crate::lexer::Tok;
use crate::operand::Syn;
use crate::symbols::SymbolTable;
use stljit_core::ir::{BitLoc, Operand};
use stljit_core::{CpuProfile, FileId, Width};

pub use stljit_core::ir::Address;

pub use stljit_source::AddressError;

/// Parses one address against `profile` (and `symbols`, for names). `T37`/`C5` mean the bit;
/// `ACn` the whole dword.
pub fn parse_address(
    text: &str,
    profile: &CpuProfile,
    symbols: Option<&SymbolTable>,
) -> Result<Address, AddressError> {
    let text = text.trim();
    let profile: &'static CpuProfile = profile.id.profile();
    let mut cx = Cx {
        profile,
        symbols,
        system: crate::system_symbols::table(profile.id),
        locals: None,
        diags: Vec::new(),
        file: FileId(0),
        line: 1,
        file_names: Vec::new(),
    };
    let tok = Tok {
        text,
        col: 1,
        len: u32::try_from(text.chars().count()).unwrap_or(u32::MAX),
    };
    let result = match cx.scope().resolve(text).map(|r| r.syn) {
        Ok(Syn::Bit { .. } | Syn::Timer(_) | Syn::Counter(_)) => {
            cx.bit(tok, BitClass::Read).map(Address::Bit)
        }
        Ok(Syn::Mem { width, .. }) => value(&mut cx, tok, width),
        Ok(Syn::Acc(_) | Syn::Hc(_)) => value(&mut cx, tok, Width::DWord),
        Ok(other) => {
            return Err(AddressError {
                message: format!("`{text}` is {}, not an address", other.describe()),
            });
        }
        Err(_) => cx.syn(tok).map(|_| {
            Address::Bit(BitLoc {
                area: stljit_core::Area::I,
                byte: 0,
                bit: 0,
            })
        }),
    };
    match (result, cx.diags.first()) {
        (Ok(a), None) => Ok(a),
        (_, Some(d)) => Err(AddressError {
            message: match &d.help {
                Some(h) => format!("{} ({h})", d.message),
                None => d.message.clone(),
            },
        }),
        (Err(_), None) => Err(AddressError {
            message: format!("`{text}` is not an address"),
        }),
    }
}

fn value(cx: &mut Cx<'_>, tok: Tok<'_>, width: Width) -> Result<Address, crate::classes::Reported> {
    match cx.value(tok, Val::input(width))? {
        Operand::Mem(loc) => Ok(Address::Value { loc, width }),
        _ => Err(crate::classes::Reported),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ProfileId;
    use stljit_core::{Area, ir::Loc};

    fn a5(t: &str) -> Result<Address, AddressError> {
        parse_address(t, ProfileId::A5.profile(), None)
    }

    #[test]
    fn addresses() {
        assert_eq!(
            a5("I0.3"),
            Ok(Address::Bit(BitLoc {
                area: Area::I,
                byte: 0,
                bit: 3
            }))
        );
        assert_eq!(
            a5("T37"),
            Ok(Address::Bit(BitLoc {
                area: Area::TimerBit,
                byte: 37,
                bit: 0
            }))
        );
        assert_eq!(
            a5("C5"),
            Ok(Address::Bit(BitLoc {
                area: Area::CounterBit,
                byte: 5,
                bit: 0
            }))
        );
        assert_eq!(
            a5("VW100"),
            Ok(Address::Value {
                loc: Loc {
                    area: Area::V,
                    offset: 100
                },
                width: Width::Word
            })
        );
        assert_eq!(
            a5("AIW0"),
            Ok(Address::Value {
                loc: Loc {
                    area: Area::AI,
                    offset: 0
                },
                width: Width::Word
            })
        );
        assert_eq!(
            a5("AC0"),
            Ok(Address::Value {
                loc: Loc {
                    area: Area::AC,
                    offset: 0
                },
                width: Width::DWord
            })
        );
        assert_eq!(
            a5("SMB28"),
            Ok(Address::Value {
                loc: Loc {
                    area: Area::SM,
                    offset: 28
                },
                width: Width::Byte
            })
        );
        assert_eq!(
            a5("VD50"),
            Ok(Address::Value {
                loc: Loc {
                    area: Area::V,
                    offset: 50
                },
                width: Width::DWord
            })
        );
        assert!(a5("Q16.0").is_err());
        assert!(a5("VW2499").is_err());
        assert!(a5("Motor").is_err());
        assert!(a5("+5").is_err());
    }
}
