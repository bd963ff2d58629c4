//! A layeredShader whose rampShader layer's transparency follows the view and whose
//! layers hold more distinct light-angle ramps or `translucenceFocus` lobes than the
//! per-hit BSDF's own slots (four): the stack's lobes are held by the material
//! (`bsdf::maya_highlight::translucent_stack`) and the hit's BSDF weights them by the
//! layers' shares at its facing ratio, exactly for any number of parts.

use crate::support;

use bsdf::maya_highlight::translucence::focus_exponent;
use bsdf::{MayaGlossy, Rgb};
use glam::Vec3A;
use material::SurfaceModel;
use maya::layered_shader::{composite_layers, ShaderLayer};
use maya::utility::Ramp;
use support::maya::compile;

/// The rampShaders' `translucence` and `diffuse`.
const T: f32 = 0.6;
const D: f32 = 0.8;

/// The top layer's transparency ramp: 0.9 at facing ratio 0 to 0.2 at 0.75 (24/32: its
/// knots lie on the path engine's table points), linear, 0.2 after.
fn view_ramp() -> Ramp {
    Ramp::new(vec![(0.0, Vec3A::splat(0.9), 1), (0.75, Vec3A::splat(0.2), 1)], Vec3A::ZERO)
}

/// A rampShader "name" (light-angle input) of colour ramp `knots` and transparency `tr`
/// (constant), or [`view_ramp`] where `tr` is `None` (`.mi` text).
fn ramp_shader(name: &str, knots: &[(f32, [f32; 3], i32)], tr: Option<f32>) -> String {
    let points: Vec<String> = knots
        .iter()
        .map(|(x, [r, g, b], i)| {
            format!("{{ \"color_Position\" {x}, \"color_Color\" {r} {g} {b}, \"color_Interp\" {i} }}")
        })
        .collect();
    let transparency = match tr {
        Some(t) => {
            format!("{{ \"transparency_Position\" 0, \"transparency_Color\" {t} {t} {t}, \"transparency_Interp\" 1 }}")
        }
        None => "{ \"transparency_Position\" 0, \"transparency_Color\" 0.9 0.9 0.9, \"transparency_Interp\" 1 }, \
                 { \"transparency_Position\" 0.75, \"transparency_Color\" 0.2 0.2 0.2, \"transparency_Interp\" 1 }"
            .into(),
    };
    format!(
        "shader \"{name}\" \"maya_rampshader\" (\"colorInput\" 0, \"diffuse\" {D}, \"translucence\" {T},\n\
         \"transparency\" [ {transparency} ], \"color\" [ {} ])\n",
        points.join(", ")
    )
}

/// Six distinct colour ramps: knots at 0, 0.15 + 0.1 i and 0.9, linear but the last
/// (spline).
fn ramps() -> Vec<Vec<(f32, [f32; 3], i32)>> {
    (0..6)
        .map(|i| {
            let k = i as f32;
            let interp = if i == 5 { 3 } else { 1 };
            vec![
                (0.0, [0.9, 0.2 + 0.1 * k, 0.4], interp),
                (0.15 + 0.1 * k, [0.1, 0.8, 0.3 + 0.1 * k], interp),
                (0.9, [0.5; 3], interp),
            ]
        })
        .collect()
}

/// The layered shader "mat" of layers "l0", "l1", … and its shading engine "m" (`.mi`).
fn layered(layers: usize) -> String {
    let inputs: Vec<String> = (0..layers)
        .map(|i| format!("{{ \"color\" = \"l{i}.outColor\", \"transparency\" = \"l{i}.outTransparency\" }}"))
        .collect();
    format!(
        "shader \"mat\" \"maya_layeredshader\" (\"inputs\" [ {} ])\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n",
        inputs.join(", ")
    )
}

/// The translated material "m" of `body` (no message, no warning).
fn translated(body: &str) -> material::SurfaceMaterial {
    let c = compile("", &format!("$include \"mayabase.mi\"\n{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let (s, warnings) =
        material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine");
    assert!(warnings.is_empty(), "{warnings:?}");
    s
}

/// The Maya model of a translated material.
fn model(s: &material::SurfaceMaterial) -> MayaGlossy {
    let SurfaceModel::Maya(g) = &s.model else { panic!("a Maya model: {:?}", s.model) };
    **g
}

/// The classic stack's shares of layers of transparencies `t` (top first):
/// `maya::layered_shader::composite_layers` compositing as textures with colour 1 for the
/// layer asked and 0 for the others.
fn classic_shares(t: &[Vec3A]) -> Vec<Vec3A> {
    (0..t.len())
        .map(|i| {
            let layers: Vec<ShaderLayer> = t
                .iter()
                .enumerate()
                .map(|(k, &transparency)| ShaderLayer {
                    color: if k == i { Vec3A::ONE } else { Vec3A::ZERO },
                    transparency,
                    includes_behind: false,
                })
                .collect();
            composite_layers(&layers, true, Vec3A::ZERO).0
        })
        .collect()
}

/// Directions spread over the sphere (a spiral), local frame.
fn directions() -> Vec<Vec3A> {
    (0..24)
        .map(|k| {
            let z = 1.0 - 2.0 * (k as f32 + 0.5) / 24.0;
            let phi = 2.4 * k as f32;
            let r = (1.0 - z * z).sqrt();
            Vec3A::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// At facing ratios 0.3, 0.55, 0.8 and 1, the translucence of the hit's BSDF (the stack
/// `s` applied at f) is Σ_i w_i(f) ⊙ (layer i alone), w_i the classic shares of the
/// layers' transparencies `transparencies(f)`, within 1e-5 over 24 × 24 direction pairs.
fn assert_sum_of_layers(
    s: &material::SurfaceMaterial,
    alone: &[MayaGlossy],
    transparencies: impl Fn(f32) -> Vec<Vec3A>,
) {
    let view = s.view_transparency.as_deref().expect("a stack that follows the view");
    for f in [0.3f32, 0.55, 0.8, 1.0] {
        let mut hit = s.constant();
        view.apply(f, &mut hit);
        let SurfaceModel::Maya(g) = &*hit.model else { panic!("a Maya model: {:?}", hit.model) };
        let shares = classic_shares(&transparencies(f));
        assert_eq!(shares.len(), alone.len());
        let singles: Vec<MayaGlossy> = alone.iter().zip(&shares).map(|(a, w)| a.scaled(*w)).collect();
        for &wo in &directions() {
            let stack = g.bsdf(Rgb::ZERO, wo);
            for &wi in &directions() {
                let want =
                    singles.iter().fold(Vec3A::ZERO, |sum, l| sum + l.bsdf(Rgb::ZERO, wo).eval_translucence(wo, wi));
                let got = stack.eval_translucence(wo, wi);
                assert!((got - want).abs().max_element() < 1e-5, "f {f}, {wo} {wi}: {got} vs {want}");
            }
        }
    }
}

/// A stack of six rampShader layers whose colour ramps all differ (six light-angle
/// shapes, more than a hit's `LightAngle` holds), the top one's transparency following
/// the view ([`view_ramp`]), the next four of transparency ½, the last opaque: the
/// path BSDF's translucence at f = 0.3, 0.55, 0.8, 1 is the sum of each layer alone (its
/// rampShader as an opaque material of its own) by its classic share at f within 1e-5,
/// with no warning. Before, the fifth and sixth ramps were added to the largest one's
/// ramp at each hit, warned.
#[test]
fn a_view_following_stack_of_six_ramps_is_the_sum_of_its_layers() {
    let ramps = ramps();
    let layers: String = ramps
        .iter()
        .enumerate()
        .map(|(i, k)| {
            let tr = match i {
                0 => None,
                5 => Some(0.0),
                _ => Some(0.5),
            };
            ramp_shader(&format!("l{i}"), k, tr)
        })
        .collect();
    let s = translated(&format!("{layers}{}", layered(6)));
    let alone: Vec<MayaGlossy> = ramps
        .iter()
        .map(|k| model(&translated(&format!("{}{}", ramp_shader("l0", k, Some(0.0)), layered(1)))))
        .collect();
    assert_sum_of_layers(&s, &alone, |f| {
        let mut t = vec![view_ramp().at(f)];
        t.extend([Vec3A::splat(0.5); 4]);
        t.push(Vec3A::ZERO);
        t
    });
}

/// A stack of a rampShader layer whose transparency follows the view ([`view_ramp`],
/// light-angle translucence) over six lamberts of `translucenceFocus` 0, 0.2, 0.4, 0.6,
/// 0.8 and 0.9 (colours differing, `translucence` 0.5; transparency ½ but the last,
/// opaque): the path BSDF's translucence at f = 0.3, 0.55, 0.8, 1 is the sum of each
/// layer alone by its classic share at f within 1e-5, with no warning. Before, a focus
/// past the fourth was merged into the lobe of the nearest exponent, warned.
#[test]
fn a_view_following_stack_of_six_foci_is_the_sum_of_its_layers() {
    let foci = [0.0f32, 0.2, 0.4, 0.6, 0.8, 0.9];
    let colour = |i: usize| [0.2 + 0.12 * i as f32, 0.8 - 0.1 * i as f32, 0.3 + 0.05 * i as f32];
    let top = &ramps()[2];
    let mut body = ramp_shader("l0", top, None);
    for (i, focus) in foci.iter().enumerate() {
        let [r, g, b] = colour(i);
        let tr = if i + 1 < foci.len() { 0.5 } else { 0.0 };
        body += &format!(
            "shader \"l{}\" \"maya_lambert\" (\"color\" {r} {g} {b}, \"diffuse\" 0.8, \"translucence\" 0.5, \
             \"translucenceFocus\" {focus}, \"transparency\" {tr} {tr} {tr})\n",
            i + 1
        );
    }
    let s = translated(&format!("{body}{}", layered(7)));
    let plain = MayaGlossy::new(bsdf::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO);
    let mut alone = vec![model(&translated(&format!("{}{}", ramp_shader("l0", top, Some(0.0)), layered(1))))];
    alone.extend(
        foci.iter()
            .enumerate()
            .map(|(i, &f)| plain.with_translucence(Vec3A::from_array(colour(i)) * 0.5, focus_exponent(f))),
    );
    assert_sum_of_layers(&s, &alone, |f| {
        let mut t = vec![view_ramp().at(f)];
        t.extend([Vec3A::splat(0.5); 5]);
        t.push(Vec3A::ZERO);
        t
    });
}
