//! mental ray's environment-light string options (`scene::options::modes`):
//! `"environment lighting scale"` multiplies the light the environment casts, not what the
//! camera sees; `"environment lighting quality"` averages more directions per estimate
//! (less noise, the same mean); `"environment lighting shadow"` decides what the
//! environment's shadow rays do. Each test states its tolerance.

use crate::support;

use render::integrator::PathSettings;
use render::{EngineKind, Settings};

/// An orthographic camera (a 2 × 2 view, 8² pixels) looking down −Z at a Lambert plane of
/// albedo 0.5 filling the left half of the view, under a constant environment of radiance
/// 2; `wall` adds a wall of material `wall` standing on the plane at y = 1.5 (out of view),
/// 2000 wide and 1000 high — from the plane it hides the half of the sky towards +y, all
/// but 0.2 % of its light; `options` go into the options block.
fn scene(options: &str, wall: Option<&str>) -> String {
    let wall = wall.map_or(String::new(), |m| {
        format!(
            r#"material "wall_m" {m} end material
object "wall" group
    -1000 1.5 -5  1000 1.5 -5  1000 1.5 995  -1000 1.5 995
    v 0 v 1 v 2 v 3
    p "wall_m" 0 1 2 3
end group end object
instance "wall_inst" "wall" end instance
"#
        )
    });
    let wall_inst = if wall.is_empty() { "" } else { "\"wall_inst\"" };
    format!(
        r#"
options "opt" filter box 1 1 {options} end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 8 8
    environment "mib_color_mix" ("num" 0, "color_base" 2 2 2 1)
end camera
instance "cam_inst" "cam" end instance
material "half" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material
object "plane" group
    -50 -50 -5  0 -50 -5  0 50 -5  -50 50 -5
    v 0 v 1 v 2 v 3
    p "half" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance
{wall}instgroup "root" "cam_inst" "plane_inst" {wall_inst} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Direct light only: one scattering event, light sampling alone.
const DIRECT: PathSettings = PathSettings { max_depth: 1, rr_depth: 1, mis: false };

/// Renders `text` with the path engine at `spp` samples per pixel: pixels and messages.
fn render_path(text: &str, spp: u32, path: PathSettings) -> (Vec<[f32; 4]>, Vec<String>) {
    let support::Compiled { scene, shading, mut messages, .. } = support::compile(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    messages.extend(world.warnings.iter().cloned());
    let settings = Settings { engine: EngineKind::Path, spp: Some(spp), path, ..Settings::default() };
    (support::render_world(&world, &shading, &settings).0.rgba(), messages)
}

/// The plane's pixels' red values (the left half of the 8² image).
fn plane(px: &[[f32; 4]]) -> Vec<f32> {
    px.iter().enumerate().filter(|(i, _)| i % 8 < 4).map(|(_, p)| p[0]).collect()
}

/// The environment's pixels (the right half).
fn sky(px: &[[f32; 4]]) -> Vec<[f32; 4]> {
    px.iter().enumerate().filter(|(i, _)| i % 8 >= 4).map(|(_, p)| *p).collect()
}

fn mean(v: &[f32]) -> f32 {
    v.iter().sum::<f32>() / v.len() as f32
}

/// `"environment lighting scale" 2` doubles the plane's direct environment light, pixel by
/// pixel (the same samples: 1e-5 relative), and leaves the environment the camera sees
/// unchanged, bit for bit; a colour scale is read as its channels' mean, with a warning.
#[test]
fn environment_lighting_scale_multiplies_its_light_not_its_view() {
    let (plain, messages) = render_path(&scene("", None), 16, DIRECT);
    assert!(messages.is_empty(), "{messages:#?}");
    let (scaled, messages) = render_path(&scene("\"environment lighting scale\" 2", None), 16, DIRECT);
    assert!(messages.is_empty(), "{messages:#?}");
    for (a, b) in plane(&plain).iter().zip(plane(&scaled)) {
        assert!((b - 2.0 * a).abs() <= 1e-5 * b.abs(), "{b} vs 2 × {a}");
    }
    assert!(mean(&plane(&plain)) > 0.5, "the plane is lit");
    assert_eq!(sky(&plain), sky(&scaled));
    let (colour, messages) = render_path(&scene("\"environment lighting scale\" 1 2 3", None), 16, DIRECT);
    assert_eq!(plane(&colour), plane(&scaled));
    assert!(messages.iter().any(|m| m.contains("\"environment lighting scale\" is a colour")), "{messages:#?}");
}

/// `"environment lighting quality" 4` (eight directions per estimate) keeps the plane's
/// mean at albedo × L = 1 (within 3 %: 32 pixels × 64 spp × 8) and lowers the pixels'
/// spread below 0.6 × the single direction's (√8 less in theory); the default quality is
/// the image without the option, bit for bit.
#[test]
fn environment_lighting_quality_lowers_the_noise_not_the_mean() {
    let spread = |v: &[f32]| {
        let m = mean(v);
        (v.iter().map(|x| (x - m) * (x - m)).sum::<f32>() / v.len() as f32).sqrt()
    };
    let (one, _) = render_path(&scene("", None), 64, DIRECT);
    let (default, _) = render_path(&scene("\"environment lighting quality\" 0.5", None), 64, DIRECT);
    assert_eq!(one, default);
    let (eight, messages) = render_path(&scene("\"environment lighting quality\" 4", None), 64, DIRECT);
    assert!(messages.is_empty(), "{messages:#?}");
    let (m1, m8) = (mean(&plane(&one)), mean(&plane(&eight)));
    let (s1, s8) = (spread(&plane(&one)), spread(&plane(&eight)));
    eprintln!("quality: mean {m1} → {m8}, spread {s1} → {s8}");
    assert!((m8 - 1.0).abs() < 0.03 && (m1 - 1.0).abs() < 0.05, "means {m1} {m8}");
    assert!(s8 < 0.6 * s1, "spread {s8} vs {s1}");
}

/// `"environment lighting shadow"` with full paths (MIS on): a wall that is half cut out
/// (`cutout_opacity` 0.5) beside the plane hides half its sky. `"transparent"` (and no
/// option) lets half of that half through: 0.75; `"solid"` stops it: 0.5; `"off"` traces no
/// shadow rays: 1 (albedo × L unshadowed) — each within 3 % (32 pixels, 1024 spp). A
/// value mira does not know warns and reads as `"transparent"`.
#[test]
fn environment_lighting_shadow_decides_what_its_shadow_rays_do() {
    let wall = r#""mia_material" ("diffuse" 0 0 0 1, "diffuse_weight" 0, "reflectivity" 0, "cutout_opacity" 0.5)"#;
    for (option, want) in [("", 0.75), ("\"transparent\"", 0.75), ("\"solid\"", 0.5), ("\"off\"", 1.0)] {
        let options =
            if option.is_empty() { String::new() } else { format!("\"environment lighting shadow\" {option}") };
        let (px, messages) = render_path(&scene(&options, Some(wall)), 1024, PathSettings::default());
        assert!(messages.is_empty(), "{option}: {messages:#?}");
        let m = mean(&plane(&px));
        eprintln!("shadow {option}: plane {m} (expected {want})");
        assert!((m - want).abs() < 0.03 * want, "{option}: plane {m} vs {want}");
    }
    let messages = support::compile(&scene("\"environment lighting shadow\" \"optimized\"", None)).messages;
    assert!(messages.iter().any(|m| m.contains("t.mi:2:") && m.contains("none of")), "{messages:#?}");
}
