//! Maya's `irradiance` input (an illumination map) on the lambert family: without any
//! light, final gathering off, a lambert of colour c and diffuse d shows c·d ⊙
//! `irradianceColor` ⊙ M in the classic engine, and the path engine's translation emits
//! exactly that — constant, or per hit from a connected map. The shading point is the
//! origin, normal +y, seen from above (`support::maya::point`).

use crate::support;

use material::{Target, Varying};
use shader::Ctx;
use support::maya::{assert_rgb, compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";
/// A 2×2 texture: red, green (bottom row), blue, white (top row).
const QUAD: &str = r#"color texture "quad" [ 2 2 ] 'ff0000' '00ff00' '0000ff' 'ffffff'"#;

fn scene(body: &str) -> Compiled {
    let c = compile("", &format!("{LIBS}{QUAD}\n{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

fn translate(c: &Compiled) -> (material::SurfaceMaterial, Vec<String>) {
    material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine")
}

#[test]
fn a_constant_irradiance_map_lights_the_lambert_family_without_lights() {
    for family in ["maya_lambert", "maya_blinn", "adskMayaPhong"] {
        let engine = if family.starts_with("adsk") { "adskMayaShadingEngine" } else { "maya_shadingengine" };
        let c = scene(&format!(
            r#"shader "mat" "{family}" ("color" 0.5 0.6 0.7, "diffuse" 0.8, "irradiance" 0.2 0.4 0.6,
                "irradianceColor" 2 0.5 1, "incandescence" 0.01 0 0)
            material "m" opaque "{engine}" ("surfaceShader" = "mat.outColor") end material"#
        ));
        // c·d ⊙ g ⊙ M + incandescence.
        let want = [0.4 * 2.0 * 0.2 + 0.01, 0.48 * 0.5 * 0.4, 0.56 * 0.6];
        let classic = run(&c, &Empty::default(), c.material("m"), point([0.0, 0.0])).color();
        assert_rgb(classic, want, 1e-5);
        let (s, warnings) = translate(&c);
        assert!(warnings.is_empty(), "{warnings:?}");
        assert!((s.emission - glam::Vec3A::from_array(want)).abs().max_element() < 1e-5, "{family}: {}", s.emission);
    }
    // The default (black) changes nothing.
    let c = scene(
        r#"shader "mat" "maya_lambert" ("color" 0.5 0.6 0.7)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material"#,
    );
    assert_rgb(run(&c, &Empty::default(), c.material("m"), point([0.0, 0.0])).color(), [0.0; 3], 1e-6);
    assert_eq!(translate(&c).0.emission, glam::Vec3A::ZERO);
}

#[test]
fn a_connected_irradiance_map_lights_each_hit_in_both_engines() {
    let c = scene(
        r#"shader "bake" "maya_file" ("fileTextureName" "quad")
        shader "lam" "maya_lambert" ("color" 0.5 0.6 0.7, "diffuse" 0.5, "irradiance" = "bake.outColor",
            "irradianceColor" 0.5 0.5 0.5)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
    );
    let (s, warnings) = translate(&c);
    assert!(warnings.is_empty(), "{warnings:?}");
    let Varying::Bindings(b) = &s.varying else { panic!("no bindings: {:?}", s.varying) };
    assert!(b.iter().any(|b| b.target == Target::IrradianceMap && b.scale == 0.5));
    let tracer = Empty::default();
    // (0.25, 0.25): red; (0.75, 0.75): white. c·d·g ⊙ M = (0.125, 0.15, 0.175) ⊙ M.
    for (uv, map) in [([0.25, 0.25], [1.0, 0.0, 0.0]), ([0.75, 0.75], [1.0, 1.0, 1.0])] {
        let want = [0.125 * map[0], 0.15 * map[1], 0.175 * map[2]];
        let classic = run(&c, &tracer, c.material("m"), point(uv)).color();
        assert_rgb(classic, want, 1e-3);
        let mut ctx = Ctx::new(&c.shading, &tracer, point(uv));
        let hit = s.at(&mut ctx);
        for i in 0..3 {
            assert!((hit.emission[i] - classic[i]).abs() < 1e-5, "{uv:?}: path {} classic {classic}", hit.emission);
        }
    }
}

/// A connected map under a coloured `irradianceColor` g = (2, 0.5, 1): the path engine's
/// hit emits c·d ⊙ g ⊙ M per channel, as the classic shader shows it (within 1e-5 of
/// the classic engine, 1e-3 of the formula), with no warning. Before, it took g's mean
/// (7/6) for every channel and warned.
#[test]
fn a_connected_irradiance_map_takes_a_coloured_irradiance_colour_per_channel() {
    let c = scene(
        r#"shader "bake" "maya_file" ("fileTextureName" "quad")
        shader "lam" "maya_lambert" ("color" 0.5 0.6 0.7, "diffuse" 0.5, "irradiance" = "bake.outColor",
            "irradianceColor" 2 0.5 1)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
    );
    let (s, warnings) = translate(&c);
    assert!(warnings.is_empty(), "{warnings:?}");
    let tracer = Empty::default();
    // (0.25, 0.25): red; (0.75, 0.75): white. c·d ⊙ g ⊙ M = (0.5, 0.15, 0.35) ⊙ M.
    for (uv, map) in [([0.25, 0.25], [1.0, 0.0, 0.0]), ([0.75, 0.75], [1.0, 1.0, 1.0])] {
        let want = [0.5 * map[0], 0.15 * map[1], 0.35 * map[2]];
        let classic = run(&c, &tracer, c.material("m"), point(uv)).color();
        assert_rgb(classic, want, 1e-3);
        let mut ctx = Ctx::new(&c.shading, &tracer, point(uv));
        let hit = s.at(&mut ctx);
        for i in 0..3 {
            assert!((hit.emission[i] - classic[i]).abs() < 1e-5, "{uv:?}: path {} classic {classic}", hit.emission);
        }
    }
}
