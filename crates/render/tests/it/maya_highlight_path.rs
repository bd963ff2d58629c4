//! Maya's blinn, phong and phongE highlights in the path engine against the classic
//! engine and against the formula: the path engine's BSDF is Maya's own highlight
//! (`bsdf::maya_highlight`), so under a point or a directional light both engines give
//! the classic c·d·I·cos θ + s·I·H(n, v, l) at every pixel.

use crate::support;
use crate::support::maya_view::{ground_points, mean, pixels, EYE};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 32;

/// A Maya light: the `.mi` light and what the formula needs.
#[derive(Clone, Copy)]
enum Light {
    /// A point light at (x, y, 0) of intensity `i`, no decay.
    Point { x: f32, y: f32, i: f32 },
    /// A directional light shining along (dx, dy, 0) (normalised) of intensity `i`.
    Directional { dx: f32, dy: f32, i: f32 },
}

impl Light {
    fn mi(self) -> String {
        match self {
            Light::Point { x, y, i } => {
                format!(r#"light "l" "maya_pointlight" ("intensity" {i}, "decayRate" 0) origin {x} {y} 0 end light"#)
            }
            Light::Directional { dx, dy, i } => {
                let d = Vec3A::new(dx, dy, 0.0).normalize();
                format!(r#"light "l" "maya_directionallight" ("intensity" {i}) direction {} {} 0 end light"#, d.x, d.y)
            }
        }
    }

    /// The unit direction towards the light from the ground point `p` and its intensity.
    fn towards(self, p: Vec3A) -> (Vec3A, f32) {
        match self {
            Light::Point { x, y, i } => ((Vec3A::new(x, y, 0.0) - p).normalize(), i),
            Light::Directional { dx, dy, i } => (-Vec3A::new(dx, dy, 0.0).normalize(), i),
        }
    }
}

/// The diffuse colour c·d of every ground (colour 0.6 0.5 0.4, diffuse 0.8).
const ALBEDO: Vec3A = Vec3A::new(0.48, 0.4, 0.32);

type Highlight = fn(Vec3A, Vec3A) -> Vec3A;

/// The three materials: their name, shader text and tinted highlight s ⊙ H(v, l).
fn materials() -> [(&'static str, &'static str, Highlight); 3] {
    [
        (
            "blinn",
            r#"shader "mat" "maya_blinn" ("color" 0.6 0.5 0.4, "diffuse" 0.8, "eccentricity" 0.3,
    "specularRollOff" 0.7, "specularColor" 0.5 0.5 0.5, "reflectivity" 0)"#,
            |v, l| Vec3A::splat(0.5 * maya::specular::blinn(Vec3A::Y, v, l, 0.3, 0.7)),
        ),
        (
            "phong",
            r#"shader "mat" "maya_phong" ("color" 0.6 0.5 0.4, "diffuse" 0.8, "cosinePower" 20,
    "specularColor" 0.6 0.5 0.4, "reflectivity" 0)"#,
            |v, l| Vec3A::new(0.6, 0.5, 0.4) * maya::specular::phong(Vec3A::Y, v, l, 20.0),
        ),
        (
            "phongE",
            r#"shader "mat" "maya_phongE" ("color" 0.6 0.5 0.4, "diffuse" 0.8, "roughness" 0.5,
    "highlightSize" 0.5, "whiteness" 0.9 0.8 0.7, "specularColor" 0.5 0.5 0.5, "reflectivity" 0)"#,
            |v, l| Vec3A::new(0.45, 0.4, 0.35) * maya::specular::phong_e(Vec3A::Y, v, l, 0.5, 0.5),
        ),
    ]
}

/// The ground lit by `light`, shaded by `material`, seen from above.
fn scene(material: &str, light: Light) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
{}
instance "l_inst" "l" end instance
{material}
material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "l_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        light.mi()
    )
}

/// The classic formula c·d·I·cos θ + s ⊙ I·H(n, v, l) averaged over the ground under
/// pixel column `col` and row `row` (16 × 16 points). The lights lie in the plane z = 0,
/// so the image is the same flipped top to bottom and the rows' direction does not matter.
fn formula(col: usize, row: usize, light: Light, highlight: Highlight) -> Vec3A {
    const SUB: usize = 16;
    let mut sum = Vec3A::ZERO;
    for p in ground_points(SIDE, col, row, SUB) {
        let v = (EYE - p).normalize();
        let (l, i) = light.towards(p);
        sum += (ALBEDO * l.y.max(0.0) + highlight(v, l)) * i;
    }
    sum / (SUB * SUB) as f32
}

/// Blinn (eccentricity 0.3), phong (cosine power 20) and phongE (roughness 0.5, tinted
/// by its whiteness) grounds under a point light 2 above and a directional light 14.5° off
/// the vertical: the path engine's image mean equals the classic engine's within 2 % per
/// channel (measured: within 0.03 %), the brightest pixel of each equals the formula
/// averaged over the pixel within 2 % (measured: 0.05 %; its highlight more than a quarter of it), and the
/// path engine's highlight is no longer the GGX lobe's (about 6× weaker than the
/// classic one): the image mean with the highlight is more than 3 % above the diffuse
/// part alone.
#[test]
fn maya_highlights_agree_in_both_engines_and_with_the_formula() {
    let lights = [Light::Point { x: 0.6, y: 2.0, i: 1.5 }, Light::Directional { dx: 0.25, dy: -0.968, i: 1.2 }];
    for (name, text, highlight) in materials() {
        for light in lights {
            let scene = scene(text, light);
            let classic = pixels(&scene, EngineKind::Classic, 4);
            let path = pixels(&scene, EngineKind::Path, 16);
            let (mc, mp) = (mean(&classic), mean(&path));
            // The diffuse part alone, by the formula.
            let mut diffuse = Vec3A::ZERO;
            let mut shaded = Vec3A::ZERO;
            for row in 0..SIDE {
                for col in 0..SIDE {
                    diffuse += formula(col, row, light, |_, _| Vec3A::ZERO);
                    shaded += formula(col, row, light, highlight);
                }
            }
            let n = (SIDE * SIDE) as f32;
            let (diffuse, shaded) = (diffuse / n, shaded / n);
            println!("{name}: classic {mc}, path {mp}, formula {shaded}, diffuse alone {diffuse}");
            for k in 0..3 {
                assert!((mp[k] / mc[k] - 1.0).abs() < 0.02, "{name}: path {mp} vs classic {mc}");
                assert!((mc[k] / shaded[k] - 1.0).abs() < 0.02, "{name}: classic {mc} vs formula {shaded}");
                assert!(mp[k] > 1.03 * diffuse[k], "{name}: the highlight shows: {mp} vs {diffuse}");
            }
            // The brightest pixel of the path engine's image against the formula there.
            let peak = (0..path.len()).max_by(|&a, &b| path[a].x.total_cmp(&path[b].x)).expect("pixels");
            let (row, col) = (peak / SIDE, peak % SIDE);
            let want = formula(col, row, light, highlight);
            let got = path[peak];
            let lit = formula(col, row, light, |_, _| Vec3A::ZERO);
            println!("{name}: peak at column {col} row {row}: path {got}, formula {want} (diffuse {lit})");
            assert!(want.x > 1.25 * lit.x, "{name}: the peak pixel is a highlight: {want} vs {lit}");
            for k in 0..3 {
                assert!((got[k] / want[k] - 1.0).abs() < 0.02, "{name}: peak {got} vs formula {want}");
            }
        }
    }
}

/// A ground that only reflects (`color` 0; phongE of `highlightSize` 0, or a blinn of
/// eccentricity 0.01 whose highlight is negligible) under a uniform environment E, no
/// lights: the classic material traces one mirror ray, r·s ⊙ E (× Schlick's factor of
/// `specularRollOff` at N·V with `reflectionRolloff`), and the path engine's mirror lobe
/// of weight r·s gives the same. PhongE: every pixel r·s ⊙ E within 1e-4 in both
/// engines; blinn with the roll-off: the image means agree within 0.5 % (measured
/// 0.08 %) and lie below r·s ⊙ E by the roll-off.
#[test]
fn the_mirror_reflection_of_reflectivity_agrees_in_both_engines() {
    let env = Vec3A::new(0.8, 0.7, 0.6);
    let view = support::maya_view::top_down(SIDE).replace("end camera", r#"environment = "sky" end camera"#);
    let scene = |material: &str| {
        format!(
            r#"
$include "mayabase.mi"
shader "sky" "mib_color_mix" ("num" 0, "color_base" {} {} {} 1)
{view}
{material}
material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
            env.x, env.y, env.z
        )
    };
    let phong_e = scene(
        r#"shader "mat" "maya_phongE" ("color" 0 0 0, "highlightSize" 0, "specularColor" 0.6 0.5 0.4,
    "reflectivity" 0.5)"#,
    );
    let want = Vec3A::new(0.6, 0.5, 0.4) * 0.5 * env;
    for engine in [EngineKind::Classic, EngineKind::Path] {
        for got in pixels(&phong_e, engine, 4) {
            assert!((got - want).abs().max_element() < 1e-4, "{engine:?}: {got} vs {want}");
        }
    }
    let blinn = scene(
        r#"shader "mat" "maya_blinn" ("color" 0 0 0, "eccentricity" 0.01, "specularRollOff" 0.3,
    "reflectionRolloff" on, "specularColor" 0.6 0.5 0.4, "reflectivity" 0.5)"#,
    );
    let (classic, path) = (mean(&pixels(&blinn, EngineKind::Classic, 4)), mean(&pixels(&blinn, EngineKind::Path, 16)));
    println!("blinn mirror: classic {classic}, path {path}, without roll-off {want}");
    for k in 0..3 {
        assert!((path[k] / classic[k] - 1.0).abs() < 0.005, "path {path} vs classic {classic}");
        assert!(classic[k] < 0.32 * want[k] && classic[k] > 0.3 * want[k], "the roll-off: {classic} vs {want}");
    }
}
