//! Maya materials translated for the path engine: the same diffuse albedo as the classic
//! shaders give (compared at the same point under a unit light straight above), constant
//! and texture-driven.

use crate::support;

use material::{SurfaceModel, Target, Varying};
use shader::Ctx;
use support::maya::{compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";
const SUN: &str = r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
instance "sun_inst" "sun" end instance
"#;
const QUAD: &str = r#"color texture "quad" [ 2 2 ] 'ff0000' '00ff00' '0000ff' 'ffffff'"#;

fn scene(body: &str) -> Compiled {
    let c = compile("", &format!("{LIBS}{SUN}{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

fn translate(c: &Compiled) -> (material::SurfaceMaterial, Vec<String>) {
    material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine")
}

#[test]
fn lambert_albedo_matches_the_classic_shader() {
    let c = scene(
        r#"shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.7, "incandescence" 0.1 0 0)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
    );
    let (s, warnings) = translate(&c);
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(s.model, SurfaceModel::Lambert);
    let classic = run(&c, &Empty::default(), c.material("m"), point([0.0, 0.0])).color();
    // Classic: c·d·I·cos θ + incandescence with I = cos θ = 1.
    for (got, want) in [(s.diffuse.x, classic.x - 0.1), (s.diffuse.y, classic.y), (s.diffuse.z, classic.z)] {
        assert!((got - want).abs() < 1e-5, "{got} vs {want}");
    }
    assert!((s.emission.x - 0.1).abs() < 1e-6 && s.opacity == 1.0);
}

#[test]
fn a_file_texture_drives_the_diffuse_colour_per_hit() {
    let c = scene(&format!(
        r#"{QUAD}
        shader "file1" "maya_file" ("fileTextureName" "quad")
        shader "lam" "maya_lambert" ("color" = "file1.outColor", "diffuse" 0.5)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
    ));
    let (s, _) = translate(&c);
    let Varying::Bindings(b) = &s.varying else { panic!("no bindings: {:?}", s.varying) };
    assert_eq!((b[0].target, b[0].member.as_deref(), b[0].scale), (Target::Diffuse, Some("outColor"), 0.5));
    let tracer = Empty::default();
    for (uv, want) in [([0.25, 0.25], [0.5, 0.0, 0.0]), ([0.75, 0.75], [0.5, 0.5, 0.5])] {
        let mut ctx = Ctx::new(&c.shading, &tracer, point(uv));
        let hit = s.at(&mut ctx);
        let classic = run(&c, &Empty::default(), c.material("m"), point(uv)).color();
        for i in 0..3 {
            assert!((hit.diffuse[i] - want[i]).abs() < 1e-3, "{uv:?}: {}", hit.diffuse);
            assert!((hit.diffuse[i] - classic[i]).abs() < 1e-5, "{uv:?}: path {} classic {classic}", hit.diffuse);
        }
    }
}

#[test]
fn blinn_becomes_a_unified_bsdf_with_the_eccentricity_as_ggx_alpha() {
    let c = scene(
        r#"shader "b" "adskMayaBlinn" ("color" 0.5 0.4 0.3, "diffuse" 0.8, "eccentricity" 0.25,
            "specularColor" 0.5 0.5 0.5, "transparency" 0.3 0.3 0.3)
        material "m" opaque "adskMayaShadingEngine" ("surfaceShader" = "b.outColor") end material"#,
    );
    let (s, _) = translate(&c);
    let SurfaceModel::Unified(u) = &s.model else { panic!("{:?}", s.model) };
    let p = u.params();
    assert!((p.base_color - bsdf::Rgb::new(0.4, 0.32, 0.24)).abs().max_element() < 1e-6);
    assert!((p.roughness * p.roughness - 0.25).abs() < 1e-6, "GGX alpha = roughness²");
    assert!((p.specular - 0.5).abs() < 1e-6);
    assert!((s.opacity - 0.7).abs() < 1e-6);
}

#[test]
fn surface_shader_emits_and_other_engines_are_not_translated() {
    let c = scene(
        r#"shader "flat" "maya_surfaceshader" ("outColor" 0.9 0.8 0.7)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#,
    );
    let (s, _) = translate(&c);
    assert_eq!(s.diffuse, bsdf::Rgb::ZERO);
    assert!((s.emission - bsdf::Rgb::new(0.9, 0.8, 0.7)).abs().max_element() < 1e-6);
    let c = scene(r#"material "m" opaque "mib_illum_lambert" ("diffuse" 1 1 1) end material"#);
    assert!(material::maya::surface_material("m", &c.shading.graph, c.material("m")).is_none());
}
