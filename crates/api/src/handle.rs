//! Addresses as the embedding API reads and writes them: a [`Handle`] is a name (`I0.0`,
//! `VW100`, `VD50:real`, `T37:i`, a symbol) resolved once against the program's dialect, profile
//! and symbol table, with its [`Type`] and its image offsets computed up front, so that reading
//! or writing through it is a bounds-checked load or store and nothing else.
//!
//! A name's type: bits are [`Type::Bool`]; bytes [`Type::Byte`]; words and dwords are signed
//! for S7 programs and unsigned for Omron ones (the way each dialect's tools show them), and a
//! suffix overrides that: `:i` signed, `:u` (or `:hex`, `:bin`) unsigned, `:real` an IEEE-754
//! binary32 in a dword. A timer or counter alone (`T37`, `C0002`) is its bit; with a numeric
//! suffix (`T37:i`) its current value. This is the syntax of `stljit run --watch`.
//!
//! Writes go where a harness or an HMI writes: an input (`I`, Omron CIO 0–1) to the physical
//! input copy, which the next scan's input refresh copies into the image; anything else into the
//! image at once. Reads show the image (an input as the program saw it in the last scan).

use crate::Error;
use stljit_core::ir::Address;
use stljit_core::layout::Layout;
use stljit_core::{Area, Family, ProfileId, Width};
use stljit_runtime::Image;
use stljit_runtime::mem;
use stljit_sim::{Format, WatchError, WatchSpec, writable, write_offset};

/// What a handle's value is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Type {
    /// A bit: `false`/`true` (0/1).
    Bool,
    /// An unsigned byte (0…255).
    Byte,
    /// A signed word (-32768…32767).
    Int16,
    /// An unsigned word (0…65535).
    UInt16,
    /// A signed dword.
    Int32,
    /// An unsigned dword.
    UInt32,
    /// A dword read as an IEEE-754 binary32.
    Real,
}

impl Type {
    /// The type's name (`bool`, `int16`, `real`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Type::Bool => "bool",
            Type::Byte => "byte",
            Type::Int16 => "int16",
            Type::UInt16 => "uint16",
            Type::Int32 => "int32",
            Type::UInt32 => "uint32",
            Type::Real => "real",
        }
    }

    /// Whether values of this type are integers (every type but `Bool` and `Real`).
    pub fn is_integer(self) -> bool {
        !matches!(self, Type::Bool | Type::Real)
    }

    /// The smallest and largest integer a write accepts: a word or dword takes both its signed
    /// and its unsigned range (`-1` and `65535` are the same word), as stimulus files do.
    pub fn write_range(self) -> (i64, i64) {
        match self {
            Type::Bool => (0, 1),
            Type::Byte => (0, 255),
            Type::Int16 | Type::UInt16 => (i64::from(i16::MIN), i64::from(u16::MAX)),
            Type::Int32 | Type::UInt32 | Type::Real => (i64::from(i32::MIN), i64::from(u32::MAX)),
        }
    }

    /// The range of values a read returns.
    pub fn read_range(self) -> (i64, i64) {
        match self {
            Type::Bool => (0, 1),
            Type::Byte => (0, 255),
            Type::Int16 => (i64::from(i16::MIN), i64::from(i16::MAX)),
            Type::UInt16 => (0, i64::from(u16::MAX)),
            Type::Int32 | Type::Real => (i64::from(i32::MIN), i64::from(i32::MAX)),
            Type::UInt32 => (0, i64::from(u32::MAX)),
        }
    }

    fn of(width: Option<Width>, format: Format, family: Family) -> Type {
        let signed_default = family == Family::S7;
        match (width, format) {
            (None, _) => Type::Bool,
            (Some(Width::Byte), _) => Type::Byte,
            (Some(Width::DWord), Format::Real) => Type::Real,
            (Some(w), f) => {
                let signed = match f {
                    Format::Signed => true,
                    Format::Default => signed_default,
                    _ => false,
                };
                match (w, signed) {
                    (Width::Word, true) => Type::Int16,
                    (Width::Word, false) => Type::UInt16,
                    (_, true) => Type::Int32,
                    (_, false) => Type::UInt32,
                }
            }
        }
    }
}

/// A value read from or written to a [`Handle`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A bit.
    Bool(bool),
    /// An integer (any integer type).
    Int(i64),
    /// A real.
    Real(f64),
}

impl Value {
    /// The value as a float (a bit is 0.0 or 1.0).
    pub fn as_f64(self) -> f64 {
        match self {
            Value::Bool(b) => f64::from(u8::from(b)),
            Value::Int(v) => v as f64,
            Value::Real(v) => v,
        }
    }
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Value::Bool(b) => write!(f, "{}", u8::from(*b)),
            Value::Int(v) => write!(f, "{v}"),
            Value::Real(v) => write!(f, "{v:?}"),
        }
    }
}

/// A resolved address: where to read and write it, and its type.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Handle {
    name: String,
    address: Address,
    ty: Type,
    profile: ProfileId,
    /// Image offset read (the byte holding a bit).
    at: u32,
    /// Image offset written (the physical input copy for inputs).
    write_at: u32,
    /// Bit number for bits.
    bit: u8,
    /// Why the address may not be written or forced, if so.
    read_only: Option<&'static str>,
}

impl Handle {
    /// Resolves `name` (an address, a symbol, optionally with a `:i`/`:u`/`:real` suffix)
    /// with `resolve`, for an image of `layout`.
    pub(crate) fn resolve(
        name: &str,
        layout: &Layout,
        resolve: &dyn Fn(&str) -> Result<Address, String>,
    ) -> Result<Handle, Error> {
        let profile = layout.profile.profile();
        let spec = WatchSpec::parse_for(name, resolve, profile.family).map_err(|e| {
            let reason = match e {
                WatchError::UnknownAddress { reason, .. } => reason,
                WatchError::UnknownFormat { .. } => {
                    "unknown type suffix (use :i, :u or :real)".to_string()
                }
                WatchError::NotApplicable { reason, .. } => reason.to_string(),
                WatchError::OutOfRange { .. } => "outside the memory image".to_string(),
            };
            Error::Address {
                name: name.trim().to_string(),
                reason,
            }
        })?;
        let out_of_range = || Error::Address {
            name: spec.text.clone(),
            reason: "outside the memory image".to_string(),
        };
        spec.check(layout).map_err(|_| out_of_range())?;
        let (width, bit, at) = match spec.address {
            Address::Bit(b) => (
                None,
                b.bit,
                stljit_runtime::image::bit_addr(layout, b, 0).ok_or_else(out_of_range)?,
            ),
            Address::Value { loc, width } => (
                Some(width),
                0,
                stljit_runtime::image::loc_addr(layout, loc, width, 0).ok_or_else(out_of_range)?,
            ),
        };
        let write_at = write_offset(layout, &spec.address).ok_or_else(out_of_range)?;
        Ok(Handle {
            ty: Type::of(width, spec.format, profile.family),
            read_only: writable(&spec.address, profile.special_memory_read_only),
            name: spec.text,
            address: spec.address,
            profile: layout.profile,
            at,
            write_at,
            bit,
        })
    }

    /// The name as written (`VD50:real`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The address.
    pub fn address(&self) -> &Address {
        &self.address
    }

    /// The value type.
    pub fn ty(&self) -> Type {
        self.ty
    }

    /// Whether the address is an input (driven through the physical input copy).
    pub fn is_input(&self) -> bool {
        self.area() == Area::I
    }

    /// The memory area.
    pub fn area(&self) -> Area {
        match self.address {
            Address::Bit(b) => b.area,
            Address::Value { loc, .. } => loc.area,
        }
    }

    /// `Err` unless the handle may be written or forced.
    pub fn check_writable(&self) -> Result<(), Error> {
        match self.read_only {
            None => Ok(()),
            Some(reason) => Err(Error::NotWritable {
                name: self.name.clone(),
                reason,
            }),
        }
    }

    fn width(&self) -> Option<Width> {
        match self.address {
            Address::Bit(_) => None,
            Address::Value { width, .. } => Some(width),
        }
    }

    /// `Err` unless the handle was made for an image like `image`.
    pub(crate) fn check_image(&self, image: &Image) -> Result<(), Error> {
        if image.layout().profile == self.profile {
            Ok(())
        } else {
            Err(Error::Foreign {
                what: format!("handle `{}`", self.name),
            })
        }
    }

    /// The raw bits at `offset` (the read or the write offset).
    pub(crate) fn load(&self, bytes: &[u8], offset: u32) -> u32 {
        match self.width() {
            None => u32::from(mem::get_bit(bytes, offset, self.bit)),
            Some(w) => mem::get_be(bytes, offset, w),
        }
    }

    /// Stores raw bits at `offset`.
    pub(crate) fn store(&self, bytes: &mut [u8], offset: u32, raw: u32) {
        match self.width() {
            None => mem::set_bit(bytes, offset, self.bit, raw & 1 != 0),
            Some(w) => mem::set_be(bytes, offset, w, raw),
        }
    }

    /// The image offset reads come from.
    pub(crate) fn read_offset(&self) -> u32 {
        self.at
    }

    /// The image offset writes go to.
    pub(crate) fn write_offset(&self) -> u32 {
        self.write_at
    }

    /// The value of raw bits of this handle.
    pub fn decode(&self, raw: u32) -> Value {
        match self.ty {
            Type::Bool => Value::Bool(raw & 1 != 0),
            Type::Byte | Type::UInt16 | Type::UInt32 => Value::Int(i64::from(raw)),
            Type::Int16 => Value::Int(i64::from(raw as u16 as i16)),
            Type::Int32 => Value::Int(i64::from(raw as i32)),
            Type::Real => Value::Real(f64::from(f32::from_bits(raw))),
        }
    }

    /// The raw bits of `value` for this handle, or why it does not fit.
    pub fn encode(&self, value: Value) -> Result<u32, Error> {
        let bad = |reason: String| Error::Value {
            name: self.name.clone(),
            reason,
        };
        let int = |v: i64| -> Result<u32, Error> {
            let (lo, hi) = self.ty.write_range();
            if v < lo || v > hi {
                return Err(bad(format!(
                    "{v} does not fit {} ({lo}…{hi})",
                    self.describe()
                )));
            }
            Ok(v as u32)
        };
        match (self.ty, value) {
            (Type::Real, Value::Real(v)) => Ok((v as f32).to_bits()),
            (Type::Real, Value::Int(v)) => Ok((v as f32).to_bits()),
            (Type::Real, Value::Bool(_)) => Err(bad("a real needs a number, not a bool".into())),
            (_, Value::Bool(b)) => Ok(u32::from(b)),
            (_, Value::Int(v)) => int(v),
            (_, Value::Real(v)) => {
                if v.fract() == 0.0 && v.is_finite() {
                    int(v as i64)
                } else {
                    Err(bad(format!(
                        "{v} is not an integer, and {} holds integers (a real needs a dword \
                         with :real)",
                        self.describe()
                    )))
                }
            }
        }
    }

    fn describe(&self) -> &'static str {
        match self.ty {
            Type::Bool => "a bit",
            Type::Byte => "a byte",
            Type::Int16 | Type::UInt16 => "a word",
            Type::Int32 | Type::UInt32 => "a dword",
            Type::Real => "a real",
        }
    }
}
