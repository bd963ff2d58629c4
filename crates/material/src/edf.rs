//! How a surface's emission is spread over directions when it is not Lambertian: MDL's
//! `df::spot_edf` ([`SpotEdf`]), `df::measured_edf` ([`MeasuredEdf`]) and their tints,
//! directional factors and mixes ([`EdfTree`]). The radiance towards a direction is the
//! material's `emission` times [`EmissionShape::factor`] (per channel).

use std::sync::Arc;

use bsdf::Rgb;
use glam::Vec3A;

use crate::edf_tree::EdfTree;
use crate::measured_edf::MeasuredEdf;
use crate::spot_edf::SpotEdf;

/// A non-Lambertian emission distribution.
#[derive(Clone, Debug, PartialEq)]
pub enum EmissionShape {
    /// A cosine lobe in a cone (`spot_edf`), normalised to the intensity.
    Spot(SpotEdf),
    /// A light profile (`measured_edf`), in candela times its multiplier.
    Measured(Arc<MeasuredEdf>),
    /// Tints, directional factors and mixes of `diffuse_edf`, `spot_edf` and
    /// `measured_edf`: radiance per unit of intensity, per channel.
    Tree(Arc<EdfTree>),
}

impl EmissionShape {
    /// The radiance towards `dir_out` (world space, unit) relative to `emission`, from a
    /// surface of shading normal `normal` (world space, unit) whose texture tangent is
    /// `tangent` (world space; orients a measured profile in the surface's frame); 0
    /// behind the surface.
    #[inline]
    pub fn factor(&self, normal: Vec3A, tangent: Option<Vec3A>, dir_out: Vec3A) -> Rgb {
        match self {
            EmissionShape::Spot(spot) => Rgb::splat(spot.factor(normal, dir_out)),
            EmissionShape::Measured(m) => Rgb::splat(m.factor(normal, tangent, dir_out)),
            EmissionShape::Tree(t) => t.radiance(normal, tangent, dir_out),
        }
    }
}
