//! Module functions as environments written other ways than a named scene environment: an
//! inline call as the camera's `environment` (both engines: the view straight into it and
//! its reflection in mirrors show the function along the direction, within 1e-4), and a
//! material's own `environment` (named or inline; the classic engine's reflections from
//! that material show the material's function, the rest of the view the camera's).

use crate::mdl_environment::{gradient, mirrors, module_dir, scene};
use crate::support;

use glam::Vec3A;
use render::{EngineKind, Settings};

#[test]
fn an_inline_call_as_the_camera_environment_is_the_module_function() {
    let dir = module_dir("inline");
    let (body, names, dirs) = mirrors();
    let declared = "declare shader color \"mdl::envs::gradient_env\" (scalar \"scale\") end declare\n";
    // Undeclared (a node of its own) and declared (the declaration's node runs it).
    for decl in ["", declared] {
        let text =
            scene("environment \"mdl::envs::gradient_env\" (\"scale\" 2)", "", &format!("{decl}{body}"), &names, 4);
        let parsed = mi::parse_str("t.mi", &text);
        let built = support::build_parsed(&parsed, 4, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        for engine in [EngineKind::Path, EngineKind::Classic] {
            let settings = Settings { engine, spp: Some(4), ..Settings::default() };
            let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
            for (i, p) in film.rgba().iter().enumerate() {
                let want = gradient(dirs[i % 4], 2.0);
                for k in 0..3 {
                    assert!((p[k] - want[k]).abs() <= 1e-4, "{engine:?} {decl}: pixel {i} {p:?} vs {want:?}");
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A mental ray mirror (`mib_reflect`, reflect 1) tilted by 30° about x in the right half
/// of a 4 × 4 view: its reflections (along (0, sin 60°, cos 60°)) show its material's own
/// `environment`, `gradient_env` × 3, while the left half shows the camera's constant
/// environment (0.1); named and inline.
#[test]
fn a_material_environment_naming_a_module_function_shows_in_its_reflections() {
    let dir = module_dir("material");
    let a = 30f32.to_radians();
    let reflected = Vec3A::new(0.0, (2.0 * a).sin(), (2.0 * a).cos());
    let z = |y: f32| -5.0 - y * a.tan();
    let mirror = format!(
        "object \"m\" group\n0 -2 {}  2 -2 {}  2 2 {}  0 2 {}\nv 0 v 1 v 2 v 3\nc \"mirror_mtl\" 0 1 2 3\nend group end object\ninstance \"m_inst\" \"m\" end instance\n",
        z(-2.0),
        z(-2.0),
        z(2.0),
        z(2.0)
    );
    let camera_env = "shader \"cam_env\" \"mdl::envs::constant_env\" (\"value\" 0.1 0.1 0.1)\n";
    let cases = [
        "shader \"mtl_env\" \"mdl::envs::gradient_env\" (\"scale\" 3)\nmaterial \"mirror_mtl\" \"mib_reflect\" (\"reflect\" 1 1 1 1) environment = \"mtl_env\" end material\n".to_string(),
        "material \"mirror_mtl\" \"mib_reflect\" (\"reflect\" 1 1 1 1) environment \"mdl::envs::gradient_env\" (\"scale\" 3) end material\n".to_string(),
    ];
    for material in &cases {
        let body = format!("{camera_env}{material}{mirror}");
        let parsed = mi::parse_str("t.mi", &scene("environment = \"cam_env\"", "", &body, &["m_inst"], 4));
        let built = support::build_parsed(&parsed, 4, std::slice::from_ref(&dir));
        // (The path engine renders `mib_reflect` grey, and says so; this is the classic
        // engine's test.)
        let others: Vec<_> = built.messages.iter().filter(|m| !m.contains("'mib_reflect' is not supported")).collect();
        assert!(others.is_empty(), "{others:#?}");
        let settings = Settings { engine: EngineKind::Classic, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        for (i, p) in film.rgba().iter().enumerate() {
            let want = if i % 4 >= 2 { gradient(reflected, 3.0) } else { [0.1; 3] };
            for k in 0..3 {
                assert!((p[k] - want[k]).abs() <= 1e-4, "{material}: pixel {i} {p:?} vs {want:?}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The path engine honours a material's own `environment` as well: a module mirror
/// (`mdl::envs::mirror`) tilted by 30° about x in the right half of a 4 × 4 view reflects
/// its material's environment (`gradient_env` × 3 along (0, sin 60°, cos 60°), named and
/// inline) while the left half shows the camera's (0.1), within 1e-4; the same mirror
/// without an environment of its own reflects the camera's.
#[test]
fn a_material_environment_shows_in_its_reflections_in_the_path_engine() {
    let dir = module_dir("material_path");
    let a = 30f32.to_radians();
    let reflected = Vec3A::new(0.0, (2.0 * a).sin(), (2.0 * a).cos());
    let z = |y: f32| -5.0 - y * a.tan();
    let mirror = format!(
        "object \"m\" group\n0 -2 {}  2 -2 {}  2 2 {}  0 2 {}\nv 0 v 1 v 2 v 3\nc \"mirror_mtl\" 0 1 2 3\nend group end object\ninstance \"m_inst\" \"m\" end instance\n",
        z(-2.0),
        z(-2.0),
        z(2.0),
        z(2.0)
    );
    let head = "shader \"cam_env\" \"mdl::envs::constant_env\" (\"value\" 0.1 0.1 0.1)\nshader \"mirror\" \"mdl::envs::mirror\" ()\n";
    let cases = [
        ("shader \"mtl_env\" \"mdl::envs::gradient_env\" (\"scale\" 3)\nmaterial \"mirror_mtl\" = \"mirror\" environment = \"mtl_env\" end material\n", Some(3.0)),
        ("material \"mirror_mtl\" = \"mirror\" environment \"mdl::envs::gradient_env\" (\"scale\" 3) end material\n", Some(3.0)),
        ("material \"mirror_mtl\" = \"mirror\" end material\n", None),
    ];
    for (material, scale) in cases {
        let body = format!("{head}{material}{mirror}");
        let parsed = mi::parse_str("t.mi", &scene("environment = \"cam_env\"", "", &body, &["m_inst"], 4));
        let built = support::build_parsed(&parsed, 4, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        let settings = Settings { engine: EngineKind::Path, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        for (i, p) in film.rgba().iter().enumerate() {
            let want = match scale {
                Some(s) if i % 4 >= 2 => gradient(reflected, s),
                _ => [0.1; 3],
            };
            for k in 0..3 {
                assert!((p[k] - want[k]).abs() <= 1e-4, "{material}: pixel {i} {p:?} vs {want:?}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
