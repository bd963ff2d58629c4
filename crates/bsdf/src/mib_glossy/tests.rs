//! Unit tests of the `mib_glossy_reflection` lobe: its albedo, its sampling against its
//! density, its convergence to the classic shader's estimate, the mirror limit, the kept
//! share table and the environment colour.

use super::*;
use crate::testing;
use crate::Bsdf;

/// The classic shader's estimate at one view: the mean over `n` stratified micro-normals
/// (its mapping) of the lobe's weight for the directions kept above the surface, each
/// weighted by `radiance(ωi)`, renormalised by the share kept (as the shader divides by
/// the rays it cast).
fn classic_estimate(lobe: &MibGlossyLobe, wo: Vec3A, n: u32, radiance: impl Fn(Vec3A) -> f32) -> f32 {
    let dist = lobe.dist.expect("a glossy lobe");
    let (mut sum, mut used) = (0.0f64, 0u32);
    for a in 0..n {
        for b in 0..n {
            let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
            let h = ward_normal(&dist, u);
            let i = 2.0 * wo.dot(h) * h - wo;
            if i.z > 0.0 {
                used += 1;
                sum += f64::from(radiance(i));
            }
        }
    }
    let w = edge_weight(wo.z, lobe.curve);
    (sum / f64::from(used)) as f32 * w * lobe.color.x
}

/// The lobe's integral ∫ f(ωo, ωi) L(ωi) cos θi dωi by importance sampling (`n` samples).
fn path_estimate(b: &Bsdf, wo: Vec3A, n: u32, radiance: impl Fn(Vec3A) -> f32) -> f32 {
    let mut sum = 0.0f64;
    for i in 0..n {
        let (u, u_lobe) = testing::r3(i);
        if let Some(s) = b.sample(wo, u, u_lobe) {
            sum += f64::from(s.weight().x * radiance(s.wi));
        }
    }
    (sum / f64::from(n)) as f32
}

/// The lobe's albedo is `reflection_color` × the view-angle curve at every view (the
/// classic shader's estimate of a white furnace), spread 0.1 and 0.3, isotropic and
/// anisotropic: within 1 % (the table's and sampling error) at the harness's three
/// incidences and at 85°. Over a white Lambertian base the albedo is 1 + that (the
/// classic shader adds its base: that sum is its, not a loss of energy conservation
/// here), within 1 %.
#[test]
fn albedo_is_the_colour_times_the_view_curve() {
    let curve = (0.6, 1.0, 5.0);
    let grazing = Vec3A::new(0.996, 0.0, 0.087_16).normalize();
    for spreads in [(0.1, 0.1), (0.3, 0.3), (0.3, 0.05)] {
        let lobe = MibGlossyLobe::new(Rgb::splat(0.9), curve, spreads);
        for wo in testing::incidences().into_iter().chain([grazing]) {
            let want = 0.9 * edge_weight(wo.z, curve);
            let a = testing::albedo(&Bsdf::MibGlossy(lobe.bsdf(Rgb::ZERO, wo)), wo, 200_000).x;
            assert!((a - want).abs() <= 0.01 * want, "{spreads:?} at {wo}: albedo {a} vs {want}");
            let white = testing::albedo(&Bsdf::MibGlossy(lobe.bsdf(Rgb::ONE, wo)), wo, 200_000).x;
            assert!((white - (1.0 + want)).abs() <= 0.01 * (1.0 + want), "{spreads:?} at {wo}: {white}");
        }
    }
}

/// The lobe converges to the classic shader's estimate under a non-uniform sky
/// (L(ωi) = 0.2 + ωi.x² + 3 max(ωi.y, 0)): the path integral by importance sampling
/// (400 000 samples) and the classic estimate (512² stratified micro-normals) agree
/// within 1 % at three views, isotropic and anisotropic.
#[test]
fn the_lobe_converges_to_the_classic_estimate() {
    let sky = |w: Vec3A| 0.2 + w.x * w.x + 3.0 * w.y.max(0.0);
    for spreads in [(0.15, 0.15), (0.4, 0.1)] {
        let lobe = MibGlossyLobe::new(Rgb::ONE, (0.6, 1.0, 5.0), spreads);
        for wo in [Vec3A::new(0.3, 0.2, 0.93).normalize(), Vec3A::new(0.0, -0.8, 0.6), Vec3A::new(-0.9, 0.1, 0.3)] {
            let wo = wo.normalize();
            let want = classic_estimate(&lobe, wo, 512, sky);
            let got = path_estimate(&Bsdf::MibGlossy(lobe.bsdf(Rgb::ZERO, wo)), wo, 400_000, sky);
            assert!((got - want).abs() <= 0.01 * want, "{spreads:?} at {wo}: path {got} vs classic {want}");
        }
    }
}

/// Spreads → 0 give `mib_reflect`'s mirror: a spread of 10⁻⁴ is a delta lobe whose one
/// sample is the mirror direction with weight c·w exactly (1e-6), and a spread of 0.002
/// (a narrow lobe) integrates a smooth sky to its mirror value within 1e-3.
#[test]
fn the_narrow_limit_is_the_mirror() {
    let curve = (0.6, 1.0, 5.0);
    let wo = Vec3A::new(0.6, 0.0, 0.8);
    let sharp = MibGlossyLobe::new(Rgb::new(0.9, 0.5, 0.2), curve, (1e-4, 1e-4));
    let b = Bsdf::MibGlossy(sharp.bsdf(Rgb::ZERO, wo));
    assert!(b.is_delta());
    let s = b.sample(wo, Vec2::new(0.3, 0.7), 0.2).expect("a mirror sample");
    assert!(s.delta && (s.wi - Vec3A::new(-0.6, 0.0, 0.8)).length() < 1e-6);
    let want = Rgb::new(0.9, 0.5, 0.2) * edge_weight(0.8, curve);
    assert!((s.weight() - want).abs().max_element() < 1e-6, "{} vs {want}", s.weight());
    let sky = |w: Vec3A| 1.2 + w.x * w.x + 0.5 * w.y + w.z;
    let narrow = MibGlossyLobe::new(Rgb::ONE, curve, (0.002, 0.002));
    let got = path_estimate(&Bsdf::MibGlossy(narrow.bsdf(Rgb::ZERO, wo)), wo, 20_000, sky);
    let mirror = edge_weight(0.8, curve) * sky(Vec3A::new(-0.6, 0.0, 0.8));
    assert!((got - mirror).abs() < 1e-3, "{got} vs {mirror}");
}

/// The harness's chi-square test of `sample` against `pdf` (glossy lobe over a base, and
/// alone), and the lobe's symmetry: f(ωo, ωi) cos θi · A(ωo) / w(θo) = f(ωi, ωo) cos θo ·
/// A(ωi) / w(θi) (relative 1e-4) — the classic estimate's density of a reflected
/// direction is symmetric, the lobe itself not reciprocal, as the estimate is not.
#[test]
fn sampling_matches_the_density_and_the_density_is_symmetric() {
    let lobe = MibGlossyLobe::new(Rgb::splat(0.8), (0.6, 1.0, 5.0), (0.3, 0.15));
    for wo in testing::incidences() {
        testing::chi_square(&Bsdf::MibGlossy(lobe.bsdf(Rgb::splat(0.4), wo)), wo);
        testing::chi_square(&Bsdf::MibGlossy(lobe.bsdf(Rgb::ZERO, wo)), wo);
    }
    let dist = lobe.dist.unwrap();
    let upper = UpperFraction::new(&dist);
    let reduced = |o: Vec3A, i: Vec3A| {
        let b = lobe.bsdf(Rgb::ZERO, o);
        b.eval(o, i).x * i.z * upper.at(o) / edge_weight(o.z, lobe.curve)
    };
    for k in 1..200 {
        let (a, b) = (testing::r2(k), testing::r2(k + 500));
        let o = crate::cosine_hemisphere(a);
        let i = crate::cosine_hemisphere(b);
        let (x, y) = (reduced(o, i), reduced(i, o));
        assert!((x - y).abs() <= 1e-4 * x.max(y).max(1e-6), "{o} {i}: {x} vs {y}");
    }
}

/// A(ωo) of the table against the direct quadrature (256² micro-normals) at views off
/// its nodes: within 3e-3; 1 at normal incidence; about a half at grazing for a wide
/// lobe, less than 1 at 80° for spread 0.3.
#[test]
fn the_kept_share_table_follows_the_quadrature() {
    for (ax, ay) in [(0.3f32, 0.3f32), (0.4, 0.1)] {
        let dist = Beckmann::new(ax, ay);
        let table = UpperFraction::new(&dist);
        for k in 0..40 {
            let u = testing::r2(k + 3);
            let wo = crate::cosine_hemisphere(u);
            let direct = upper_fraction(&dist, wo, 256);
            assert!((table.at(wo) - direct).abs() < 3e-3, "({ax}, {ay}) at {wo}: {} vs {direct}", table.at(wo));
        }
        assert_eq!(table.at(Vec3A::Z), 1.0);
    }
    let a80 = upper_fraction(&Beckmann::new(0.3, 0.3), Vec3A::new(0.985, 0.0, 0.174), 256);
    assert!(a80 < 0.97 && a80 > 0.5, "{a80}");
}

/// `environment_color` where `reflection_color` is 0: the lobe of colour (0.8, 0, 0.8)
/// and environment colour (0.2, 0.4, 1) carries (0.8, 0.4, 0.8) (its samples' weight
/// over a glossy direction is that × the view curve / A, exactly as a lobe of that
/// colour's, 1e-6), reflects (1, 0, 1) of what it finds (f for lights: green 0) and
/// weighs the environment by (0.25, 1, 1.25); a lobe without environment colour carries
/// its own colour, sees all of it.
#[test]
fn environment_colour_is_carried_where_the_reflection_colour_is_black() {
    let lobe = MibGlossyLobe::new(Rgb::new(0.8, 0.0, 0.8), (1.0, 1.0, 5.0), (0.2, 0.2)).with_reach(
        Rgb::new(0.2, 0.4, 1.0),
        0.0,
        2.0,
    );
    assert_eq!(lobe.carried(), Rgb::new(0.8, 0.4, 0.8));
    assert_eq!(lobe.seen(), Rgb::new(1.0, 0.0, 1.0));
    assert!((lobe.environment_ratio() - Rgb::new(0.25, 1.0, 1.25)).abs().max_element() < 1e-6);
    let twin = MibGlossyLobe::new(Rgb::new(0.8, 0.4, 0.8), (1.0, 1.0, 5.0), (0.2, 0.2));
    let wo = Vec3A::new(0.3, 0.0, 0.95).normalize();
    let (b, t) = (lobe.bsdf(Rgb::ZERO, wo), twin.bsdf(Rgb::ZERO, wo));
    let s = b.sample(wo, Vec2::new(0.3, 0.6), 0.5).expect("a glossy sample");
    let s2 = t.sample(wo, Vec2::new(0.3, 0.6), 0.5).expect("a glossy sample");
    assert!((s.weight() - s2.weight()).abs().max_element() < 1e-6, "{} vs {}", s.weight(), s2.weight());
    let f = b.eval(wo, s.wi);
    assert!(f.y == 0.0 && (f.x - s2.f.x).abs() < 1e-6 * s2.f.x.max(1.0), "{f} vs {}", s2.f);
    let plain = MibGlossyLobe::new(Rgb::new(0.8, 0.0, 0.8), (1.0, 1.0, 5.0), (0.2, 0.2));
    assert_eq!((plain.carried(), plain.seen()), (Rgb::new(0.8, 0.0, 0.8), Rgb::ONE));
}
