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
fn blinn_phong_and_phong_e_become_maya_highlights_that_give_the_classic_colour() {
    // Under the unit light straight above and seen from 30° off the normal (light
    // 20° the other way, so the highlight is off its peak), the path engine's BSDF times
    // the light it delivers (π·I·cos θ) is the classic shader's colour.
    let t = 20f32.to_radians();
    let to_light = glam::Vec3A::new(0.0, t.cos(), t.sin());
    for body in [
        r#"shader "b" "adskMayaBlinn" ("color" 0.5 0.4 0.3, "diffuse" 0.8, "eccentricity" 0.25,
            "specularColor" 0.5 0.5 0.5, "reflectivity" 0, "transparency" 0.3 0.3 0.3)"#,
        r#"shader "b" "maya_phong" ("color" 0.5 0.4 0.3, "diffuse" 0.8, "cosinePower" 12,
            "specularColor" 0.6 0.5 0.4, "reflectivity" 0)"#,
        r#"shader "b" "maya_phongE" ("color" 0.5 0.4 0.3, "diffuse" 0.8, "roughness" 0.4,
            "highlightSize" 0.7, "whiteness" 0.9 0.8 0.7, "specularColor" 0.6 0.5 0.4, "reflectivity" 0)"#,
    ] {
        let engine = if body.contains("adskMaya") { "adskMayaShadingEngine" } else { "maya_shadingengine" };
        let text = format!(
            "light \"sun\" \"maya_directionallight\" (\"intensity\" 1) direction {} {} {} end light\n\
             instance \"sun_inst\" \"sun\" end instance\n{body}\n\
             material \"m\" opaque \"{engine}\" (\"surfaceShader\" = \"b.outColor\") end material",
            -to_light.x, -to_light.y, -to_light.z
        );
        let c = compile("", &format!("{LIBS}{text}"), &["m"], "");
        assert!(c.messages.is_empty(), "{:#?}", c.messages);
        let (s, warnings) = translate(&c);
        assert!(warnings.is_empty(), "{warnings:?}");
        let SurfaceModel::Maya(g) = &s.model else { panic!("{:?}", s.model) };
        assert!((s.diffuse - bsdf::Rgb::new(0.4, 0.32, 0.24)).abs().max_element() < 1e-6);
        // The viewer 30° off the normal towards −z (the shading point is seen from the
        // camera `support::maya::point` places straight above: only the BSDF is compared
        // off-axis here, against the classic formula of the same directions).
        let frame = bsdf::Frame::from_normal(glam::Vec3A::Y);
        let v = glam::Vec3A::new(0.0, 30f32.to_radians().cos(), -30f32.to_radians().sin());
        let path = g.bsdf(s.diffuse, frame.to_local(v)).eval(frame.to_local(v), frame.to_local(to_light))
            * (std::f32::consts::PI * t.cos());
        let classic = s.diffuse * t.cos()
            + s.maya_highlight.expect("the classic highlight").model.value(glam::Vec3A::Y, v, to_light)
                * s.maya_highlight.expect("the classic highlight").color;
        assert!((path - classic).abs().max_element() < 1e-5, "{body}: {path} vs {classic}");
        // Seen from straight above, as `run` shades it: the classic shader's colour.
        let shaded = run(&c, &Empty::default(), c.material("m"), point([0.0, 0.0])).color();
        let up = frame.to_local(glam::Vec3A::Y);
        let path = g.bsdf(s.diffuse, up).eval(up, frame.to_local(to_light)) * (std::f32::consts::PI * t.cos());
        // The classic shader fades its diffuse part by 1 − T, not its highlight; the
        // path engine hits a share `opacity` = 1 − T of the rays, whose BSDF carries both
        // divided by it: over all rays, the classic colour.
        let opacity = if body.contains("transparency") { 0.7 } else { 1.0 };
        assert!((s.opacity - opacity).abs() < 1e-6);
        for i in 0..3 {
            assert!((shaded[i] - path[i] * opacity).abs() < 1e-5, "{body}: channel {i}: classic {shaded} vs {path}");
        }
    }
}

/// A file texture on a blinn's `specularColor`: at each hit the Maya lobe's tint is the
/// texel's colour and its mirror `reflectivity` × it (within 1e-3), and the path engine's
/// BSDF under the unit light straight above, seen from above, gives the classic shader's
/// colour within 1e-5 (red and white texels: the highlight 0.7 × the texel).
#[test]
fn a_texture_on_specular_color_tints_the_highlight_and_the_mirror_per_hit() {
    let c = scene(&format!(
        r#"{QUAD}
        shader "file1" "maya_file" ("fileTextureName" "quad")
        shader "b" "maya_blinn" ("color" 0.5 0.4 0.3, "diffuse" 0.8, "eccentricity" 0.3,
            "specularColor" = "file1.outColor", "reflectivity" 0.3)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "b.outColor") end material"#
    ));
    let (s, warnings) = translate(&c);
    assert!(warnings.is_empty(), "{warnings:?}");
    let Varying::Bindings(b) = &s.varying else { panic!("no bindings: {:?}", s.varying) };
    assert!(b.iter().any(|b| b.target == Target::SpecularColor && b.scale == 2.0), "{b:?}");
    let tracer = Empty::default();
    for (uv, texel) in [([0.25, 0.25], [1.0, 0.0, 0.0]), ([0.75, 0.75], [1.0, 1.0, 1.0])] {
        let texel = bsdf::Rgb::from_array(texel);
        let mut ctx = Ctx::new(&c.shading, &tracer, point(uv));
        let hit = s.at(&mut ctx);
        let SurfaceModel::Maya(g) = &*hit.model else { panic!("{:?}", hit.model) };
        assert!((g.tint - texel).abs().max_element() < 1e-3, "{uv:?}: tint {}", g.tint);
        assert!((g.mirror - texel * 0.3).abs().max_element() < 1e-3, "{uv:?}: mirror {}", g.mirror);
        let up = glam::Vec3A::Z;
        let path = g.bsdf(hit.diffuse, up).eval(up, up) * std::f32::consts::PI;
        let classic = run(&c, &Empty::default(), c.material("m"), point(uv)).color();
        for i in 0..3 {
            let want = 0.8 * [0.5, 0.4, 0.3][i] + 0.7 * texel[i];
            assert!((classic[i] - want).abs() < 1e-3, "{uv:?}: classic {classic} vs {want}");
            assert!((path[i] - classic[i]).abs() < 1e-5, "{uv:?}: path {path} vs classic {classic}");
        }
    }
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
