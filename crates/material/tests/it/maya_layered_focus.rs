//! A layeredShader's translucent layers in the path engine's translation keep their own
//! `translucenceFocus` (`bsdf::MayaGlossy::add_translucence`): each focus a forward lobe
//! of albedo Σ w_i · c_i · t_i over its layers (w_i the layer's share), up to three
//! distinct foci; a fourth is merged into the third's with a warning naming its layer.

use crate::support;

use bsdf::maya_highlight::translucence::focus_exponent;
use glam::Vec3A;
use material::SurfaceModel;
use support::maya::{compile, Compiled};

const LIBS: &str = "$include \"mayabase.mi\"\n";

/// The layers' colours, in order.
const COLORS: [[f32; 3]; 4] = [[0.9, 0.2, 0.1], [0.2, 0.8, 0.3], [0.1, 0.3, 0.9], [0.5, 0.5, 0.5]];

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
    (g.translucence_lobes().filter(|(a, _)| *a != Vec3A::ZERO).collect(), warnings)
}

/// Three layers of foci 0.5, 0 and 0.25 (shares ½, ¼, ¼): three lobes, the focus-0 one
/// first, each of albedo w_i · c_i · t and exponent 2φ/(1 − φ) within 1e-6, no warning.
/// Two layers of one focus (0.5) share a lobe of albedo the sum of theirs. A fourth
/// distinct focus (0.75 under 0.5, 0, 0.25): still three lobes, the fourth layer's albedo
/// added to the last (the total albedo kept within 1e-6), and a warning naming "l3".
/// Before, the stack took the first translucent layer's focus for all (warned).
#[test]
fn each_layers_focus_is_a_lobe_of_its_own_up_to_three() {
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
    assert_eq!(got.len(), 3, "{got:?}");
    assert!(warnings.len() == 1 && warnings[0].contains("'l3'"), "{warnings:?}");
    let total = got.iter().fold(Vec3A::ZERO, |s, (a, _)| s + *a);
    let want = c(0) * 0.5 + c(1) * 0.25 + c(2) * 0.125 + c(3) * 0.125;
    assert!((total - want).abs().max_element() < 1e-6, "{total} vs {want}");
}
