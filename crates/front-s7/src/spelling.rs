//! How S7 STL spells the IR's areas, widths and timer and counter kinds (`VW`, `SM`, `TONR`,
//! `CTUD`). These are the only copies of the S7 spellings; the IR itself names areas and kinds
//! by its own enums, and other dialects spell them their own way.

use stljit_core::ir::{CounterKind, TimerKind};
use stljit_core::{Area, Width};

/// The area's prefix in STL text (`V`, `SM`, `AI`, `T`, ...).
pub fn area_prefix(area: Area) -> &'static str {
    match area {
        Area::I => "I",
        Area::Q => "Q",
        Area::M => "M",
        Area::S => "S",
        Area::SM => "SM",
        Area::V => "V",
        Area::L => "L",
        Area::AI => "AI",
        Area::AQ => "AQ",
        Area::TimerValue | Area::TimerBit => "T",
        Area::CounterValue | Area::CounterBit => "C",
        Area::HC => "HC",
        Area::AC => "AC",
        // Omron areas have size 0 on every S7 profile, so no S7 program names them; these
        // spellings only keep messages about a foreign IR readable.
        Area::Cio => "CIO",
        Area::Work => "W",
        Area::Holding => "H",
        Area::Aux => "A",
        Area::Dm => "D",
        Area::Flags => "P_",
        Area::Tr => "TR",
        Area::IndexReg => "IR",
        Area::DataReg => "DR",
    }
}

/// The width letter of an address or mnemonic (`B`, `W`, `D`: `VW100`, `MOVD`).
pub fn width_letter(width: Width) -> char {
    match width {
        Width::Byte => 'B',
        Width::Word => 'W',
        Width::DWord => 'D',
    }
}

/// The timer instruction's mnemonic.
pub fn timer_mnemonic(kind: TimerKind) -> &'static str {
    match kind {
        TimerKind::On => "TON",
        TimerKind::Retentive => "TONR",
        TimerKind::Off => "TOF",
    }
}

/// The counter instruction's mnemonic.
pub fn counter_mnemonic(kind: CounterKind) -> &'static str {
    match kind {
        CounterKind::Up => "CTU",
        CounterKind::Down => "CTD",
        CounterKind::UpDown => "CTUD",
    }
}
