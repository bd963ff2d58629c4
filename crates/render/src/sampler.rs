//! Sample numbers: Owen-scrambled Sobol points (Burley 2020), one independent scramble per
//! pixel, dimensions assigned in a fixed order so that every pixel's samples are the same
//! whatever the thread count or tile order.

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

/// The sample stream of one pixel sample. Numbers are made four dimensions at a time
/// (`sobol_burley::sample_4d`, which computes them together) and handed out one by one.
#[derive(Clone, Debug)]
pub struct Sampler {
    index: u32,
    seed: u32,
    dimension: u32,
    buffer: [f32; 4],
}

impl Sampler {
    /// Sample `index` of the pixel whose scramble seed is `seed`.
    pub fn new(seed: u32, index: u32) -> Sampler {
        Sampler { index, seed, dimension: 0, buffer: [0.0; 4] }
    }

    /// The next number in [0, 1).
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        let d = self.dimension;
        self.dimension += 1;
        let lane = (d % 4) as usize;
        if d < sobol_burley::NUM_DIMENSIONS {
            if lane == 0 {
                self.buffer = sobol_burley::sample_4d(self.index, d / 4, self.seed);
            }
            self.buffer[lane]
        } else {
            // Past the Sobol table: a hashed random number (still deterministic).
            let h = pixel_seed(self.index, d, self.seed);
            (h >> 8) as f32 / (1u32 << 24) as f32
        }
    }

    /// A number identifying this pixel sample (its seed and index hashed), for random
    /// decisions outside the low-discrepancy dimensions.
    pub fn stream(&self) -> u32 {
        pixel_seed(self.index, 0x5eed, self.seed)
    }

    /// The next two numbers.
    #[inline]
    pub fn next_2d(&mut self) -> glam::Vec2 {
        glam::Vec2::new(self.next_1d(), self.next_1d())
    }
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
}
