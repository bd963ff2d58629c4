//! The sample numbers of one sampling loop of a shader ([`SitePairs`]): the pairs
//! [`Ctx::sample2`](crate::Ctx::sample2) hands out for the `i`-th of `n` samples at one
//! sampling site, with the hashes the loop's samples share computed once.
//!
//! Sample `i` of a loop of `n` at sampling site `site` is sample `index = sample_index · n + i`
//! of an Owen-scrambled Sobol sequence (Burley 2020) whose seed hashes the pixel, the
//! scene's seed, the ray depth, `index >> 16` and the site; its two numbers are dimensions
//! 128 + 2k and 129 + 2k (k = `site` mod 64). Within a loop only the index changes, so the
//! seed, the index shuffle's key and the two dimensions' scrambles are computed when the
//! loop starts; each sample then costs one index shuffle, four table lookups and two
//! scalar scrambles — exactly the bits of `sobol_burley::sample`, which the tests check.

use glam::Vec2;
use sobol_burley::parts::{self, Int4};

/// The scramble constants of the four lanes of a dimension set (`sobol_burley::sample_4d`'s).
const LANE_KEYS: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];

/// The keys of one sequence seed: the index shuffle's and the two dimensions' scrambles.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Keys {
    shuffle: u32,
    scramble: [u32; 2],
}

impl Keys {
    fn new(seed: u32, set: u32, lane: usize) -> Keys {
        let s = seed.wrapping_mul(0x9c8f_2d3b) ^ set;
        Keys {
            shuffle: parts::hash(seed ^ 0x79c6_8e4a),
            scramble: [parts::hash(s ^ LANE_KEYS[lane]), parts::hash(s ^ LANE_KEYS[lane + 1])],
        }
    }
}

/// The sample pairs of one sampling loop: [`SitePairs::pair`]`(i)` is, bit for bit,
/// `Ctx::sample2(site, i, n)` at the shading point the loop started at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SitePairs {
    /// The hashed words before `index >> 16`: pixel x, pixel y, the scene's seed, the depth.
    words: [u32; 4],
    site: u32,
    /// `sample_index · n`: sample `i`'s index is this plus `i` (wrapping).
    base: u32,
    /// The `index >> 16` that `keys` were made for.
    high: u32,
    keys: Keys,
    /// The dimension set (of four dimensions) holding the site's two dimensions.
    set: u32,
    /// The first of the two dimensions' lanes in the set (0 or 2).
    lane: usize,
    /// The set's Sobol table ([`crate::sobol::set_table`]).
    table: &'static crate::sobol::SetTable,
}

impl SitePairs {
    /// The pairs of a loop of `n` samples at `site`, for the eye sample `sample_index` of
    /// pixel `pixel` under the scene's seed `seed`, at ray depth `depth` (reflections +
    /// 7 refractions + 31 final gather bounces).
    pub fn new(pixel: [u32; 2], seed: u32, depth: u32, sample_index: u32, site: u32, n: u32) -> SitePairs {
        let dim = (site % 64) * 2 + 128;
        let (set, lane) = (dim / 4, (dim % 4) as usize);
        let words = [pixel[0], pixel[1], seed, depth];
        let base = sample_index.wrapping_mul(n.max(1));
        let high = base >> 16;
        let keys = Keys::new(sequence_seed(words, high, site), set, lane);
        SitePairs { words, site, base, high, keys, set, lane, table: crate::sobol::set_table(set) }
    }

    /// The two sample numbers in [0, 1)² of sample `i` of the loop.
    #[inline]
    pub fn pair(&self, i: u32) -> Vec2 {
        let index = self.base.wrapping_add(i);
        let high = index >> 16;
        let keys = if high == self.high {
            self.keys
        } else {
            Keys::new(sequence_seed(self.words, high, self.site), self.set, self.lane)
        };
        let shuffled = parts::owen_scramble_rev((index & 0xffff).reverse_bits(), keys.shuffle);
        let point: [u32; 4] = crate::sobol::sobol_int4_rev_in(self.table, shuffled).into();
        let number = |lane: usize, scramble: u32| {
            parts::u32_to_f32_norm(parts::owen_scramble_rev(point[lane], scramble).reverse_bits())
        };
        Vec2::new(number(self.lane, keys.scramble[0]), number(self.lane + 1, keys.scramble[1]))
    }

    /// [`SitePairs::pair`] of samples `first` to `first + 3`, bit for bit, computed four
    /// at a time (the scrambles and bit reversals in SIMD lanes): for a loop that takes its
    /// samples' numbers ahead, as the light loop does for its shadow packets.
    #[inline]
    pub fn pairs4(&self, first: u32) -> [Vec2; 4] {
        let index = [0, 1, 2, 3].map(|k| self.base.wrapping_add(first).wrapping_add(k));
        if index.iter().any(|&i| i >> 16 != self.high) {
            // Past an index multiple of 2¹⁶ (another sequence seed): one at a time.
            return [0, 1, 2, 3].map(|k| self.pair(first.wrapping_add(k)));
        }
        let keys = self.keys;
        let low = Int4::from(index.map(|i| i & 0xffff));
        let shuffled: [u32; 4] = parts::owen_scramble_int4_rev(low.reverse_bits(), [keys.shuffle; 4].into()).into();
        let points: [[u32; 4]; 4] = shuffled.map(|i| crate::sobol::sobol_int4_rev_in(self.table, i).into());
        let numbers = |lane: usize, scramble: u32| {
            let lanes = Int4::from(points.map(|p| p[lane]));
            parts::owen_scramble_int4_rev(lanes, [scramble; 4].into()).reverse_bits().to_f32_norm()
        };
        let (x, y) = (numbers(self.lane, keys.scramble[0]), numbers(self.lane + 1, keys.scramble[1]));
        [0, 1, 2, 3].map(|k| Vec2::new(x[k], y[k]))
    }

    /// [`SitePairs::pair`] of samples `first` to `first + 7`, bit for bit, computed
    /// eight at a time in plain integer code over arrays, built for the CPU's vector
    /// units ([`crate::simd`]): for the light loop's batches of eight.
    #[inline]
    pub fn pairs8(&self, first: u32) -> [Vec2; 8] {
        let index: [u32; 8] = std::array::from_fn(|k| self.base.wrapping_add(first).wrapping_add(k as u32));
        if index.iter().any(|&i| i >> 16 != self.high) {
            // Past an index multiple of 2¹⁶ (another sequence seed): one at a time.
            return std::array::from_fn(|k| self.pair(first.wrapping_add(k as u32)));
        }
        let (x, y) = self.numbers8_dispatched(index);
        std::array::from_fn(|k| Vec2::new(x[k], y[k]))
    }

    /// [`SitePairs::numbers8`] built for AVX2 or SSE4.1 when the CPU has it (the
    /// same bits; see [`crate::simd`]), else the baseline build.
    #[inline]
    #[allow(unsafe_code)]
    fn numbers8_dispatched(&self, index: [u32; 8]) -> ([f32; 8], [f32; 8]) {
        #[cfg(target_arch = "x86_64")]
        if crate::simd::has_avx2() {
            // SAFETY: the CPU has AVX2 (checked just above).
            return unsafe { self.numbers8_avx2(index) };
        }
        #[cfg(target_arch = "x86_64")]
        if crate::simd::has_sse41() {
            // SAFETY: the CPU has SSE4.1 (checked just above).
            return unsafe { self.numbers8_sse41(index) };
        }
        self.numbers8(index)
    }

    /// [`SitePairs::numbers8`] built with AVX2.
    ///
    /// # Safety
    ///
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[allow(unsafe_code)]
    unsafe fn numbers8_avx2(&self, index: [u32; 8]) -> ([f32; 8], [f32; 8]) {
        self.numbers8(index)
    }

    /// [`SitePairs::numbers8`] built with SSE4.1.
    ///
    /// # Safety
    ///
    /// The CPU must support SSE4.1.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "sse4.1")]
    #[allow(unsafe_code)]
    unsafe fn numbers8_sse41(&self, index: [u32; 8]) -> ([f32; 8], [f32; 8]) {
        self.numbers8(index)
    }

    /// The two numbers of the samples with sequence indices `index` (all sharing
    /// `self.high`), lane by lane as [`SitePairs::pair`] makes them.
    #[inline(always)]
    fn numbers8(&self, index: [u32; 8]) -> ([f32; 8], [f32; 8]) {
        let keys = self.keys;
        let mut shuffled = [0u32; 8];
        for (s, &i) in shuffled.iter_mut().zip(&index) {
            *s = parts::owen_scramble_rev((i & 0xffff).reverse_bits(), keys.shuffle);
        }
        // The two dimensions' lanes of each point: the XOR of its four nibbles' entries.
        let (mut xs, mut ys) = ([0u32; 8], [0u32; 8]);
        for k in 0..8 {
            let n = shuffled[k] >> 16;
            let entry = |nibble: usize| &self.table[nibble][((n >> (4 * nibble)) & 15) as usize];
            let (e0, e1, e2, e3) = (entry(0), entry(1), entry(2), entry(3));
            xs[k] = e0[self.lane] ^ e1[self.lane] ^ e2[self.lane] ^ e3[self.lane];
            ys[k] = e0[self.lane + 1] ^ e1[self.lane + 1] ^ e2[self.lane + 1] ^ e3[self.lane + 1];
        }
        let finish = |points: [u32; 8], scramble: u32| {
            let mut out = [0.0; 8];
            for (o, &p) in out.iter_mut().zip(&points) {
                *o = parts::u32_to_f32_norm(parts::owen_scramble_rev(p, scramble).reverse_bits());
            }
            out
        };
        (finish(xs, keys.scramble[0]), finish(ys, keys.scramble[1]))
    }
}

/// The seed of the Sobol sequence of a site's samples whose indices share `high`.
fn sequence_seed(words: [u32; 4], high: u32, site: u32) -> u32 {
    hash(&[words[0], words[1], words[2], words[3], high, site])
}

/// Mixes numbers into a 32-bit hash.
pub fn hash(words: &[u32]) -> u32 {
    let mut h: u64 = 0x243f_6a88_85a3_08d3;
    for &w in words {
        h ^= u64::from(w);
        h = h.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        h ^= h >> 29;
    }
    h ^= h >> 32;
    h as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pair is, bit for bit, the two one-dimension `sobol_burley::sample` numbers of
    /// its dimensions under its sequence seed: every site, loops of several lengths, eye
    /// sample indices whose loops cross an index multiple of 2¹⁶ and wrap past 2³².
    #[test]
    #[allow(unsafe_code)]
    fn pairs_are_the_one_dimension_samples() {
        let words = [3u32, 7, 0x5eed, 9];
        for site in 0..130 {
            for (sample_index, n) in [(0u32, 1u32), (5, 16), (4095, 16), (4096, 17), (0x1234_5678, 64), (u32::MAX, 7)] {
                let pairs = SitePairs::new([words[0], words[1]], words[2], words[3], sample_index, site, n);
                for i in 0..n {
                    let index = sample_index.wrapping_mul(n).wrapping_add(i);
                    let seed = hash(&[words[0], words[1], words[2], words[3], index >> 16, site]);
                    let dim = (site % 64) * 2 + 128;
                    let expect = [
                        sobol_burley::sample(index & 0xffff, dim, seed),
                        sobol_burley::sample(index & 0xffff, dim + 1, seed),
                    ];
                    let got = pairs.pair(i);
                    assert_eq!(
                        [got.x.to_bits(), got.y.to_bits()],
                        expect.map(f32::to_bits),
                        "site {site} sample {sample_index} of {n}, i {i}"
                    );
                    // Four and eight at a time from here: the same numbers.
                    for (k, four) in pairs.pairs4(i).into_iter().enumerate() {
                        let one = pairs.pair(i + k as u32);
                        assert_eq!([four.x.to_bits(), four.y.to_bits()], [one.x.to_bits(), one.y.to_bits()]);
                    }
                    let index = |k: u32| sample_index.wrapping_mul(n).wrapping_add(i + k);
                    let eight = pairs.pairs8(i);
                    // The vector builds and the baseline one, each where it ran.
                    let mut builds = vec![];
                    if (0..8).all(|k| index(k) >> 16 == index(0) >> 16) {
                        let indices = std::array::from_fn(|k| index(k as u32));
                        builds.push(pairs.numbers8(indices));
                        #[cfg(target_arch = "x86_64")]
                        if std::is_x86_feature_detected!("sse4.1") {
                            // SAFETY: checked just above.
                            builds.push(unsafe { pairs.numbers8_sse41(indices) });
                        }
                        #[cfg(target_arch = "x86_64")]
                        if std::is_x86_feature_detected!("avx2") {
                            // SAFETY: checked just above.
                            builds.push(unsafe { pairs.numbers8_avx2(indices) });
                        }
                    }
                    for k in 0..8 {
                        let one = pairs.pair(i + k as u32);
                        let want = [one.x.to_bits(), one.y.to_bits()];
                        assert_eq!([eight[k].x.to_bits(), eight[k].y.to_bits()], want, "pairs8, i {i} + {k}");
                        for (x, y) in &builds {
                            assert_eq!([x[k].to_bits(), y[k].to_bits()], want, "a build of numbers8, i {i} + {k}");
                        }
                    }
                }
            }
        }
    }
}
