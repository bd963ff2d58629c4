//! The path engine's inlined case of lights — a still rectangle of radiance — against the
//! general code: ray hits bit for bit, samples bit for bit against the shape's own point
//! and area, and consistent with the light's density and its surface.

use bsdf::Rgb;
use glam::{Affine3A, Vec2, Vec3A};
use render::light::{LightSource, Output, RectFrame, Shape};
use render::ray::Ray;
use scene::LightKind;

/// A parallelogram light centred at (0.3, −0.2, 2) with non-orthogonal edges, facing −Z.
fn rect_light(two_sided: bool) -> LightSource {
    LightSource {
        name: "rect".into(),
        kind: LightKind::Point,
        position: Vec3A::new(0.3, -0.2, 2.0),
        direction: -Vec3A::Z,
        shape: Shape::rect(Vec3A::new(1.5, 0.0, 0.0), Vec3A::new(0.4, 1.1, 0.0), -Vec3A::Z),
        // Skewed edges: no frame, sampled by area.
        rect_frame: None,
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

/// Numbers in [0, 1) from a SplitMix64 stream.
fn numbers() -> impl FnMut() -> f32 {
    let mut z = 0x0bad_5eed_u64;
    move || {
        z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut x = z;
        x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((x ^ (x >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// A still light's hits equal, bit for bit, those of the same light given motion keys that
/// hold it still (which takes the general, out-of-line path: the ray carried back by the
/// identity), for rays from above and below, one- and two-sided, with `tmax` cutting some.
#[test]
fn rect_hits_equal_the_general_path() {
    let mut r = numbers();
    for two_sided in [false, true] {
        let fast = rect_light(two_sided);
        let general = LightSource { motion: vec![Affine3A::IDENTITY; 2], ..fast.clone() };
        let (mut hits, mut misses) = (0, 0);
        for k in 0..20_000 {
            let z = if k % 2 == 0 { -1.0 } else { 4.0 };
            let origin = Vec3A::new(4.0 * r() - 2.0, 4.0 * r() - 2.0, z);
            let target = Vec3A::new(3.0 * r() - 1.2, 3.0 * r() - 1.7, 2.0);
            let dir = (target - origin).normalize();
            let tmax = if k % 5 == 0 { 2.5 * r() } else { f32::INFINITY };
            let ray = Ray { tmax, time: r(), ..Ray::new(origin, dir) };
            let (a, b) = (fast.intersect(&ray), general.intersect(&ray));
            assert_eq!(a.map(|(t, l)| (t.to_bits(), l)), b.map(|(t, l)| (t.to_bits(), l)), "{ray:?}");
            if a.is_some() {
                hits += 1;
            } else {
                misses += 1;
            }
        }
        // Both outcomes were exercised (from below the light faces the ray; from above
        // only the two-sided one is hit).
        assert!(hits > 1_000 && misses > 1_000, "{hits} hits, {misses} misses");
    }
}

/// A sample of a still rectangle: the point is the shape's own `point_on`, the density its
/// distance² over (cosine × the edges' cross product's length), bit for bit; a ray along the sample finds the light at
/// the sample's distance (relative 1e-4) with the light's radiance, and `pdf_at` there
/// gives the sample's density (relative 1e-4). Points behind a one-sided light get none.
#[test]
fn rect_samples_match_the_shape_and_the_density() {
    let mut r = numbers();
    for two_sided in [false, true] {
        let light = rect_light(two_sided);
        let (mut front, mut behind) = (0, 0);
        for k in 0..5_000 {
            let z = if k % 3 == 0 { 3.5 } else { -0.5 - 2.0 * r() };
            let p = Vec3A::new(4.0 * r() - 2.0, 4.0 * r() - 2.0, z);
            let u = Vec2::new(r(), r());
            let got = light.sample_at(p, u, r());
            let (q, n) = light.shape.point_on(light.position, u);
            let d = q - p;
            let dist2 = d.length_squared();
            let wi = d / dist2.sqrt();
            let cos_l = -wi.dot(n);
            if cos_l <= 0.0 && !two_sided {
                assert!(got.is_none(), "a point behind the light got {got:?}");
                behind += 1;
                continue;
            }
            front += 1;
            let ls = got.expect("a sample");
            assert_eq!(ls.wi.to_array().map(f32::to_bits), wi.to_array().map(f32::to_bits));
            assert_eq!(ls.dist.to_bits(), dist2.sqrt().to_bits());
            // The area from the edges, as the sample worked it out before the shape kept it.
            let Shape::Rect { u: eu, v: ev, .. } = light.shape else { unreachable!() };
            assert_eq!(ls.pdf.to_bits(), (dist2 / (cos_l.abs() * eu.cross(ev).length())).to_bits());
            assert!(!ls.delta && ls.radiance == Rgb::new(4.0, 3.0, 2.0));
            let (t, l) = light.intersect(&Ray::new(p, ls.wi)).expect("the ray along the sample finds the light");
            assert!((t - ls.dist).abs() <= 1e-4 * ls.dist, "t {t} against {}", ls.dist);
            assert_eq!(l, ls.radiance);
            let pdf = light.pdf_at(p, ls.wi, t, 0.0);
            assert!((pdf - ls.pdf).abs() <= 1e-4 * ls.pdf, "pdf {pdf} against {}", ls.pdf);
        }
        assert!(front > 1_000 && (two_sided || behind > 1_000), "{front} in front, {behind} behind");
    }
}

/// A 1.5 × 1.1 rectangle light (orthogonal edges, turned about Z) at the same place: sampled
/// uniformly in solid angle near it. The inlined sample equals `sample`'s bit for bit and
/// the moving-light path's (motion keys holding it still) to 1e-6; a ray along it finds the light at the sample's
/// distance (relative 1e-4) with the light's radiance; `pdf_at` gives the sample's density
/// (relative 1e-5); points behind a one-sided light get none.
#[test]
fn rect_solid_angle_samples_match_the_general_path() {
    let mut r = numbers();
    let (s, c) = 0.3f32.sin_cos();
    for two_sided in [false, true] {
        let shape = Shape::rect(Vec3A::new(1.5 * c, 1.5 * s, 0.0), Vec3A::new(-1.1 * s, 1.1 * c, 0.0), -Vec3A::Z);
        let fast = LightSource { rect_frame: RectFrame::of(&shape), shape, ..rect_light(two_sided) };
        assert!(fast.rect_frame.is_some(), "orthogonal edges: a frame");
        let general = LightSource { motion: vec![Affine3A::IDENTITY; 2], ..fast.clone() };
        let (mut front, mut behind) = (0, 0);
        for k in 0..5_000 {
            let z = if k % 3 == 0 { 2.0 + 1.5 * r() } else { 2.0 - 1.5 * r() };
            let p = Vec3A::new(4.0 * r() - 2.0, 4.0 * r() - 2.0, z);
            let (u, time) = (Vec2::new(r(), r()), r());
            let got = fast.sample_at(p, u, time);
            let bits = |ls: render::light::LightSample| {
                (ls.wi.to_array().map(f32::to_bits), ls.dist.to_bits(), ls.pdf.to_bits())
            };
            assert_eq!(got.map(bits), fast.sample(p, u).map(bits), "{p}");
            // The moving light's path normalises the direction again: equal to 1e-6.
            let other = general.sample_at(p, u, time);
            assert_eq!(got.is_some(), other.is_some(), "{p}");
            if let (Some(a), Some(b)) = (got, other) {
                assert!((a.wi - b.wi).length() < 1e-6 && a.dist == b.dist && a.pdf == b.pdf, "{a:?} {b:?}");
            }
            if z > 2.0 && !two_sided {
                assert!(got.is_none(), "a point behind the light got {got:?}");
                behind += 1;
                continue;
            }
            let Some(ls) = got else { continue };
            front += 1;
            let (t, l) = fast.intersect(&Ray::new(p, ls.wi)).expect("the ray along the sample finds the light");
            assert!((t - ls.dist).abs() <= 1e-4 * ls.dist, "t {t} against {}", ls.dist);
            assert_eq!(l, ls.radiance);
            let pdf = fast.pdf_at(p, ls.wi, t, 0.0);
            assert!((pdf - ls.pdf).abs() <= 1e-5 * ls.pdf, "pdf {pdf} against {}", ls.pdf);
        }
        assert!(front > 2_000 && (two_sided || behind > 1_000), "{front} in front, {behind} behind");
    }
}
