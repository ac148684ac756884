//! The physical outputs of a case (s7-200-more §9.5, §11.2 `q_phys`): `phys_q = { "Q0.0" = 1 }`
//! in a `[[scan]]` is the bit the harness sees at the output terminals after the scan, which a
//! running pulse generator drives instead of the image bit (`expect = { "Q0.0" = … }` reads the
//! image).

use stljit_runtime::Image;
use toml::{Table, Value};

/// Reads a scan's `phys_q` table: `(name, byte, bit, level)`.
pub(crate) fn parse(t: &Table) -> Result<Vec<(String, u32, u8, bool)>, String> {
    let mut out = Vec::new();
    for (k, v) in t {
        let bad = || format!("phys_q: `{k}` is not an output bit like \"Q0.0\"");
        let (byte, bit) = k
            .strip_prefix('Q')
            .and_then(|r| r.split_once('.'))
            .ok_or_else(bad)?;
        let byte: u32 = byte.parse().map_err(|_| bad())?;
        let bit: u8 = bit.parse().ok().filter(|b| *b < 8).ok_or_else(bad)?;
        let level = match v {
            Value::Integer(0) => false,
            Value::Integer(1) => true,
            _ => return Err(format!("phys_q: `{k}` needs 0 or 1")),
        };
        out.push((k.clone(), byte, bit, level));
    }
    Ok(out)
}

/// Every mismatch of the physical output bits as `(what, detail)`.
pub(crate) fn check(image: &Image, want: &[(String, u32, u8, bool)]) -> Vec<(String, String)> {
    let phys = image.phys_out();
    want.iter()
        .filter_map(|(name, byte, bit, level)| {
            let got = phys
                .get(*byte as usize)
                .map(|b| b >> bit & 1 == 1)
                .unwrap_or(false);
            (got != *level).then(|| {
                (
                    format!("phys {name}"),
                    format!("expected {}, got {}", u8::from(*level), u8::from(got)),
                )
            })
        })
        .collect()
}
