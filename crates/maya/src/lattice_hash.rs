//! The integer hash of lattice points that mira's Maya noises and cells draw their
//! random numbers from.

/// A 32-bit hash of a lattice point.
pub fn lattice(i: i32, j: i32, k: i32) -> u32 {
    let mut h = (i as u32).wrapping_mul(0x8da6_b343)
        ^ (j as u32).wrapping_mul(0xd816_3841)
        ^ (k as u32).wrapping_mul(0xcb1a_b31f);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^ (h >> 15)
}
