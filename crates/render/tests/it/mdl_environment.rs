//! A module's own MDL function as the scene's environment (camera `environment` or the
//! options' `environment_function`): camera rays and mirrors show the function of the
//! direction in both engines, a Lambert sphere under a constant module environment is a
//! white furnace, and a bright lobe is importance sampled from the table baked from the
//! function.

use crate::environment::{ball, plane_stats};
use crate::support;

use glam::Vec3A;
use render::environment::Environment;
use render::{EngineKind, Settings};

const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::state::*;
import ::math::*;
import ::base::*;

// A colour that is a known function of the direction (see `gradient` in the test).
export base::texture_return gradient_env(float scale = 1.0) {
    float3 d = state::direction();
    return base::texture_return(color(0.5 + 0.5 * d.y, 0.25 * (1.0 + d.y * d.y), 1.0 - 0.5 * d.y) * scale, 1.0);
}
export color constant_env(color value = color(0.5)) {
    return value;
}
// A dim sky with a bright disc of cos 0.99 around `centre`.
export color lobe_env(float3 centre = float3(0.0, 0.0, 1.0)) {
    return math::dot(state::direction(), math::normalize(centre)) > 0.99 ? color(200.2) : color(0.2);
}
export material mirror() = material(surface: material_surface(
    scattering: df::specular_bsdf(tint: color(1.0), mode: df::scatter_reflect)));
export material matte(color tint = color(0.5)) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: tint)));
"#;

/// `gradient_env` along unit direction `d` (× `scale`).
pub(crate) fn gradient(d: Vec3A, scale: f32) -> [f32; 3] {
    [(0.5 + 0.5 * d.y) * scale, 0.25 * (1.0 + d.y * d.y) * scale, (1.0 - 0.5 * d.y) * scale]
}

/// Writes the module into a directory of its own.
pub(crate) fn module_dir(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mira_mdl_env_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("envs.mdl"), MODULE).unwrap();
    dir
}

/// An orthographic camera at the origin looking down −Z at a 2×2 view (`res`² pixels) with
/// `camera` in its block; `body` holds the rest, `extra` names its instances.
pub(crate) fn scene(camera: &str, options: &str, body: &str, extra: &[&str], res: u32) -> String {
    let instances: String = extra.iter().map(|n| format!(" \"{n}\"")).collect();
    format!(
        r#"
options "opt" filter box 1 1 {options} end options
camera "cam" focal infinity aperture 2 aspect 1 resolution {res} {res} {camera} end camera
instance "cam_inst" "cam" end instance
{body}
instgroup "root" "cam_inst"{instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Three mirror strips in pixel columns 1–3 of a 4-pixel-wide view (x from −0.5 to 1),
/// tilted about x by 15°, 30° and 45° so that they reflect the camera's −Z rays into
/// (0, sin 2α, cos 2α); column 0 sees the environment directly.
pub(crate) fn mirrors() -> (String, Vec<&'static str>, [Vec3A; 4]) {
    let mut body =
        String::from("shader \"mirror\" \"mdl::envs::mirror\" ()\nmaterial \"mirror_mtl\" = \"mirror\" end material\n");
    let mut names = Vec::new();
    let mut dirs = [Vec3A::NEG_Z; 4];
    for (k, deg) in [15.0f32, 30.0, 45.0].into_iter().enumerate() {
        let a = deg.to_radians();
        let (x0, x1) = (-0.5 + 0.5 * k as f32, 0.5 * k as f32);
        let z = |y: f32| -5.0 - y * a.tan();
        body += &format!(
            "object \"m{k}\" group\n{x0} -2 {}  {x1} -2 {}  {x1} 2 {}  {x0} 2 {}\nv 0 v 1 v 2 v 3\nc \"mirror_mtl\" 0 1 2 3\nend group end object\ninstance \"m{k}_inst\" \"m{k}\" end instance\n",
            z(-2.0),
            z(-2.0),
            z(2.0),
            z(2.0)
        );
        names.push(["m0_inst", "m1_inst", "m2_inst"][k]);
        dirs[k + 1] = Vec3A::new(0.0, (2.0 * a).sin(), (2.0 * a).cos());
    }
    (body, names, dirs)
}

#[test]
fn camera_rays_and_mirrors_see_the_module_function_in_both_engines() {
    let dir = module_dir("gradient");
    let (body, names, dirs) = mirrors();
    // Declared in the scene (the declaration's node runs it) and undeclared (a node of its
    // own), as the camera's environment and as `environment_function`.
    let declared = "declare shader color \"mdl::envs::gradient_env\" (scalar \"scale\") end declare\n";
    let cases = [
        (
            format!("{declared}shader \"env\" \"mdl::envs::gradient_env\" (\"scale\" 2)\n{body}"),
            "environment = \"env\"",
            "",
            2.0,
        ),
        (
            format!("shader \"env\" \"mdl::envs::gradient_env\" ()\n{body}"),
            "",
            "attribute string \"environment_function\" \"env\"",
            1.0,
        ),
    ];
    for (body, camera, options, scale) in &cases {
        let parsed = mi::parse_str("t.mi", &scene(camera, options, body, &names, 4));
        let built = support::build_parsed(&parsed, 4, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        for engine in [EngineKind::Path, EngineKind::Classic] {
            let settings = Settings { engine, spp: Some(4), ..Settings::default() };
            let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
            for (i, p) in film.rgba().iter().enumerate() {
                let want = gradient(dirs[i % 4], *scale);
                for k in 0..3 {
                    assert!(
                        (p[k] - want[k]).abs() <= 1e-4,
                        "{engine:?} {camera}{options}: pixel {i} {p:?} vs {want:?}"
                    );
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_lambert_sphere_under_a_constant_module_environment_is_a_white_furnace() {
    let dir = module_dir("furnace");
    let body = format!(
        "shader \"env\" \"mdl::envs::constant_env\" (\"value\" 0.8 0.8 0.8)\nshader \"matte\" \"mdl::envs::matte\" (\"tint\" 0.6 0.6 0.6)\nmaterial \"ball_mtl\" = \"matte\" end material\n{}",
        ball(1.0)
    );
    let parsed = mi::parse_str("t.mi", &scene("environment = \"env\"", "", &body, &["ball_inst"], 16));
    let built = support::build_parsed(&parsed, 16, std::slice::from_ref(&dir));
    assert!(built.messages.is_empty(), "{:#?}", built.messages);
    let settings = Settings { engine: EngineKind::Path, spp: Some(64), ..Settings::default() };
    let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
    let (mut inside, mut n) = (0.0, 0);
    for (i, p) in film.rgba().iter().enumerate() {
        let (x, y) = ((i % 16) as f32 / 8.0 - 1.0 + 1.0 / 16.0, (i / 16) as f32 / 8.0 - 1.0 + 1.0 / 16.0);
        let r = (x * x + y * y).sqrt();
        if r > 1.1 {
            assert!((p[0] - 0.8).abs() < 1e-5, "background pixel {i}: {p:?}");
        } else if r < 0.85 {
            // A convex Lambert surface sees only the environment: albedo × L = 0.48.
            assert!((p[0] - 0.48).abs() < 0.03, "sphere pixel {i}: {p:?}");
            inside += p[0];
            n += 1;
        }
    }
    let m = inside / n as f32;
    eprintln!("module white furnace: sphere mean {m} (exact 0.48) over {n} pixels");
    assert!((m - 0.48).abs() < 0.005, "sphere mean {m}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_bright_lobe_of_a_module_environment_is_importance_sampled() {
    // A Lambert plane (albedo 0.5) facing the camera; the lobe 40° from its normal, wholly
    // above its horizon: radiance 0.5/π × (0.2 π + 200 · n·c · π (1 − 0.99²)).
    let dir = module_dir("lobe");
    let c = Vec3A::new(40f32.to_radians().sin(), 0.0, 40f32.to_radians().cos());
    let body = format!(
        r#"shader "env" "mdl::envs::lobe_env" ("centre" {} {} {})
shader "matte" "mdl::envs::matte" ("tint" 0.5 0.5 0.5)
material "plane_mtl" = "matte" end material
object "plane" group
    -50 -50 -5  50 -50 -5  50 50 -5  -50 50 -5
    v 0 v 1 v 2 v 3
    c "plane_mtl" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance"#,
        c.x, c.y, c.z
    );
    let parsed = mi::parse_str("t.mi", &scene("environment = \"env\"", "", &body, &["plane_inst"], 16));
    let built = support::build_parsed(&parsed, 16, std::slice::from_ref(&dir));
    assert!(built.messages.is_empty(), "{:#?}", built.messages);
    let (world, shading) = (&built.built.world, &built.built.shading);
    let accel = render::accel::build(world, render::Backend::default_available());
    let sampled = Environment::of_scene(world, accel.as_ref(), shading).expect("an environment");
    // The evaluation is the function's own, exactly.
    let lit = sampled.radiance(c);
    assert!((lit.x - 200.2).abs() < 1e-3 && (sampled.radiance(-c).x - 0.2).abs() < 1e-6, "{lit:?}");
    let mut cosine = Environment::of_scene(world, accel.as_ref(), shading).expect("an environment");
    cosine.sampled = false;
    let pi = std::f64::consts::PI;
    let exact = 0.5 / pi * (0.2 * pi + 200.0 * f64::from(c.z) * pi * (1.0 - 0.99 * 0.99));
    let (m_imp, v_imp) = plane_stats(world, &sampled, 16, 16);
    let (m_cos, v_cos) = plane_stats(world, &cosine, 16, 16);
    eprintln!(
        "module lobe: exact {exact:.4}; table-sampled {m_imp:.4} (pixel variance {v_imp:.5}), cosine only {m_cos:.4} (variance {v_cos:.5}) at 16 spp"
    );
    assert!((m_imp - exact).abs() < 0.01 * exact, "importance sampled {m_imp} vs {exact}");
    assert!((m_cos - exact).abs() < 5.0 * (v_cos / 256.0).sqrt(), "cosine sampled {m_cos} vs {exact}");
    assert!(v_imp * 10.0 < v_cos, "variance {v_imp} (importance) vs {v_cos} (cosine)");
    std::fs::remove_dir_all(&dir).ok();
}
