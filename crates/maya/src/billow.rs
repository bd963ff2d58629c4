//! The cells of Maya's Billow noise type (noise and volumeNoise, `noiseType` 1): puffy
//! blobs scattered over a grid, one octave of [`crate::noise::Noise`]'s fractal.
//!
//! Maya's node reference names the attributes and what they do, with their defaults:
//! `density` (1: "how many cells are embedded in the medium", 1 fully packed),
//! `spottyness` (0.1: the randomisation of each cell's intensity), `sizeRand` (0: the
//! randomisation of the blobs' sizes), `randomness` (1: 0 lays the cells out in a
//! regular lattice, 1 a random distribution) and `falloff` (2, Fast: how a blob's
//! intensity falls off: Linear, Smooth — "Gaussian" —, Fast — "focuses the intensity
//! towards the centre" — and Bubble — "a reverse falloff, fading to zero at the blob
//! centre"). It gives no formulas; these are mira's:
//!
//! ```text
//! cell c (integer grid, of the octave's coordinate), r_1, r_2, … hashes of c and the octave in [0, 1)
//! blob present when  r_d < density
//! centre     x_c = c + ½ + randomness · (r_x − ½, r_y − ½[, r_z − ½])   (randomness in [0, 1])
//! radius     R_c = RADIUS · (1 − sizeRand · r_s)                        (sizeRand in [0, 1], RADIUS = 0.75)
//! intensity  s_c = 1 − spottyness · r_i                                 (spottyness in [0, 1])
//! blob       b_c(p) = s_c · f(|p − x_c| / R_c),  f(t) = 0 for t ≥ 1
//! octave     n(p) = 1 − Π_c (1 − b_c(p))   over the 3×3 (3D: 3×3×3) cells around p
//!
//! Linear  f(t) = 1 − t
//! Smooth  f(t) = (e^(−4t²) − e^(−4)) / (1 − e^(−4))     (a Gaussian brought to 0 at the edge)
//! Fast    f(t) = (1 − t)²
//! Bubble  f(t) = (27/4) · t² · (1 − t)                   (0 at the centre and edge, 1 at t = ⅔)
//! ```
//!
//! n is in [0, 1], a lone blob's own value where blobs do not overlap, continuous
//! (every curve is 0 at the edge), and no blob reaches past the cells around its own
//! (|x_c − c − ½| ≤ ½ per axis and R_c ≤ 0.75 < 1). The 2D texture's cells lie in the
//! (u, v) plane of the octave's coordinate, with `time` moving the point along (1, 1)
//! (mira's reading, like volumeNoise's shift along (1, 1, 1)). The pattern is mira's,
//! not Maya's.

use glam::Vec3A;

use crate::lattice_hash::lattice;

/// The radius of a blob of `sizeRand` 0, in cells.
pub const RADIUS: f32 = 0.75;

/// How a blob's intensity falls from its centre to its edge (Maya's `falloff`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Falloff {
    /// 0: 1 − t.
    Linear,
    /// 1: a Gaussian, (e^(−4t²) − e^(−4)) / (1 − e^(−4)).
    Smooth,
    /// 2 (Maya's default): (1 − t)².
    Fast,
    /// 3: (27/4) t² (1 − t), zero at the centre.
    Bubble,
}

impl Falloff {
    /// Maya's `falloff` enum (unknown values read as Fast, the default).
    pub fn from_maya(value: i32) -> Falloff {
        match value {
            0 => Falloff::Linear,
            1 => Falloff::Smooth,
            3 => Falloff::Bubble,
            _ => Falloff::Fast,
        }
    }

    /// The curve at t = distance / radius (0 at t ≥ 1 and for NaN).
    pub fn curve(self, t: f32) -> f32 {
        // NaN fails the comparison: no contribution.
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(t < 1.0) {
            return 0.0;
        }
        let t = t.max(0.0);
        match self {
            Falloff::Linear => 1.0 - t,
            Falloff::Smooth => {
                let edge = (-4.0f32).exp();
                ((-4.0 * t * t).exp() - edge) / (1.0 - edge)
            }
            Falloff::Fast => (1.0 - t) * (1.0 - t),
            Falloff::Bubble => 6.75 * t * t * (1.0 - t),
        }
    }
}

/// The Billow cells' settings (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cells {
    /// `density`: the probability that a cell holds a blob.
    pub density: f32,
    /// `spottyness`: how much a blob's intensity may drop below 1.
    pub spottyness: f32,
    /// `sizeRand`: how much a blob's radius may drop below [`RADIUS`].
    pub size_rand: f32,
    /// `randomness`: how far blob centres move from the cell centres (1: anywhere in
    /// the cell).
    pub randomness: f32,
    /// `falloff`.
    pub falloff: Falloff,
}

impl Cells {
    /// Maya's defaults.
    pub const MAYA_DEFAULT: Cells =
        Cells { density: 1.0, spottyness: 0.1, size_rand: 0.0, randomness: 1.0, falloff: Falloff::Fast };

    /// The octave's value at `p` (octave coordinates), in [0, 1]; `planar`: cells in
    /// the (x, y) plane (z ignored), else in space.
    pub fn at(&self, p: Vec3A, octave: u32, planar: bool) -> f32 {
        if !p.is_finite() {
            return 0.0;
        }
        let p = if planar { Vec3A::new(p.x, p.y, 0.0) } else { p };
        let f = p.floor();
        let (i, j, k) = (f.x as i32, f.y as i32, f.z as i32);
        let jitter = self.randomness.clamp(0.0, 1.0);
        let size_rand = self.size_rand.clamp(0.0, 1.0);
        let spotty = self.spottyness.clamp(0.0, 1.0);
        let layers = if planar { 0..=0 } else { -1..=1 };
        let mut clear = 1.0f32;
        for dk in layers {
            for dj in -1..=1 {
                for di in -1..=1 {
                    // Wrapping: a hostile frequency puts the lattice at the edge of i32.
                    let (ci, cj, ck) = (i.wrapping_add(di), j.wrapping_add(dj), k.wrapping_add(dk));
                    let cell = lattice(ci, cj, ck) as i32;
                    let r = |salt: i32| (lattice(cell, octave as i32, salt) >> 8) as f32 / (1u32 << 24) as f32;
                    if r(0) >= self.density {
                        continue;
                    }
                    let offset = Vec3A::new(r(1) - 0.5, r(2) - 0.5, if planar { 0.0 } else { r(3) - 0.5 });
                    let base = Vec3A::new(f.x + di as f32, f.y + dj as f32, f.z + dk as f32);
                    let centre = base + Vec3A::new(0.5, 0.5, if planar { 0.0 } else { 0.5 }) + jitter * offset;
                    let radius = RADIUS * (1.0 - size_rand * r(4));
                    if radius <= 0.0 {
                        continue;
                    }
                    let blob = (1.0 - spotty * r(5)) * self.falloff.curve(p.distance(centre) / radius);
                    clear *= 1.0 - blob;
                }
            }
        }
        (1.0 - clear).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each curve at hand-computed radii (1e-5): t = 0.5 and 0.2; 0 from the edge on.
    #[test]
    fn falloff_curves_match_their_formulas() {
        let smooth = |t: f64| (((-4.0 * t * t).exp() - (-4.0f64).exp()) / (1.0 - (-4.0f64).exp())) as f32;
        // (e^-1 − e^-4) / (1 − e^-4) = 0.356086, (e^-0.16 − e^-4) / (1 − e^-4) = 0.849385.
        assert!((smooth(0.5) - 0.356086).abs() < 1e-5 && (smooth(0.2) - 0.849385).abs() < 1e-5);
        let cases = [
            (Falloff::Linear, [1.0, 0.5, 0.8]),
            (Falloff::Smooth, [1.0, 0.356086, 0.849385]),
            (Falloff::Fast, [1.0, 0.25, 0.64]),
            // 27/4 · 0.25 · 0.5 = 0.84375, 27/4 · 0.04 · 0.8 = 0.216.
            (Falloff::Bubble, [0.0, 0.84375, 0.216]),
        ];
        for (falloff, [at0, at_half, at_fifth]) in cases {
            assert!((falloff.curve(0.0) - at0).abs() < 1e-5, "{falloff:?}");
            assert!((falloff.curve(0.5) - at_half).abs() < 1e-5, "{falloff:?}");
            assert!((falloff.curve(0.2) - at_fifth).abs() < 1e-5, "{falloff:?}");
            for t in [1.0, 1.5, f32::NAN, f32::INFINITY] {
                assert_eq!(falloff.curve(t), 0.0, "{falloff:?} at {t}");
            }
            // Continuous at the edge.
            assert!(falloff.curve(0.9999) < 1e-3, "{falloff:?}");
        }
        assert!((Falloff::Bubble.curve(2.0 / 3.0) - 1.0).abs() < 1e-5);
        assert_eq!(Falloff::from_maya(0), Falloff::Linear);
        assert_eq!(Falloff::from_maya(1), Falloff::Smooth);
        assert_eq!(Falloff::from_maya(2), Falloff::Fast);
        assert_eq!(Falloff::from_maya(3), Falloff::Bubble);
        assert_eq!(Falloff::from_maya(9), Falloff::Fast);
    }

    /// Randomness 0: every blob sits at its cell's centre, so the value there is the
    /// curve's value at 0 (the neighbours' blobs, a cell away, do not reach it: R = 0.75),
    /// and at 0.15 from the centre (t = 0.2, still out of the neighbours' reach) the
    /// curve at 0.2; with spottyness 0 in 2D and 3D, every cell shows the same peak.
    #[test]
    fn regular_cells_peak_at_their_centres() {
        for falloff in [Falloff::Linear, Falloff::Smooth, Falloff::Fast, Falloff::Bubble] {
            let cells = Cells { randomness: 0.0, spottyness: 0.0, falloff, ..Cells::MAYA_DEFAULT };
            for (i, j, k) in [(0, 0, 0), (3, -2, 5), (-7, 11, -1)] {
                let centre = Vec3A::new(i as f32 + 0.5, j as f32 + 0.5, k as f32 + 0.5);
                for octave in [0, 2] {
                    assert!((cells.at(centre, octave, false) - falloff.curve(0.0)).abs() < 1e-5);
                    let planar = cells.at(Vec3A::new(centre.x, centre.y, 9.3), octave, true);
                    assert!((planar - falloff.curve(0.0)).abs() < 1e-5);
                    let off = cells.at(centre + Vec3A::new(0.09, 0.0, 0.12), octave, false);
                    assert!((off - falloff.curve(0.2)).abs() < 1e-5, "{falloff:?}: {off}");
                }
            }
        }
    }

    /// Spottyness 0 gives every blob the same peak (1); spottyness 1 spreads the peaks
    /// (the blob of sizeRand 1 keeps its centre value: only the radius changes).
    #[test]
    fn spottyness_varies_the_peaks() {
        let peaks = |spottyness: f32, size_rand: f32| -> Vec<f32> {
            let cells =
                Cells { randomness: 0.0, spottyness, size_rand, falloff: Falloff::Linear, ..Cells::MAYA_DEFAULT };
            (0..100).map(|c| cells.at(Vec3A::new(c as f32 + 0.5, (c * 7) as f32 + 0.5, 0.0), 0, true)).collect()
        };
        assert!(peaks(0.0, 0.0).iter().all(|&v| (v - 1.0).abs() < 1e-6));
        assert!(peaks(0.0, 1.0).iter().all(|&v| (v - 1.0).abs() < 1e-6));
        let spotty = peaks(1.0, 0.0);
        let (lo, hi) = spotty.iter().fold((1f32, 0f32), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        assert!(lo >= 0.0 && hi <= 1.0 && hi - lo > 0.5, "{lo}..{hi}");
    }

    /// Density 0: no blob anywhere, exactly 0; density 0.5: about half the cells of a
    /// regular grid hold a blob (1000 cells, 0.5 ± 0.08).
    #[test]
    fn density_is_the_share_of_cells_with_a_blob() {
        let none = Cells { density: 0.0, ..Cells::MAYA_DEFAULT };
        for c in 0..200 {
            let p = Vec3A::new(c as f32 * 0.37, c as f32 * 0.11, c as f32 * 0.05);
            assert_eq!(none.at(p, 0, false), 0.0);
            assert_eq!(none.at(p, 1, true), 0.0);
        }
        let half = Cells { density: 0.5, randomness: 0.0, ..Cells::MAYA_DEFAULT };
        let filled = (0..1000).filter(|&c| half.at(Vec3A::new(c as f32 + 0.5, 0.5, 0.0), 0, true) > 0.0).count();
        assert!((filled as f32 / 1000.0 - 0.5).abs() < 0.08, "{filled}");
    }

    /// In range, deterministic and continuous over random cells, 2D and 3D; hostile
    /// points give 0.
    #[test]
    fn cells_stay_in_range_and_continuous() {
        let cells = Cells { size_rand: 0.5, spottyness: 0.5, falloff: Falloff::Smooth, ..Cells::MAYA_DEFAULT };
        let (mut lo, mut hi) = (1f32, 0f32);
        for i in 0..2000 {
            let p = Vec3A::new(i as f32 * 0.173 - 50.0, i as f32 * 0.0713, (i % 37) as f32 * 0.29);
            for planar in [true, false] {
                let v = cells.at(p, 1, planar);
                assert!((0.0..=1.0).contains(&v) && v == cells.at(p, 1, planar));
                assert!((cells.at(p + Vec3A::splat(1e-4), 1, planar) - v).abs() < 0.01, "jump at {p}");
                (lo, hi) = (lo.min(v), hi.max(v));
            }
        }
        assert!(lo < 0.05 && hi > 0.8, "{lo}..{hi}");
        for p in [Vec3A::splat(f32::NAN), Vec3A::splat(f32::INFINITY)] {
            assert_eq!(cells.at(p, 0, false), 0.0);
        }
        assert!((0.0..=1.0).contains(&cells.at(Vec3A::splat(3e9), 0, false)));
    }
}
