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
