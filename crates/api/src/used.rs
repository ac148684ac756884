//! What a program touches: the I/O it reads and writes (the FMU's inputs and outputs), the
//! outputs shown in `stljit run`'s summary, the I/Q/M bits traced when no watch list is given,
//! and names for addresses (the symbol when the table has one).

use std::collections::{BTreeSet, HashMap};
use stljit_core::ir::{Access, Address, BitLoc, BoxOp, Loc, Op, Operand, Program};
use stljit_core::{Area, ProfileId, Width};
use stljit_front::{Dialect, Symbols};
use stljit_runtime::Image;
use stljit_sim::read_address;

/// Every bit the program reads or writes in I, Q or M, in address order.
pub fn io_bits(program: &Program) -> Vec<BitLoc> {
    let mut bits = BTreeSet::new();
    for op in program.pous.iter().flat_map(|p| &p.ops) {
        let bit = match op {
            Op::Load(c) | Op::And(c) | Op::Or(c) => match c {
                stljit_core::ir::Contact::Bit { bit, .. }
                | stljit_core::ir::Contact::ImmediateInput { bit, .. } => Some(*bit),
                stljit_core::ir::Contact::Compare { .. } => None,
            },
            Op::Assign { bit, .. } | Op::SetRange { start: bit, .. } => Some(*bit),
            _ => None,
        };
        if let Some(b) = bit
            && matches!(b.area, Area::I | Area::Q | Area::M)
        {
            bits.insert((b.area, b.byte, b.bit));
        }
    }
    bits.into_iter()
        .map(|(area, byte, bit)| BitLoc { area, byte, bit })
        .collect()
}

/// The outputs the program writes: Q bits, Q bytes/words/dwords and AQ words, in address order.
pub fn outputs(program: &Program) -> Vec<Address> {
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
                out.insert(Key::Bit(Area::Q, bit.byte, bit.bit));
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

/// The process I/O of a program, for a co-simulation interface: the inputs it reads (I bits
/// and I/AI values; Omron CIO 0–1) and the outputs it writes (Q bits and Q/AQ values; Omron CIO
/// 100–101), each list in address order, bits before values of the same area.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ProcessIo {
    /// What the program reads from the process.
    pub inputs: Vec<Address>,
    /// What the program writes to the process.
    pub outputs: Vec<Address>,
}

/// The process I/O `program` uses (every op's bit and value operands, read or written).
pub fn process_io(program: &Program) -> ProcessIo {
    let mut inputs = BTreeSet::new();
    let mut outputs = BTreeSet::new();
    for op in program.pous.iter().flat_map(|p| &p.ops) {
        for (bit, access) in op.bit_uses() {
            let key = Key::Bit(bit.area, bit.byte, bit.bit);
            match (bit.area, access) {
                (Area::I, Access::Read | Access::ReadWrite) => {
                    inputs.insert(key);
                }
                (Area::Q, Access::Write | Access::ReadWrite) => {
                    outputs.insert(key);
                }
                _ => {}
            }
        }
        for u in op.operand_uses().iter() {
            let Operand::Mem(loc) = u.operand else {
                continue;
            };
            let key = Key::Value(loc.area, loc.offset, u.width);
            match (loc.area, u.access) {
                (Area::I | Area::AI, Access::Read | Access::ReadWrite) => {
                    inputs.insert(key);
                }
                (Area::Q | Area::AQ, Access::Write | Access::ReadWrite) => {
                    outputs.insert(key);
                }
                _ => {}
            }
        }
    }
    ProcessIo {
        inputs: inputs.into_iter().map(Key::address).collect(),
        outputs: outputs.into_iter().map(Key::address).collect(),
    }
}

#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Key {
    Bit(Area, u32, u8),
    Value(Area, u32, Width),
}

impl Key {
    fn address(self) -> Address {
        match self {
            Key::Bit(area, byte, bit) => Address::Bit(BitLoc { area, byte, bit }),
            Key::Value(area, offset, width) => Address::Value {
                loc: Loc { area, offset },
                width,
            },
        }
    }
}

/// Names for addresses: the symbol when the table has one, else the address itself.
pub struct Names {
    by_address: HashMap<Address, String>,
    dialect: Dialect,
}

impl Names {
    /// Reverse index of a symbol table (resolving each symbol against `profile`); of two symbols
    /// for one address the first in the table's order wins.
    pub fn new(profile: ProfileId, dialect: Dialect, symbols: Option<&Symbols>) -> Names {
        let mut by_address = HashMap::new();
        if let Some(table) = symbols {
            for name in table.names() {
                if let Ok(a) = dialect.parse_address(name, profile, Some(table)) {
                    by_address.entry(a).or_insert_with(|| name.to_string());
                }
            }
        }
        Names {
            by_address,
            dialect,
        }
    }

    /// The symbol of an address, if the table has one.
    pub fn symbol(&self, a: &Address) -> Option<&str> {
        self.by_address.get(a).map(String::as_str)
    }

    /// The address in the dialect's spelling (`Q0.0`, `100.01`).
    pub fn plain(&self, a: &Address) -> String {
        self.dialect.print_address(a)
    }

    /// `Car_Red (Q0.0)` or `Q0.0`.
    pub fn name(&self, a: &Address) -> String {
        let plain = self.plain(a);
        match self.symbol(a) {
            Some(sym) => format!("{sym} ({plain})"),
            None => plain,
        }
    }

    /// The symbol if there is one, else the address: something a watch list accepts.
    pub fn watch_name(&self, a: &Address) -> String {
        self.symbol(a)
            .map_or_else(|| self.plain(a), ToString::to_string)
    }
}

/// `(name, value)` of each address in `image`: bits 0/1, bytes unsigned, words and dwords
/// signed decimal, `?` for an address outside the image.
pub fn describe(addresses: &[Address], image: &Image, names: &Names) -> Vec<(String, String)> {
    addresses
        .iter()
        .map(|a| {
            let value = match (a, read_address(image, a)) {
                (_, None) => "?".to_string(),
                (Address::Bit(_), Some(v)) => v.to_string(),
                (Address::Value { width, .. }, Some(v)) => match width {
                    Width::Byte => v.to_string(),
                    Width::Word => (v as u16 as i16).to_string(),
                    Width::DWord => (v as i32).to_string(),
                },
            };
            (names.name(a), value)
        })
        .collect()
}
