//! What a program touches, for defaults that a PLC engineer expects: the outputs shown in the
//! run summary and the I/Q/M bits traced when no `--watch` is given. Names come from the symbol
//! table when one was given.

use std::collections::{BTreeSet, HashMap};
use stljit_core::ir::{Address, BitLoc, BoxOp, Contact, Loc, Op, Operand, Program};
use stljit_core::{Area, Width};
use stljit_front::{Dialect, Symbols};
use stljit_runtime::Image;
use stljit_sim::read_address;

/// Every bit the program reads or writes in I, Q or M, in address order.
pub(crate) fn io_bits(program: &Program) -> Vec<BitLoc> {
    let mut bits = BTreeSet::new();
    let mut note = |b: BitLoc| {
        if matches!(b.area, Area::I | Area::Q | Area::M) {
            bits.insert((b.area, b.byte, b.bit));
        }
    };
    for op in program.pous.iter().flat_map(|p| &p.ops) {
        match op {
            Op::Load(c) | Op::And(c) | Op::Or(c) => {
                if let Contact::Bit { bit, .. } | Contact::ImmediateInput { bit, .. } = c {
                    note(*bit);
                }
            }
            Op::Assign { bit, .. } => note(*bit),
            Op::SetRange { start, .. } => note(*start),
            _ => {}
        }
    }
    bits.into_iter()
        .map(|(area, byte, bit)| BitLoc { area, byte, bit })
        .collect()
}

/// The outputs the program writes: Q bits, Q bytes/words/dwords and AQ words, in address order.
pub(crate) fn outputs(program: &Program) -> Vec<Address> {
    let mut out = BTreeSet::new();
    let value = |o: &Operand, width: Width| match o {
        Operand::Mem(loc) if matches!(loc.area, Area::Q | Area::AQ) => {
            Some(Key::Value(loc.area, loc.offset, width))
        }
        _ => None,
    };
    for op in program.pous.iter().flat_map(|p| &p.ops) {
        match op {
            Op::Assign { bit, .. } | Op::SetRange { start: bit, .. } if bit.area == Area::Q => {
                out.insert(Key::Bit(bit.byte, bit.bit));
            }
            Op::Box(b) => match b {
                BoxOp::Move { width, dst, .. } => out.extend(value(dst, *width)),
                BoxOp::ImmediateWrite { output, .. } => {
                    out.insert(Key::Value(Area::Q, *output, Width::Byte));
                }
                _ => {}
            },
            _ => {}
        }
    }
    out.into_iter().map(Key::address).collect()
}

#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Key {
    Bit(u32, u8),
    Value(Area, u32, Width),
}

impl Key {
    fn address(self) -> Address {
        match self {
            Key::Bit(byte, bit) => Address::Bit(BitLoc {
                area: Area::Q,
                byte,
                bit,
            }),
            Key::Value(area, offset, width) => Address::Value {
                loc: Loc { area, offset },
                width,
            },
        }
    }
}

/// Names for addresses: the symbol when the table has one, else the address itself.
pub(crate) struct Names {
    by_address: HashMap<Address, String>,
    dialect: Dialect,
}

impl Names {
    /// Reverse index of a symbol table (resolving each symbol against the program's profile).
    pub(crate) fn new(program: &Program, dialect: Dialect, symbols: Option<&Symbols>) -> Names {
        let mut by_address = HashMap::new();
        if let Some(table) = symbols {
            for name in table.names() {
                if let Ok(a) = dialect.parse_address(name, program.profile, Some(table)) {
                    by_address.entry(a).or_insert_with(|| name.to_string());
                }
            }
        }
        Names {
            by_address,
            dialect,
        }
    }

    /// `Car_Red (Q0.0)` or `Q0.0`.
    pub(crate) fn name(&self, a: &Address) -> String {
        let plain = self.dialect.print_address(a);
        match self.by_address.get(a) {
            Some(sym) => format!("{sym} ({plain})"),
            None => plain,
        }
    }

    /// The symbol if there is one, else the address: something `--watch` accepts.
    pub(crate) fn watch_name(&self, a: &Address) -> String {
        self.by_address
            .get(a)
            .cloned()
            .unwrap_or_else(|| self.dialect.print_address(a))
    }
}

/// `(name, value)` of each address after the run: bits 0/1, values signed decimal.
pub(crate) fn describe(
    addresses: &[Address],
    image: &Image,
    names: &Names,
) -> Vec<(String, String)> {
    addresses
        .iter()
        .map(|a| {
            let raw = read_address(image, a);
            let value = match (a, raw) {
                (_, None) => "?".to_string(),
                (Address::Bit(_), Some(v)) => v.to_string(),
                (
                    Address::Value {
                        width: Width::Byte, ..
                    },
                    Some(v),
                ) => v.to_string(),
                (
                    Address::Value {
                        width: Width::Word, ..
                    },
                    Some(v),
                ) => (v as u16 as i16).to_string(),
                (
                    Address::Value {
                        width: Width::DWord,
                        ..
                    },
                    Some(v),
                ) => (v as i32).to_string(),
            };
            (names.name(a), value)
        })
        .collect()
}
