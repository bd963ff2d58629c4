//! Combinations of emission distributions: MDL's `df::tint`, `df::directional_factor` and
//! the mixes (`normalized_mix`, `clamped_mix`, `unbounded_mix` and their `color_` forms) of
//! `diffuse_edf`, `spot_edf` and `measured_edf`. An [`EdfTree`] gives the radiance leaving
//! towards a direction per unit of the emission's intensity, per channel: the weighted sum
//! of its components' radiances, each scaled by the factors above it.

use std::sync::Arc;

use bsdf::Rgb;
use glam::Vec3A;

use crate::measured_edf::MeasuredEdf;
use crate::spot_edf::SpotEdf;

/// A tree of emission distributions whose weights are resolved (a mix's normalisation or
/// clamp already applied).
#[derive(Clone, Debug, PartialEq)]
pub enum EdfTree {
    /// `diffuse_edf`: 1/π on both sides (as mira's Lambertian emission).
    Diffuse,
    /// `spot_edf`: N · its shape in front of the surface, 0 behind ([`SpotEdf::factor`]).
    Spot(SpotEdf),
    /// `measured_edf`: multiplier × the profile's candela towards the direction, in the
    /// surface's frame (the hit's tangent) or its global frame; 0 behind the surface
    /// ([`MeasuredEdf::factor`]).
    Measured(Arc<MeasuredEdf>),
    /// A weighted sum of components (per-channel weights).
    Sum(Vec<(Rgb, EdfTree)>),
    /// `directional_factor`: the base scaled by normal + (grazing − normal)(1 − cos θ)^exponent,
    /// θ the angle between the direction of emission and the normal.
    Factor {
        /// The factor at normal emission.
        normal: Rgb,
        /// The factor at grazing emission.
        grazing: Rgb,
        /// The curve's exponent.
        exponent: f32,
        /// What is scaled.
        base: Box<EdfTree>,
    },
}

impl EdfTree {
    /// The radiance towards `dir_out` (world space, unit) per unit of intensity, from a
    /// surface of shading normal `normal` (world space, unit) whose `tangent_u` is
    /// `tangent` (world space; orients a measured profile in the surface's frame).
    pub fn radiance(&self, normal: Vec3A, tangent: Option<Vec3A>, dir_out: Vec3A) -> Rgb {
        match self {
            EdfTree::Diffuse => Rgb::splat(std::f32::consts::FRAC_1_PI),
            EdfTree::Spot(spot) => Rgb::splat(spot.normalization * spot.factor(normal, dir_out)),
            EdfTree::Measured(m) => Rgb::splat(m.factor(normal, tangent, dir_out)),
            EdfTree::Sum(parts) => {
                parts.iter().fold(Rgb::ZERO, |s, (w, t)| s + *w * t.radiance(normal, tangent, dir_out))
            }
            EdfTree::Factor { normal: n, grazing, exponent, base } => {
                let c = normal.dot(dir_out).abs().min(1.0);
                let t = (1.0 - c).max(0.0).powf(exponent.max(0.0));
                (*n + (*grazing - *n) * t) * base.radiance(normal, tangent, dir_out)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sum is the weighted sum of its parts and a factor of exponent e is the Schlick
    /// curve of the emission angle (1e-6 at 0°, 60° and 85°).
    #[test]
    fn sums_and_factors_follow_their_definitions() {
        let spot = SpotEdf::new(4.0, 2.0, None);
        let tree = EdfTree::Factor {
            normal: Rgb::new(1.0, 0.5, 0.2),
            grazing: Rgb::ONE,
            exponent: 3.0,
            base: Box::new(EdfTree::Sum(vec![
                (Rgb::new(0.3, 0.6, 0.9), EdfTree::Diffuse),
                (Rgb::splat(2.0), EdfTree::Spot(spot)),
            ])),
        };
        for deg in [0.0f32, 60.0, 85.0] {
            let d = Vec3A::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
            let c = d.z;
            let curve = Rgb::new(1.0, 0.5, 0.2) + (Rgb::ONE - Rgb::new(1.0, 0.5, 0.2)) * (1.0 - c).powi(3);
            let sum = Rgb::new(0.3, 0.6, 0.9) / std::f32::consts::PI
                + Rgb::splat(2.0 * spot.normalization * spot.factor(Vec3A::Z, d));
            let got = tree.radiance(Vec3A::Z, None, d);
            assert!((got - curve * sum).abs().max_element() < 1e-6, "{deg}°: {got:?}");
        }
    }
}
