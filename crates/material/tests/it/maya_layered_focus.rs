//! A layeredShader's translucent layers in the path engine's translation keep their own
//! `translucenceFocus` (`bsdf::MayaGlossy::add_translucence`): each focus a forward lobe
//! of albedo Σ w_i · c_i · t_i over its layers (w_i the layer's share), up to four
//! distinct foci in the BSDF's own lobes; past them every layer's lobe is held by the
//! material (`bsdf::maya_highlight::translucent_stack`), exactly, with no warning.

use crate::support;

use bsdf::maya_highlight::translucence::focus_exponent;
use glam::Vec3A;
use material::SurfaceModel;
use support::maya::{compile, Compiled};

const LIBS: &str = "$include \"mayabase.mi\"\n";

/// The layers' colours, in order.
const COLORS: [[f32; 3]; 6] =
    [[0.9, 0.2, 0.1], [0.2, 0.8, 0.3], [0.1, 0.3, 0.9], [0.5, 0.5, 0.5], [0.7, 0.6, 0.2], [0.3, 0.6, 0.8]];

/// The layers' `translucence`.
const T: f32 = 0.6;

/// A layeredShader of lamberts "l0" … with the foci `foci`, each but the last of
/// transparency 0.5 (shares ½, ¼, …; the last takes what remains).
fn stack(foci: &[f32]) -> Compiled {
    let mut body = String::new();
    let mut inputs = Vec::new();
    for (i, focus) in foci.iter().enumerate() {
        let [r, g, b] = COLORS[i];
        let tr = if i + 1 < foci.len() { 0.5 } else { 0.0 };
        body += &format!(
            "shader \"l{i}\" \"maya_lambert\" (\"color\" {r} {g} {b}, \"diffuse\" 0.8, \"translucence\" {T}, \
             \"translucenceFocus\" {focus}, \"transparency\" {tr} {tr} {tr})\n"
        );
        inputs.push(format!("{{ \"color\" = \"l{i}.outColor\", \"transparency\" = \"l{i}.outTransparency\" }}"));
    }
    body += &format!(
        "shader \"mat\" \"maya_layeredshader\" (\"inputs\" [ {} ])\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n",
        inputs.join(", ")
    );
    let c = compile("", &format!("{LIBS}{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

/// The translation's translucence lobes (albedo, exponent) and its warnings.
fn lobes(c: &Compiled) -> (Vec<(Vec3A, f32)>, Vec<String>) {
    let (s, warnings) =
        material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine");
    let SurfaceModel::Maya(g) = &s.model else { panic!("a Maya model: {:?}", s.model) };
    (g.translucence_parts().iter().map(|l| (l.albedo, l.exponent)).collect(), warnings)
}

/// Three layers of foci 0.5, 0 and 0.25 (shares ½, ¼, ¼): three lobes, the focus-0 one
/// first, each of albedo w_i · c_i · t and exponent 2φ/(1 − φ) within 1e-6, no warning.
/// Two layers of one focus (0.5) share a lobe of albedo the sum of theirs. Four distinct
/// foci (0.75 under 0.5, 0, 0.25): four lobes, no warning. A fifth (0.8, exponent 8,
/// under those): five lobes held by the material, each layer's w_i · c_i · t at its own
/// exponent within 1e-6, no warning. Before, a fifth focus was merged into the lobe of
/// the nearest exponent (warned), and before that a fourth into the third's.
#[test]
fn each_layers_focus_is_a_lobe_of_its_own() {
    let c = |i: usize| Vec3A::from_array(COLORS[i]) * T;
    let (got, warnings) = lobes(&stack(&[0.5, 0.0, 0.25]));
    assert!(warnings.is_empty(), "{warnings:?}");
    let want =
        [(c(1) * 0.25, focus_exponent(0.0)), (c(0) * 0.5, focus_exponent(0.5)), (c(2) * 0.25, focus_exponent(0.25))];
    assert_eq!(got.len(), 3, "{got:?}");
    for ((a, n), (wa, wn)) in got.iter().zip(want) {
        assert!((*a - wa).abs().max_element() < 1e-6 && (n - wn).abs() < 1e-6, "{a} {n} vs {wa} {wn}");
    }
    let (got, warnings) = lobes(&stack(&[0.5, 0.5]));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(got.len(), 1, "{got:?}");
    assert!((got[0].0 - (c(0) * 0.5 + c(1) * 0.5)).abs().max_element() < 1e-6, "{got:?}");
    let (got, warnings) = lobes(&stack(&[0.5, 0.0, 0.25, 0.75]));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(got.len(), 4, "{got:?}");
    let foci = [0.5, 0.0, 0.25, 0.75, 0.8];
    let (got, warnings) = lobes(&stack(&foci));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(got.len(), 5, "{got:?}");
    let shares = [0.5, 0.25, 0.125, 0.0625, 0.0625];
    for (i, (a, n)) in got.iter().enumerate() {
        let (wa, wn) = (c(i) * shares[i], focus_exponent(foci[i]));
        assert!((*a - wa).abs().max_element() < 1e-6 && (n - wn).abs() < 1e-6, "{i}: {a} {n} vs {wa} {wn}");
    }
}

/// A stack of four layers of foci 0, 0.3, 0.6 and 0.9 (shares ½, ¼, ⅛, ⅛), and one of six
/// (0, 0.2, 0.4, 0.6, 0.8, 0.9; shares ½ … 1/32, 1/32: held by the material): the path
/// engine's translucence, f of the translated stack's BSDF, is the sum of each layer's
/// alone — a Maya BSDF of albedo w_i · c_i · t and exponent 2φ_i/(1 − φ_i) — within 1e-5
/// over 24 × 24 direction pairs, with no warning. Before, the fourth focus (0.9,
/// exponent 18) was merged into the third's lobe (0.6, exponent 3): its forward peak 2.5
/// instead of 10; later a fifth into the nearest.
#[test]
fn foci_are_the_sum_of_their_layers() {
    for foci in [&[0.0f32, 0.3, 0.6, 0.9][..], &[0.0, 0.2, 0.4, 0.6, 0.8, 0.9]] {
        foci_sum(foci);
    }
}

/// [`foci_are_the_sum_of_their_layers`] for the stack of `foci`.
fn foci_sum(foci: &[f32]) {
    use bsdf::maya_highlight::Shape;
    let c = stack(foci);
    let (s, warnings) =
        material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine");
    assert!(warnings.is_empty(), "{warnings:?}");
    let SurfaceModel::Maya(g) = &s.model else { panic!("a Maya model: {:?}", s.model) };
    let plain = bsdf::MayaGlossy::new(Shape::Phong { power: 1.0 }, Vec3A::ZERO);
    let shares: Vec<f32> = (0..foci.len())
        .map(|i| if i + 1 < foci.len() { 0.5f32.powi(i as i32 + 1) } else { 0.5f32.powi(i as i32) })
        .collect();
    let alone: Vec<bsdf::MayaGlossy> = (0..foci.len())
        .map(|i| plain.with_translucence(Vec3A::from_array(COLORS[i]) * T * shares[i], focus_exponent(foci[i])))
        .collect();
    let directions: Vec<Vec3A> = (0..24)
        .map(|k| {
            let z = 1.0 - 2.0 * (k as f32 + 0.5) / 24.0;
            let phi = 2.4 * k as f32;
            let r = (1.0 - z * z).sqrt();
            Vec3A::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect();
    for &wo in &directions {
        let stack = g.bsdf(Vec3A::ZERO, wo);
        for &wi in &directions {
            let want = alone.iter().fold(Vec3A::ZERO, |sum, l| sum + l.bsdf(Vec3A::ZERO, wo).eval_translucence(wo, wi));
            let got = stack.eval_translucence(wo, wi);
            assert!((got - want).abs().max_element() < 1e-5, "{wo} {wi}: {got} vs {want}");
        }
    }
}

/// The transparency ramp of [`view_stack`]'s top layer: 0.9 at facing ratio 0 to 0.2 at
/// 0.75 (24/32: its knots lie on the path engine's table points), linear, 0.2 after.
fn view_ramp() -> maya::utility::Ramp {
    maya::utility::Ramp::new(vec![(0.0, Vec3A::splat(0.9), 1), (0.75, Vec3A::splat(0.2), 1)], Vec3A::ZERO)
}

/// The rampShader layer's colour and translucence, the lambert layer's.
const RAMP_LAYER: ([f32; 3], f32) = ([0.7, 0.5, 0.2], 0.6);
const LAMBERT_LAYER: ([f32; 3], f32) = ([0.2, 0.4, 0.9], 0.5);

/// A layeredShader whose top layer follows the view: a rampShader (light-angle input,
/// constant colour, `translucence` 0.6, transparency ramp [`view_ramp`]) over an opaque
/// lambert of `translucenceFocus` `focus`.
fn view_stack(focus: f32) -> Compiled {
    let ([r, g, b], ta) = RAMP_LAYER;
    let ([r2, g2, b2], tb) = LAMBERT_LAYER;
    let body = format!(
        "shader \"a\" \"maya_rampshader\" (\"colorInput\" 0, \"diffuse\" 0.8, \"translucence\" {ta},\n\
         \"color\" [ {{ \"color_Position\" 0, \"color_Color\" {r} {g} {b}, \"color_Interp\" 1 }} ],\n\
         \"transparency\" [ {{ \"transparency_Position\" 0, \"transparency_Color\" 0.9 0.9 0.9, \"transparency_Interp\" 1 }},\n\
         {{ \"transparency_Position\" 0.75, \"transparency_Color\" 0.2 0.2 0.2, \"transparency_Interp\" 1 }} ])\n\
         shader \"b\" \"maya_lambert\" (\"color\" {r2} {g2} {b2}, \"diffuse\" 0.8, \"translucence\" {tb}, \
         \"translucenceFocus\" {focus})\n\
         shader \"mat\" \"maya_layeredshader\" (\"inputs\" [ {{ \"color\" = \"a.outColor\", \"transparency\" = \"a.outTransparency\" }},\n\
         {{ \"color\" = \"b.outColor\", \"transparency\" = \"b.outTransparency\" }} ])\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"mat.outColor\") end material\n"
    );
    let c = compile("", &format!("{LIBS}{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

/// The classic stack's shares of its two layers at facing ratio `f`: what
/// `maya::layered_shader::composite_layers` (compositing as textures, colour 1 for the
/// layer asked, 0 for the other) gives, the top layer's transparency the classic ramp's
/// at f, the bottom one opaque.
fn classic_shares(f: f32) -> [Vec3A; 2] {
    use maya::layered_shader::{composite_layers, ShaderLayer};
    let t = view_ramp().at(f);
    std::array::from_fn(|i| {
        let layer = |k: usize, transparency: Vec3A| ShaderLayer {
            color: if k == i { Vec3A::ONE } else { Vec3A::ZERO },
            transparency,
            includes_behind: false,
        };
        composite_layers(&[layer(0, t), layer(1, Vec3A::ZERO)], true, Vec3A::ZERO).0
    })
}

/// A layeredShader whose rampShader layer's transparency follows the view weights its
/// layers' translucence lobes by their shares at each hit's facing ratio f
/// (`material::maya::StackTranslucence`, applied by `ViewTransparency::apply`), as the
/// classic stack composites them at that ray. [`view_stack`] at f = 0.3, 0.55, 0.8 and 1:
/// the hit's two lobes (held by the material, read at f) are w_a(f) · A_a (focus 0, the
/// rampShader's light-angle shape, A_a = 2 · t_a · c_a for its constant ramp) and
/// w_b(f) · c_b · t_b (the lambert layer's focus 0.5, exponent 2, or 0), w the classic
/// composite's shares at f, within 1e-5; with focus 0 their A ⊙ S(u) sum to
/// w_a · t_a · c_a + w_b · c_b · t_b · u within 1e-5 at u = 0.1 … 1. Before, the lobes kept
/// the shares at f = 1 (w_a = 0.8): at f = 0.3, w_a = 0.38.
#[test]
fn a_view_following_stack_weights_its_translucence_at_the_hits_facing_ratio() {
    let (ca, ta) = (Vec3A::from_array(RAMP_LAYER.0), RAMP_LAYER.1);
    let (cb, tb) = (Vec3A::from_array(LAMBERT_LAYER.0), LAMBERT_LAYER.1);
    for focus in [0.5f32, 0.0] {
        let c = view_stack(focus);
        let (s, warnings) =
            material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine");
        assert!(warnings.is_empty(), "{warnings:?}");
        let view = s.view_transparency.as_deref().expect("a stack that follows the view");
        for f in [0.3f32, 0.55, 0.8, 1.0] {
            let mut hit = s.constant();
            view.apply(f, &mut hit);
            let SurfaceModel::Maya(g) = &*hit.model else { panic!("a Maya model: {:?}", hit.model) };
            let [wa, wb] = classic_shares(f);
            let got = g.translucence_parts();
            assert_eq!(got.len(), 2, "f {f}: {got:?}");
            let want = [(wa * ca * ta * 2.0, 0.0), (wb * cb * tb, focus_exponent(focus))];
            for (l, (wa, wn)) in got.iter().zip(want) {
                assert!(
                    (l.albedo - wa).abs().max_element() < 1e-5 && (l.exponent - wn).abs() < 1e-6,
                    "f {f}: {l:?} vs {wa} {wn}"
                );
            }
            let shape = got[0].light_angle.expect("the rampShader layer's light-angle shape");
            if focus <= 0.0 {
                for u in [0.1f32, 0.25, 0.5, 0.75, 1.0] {
                    let a = got[0].albedo * shape.factor(u) * u + got[1].albedo * u;
                    let want = wa * ca * ta + wb * cb * tb * u;
                    assert!((a - want).abs().max_element() < 1e-5, "f {f}, u {u}: {a} vs {want}");
                }
            }
        }
    }
}
