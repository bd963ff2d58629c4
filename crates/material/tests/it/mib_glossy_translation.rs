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
/// `environment_color` other than the reflection colour (here its default, black),
/// `max_distance`, `single_env_sample` (default on) with a spread lobe, `u_axis`.
#[test]
fn unhonoured_parameters_are_warned_about() {
    let (s, warnings) = translated(
        r#"material "m" "mib_glossy_reflection" ("reflection_color" 1 1 1, "environment_color" 0.2 0.2 0.2,
    "max_distance" 5, "u_axis" 0 0 1) end material
"#,
    );
    assert!(matches!(s.model, SurfaceModel::MibGlossy(_)));
    for what in ["environment_color", "max_distance", "single_env_sample", "u_axis"] {
        assert!(warnings.iter().any(|w| w.contains(what)), "no warning about {what}: {warnings:?}");
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
/// parameter is honoured; `samples` 0 leaves the top alone. `back_material`,
/// `max_distance` and `v_axis` are warned about.
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
    let (_, warnings) = translated(
        r#"shader "top" "mib_illum_lambert" ("diffuse" 0.4 0.4 0.4)
material "m" "mib_glossy_refraction" ("top_material" "top", "back_material" "top", "max_distance" 3,
    "v_axis" 1 0 0) end material
"#,
    );
    for what in ["back_material", "max_distance", "v_axis"] {
        assert!(warnings.iter().any(|w| w.contains(what)), "no warning about {what}: {warnings:?}");
    }
}
