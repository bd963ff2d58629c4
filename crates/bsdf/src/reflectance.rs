//! The highlight functions of mental ray's shader interface (`mi_phong_specular`,
//! `mi_blinn_specular`, `mi_cooktorr_specular`, `mi_ward_glossy`) and the Kajiya–Kay hair
//! terms, as pure functions of directions.
//!
//! Conventions: `view` is the ray direction (towards the surface, mental ray's
//! `state->dir`), `light` the unit direction from the point towards the light, `normal` the
//! unit shading normal facing the viewer.

use glam::Vec3A;

/// Phong: (R·L)^exponent with R the mirror direction of the view ray; 0 when R·L ≤ 0.
pub fn phong(exponent: f32, view: Vec3A, normal: Vec3A, light: Vec3A) -> f32 {
    let r = view - 2.0 * view.dot(normal) * normal;
    let c = r.dot(light);
    if c > 0.0 {
        c.powf(exponent)
    } else {
        0.0
    }
}

/// Fresnel reflectance of unpolarised light for relative index `eta` (inside / outside)
/// at incidence cosine `c` (Cook and Torrance's form).
pub fn fresnel(eta: f32, c: f32) -> f32 {
    let g2 = eta * eta + c * c - 1.0;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// The Torrance–Sparrow microfacet terms shared by Blinn and Cook–Torrance, in the form
/// mental images' sources cite (Foley et al., *Computer Graphics*, pp. 764–770): Beckmann
/// distribution D = exp(−(tan α / m)²) / (4 m² cos⁴ α) with m = `roughness` (the mean
/// microfacet slope), V-cavity masking G, over π (N·V)(N·L). Returns (D·G / (π (N·V)(N·L)),
/// cosine of the half vector with the view).
fn microfacet(view: Vec3A, light: Vec3A, normal: Vec3A, roughness: f32) -> Option<(f32, f32)> {
    let v = -view;
    let nv = normal.dot(v);
    let nl = normal.dot(light);
    if nv <= 0.0 || nl <= 0.0 {
        return None;
    }
    let h = (v + light).normalize();
    let nh = normal.dot(h).max(1e-6);
    let vh = v.dot(h).max(1e-6);
    let m = roughness.max(1e-4);
    let nh2 = nh * nh;
    let tan2 = (1.0 - nh2) / nh2;
    let d = (-tan2 / (m * m)).exp() / (4.0 * m * m * nh2 * nh2);
    let g = (2.0 * nh * nv / vh).min(2.0 * nh * nl / vh).min(1.0);
    Some((d * g / (std::f32::consts::PI * nv * nl), vh))
}

/// Blinn's highlight (Torrance–Sparrow with a scalar Fresnel term for relative index `ior`,
/// values below 1 taken as 1, which gives no highlight): multiplied by the light colour
/// only (not by N·L).
pub fn blinn(view: Vec3A, light: Vec3A, normal: Vec3A, roughness: f32, ior: f32) -> f32 {
    match microfacet(view, light, normal, roughness) {
        Some((dg, vh)) => dg * fresnel(ior.max(1.0), vh),
        None => 0.0,
    }
}

/// Cook–Torrance's highlight: as [`blinn`] with the Fresnel term per RGB channel.
pub fn cooktorr(view: Vec3A, light: Vec3A, normal: Vec3A, roughness: f32, ior: Vec3A) -> Vec3A {
    match microfacet(view, light, normal, roughness) {
        Some((dg, vh)) => Vec3A::new(
            dg * fresnel(ior.x.max(1.0), vh),
            dg * fresnel(ior.y.max(1.0), vh),
            dg * fresnel(ior.z.max(1.0), vh),
        ),
        None => Vec3A::ZERO,
    }
}

/// Ward's anisotropic glossy BRDF with brushing directions `u`, `v` and inverse widths
/// `shiny_u`, `shiny_v` (α = 1/shiny; mental ray's "5 is very wide, 100 very narrow"):
/// exp(−tan²δ (cos²φ/αu² + sin²φ/αv²)) / (4π αu αv √(cosθi cosθo)); mental ray's
/// `mib_illum_ward` multiplies it by N·L and the light colour.
pub fn ward(view: Vec3A, light: Vec3A, normal: Vec3A, u: Vec3A, v: Vec3A, shiny_u: f32, shiny_v: f32) -> f32 {
    let o = -view;
    let ci = normal.dot(light);
    let co = normal.dot(o);
    if ci <= 0.0 || co <= 0.0 {
        return 0.0;
    }
    let au = 1.0 / shiny_u.max(1e-3);
    let av = 1.0 / shiny_v.max(1e-3);
    let h = light + o;
    let hn = h.dot(normal);
    if hn <= 0.0 {
        return 0.0;
    }
    let hu = h.dot(u) / au;
    let hv = h.dot(v) / av;
    let exponent = -(hu * hu + hv * hv) / (hn * hn);
    exponent.exp() / (4.0 * std::f32::consts::PI * au * av * (ci * co).sqrt())
}

/// The hair highlight of `mib_illum_hair`: sin(t, H)^exponent with H the half vector of
/// the light direction `l` and the direction to the viewer `v` (a Kajiya–Kay highlight on
/// the half vector).
pub fn hair_specular(t: Vec3A, l: Vec3A, v: Vec3A, exponent: f32) -> f32 {
    let h = (v + l).normalize_or_zero();
    let th = t.dot(h);
    let s = 1.0 - th * th;
    if s > 0.0 {
        s.powf(exponent * 0.5)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phong_peaks_in_the_mirror_direction_and_falls_as_a_cosine_power() {
        let n = Vec3A::Z;
        let view = Vec3A::new(1.0, 0.0, -1.0).normalize();
        let mirror = Vec3A::new(1.0, 0.0, 1.0).normalize();
        assert!((phong(20.0, view, n, mirror) - 1.0).abs() < 1e-5);
        // 10° off the mirror direction: cos(10°)^20.
        let a = 45f32.to_radians() + 10f32.to_radians();
        let off = Vec3A::new(a.sin(), 0.0, a.cos());
        let expected = 10f32.to_radians().cos().powf(20.0);
        assert!((phong(20.0, view, n, off) - expected).abs() < 1e-5);
        assert_eq!(phong(20.0, view, n, -mirror), 0.0);
    }

    #[test]
    fn fresnel_matches_known_values() {
        // Normal incidence: ((n−1)/(n+1))² = 0.04 for n = 1.5.
        assert!((fresnel(1.5, 1.0) - 0.04).abs() < 1e-6);
        // Grazing: 1.
        assert!((fresnel(1.5, 1e-4) - 1.0).abs() < 1e-2);
        // 60° in glass from air (tabulated 0.0892).
        assert!((fresnel(1.5, 60f32.to_radians().cos()) - 0.0892).abs() < 1e-3);
    }

    #[test]
    fn highlights_are_reciprocal() {
        let n = Vec3A::Z;
        let a = Vec3A::new(0.3, 0.2, 0.9).normalize();
        let b = Vec3A::new(-0.5, 0.1, 0.7).normalize();
        let u = Vec3A::X;
        let v = Vec3A::Y;
        // view = −(direction to viewer): swapping viewer and light.
        assert!((blinn(-a, b, n, 0.3, 1.5) - blinn(-b, a, n, 0.3, 1.5)).abs() < 1e-5);
        assert!((ward(-a, b, n, u, v, 5.0, 10.0) - ward(-b, a, n, u, v, 5.0, 10.0)).abs() < 1e-5);
    }
}
