//! Expectations on the L memory of a call level, for the cases of subroutine parameters
//! (s7-200-more §12 M1 lists the callee's frame): `frame = { 1 = { "LW9" = 300 } }` in a
//! `[[scan]]` reads L memory of nesting level 1 (0 is the main program's frame), which no watch
//! spec can name.

use stljit_core::Area;
use stljit_core::ir::Address;
use stljit_runtime::Image;
use stljit_sim::ValueKind;
use toml::{Table, Value};

/// One expected L value: frame, the address as written, the address, the raw value.
pub(crate) struct FrameExpect {
    frame: u32,
    text: String,
    address: Address,
    want: u32,
}

/// Reads a scan's `frame` table.
pub(crate) fn parse(
    t: &Table,
    resolve: &dyn Fn(&str) -> Result<Address, String>,
    raw_value: &dyn Fn(&Value, ValueKind) -> Result<u32, String>,
) -> Result<Vec<FrameExpect>, String> {
    let mut out = Vec::new();
    for (k, t) in t {
        let frame: u32 = k
            .parse()
            .ok()
            .filter(|&f| f < stljit_core::layout::L_FRAMES)
            .ok_or(format!("frame: `{k}` is not a frame number 0 .. 8"))?;
        let Value::Table(t) = t else {
            return Err(format!("frame {k}: must be a table of L addresses"));
        };
        for (name, v) in t {
            let address = resolve(name).map_err(|e| format!("frame {k}: `{name}`: {e}"))?;
            let area = match address {
                Address::Bit(b) => b.area,
                Address::Value { loc, .. } => loc.area,
            };
            if area != Area::L {
                return Err(format!("frame {k}: `{name}` is not an L address"));
            }
            let want = raw_value(v, ValueKind::of(&address))
                .map_err(|e| format!("frame {k}: `{name}`: {e}"))?;
            out.push(FrameExpect {
                frame,
                text: name.clone(),
                address,
                want,
            });
        }
    }
    Ok(out)
}

/// Every mismatch as `(what, detail)`.
pub(crate) fn check(image: &Image, expects: &[FrameExpect]) -> Vec<(String, String)> {
    expects
        .iter()
        .filter_map(|e| {
            let got = read(image, e.frame, &e.address);
            (got != Some(e.want)).then(|| {
                (
                    format!("frame {} {}", e.frame, e.text),
                    format!("expected {}, got {got:?}", e.want),
                )
            })
        })
        .collect()
}

/// Reads an L address of call frame `frame`.
fn read(image: &Image, frame: u32, address: &Address) -> Option<u32> {
    let l = image.layout();
    let bytes = image.bytes();
    match *address {
        Address::Bit(b) => {
            let at = l.addr(Area::L, b.byte, frame) as usize;
            bytes.get(at).map(|v| u32::from(v >> b.bit & 1))
        }
        Address::Value { loc, width } => {
            let at = l.addr(Area::L, loc.offset, frame) as usize;
            let v = bytes.get(at..at + width.bytes() as usize)?;
            Some(v.iter().fold(0, |acc, &b| acc << 8 | u32::from(b)))
        }
    }
}
