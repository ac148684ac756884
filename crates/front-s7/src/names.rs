//! Name resolution: what an operand's text names, in which order (s7-200-more §1.3, §2).
//!
//! Address and constant syntax comes first (`operand::parse_syn`). `#name` is a local variable of
//! the block; an unprefixed name is looked up in the block's locals (a local hides a global of the
//! same name inside its POU), then in the project symbol table, then in the CPU's system symbols
//! (so the project table overrides a system name). `symbol:address` — MicroWIN's "symbol and
//! address" view — is the address, after checking that the symbol names it. `"quoted"` names go
//! to the symbol tables only; `&x` and `*x` resolve `x` first.

use crate::locals::Locals;
use crate::operand::{Syn, SynError, address_of, indirect, parse_syn};
use crate::symbols::{SymTarget, SymbolTable};

/// What names are visible where an operand is resolved.
#[derive(Clone, Copy)]
pub(crate) struct Scope<'a> {
    /// The project symbol table, if one was given.
    pub(crate) user: Option<&'a SymbolTable>,
    /// The CPU profile's system symbols.
    pub(crate) system: &'a SymbolTable,
    /// The current block's local variables.
    pub(crate) locals: Option<&'a Locals>,
}

/// How a name was found, for the warnings a resolution may deserve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Via {
    /// Address or constant syntax, or a symbol.
    Plain,
    /// A local variable written without `#` (`hides` a global of the same name).
    BareLocal {
        /// A symbol table also defines the name.
        hides: bool,
    },
    /// `symbol:address` whose symbol no table defines: the address was used unchecked.
    Unchecked,
}

/// A resolved operand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Resolved {
    /// What it names.
    pub(crate) syn: Syn,
    /// How.
    pub(crate) via: Via,
}

/// Why an operand could not be resolved.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum ResolveError {
    /// Looks like an address or constant but is malformed.
    Malformed(&'static str),
    /// Neither an address nor a known symbol.
    UnknownSymbol(String),
    /// `#name` that the block does not declare.
    UnknownLocal(String),
    /// `#v.3`: a bit of a local variable; the absolute L bit, if the variable is a byte or wider.
    LocalBit(String, Option<String>),
    /// A symbol that names a POU where a memory operand is needed.
    PouSymbol(String),
    /// A symbol whose definition was rejected (already reported).
    Invalid,
    /// `symbol:address` whose symbol names `names`, not the `written` address.
    Mismatch {
        /// The symbol.
        symbol: String,
        /// What it names.
        names: Syn,
        /// The address written after it.
        written: Syn,
    },
}

/// Strips the quotes of a `"quoted symbol"`.
pub(crate) fn unquote(t: &str) -> Option<&str> {
    t.strip_prefix('"')?.strip_suffix('"')
}

fn plain(syn: Syn) -> Resolved {
    Resolved {
        syn,
        via: Via::Plain,
    }
}

impl Scope<'_> {
    /// A name of the symbol tables: the project's first, then the system's.
    fn global(&self, name: &str) -> Option<&SymTarget> {
        self.user
            .and_then(|t| t.get(name))
            .or_else(|| self.system.get(name))
    }

    fn lookup_global(&self, name: &str) -> Result<Syn, ResolveError> {
        match self.global(name) {
            Some(SymTarget::Operand(syn)) => Ok(*syn),
            Some(SymTarget::Pou(_)) => Err(ResolveError::PouSymbol(name.to_owned())),
            Some(SymTarget::Invalid) => Err(ResolveError::Invalid),
            None => Err(ResolveError::UnknownSymbol(name.to_owned())),
        }
    }

    /// An unprefixed name: a local of the block, else a global symbol.
    fn lookup_name(&self, name: &str) -> Result<Resolved, ResolveError> {
        if let Some(local) = self.locals.and_then(|l| l.get(name)) {
            if !local.valid {
                return Err(ResolveError::Invalid);
            }
            return Ok(Resolved {
                syn: local.syn(),
                via: Via::BareLocal {
                    hides: self.global(name).is_some(),
                },
            });
        }
        self.lookup_global(name).map(plain)
    }

    /// `#name` (without the `#`).
    fn lookup_local(&self, name: &str) -> Result<Resolved, ResolveError> {
        let locals = self.locals;
        if let Some(local) = locals.and_then(|l| l.get(name)) {
            return if local.valid {
                Ok(plain(local.syn()))
            } else {
                Err(ResolveError::Invalid)
            };
        }
        // `#v.3`: a bit of a declared variable.
        if let Some((var, bit)) = name.rsplit_once('.')
            && let Some(local) = locals.and_then(|l| l.get(var))
        {
            let absolute = match local.syn() {
                Syn::Mem { offset, .. } if matches!(bit.as_bytes(), [b'0'..=b'7']) => {
                    Some(format!("L{offset}.{bit}"))
                }
                _ => None,
            };
            return Err(ResolveError::LocalBit(format!("#{name}"), absolute));
        }
        Err(ResolveError::UnknownLocal(format!("#{name}")))
    }

    /// Resolves operand text (see the module doc for the order).
    pub(crate) fn resolve(&self, t: &str) -> Result<Resolved, ResolveError> {
        if let Some(name) = unquote(t) {
            return self.lookup_global(name).map(plain);
        }
        if let Some(name) = t.strip_prefix('#') {
            return self.lookup_local(name);
        }
        for (sigil, wrap) in [('&', address_of as fn(Syn) -> _), ('*', indirect)] {
            if let Some(inner) = t.strip_prefix(sigil) {
                let r = self.resolve(inner.trim_start())?;
                let syn = wrap(r.syn).map_err(|e| match e {
                    SynError::Malformed(m) => ResolveError::Malformed(m),
                    SynError::NotAddress => ResolveError::Malformed("bad operand"),
                })?;
                return Ok(Resolved { syn, ..r });
            }
        }
        if let Some(r) = self.symbol_and_address(t) {
            return r;
        }
        match parse_syn(t) {
            Ok(s) => Ok(plain(s)),
            Err(SynError::NotAddress) => self.lookup_name(t),
            // A symbol may look like a broken address (`M1_Run`); prefer the symbol when it
            // exists.
            Err(SynError::Malformed(m)) => {
                self.lookup_name(t).map_err(|_| ResolveError::Malformed(m))
            }
        }
    }

    /// `symbol:address`, when the text after the last `:` is an address: the address, checked
    /// against what the symbol names (an unknown symbol leaves the address unchecked). `None`
    /// when the text is not of that form.
    fn symbol_and_address(&self, t: &str) -> Option<Result<Resolved, ResolveError>> {
        let (symbol, address) = t.rsplit_once(':')?;
        let (symbol, address) = (symbol.trim_end(), address.trim_start());
        let written = match parse_syn(address) {
            Ok(Syn::Const(_)) | Err(_) => return None,
            Ok(s) => s,
        };
        if symbol.is_empty() {
            return None;
        }
        Some(match self.resolve(symbol) {
            Ok(r) if r.syn == written => Ok(Resolved { syn: written, ..r }),
            Ok(r) => Err(ResolveError::Mismatch {
                symbol: symbol.to_owned(),
                names: r.syn,
                written,
            }),
            Err(ResolveError::UnknownSymbol(_)) => Ok(Resolved {
                syn: written,
                via: Via::Unchecked,
            }),
            Err(e) => Err(e),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::{Area, FileId, ProfileId};

    fn bit(area: Area, byte: u32, bit: u8) -> Syn {
        Syn::Bit { area, byte, bit }
    }

    #[test]
    fn project_table_overrides_system_names() {
        let system = crate::system_symbols::table(ProfileId::Smart);
        let (user, d) = SymbolTable::parse("Always_On\tM0.0\n启动\tI0.1\n", FileId(1));
        assert!(d.is_empty());
        let with = Scope {
            user: Some(&user),
            system,
            locals: None,
        };
        let without = Scope { user: None, ..with };
        let syn = |s: &Scope<'_>, t: &str| s.resolve(t).map(|r| r.syn);
        assert_eq!(syn(&with, "Always_On"), Ok(bit(Area::M, 0, 0)));
        assert_eq!(syn(&without, "Always_On"), Ok(bit(Area::SM, 0, 0)));
        assert_eq!(syn(&with, "First_Scan_On"), Ok(bit(Area::SM, 0, 1)));
        assert_eq!(
            syn(&without, "Motor"),
            Err(ResolveError::UnknownSymbol("Motor".into()))
        );
        assert_eq!(
            syn(&without, "\"Start Button\""),
            Err(ResolveError::UnknownSymbol("Start Button".into()))
        );
    }

    #[test]
    fn symbol_and_address_is_checked() {
        let system = crate::system_symbols::table(ProfileId::Smart);
        let (user, _) = SymbolTable::parse("启动\tI0.1\n", FileId(1));
        let s = Scope {
            user: Some(&user),
            system,
            locals: None,
        };
        assert_eq!(
            s.resolve("启动:I0.1").map(|r| r.syn),
            Ok(bit(Area::I, 0, 1))
        );
        assert_eq!(
            s.resolve("Always_On:SM0.0").map(|r| r.syn),
            Ok(bit(Area::SM, 0, 0))
        );
        assert!(matches!(
            s.resolve("启动:I0.2"),
            Err(ResolveError::Mismatch { .. })
        ));
        assert_eq!(
            s.resolve("Unknown:Q0.1"),
            Ok(Resolved {
                syn: bit(Area::Q, 0, 1),
                via: Via::Unchecked
            })
        );
    }
}
