//! A small address resolver for the simulation's unit tests, so they do not depend on the front
//! end: `I0.3`, `Q1.0`, `M2.1`, `V10.2`, `SM0.1`, `IB1`, `QB0`, `VB0`, `SMB0`, `MW4`, `VW100`,
//! `VD50`, `AIW0`, `HC0`, `LB0`, `T37`, `C5`; and the trace writers' test steps over it.

use crate::driver::{Observer, ScanEvent};
use crate::value::write_address;
use crate::watch::WatchSpec;
use stljit_core::ir::{Address, BitLoc, Loc};
use stljit_core::{Area, ScanStatus, Width};
use stljit_runtime::image::Image;

/// The watches `specs` name, resolved by [`resolve`].
pub(crate) fn watches(specs: &[&str]) -> Vec<WatchSpec> {
    specs
        .iter()
        .map(|t| WatchSpec::parse(t, &resolve).unwrap())
        .collect()
}

/// Writes `bits[i]` (raw bits) to the address of `watches[i]`.
pub(crate) fn write_watches(img: &mut Image, watches: &[WatchSpec], bits: &[u32]) {
    for (w, &v) in watches.iter().zip(bits) {
        write_address(img, &w.address, v);
    }
}

/// Shows `img` to `observer` as scan `k` at `10·k` ms, completed in RUN.
pub(crate) fn observe_scan(observer: &mut impl Observer, img: &Image, k: usize) {
    let e = ScanEvent {
        scan: k as u64,
        t_ms: 10 * k as u64,
        image: img,
        status: ScanStatus::Ok,
    };
    observer.observe(&e).unwrap();
}

pub(crate) fn resolve(name: &str) -> Result<Address, String> {
    let bad = || format!("no such address `{name}`");
    let num = |s: &str| s.parse::<u32>().map_err(|_| bad());
    let value = |area, width, rest: &str| {
        Ok(Address::Value {
            loc: Loc {
                area,
                offset: num(rest)?,
            },
            width,
        })
    };
    for (prefix, area, width) in [
        ("AIW", Area::AI, Width::Word),
        ("SMB", Area::SM, Width::Byte),
        ("SMW", Area::SM, Width::Word),
        ("IB", Area::I, Width::Byte),
        ("QB", Area::Q, Width::Byte),
        ("VB", Area::V, Width::Byte),
        ("LB", Area::L, Width::Byte),
        ("MW", Area::M, Width::Word),
        ("VW", Area::V, Width::Word),
        ("VD", Area::V, Width::DWord),
        ("HC", Area::HC, Width::DWord),
    ] {
        if let Some(rest) = name.strip_prefix(prefix) {
            return value(area, width, rest);
        }
    }
    for (prefix, area) in [("T", Area::TimerBit), ("C", Area::CounterBit)] {
        if let Some(rest) = name.strip_prefix(prefix)
            && let Ok(n) = rest.parse::<u32>()
        {
            return Ok(Address::Bit(BitLoc {
                area,
                byte: n,
                bit: 0,
            }));
        }
    }
    for (prefix, area) in [
        ("SM", Area::SM),
        ("I", Area::I),
        ("Q", Area::Q),
        ("M", Area::M),
        ("V", Area::V),
    ] {
        if let Some(rest) = name.strip_prefix(prefix)
            && let Some((byte, bit)) = rest.split_once('.')
        {
            let bit = num(bit)?;
            if bit > 7 {
                return Err(bad());
            }
            return Ok(Address::Bit(BitLoc {
                area,
                byte: num(byte)?,
                bit: bit as u8,
            }));
        }
    }
    Err(bad())
}
