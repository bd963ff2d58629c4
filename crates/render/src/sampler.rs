//! Sample numbers: Owen-scrambled Sobol points (Burley 2020), one independent scramble per
//! pixel, dimensions assigned in a fixed order so that every pixel's samples are the same
//! whatever the thread count or tile order.
//!
//! The numbers are exactly `sobol_burley::sample_4d`'s, computed from its parts so that
//! the work that depends only on the pixel (the per-dimension Owen scramble hashes) or
//! only on the sample (the shuffled sample index) is done once, not for every four
//! dimensions: a [`Sampler`] is made once per pixel and [`Sampler::restart`]ed for each of
//! its samples. Two sets (eight dimensions) are made at once, in one pass of 8-lane
//! vector code where the CPU has it: a path draws 7 numbers a bounce, and one refill of
//! eight costs little more than one of four.

mod scramble;

use std::sync::OnceLock;

use sobol_burley::parts::{self, Int4};

/// Hashes pixel coordinates and the render seed into a scramble seed.
pub fn pixel_seed(x: u32, y: u32, seed: u32) -> u32 {
    let mut h = (x as u64) | ((y as u64) << 32);
    h ^= (seed as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    h ^= h >> 33;
    h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
    h ^= h >> 33;
    h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    h ^= h >> 33;
    h as u32
}

/// Dimension sets (four dimensions each) whose scramble hashes a [`Sampler`] keeps: the
/// first 64 dimensions, more than a path of nine bounces uses. Later sets hash each time.
const KEPT_SETS: usize = 16;

/// Pairs of kept dimension sets: a refill makes sets `2·pair` and `2·pair + 1` together.
const KEPT_PAIRS: usize = KEPT_SETS / 2;

/// Sobol points of the kept dimension sets for each nibble of the sample index (the top
/// 16 bits of the bit-reversed index, which are the ones Sobol's table uses), two sets a
/// row: the construction is linear over XOR in the index bits, so a point is the XOR of
/// four entries instead of one table row per set bit. Entry `[pair][k][v]` holds the points
/// of sets `2·pair` (lanes 0–3) and `2·pair + 1` (lanes 4–7) of the index whose nibble `k`
/// (bits 16 + 4k …) is `v` and whose other bits are 0: one refill reads four rows of eight
/// lanes (one 256-bit vector each with AVX2).
type NibbleTable = [scramble::PairRows; KEPT_PAIRS];

fn nibble_table() -> &'static NibbleTable {
    static TABLE: OnceLock<Box<NibbleTable>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut table = Box::new([[[[0u32; 8]; 16]; 4]; KEPT_PAIRS]);
        for (pair, nibbles) in table.iter_mut().enumerate() {
            for (k, points) in nibbles.iter_mut().enumerate() {
                for (v, point) in points.iter_mut().enumerate() {
                    let index = (v as u32) << (16 + 4 * k);
                    let set = 2 * pair as u32;
                    let first: [u32; 4] = parts::sobol_int4_rev(index, set).into();
                    let second: [u32; 4] = parts::sobol_int4_rev(index, set + 1).into();
                    point[..4].copy_from_slice(&first);
                    point[4..].copy_from_slice(&second);
                }
            }
        }
        table
    })
}

/// The hashed Owen scramble of dimension set `set` under `seed` (one per lane), as
/// `sobol_burley::sample_4d` makes it.
#[inline]
fn set_scramble(seed: u32, set: u32) -> Int4 {
    let s = seed.wrapping_mul(0x9c8f_2d3b) ^ set;
    let lanes: Int4 = LANE_SALTS.map(|salt| s ^ salt).into();
    parts::hash_int4(lanes)
}

/// Dimensions made at once: two of Sobol's four-dimension sets.
const BUFFERED: u32 = 8;

/// The salts of the four lanes of a set's scramble hash (`sobol_burley::sample_4d`'s).
const LANE_SALTS: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];

/// Writes to `out` the scramble hashes of the kept dimension sets under `seed`:
/// [`set_scramble`] of sets `0 .. KEPT_SETS`, in plain integer code so that the 64 lanes
/// vectorise (see [`scramble::dispatch`]).
#[inline(always)]
fn kept_scrambles(seed: u32, out: &mut [[u32; 4]; KEPT_SETS]) {
    let base = seed.wrapping_mul(0x9c8f_2d3b);
    for (set, lanes) in out.iter_mut().enumerate() {
        let s = base ^ set as u32;
        for (lane, salt) in lanes.iter_mut().zip(LANE_SALTS) {
            *lane = parts::hash(s ^ salt);
        }
    }
}

/// The sample stream of one pixel sample. Numbers are made eight dimensions at a time
/// (two of Sobol's four-dimension sets together) and handed out one by one.
#[derive(Clone, Debug)]
pub struct Sampler {
    index: u32,
    seed: u32,
    /// The hash of the seed that Owen-shuffles the sample index ([`Sampler::shuffle`]).
    shuffle_seed: u32,
    /// The sample index bit-reversed and Owen-shuffled by the seed (which Sobol point of
    /// the pixel's sequence this sample is).
    shuffled: u32,
    dimension: u32,
    /// Dimensions below this one are in `buffer` (dimension `d` at `d % 8`; the buffer holds
    /// `filled − 8 .. filled`); 0 when nothing is. Past the Sobol table it stays at the
    /// table's end, so every later dimension is hashed.
    filled: u32,
    /// The numbers of dimensions `filled − 8 .. filled`, and one spare slot so that a pair
    /// read at `d % 8` and `d % 8 + 1` needs no bounds check.
    buffer: [f32; BUFFERED as usize + 1],
    /// Scramble hashes of the first dimension sets (they depend on the seed alone, so they
    /// outlive [`Sampler::restart`]), all made with the sampler.
    scrambles: [[u32; 4]; KEPT_SETS],
    nibbles: &'static NibbleTable,
    /// The refill's vector code for this CPU.
    xor_finish: scramble::XorFinish,
}

impl Sampler {
    /// Sample `index` of the pixel whose scramble seed is `seed`.
    pub fn new(seed: u32, index: u32) -> Sampler {
        let mut sampler = Sampler {
            index,
            seed,
            shuffle_seed: 0,
            shuffled: 0,
            dimension: 0,
            filled: 0,
            buffer: [0.0; BUFFERED as usize + 1],
            scrambles: [[0; 4]; KEPT_SETS],
            nibbles: nibble_table(),
            xor_finish: scramble::XorFinish::detect(),
        };
        sampler.start_pixel(seed, index);
        sampler
    }

    /// Starts sample `index` of the pixel whose scramble seed is `seed`, in place: the same
    /// numbers as `Sampler::new(seed, index)` (a band reuses its samplers' slots rather than
    /// moving a new one into them).
    #[inline(never)]
    pub fn start_pixel(&mut self, seed: u32, index: u32) {
        self.seed = seed;
        self.shuffle_seed = parts::hash(seed ^ 0x79c6_8e4a);
        self.restart(index);
        let scrambles = &mut self.scrambles;
        scramble::dispatch(
            #[inline(always)]
            || kept_scrambles(seed, scrambles),
        );
    }

    /// Starts sample `index` of the same pixel (dimension 0 again), keeping what depends on
    /// the pixel alone.
    #[inline]
    pub fn restart(&mut self, index: u32) {
        self.index = index;
        self.shuffled = Self::shuffle(self.shuffle_seed, index);
        self.dimension = 0;
        self.filled = 0;
    }

    /// The sample index bit-reversed and Owen-shuffled by `shuffle_seed` (the hash of the
    /// pixel's seed `sobol_burley` uses).
    #[inline]
    fn shuffle(shuffle_seed: u32, index: u32) -> u32 {
        parts::owen_scramble_rev(index.reverse_bits(), shuffle_seed)
    }

    /// The bit-reversed Sobol points and the scramble hashes of dimensions
    /// `4·set … 4·set + 3` of this sample, for a set past the kept ones.
    #[inline(always)]
    fn set_parts(&self, set: u32) -> ([u32; 4], [u32; 4]) {
        (parts::sobol_int4_rev(self.shuffled, set).into(), set_scramble(self.seed, set).into())
    }

    /// Dimensions `4·set … 4·set + 7` of this sample (sets `set` and `set + 1`), past the
    /// kept sets.
    #[inline(always)]
    fn two_sets(&self, set: u32) -> [f32; BUFFERED as usize] {
        let (s0, h0) = self.set_parts(set);
        let (s1, h1) = self.set_parts(set + 1);
        let mut sobol = [0u32; 8];
        let mut hashes = [0u32; 8];
        sobol[..4].copy_from_slice(&s0);
        sobol[4..].copy_from_slice(&s1);
        hashes[..4].copy_from_slice(&h0);
        hashes[4..].copy_from_slice(&h1);
        scramble::finish(sobol, hashes)
    }

    /// The next number in [0, 1).
    #[inline(always)]
    pub fn next_1d(&mut self) -> f32 {
        let d = self.dimension;
        self.dimension = d + 1;
        // Seven numbers in eight come from the buffer filled at the first dimension of a
        // pair of sets: that path stays small enough to inline into the integrator.
        if d < self.filled {
            self.buffer[(d % BUFFERED) as usize]
        } else {
            self.refill(d)
        }
    }

    /// Dimension `d` (= `filled`), the first of a pair of sets (which fills the buffer) or
    /// past the table.
    #[inline(never)]
    fn refill(&mut self, d: u32) -> f32 {
        // (`d` is a multiple of 8: the pair of sets `d / 8`, sets `d / 4` and `d / 4 + 1`.)
        let pair = (d / BUFFERED) as usize;
        if pair >= KEPT_PAIRS {
            return self.refill_past_kept(d);
        }
        // Both sets' points are the XOR of four rows of the table, one a nibble of the
        // shuffled index; the scrambles of the two sets lie side by side.
        let table: &'static NibbleTable = self.nibbles;
        let hashes = self.scrambles[2 * pair..2 * pair + 2].as_flattened();
        let hashes: &[u32; BUFFERED as usize] = hashes.try_into().expect("two sets of four");
        let out = self.buffer.first_chunk_mut::<{ BUFFERED as usize }>().expect("the buffer");
        self.xor_finish.run(&table[pair], self.shuffled >> 16, hashes, out);
        self.filled = d + BUFFERED;
        self.buffer[0]
    }

    /// [`Sampler::refill`] past the kept sets: the points and scrambles worked out, or past
    /// the table a hashed number.
    #[inline(never)]
    fn refill_past_kept(&mut self, d: u32) -> f32 {
        if d < sobol_burley::NUM_DIMENSIONS {
            // The set's arithmetic built for the best instructions the CPU has.
            // (Sets `d / 4` and `d / 4 + 1` are both in the table.)
            let numbers = scramble::dispatch(
                #[inline(always)]
                || self.two_sets(d / 4),
            );
            self.buffer[..BUFFERED as usize].copy_from_slice(&numbers);
            self.filled = d + BUFFERED;
            numbers[0]
        } else {
            // Past the Sobol table: a hashed random number (still deterministic).
            let h = pixel_seed(self.index, d, self.seed);
            (h >> 8) as f32 / (1u32 << 24) as f32
        }
    }

    /// Where this sample's stream stands (its index and the dimensions drawn), to go on
    /// from there with [`Sampler::resume`] after other samples of the pixel were drawn.
    #[inline]
    pub fn position(&self) -> SamplerPosition {
        SamplerPosition {
            index: self.index,
            shuffled: self.shuffled,
            dimension: self.dimension,
            filled: self.filled,
            buffer: self.buffer,
        }
    }

    /// Goes on with the sample at `position` (taken from this pixel's sampler): the next
    /// numbers are the ones that sampler would have given next.
    #[inline]
    pub fn resume(&mut self, position: &SamplerPosition) {
        self.index = position.index;
        self.shuffled = position.shuffled;
        self.dimension = position.dimension;
        self.filled = position.filled;
        self.buffer = position.buffer;
    }

    /// A number identifying this pixel sample (its seed and index hashed), for random
    /// decisions outside the low-discrepancy dimensions.
    pub fn stream(&self) -> u32 {
        pixel_seed(self.index, 0x5eed, self.seed)
    }

    /// The next two numbers (the same as two calls of [`Sampler::next_1d`]).
    #[inline(always)]
    pub fn next_2d(&mut self) -> glam::Vec2 {
        let d = self.dimension;
        // Both in the buffer (then `d % 8` ≤ 6: `filled` is a multiple of 8): one test.
        if d + 1 < self.filled {
            self.dimension = d + 2;
            let lane = (d % BUFFERED) as usize;
            glam::Vec2::new(self.buffer[lane], self.buffer[lane + 1])
        } else {
            glam::Vec2::new(self.next_1d(), self.next_1d())
        }
    }
}

/// A pixel sample's place in its stream ([`Sampler::position`]): what depends on the sample,
/// not on the pixel.
#[derive(Clone, Copy, Debug)]
pub struct SamplerPosition {
    index: u32,
    shuffled: u32,
    dimension: u32,
    filled: u32,
    buffer: [f32; BUFFERED as usize + 1],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buffered_numbers_equal_the_direct_ones() {
        let mut s = Sampler::new(1234, 7);
        for d in 0..40 {
            assert_eq!(s.next_1d(), sobol_burley::sample(7, d, 1234), "dimension {d}");
        }
    }

    /// Samples interleaved through [`Sampler::position`] and [`Sampler::resume`] (three
    /// dimensions of each of four samples, then the rest of each in turn) give, bit for bit,
    /// the numbers each gives alone.
    #[test]
    fn resumed_samples_equal_uninterrupted_ones() {
        let seed = pixel_seed(5, 11, 3);
        let mut s = Sampler::new(seed, 0);
        let mut positions = Vec::new();
        for index in 0..4 {
            s.restart(index);
            for d in 0..3 {
                assert_eq!(s.next_1d().to_bits(), sobol_burley::sample(index, d, seed).to_bits());
            }
            positions.push(s.position());
        }
        for (index, p) in (0..4).zip(&positions) {
            s.resume(p);
            for d in 3..40 {
                assert_eq!(s.next_1d().to_bits(), sobol_burley::sample(index, d, seed).to_bits(), "{index} {d}");
            }
        }
    }

    /// A sampler restarted for each sample of a pixel gives, bit for bit, the numbers of
    /// `sobol_burley::sample_4d` (all 256 table dimensions, kept and recomputed scramble
    /// sets alike), whatever order the samples come in.
    #[test]
    fn restarted_samplers_equal_sample_4d() {
        for seed in [0u32, 1, 0xdead_beef, pixel_seed(3, 9, 42)] {
            let mut s = Sampler::new(seed, 0);
            for index in [0u32, 1, 2, 63, 5, 1000, 65_535, 17] {
                s.restart(index);
                for set in 0..sobol_burley::NUM_DIMENSION_SETS_4D {
                    let expect = sobol_burley::sample_4d(index, set, seed);
                    let got = [s.next_1d(), s.next_1d(), s.next_1d(), s.next_1d()];
                    assert_eq!(got.map(f32::to_bits), expect.map(f32::to_bits), "seed {seed} index {index} set {set}");
                }
                // Past the table: the hashed numbers of a fresh sampler.
                let mut fresh = Sampler::new(seed, index);
                for _ in 0..sobol_burley::NUM_DIMENSIONS {
                    fresh.next_1d();
                }
                assert_eq!(s.next_1d().to_bits(), fresh.next_1d().to_bits());
            }
        }
    }

    /// A sampler started in place for another pixel ([`Sampler::start_pixel`], after
    /// numbers of its old pixel were drawn) gives, bit for bit, a new sampler's numbers.
    #[test]
    fn started_in_place_equals_new() {
        let mut reused = Sampler::new(pixel_seed(1, 2, 3), 5);
        for (x, index) in [(0u32, 0u32), (7, 3), (9, 1000), (65_000, 17)] {
            for _ in 0..13 {
                reused.next_1d();
            }
            let seed = pixel_seed(x, 4, 3);
            reused.start_pixel(seed, index);
            let mut fresh = Sampler::new(seed, index);
            for d in 0..80 {
                assert_eq!(reused.next_1d().to_bits(), fresh.next_1d().to_bits(), "{x} {index} {d}");
            }
            assert_eq!(reused.stream(), fresh.stream());
        }
    }

    /// The scramble hashes made with the sampler (all kept sets at once, in the build the
    /// CPU's best instructions give) equal [`set_scramble`]'s, set by set, bit for bit.
    #[test]
    fn kept_scrambles_equal_set_scramble() {
        for seed in [0u32, 1, 0x8000_0000, u32::MAX, 0xdead_beef, pixel_seed(3, 9, 42)] {
            let s = Sampler::new(seed, 0);
            for set in 0..KEPT_SETS {
                assert_eq!(s.scrambles[set], <[u32; 4]>::from(set_scramble(seed, set as u32)), "{seed} {set}");
            }
        }
    }

    /// [`Sampler::next_2d`] gives, bit for bit, the numbers of two [`Sampler::next_1d`]
    /// calls, whatever dimension it starts at (every offset within the eight-number
    /// buffer, its last slot, and past the Sobol table).
    #[test]
    fn pairs_equal_two_single_numbers() {
        let seed = pixel_seed(7, 2, 9);
        for index in [0u32, 3, 17, 4095] {
            for start in 0..40u32 {
                let (mut pairs, mut singles) = (Sampler::new(seed, 0), Sampler::new(seed, 0));
                pairs.restart(index);
                singles.restart(index);
                for _ in 0..start {
                    assert_eq!(pairs.next_1d().to_bits(), singles.next_1d().to_bits());
                }
                for _ in 0..(sobol_burley::NUM_DIMENSIONS + 8) / 2 {
                    let p = pairs.next_2d();
                    let (a, b) = (singles.next_1d(), singles.next_1d());
                    assert_eq!((p.x.to_bits(), p.y.to_bits()), (a.to_bits(), b.to_bits()), "{index} {start}");
                }
            }
        }
    }
}
