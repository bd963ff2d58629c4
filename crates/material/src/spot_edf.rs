//! MDL's `df::spot_edf`: emission concentrated around an axis. The radiance leaving in a
//! direction at angle θ from the axis is the emission intensity (radiant exitance, W·m⁻²)
//! times N · cos(θ · π / spread)^exponent inside the cone of full opening angle `spread`
//! (the hemisphere's distribution rescaled to the cone), 0 outside it and behind the
//! surface. N makes the distribution emit the intensity (∫ over the hemisphere of the
//! radiance times cos θ is the intensity when the axis is the normal), as `diffuse_edf`
//! does with N = 1/π — a spot of exponent 0 and spread π is exactly `diffuse_edf`.
//! The axis is the shading normal, or, with `global_distribution`, the z axis of the
//! `global_frame` in world space.

use glam::Vec3A;

/// A spot emission distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotEdf {
    /// The cosine's exponent.
    pub exponent: f32,
    /// The cone's full opening angle (radians, in (0, π]).
    pub spread: f32,
    /// The axis in world space (unit), or `None`: the shading normal.
    pub global_axis: Option<Vec3A>,
    /// N: radiance per unit of intensity on the axis (sr⁻¹).
    pub normalization: f32,
}

impl SpotEdf {
    /// A spot of `exponent` and full opening angle `spread` (clamped to (0, π]) around
    /// `global_axis` (`None`: the normal).
    pub fn new(exponent: f32, spread: f32, global_axis: Option<Vec3A>) -> SpotEdf {
        let spread = if spread.is_finite() { spread.clamp(1e-4, std::f32::consts::PI) } else { std::f32::consts::PI };
        let exponent = if exponent.is_finite() { exponent.max(0.0) } else { 0.0 };
        let global_axis = global_axis.and_then(|a| a.try_normalize());
        let mut spot = SpotEdf { exponent, spread, global_axis, normalization: 1.0 };
        // ∫ shape(θ) cos θ dω over the cone (inside the hemisphere): midpoint rule in θ.
        const STEPS: usize = 4096;
        let top = (spread / 2.0).min(std::f32::consts::FRAC_PI_2) as f64;
        let mut sum = 0.0f64;
        for i in 0..STEPS {
            let t = (i as f64 + 0.5) / STEPS as f64 * top;
            sum += f64::from(spot.shape(t.cos() as f32)) * t.cos() * t.sin();
        }
        let integral = sum * top / STEPS as f64 * std::f64::consts::TAU;
        spot.normalization = if integral > 0.0 { (1.0 / integral) as f32 } else { 0.0 };
        spot
    }

    /// cos(θ π / spread)^exponent for the cosine `cos_axis` of the angle θ to the axis;
    /// 0 outside the cone.
    pub fn shape(&self, cos_axis: f32) -> f32 {
        let theta = cos_axis.clamp(-1.0, 1.0).acos();
        if theta >= self.spread / 2.0 {
            return 0.0;
        }
        let c = (theta * std::f32::consts::PI / self.spread).cos().max(0.0);
        if self.exponent == 0.0 {
            1.0
        } else {
            c.powf(self.exponent)
        }
    }

    /// The radiance leaving towards `dir_out` (world space, unit) from a surface of shading
    /// normal `normal` (world space, unit) relative to the radiance on the axis (which is
    /// N times the intensity): the shape, 0 behind the surface.
    pub fn factor(&self, normal: Vec3A, dir_out: Vec3A) -> f32 {
        if normal.dot(dir_out) <= 0.0 {
            return 0.0;
        }
        let axis = self.global_axis.unwrap_or(normal);
        self.shape(axis.dot(dir_out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Over the hemisphere (spread π) N = (exponent + 2) / 2π exactly: the integral of
    /// cosᵉθ cos θ is 2π / (e + 2). Within 1e-4 relative; exponent 0 is Lambert's 1/π.
    #[test]
    fn the_normalization_is_the_analytic_one_over_the_hemisphere() {
        for e in [0.0f32, 1.0, 4.0, 20.0] {
            let s = SpotEdf::new(e, std::f32::consts::PI, None);
            let n = (e + 2.0) / std::f32::consts::TAU;
            assert!((s.normalization / n - 1.0).abs() < 1e-4, "e {e}: {} vs {n}", s.normalization);
        }
    }

    /// A narrow cone: nothing outside spread/2, the rescaled cosine inside.
    #[test]
    fn a_narrow_spot_emits_inside_its_cone_only() {
        let s = SpotEdf::new(2.0, 1.0, None);
        let dir = |t: f32| Vec3A::new(t.sin(), 0.0, t.cos());
        assert_eq!(s.factor(Vec3A::Z, dir(0.51)), 0.0);
        let f = s.factor(Vec3A::Z, dir(0.25));
        assert!((f - (0.25 * std::f32::consts::PI).cos().powi(2)).abs() < 1e-6, "{f}");
        assert_eq!(s.factor(Vec3A::Z, -Vec3A::Z), 0.0);
    }
}
