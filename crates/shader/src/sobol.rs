//! Owen-scrambled Sobol points (Burley 2020): exactly the numbers of
//! `sobol_burley::sample_4d`, with the Sobol part looked up in a table.
//!
//! Sobol's construction is linear over XOR in the bits of the sample index, and it uses the
//! top 16 bits of the bit-reversed index. So the point of an index is the XOR of the points
//! of its four nibbles: four table lookups instead of one table row per set bit. The table
//! holds every dimension set (64 KiB), built once per process.

use std::sync::OnceLock;

use sobol_burley::parts::{self, Int4};

/// How many sets of four dimensions the sequence has.
const SETS: usize = sobol_burley::NUM_DIMENSION_SETS_4D as usize;

/// Entry `[set][k][v]`: the bit-reversed point (the four dimensions of `set`) of the
/// bit-reversed index whose nibble `k` (bits 16 + 4k to 19 + 4k) is `v` and whose other
/// bits are 0.
type NibbleTable = [[[[u32; 4]; 16]; 4]; SETS];

fn nibble_table() -> &'static NibbleTable {
    static TABLE: OnceLock<Box<NibbleTable>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut table = Box::new([[[[0u32; 4]; 16]; 4]; SETS]);
        for (set, nibbles) in table.iter_mut().enumerate() {
            for (k, points) in nibbles.iter_mut().enumerate() {
                for (v, point) in points.iter_mut().enumerate() {
                    *point = parts::sobol_int4_rev((v as u32) << (16 + 4 * k), set as u32).into();
                }
            }
        }
        table
    })
}

/// One dimension set's part of the nibble table: entry `[k][v]` as in [`NibbleTable`].
pub type SetTable = [[[u32; 4]; 16]; 4];

/// The nibble table's part for dimension set `set` (< 64), for a loop that looks many
/// points of one set up ([`sobol_int4_rev_in`]).
#[inline]
pub fn set_table(set: u32) -> &'static SetTable {
    &nibble_table()[set as usize % SETS]
}

/// The bit-reversed Sobol point of dimension set `set` (< 64) for the bit-reversed sample
/// index `index_rev`: `sobol_burley::parts::sobol_int4_rev`, the same bits.
#[inline]
pub fn sobol_int4_rev(index_rev: u32, set: u32) -> Int4 {
    sobol_int4_rev_in(set_table(set), index_rev)
}

/// [`sobol_int4_rev`] of the set whose table is `table` ([`set_table`]).
#[inline(always)]
pub fn sobol_int4_rev_in(table: &SetTable, index_rev: u32) -> Int4 {
    let n = index_rev >> 16;
    let point = |k: usize| Int4::from(table[k][((n >> (4 * k)) & 15) as usize]);
    point(0) ^ point(1) ^ point(2) ^ point(3)
}

/// The Owen scramble hashes of dimension set `set` under `seed` (one per lane), as
/// `sobol_burley::sample_4d` makes them.
#[inline]
pub fn set_scramble(seed: u32, set: u32) -> Int4 {
    let s = seed.wrapping_mul(0x9c8f_2d3b) ^ set;
    parts::hash_int4([s ^ 0x912f_69ba, s ^ 0x174f_18ab, s ^ 0x691e_72ca, s ^ 0xb40c_c1b8].into())
}

/// Sample `index` (< 2¹⁶) of the Owen-scrambled Sobol sequence `seed`, dimensions
/// 4·`set` to 4·`set` + 3 (`set` < 64), in [0, 1): `sobol_burley::sample_4d`, the same
/// bits.
#[inline]
pub fn sample_4d(index: u32, set: u32, seed: u32) -> [f32; 4] {
    let shuffled = parts::owen_scramble_rev(index.reverse_bits(), parts::hash(seed ^ 0x79c6_8e4a));
    parts::owen_scramble_int4_rev(sobol_int4_rev(shuffled, set), set_scramble(seed, set)).reverse_bits().to_f32_norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every dimension set, sample indices over the whole range (every 97th, and the last)
    /// under several seeds: bit for bit `sobol_burley::sample_4d`.
    #[test]
    fn samples_equal_sobol_burley() {
        for seed in [0u32, 1, 0x5eed, 0xdead_beef] {
            for set in 0..SETS as u32 {
                for index in (0..1u32 << 16).step_by(97).chain([0xffff]) {
                    let expect = sobol_burley::sample_4d(index, set, seed).map(f32::to_bits);
                    assert_eq!(
                        sample_4d(index, set, seed).map(f32::to_bits),
                        expect,
                        "seed {seed} set {set} index {index}"
                    );
                }
            }
        }
    }
}
