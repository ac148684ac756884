//! Where the generator's choices come from: a seeded PRNG for campaigns, or the fuzzer's bytes
//! (`arbitrary::Unstructured`) for coverage-guided fuzzing. Both answer the same questions, so one
//! generator serves `stljit fuzz` and `cargo fuzz` alike.

use arbitrary::Unstructured;

/// SplitMix64: tiny, fast, and good enough that every seed gives an unrelated program. Owning the
/// generator (instead of depending on `rand`) pins the program of a seed forever.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator starting at `seed`.
    pub fn new(seed: u64) -> SplitMix64 {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// Mixes a campaign seed and a program number into the seed of that program, so that program `i`
/// of seed `s` is the same whatever the job count or shard that generates it.
pub fn program_seed(campaign_seed: u64, index: u64) -> u64 {
    let mut r = SplitMix64::new(campaign_seed ^ index.wrapping_mul(0xD6E8_FEB8_6659_FD93));
    r.next_u64()
}

enum Source<'a> {
    Rng(SplitMix64),
    Bytes(Unstructured<'a>),
}

/// A stream of choices. When fuzzer bytes run out every choice is 0, and the generator is built
/// so that choice 0 always means "the smallest thing": generation then ends quickly.
pub struct Choices<'a> {
    src: Source<'a>,
}

impl Choices<'static> {
    /// Choices from a seed.
    pub fn from_seed(seed: u64) -> Choices<'static> {
        Choices {
            src: Source::Rng(SplitMix64::new(seed)),
        }
    }
}

impl<'a> Choices<'a> {
    /// Choices read from fuzzer bytes.
    pub fn from_bytes(data: &'a [u8]) -> Choices<'a> {
        Choices {
            src: Source::Bytes(Unstructured::new(data)),
        }
    }

    /// A value in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: u32) -> u32 {
        if n <= 1 {
            return 0;
        }
        match &mut self.src {
            // Multiply-shift maps 32 random bits onto 0..n with negligible bias and no division.
            Source::Rng(r) => (((r.next_u64() >> 32) * u64::from(n)) >> 32) as u32,
            Source::Bytes(u) => u.int_in_range(0..=n - 1).unwrap_or(0),
        }
    }

    /// A value in `lo..=hi` (`lo` when `hi < lo`).
    pub fn range(&mut self, lo: u32, hi: u32) -> u32 {
        if hi <= lo {
            return lo;
        }
        lo + self.below(hi - lo + 1)
    }

    /// 32 arbitrary bits.
    pub fn bits(&mut self) -> u32 {
        match &mut self.src {
            Source::Rng(r) => (r.next_u64() >> 32) as u32,
            Source::Bytes(u) => u.arbitrary::<u32>().unwrap_or(0),
        }
    }

    /// True with probability `num / den` (never when bytes have run out and `num < den`).
    pub fn chance(&mut self, num: u32, den: u32) -> bool {
        self.below(den) >= den.saturating_sub(num)
    }

    /// An element of a non-empty slice (the first one for an empty choice stream).
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len() as u32) as usize]
    }

    /// An index into `weights`, chosen with probability proportional to its weight. An exhausted
    /// byte stream yields the first index of non-zero weight.
    pub fn weighted(&mut self, weights: &[u32]) -> usize {
        let total: u32 = weights.iter().sum();
        let mut x = self.below(total);
        for (i, &w) in weights.iter().enumerate() {
            if x < w {
                return i;
            }
            x -= w;
        }
        0
    }

    /// Whether the choices come from fuzzer bytes that are used up.
    pub fn exhausted(&self) -> bool {
        match &self.src {
            Source::Rng(_) => false,
            Source::Bytes(u) => u.is_empty(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeded_choices_repeat() {
        let mut a = Choices::from_seed(7);
        let mut b = Choices::from_seed(7);
        let xs: Vec<u32> = (0..100).map(|_| a.below(1000)).collect();
        let ys: Vec<u32> = (0..100).map(|_| b.below(1000)).collect();
        assert_eq!(xs, ys);
        assert!(xs.iter().all(|&x| x < 1000));
        assert!(xs.iter().any(|&x| x != xs[0]));
    }

    #[test]
    fn empty_bytes_choose_zero() {
        let mut c = Choices::from_bytes(&[]);
        assert_eq!(c.below(10), 0);
        assert_eq!(c.weighted(&[0, 5, 3]), 1);
        assert!(!c.chance(1, 2));
        assert!(c.exhausted());
    }

    #[test]
    fn below_covers_range() {
        let mut c = Choices::from_seed(1);
        let mut seen = [false; 7];
        for _ in 0..1000 {
            seen[c.below(7) as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }
}
