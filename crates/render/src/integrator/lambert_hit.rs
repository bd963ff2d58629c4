//! The commonest hit's scattering, without the general BSDF's dispatch: a Lambertian
//! material (`material::SurfaceModel::Lambert`, constant or evaluated at the hit, without
//! a bump or normal map or tangent there). The path loop chooses it from the material's own description
//! ([`is_lambert`]); every number it gives is the general code's for
//! `Bsdf::Lambert(Lambert { albedo })` bit for bit (the same formulas in the same order:
//! [`bsdf::Lambert`], [`light_lobes`](super::light_lobes)), so images do not change.
//!
//! What it leaves out for such a hit, each a fact of the Lambertian lobe: it is no delta
//! (light sampling always applies), light cannot enter it (the normals face the ray), its
//! samples never raise the reflection or refraction level (`levels`: neither a mirror nor a
//! transmission) and have no glossy share (`glossy_reach`).

use bsdf::{BsdfSample, Rgb};
use glam::{Vec2, Vec3A};
use material::emission::maya::LightLobes;
use material::{HitMaterial, SurfaceModel};

/// Whether the hit material `m` scatters as one plain Lambertian lobe of its diffuse
/// colour in the frame of the shading normal (what `SurfaceModel::bsdf_in` then builds is
/// `Bsdf::Lambert` of that colour).
#[inline(always)]
pub(super) fn is_lambert(m: &HitMaterial) -> bool {
    matches!(*m.model, SurfaceModel::Lambert) && m.normal.is_none() && m.tangent.is_none()
}

/// f(ωo, ωi) of the lobe of reflectance `albedo` as a light with `lobes` sees it
/// (`light_lobes::eval` of `Bsdf::Lambert`): all of it for a light of diffuse light.
#[inline(always)]
pub(super) fn eval(albedo: Rgb, wo: Vec3A, wi: Vec3A, lobes: LightLobes) -> Rgb {
    let f = if wo.z * wi.z > 0.0 { albedo * std::f32::consts::FRAC_1_PI } else { Rgb::ZERO };
    if lobes.diffuse && lobes.specular {
        return f;
    }
    // (The general split: the diffuse part, and a specular part of zero.)
    let pick = |on: bool, f: Rgb| if on { f } else { Rgb::ZERO };
    pick(lobes.diffuse, f) + pick(lobes.specular, Rgb::ZERO)
}

/// The density of [`sample`]: |cos θi|/π on ωo's side, 0 on the other.
#[inline(always)]
pub(super) fn pdf(wo: Vec3A, wi: Vec3A) -> f32 {
    bsdf::cosine_pdf_on_side(wo, wi)
}

/// A cosine-weighted direction on ωo's side, picked by `u` (uniform in [0, 1)²).
#[inline(always)]
pub(super) fn sample(albedo: Rgb, wo: Vec3A, u: Vec2) -> Option<BsdfSample> {
    let wi = bsdf::cosine_on_side(wo, u)?;
    let pdf = bsdf::cosine_pdf_on_side(wo, wi);
    (pdf > 0.0).then(|| BsdfSample { wi, f: eval(albedo, wo, wi, LightLobes::default()), pdf, delta: false })
}

#[cfg(test)]
mod tests {
    use super::*;
    use bsdf::{Bsdf, Lambert};

    /// Directions all over the sphere (some exactly in the tangent plane), from a fixed
    /// sequence.
    fn directions(n: usize) -> Vec<Vec3A> {
        let mut z = 0x1234_5678_u64;
        let mut next = move || {
            z = z.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((z >> 40) as f32) / (1u64 << 24) as f32
        };
        (0..n)
            .map(|i| {
                let (a, b) = (next(), next());
                let zc = if i % 97 == 0 { 0.0 } else { 1.0 - 2.0 * a };
                let r = (1.0 - zc * zc).max(0.0).sqrt();
                let phi = std::f32::consts::TAU * b;
                Vec3A::new(r * phi.cos(), r * phi.sin(), zc)
            })
            .collect()
    }

    fn bits(c: Rgb) -> [u32; 3] {
        c.to_array().map(f32::to_bits)
    }

    /// The fast path's f, pdf and light-lobe f equal the general `Bsdf::Lambert`'s bit for
    /// bit (tolerance: none) for 4,000 direction pairs, both sides, three albedos and all
    /// four light-lobe choices.
    #[test]
    fn eval_and_pdf_equal_the_general_lambert_bit_for_bit() {
        let dirs = directions(4000);
        for albedo in [Rgb::new(0.7, 0.7, 0.7), Rgb::new(0.15, 0.7, 0.15), Rgb::new(1.0, 0.0, 0.3)] {
            let general = Bsdf::Lambert(Lambert { albedo });
            for pair in dirs.windows(2) {
                let (wo, wi) = (pair[0], pair[1]);
                assert_eq!(pdf(wo, wi).to_bits(), general.pdf(wo, wi).to_bits(), "{wo} {wi}");
                for (diffuse, specular) in [(true, true), (true, false), (false, true), (false, false)] {
                    let lobes = LightLobes { diffuse, specular };
                    let want = super::super::light_lobes::eval(&general, wo, wi, lobes);
                    assert_eq!(bits(eval(albedo, wo, wi, lobes)), bits(want), "{wo} {wi} {lobes:?}");
                }
            }
        }
    }

    /// The fast path's samples (direction, f, pdf, delta, and `None` where the general one
    /// gives none) equal `Bsdf::Lambert::sample`'s bit for bit (tolerance: none) on a
    /// 64 × 64 grid of sample numbers (its edges included) for 50 directions ωo on both
    /// sides and in the tangent plane; the weight f·cos/pdf is the albedo to 1e-6.
    #[test]
    fn samples_equal_the_general_lambert_bit_for_bit() {
        let albedo = Rgb::new(0.15, 0.7, 0.15);
        let general = Bsdf::Lambert(Lambert { albedo });
        let grid: Vec<f32> = (0..64).map(|i| i as f32 / 63.0 * (1.0 - f32::EPSILON)).collect();
        let (mut some, mut none) = (0, 0);
        for wo in directions(50) {
            for &x in &grid {
                for &y in &grid {
                    let u = Vec2::new(x, y);
                    let (fast, want) = (sample(albedo, wo, u), general.sample(wo, u, 0.5));
                    match (fast, want) {
                        (Some(a), Some(b)) => {
                            assert_eq!(a.wi.to_array().map(f32::to_bits), b.wi.to_array().map(f32::to_bits));
                            assert_eq!(bits(a.f), bits(b.f));
                            assert_eq!((a.pdf.to_bits(), a.delta), (b.pdf.to_bits(), b.delta));
                            assert!((a.weight() - albedo).abs().max_element() < 1e-6, "{:?}", a.weight());
                            some += 1;
                        }
                        (None, None) => none += 1,
                        (a, b) => panic!("wo {wo} u {u}: {a:?} against {b:?}"),
                    }
                }
            }
        }
        assert!(some > 100_000 && none > 0, "{some} samples, {none} without (ωo in the plane)");
    }
}
