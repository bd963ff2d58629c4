//! Parameters of distribution functions that vary over the surface, read at each hit
//! (tests/mdl/per_hit.mdl): `fresnel_factor`'s `ior` and `extinction_coefficient`,
//! `fresnel_layer`'s and `color_fresnel_layer`'s `ior`, the weights of edf mixes and the
//! tint of an edf, and a power (`intensity_power`) that varies. Each varying material,
//! driven by the texture coordinate u, is compared at two points with its constant twin of
//! the value u gives there. Each test states its tolerance.

use crate::mdl_support;

use bsdf::Rgb;
use glam::Vec3A;
use material::{HitMaterial, SurfaceMaterial};
use mdl_support::per_hit::{at, direction_pairs, twins_text};
use mdl_support::{close, compile_text, get};

/// Compiles `varying` and, for each (u, constant shader parameters), its constant twin
/// `constant`; checks that at u the varying material's model is the twin's and that their
/// BSDFs agree at every pair of directions within 1e-6 of the larger value, and that the
/// models at the two points differ (the parameter is read per hit).
fn same_as_constant_twins(varying: &str, constant: &str, twins: [(f32, &str); 2]) {
    let (mdl, lib, diags) = compile_text(&twins_text("per_hit", varying, constant, &twins));
    assert!(diags.is_empty(), "{varying}: {diags:#?}");
    let v = get(&mdl, &lib, "v");
    let mut models = Vec::new();
    for (k, (u, _)) in twins.iter().enumerate() {
        let h = at(v, *u);
        let want = get(&mdl, &lib, &format!("c{k}"));
        assert_eq!(*h.model, want.model, "{varying} at u = {u}");
        for (wo, wi) in direction_pairs() {
            let a = h.model.bsdf(h.diffuse, wo).eval(wo, wi);
            let b = want.bsdf(wo).eval(wo, wi);
            let scale = a.max_element().max(b.max_element()).max(1.0);
            assert!(close(a, b, 1e-6 * scale), "{varying} at u = {u}, {wo:?} → {wi:?}: {a:?} vs {b:?}");
        }
        models.push(h.model.into_owned());
    }
    assert_ne!(models[0], models[1], "{varying}: the parameter changes the model");
}

/// `fresnel_factor` with `ior` (0.25, 1, 1.5) + u and `extinction_coefficient` 2(1 + u)
/// is, at u = 0.5 and 0.75, the constant factor of those values (models equal, BSDF values
/// within 1e-6).
#[test]
fn a_fresnel_factor_of_a_varying_index_is_read_per_hit() {
    same_as_constant_twins(
        "fresnel_factor_varying",
        "fresnel_factor_of",
        [(0.5, r#""ior" 0.75 1.5 2, "k" 3 3 3"#), (0.75, r#""ior" 1 1.75 2.25, "k" 3.5 3.5 3.5"#)],
    );
}

/// `fresnel_layer` of index 1 + u (a white coat over a Lambertian base: the unified
/// material's dielectric coat) and `color_fresnel_layer` of index (1, 1.25, 1.5) + u (a
/// general lobe sum's per-channel Fresnel curve) are, at u = 0.5 and 0.75, the constant
/// layers of those indices (models equal, BSDF values within 1e-6).
#[test]
fn fresnel_layers_of_a_varying_index_are_read_per_hit() {
    same_as_constant_twins("coat_varying", "coat_of", [(0.5, r#""ior" 1.5"#), (0.75, r#""ior" 1.75"#)]);
    same_as_constant_twins(
        "color_coat_varying",
        "color_coat_of",
        [(0.5, r#""ior" 1.5 1.75 2"#), (0.75, r#""ior" 1.75 2 2.25"#)],
    );
}

/// `custom_curve_layer` of normal reflectivity u/2, grazing 1 − u/2 and exponent 4u
/// (numbers that were already read per hit) is, at u = 0.5 and 0.75, the constant layer of
/// those values (models equal, BSDF values within 1e-6).
#[test]
fn a_custom_curve_of_varying_reflectivities_is_read_per_hit() {
    same_as_constant_twins(
        "custom_curve_varying",
        "custom_curve_of",
        [(0.5, r#""n" 0.25, "g" 0.75, "e" 2"#), (0.75, r#""n" 0.375, "g" 0.625, "e" 3"#)],
    );
}

/// Two nested `df::tint`s of two tints, both reflection tints varying per hit (outer
/// (u, 0.6, 0.3), inner (0.8, u, 0.5), the inner transmission tint (0.5, 0.5, u)), over a
/// sheen whose base transmits (once an error at its line): at u = 0.5 and 0.75 the
/// material is its constant twin (the sheen lobe under the product of the reflection
/// tints, the base's halves tinted apart; models equal, BSDF values within 1e-6).
#[test]
fn nested_two_tint_tints_varying_per_hit_over_a_transmitting_sheen_compile() {
    same_as_constant_twins(
        "nested_tint_sheen_varying",
        "nested_tint_sheen_of",
        [
            (0.5, r#""r1" 0.5 0.6 0.3, "r2" 0.8 0.5 0.5, "t2" 0.5 0.5 0.5"#),
            (0.75, r#""r1" 0.75 0.6 0.3, "r2" 0.8 0.75 0.5, "t2" 0.5 0.5 0.75"#),
        ],
    );
}

/// The emitted radiance of `h` towards the direction at `deg` degrees from the normal
/// (z), in the x–z plane.
fn radiance(h: &HitMaterial<'_>, deg: f32) -> Rgb {
    let d = Vec3A::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
    h.emission * h.emission_shape.as_deref().map_or(Rgb::ONE, |s| s.factor(Vec3A::Z, None, d))
}

/// Checks that `varying` at each u emits what its constant twin (parameters given) emits
/// at 0°, 30°, 55° and 80° (1e-4 of the larger), and that the two points differ.
fn emits_as_constant_twins(varying: &str, constant: &str, twins: [(f32, &str); 2]) {
    let (mdl, lib, diags) = compile_text(&twins_text("per_hit", varying, constant, &twins));
    assert!(diags.is_empty(), "{varying}: {diags:#?}");
    let v = get(&mdl, &lib, "v");
    let mut seen = Vec::new();
    for (k, (u, _)) in twins.iter().enumerate() {
        let h = at(v, *u);
        let want = get(&mdl, &lib, &format!("c{k}")).constant();
        for deg in [0.0f32, 30.0, 55.0, 80.0] {
            let (a, b) = (radiance(&h, deg), radiance(&want, deg));
            let scale = a.max_element().max(b.max_element()).max(1e-6);
            assert!(close(a, b, 1e-4 * scale), "{varying} at u = {u}, {deg}°: {a:?} vs {b:?}");
        }
        seen.push(radiance(&h, 30.0));
    }
    assert!(!close(seen[0], seen[1], 1e-3), "{varying}: the weights change the emission: {seen:?}");
}

/// A normalised mix of a diffuse and a spot edf weighted 1.5u and 1.5(1 − u) (their sum
/// 1.5 normalised away), and a spot tinted (u, 0.5, 1), emit at u = 0.5 and 0.75 what the
/// constant mix and tint of those weights emit (1e-4 at four angles).
#[test]
fn edf_mixes_and_tints_of_varying_weights_are_read_per_hit() {
    emits_as_constant_twins(
        "edf_mix_varying",
        "edf_mix_of",
        [(0.5, r#""a" 0.75, "b" 0.75"#), (0.75, r#""a" 1.125, "b" 0.375"#)],
    );
    emits_as_constant_twins(
        "edf_tint_varying",
        "edf_tint_of",
        [(0.5, r#""t" 0.5 0.5 1"#), (0.75, r#""t" 0.75 0.5 1"#)],
    );
}

/// A Lambertian emitter of power 4u (`intensity_power`) spread over an area of 2 emits at
/// u = 0.5 and 0.75 what the constant power of 2 and 3 does over the same area: Φ/(π A)
/// (1e-6), where before it emitted nothing.
#[test]
fn a_varying_power_is_spread_over_the_area() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "v" "mdl::per_hit::power_varying" ()
shader "c0" "mdl::per_hit::power_of" ("intensity" 2 2 2)
shader "c1" "mdl::per_hit::power_of" ("intensity" 3 3 3)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let mut v = get(&mdl, &lib, "v").clone();
    assert!(v.emission_over_area);
    v.spread_emission_over(2.0);
    for (u, twin, power) in [(0.5, "c0", 2.0f32), (0.75, "c1", 3.0)] {
        let mut c = get(&mdl, &lib, twin).clone();
        c.spread_emission_over(2.0);
        let h = at(&v, u);
        let want = Rgb::splat(power / (std::f32::consts::PI * 2.0));
        assert!(
            close(h.emission, want, 1e-6) && close(c.emission, want, 1e-6),
            "u = {u}: {:?}, {:?}",
            h.emission,
            c.emission
        );
    }
}

/// f(ωo, ωi) (world directions) of the material `m` at texture coordinate u, in the
/// shading frame the path engine builds: the normal z, its x axis the hit's tangent.
fn eval_world(m: &SurfaceMaterial, u: f32, wo: Vec3A, wi: Vec3A) -> Rgb {
    let h = at(m, u);
    let frame = bsdf::Frame::from_normal_and_tangent(Vec3A::Z, h.tangent.unwrap_or(Vec3A::X));
    let (o, i) = (frame.to_local(wo), frame.to_local(wi));
    h.model.bsdf_in(h.diffuse, o, &frame).eval(o, i)
}

/// Two anisotropic lobes turned by different `tangent_u`s (GGX along x, Ward along
/// (1, u, 0), mixed half and half) are at u = 0.5 and 2 half the sum of the two lobes
/// built alone, each turned by its own tangent: equal at every pair of directions within
/// 1e-5 of the larger value (before, both followed the first lobe's tangent, with a
/// warning: that differs by more than 1e-3 somewhere).
/// The mix passes the standard checks (reciprocity, energy, χ² sampling of its density).
#[test]
fn lobes_turned_by_different_tangents_each_follow_their_own() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "two" "mdl::per_hit::two_tangents" ()
shader "ggx" "mdl::per_hit::ggx_along" ()
shader "w0" "mdl::per_hit::ward_along" ("t" 1 0.5 0)
shader "w1" "mdl::per_hit::ward_along" ("t" 1 2 0)
shader "wx" "mdl::per_hit::ward_along" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let two = get(&mdl, &lib, "two");
    let (ggx, along_x) = (get(&mdl, &lib, "ggx"), get(&mdl, &lib, "wx"));
    // Whether following the first lobe's tangent (as before) would differ.
    let mut differs = false;
    for (u, ward) in [(0.5, "w0"), (2.0, "w1")] {
        let ward = get(&mdl, &lib, ward);
        for (wo, wi) in direction_pairs() {
            let got = eval_world(two, u, wo, wi);
            let want = 0.5 * (eval_world(ggx, u, wo, wi) + eval_world(ward, u, wo, wi));
            let followed = 0.5 * (eval_world(ggx, u, wo, wi) + eval_world(along_x, u, wo, wi));
            let scale = got.max_element().max(want.max_element()).max(1e-3);
            assert!(close(got, want, 1e-5 * scale), "u = {u}, {wo:?} → {wi:?}: {got:?} vs {want:?}");
            differs |= !close(followed, want, 1e-3 * scale);
        }
        let h = at(two, u);
        let frame = bsdf::Frame::from_normal_and_tangent(Vec3A::Z, h.tangent.unwrap_or(Vec3A::X));
        bsdf::testing::standard_checks(&h.model.bsdf_in(h.diffuse, Vec3A::Z, &frame), 1.01, "two tangents");
    }
    assert!(differs, "the Ward lobe's own tangent changes the mix");
}

/// A Ward lobe of its own `tangent_u` (1, u, 0) inside a `weighted_layer` of its own
/// `normal` n = (0.3, 0.1, 1) (normalised), mixed half and half with a GGX lobe along x
/// (the shading frame's), at u = 0.5 and 2: half the GGX lobe plus half the Ward lobe built
/// alone and evaluated in the frame of normal n whose x axis is the tangent made
/// orthogonal to n — its value times |cos θi| about n over |cos θi| about the shading
/// normal, nothing where the two normals disagree on a side — within 1e-5 of the larger
/// value at every pair of directions (before, the lobe followed the shading frame's x laid
/// into the layer's plane, with a warning: that differs by more than 1e-3 somewhere). No
/// warning; the mix reflects at most 1 + 1 % (50 000 samples) and samples its density
/// (χ²) at the standard incidences. (Not reciprocal: no part in a tilted own frame is,
/// by the ratio of cosines; the Ward lobe in it is, as built alone.)
#[test]
fn a_tangent_under_a_layer_normal_turns_about_that_normal() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "mix" "mdl::per_hit::tangent_under_normal" ()
shader "ggx" "mdl::per_hit::ggx_along" ()
shader "w0" "mdl::per_hit::ward_along" ("t" 1 0.5 0)
shader "w1" "mdl::per_hit::ward_along" ("t" 1 2 0)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (mix, ggx) = (get(&mdl, &lib, "mix"), get(&mdl, &lib, "ggx"));
    let n = Vec3A::new(0.3, 0.1, 1.0).normalize();
    // A lone lobe evaluated in `frame` (world directions), as it counts in the mix.
    let in_frame = |m: &SurfaceMaterial, frame: &bsdf::Frame, wo: Vec3A, wi: Vec3A| {
        let agree = wo.dot(n) * wo.z > 0.0 && wi.dot(n) * wi.z > 0.0 && wi.z.abs() > 1e-6;
        if !agree {
            return Rgb::ZERO;
        }
        let h = m.constant();
        let (o, i) = (frame.to_local(wo), frame.to_local(wi));
        h.model.bsdf_in(h.diffuse, o, frame).eval(o, i) * (wi.dot(n).abs() / wi.z.abs())
    };
    let mut differs = false;
    for (u, ward, t) in [(0.5, "w0", Vec3A::new(1.0, 0.5, 0.0)), (2.0, "w1", Vec3A::new(1.0, 2.0, 0.0))] {
        let ward = get(&mdl, &lib, ward);
        let (own, laid) =
            (bsdf::Frame::from_normal_and_tangent(n, t), bsdf::Frame::from_normal_and_tangent(n, Vec3A::X));
        for (wo, wi) in direction_pairs() {
            let got = eval_world(mix, u, wo, wi);
            let want = 0.5 * (eval_world(ggx, u, wo, wi) + in_frame(ward, &own, wo, wi));
            let followed = 0.5 * (eval_world(ggx, u, wo, wi) + in_frame(ward, &laid, wo, wi));
            let scale = got.max_element().max(want.max_element()).max(1e-3);
            assert!(close(got, want, 1e-5 * scale), "u = {u}, {wo:?} → {wi:?}: {got:?} vs {want:?}");
            differs |= !close(followed, want, 1e-3 * scale);
        }
        let h = at(mix, u);
        let frame = bsdf::Frame::from_normal_and_tangent(Vec3A::Z, h.tangent.unwrap_or(Vec3A::X));
        let b = h.model.bsdf_in(h.diffuse, Vec3A::Z, &frame);
        for wo in bsdf::testing::incidences() {
            let a = bsdf::testing::albedo(&b, wo, 50_000);
            assert!(a.max_element() <= 1.01, "u = {u}: albedo {a:?} at {wo:?}");
            bsdf::testing::chi_square(&b, wo);
        }
    }
    assert!(differs, "the Ward lobe's own tangent changes the mix");
}
