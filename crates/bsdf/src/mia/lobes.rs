//! The shading functions of `mia_material`'s layers, as pure functions of directions.
//!
//! Conventions: `n` the unit shading normal facing the viewer, `v` the unit direction to
//! the viewer, `l` the unit direction to the light, `frame` the tangent frame whose `u`
//! axis is the anisotropy direction. Lights use mental ray's convention (a light colour
//! of 1 straight above a white Lambertian surface gives 1): the diffuse term has no 1/π,
//! and the highlights are π × a normalised BRDF × cos, so that both stay in proportion.
//! Sources and the reasoning behind each choice: `/work/notes/mia-details.md` (summarised
//! in the function docs).

use std::f32::consts::PI;

use glam::{Vec2, Vec3A};

use crate::Frame;

/// Hermite smoothstep of `x` over [a, b].
pub fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The author's terminator fix: the cosine with its lowest quarter smoothed,
/// cos · smoothstep(0, ¼, cos) — the cosine itself from ¼ up, with value and slope
/// continuous at ¼ and at 0.
pub fn smooth_cos(c: f32) -> f32 {
    if c <= 0.0 {
        0.0
    } else {
        c * smoothstep(0.0, 0.25, c)
    }
}

/// Oren–Nayar (the two-coefficient form) with roughness σ = `roughness` radians, times the
/// smoothed cosine: what a light of colour 1 from `l` gives a white surface (roughness 0:
/// the smoothed Lambert cosine).
pub fn oren_nayar(n: Vec3A, v: Vec3A, l: Vec3A, roughness: f32) -> f32 {
    let cos_i = n.dot(l);
    if cos_i <= 0.0 {
        return 0.0;
    }
    let lit = smooth_cos(cos_i);
    if roughness <= 0.0 {
        return lit;
    }
    let s2 = roughness * roughness;
    let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
    let b = 0.45 * s2 / (s2 + 0.09);
    let cos_r = n.dot(v).clamp(0.0, 1.0);
    let (sin_i, sin_r) = ((1.0 - cos_i * cos_i).max(0.0).sqrt(), (1.0 - cos_r * cos_r).max(0.0).sqrt());
    // cos(φi − φr) from the directions projected onto the tangent plane.
    let pi = (l - n * cos_i).normalize_or_zero();
    let pr = (v - n * cos_r).normalize_or_zero();
    let cos_phi = pi.dot(pr).max(0.0);
    // sin α tan β with α = max(θi, θr), β = min(θi, θr).
    let (sin_a, tan_b) =
        if cos_i < cos_r { (sin_i, sin_r / cos_r.max(1e-6)) } else { (sin_r, sin_i / cos_i.max(1e-6)) };
    lit * (a + b * cos_phi * sin_a * tan_b)
}

/// The Ward shininesses (1/α) along u and v for a base shininess and `anisotropy`, with
/// NVIDIA's "mia semantic" split (the geometric mean is kept): above 1 the u lobe is
/// `anisotropy` times narrower than the v lobe, below 1 wider by √anisotropy.
pub fn anisotropic_shininess(shiny: f32, anisotropy: f32) -> (f32, f32) {
    let a = anisotropy.max(1e-4);
    let iso = if a > 1.0 { (1.0 / a).sqrt() } else { a.powf(0.25) }.max(1e-4);
    // Roughness r_u = r/iso, r_v = r·iso for a > 1 (and the other way round below 1);
    // shininess is 1/roughness.
    if a > 1.0 {
        (shiny * iso, shiny / iso)
    } else {
        (shiny / iso, shiny * iso)
    }
}

/// The normalised Ward BRDF with shininesses (1/α) `su`, `sv` along the frame's tangent
/// and bitangent.
pub fn ward(frame: &Frame, v: Vec3A, l: Vec3A, su: f32, sv: f32) -> f32 {
    let n = frame.normal;
    let (cv, cl) = (n.dot(v), n.dot(l));
    if cv <= 0.0 || cl <= 0.0 {
        return 0.0;
    }
    let h = (v + l).normalize();
    let hn = h.dot(n);
    if hn <= 0.0 {
        return 0.0;
    }
    let (hu, hv) = (h.dot(frame.tangent) * su, h.dot(frame.bitangent) * sv);
    let e = -(hu * hu + hv * hv) / (hn * hn);
    su * sv * e.exp() / (4.0 * PI * (cv * cl).sqrt())
}

/// Weights and exponent divisors of the three highlight lobes.
pub const HIGHLIGHT_LOBES: [(f32, f32); 3] = [(1.0 / 6.0, 1.0), (1.0 / 3.0, 2.0), (1.0 / 2.0, 4.0)];

/// The base Ward shininess of glossiness `g`: 2^(8g) (1 at g = 0, 256 at g = 1).
pub fn base_shininess(gloss: f32) -> f32 {
    (2.0f32).powf(8.0 * gloss.clamp(0.0, 1.0))
}

/// The highlight a light of colour 1 from `l` makes (before the specular level): three
/// Ward lobes with shininess e, e/2, e/4 (e = [`base_shininess`]) weighted 1/6, 1/3, 1/2,
/// times π, N·L and the terminator smoothstep.
pub fn highlight(frame: &Frame, v: Vec3A, l: Vec3A, su: f32, sv: f32) -> f32 {
    let cl = frame.normal.dot(l);
    if cl <= 0.0 {
        return 0.0;
    }
    let lobes: f32 = HIGHLIGHT_LOBES.iter().map(|&(w, d)| w * ward(frame, v, l, su / d, sv / d)).sum();
    PI * lobes * cl * smoothstep(0.0, 0.25, cl)
}

/// A Ward half vector around the frame's normal for uniform numbers `u` (shininesses
/// `su`, `sv`; Walter's form of Ward's sampling).
pub fn sample_ward_half(frame: &Frame, su: f32, sv: f32, u: Vec2) -> Vec3A {
    let (au, av) = (1.0 / su.max(1e-4), 1.0 / sv.max(1e-4));
    let phi = (av / au * (2.0 * PI * u.y).tan()).atan();
    // Keep φ in the quadrant of 2πu.
    let phi = if u.y > 0.25 && u.y <= 0.75 {
        phi + PI
    } else if u.y > 0.75 {
        phi + 2.0 * PI
    } else {
        phi
    };
    let (sp, cp) = phi.sin_cos();
    let tan2 = -(1.0 - u.x).max(1e-12).ln() / (cp * cp / (au * au) + sp * sp / (av * av));
    let cos_t = 1.0 / (1.0 + tan2).sqrt();
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    frame.to_world(Vec3A::new(sin_t * cp, sin_t * sp, cos_t))
}

/// mia's glossy reflection direction for the `i`-th jitter `u`: a Ward half vector H about
/// the normal is used the way mental ray's glossy-direction function returns it — as the
/// normal reflected about H, a jittered normal — and the view ray is mirrored about that;
/// a ray that ends up below the geometric surface is flipped above it (the author's
/// "stretchiness" solution). `dir` is the incoming ray direction.
pub fn jittered_reflection(frame: &Frame, ng: Vec3A, dir: Vec3A, su: f32, sv: f32, u: Vec2) -> Vec3A {
    let n = frame.normal;
    let h = sample_ward_half(frame, su, sv, u);
    let jittered = (2.0 * n.dot(h) * h - n).normalize_or(n);
    let mut r = dir - 2.0 * dir.dot(jittered) * jittered;
    let below = r.dot(ng);
    if below < 0.0 {
        r -= 2.0 * below * ng;
    }
    r.normalize_or(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothed_cosine_matches_the_cosine_above_a_quarter_and_is_smooth() {
        assert_eq!(smooth_cos(0.5), 0.5);
        assert_eq!(smooth_cos(0.25), 0.25);
        assert_eq!(smooth_cos(0.0), 0.0);
        assert!((smooth_cos(0.1) - 0.1 * 0.352).abs() < 1e-6);
        // Slope 1 at ¼ from below.
        let d = (smooth_cos(0.25) - smooth_cos(0.25 - 1e-4)) / 1e-4;
        assert!((d - 1.0).abs() < 5e-3, "{d}");
    }

    #[test]
    fn oren_nayar_at_zero_roughness_is_the_smoothed_cosine_and_flattens_with_roughness() {
        let n = Vec3A::Z;
        let l = Vec3A::new(0.6, 0.0, 0.8);
        let v = Vec3A::new(-0.6, 0.0, 0.8);
        assert_eq!(oren_nayar(n, v, l, 0.0), 0.8);
        // Rough surfaces look brighter towards the light at grazing view (back-scatter).
        let grazing_v = Vec3A::new(0.95, 0.0, 0.312).normalize();
        assert!(oren_nayar(n, grazing_v, l, 1.0) > oren_nayar(n, v, l, 1.0));
    }

    #[test]
    fn ward_integrates_to_at_most_one_and_is_reciprocal() {
        let frame = Frame::from_normal(Vec3A::Z);
        let v = Vec3A::new(0.3, 0.1, 0.9).normalize();
        // ∫ f cos dω over the hemisphere (Monte Carlo with a fixed grid).
        let n = 400;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let (z, phi) = ((i as f32 + 0.5) / n as f32, 2.0 * PI * (j as f32 + 0.5) / n as f32);
                let r = (1.0 - z * z).sqrt();
                let l = Vec3A::new(r * phi.cos(), r * phi.sin(), z);
                sum += ward(&frame, v, l, 8.0, 8.0) * z;
            }
        }
        let albedo = sum * 2.0 * PI / (n * n) as f32;
        assert!(albedo < 1.0 && albedo > 0.8, "{albedo}");
        let l = Vec3A::new(-0.2, 0.4, 0.8).normalize();
        assert!((ward(&frame, v, l, 5.0, 20.0) - ward(&frame, l, v, 5.0, 20.0)).abs() < 1e-4);
    }

    #[test]
    fn highlight_lobes_weigh_one_sixth_one_third_one_half() {
        let sum: f32 = HIGHLIGHT_LOBES.iter().map(|l| l.0).sum();
        assert!((sum - 1.0).abs() < 1e-6);
        assert_eq!(base_shininess(1.0), 256.0);
        assert_eq!(base_shininess(0.5), 16.0);
        assert_eq!(base_shininess(0.0), 1.0);
    }

    #[test]
    fn anisotropy_keeps_the_mean_shininess() {
        let (u, v) = anisotropic_shininess(16.0, 4.0);
        assert!((u * v - 256.0).abs() < 1e-2 && v > u);
        assert_eq!(anisotropic_shininess(16.0, 1.0), (16.0, 16.0));
    }

    /// The jittered-normal reflections of a horizontal surface seen at a grazing angle are
    /// stretched: they spread far more up and down (in the plane of incidence) than to the
    /// side — the seed's figures 8–10.
    #[test]
    fn jittered_normal_reflections_stretch_in_the_plane_of_incidence() {
        let frame = Frame::from_normal(Vec3A::Z);
        let dir = Vec3A::new(0.0, 0.95, -0.312).normalize();
        let mirror = dir - 2.0 * dir.dot(Vec3A::Z) * Vec3A::Z;
        let (mut along, mut across) = (0.0, 0.0);
        for i in 0..32 {
            for j in 0..32 {
                let u = Vec2::new((i as f32 + 0.5) / 32.0, (j as f32 + 0.5) / 32.0);
                let r = jittered_reflection(&frame, Vec3A::Z, dir, 16.0, 16.0, u);
                assert!(r.z >= -1e-6, "below the surface: {r}");
                let d = r - mirror;
                along += d.z * d.z;
                across += d.x * d.x;
            }
        }
        assert!(along > 2.0 * across, "along {along} across {across}");
    }
}
