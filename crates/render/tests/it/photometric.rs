//! Photometric point lights over a Lambert plane in both engines: the irradiance at each
//! pixel is E = I(θ, φ) · cos θ / r², I the IES profile's intensity towards the pixel's
//! point (light-local direction; the profile's nadir is the light's local −Z).

use crate::support;

use glam::Vec3A;
use render::{EngineKind, Settings};
use shader::light::ies::Profile;

const RES: usize = 16;
/// Height of the light above the plane.
const H: f32 = 2.0;
/// A quadrant-symmetric type C profile, lower hemisphere: brighter along local ±X
/// (horizontal 0°) than along ±Y (90°), peak 1000 cd at the nadir.
const IES: &str = "IESNA:LM-63-2002\n[TEST] mira photometric test\nTILT=NONE\n\
    1 -1 1 4 2 1 2 0 0 0\n1 1 10\n0 30 60 90\n0 90\n1000 900 500 100\n1000 600 200 0\n";

/// An orthographic camera looking down −Z at a 4×4 view of the plane z = −5; the light
/// stands `H` above the plane's centre.
fn scene(light: &str, file: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 samples 0 2 end options
camera "cam" focal infinity aperture 4 aspect 1 resolution {RES} {RES} end camera
instance "cam_inst" "cam" end instance
lightprofile "lamp" format ies file "{file}" end lightprofile
light "L" {light} origin 0 0 {z} end light
instance "L_inst" "L" end instance
material "plane_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1, "mode" 2) end material
object "plane" group
    -4 -4 -5  4 -4 -5  4 4 -5  -4 4 -5
    v 0 v 1 v 2 v 3
    c "plane_mtl" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "plane_inst" "L_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        z = -5.0 + H
    )
}

fn render(text: &str, engine: EngineKind) -> Vec<[f32; 4]> {
    let support::Compiled { scene, shading, messages, read } = support::compile(text);
    assert!(read == 0);
    let lights: Vec<&String> = messages.iter().filter(|m| m.contains("profile")).collect();
    assert!(lights.is_empty(), "{lights:?}");
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let settings = Settings { engine, spp: Some(16), ..Settings::default() };
    support::render_world(&world, &shading, &settings).0.rgba()
}

/// The irradiance a pixel's footprint receives on average (8×8 points), for intensity
/// `i` (light-local direction → candela).
fn expected(i: &dyn Fn(Vec3A) -> f32, px: usize, py: usize) -> f32 {
    let n = 8;
    let mut sum = 0.0;
    for a in 0..n {
        for b in 0..n {
            let x = (px as f32 + (a as f32 + 0.5) / n as f32) / RES as f32 * 4.0 - 2.0;
            let y = 2.0 - (py as f32 + (b as f32 + 0.5) / n as f32) / RES as f32 * 4.0;
            let d = Vec3A::new(x, y, -H);
            let r = d.length();
            sum += i(d) * (H / r) / (r * r);
        }
    }
    sum / (n * n) as f32
}

fn check(px: &[[f32; 4]], i: &dyn Fn(Vec3A) -> f32, k: f32, what: &str) {
    let mut worst = 0.0f32;
    for (j, row) in px.chunks(RES).enumerate() {
        for (x, p) in row.iter().enumerate() {
            let want = k * expected(i, x, j);
            worst = worst.max((p[0] - want).abs() / want.max(1e-3));
        }
    }
    eprintln!("{what}: worst relative error {worst}");
    assert!(worst < 0.01, "{what}: worst relative error {worst}");
}

#[test]
fn ies_point_lights_give_i_cos_over_r_squared() {
    let dir = std::env::temp_dir().join(format!("mira_photometric_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("lamp.ies");
    std::fs::write(&file, IES).unwrap();
    let profile = Profile::parse(IES, false).unwrap().0;
    let file = file.display().to_string();
    let candela = |d: Vec3A| profile.candela(d);
    // The profile is not symmetric under swapping X and Y: a turned frame would show.
    assert!(candela(Vec3A::new(1.0, 0.0, -1.0)) > 1.2 * candela(Vec3A::new(0.0, 1.0, -1.0)));

    // MDL light_ies (path engine): the measured candela × intensity; Lambert ρ/π.
    let mdl = r#""mdl::nvidia::core_definitions::light_ies" ("profile" "lamp", "intensity" 2)"#;
    let px = render(&scene(mdl, &file), EngineKind::Path);
    check(&px, &|d| 2.0 * candela(d), 0.5 / std::f32::consts::PI, "light_ies, path");

    // mia_photometric_light with the profile's intensity, both engines (the classic
    // Lambert shader returns ρ · E).
    let mia = r#""mia_photometric_light" ("intensity_mode" 2, "distribution_mode" 2, "profile" "lamp")"#;
    let px = render(&scene(mia, &file), EngineKind::Path);
    check(&px, &candela, 0.5 / std::f32::consts::PI, "mia_photometric_light, path");
    let px = render(&scene(mia, &file), EngineKind::Classic);
    check(&px, &candela, 0.5, "mia_photometric_light, classic");

    // mib_light_photometric: colour × profile / peak, falling off with the light's exponent.
    let mib = r#""mib_light_photometric" ("color" 500 500 500, "profile" "lamp") exponent 2"#;
    let norm = |d: Vec3A| 500.0 * profile.normalized(d);
    let px = render(&scene(mib, &file), EngineKind::Classic);
    check(&px, &norm, 0.5, "mib_light_photometric, classic");
    let px = render(&scene(mib, &file), EngineKind::Path);
    check(&px, &norm, 0.5 / std::f32::consts::PI, "mib_light_photometric, path");
    let _ = std::fs::remove_dir_all(&dir);
}
