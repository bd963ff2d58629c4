//! The physical sun and sky (`mia_physicalsun` on a directional light, `mia_physicalsky` as
//! the camera environment linked to it) in the path engine against the classic engine: the
//! sun's irradiance on a plane against the sun model, and a plane under sun and sky whose
//! image means agree with final gathering's. The sky's disk and glow are seen by the camera
//! but gather no light in either engine when a sun light delivers the sun.

use crate::support;

use glam::Vec3A;
use render::{EngineKind, Settings};

/// The direction the sun shines in: towards −y (down) and −z, 50° above the horizon.
fn sun_travel() -> Vec3A {
    let e = 50f32.to_radians();
    Vec3A::new(0.0, -e.sin(), -e.cos())
}

/// A matte `mia_material` plane (ρ 0.5, y = 0) filling the view of an 8² camera 4 above it
/// looking straight down, lit by the sun and, with `sky`, by the sky through final
/// gathering (accuracy 256).
fn plane_scene(sky: bool) -> String {
    let d = sun_travel();
    let environment = if sky {
        r#"environment "mia_physicalsky" ("sun" "sun_inst", "y_is_up" on, "haze" 1, "sun_disk_scale" 4)"#
    } else {
        ""
    };
    format!(
        r#"
options "opt" filter box 1 1 samples 0 0 finalgather on finalgather accuracy 256 end options
light "sun" "mia_physicalsun" ("y_is_up" on, "haze" 1, "samples" 8) direction {} {} {} end light
instance "sun_inst" "sun" end instance
camera "cam" focal 1 aperture 1 aspect 1 resolution 8 8
    {environment}
end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -4 1 end instance
material "m" "mia_material" ("diffuse" 0.5 0.5 0.5, "diffuse_weight" 1, "reflectivity" 0, "diffuse_roughness" 0)
end material
object "plane" group -50 0 50  50 0 50  50 0 -50  -50 0 -50  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "sun_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        d.x, d.y, d.z
    )
}

/// Renders `text` with `engine` at `spp`: the pixels, asserting the path engine
/// translated every light (no warning).
fn render(text: &str, engine: EngineKind, spp: u32) -> Vec<[f32; 4]> {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    assert_eq!(world.lights.len(), 1, "the sun is a path-engine light");
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    support::render_world(&world, &shading, &settings).0.rgba()
}

fn mean(px: &[[f32; 4]]) -> Vec3A {
    px.iter().map(|p| Vec3A::new(p[0], p[1], p[2])).sum::<Vec3A>() / px.len() as f32
}

/// The sun alone: both engines give the plane ρ × the sun's colour (the sun model of
/// `mia::sun`, `haze` 1, Y up) × cos θ, θ = 40° from the normal, within 0.5 % — the
/// classic engine from its light shader, the path engine from its distant light of π ×
/// that colour (reflected as ρ/π).
#[test]
fn the_suns_irradiance_on_a_plane_is_the_classic_engines() {
    let text = plane_scene(false);
    let sun = mia::sun::PhysicalSun { y_is_up: true, haze: 1.0, ..Default::default() };
    let colour = sun.color(-sun_travel()).expect("the sun is up");
    let want = colour * 0.5 * 50f32.to_radians().sin();
    let classic = mean(&render(&text, EngineKind::Classic, 1));
    let path = mean(&render(&text, EngineKind::Path, 4));
    println!("sun on the plane: formula {want}, classic {classic}, path {path}");
    for k in 0..3 {
        assert!((classic[k] / want[k] - 1.0).abs() < 5e-3, "classic {classic} vs {want}");
        assert!((path[k] / want[k] - 1.0).abs() < 5e-3, "path {path} vs {want}");
    }
}

/// Sun and sky: the path engine's image mean (64 samples a pixel) is the classic engine's
/// (the sun light plus final gathering's sky, `mia_material`'s irradiance/π) within 2 %
/// per channel. The sky's disk and glow (4 × the real disk) would add about a tenth of the
/// sun's light if either engine gathered them.
#[test]
fn a_plane_under_sun_and_sky_agrees_in_both_engines() {
    let text = plane_scene(true);
    let classic = mean(&render(&text, EngineKind::Classic, 4));
    let path = mean(&render(&text, EngineKind::Path, 64));
    let sun_only = mean(&render(&plane_scene(false), EngineKind::Classic, 1));
    println!("sun and sky: classic {classic}, path {path} (sun alone {sun_only})");
    for k in 0..3 {
        // The sky adds a visible share (so the comparison covers it).
        assert!(classic[k] > 1.1 * sun_only[k], "classic {classic} vs sun alone {sun_only}");
        assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "path {path} vs classic {classic}");
    }
}

/// The environment of a sky linked to a sun light: seen (camera rays, mirrors) it shows
/// the disk — far brighter towards the sun than 16° away (outside the glow's 10.7°) —, as light it does not: towards
/// the sun it is within a factor 3 of the sky 16° away (the sky brightens towards the sun
/// by itself, Perez's circumsolar term).
#[test]
fn the_sun_disk_is_seen_but_casts_no_light_of_its_own() {
    let (scene, shading) = support::build_clean(&plane_scene(true));
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    let accel = render::accel::build(&world, render::Backend::default_available());
    let env = render::environment::Environment::of_scene(&world, accel.as_ref(), &shading).expect("an environment");
    let to_sun = -sun_travel();
    let beside = (to_sun + Vec3A::new(0.0, 0.0, 0.4)).normalize();
    let lum = |c: Vec3A| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    let (seen, seen_beside) = (lum(env.radiance(to_sun)), lum(env.radiance(beside)));
    let (light, light_beside) = (lum(env.light_radiance(to_sun)), lum(env.light_radiance(beside)));
    println!("towards the sun: seen {seen}, light {light}; 16° away: seen {seen_beside}, light {light_beside}");
    assert!(seen > 100.0 * seen_beside, "the disk is seen: {seen} vs {seen_beside}");
    assert!(light < 3.0 * light_beside, "no disk in the light: {light} vs {light_beside}");
    assert!((seen_beside - light_beside).abs() <= 1e-6 * seen_beside, "the rest of the sky is the same");
}
