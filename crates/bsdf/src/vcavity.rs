//! The V-cavity masking–shadowing of micro-mirror reflection (Heitz 2014, "Understanding
//! the Masking-Shadowing Function in Microfacet-Based BRDFs", §3.2 and appendix; after
//! Torrance and Sparrow's symmetric V-grooves): each micro-normal m is one face of a
//! V-groove whose other face mirrors it about the normal, so what hides it is a closed
//! form of the three directions,
//!
//! G(ωo, ωi, m) = min(1, 2 (n·m)(n·ωo)/(ωo·m), 2 (n·m)(n·ωi)/(ωi·m)),
//!
//! symmetric in ωo and ωi (the lobes are reciprocal). MDL's `microfacet_ggx_vcavities_bsdf`
//! and `microfacet_beckmann_vcavities_bsdf` are micro-mirrors of the GGX or Beckmann
//! distribution with it instead of Smith's G2; they are sampled as their Smith forms are
//! (GGX: visible normals; Beckmann: D(h) cos θh) with the density of that sampling. Local
//! frame, z = the normal n; directions on the upper side.

use glam::Vec3A;

use crate::beckmann::Beckmann;
use crate::microfacet::Ggx;

/// The V-cavity masking–shadowing G(ωo, ωi, m) of the micro-normal `m` for the
/// directions `o` and `i` (local frame, z > 0): 0 where either direction sees the back of
/// the micro-facet.
pub fn g(o: Vec3A, i: Vec3A, m: Vec3A) -> f32 {
    let (om, im) = (o.dot(m), i.dot(m));
    if om <= 0.0 || im <= 0.0 || m.z <= 0.0 || o.z <= 0.0 || i.z <= 0.0 {
        return 0.0;
    }
    let shadow = |w: Vec3A, wm: f32| 2.0 * m.z * w.z / wm;
    shadow(o, om).min(shadow(i, im)).min(1.0)
}

/// The V-cavity masking of one direction `k` by the groove of micro-normal `m`, from
/// either side of the surface: G1(k, m) = min(1, 2 |n·m| |n·k| / |k·m|) (local frame, n =
/// z; which side sees which face is the caller's check).
pub fn g1(k: Vec3A, m: Vec3A) -> f32 {
    let km = k.dot(m).abs();
    if km == 0.0 {
        return 1.0;
    }
    (2.0 * m.z.abs() * k.z.abs() / km).min(1.0)
}

/// The V-cavity masking–shadowing of a pair of directions on the same side (reflection,
/// from either side): min(G1(ωo), G1(ωi)) — [`g`] without its checks of sides.
pub fn g_reflect(o: Vec3A, i: Vec3A, m: Vec3A) -> f32 {
    g1(o, m).min(g1(i, m))
}

/// The V-cavity masking–shadowing of a pair on opposite sides (refraction through the
/// face `m`): max(0, G1(ωo) + G1(ωi) − 1), the form the MDL SDK's libbsdf gives
/// transmitted pairs (the light that is neither masked on the way in nor shadowed on the
/// way out when the two are as anti-correlated as they can be); symmetric, and at most
/// the reflection's min(G1(ωo), G1(ωi)).
pub fn g_refract(o: Vec3A, i: Vec3A, m: Vec3A) -> f32 {
    (g1(o, m) + g1(i, m) - 1.0).max(0.0)
}

/// ωo and ωi flipped onto +z together when ωo is below (two-sided), with their half
/// vector; `None` when they lie on opposite sides or have no half vector.
fn upper_half(wo: Vec3A, wi: Vec3A) -> Option<(Vec3A, Vec3A, Vec3A)> {
    if wo.z * wi.z <= 0.0 {
        return None;
    }
    let flip = |w: Vec3A| Vec3A::new(w.x, w.y, w.z.abs());
    let (o, i) = (flip(wo), flip(wi));
    let h = (o + i).try_normalize()?;
    Some((o, i, h))
}

/// GGX micro-mirrors with V-cavity shadowing: f = D(h) G(ωo, ωi, h) / (4 |cos θo cos θi|)
/// on ωo's side (no Fresnel term).
pub fn ggx_eval(g_dist: &Ggx, wo: Vec3A, wi: Vec3A) -> f32 {
    if g_dist.is_smooth() {
        return 0.0;
    }
    upper_half(wo, wi).map_or(0.0, |(o, i, h)| g_dist.d(h) * g(o, i, h) / (4.0 * o.z * i.z))
}

/// Beckmann micro-mirrors with V-cavity shadowing: f = D(h) G(ωo, ωi, h) / (4 |cos θo
/// cos θi|) on ωo's side (no Fresnel term).
pub fn beckmann_eval(b: &Beckmann, wo: Vec3A, wi: Vec3A) -> f32 {
    upper_half(wo, wi).map_or(0.0, |(o, i, h)| b.d(h) * g(o, i, h) / (4.0 * o.z * i.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form at hand-computed configurations: facing the normal nothing hides
    /// (G = 1, 1e-6); m = n never hides itself (a mirror pair at 80°: 1); m tilted 45°
    /// towards +x seen from 80° towards +x (ωi its mirror about m, at 10°): G =
    /// 2 cos 45° cos 80° / cos 35° = 0.299787 (1e-5), symmetric in the two directions; a
    /// micro-normal whose back faces ωo, or below the surface, is hidden (0).
    #[test]
    fn the_masking_is_its_closed_form() {
        let n = Vec3A::Z;
        assert!((g(n, n, n) - 1.0).abs() < 1e-6);
        let t = 80f32.to_radians();
        let (o, i) = (Vec3A::new(t.sin(), 0.0, t.cos()), Vec3A::new(-t.sin(), 0.0, t.cos()));
        assert!((g(o, i, n) - 1.0).abs() < 1e-6);
        let m = Vec3A::new(std::f32::consts::FRAC_1_SQRT_2, 0.0, std::f32::consts::FRAC_1_SQRT_2);
        let o = Vec3A::new(t.sin(), 0.0, t.cos());
        let i = 2.0 * o.dot(m) * m - o;
        assert!((i.z - 10f32.to_radians().cos()).abs() < 1e-5, "{i}");
        assert!((g(o, i, m) - 0.299_787).abs() < 1e-5, "{}", g(o, i, m));
        assert_eq!(g(o, i, m), g(i, o, m));
        // The same groove turned about the normal (the form depends on angles only).
        let turn = glam::Mat3A::from_rotation_z(1.1);
        assert!((g(turn * o, turn * i, turn * m) - 0.299_787).abs() < 1e-5);
        // ωo at 80° towards −x sees the back of m.
        let back = Vec3A::new(-t.sin(), 0.0, t.cos());
        assert_eq!(g(back, n, m), 0.0);
        assert_eq!(g(n, n, Vec3A::new(0.0, 0.6, -0.8)), 0.0);
    }
}
