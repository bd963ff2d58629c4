//! Layers with their own `normal` in module materials (tests/mdl/normals.mdl): the layer's
//! lobes and its curve are evaluated about that normal (a mirror reflects about it, a
//! narrow glossy coat's highlight moves to that mirror direction), the base keeps the
//! shading normal, white furnaces stay at most 1, and a normal that depends on the hit is
//! brought into the hit's shading frame.

use crate::mdl_support;

use bsdf::testing::{albedo, incidences, r3};
use bsdf::{Frame, Rgb};
use glam::{Vec2, Vec3A};
use material::{SurfaceMaterial, SurfaceModel, Varying};
use mdl_support::{compile_text, get};

fn tilted(degrees: f32) -> Vec3A {
    let t = degrees.to_radians();
    Vec3A::new(t.sin(), 0.0, t.cos())
}

fn mirror_about(wo: Vec3A, n: Vec3A) -> Vec3A {
    2.0 * wo.dot(n) * n - wo
}

/// The BSDF of `m` at a hit of shading normal `n` (world space), in the frame around it.
fn bsdf_at(m: &SurfaceMaterial, n: Vec3A) -> (bsdf::Bsdf, Frame) {
    let mut h = m.constant();
    if let Varying::Evaluated(e) = &m.varying {
        let state = shader::State { normal: n, normal_geom: n, dir: -n, tex_count: 1, ..Default::default() };
        e.0.apply(&state, &mut h);
    }
    let frame = Frame::from_normal(n);
    (h.model.bsdf_in(h.diffuse, Vec3A::Z, &frame), frame)
}

#[test]
fn layer_normals_turn_their_layers() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "mirror" "mdl::normals::tilted_mirror" ()
shader "coat" "mdl::normals::tilted_coat" ()
shader "lean" "mdl::normals::leaning_curve" ()
shader "plain" "mdl::normals::plain_normal" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");

    // The mirror reflects about the normal tilted by 20°, with weight 0.3 (1e-5).
    let (mirror, frame) = bsdf_at(get(&mdl, &lib, "mirror"), Vec3A::Z);
    let n = frame.to_local(tilted(20.0));
    for wo in [Vec3A::Z, Vec3A::new(0.3, 0.1, 0.9).normalize()] {
        let s = (0..64).find_map(|i| mirror.sample(wo, Vec2::splat(0.5), i as f32 / 64.0).filter(|s| s.delta));
        let s = s.expect("a mirror sample");
        assert!((s.wi - mirror_about(wo, n)).length() < 1e-5, "{wo}: {}", s.wi);
    }

    // The coat's highlight (α 0.05, Fresnel 4 % head-on): over ten times the diffuse
    // base's value at the mirror direction about the tilted normal; at the mirror
    // direction about the shading normal only the base is left: ρ/π times what the coat
    // leaves, (1 − F(θo))(1 − F(θi)), between 0.8 and 1 here.
    let (coat, frame) = bsdf_at(get(&mdl, &lib, "coat"), Vec3A::Z);
    let n = frame.to_local(tilted(25.0));
    let wo = Vec3A::new(-0.2, 0.0, 1.0).normalize();
    let (a, b) = (coat.eval(wo, mirror_about(wo, n)).x, coat.eval(wo, mirror_about(wo, Vec3A::Z)).x);
    assert!(a > 10.0 * b, "{a} at the own mirror direction, {b} at the plain one");
    let lambert = 1.0 / std::f32::consts::PI;
    assert!(b <= lambert && b > 0.8 * lambert, "{b}");

    // White furnaces: at most 1 (+0.5 % Monte Carlo), and the plain normal is the plain
    // layer (no own frame).
    for name in ["mirror", "coat", "lean"] {
        let (b, _) = bsdf_at(get(&mdl, &lib, name), Vec3A::Z);
        for wo in incidences() {
            let alb = albedo(&b, wo, 50_000);
            assert!(alb.max_element() <= 1.005, "{name}: albedo {alb:?} at {wo}");
        }
    }
    // (`weighted_layer` of a mirror over a diffuse base: the constant-weight family.)
    let plain = &get(&mdl, &lib, "plain").model;
    assert!(matches!(plain, SurfaceModel::Lobes(_)), "plain: {plain:?}");

    // A normal leaning towards +X of whatever shading normal the hit has: at a hit of
    // normal +Y the layer's own normal is (0.4, 1, 0) normalised, whose local direction
    // in the hit's frame is then compared with the sum's placed normal.
    let lean = get(&mdl, &lib, "lean");
    let n_world = Vec3A::Y;
    let (b, frame) = bsdf_at(lean, n_world);
    let bsdf::Bsdf::Lobes(l) = b else { panic!("lean: a lobe sum") };
    let want = frame.to_local(Vec3A::new(0.4, 1.0, 0.0).normalize());
    let got = Vec3A::from_array(l.normals[0]);
    assert!((got - want).length() < 1e-5, "{got} vs {want}");
    // Samples of it integrate like its density (a sanity check that nothing is lost).
    let mut sum = Rgb::ZERO;
    for i in 0..20_000 {
        let (u, ul) = r3(i);
        if let Some(s) = bsdf::Bsdf::Lobes(l).sample(Vec3A::Z, u, ul) {
            sum += s.weight();
        }
    }
    assert!((sum / 20_000.0).max_element() <= 1.005);
}
