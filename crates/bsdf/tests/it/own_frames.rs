//! Lobes in a layer's own frame (MDL's per-layer `normal`): a mirror or a narrow GGX lobe
//! around a tilted normal reflects about that normal (analytic mirror direction; a plain
//! mirror about the shading normal), the
//! sampling matches the density (chi-square), and a white furnace of layers with tilted
//! normals over a white Lambertian base stays at most 1.

use bsdf::layer_curve::{CurveKind, LayerCurve};
use bsdf::microfacet::Ggx;
use bsdf::testing::{albedo, chi_square, incidences, r3};
use bsdf::{Bsdf, Frame, Lobe, Lobes, Rgb, Role};
use glam::{Vec2, Vec3A};

/// A normal tilted by `degrees` from +Z towards +X.
fn tilted(degrees: f32) -> Vec3A {
    let t = degrees.to_radians();
    Vec3A::new(t.sin(), 0.0, t.cos())
}

/// `layer` of weight `w` in the frame of `normal` over a white Lambertian base in the
/// shading frame (MDL's `weighted_layer(w, layer, diffuse_reflection_bsdf(), normal)`),
/// placed in the identity shading frame.
fn weighted(w: f32, layer: Lobe, normal: Vec3A) -> Lobes {
    let mut l = Lobes::default();
    let f = l.add_normal(normal).expect("a frame");
    assert!(l.push_in_frame(Rgb::splat(w), layer, Role::default(), f));
    assert!(l.push(Rgb::splat(1.0 - w), Lobe::Diffuse(0.0)));
    l.place(&Frame::from_normal(Vec3A::Z));
    l
}

fn mirror_about(wo: Vec3A, n: Vec3A) -> Vec3A {
    2.0 * wo.dot(n) * n - wo
}

/// A mirror around a normal tilted by 20°: every sample of it is the mirror direction of
/// ωo about that normal (1e-5), with the layer's weight as its throughput.
#[test]
fn a_mirror_layer_reflects_about_its_own_normal() {
    let n = tilted(20.0);
    let bsdf = Bsdf::Lobes(weighted(1.0, Lobe::Mirror, n));
    for wo in [Vec3A::Z, Vec3A::new(0.3, 0.1, 0.9).normalize(), Vec3A::new(-0.5, 0.2, 0.8).normalize()] {
        let want = mirror_about(wo, n);
        let s = bsdf.sample(wo, Vec2::new(0.3, 0.7), 0.1).expect("a mirror sample");
        assert!(s.delta);
        assert!((s.wi - want).length() < 1e-5, "{wo}: {} vs {want}", s.wi);
        assert!((s.weight() - Rgb::ONE).abs().max_element() < 1e-5, "{:?}", s.weight());
    }
    // In the shading frame: the mirror direction about +Z (on ωo's side, not through).
    let mut plain = Lobes::default();
    assert!(plain.push(Rgb::ONE, Lobe::Mirror));
    let wo = Vec3A::new(0.6, 0.0, 0.8);
    let s = Bsdf::Lobes(plain).sample(wo, Vec2::new(0.3, 0.7), 0.1).expect("a mirror sample");
    assert!((s.wi - Vec3A::new(-0.6, 0.0, 0.8)).length() < 1e-6, "{}", s.wi);
}

/// A narrow GGX lobe (α 0.02) around a normal tilted by 15°: its value at the mirror
/// direction about the tilted normal is over 100 times its value at the mirror direction
/// about the shading normal, and the mean of its samples lies within 1° of the former.
#[test]
fn a_glossy_layer_moves_its_highlight_to_the_mirror_direction_of_its_normal() {
    let n = tilted(15.0);
    let bsdf = Bsdf::Lobes(weighted(1.0, Lobe::Ggx(Ggx::isotropic(0.02)), n));
    for wo in [Vec3A::Z, Vec3A::new(-0.4, 0.1, 0.9).normalize()] {
        let own = mirror_about(wo, n);
        let plain = mirror_about(wo, Vec3A::Z);
        let (a, b) = (bsdf.eval(wo, own).x, bsdf.eval(wo, plain).x);
        assert!(a > 100.0 * b && a > 1.0, "{wo}: {a} at the own mirror, {b} at the plain one");
        let mut mean = Vec3A::ZERO;
        for i in 0..4000 {
            let (u, ul) = r3(i);
            if let Some(s) = bsdf.sample(wo, u, ul) {
                mean += s.wi;
            }
        }
        let angle = mean.normalize().dot(own).clamp(-1.0, 1.0).acos().to_degrees();
        assert!(angle < 1.0, "{wo}: mean sample {angle}° from the mirror direction");
    }
}

/// White furnaces with tilted layers over a white Lambertian base: a weighted GGX layer
/// (α 0.3, 25° tilt), a mirror (20°), a Fresnel layer whose curve measures its angles
/// from its own normal (30°), and a translucent layer: albedo at most 1 (+0.5 % Monte
/// Carlo) at every incidence; the sampling matches the density (chi-square).
#[test]
fn white_furnaces_of_tilted_layers_stay_at_most_one() {
    let mut cases: Vec<(&str, Lobes)> = vec![
        ("ggx", weighted(0.5, Lobe::Ggx(Ggx::isotropic(0.3)), tilted(25.0))),
        ("mirror", weighted(0.3, Lobe::Mirror, tilted(20.0))),
        ("translucent", weighted(0.4, Lobe::Translucent, tilted(30.0))),
    ];
    let mut fresnel = Lobes::default();
    let f = fresnel.add_normal(tilted(30.0)).unwrap();
    let k = fresnel.add_curve_in_frame(LayerCurve::new(CurveKind::Fresnel { ior: 1.5 }, Rgb::ONE, false), f).unwrap();
    assert!(fresnel.push_in_frame(
        Rgb::ONE,
        Lobe::Ggx(Ggx::isotropic(0.2)),
        Role { over: 1 << k, ..Role::default() },
        f
    ));
    assert!(fresnel.push_with_role(Rgb::ONE, Lobe::Diffuse(0.0), Role { under: 1 << k, ..Role::default() }));
    fresnel.place(&Frame::from_normal(Vec3A::Z));
    cases.push(("fresnel", fresnel));
    for (what, l) in cases {
        let bsdf = Bsdf::Lobes(l);
        for wo in incidences() {
            let a = albedo(&bsdf, wo, 50_000);
            eprintln!("{what} at {wo}: albedo {a:?}");
            assert!(a.max_element() <= 1.005, "{what}: albedo {a:?} at {wo:?}");
            if !bsdf.is_delta() && what != "mirror" {
                chi_square(&bsdf, wo);
            }
        }
    }
}

/// Placing a sum in a shading frame brings its world-space normal into that frame, on the
/// side of the shading normal: a normal of world +X seen in a frame around +X is local
/// +Z (the layer is then the plain lobe), and from the other side as well.
#[test]
fn placing_brings_world_normals_into_the_shading_frame() {
    for shading in [Vec3A::X, -Vec3A::X] {
        let mut l = Lobes::default();
        let f = l.add_normal(Vec3A::X).unwrap();
        assert!(l.push_in_frame(Rgb::ONE, Lobe::Ggx(Ggx::isotropic(0.3)), Role::default(), f));
        l.place(&Frame::from_normal(shading));
        let n = Vec3A::from_array(l.normals[0]);
        assert!((n - Vec3A::Z).length() < 1e-6, "{n}");
        let mut plain = Lobes::default();
        assert!(plain.push(Rgb::ONE, Lobe::Ggx(Ggx::isotropic(0.3))));
        let (wo, wi) = (Vec3A::new(0.3, 0.2, 0.9).normalize(), Vec3A::new(-0.4, 0.1, 0.8).normalize());
        let (a, b) = (Bsdf::Lobes(l).eval(wo, wi), Bsdf::Lobes(plain).eval(wo, wi));
        assert!((a - b).abs().max_element() < 1e-5 * b.max_element(), "{a} vs {b}");
    }
}
