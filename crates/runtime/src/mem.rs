//! Bounds-checked access to the raw image bytes.
//!
//! Every runtime function works on `&[u8]`/`&mut [u8]` (so the JIT can hand over its raw image)
//! and must never panic, whatever offset a malformed program produces. Reads outside the buffer
//! yield 0 and writes outside it are dropped; callers that care check ranges first (the
//! interpreter and the pointer resolver do), so these fallbacks only keep a bug from becoming a
//! crash across `extern "C"`.

use stljit_core::Width;
use stljit_core::layout::Layout;

/// Reads one byte (0 when out of range).
#[inline]
pub fn get_u8(img: &[u8], off: u32) -> u8 {
    img.get(off as usize).copied().unwrap_or(0)
}

/// Writes one byte (dropped when out of range).
#[inline]
pub fn set_u8(img: &mut [u8], off: u32, v: u8) {
    if let Some(b) = img.get_mut(off as usize) {
        *b = v;
    }
}

/// Reads `N` bytes at `off` with one range check (all 0 when out of range).
#[inline]
pub fn get_array<const N: usize>(img: &[u8], off: u32) -> [u8; N] {
    let start = off as usize;
    img.get(start..start.saturating_add(N))
        .and_then(|s| <[u8; N]>::try_from(s).ok())
        .unwrap_or([0; N])
}

/// Writes `N` bytes at `off` with one range check (dropped when out of range).
#[inline]
pub fn set_array<const N: usize>(img: &mut [u8], off: u32, v: [u8; N]) {
    let start = off as usize;
    if let Some(s) = img.get_mut(start..start.saturating_add(N)) {
        s.copy_from_slice(&v);
    }
}

/// Reads a big-endian value of `width` bits, zero-extended to `u32`.
#[inline]
pub fn get_be(img: &[u8], off: u32, width: Width) -> u32 {
    match width {
        Width::Byte => u32::from(get_u8(img, off)),
        Width::Word => u32::from(u16::from_be_bytes(get_array(img, off))),
        Width::DWord => u32::from_be_bytes(get_array(img, off)),
    }
}

/// Writes the low `width` bits of `v` big-endian.
#[inline]
pub fn set_be(img: &mut [u8], off: u32, width: Width, v: u32) {
    match width {
        Width::Byte => set_u8(img, off, v as u8),
        Width::Word => set_array(img, off, (v as u16).to_be_bytes()),
        Width::DWord => set_array(img, off, v.to_be_bytes()),
    }
}

/// Reads a big-endian `i16` (timer and counter current values).
#[inline]
pub fn get_i16_be(img: &[u8], off: u32) -> i16 {
    i16::from_be_bytes(get_array(img, off))
}

/// Writes a big-endian `i16`.
#[inline]
pub fn set_i16_be(img: &mut [u8], off: u32, v: i16) {
    set_array(img, off, v.to_be_bytes());
}

/// Reads a native-endian `i16` (private timer state).
#[inline]
pub fn get_i16_ne(img: &[u8], off: u32) -> i16 {
    i16::from_ne_bytes(get_array(img, off))
}

/// Writes a native-endian `i16`.
#[inline]
pub fn set_i16_ne(img: &mut [u8], off: u32, v: i16) {
    set_array(img, off, v.to_ne_bytes());
}

/// Reads a native-endian `u16` (scheduler fields).
#[inline]
pub fn get_u16_ne(img: &[u8], off: u32) -> u16 {
    u16::from_ne_bytes(get_array(img, off))
}

/// Writes a native-endian `u16`.
#[inline]
pub fn set_u16_ne(img: &mut [u8], off: u32, v: u16) {
    set_array(img, off, v.to_ne_bytes());
}

/// Reads a native-endian `u32`.
#[inline]
pub fn get_u32_ne(img: &[u8], off: u32) -> u32 {
    u32::from_ne_bytes(get_array(img, off))
}

/// Writes a native-endian `u32`.
#[inline]
pub fn set_u32_ne(img: &mut [u8], off: u32, v: u32) {
    set_array(img, off, v.to_ne_bytes());
}

/// Reads a native-endian `u64`.
#[inline]
pub fn get_u64_ne(img: &[u8], off: u32) -> u64 {
    u64::from_ne_bytes(get_array(img, off))
}

/// Writes a native-endian `u64`.
#[inline]
pub fn set_u64_ne(img: &mut [u8], off: u32, v: u64) {
    set_array(img, off, v.to_ne_bytes());
}

/// Reads bit `bit` (0 = LSB) of byte `off`.
#[inline]
pub fn get_bit(img: &[u8], off: u32, bit: u8) -> bool {
    (get_u8(img, off) >> (bit & 7)) & 1 != 0
}

/// Writes bit `bit` of byte `off`, leaving the other bits alone.
#[inline]
pub fn set_bit(img: &mut [u8], off: u32, bit: u8, v: bool) {
    let mask = 1u8 << (bit & 7);
    let old = get_u8(img, off);
    set_u8(img, off, if v { old | mask } else { old & !mask });
}

/// Reads a scheduler `u8` field ([`stljit_core::layout::Sched`] constant).
#[inline]
pub fn sched_u8(img: &[u8], layout: &Layout, field: u32) -> u8 {
    get_u8(img, layout.sched(field))
}

/// Writes a scheduler `u8` field.
#[inline]
pub fn set_sched_u8(img: &mut [u8], layout: &Layout, field: u32, v: u8) {
    set_u8(img, layout.sched(field), v);
}

/// Reads a scheduler `u32` field.
#[inline]
pub fn sched_u32(img: &[u8], layout: &Layout, field: u32) -> u32 {
    get_u32_ne(img, layout.sched(field))
}

/// Writes a scheduler `u32` field.
#[inline]
pub fn set_sched_u32(img: &mut [u8], layout: &Layout, field: u32, v: u32) {
    set_u32_ne(img, layout.sched(field), v);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_never_panics() {
        let mut img = [0u8; 4];
        assert_eq!(get_be(&img, 3, Width::DWord), 0);
        set_be(&mut img, 3, Width::Word, 0xFFFF);
        assert_eq!(img, [0; 4]);
        set_u8(&mut img, u32::MAX, 1);
        assert_eq!(get_u64_ne(&img, u32::MAX), 0);
    }

    #[test]
    fn big_endian_overlap() {
        // Spec §1.3: VW100 = VB100 (high) · VB101 (low).
        let mut img = [0u8; 8];
        set_be(&mut img, 0, Width::DWord, 0x1234_5678);
        assert_eq!(get_be(&img, 0, Width::Word), 0x1234);
        assert_eq!(get_be(&img, 1, Width::Word), 0x3456);
        assert_eq!(get_be(&img, 3, Width::Byte), 0x78);
        // Bit 0 of VW0 is bit 0 of VB1.
        assert!(!get_bit(&img, 1, 0));
        set_bit(&mut img, 1, 0, true);
        assert_eq!(get_be(&img, 0, Width::Word), 0x1235);
    }
}
