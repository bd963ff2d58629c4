//! Which bounces of a path count as mental ray's reflection level (Maya's
//! `reflectionLimit`): the classic engine raises it for every reflection ray a shader
//! traces — mirror rays, and the glossy reflection rays of `mia_material` — but not for
//! final gather rays, which stand for diffuse bounces. The path engine counts a delta
//! reflection, and a sample of a `mia_material`-like BSDF ([`bsdf::Bsdf::Mia`]) or of
//! `mib_glossy_reflection` ([`bsdf::Bsdf::MibGlossy`], whose rays the classic shader casts
//! as reflection rays) in the same hemisphere with the probability that its glossy
//! reflection lobe gave it (its share of f there, [`bsdf::MiaBsdf::reflection_share`],
//! [`bsdf::MibGlossy::reflection_share`]), so that on average the paths past a glossy
//! bounce are counted as the classic engine counts its glossy rays.
//!
//! The refraction level (Maya's `refractionLimit`) counts a delta transmission, and every
//! transmitted sample of `mib_glossy_refraction` ([`bsdf::Bsdf::MibGlossyRefraction`],
//! whose rays through the surface the classic shader casts as refraction rays, but for
//! the sharp straight pass of `ior` 1, a transparency ray); its totally reflected samples
//! count as reflections (the classic shader casts them as reflection rays); a transmitted
//! sample its back material's diffuse transmission may have given counts with the glossy
//! lobe's share of f.

use bsdf::{Bsdf, BsdfSample};
use glam::Vec3A;

/// The `depth` offset of the number the glossy choice is made with (apart from the
/// cut-out choices', `cutout::cutout_number`).
pub(super) const SALT: u32 = 0x5eed_0000;

/// Whether the sample `bs` of `bsdf` seen from `wo` (local frame) is a reflection that
/// raises the reflection level; `u` gives a number in [0, 1) for the glossy choice (asked
/// only for a non-delta sample of a `mia_material`-like BSDF).
#[inline]
pub(super) fn reflects(bsdf: &Bsdf, wo: Vec3A, bs: &BsdfSample, u: impl FnOnce() -> f32) -> bool {
    if (bs.wi.z > 0.0) != (wo.z > 0.0) {
        return false;
    }
    if bs.delta {
        return true;
    }
    match bsdf {
        Bsdf::Mia(m) => {
            let share = m.reflection_share(wo, bs.wi);
            share > 0.0 && u() < share
        }
        Bsdf::MibGlossy(g) => {
            let share = g.reflection_share(wo, bs.wi);
            share > 0.0 && u() < share
        }
        Bsdf::MibGlossyRefraction(g) => {
            let share = g.glossy_share(wo, bs.wi);
            share > 0.0 && u() < share
        }
        _ => false,
    }
}

/// Whether the sample `bs` of `bsdf` seen from `wo` (local frame) is a transmission that
/// raises the refraction level; `u` gives a number in [0, 1) for the choice between
/// `mib_glossy_refraction`'s glossy lobe and its back material's diffuse transmission
/// (`render_reverse_of_back_material`, which the classic shader lights without casting a
/// refraction ray), by the glossy lobe's share of f.
#[inline]
pub(super) fn refracts(bsdf: &Bsdf, wo: Vec3A, bs: &BsdfSample, u: impl FnOnce() -> f32) -> bool {
    if (bs.wi.z > 0.0) == (wo.z > 0.0) {
        return false;
    }
    match bsdf {
        Bsdf::MibGlossyRefraction(g) if !bs.delta && g.base_transmits(wo) => {
            let share = g.glossy_share(wo, bs.wi);
            g.refracts() && share > 0.0 && u() < share
        }
        Bsdf::MibGlossyRefraction(g) => g.refracts(),
        _ => bs.delta,
    }
}
