//! Object area lights over displaced geometry (`crate::displace::emitters`): the light's
//! triangles are the displaced ones in both engines, against the closed-form irradiance
//! of a Lambertian rectangle.

use bsdf::Rgb;
use glam::Vec2;
use render::light::{Output, Shape};
use render::{EngineKind, Settings};

use crate::displacement::build;
use crate::support;

/// A 4 × 4 plane at z = −5 (lambert, diffuse 0.5) seen straight down through a 0.02-wide
/// orthographic view at its centre, and a 1 × 1 lamp facing it, x ∈ [0.5, 1.5],
/// y ∈ [−0.5, 0.5], one unit above it (z = −4), invisible to every ray, whose material
/// "lamp_mtl" displaces it by `d` along its normal (−z: towards the plane); the object
/// light "L" takes its triangles.
fn lamp_scene(d: f32) -> String {
    format!(
        r#"
options "opt" filter box 1 1 samples 0 2 end options
camera "cam" focal infinity aperture 0.02 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" end instance
light "L" "mib_light_point" ("color" 1 1 1, "shadow" on) origin 1 0 -4 object "lamp_inst" 4 4 end light
instance "L_inst" "L" end instance
material "plane_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1, "mode" 3) end material
shader "disp" "maya_material_displace" ("displacement" {d})
material "lamp_mtl" "mib_illum_lambert" ("diffuse" 0 0 0 1) displace = "disp" end material
object "lamp" group
    0.5 -0.5 -4  1.5 -0.5 -4  1.5 0.5 -4  0.5 0.5 -4
    v 0 v 1 v 2 v 3
    c "lamp_mtl" 0 3 2 1
end group end object
instance "lamp_inst" "lamp" visible off shadow off trace off end instance
object "plane" group
    -2 -2 -5  2 -2 -5  2 2 -5  -2 2 -5
    v 0 v 1 v 2 v 3
    c "plane_mtl" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "plane_inst" "L_inst" "lamp_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Form factor from a point to the rectangle [0, a] × [0, b] parallel to it at height h
/// with a corner straight above it (the classic closed form).
fn corner(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
}

/// Form factor from the origin of the plane to the lamp [0.5, 1.5] × [−0.5, 0.5] at
/// height h (corners added and taken away).
fn lamp_form_factor(h: f64) -> f64 {
    2.0 * (corner(1.5, 0.5, h) - corner(0.5, 0.5, h))
}

/// The mean over the lamp (x ∈ [0.5, 1.5], y ∈ [−0.5, 0.5], height h) of the cosine at
/// the origin, h / r: what mental ray's non-attenuating point light spread over it gives
/// (400 × 400 midpoint rule, error ≪ 1e-4).
fn mean_cosine(h: f64) -> f64 {
    let n = 400;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = 0.5 + (i as f64 + 0.5) / n as f64;
            let y = -0.5 + (j as f64 + 0.5) / n as f64;
            sum += h / (x * x + y * y + h * h).sqrt();
        }
    }
    sum / (n * n) as f64
}

/// The displaced lamp is the light's shape in both engines: its triangles lie at
/// z = −4 − d (1e-5) with area 1 in the path engine's light and the classic engine's,
/// for d = 0 and d = 0.5 (towards the plane, which makes the lamp more oblique from the
/// plane's centre). Made physical (radiance 1, one-sided), the path engine's plane below
/// it shows ρ·F(h) (ρ = 0.5, F the lamp's form factor at height h: 0.0349 at h = 0.5,
/// 0.0422 at h = 1), within 2 %. The classic engine's lambert under the non-attenuating
/// `mib_light_point` spread over the lamp shows 0.5 × the mean of h/r over the lamp
/// (0.2254 at h = 0.5, 0.3492 at h = 1), within 2 %.
#[test]
fn an_object_light_emits_from_its_displaced_triangles() {
    for (d, h) in [(0.0f32, 1.0f64), (0.5, 0.5)] {
        let mut b = build(&lamp_scene(d));
        assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("warning")), "{:?}", b.messages);
        let z = -4.0 - d;
        let Shape::Mesh(path_mesh) = &b.built.world.lights[0].shape else { panic!("not a mesh light") };
        let Some(Shape::Mesh(classic_mesh)) = &b.built.shading.lights[0].shape else { panic!("not a mesh light") };
        for m in [path_mesh, classic_mesh] {
            assert!((m.area() - 1.0).abs() < 1e-5, "{}", m.area());
            for u in [Vec2::new(0.1, 0.2), Vec2::new(0.7, 0.9), Vec2::new(0.5, 0.4)] {
                let (p, n) = m.point_on(u);
                assert!((p.z - z).abs() < 1e-5 && n.z < -0.99, "d = {d}: {p} {n}");
            }
        }
        let settings = Settings { engine: EngineKind::Classic, spp: Some(16), ..Settings::default() };
        let px = support::render_world(&b.built.world, &b.built.shading, &settings).0.rgba();
        let classic = f64::from(support::mean(&px, 4, (0, 4), (0, 4))[0]);
        let want = 0.5 * mean_cosine(h);
        eprintln!("classic, d = {d}: {classic} vs {want}");
        assert!((classic / want - 1.0).abs() < 0.02, "classic, d = {d}: {classic} vs {want}");

        let light = &mut b.built.world.lights[0];
        light.output = Output::Radiance { l: Rgb::splat(1.0), two_sided: false };
        light.visible = true;
        let settings = Settings { engine: EngineKind::Path, spp: Some(256), ..Settings::default() };
        let px = support::render_world(&b.built.world, &b.built.shading, &settings).0.rgba();
        let path = f64::from(support::mean(&px, 4, (0, 4), (0, 4))[0]);
        let want = 0.5 * lamp_form_factor(h);
        eprintln!("path, d = {d}: {path} vs {want}");
        assert!((path / want - 1.0).abs() < 0.02, "path, d = {d}: {path} vs {want}");
    }
}

/// Emission given for the whole surface is spread over the displaced surface: MDL's
/// `add_emission` of 4 candela (radiance = 4 / area) on the 2 × 2 square of
/// `support::lit_square` displaced by a wave of amplitude 0.3 across it (h = 0.3·cos 2πu,
/// `regular parametric 4`), seen head-on by the path engine, shows 4 / A, A the area of
/// the displaced triangles (within 1e-3), which lies within 2 % of the smooth surface's
/// 2·∫ √(1 + (0.3π sin π(x + 1))²) dx over [−1, 1] (≈ 4.8, not the undisplaced 4).
#[test]
fn emission_over_the_whole_surface_spreads_over_the_displaced_area() {
    let body = r#"shader "glow" "mdl::nvidia::core_definitions::add_emission" ("intensity" 4, "unit" "candela")
shader "coord" "mib_texture_vector" ("select" 0, "selspace" 0)
shader "wave" "mib_texture_wave" ("coord" = "coord", "amplitude_x" 0.3, "amplitude_y" 0, "amplitude_z" 0, "offset" 0)
material "m" = "glow" displace = "wave" end material"#;
    let text = support::lit_square(body, "m")
        .replace("object \"square\" group", "object \"square\"\n approximate displace regular parametric 4\n group");
    let b = build(&text);
    assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("warning")), "{:?}", b.messages);
    let world = &b.built.world;
    let mut area = 0.0f64;
    for inst in &world.instances {
        let mesh = &world.meshes[inst.mesh as usize];
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| inst.object_to_world.transform_point3a(mesh.position(i)));
            area += 0.5 * f64::from((b - a).cross(c - a).length());
        }
    }
    let n = 20000;
    let smooth: f64 = (0..n)
        .map(|k| {
            let x = -1.0 + 2.0 * (k as f64 + 0.5) / n as f64;
            let slope = 0.3 * std::f64::consts::PI * (std::f64::consts::PI * (x + 1.0)).sin();
            2.0 * (1.0 + slope * slope).sqrt() * 2.0 / n as f64
        })
        .sum();
    assert!((area / smooth - 1.0).abs() < 0.02, "mesh {area} vs smooth {smooth}");
    let settings = Settings { engine: EngineKind::Path, spp: Some(1), ..Settings::default() };
    let px = support::render_world(world, &b.built.shading, &settings).0.rgba();
    let want = (4.0 / area) as f32;
    for i in [9, 27, 36, 54] {
        assert!((px[i][0] / want - 1.0).abs() < 1e-3, "pixel {i}: {:?} vs {want} (area {area})", px[i]);
    }
}
