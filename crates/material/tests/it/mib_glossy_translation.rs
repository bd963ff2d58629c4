//! The path engine's translation of `mib_glossy_reflection` (`material`'s `reader::mib_glossy`): its
//! base material, lobe, the parameters it cannot honour (warned) and `samples` 0.

use bsdf::{Bsdf, Rgb};
use glam::Vec3A;
use material::SurfaceModel;

/// `shaders` and a triangle of material "m" as a scene.
fn scene(shaders: &str) -> scene::Scene {
    let text = format!(
        r#"{shaders}options "o" end options
camera "c" end camera
instance "ci" "c" end instance
object "tri" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 c "m" 0 1 2 end group end object
instance "ti" "tri" end instance
instgroup "root" "ci" "ti" end instgroup
render "root" "ci" "o"
"#
    );
    let parsed = mi::parse_str("t.mi", &text);
    let mut diags = Vec::new();
    scene::Scene::build(&parsed, 0, &mut diags).expect("a scene")
}

/// Material "m" of `shaders` translated without a shader graph: the surface and warnings.
fn translated(shaders: &str) -> (material::SurfaceMaterial, Vec<String>) {
    let s = scene(shaders);
    let m = s.materials.iter().find(|m| m.name == "m").expect("material m");
    material::translate(m, &s.library, None)
}

/// A glossy reflection over a `mib_illum_lambert` base: the base's diffuse colour under
/// the lobe, whose weight at normal incidence is `reflection_color` × the base weight 0.6
/// (exactly, 1e-6), and no warning when every parameter is honoured; anisotropic spreads
/// put the lobe along dP/du.
#[test]
fn the_base_material_lies_under_the_glossy_lobe() {
    let (s, warnings) = translated(
        r#"shader "base" "mib_illum_lambert" ("diffuse" 0.3 0.2 0.1)
material "m" "mib_glossy_reflection" ("base_material" "base", "reflection_color" 0.5 0.6 0.7,
    "environment_color" 0.5 0.6 0.7, "single_env_sample" off, "u_spread" 0.2, "v_spread" 0.2) end material
"#,
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(s.diffuse, Rgb::new(0.3, 0.2, 0.1));
    assert!(matches!(s.model, SurfaceModel::MibGlossy(_)));
    assert_eq!(s.tangent_angle, None);
    let Bsdf::MibGlossy(b) = s.bsdf(Vec3A::Z) else { panic!("a mib_glossy BSDF") };
    assert_eq!(b.base, Rgb::new(0.3, 0.2, 0.1));
    assert!((b.tint - Rgb::new(0.3, 0.36, 0.42)).abs().max_element() < 1e-6, "{}", b.tint);
    let (aniso, _) = translated(
        r#"material "m" "mib_glossy_reflection" ("reflection_color" 1 1 1, "environment_color" 1 1 1,
    "single_env_sample" off, "u_spread" 0.3, "v_spread" 0.05) end material
"#,
    );
    assert_eq!(aniso.tangent_angle, Some(0.0));
}

/// Parameters the path engine does not honour are named in warnings: an
/// `single_env_sample` (default on) with a spread lobe, a `u_axis` connected where there
/// is no shader graph to follow (translated without one). `max_distance` (5), `falloff`
/// (its default 2) and `environment_color` (0.2) are the lobe's, unwarned; so is an
/// `environment_color` with light where `reflection_color` has none (the lobe carries it
/// there and sees nothing it finds: `carried` 1, `seen` 0 in those channels), even under
/// a black `reflection_color`.
#[test]
fn unhonoured_parameters_are_warned_about() {
    let (s, warnings) = translated(
        r#"shader "axis" "mib_color_mix" ("num" 0)
material "m" "mib_glossy_reflection" ("reflection_color" 1 1 1, "environment_color" 0.2 0.2 0.2,
    "max_distance" 5, "u_spread" 0.3, "v_spread" 0.05, "u_axis" = "axis") end material
"#,
    );
    assert!(matches!(s.model, SurfaceModel::MibGlossy(_)));
    for what in ["single_env_sample", "u_axis"] {
        assert!(warnings.iter().any(|w| w.contains(what)), "no warning about {what}: {warnings:?}");
    }
    assert!(!warnings.iter().any(|w| w.contains("max_distance") || w.contains("environment_color")), "{warnings:?}");
    let SurfaceModel::MibGlossy(lobe) = &s.model else { panic!("a mib_glossy lobe") };
    assert_eq!((lobe.max_distance, lobe.falloff, lobe.env_color), (5.0, 2.0, Rgb::splat(0.2)));
    for (reflection, seen) in [("1 0 1", Rgb::new(1.0, 0.0, 1.0)), ("0 0 0", Rgb::ZERO)] {
        let (t, warnings) = translated(&format!(
            r#"material "m" "mib_glossy_reflection" ("reflection_color" {reflection}, "environment_color" 1 1 1,
    "single_env_sample" off) end material
"#
        ));
        assert!(warnings.is_empty(), "{warnings:?}");
        let SurfaceModel::MibGlossy(lobe) = &t.model else { panic!("a mib_glossy lobe: {:?}", t.model) };
        assert_eq!((lobe.carried(), lobe.seen()), (Rgb::ONE, seen), "reflection_color {reflection}");
    }
    assert_eq!((s.tangent_axis, s.tangent_angle), (None, Some(0.0)), "dP/du is the axis");
}

/// Material "m" of `shaders` translated with the scene's shader graph: the surface, its
/// warnings and the shading (to evaluate it per hit).
fn translated_with_graph(shaders: &str) -> (material::SurfaceMaterial, Vec<String>, shader::Shading) {
    let s = scene(shaders);
    let (shading, diags) = shader::Shading::build(&s, &shader::ShadingOptions::default(), &material::registry());
    assert!(diags.is_empty(), "{} diagnostics", diags.len());
    let index = s.materials.iter().position(|m| m.name == "m").expect("material m");
    let (surface, warnings) = material::translate(&s.materials[index], &s.library, Some((&shading, index)));
    (surface, warnings, shading)
}

/// A connected `u_axis` is evaluated at each hit: connected to a shader whose value is
/// the constant (0, 1, 0.7), it gives at a hit of normal +z and dP/du +x the tangent of
/// the constant `u_axis` (0, 1, 0.7) projected, +y (1e-6), and there the BSDF of the
/// constant axis at 64 pairs of directions within 1e-5 relative, for both shaders; no
/// warning. The connection is a per-hit binding, not the constant's fixed axis.
#[test]
fn a_connected_u_axis_of_constant_value_equals_the_constant() {
    for (shader, extra) in [
        ("mib_glossy_reflection", r#""reflection_color" 1 1 1, "environment_color" 1 1 1, "single_env_sample" off"#),
        ("mib_glossy_refraction", r#""refraction_color" 1 1 1, "ior" 1.4"#),
    ] {
        let spreads = r#""u_spread" 0.3, "v_spread" 0.05"#;
        let (connected, warnings, shading) = translated_with_graph(&format!(
            r#"shader "axis" "mib_color_mix" ("num" 0, "color_base" 0 1 0.7 1)
material "m" "{shader}" ({extra}, {spreads}, "u_axis" = "axis") end material
"#
        ));
        assert!(warnings.is_empty(), "{shader}: {warnings:?}");
        assert_eq!(connected.tangent_axis, None, "{shader}: not a fixed axis");
        assert!(
            matches!(&connected.varying, material::Varying::Bindings(b) if b.iter().any(|b| b.target == material::Target::TangentAxis)),
            "{shader}: {:?}",
            connected.varying
        );
        let (constant, _) = translated(&format!(
            r#"material "m" "{shader}" ({extra}, {spreads}, "u_axis" 0 1 0.7) end material
"#
        ));
        let tracer = crate::support::Empty::default();
        let mut state = crate::support::maya::point([0.3, 0.4]);
        (state.normal, state.normal_geom, state.dir) = (Vec3A::Z, Vec3A::Z, -Vec3A::Z);
        state.derivs[0] = Vec3A::X;
        let mut ctx = shader::Ctx::new(&shading, &tracer, state);
        let hit = connected.at(&mut ctx);
        let tangent = hit.tangent.expect("a tangent");
        assert!((tangent - Vec3A::Y).abs().max_element() < 1e-6, "{shader}: tangent {tangent}");
        let frame = bsdf::Frame::from_normal_and_tangent(Vec3A::Z, tangent);
        for k in 0..64 {
            let a = k as f32 * 0.7;
            let b = k as f32 * 1.3 + 0.4;
            let wo = Vec3A::new(a.cos() * 0.6, a.sin() * 0.6, 0.8).normalize();
            let side = if shader == "mib_glossy_reflection" { 1.0 } else { -1.0 };
            let wi = Vec3A::new(-wo.x + 0.25 * b.cos(), -wo.y + 0.25 * b.sin(), side * 0.8).normalize();
            let (o, i) = (frame.to_local(wo), frame.to_local(wi));
            let got = hit.model.bsdf(hit.diffuse, o).eval(o, i);
            let want = world_eval(&constant, wo, wi);
            let scale = want.max_element().max(1e-3);
            assert!((got - want).abs().max_element() <= 1e-5 * scale, "{shader} pair {k}: {got} vs {want}");
        }
    }
}

/// f(ωo, ωi) (world-space directions) of translated material `s` at a hit of normal +z
/// and dP/du +x: in the frame its tangent rule gives there.
fn world_eval(s: &material::SurfaceMaterial, wo: Vec3A, wi: Vec3A) -> Rgb {
    let n = Vec3A::Z;
    let frame = match s.tangent_at(n, Vec3A::X) {
        Some(t) => bsdf::Frame::from_normal_and_tangent(n, t),
        None => bsdf::Frame::from_normal(n),
    };
    let (o, i) = (frame.to_local(wo), frame.to_local(wi));
    s.bsdf(o).eval(o, i)
}

/// `u_axis` lays the anisotropic spreads along it (projected onto the tangent plane, as
/// the classic shader does), for `mib_glossy_reflection` and `mib_glossy_refraction`
/// alike: with the axis turned 90° about the normal (+x to +y, the latter given tilted
/// out of the plane as (0, 1, 0.7)), spreads (0.3, 0.05) give at every one of 64 pairs
/// of directions the BSDF values of spreads (0.05, 0.3) along +x, within 1e-5 relative;
/// the turn changes them (some pair by over 50 %); `v_axis` changes nothing; no warning.
#[test]
fn turning_u_axis_a_quarter_turn_swaps_the_spreads() {
    for (shader, extra) in [
        ("mib_glossy_reflection", r#", "environment_color" 1 1 1, "single_env_sample" off"#),
        ("mib_glossy_refraction", r#", "ior" 1.4"#),
    ] {
        let material = |spreads: (f32, f32), axes: &str| {
            let (s, warnings) = translated(&format!(
                r#"material "m" "{shader}" ("{}" 1 1 1{extra}, "u_spread" {}, "v_spread" {}{axes}) end material
"#,
                if shader == "mib_glossy_reflection" { "reflection_color" } else { "refraction_color" },
                spreads.0,
                spreads.1
            ));
            assert!(warnings.is_empty(), "{shader}: {warnings:?}");
            s
        };
        let along_x = material((0.3, 0.05), r#", "u_axis" 1 0 0"#);
        let turned = material((0.3, 0.05), r#", "u_axis" 0 1 0.7"#);
        let turned_v = material((0.3, 0.05), r#", "u_axis" 0 1 0.7, "v_axis" 1 0.3 0"#);
        let swapped = material((0.05, 0.3), r#", "u_axis" 1 0 0"#);
        assert_eq!(turned.tangent_axis, Some(Vec3A::new(0.0, 1.0, 0.7)));
        let mut changed = 0.0f32;
        for k in 0..64 {
            let a = k as f32 * 0.7;
            let b = k as f32 * 1.3 + 0.4;
            let wo = Vec3A::new(a.cos() * 0.6, a.sin() * 0.6, 0.8).normalize();
            // Near the mirror (or the refraction) of wo, where the lobe is.
            let side = if shader == "mib_glossy_reflection" { 1.0 } else { -1.0 };
            let wi = Vec3A::new(-wo.x + 0.25 * b.cos(), -wo.y + 0.25 * b.sin(), side * 0.8).normalize();
            let (t, w, v) = (world_eval(&turned, wo, wi), world_eval(&swapped, wo, wi), world_eval(&turned_v, wo, wi));
            let scale = w.max_element().max(1e-3);
            assert!((t - w).abs().max_element() <= 1e-5 * scale, "{shader} pair {k}: turned {t} vs swapped {w}");
            assert_eq!(v, t, "{shader} pair {k}: v_axis changes nothing");
            let x = world_eval(&along_x, wo, wi);
            changed = changed.max((x - t).abs().max_element() / scale);
        }
        assert!(changed > 0.5, "{shader}: turning u_axis changes the lobe ({changed})");
    }
}

/// `samples` 0 casts no glossy ray in the classic shader: the base alone (a Lambertian
/// surface of its colour), as does a black `reflection_color`.
#[test]
fn no_samples_leave_the_base_alone() {
    for params in [r#""reflection_color" 1 1 1, "samples" 0"#, r#""reflection_color" 0 0 0"#] {
        let (s, warnings) = translated(&format!(
            r#"shader "base" "mib_illum_lambert" ("diffuse" 0.4 0.4 0.4)
material "m" "mib_glossy_reflection" ("base_material" "base", {params}) end material
"#
        ));
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(s.model, SurfaceModel::Lambert);
        assert_eq!(s.diffuse, Rgb::splat(0.4));
    }
}

/// `mib_glossy_refraction` over a `mib_illum_lambert` top: the top's diffuse colour over
/// the lobe (front only), which is seen from inside too (the model has an inside); its
/// weight at normal incidence from the front is `refraction_color` × the base weight 1
/// (exactly, 1e-6), η = 1/`ior` there and `ior` from inside; no warning when every
/// parameter is honoured; `samples` 0 leaves the top alone. `max_distance` and `falloff`
/// are the lobe's (3 and the default 2), not warned about; nor is `v_axis` (it changes
/// nothing).
#[test]
fn glossy_refraction_lies_under_its_top_material() {
    let (s, warnings) = translated(
        r#"shader "top" "mib_illum_lambert" ("diffuse" 0.3 0.2 0.1)
material "m" "mib_glossy_refraction" ("top_material" "top", "refraction_color" 0.5 0.6 0.7, "ior" 1.5) end material
"#,
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(s.diffuse, Rgb::new(0.3, 0.2, 0.1));
    assert!(s.has_inside());
    let SurfaceModel::MibGlossyRefraction(lobe) = &s.model else { panic!("{:?}", s.model) };
    let front = lobe.bsdf(s.diffuse, Vec3A::Z);
    assert!((front.tint - Rgb::new(0.5, 0.6, 0.7)).abs().max_element() < 1e-6, "{}", front.tint);
    assert_eq!(front.base, s.diffuse);
    assert!((front.eta - 1.0 / 1.5).abs() < 1e-6);
    let inside = lobe.bsdf(s.diffuse, -Vec3A::Z);
    assert_eq!((inside.base, inside.eta), (Rgb::ZERO, 1.5));
    let (alone, warnings) = translated(
        r#"shader "top" "mib_illum_lambert" ("diffuse" 0.4 0.4 0.4)
material "m" "mib_glossy_refraction" ("top_material" "top", "samples" 0) end material
"#,
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!((alone.model, alone.diffuse), (SurfaceModel::Lambert, Rgb::splat(0.4)));
    let (s, warnings) = translated(
        r#"shader "top" "mib_illum_lambert" ("diffuse" 0.4 0.4 0.4)
material "m" "mib_glossy_refraction" ("top_material" "top", "max_distance" 3, "v_axis" 1 0 0) end material
"#,
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    let SurfaceModel::MibGlossyRefraction(lobe) = &s.model else { panic!("{:?}", s.model) };
    assert_eq!((lobe.max_distance, lobe.falloff), (3.0, 2.0));
    assert!(lobe.reaches());
}

/// `mib_glossy_refraction`'s `back_material` (a `mib_illum_lambert`): its diffuse colour
/// is the lobe's base seen from the back (exactly), reflected on the back's side, or
/// transmitted from the front's with `render_reverse_of_back_material`; the top stays the
/// front's; no warning (refraction colour 0.05: the layer's cap 0.95 keeps the colour
/// whole). A black `refraction_color` with a back material keeps both (a
/// lobe of colour 0). A back material whose colour is connected to a texture warns (its
/// constant colour is kept, the top's colour is not driven by it).
#[test]
fn glossy_refraction_shows_its_back_material_from_the_back() {
    for (reverse, through) in [("off", false), ("on", true)] {
        let (s, warnings) = translated(&format!(
            r#"shader "top" "mib_illum_lambert" ("diffuse" 0.3 0.2 0.1)
shader "back" "mib_illum_lambert" ("diffuse" 0.1 0.5 0.9)
material "m" "mib_glossy_refraction" ("top_material" "top", "back_material" "back",
    "render_reverse_of_back_material" {reverse}, "ior" 1.5, "refraction_color" 0.05 0.05 0.05) end material
"#
        ));
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(s.diffuse, Rgb::new(0.3, 0.2, 0.1));
        let SurfaceModel::MibGlossyRefraction(lobe) = &s.model else { panic!("{:?}", s.model) };
        let inside = lobe.bsdf(s.diffuse, -Vec3A::Z);
        assert_eq!((inside.base, inside.base_through), (Rgb::new(0.1, 0.5, 0.9), through));
        let front = lobe.bsdf(s.diffuse, Vec3A::Z);
        assert_eq!((front.base, front.base_through), (s.diffuse, false));
    }
    let (s, warnings) = translated(
        r#"shader "back" "mib_illum_lambert" ("diffuse" 0.1 0.5 0.9)
material "m" "mib_glossy_refraction" ("back_material" "back", "refraction_color" 0 0 0) end material
"#,
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    let SurfaceModel::MibGlossyRefraction(lobe) = &s.model else { panic!("{:?}", s.model) };
    assert_eq!(lobe.color, Rgb::ZERO);
    assert_eq!(lobe.bsdf(s.diffuse, -Vec3A::Z).base, Rgb::new(0.1, 0.5, 0.9));
    let (s, warnings, _) = translated_with_graph(
        r#"shader "tex" "mib_color_mix" ("num" 0, "color_base" 0.2 0.2 0.2 1)
shader "back" "mib_illum_lambert" ("diffuse" = "tex")
material "m" "mib_glossy_refraction" ("back_material" "back") end material
"#,
    );
    assert!(warnings.iter().any(|w| w.contains("back_material 'back' has connected")), "{warnings:?}");
    assert!(matches!(s.varying, material::Varying::Constant), "{:?}", s.varying);
}
