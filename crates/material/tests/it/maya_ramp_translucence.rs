//! rampShader's light from behind (light-angle input) in the path engine's translation:
//! the transmission lobe evaluates the colour ramp itself — its knots and interpolation
//! (`bsdf::maya_highlight::translucence::LightAngle`) — where the classic shader reads
//! t · C((1 + cos θ)/2) for a light behind at cos θ.

use crate::support;

use glam::Vec3A;
use material::SurfaceModel;
use maya::ramp_shader::{lit_color, ColorInput};
use maya::utility::Ramp;
use support::maya::compile;

/// The colour ramp's knots: position and colour (off the former table's sixteenths of
/// [0, ½]: 0.1 and 0.37, then one past ½).
const KNOTS: [(f32, [f32; 3]); 3] = [(0.1, [0.9, 0.1, 0.3]), (0.37, [0.2, 0.8, 0.6]), (0.8, [0.5, 0.3, 1.2])];

/// The rampShader's `translucence` and `diffuse`.
const T: f32 = 0.7;
const D: f32 = 0.8;

/// For the colour ramp [`KNOTS`] with Maya interpolation `interp` (0 none, 1 linear,
/// 2 smooth, 3 spline): the path engine's light from behind at 100 light cosines
/// u = 0.005 … 0.995, seen head-on — the translated BSDF's f · π · u (a unit light's
/// radiance through the lobe) — is the classic shader's `lit_color` for a unit light at
/// cos θ = −u, t · C((1 − u)/2), within 1e-4 per channel; no warning. Before, the lobe read
/// a table of the ramp at every sixteenth of [0, ½], linearly between: a knot at 0.1 or
/// 0.37 and the smooth and spline segments were followed only at those points.
#[test]
fn the_light_from_behind_follows_the_ramp_in_every_interpolation() {
    for interp in 0..4 {
        let points: Vec<String> = KNOTS
            .iter()
            .map(|(x, [r, g, b])| {
                format!("{{ \"color_Position\" {x}, \"color_Color\" {r} {g} {b}, \"color_Interp\" {interp} }}")
            })
            .collect();
        let body = format!(
            "$include \"mayabase.mi\"\n\
             shader \"mat\" \"maya_rampshader\" (\"colorInput\" 0, \"diffuse\" {D}, \"translucence\" {T},\n\
             \"color\" [ {} ])\n\
             material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n",
            points.join(", ")
        );
        let c = compile("", &body, &["m"], "");
        assert!(c.messages.is_empty(), "{:#?}", c.messages);
        let (s, warnings) =
            material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine");
        assert!(warnings.is_empty(), "{warnings:?}");
        let SurfaceModel::Maya(g) = &s.model else { panic!("a Maya model: {:?}", s.model) };
        let classic = Ramp::new(KNOTS.iter().map(|(x, c)| (*x, Vec3A::from_array(*c), interp)).collect(), Vec3A::ZERO);
        let wo = Vec3A::Z;
        let bsdf = g.bsdf(s.diffuse, wo);
        let mut worst = 0.0f32;
        for i in 0..100 {
            let u = (i as f32 + 0.5) / 100.0;
            let wi = Vec3A::new((1.0 - u * u).sqrt(), 0.0, -u);
            let got = bsdf.eval(wo, wi) * (std::f32::consts::PI * u);
            let want = lit_color(ColorInput::LightAngle, &classic, &[(Vec3A::ONE, -u)], D, T, 1.0);
            worst = worst.max((got - want).abs().max_element());
            assert!((got - want).abs().max_element() < 1e-4, "interp {interp}, u {u}: {got} vs {want}");
        }
        println!("interp {interp}: largest difference {worst:e}");
    }
}

/// A 5-knot and a 7-knot colour ramp, 4 and 5 of their knots in [0, ½], the rest past it,
/// smooth (2) and spline (3) segments: position, colour, interpolation.
fn many_knots() -> [Vec<(f32, [f32; 3], i32)>; 2] {
    [
        vec![
            (0.05, [0.9, 0.2, 0.4], 2),
            (0.18, [0.1, 0.7, 0.3], 3),
            (0.31, [0.6, 0.1, 0.9], 2),
            (0.47, [0.3, 0.9, 0.2], 3),
            (0.72, [1.1, 0.4, 0.6], 2),
        ],
        vec![
            (0.0, [0.2, 0.5, 0.8], 3),
            (0.08, [0.9, 0.1, 0.2], 2),
            (0.15, [0.4, 0.8, 0.1], 3),
            (0.26, [0.7, 0.3, 0.5], 2),
            (0.39, [0.1, 0.6, 0.9], 3),
            (0.55, [0.8, 0.8, 0.3], 2),
            (0.9, [0.3, 0.2, 0.7], 3),
        ],
    ]
}

/// A rampShader "name" of colour ramp `knots`, `translucence` [`T`], `diffuse` [`D`] and
/// transparency `tr` (`.mi` text).
fn ramp_shader(name: &str, knots: &[(f32, [f32; 3], i32)], tr: f32) -> String {
    let points: Vec<String> = knots
        .iter()
        .map(|(x, [r, g, b], i)| {
            format!("{{ \"color_Position\" {x}, \"color_Color\" {r} {g} {b}, \"color_Interp\" {i} }}")
        })
        .collect();
    format!(
        "shader \"{name}\" \"maya_rampshader\" (\"colorInput\" 0, \"diffuse\" {D}, \"translucence\" {T},\n\
         \"transparency\" [ {{ \"transparency_Position\" 0, \"transparency_Color\" {tr} {tr} {tr}, \
         \"transparency_Interp\" 1 }} ], \"color\" [ {} ])\n",
        points.join(", ")
    )
}

/// The translated Maya model of material "m" in `body` (no warning) and its diffuse colour.
fn translated(body: &str) -> (bsdf::MayaGlossy, bsdf::Rgb) {
    let c = compile("", &format!("$include \"mayabase.mi\"\n{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let (s, warnings) =
        material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine");
    assert!(warnings.is_empty(), "{warnings:?}");
    let SurfaceModel::Maya(g) = &s.model else { panic!("a Maya model: {:?}", s.model) };
    (**g, s.diffuse)
}

/// The light from behind a unit light at cosine `u` gives through `g` seen head-on:
/// f · π · u.
fn through(g: &bsdf::MayaGlossy, diffuse: bsdf::Rgb, u: f32) -> Vec3A {
    let wo = Vec3A::Z;
    let wi = Vec3A::new((1.0 - u * u).sqrt(), 0.0, -u);
    g.bsdf(diffuse, wo).eval(wo, wi) * (std::f32::consts::PI * u)
}

/// Ramps of 5 and 7 knots (past the former limit of 3 in [0, ½], which read them at 4
/// points, linearly between, with a warning): at 9 light angles θ = 0°, 10° … 80° behind,
/// the path engine's light from behind seen head-on is the classic shader's `lit_color`
/// for a unit light at cos θ within 1e-4 per channel; no warning.
#[test]
fn ramps_of_many_knots_are_followed_at_every_light_angle() {
    for knots in many_knots() {
        let (g, diffuse) = translated(&format!(
            "{}material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n",
            ramp_shader("mat", &knots, 0.0)
        ));
        let classic = Ramp::new(knots.iter().map(|(x, c, i)| (*x, Vec3A::from_array(*c), *i)).collect(), Vec3A::ZERO);
        for k in 0..9 {
            let u = (k as f32 * 10.0).to_radians().cos();
            let got = through(&g, diffuse, u);
            let want = lit_color(ColorInput::LightAngle, &classic, &[(Vec3A::ONE, -u)], D, T, 1.0);
            assert!((got - want).abs().max_element() < 1e-4, "{} knots, θ {}°: {got} vs {want}", knots.len(), k * 10);
        }
    }
}

/// A layeredShader of two rampShader layers whose ramps' knots differ (the 5-knot ramp
/// over the 7-knot one, the top of transparency 0.4: shares 0.6 and 0.4): its light from
/// behind at 9 light angles equals the sum of each layer's alone (each as a material of its
/// own and opaque, times its share) within 1e-5, no warning (before: the union of their knots, linearly
/// between, warned).
#[test]
fn a_stack_of_differing_ramps_is_the_sum_of_each() {
    let [five, seven] = many_knots();
    let layers = format!("{}{}", ramp_shader("top", &five, 0.4), ramp_shader("under", &seven, 0.0));
    let (stack, stack_diffuse) = translated(&format!(
        "{layers}shader \"mat\" \"maya_layeredshader\" (\"inputs\" [ \
         {{ \"color\" = \"top.outColor\", \"transparency\" = \"top.outTransparency\" }}, \
         {{ \"color\" = \"under.outColor\", \"transparency\" = \"under.outTransparency\" }} ])\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n"
    ));
    let alone = |knots: &[(f32, [f32; 3], i32)]| {
        translated(&format!(
            "{}material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n",
            ramp_shader("mat", knots, 0.0)
        ))
    };
    let ((top, top_diffuse), (under, under_diffuse)) = (alone(&five), alone(&seven));
    for k in 0..9 {
        let u = (k as f32 * 10.0).to_radians().cos();
        let got = through(&stack, stack_diffuse, u);
        let want = through(&top, top_diffuse, u) * 0.6 + through(&under, under_diffuse, u) * 0.4;
        assert!((got - want).abs().max_element() < 1e-5, "θ {}°: {got} vs {want}", k * 10);
    }
}

/// A layeredShader of six rampShader layers whose ramps all differ (two linear knots,
/// the second at 0.15, 0.25, … 0.65, and a spline one; transparency ½ over the five top
/// ones: shares ½, ¼, ⅛, 1/16, 1/32, 1/32): more distinct ramps than a `LightAngle`
/// holds parts, its light from behind at 9 light angles still equals the sum of each
/// layer's alone by its share within 1e-5, with no warning (maya45: the translation folds
/// the smallest parts into interned composites; before, the fifth and sixth were added
/// to the largest one's ramp, warned).
#[test]
fn a_stack_of_six_differing_ramps_is_the_sum_of_each() {
    let ramps: Vec<Vec<(f32, [f32; 3], i32)>> = (0..6)
        .map(|i| {
            let x = 0.15 + 0.1 * i as f32;
            let interp = if i == 5 { 3 } else { 1 };
            vec![
                (0.0, [0.9, 0.2 + 0.1 * i as f32, 0.4], interp),
                (x, [0.1, 0.8, 0.3 + 0.1 * i as f32], interp),
                (0.9, [0.5; 3], interp),
            ]
        })
        .collect();
    let layers: String = ramps
        .iter()
        .enumerate()
        .map(|(i, k)| ramp_shader(&format!("l{i}"), k, if i < 5 { 0.5 } else { 0.0 }))
        .collect();
    let inputs: Vec<String> = (0..6)
        .map(|i| format!("{{ \"color\" = \"l{i}.outColor\", \"transparency\" = \"l{i}.outTransparency\" }}"))
        .collect();
    let (stack, stack_diffuse) = translated(&format!(
        "{layers}shader \"mat\" \"maya_layeredshader\" (\"inputs\" [ {} ])\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n",
        inputs.join(", ")
    ));
    let shares = [0.5f32, 0.25, 0.125, 0.0625, 0.03125, 0.03125];
    let alone: Vec<(bsdf::MayaGlossy, bsdf::Rgb)> = ramps
        .iter()
        .map(|k| {
            translated(&format!(
                "{}material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n",
                ramp_shader("mat", k, 0.0)
            ))
        })
        .collect();
    for k in 0..9 {
        let u = (k as f32 * 10.0).to_radians().cos();
        let got = through(&stack, stack_diffuse, u);
        let want: Vec3A = alone.iter().zip(shares).map(|((g, d), w)| through(g, *d, u) * w).sum();
        assert!((got - want).abs().max_element() < 1e-5, "θ {}°: {got} vs {want}", k * 10);
    }
}
