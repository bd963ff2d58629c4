//! Displacement mapping (`crate::displace`, the stage after the world's translation):
//! constant, textured (cosine wave) and Maya shading-group displacement measured by ray
//! hits against closed forms, `max displace`'s clamp, a hostile subdivision level, and
//! both engines rendering the displaced surface.

use glam::Vec3A;
use render::accel::{self, Backend};
use render::ray::Ray;
use render::{EngineKind, Settings};

use crate::support;

/// A unit square in z = 0 (x, y and its texture coordinates 0…1, normal +z) with the
/// material `material`, its object carrying `object_stmts`; `body` (shaders, materials)
/// and `options` statements go before it. A camera above it at 8×8 pixels.
pub fn plane(options: &str, body: &str, object_stmts: &str, material: &str) -> String {
    format!(
        r#"
options "opt" {options} end options
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0 0 1 0 0 0 0 1 0 -0.5 -0.5 -3 1 end instance
{body}
object "square"
    {object_stmts}
    group
    0 0 0  1 0 0  1 1 0  0 1 0
    0 0 0  1 0 0  1 1 0  0 1 0
    v 0 t 4 v 1 t 5 v 2 t 6 v 3 t 7
    p 0 1 2 3
end group end object
instance "square_inst" "square" material "{material}" end instance
instgroup "root" "cam_inst" "square_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The height of the displaced surface above (x, y): where a ray straight down from
/// z = 10 hits it (Rust backend), or `None`.
pub fn height_at(world: &render::World, x: f32, y: f32) -> Option<f32> {
    let bvh = accel::build(world, Backend::Rust);
    bvh.intersect(&Ray::new(Vec3A::new(x, y, 10.0), Vec3A::new(0.0, 0.0, -1.0))).map(|h| 10.0 - h.t)
}

/// Builds `text` through the pipeline's world stage: the built scene and its messages.
pub fn build(text: &str) -> support::BuiltScene {
    support::build_parsed(&mi::parse_str("t.mi", text), 8, &[])
}

/// A material `m` whose displacement is the constant `d` through `maya_material_displace`
/// (a shading group's displacement with nothing connected), shaded by a lambert.
pub fn constant_material(d: f32) -> String {
    format!(
        r#"shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1)
shader "disp" "maya_material_displace" ("displacement" {d})
material "m" = "lam" displace = "disp" end material"#
    )
}

/// A plane displaced by the constant d moves d along its normal: the hit from a ray
/// straight down lies at z = d (1e-4), at the corners' and the middle's columns, with the
/// object's own vertices only (no approximation) and with 4 × 4 subdivision alike.
#[test]
fn a_constant_displacement_moves_the_plane_along_its_normal() {
    for approx in ["", "approximate displace regular parametric 2"] {
        let b = build(&plane("", &constant_material(0.375), approx, "m"));
        assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
        for (x, y) in [(0.1, 0.1), (0.5, 0.5), (0.9, 0.3), (0.25, 0.75)] {
            let h = height_at(&b.built.world, x, y).expect("the plane is hit");
            assert!((h - 0.375).abs() < 1e-4, "{approx}: ({x}, {y}) at {h}");
        }
        let tris: usize =
            b.built.world.instances.iter().map(|i| b.built.world.meshes[i.mesh as usize].triangles.len()).sum();
        assert_eq!(tris, if approx.is_empty() { 2 } else { 32 });
    }
}

/// `max displace 0.25` clamps a displacement of 1 to 0.25 (the object's statement, and
/// the options' where the object has none).
#[test]
fn max_displace_clamps_the_displacement() {
    for (options, object) in [("", "max displace 0.25"), ("max displace 0.25", "")] {
        let b = build(&plane(options, &constant_material(1.0), object, "m"));
        let h = height_at(&b.built.world, 0.5, 0.5).expect("hit");
        assert!((h - 0.25).abs() < 1e-4, "{options}{object}: {h}");
    }
    let b = build(&plane("", &constant_material(-1.0), "max displace 0.25", "m"));
    let h = height_at(&b.built.world, 0.5, 0.5).expect("hit");
    assert!((h + 0.25).abs() < 1e-4, "{h}");
}

/// A base-library texture as the displacement: `mib_texture_wave` of the first texture
/// space, h(u) = 0.1·cos 2πu, on a plane split 32 × 32 (`regular parametric 5`). Along
/// the grid's lines x = k/32 the displaced surface is exactly h(x): the hits at
/// x = 0, ¼, ½, ⅝ are 0.1, 0, −0.1 and −0.1·cos(π/4) (1e-4).
#[test]
fn a_wave_texture_displaces_to_its_closed_form_heights() {
    let body = r#"shader "coord" "mib_texture_vector" ("select" 0, "selspace" 0)
shader "wave" "mib_texture_wave" ("coord" = "coord", "amplitude_x" 0.1, "amplitude_y" 0, "amplitude_z" 0, "offset" 0)
shader "lam" "mib_illum_lambert" ("diffuse" 1 1 1)
material "m" = "lam" displace = "wave" end material"#;
    let b = build(&plane("", body, "approximate displace regular parametric 5", "m"));
    assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
    for x in [0.0f32, 0.25, 0.5, 0.625] {
        let expect = 0.1 * (2.0 * std::f32::consts::PI * x).cos();
        let x_ray = if x == 0.0 { 1e-6 } else { x };
        let h = height_at(&b.built.world, x_ray, 0.3).expect("hit");
        assert!((h - expect).abs() < 1e-4, "x = {x}: {h} vs {expect}");
    }
}

/// A Maya shading group's displacement connection: `maya_material_displace` with its
/// `displacement` connected to a texture's output (`mib_texture_wave`'s colour through
/// `maya_*`'s scalar parameter reads its first component: the constant offset 0.2).
#[test]
fn the_maya_shading_group_displacement_connection_displaces() {
    let body = r#"shader "c" "mib_texture_wave" ("offset" 0.2)
shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1)
shader "sg" "maya_shadingengine" ("surfaceShader" = "lam")
shader "sg_disp" "adskMayaMaterialDisplace" ("displacement" = "c")
material "m" = "sg" displace = "sg_disp" end material"#;
    let b = build(&plane("", body, "", "m"));
    let h = height_at(&b.built.world, 0.4, 0.6).expect("hit");
    assert!((h - 0.2).abs() < 1e-4, "{h} {:?}", b.messages);
}

/// A hostile `approximate displace regular parametric 40` (4^40 triangles per triangle)
/// is an error at its line and column; nothing is made. A form mira does not implement
/// (`fine` without a criterion) warns at its line and splits by the default level.
#[test]
fn a_hostile_level_fails_at_its_line_and_other_forms_warn() {
    let b = build(&plane("", &constant_material(0.5), "approximate displace regular parametric 40", "m"));
    let errors: Vec<&String> = b.messages.iter().filter(|m| m.contains("error")).collect();
    assert_eq!(errors.len(), 1, "{:?}", b.messages);
    assert!(errors[0].contains("t.mi:9:") && errors[0].contains("parametric 40"), "{}", errors[0]);
    assert!(b.built.diagnostics.iter().any(mi::Diagnostic::is_error));

    let b = build(&plane("", &constant_material(0.5), "approximate displace fine sharp 0.5 0 4", "m"));
    let warning = b.messages.iter().find(|m| m.contains("fine sharp")).expect("a warning");
    assert!(warning.contains("t.mi:9:") && warning.contains("not implemented"), "{warning}");
    let h = height_at(&b.built.world, 0.5, 0.5).expect("hit");
    assert!((h - 0.5).abs() < 1e-4);
}

/// Both engines render the displaced surface: a 1 × 1 square 3 below a 90° camera covers
/// the middle 8/6 ≈ 1.33 pixels across at 8 × 8; displaced 1.5 towards the camera it
/// covers the middle 8/3 ≈ 2.67, so the pixels (3, 3)…(4, 4) are fully covered and
/// evenly lit and the pixels beside them a third covered (their mean a third of the
/// middle's, ± 0.05), the next column empty — where the undisplaced square would leave
/// the ring empty. The lambert under a head-on light of irradiance π is π in the classic
/// engine (mental ray's lambert has no 1/π) and 1 in the path engine (2 %).
#[test]
fn both_engines_render_the_displaced_surface() {
    let body = r#"light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265) direction 0 0 -1 end light
instance "sun_inst" "sun" end instance
shader "lam" "mib_illum_lambert" ("diffuse" 1 1 1, "lights" ["sun_inst"])
shader "disp" "maya_material_displace" ("displacement" 1.5)
material "m" = "lam" displace = "disp" end material"#;
    let text = plane("filter box 1 1", body, "", "m").replace(
        r#"instgroup "root" "cam_inst" "square_inst""#,
        r#"instgroup "root" "cam_inst" "sun_inst" "square_inst""#,
    );
    let b = build(&text);
    assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
    for (engine, spp, lambert) in [(EngineKind::Classic, 16, std::f32::consts::PI), (EngineKind::Path, 64, 1.0)] {
        let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
        let px = support::render_world(&b.built.world, &b.built.shading, &settings).0.rgba();
        let middle = support::mean(&px, 8, (3, 5), (3, 5));
        assert!(middle.iter().all(|c| (c / lambert - 1.0).abs() < 0.02), "{engine:?}: {middle:?}");
        for (columns, rows) in [((2, 3), (3, 5)), ((5, 6), (3, 5)), ((3, 5), (2, 3)), ((3, 5), (5, 6))] {
            let edge = support::mean(&px, 8, columns, rows);
            assert!((edge[1] / middle[1] - 1.0 / 3.0).abs() < 0.05, "{engine:?}: edge {columns:?} {rows:?} {edge:?}");
        }
        let outside = support::mean(&px, 8, (1, 2), (0, 8));
        assert!(outside[1] < 1e-6, "{engine:?}: {outside:?}");
    }
}

/// One object placed twice, with a displaced and a plain material: the displaced
/// instance's hits are at d (1e-4), the plain one's stay at 0 (its mesh is kept).
#[test]
fn an_object_placed_with_and_without_displacement_keeps_both_forms() {
    let body = format!(
        "{}\nmaterial \"plain\" \"mib_illum_lambert\" (\"diffuse\" 1 1 1) end material",
        constant_material(0.5)
    );
    let text = plane("", &body, "", "m").replace(
        r#"instgroup "root" "cam_inst" "square_inst""#,
        "instance \"moved_inst\" \"square\" material \"plain\" transform 1 0 0 0 0 1 0 0 0 0 1 0 -2 0 0 1 end instance\n\
         instgroup \"root\" \"cam_inst\" \"moved_inst\" \"square_inst\"",
    );
    let b = build(&text);
    assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
    let displaced = height_at(&b.built.world, 0.5, 0.5).expect("hit");
    let plain = height_at(&b.built.world, 2.5, 0.5).expect("hit");
    assert!((displaced - 0.5).abs() < 1e-4 && plain.abs() < 1e-4, "{displaced} {plain}");
}

/// The options' `approximate displace … all` overrides the object's own (mental ray 3.9
/// manual, "Approximations": options approximations "override the approximation
/// statements in the object"): an object asking for `parametric 2` (2 × 16 triangles)
/// under options' `parametric 1` is split into 2 × 4, still displaced by d (1e-4); the
/// object's statement holds where the options have none.
#[test]
fn the_options_approximation_overrides_the_objects() {
    let object = "approximate displace regular parametric 2";
    for (options, triangles) in [("approximate displace regular parametric 1 all", 8), ("", 32)] {
        let b = build(&plane(options, &constant_material(0.25), object, "m"));
        assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
        let world = &b.built.world;
        let made: usize = world.instances.iter().map(|i| world.meshes[i.mesh as usize].triangles.len()).sum();
        assert_eq!(made, triangles, "options '{options}'");
        let h = height_at(world, 0.3, 0.6).expect("hit");
        assert!((h - 0.25).abs() < 1e-4, "{options}: {h}");
    }
}
