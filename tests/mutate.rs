//! The fixed-seed number stream the no-panic tests use to mutate valid input files.

/// A xorshift64 stream from `seed` (non-zero): cheap, deterministic, and the same on every
/// machine, so a mutated input that fails can be regenerated from the test alone.
pub(crate) fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}
