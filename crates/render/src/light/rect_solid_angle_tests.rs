//! Tests of solid-angle sampling of rectangle lights: the density, where samples land, their
//! distribution, irradiance against the closed form, and the density `pdf` reports.

use super::*;
use crate::light::{rect_sample, rect_sample_by_area, LightSource, Output, Shape};
use bsdf::Rgb;
use scene::LightKind;

/// A rectangle light 2 × 1 centred at (0.3, −0.2, 2), its edges turned about Z by 0.4 rad,
/// facing −Z (down).
fn rect_light(two_sided: bool) -> LightSource {
    let (s, c) = 0.4f32.sin_cos();
    let shape = Shape::rect(Vec3A::new(2.0 * c, 2.0 * s, 0.0), Vec3A::new(-s, c, 0.0), -Vec3A::Z);
    LightSource {
        name: "rect".into(),
        kind: LightKind::Point,
        position: Vec3A::new(0.3, -0.2, 2.0),
        direction: -Vec3A::Z,
        rect_frame: RectFrame::of(&shape),
        shape,
        output: Output::Radiance { l: Rgb::new(4.0, 3.0, 2.0), two_sided },
        spread: 0.0,
        cone: None,
        spot_exponent: None,
        maya_spot: None,
        visible: true,
        shadow: true,
        shadow_color: Rgb::ZERO,
        soft_shadow: None,
        motion: Vec::new(),
        lobes: Default::default(),
    }
}

/// The light's centre, edges, normal and area.
fn rect_of(light: &LightSource) -> (Vec3A, Vec3A, Vec3A, Vec3A, f32) {
    let Shape::Rect { u, v, normal, area, .. } = light.shape else { unreachable!() };
    (light.position, u, v, normal, area)
}

/// The light's frame (it has one: its edges are orthogonal).
fn frame_of(light: &LightSource) -> RectFrame {
    light.rect_frame.expect("a rectangle with orthogonal edges has a frame")
}

/// Numbers in [0, 1) from a SplitMix64 stream.
fn numbers(seed: u64) -> impl FnMut() -> f32 {
    let mut z = seed;
    move || {
        z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut x = z;
        x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((x ^ (x >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The solid angle (f64) of the part [s0, s1] × [t0, t1] (fractions of the edges) of the
/// rectangle seen from `p`: ∫ cos / dist² dA by the midpoint rule on n × n cells.
fn solid_angle_of_part(light: &LightSource, p: Vec3A, (s0, s1): (f64, f64), (t0, t1): (f64, f64), n: usize) -> f64 {
    let (c, eu, ev, normal, area) = rect_of(light);
    let [c, eu, ev, normal, p] = [c, eu, ev, normal, p].map(|v| v.as_dvec3());
    let cell = f64::from(area) * (s1 - s0) * (t1 - t0) / (n * n) as f64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let s = s0 + (s1 - s0) * (i as f64 + 0.5) / n as f64;
            let t = t0 + (t1 - t0) * (j as f64 + 0.5) / n as f64;
            let d = c + eu * (s - 0.5) + ev * (t - 0.5) - p;
            let r2 = d.length_squared();
            sum += d.dot(normal).abs() / (r2 * r2.sqrt()) * cell;
        }
    }
    sum
}

/// Points where the light is sampled in solid angle: close under it, beside it, off
/// centre, further down, and above it.
const VIEWPOINTS: [[f32; 3]; 6] =
    [[0.3, -0.2, 1.9], [0.5, 0.1, 1.5], [1.4, -0.6, 1.5], [-0.5, 0.8, 0.8], [0.0, 0.0, 0.0], [0.0, 0.5, 3.0]];

/// ∫ pdf dω over the directions that reach the light is 1 (relative 1e-3), the integral
/// taken over the rectangle's area (dω = cos / dist² dA, 800² cells, f64), from points near
/// and far; every one of them is sampled in solid angle.
#[test]
fn density_integrates_to_one() {
    let light = rect_light(false);
    for p in VIEWPOINTS.map(Vec3A::from) {
        let pdf = light.pdf(p, Vec3A::Z, 1.0);
        let (c, ..) = rect_of(&light);
        assert!(frame_of(&light).view(c, p).is_some(), "{p} is sampled in solid angle");
        let integral = f64::from(pdf) * solid_angle_of_part(&light, p, (0.0, 1.0), (0.0, 1.0), 800);
        assert!((integral - 1.0).abs() < 1e-3, "∫ pdf dω = {integral} from {p}");
    }
}

/// Samples land on the rectangle: within 1e-4 of its plane and inside its edges (to 1e-4 of
/// their lengths), from every viewpoint, for 20 000 numbers each.
#[test]
fn samples_land_on_the_rectangle() {
    let light = rect_light(true);
    let (c, eu, ev, normal, _) = rect_of(&light);
    let mut r = numbers(7);
    for p in VIEWPOINTS.map(Vec3A::from) {
        let rect = frame_of(&light).view(c, p).expect("in solid angle");
        for k in 0..20_000 {
            // The corners of the unit square too.
            let u = if k < 4 { Vec2::new((k & 1) as f32, (k >> 1) as f32 * 0.9999999) } else { Vec2::new(r(), r()) };
            let q = rect.point(u);
            let rel = q - c;
            assert!(rel.dot(normal).abs() < 1e-4, "{q} off the plane by {} from {p}", rel.dot(normal));
            let s = rel.dot(eu) / eu.length_squared();
            let t = rel.dot(ev) / ev.length_squared();
            assert!(s.abs() <= 0.5 + 1e-4 && t.abs() <= 0.5 + 1e-4, "{q} outside ({s}, {t}) from {p}");
        }
    }
}

/// Chi-square test of the sampled directions against the density: the rectangle cut into
/// 8 × 8 cells, each cell's expected count N · Ω_cell / Ω (Ω_cell integrated in f64), for
/// 200 000 samples; χ² (63 degrees of freedom) below 110 (p ≈ 2·10⁻⁴), from each viewpoint.
#[test]
fn directions_follow_the_density_chi_square() {
    let light = rect_light(true);
    let (c, eu, ev, ..) = rect_of(&light);
    let mut r = numbers(11);
    const CELLS: usize = 8;
    const N: usize = 200_000;
    for p in VIEWPOINTS.map(Vec3A::from) {
        let rect = frame_of(&light).view(c, p).expect("in solid angle");
        let mut counts = [0usize; CELLS * CELLS];
        for _ in 0..N {
            let q = rect.point(Vec2::new(r(), r())) - c;
            let s = (q.dot(eu) / eu.length_squared() + 0.5).clamp(0.0, 0.999_999);
            let t = (q.dot(ev) / ev.length_squared() + 0.5).clamp(0.0, 0.999_999);
            counts[(s * CELLS as f32) as usize * CELLS + (t * CELLS as f32) as usize] += 1;
        }
        let whole = solid_angle_of_part(&light, p, (0.0, 1.0), (0.0, 1.0), 800);
        let mut chi2 = 0.0;
        for (cell, &count) in counts.iter().enumerate() {
            let (i, j) = ((cell / CELLS) as f64, (cell % CELLS) as f64);
            let w = 1.0 / CELLS as f64;
            let part = solid_angle_of_part(&light, p, (i * w, (i + 1.0) * w), (j * w, (j + 1.0) * w), 100);
            let expected = N as f64 * part / whole;
            chi2 += (count as f64 - expected).powi(2) / expected;
        }
        assert!(chi2 < 110.0, "χ² = {chi2} from {p}");
    }
}

/// The irradiance E = ∫ L cos θ dω under an axis-aligned a × b rectangle at height h, from a
/// point under a corner, in closed form: π L F with the corner form factor
/// F = 1/(2π) [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))], X = a/h, Y = b/h.
fn corner_irradiance(l: f64, a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let f = (x / (1.0 + x * x).sqrt() * (y / (1.0 + x * x).sqrt()).atan()
        + y / (1.0 + y * y).sqrt() * (x / (1.0 + y * y).sqrt()).atan())
        / (2.0 * std::f64::consts::PI);
    std::f64::consts::PI * l * f
}

/// Mean and variance (f64) of the irradiance estimates L cos θ / pdf over `n` samples.
fn irradiance_estimate(sample: impl Fn(Vec2) -> Option<crate::light::LightSample>, n: usize, seed: u64) -> (f64, f64) {
    let mut r = numbers(seed);
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let e = sample(Vec2::new(r(), r())).map_or(0.0, |ls| f64::from(ls.radiance.x * ls.wi.z.max(0.0) / ls.pdf));
        sum += e;
        sum2 += e * e;
    }
    let mean = sum / n as f64;
    (mean, sum2 / n as f64 - mean * mean)
}

/// A 2 × 1 rectangle of radiance 3 facing down at height h above points under its centre and
/// a corner (receiver facing up): both samplers' mean irradiance over 10⁶ samples is the
/// closed form's within 1 %; the solid-angle sampler's variance is below half the area
/// sampler's close under the light (h = 0.3, 0.6), and not above it further off (h = 3, where the
/// criterion may pick area sampling).
#[test]
fn irradiance_matches_the_closed_form_with_less_variance() {
    let (a, b, l) = (2.0f32, 1.0f32, 3.0f32);
    let (eu, ev, normal) = (Vec3A::new(a, 0.0, 0.0), Vec3A::new(0.0, b, 0.0), -Vec3A::Z);
    let frame = RectFrame::of(&Shape::rect(eu, ev, normal));
    assert!(frame.is_some(), "orthogonal edges: a frame");
    for h in [0.3f32, 0.6, 3.0] {
        let centre = Vec3A::new(0.0, 0.0, h);
        for (at, expected) in [
            (Vec3A::ZERO, 4.0 * corner_irradiance(3.0, 1.0, 0.5, f64::from(h))),
            (Vec3A::new(-1.0, -0.5, 0.0), corner_irradiance(3.0, 2.0, 1.0, f64::from(h))),
        ] {
            let rgb = Rgb::splat(l);
            let n = 1_000_000;
            let solid = irradiance_estimate(
                |u| rect_sample(centre, eu, ev, normal, a * b, frame.as_ref(), rgb, false, at, u),
                n,
                3,
            );
            let by_area =
                irradiance_estimate(|u| rect_sample_by_area(centre, eu, ev, normal, a * b, rgb, false, at, u), n, 3);
            for (name, (mean, _)) in [("solid angle", solid), ("area", by_area)] {
                assert!((mean - expected).abs() < 0.01 * expected, "{name} at h {h} {at}: {mean} against {expected}");
            }
            let ratio = solid.1 / by_area.1;
            if h < 1.0 {
                assert!(ratio < 0.5, "variance ratio {ratio} at h {h} {at}");
            } else {
                assert!(ratio < 1.05, "variance ratio {ratio} at h {h} {at}");
            }
        }
    }
}

/// MIS needs the density `pdf` reports for a direction to be the one its sample came with:
/// for 20 000 random points (near the light: solid angle; far: by area) and samples, `pdf_at`
/// along the sample's direction equals the sample's density within 1e-5 (relative), and so
/// does `pdf_at` for a direction from the point to another point of the light. Both
/// samplers are exercised.
#[test]
fn pdf_equals_the_samplers_density() {
    let mut r = numbers(5);
    for two_sided in [false, true] {
        let light = rect_light(two_sided);
        let (c, ..) = rect_of(&light);
        let (mut solid, mut by_area) = (0, 0);
        for k in 0..20_000 {
            let spread = if k % 2 == 0 { 4.0 } else { 300.0 };
            let z = if k % 3 == 0 { 2.0 + 0.5 * spread * r() } else { 2.0 - 0.5 * spread * r() };
            let p = Vec3A::new(spread * (r() - 0.5), spread * (r() - 0.5), z);
            let Some(ls) = light.sample_at(p, Vec2::new(r(), r()), 0.0) else { continue };
            if frame_of(&light).view(c, p).is_some() {
                solid += 1;
            } else {
                by_area += 1;
            }
            let pdf = light.pdf_at(p, ls.wi, ls.dist, 0.0);
            assert!((pdf - ls.pdf).abs() <= 1e-5 * ls.pdf, "pdf {pdf} against the sample's {} at {p}", ls.pdf);
            // Another direction to the light, from a second sample.
            let Some(other) = light.sample_at(p, Vec2::new(r(), r()), 0.0) else { continue };
            let q = p + other.wi * other.dist;
            let (wi, t) = ((q - p).normalize(), (q - p).length());
            let pdf = light.pdf_at(p, wi, t, 0.0);
            assert!((pdf - other.pdf).abs() <= 1e-5 * other.pdf, "pdf {pdf} against {} at {p}", other.pdf);
        }
        assert!(solid > 500 && by_area > 2_000, "{solid} in solid angle, {by_area} by area");
    }
}

/// A frame is worked out only for rectangles whose edges are orthogonal (cosine at most
/// 1e-4): a skewed parallelogram and other shapes have none, so they are sampled by area; a
/// built rectangle light carries its frame.
#[test]
fn frames_only_for_orthogonal_rectangles() {
    let skewed = Shape::rect(Vec3A::new(1.5, 0.0, 0.0), Vec3A::new(0.4, 1.1, 0.0), -Vec3A::Z);
    assert!(RectFrame::of(&skewed).is_none());
    assert!(RectFrame::of(&Shape::Sphere { radius: 1.0 }).is_none());
    let light = rect_light(false);
    assert_eq!(light.rect_frame, RectFrame::of(&light.shape));
    assert!(light.rect_frame.is_some());
}

/// The far-away quick reject in `looks_large` never changes the decision: for 200 000
/// points at distances from 0.01 to 100 light sizes (most of them near the reach) it equals
/// speed37's test, area × |cos| / dist² ≥ `MIN_SOLID_ANGLE` without a division, exactly.
#[test]
fn quick_reject_keeps_the_decision() {
    let light = rect_light(false);
    let (c, _, _, normal, area) = rect_of(&light);
    let frame = frame_of(&light);
    let mut r = numbers(13);
    let reach = (area / MIN_SOLID_ANGLE).sqrt();
    let (mut large, mut small) = (0, 0);
    for k in 0..200_000 {
        let dir = Vec3A::new(r() - 0.5, r() - 0.5, r() - 0.5).normalize_or(Vec3A::Z);
        let dist = if k % 2 == 0 { reach * (0.5 + r()) } else { reach * 10f32.powf(4.0 * r() - 2.0) };
        let p = c + dist * dir;
        let rel = p - c;
        let (h, r2) = (rel.dot(normal).abs(), rel.length_squared());
        let exact = h > 0.0 && area * h >= MIN_SOLID_ANGLE * r2 * r2.sqrt();
        assert_eq!(frame.looks_large(c, p), exact, "{p}");
        if exact {
            large += 1;
        } else {
            small += 1;
        }
    }
    assert!(large > 10_000 && small > 10_000, "{large} large, {small} small");
}
