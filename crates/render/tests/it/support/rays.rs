//! Random rays for the acceleration tests: origins spread over the inside of the seed
//! Cornell box (`scenes/iray_cornell_box.mi`, scene units), directions uniform over the
//! sphere, from a fixed-seed generator so that every run traces the same rays.

use glam::Vec3A;
use render::ray::Ray;

/// `n` rays from inside the Cornell box in all directions, drawn by a 64-bit linear
/// congruential generator started at `seed`.
pub fn in_cornell_box(n: usize, seed: u64) -> Vec<Ray> {
    let mut state = seed;
    let mut rnd = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 40) as f32) / (1u64 << 24) as f32
    };
    (0..n)
        .map(|_| {
            let origin = Vec3A::new(20.0 + 510.0 * rnd(), 10.0 + 520.0 * rnd(), 10.0 + 540.0 * rnd());
            let z = 2.0 * rnd() - 1.0;
            let r = (1.0 - z * z).sqrt();
            let phi = std::f32::consts::TAU * rnd();
            Ray::new(origin, Vec3A::new(r * phi.cos(), r * phi.sin(), z))
        })
        .collect()
}
