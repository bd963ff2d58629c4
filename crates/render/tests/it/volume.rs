//! Volume shaders in the classic engine: the camera's volume (`mib_volume` fog,
//! `parti_volume` extinction and single scattering) on eye rays, and a material's volume on
//! the rays travelling inside its object only. Expected values are worked out from the
//! shaders' formulas; the single-scattering one by quadrature of the single-scatter
//! integral.

use crate::support;

use render::{EngineKind, Settings};

/// Pixels across (and down).
const RES: usize = 8;
/// The plane's colour: `mib_illum_lambert` with ambient only.
const PLANE: [f32; 3] = [0.8, 0.5, 0.3];
/// Distance from the camera to the plane.
const DEPTH: f32 = 5.0;

/// An orthographic camera at the origin looking down −Z at a 2×2 view with `camera`
/// statements added; a plane of colour [`PLANE`] at z = −5; `body` adds shaders,
/// materials, lights and objects, `extra` names instances to render.
fn scene(camera: &str, body: &str, extra: &[&str]) -> String {
    let instances: String = extra.iter().map(|n| format!(" \"{n}\"")).collect();
    let [r, g, b] = PLANE;
    format!(
        r#"
options "opt" filter box 1 1 samples 0 2 end options
{body}
camera "cam" focal infinity aperture 2 aspect 1 resolution {RES} {RES} {camera} end camera
instance "cam_inst" "cam" end instance
material "plane_mtl" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" {r} {g} {b} 1, "diffuse" 0 0 0) end material
object "plane" group
    -4 -4 -{DEPTH}  4 -4 -{DEPTH}  4 4 -{DEPTH}  -4 4 -{DEPTH}
    v 0 v 1 v 2 v 3
    c "plane_mtl" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "plane_inst"{instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

fn render(text: &str) -> Vec<[f32; 4]> {
    let support::Compiled { scene, shading, messages, .. } = support::compile(text);
    assert!(messages.is_empty(), "{messages:?}");
    let world = render::World::from_scene(&scene);
    let settings = Settings { engine: EngineKind::Classic, spp: Some(4), ..Settings::default() };
    support::render_world(&world, &shading, &settings).0.rgba()
}

fn pixel(px: &[[f32; 4]], x: usize, y: usize) -> [f32; 4] {
    px[y * RES + x]
}

fn assert_rgb(got: [f32; 4], want: [f32; 3], tol: f32, what: &str) {
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() <= tol, "{what}: got {got:?}, want {want:?}");
    }
}

#[test]
fn mib_volume_fog_blends_by_distance_over_max() {
    let body = r#"shader "fog" "mib_volume" ("color" 0.2 0.4 0.6 1, "max" 20, "lightrays" off)"#;
    let px = render(&scene(r#"volume = "fog""#, body, &[]));
    // f = 5 / 20: result = plane (1 − f) + fog f, alpha 1.
    let f = DEPTH / 20.0;
    let fog = [0.2, 0.4, 0.6];
    let want: [f32; 3] = std::array::from_fn(|k| PLANE[k] * (1.0 - f) + fog[k] * f);
    for (i, p) in px.iter().enumerate() {
        assert_rgb(*p, want, 1e-5, &format!("pixel {i}"));
        assert!((p[3] - 1.0).abs() < 1e-5);
    }
    // Beyond max the fog is solid; a fog colour with alpha ½ lets half through.
    let body = r#"shader "fog" "mib_volume" ("color" 0.1 0.2 0.3 0.5, "max" 2)"#;
    let px = render(&scene(r#"volume = "fog""#, body, &[]));
    let want: [f32; 3] = std::array::from_fn(|k| PLANE[k] * 0.5 + [0.1, 0.2, 0.3][k]);
    assert_rgb(pixel(&px, 3, 3), want, 1e-5, "solid fog of opacity ½");
}

#[test]
fn mib_ray_marcher_adds_the_mean_of_its_shader_along_the_ray() {
    // A constant shader (ambient only): its mean along the ray is itself.
    let body = r#"
shader "glow" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 0.1 0.05 0.02 0, "diffuse" 0 0 0)
shader "march" "mib_ray_marcher" ("shader" "glow", "num" 5, "subdiv" 2)
"#;
    let px = render(&scene(r#"volume = "march""#, body, &[]));
    let want = [PLANE[0] + 0.1, PLANE[1] + 0.05, PLANE[2] + 0.02];
    for (i, p) in px.iter().enumerate() {
        assert_rgb(*p, want, 1e-5, &format!("pixel {i}"));
    }
}

#[test]
fn parti_volume_without_scattering_attenuates_by_beer_lambert() {
    let sigma = 0.2f32;
    let body = format!(r#"shader "medium" "parti_volume" ("mode" 0, "scatter" 0 0 0, "extinction" {sigma})"#);
    let px = render(&scene(r#"volume = "medium""#, &body, &[]));
    let t = (-sigma * DEPTH).exp();
    for (i, p) in px.iter().enumerate() {
        assert_rgb(*p, PLANE.map(|c| c * t), 1e-3, &format!("pixel {i}"));
        assert!((p[3] - 1.0).abs() < 1e-5);
    }
    // A layer below y = 0 (mode 1): the lower half of the view sees through 5 units of
    // it, the upper half sees the plane untouched.
    let body = format!(r#"shader "medium" "parti_volume" ("mode" 1, "height" 0, "extinction" {sigma})"#);
    let px = render(&scene(r#"volume = "medium""#, &body, &[]));
    for x in 0..RES {
        assert_rgb(pixel(&px, x, 1), PLANE, 1e-5, "above the layer");
        assert_rgb(pixel(&px, x, RES - 2), PLANE.map(|c| c * t), 1e-3, "in the layer");
    }
}

/// The single-scatter integral along an orthographic eye ray from (x, y, 0) down −Z to the
/// plane: ∫ e^−σt·t σs p(θ) I e^−σt·r dt, r the distance to the light at `light`, p
/// Schlick's phase function of asymmetry `g` normalised to π (isotropic: 1/4), θ between
/// the light's travel and the way back to the camera, by the midpoint rule.
fn single_scatter(x: f32, y: f32, light: [f32; 3], (sigma_t, sigma_s): (f32, f32), g: f32, intensity: f32) -> f32 {
    let n = 20_000;
    let dt = DEPTH / n as f32;
    let mut sum = 0.0f64;
    for i in 0..n {
        let t = (i as f32 + 0.5) * dt;
        let (dx, dy, dz) = (light[0] - x, light[1] - y, light[2] + t);
        let r = (dx * dx + dy * dy + dz * dz).sqrt();
        // cos θ = (towards the light) · (the eye ray's direction −Z).
        let cos = -dz / r;
        let p = (1.0 - g * g) / (4.0 * (1.0 - g * cos).powi(2));
        sum += f64::from((-sigma_t * t).exp() * sigma_s * p * intensity * (-sigma_t * r).exp() * dt);
    }
    sum as f32
}

#[test]
fn parti_volume_single_scattering_matches_the_integral() {
    // Isotropic, then forward scattering (g 0.6) with the lamp beyond the plane's middle.
    for (g, light) in [(0.0f32, [0.0f32, 1.5, -2.5]), (0.6, [0.5, -1.0, -4.0])] {
        let worst = single_scattering_error(g, light);
        eprintln!("single scattering, g {g}: worst relative error {worst:.4}");
        assert!(worst < 0.01, "g {g}: {worst}");
    }
}

/// The worst relative error of five pixels' single scattering in a thin medium (σt = σs =
/// 0.1, optical depth 0.5 to the plane) lit by a point light at `light`, phase asymmetry
/// `g` in the second lobe (weight 1 − r = ½; the first lobe isotropic).
fn single_scattering_error(g: f32, light: [f32; 3]) -> f32 {
    let sigma = 0.1f32;
    let body = format!(
        r#"
light "lamp" "mib_light_point" ("color" 2 2 2, "shadow" on) origin {} {} {} end light
instance "lamp_inst" "lamp" end instance
shader "medium" "parti_volume" ("mode" 0, "scatter" {sigma} {sigma} {sigma}, "extinction" {sigma},
    "r" 0.5, "g1" 0, "g2" {g}, "max_step_len" 0.05)
material "black" "mib_illum_lambert" ("ambience" 0 0 0, "diffuse" 0 0 0) end material
"#,
        light[0], light[1], light[2]
    );
    let text = scene(r#"volume = "medium""#, &body, &["lamp_inst"])
        .replace(r#"c "plane_mtl" 0 1 2 3"#, r#"c "black" 0 1 2 3"#);
    let px = render(&text);
    let mut worst = 0.0f32;
    for (x, y) in [(0usize, 0usize), (3, 3), (4, 1), (7, 7), (2, 6)] {
        // The pixel's mean over 4×4 points of its footprint.
        let mut want = 0.0;
        for a in 0..4 {
            for b in 0..4 {
                let wx = (x as f32 + (a as f32 + 0.5) / 4.0) / RES as f32 * 2.0 - 1.0;
                let wy = 1.0 - (y as f32 + (b as f32 + 0.5) / 4.0) / RES as f32 * 2.0;
                let iso = single_scatter(wx, wy, light, (sigma, sigma), 0.0, 2.0);
                let lobe = single_scatter(wx, wy, light, (sigma, sigma), g, 2.0);
                want += 0.5 * (iso + lobe) / 16.0;
            }
        }
        let got = pixel(&px, x, y)[0];
        assert!(want > 0.01, "the test lights the medium: {want}");
        worst = worst.max((got - want).abs() / want);
    }
    worst
}

#[test]
fn a_material_volume_acts_only_inside_its_object() {
    // A clear box (straight-through transparency) from z = −2 to −4 over x < 0, filled with
    // an absorbing medium; the plane behind it is seen through 2 units of it.
    let sigma = 0.3f32;
    let body = format!(
        r#"
shader "inside" "parti_volume" ("mode" 0, "extinction" {sigma})
material "clear" "mib_transparency" ("input" 0 0 0 0, "transp" 1 1 1 1)
    volume = "inside"
end material
object "box" group
    -3 -3 -2  0 -3 -2  0 3 -2  -3 3 -2
    -3 -3 -4  0 -3 -4  0 3 -4  -3 3 -4
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    c "clear" 0 1 2 3
    c "clear" 7 6 5 4
    c "clear" 0 4 5 1
    c "clear" 1 5 6 2
    c "clear" 2 6 7 3
    c "clear" 3 7 4 0
end group end object
instance "box_inst" "box" end instance
"#
    );
    let px = render(&scene("", &body, &["box_inst"]));
    let t = (-sigma * 2.0).exp();
    for y in 0..RES {
        for x in [0, 1, 2] {
            assert_rgb(pixel(&px, x, y), PLANE.map(|c| c * t), 1e-3, &format!("through the box ({x}, {y})"));
        }
        for x in [5, 6, 7] {
            assert_rgb(pixel(&px, x, y), PLANE, 1e-5, &format!("beside the box ({x}, {y})"));
        }
    }
}
