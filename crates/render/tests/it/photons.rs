//! The classic engine's photon maps: the global map's estimate one diffuse bounce from a
//! point light against a numerical integral, the caustic map's total flux under a glass
//! sphere against the light's energy (energy conservation), and renders without photons
//! unchanged by a light's `energy`.

use std::sync::atomic::AtomicBool;

use crate::support;
use glam::Vec3A;
use render::{EngineKind, Settings};

use support::build_clean as build;

/// The scene text around `body` (materials, objects, lights and their instances listed in
/// `instances`), with `options` in the options block.
fn scene(options: &str, body: &str, instances: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 {options} end options
camera "cam" focal 1 aperture 1 aspect 1 resolution 24 24 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -8 1 end instance
{body}
instgroup "root" "cam_inst" {instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// A square of half size `h` at height `z`, facing up (`up`) or down.
fn square(name: &str, mtl: &str, h: f32, z: f32, up: bool) -> String {
    let order = if up { "0 1 2 3" } else { "0 3 2 1" };
    format!(
        "object \"{name}\" group\n {a} {a} {z}  {h} {a} {z}  {h} {h} {z}  {a} {h} {z}\n v 0 v 1 v 2 v 3\n c \"{mtl}\" {order}\nend group end object\ninstance \"{name}_inst\" \"{name}\" end instance\n",
        a = -h
    )
}

/// A UV sphere of radius `r` centred at (0, 0, `z`), outward-facing triangles.
fn sphere(name: &str, mtl: &str, r: f32, z: f32) -> String {
    let (nt, np) = (32usize, 64usize);
    let mut s = format!("object \"{name}\" group\n");
    let mut count = 0;
    s += &format!(" 0 0 {}\n 0 0 {}\n", z + r, z - r);
    count += 2;
    for i in 1..nt {
        let t = std::f32::consts::PI * i as f32 / nt as f32;
        for j in 0..np {
            let p = std::f32::consts::TAU * j as f32 / np as f32;
            s += &format!(" {} {} {}\n", r * t.sin() * p.cos(), r * t.sin() * p.sin(), z + r * t.cos());
            count += 1;
        }
    }
    for k in 0..count {
        s += &format!(" v {k}");
    }
    s += "\n";
    let ring = |i: usize, j: usize| 2 + (i - 1) * np + j % np;
    for j in 0..np {
        s += &format!(" c \"{mtl}\" 0 {} {}\n", ring(1, j), ring(1, j + 1));
        s += &format!(" c \"{mtl}\" 1 {} {}\n", ring(nt - 1, j + 1), ring(nt - 1, j));
    }
    for i in 1..nt - 1 {
        for j in 0..np {
            let (a, b, c, d) = (ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
            s += &format!(" c \"{mtl}\" {a} {d} {c}\n c \"{mtl}\" {a} {c} {b}\n");
        }
    }
    s += &format!("end group end object\ninstance \"{name}_inst\" \"{name}\" end instance\n");
    s
}

const LAMBERT: &str = r#"material "white" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material
material "dark" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.001 0.001 0.001 1) end material
"#;

/// Global illumination one bounce from a point light of energy Φ = 100 (exponent 2) at
/// height 1 over a floor of reflectance ρ = 0.5: the estimate at the centre of a nearly
/// black ceiling at height 2 against E = ∫ (ρ/π) E_floor cos θ cos θ' / d² dA, E_floor =
/// Φ cos θ / (4π r²).
#[test]
fn global_map_matches_one_bounce_irradiance() {
    let h = 5.0;
    let body = format!(
        "{LAMBERT}{}{}light \"pt\" \"mib_light_point\" (\"color\" 1 1 1) origin 0 0 1 energy 100 100 100 exponent 2 globillum photons 400000 end light\ninstance \"pt_inst\" \"pt\" end instance\n",
        square("floor", "white", h, 0.0, true),
        square("ceiling", "dark", h, 2.0, false),
    );
    let text = scene("globillum on globillum accuracy 800 1", &body, "\"floor_inst\" \"ceiling_inst\" \"pt_inst\"");
    let (scene, shading) = build(&text);
    let world = render::World::from_scene(&scene);
    let accel = render::accel::build(&world, render::Backend::default_available());
    let stats = render::photons::build(&world, accel.as_ref(), &shading, &AtomicBool::new(false)).expect("photons");
    assert!(stats.global >= 400_000, "{stats:?}");
    assert_eq!(stats.caustic, 0);
    let maps = shading.photons.get().expect("maps");
    // The numerical integral over the floor.
    let n = 1000;
    let mut expected = 0.0f64;
    let cell = (2.0 * h as f64) / n as f64;
    for i in 0..n {
        for j in 0..n {
            let x = -h as f64 + (i as f64 + 0.5) * cell;
            let y = -h as f64 + (j as f64 + 0.5) * cell;
            let r2 = x * x + y * y + 1.0;
            let e_floor = 100.0 / (4.0 * std::f64::consts::PI) / (r2 * r2.sqrt());
            let d2 = x * x + y * y + 4.0;
            expected += 0.5 / std::f64::consts::PI * e_floor * 4.0 / (d2 * d2) * cell * cell;
        }
    }
    for (x, y) in [(0.0, 0.0), (0.5, -0.3)] {
        let want = if x == 0.0 { expected } else { expected_at(x, y, h as f64) };
        let got = maps.global_irradiance(Vec3A::new(x as f32, y as f32, 2.0), -Vec3A::Z).unwrap();
        let err = (f64::from(got.x) - want).abs() / want;
        eprintln!("global estimate at ({x}, {y}): {} vs {want:.5} ({:.2} %), {stats:?}", got.x, err * 100.0);
        assert!(err < 0.05, "{got} vs {want}");
    }
}

/// The one-bounce irradiance at (x, y) on the ceiling.
fn expected_at(px: f64, py: f64, h: f64) -> f64 {
    let n = 1000;
    let cell = 2.0 * h / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -h + (i as f64 + 0.5) * cell;
            let y = -h + (j as f64 + 0.5) * cell;
            let r2 = x * x + y * y + 1.0;
            let e_floor = 100.0 / (4.0 * std::f64::consts::PI) / (r2 * r2.sqrt());
            let d2 = (x - px).powi(2) + (y - py).powi(2) + 4.0;
            sum += 0.5 / std::f64::consts::PI * e_floor * 4.0 / (d2 * d2) * cell * cell;
        }
    }
    sum
}

/// A spot light (energy 50, cone 12° inside the sphere's silhouette) over a clear glass
/// sphere over a floor: every photon goes through the glass, so the caustic map holds the
/// light's whole energy; the floor right under the sphere is brighter than its
/// surroundings.
#[test]
fn caustic_map_conserves_the_light_energy() {
    for glass in [
        r#"material "glass" "mib_dielectric" ("refract" 1, "ior" 1.5) end material"#,
        r#"material "glass" "mia_material" ("diffuse_weight" 0, "reflectivity" 0, "transparency" 1, "refr_color" 1 1 1, "refr_ior" 1.5, "cutout_opacity" 1, "brdf_conserve_energy" 1) end material"#,
    ] {
        let spread = 12f32.to_radians().cos();
        let body = format!(
            "{LAMBERT}{glass}\n{}{}light \"spot\" \"mib_light_spot\" (\"color\" 1 1 1) origin 0 0 4.2 direction 0 0 -1 spread {spread} energy 50 50 50 caustic photons 100000 end light\ninstance \"spot_inst\" \"spot\" end instance\n",
            square("floor", "white", 20.0, 0.0, true),
            sphere("ball", "glass", 1.0, 1.2),
        );
        let text = scene("caustic on caustic accuracy 200 0.5", &body, "\"floor_inst\" \"ball_inst\" \"spot_inst\"");
        let (scene, shading) = build(&text);
        let world = render::World::from_scene(&scene);
        let accel = render::accel::build(&world, render::Backend::default_available());
        let stats = render::photons::build(&world, accel.as_ref(), &shading, &AtomicBool::new(false)).expect("photons");
        let maps = shading.photons.get().expect("maps");
        let (map, _) = maps.caustic.as_ref().expect("a caustic map");
        let total: f32 = map.photons().iter().map(|p| p.power.x).sum();
        eprintln!("caustic map: total flux {total} of 50, {stats:?}");
        assert!((total - 50.0).abs() < 0.02 * 50.0, "{total}");
        assert!(map.photons().iter().all(|p| p.position.z.abs() < 1e-3), "photons only on the floor");
        let centre = maps.caustic_irradiance(Vec3A::ZERO, Vec3A::Z).x;
        let aside = maps.caustic_irradiance(Vec3A::new(3.0, 0.0, 0.0), Vec3A::Z).x;
        assert!(centre > 10.0 * aside.max(1e-6), "{centre} vs {aside}");
    }
}

/// Without `caustic` or `globillum`, a light's `energy` changes nothing: the image is the
/// same bit for bit and no photon pass runs.
#[test]
fn photons_off_leave_the_image_unchanged() {
    let render = |energy: &str, options: &str| {
        let body = format!(
            "{LAMBERT}{}light \"pt\" \"mib_light_point\" (\"color\" 1 1 1) origin 0 0 1 {energy} end light\ninstance \"pt_inst\" \"pt\" end instance\n",
            square("floor", "white", 5.0, 0.0, true),
        );
        let text = scene(options, &body, "\"floor_inst\" \"pt_inst\"");
        let (scene, shading) = build(&text);
        let world = render::World::from_scene(&scene);
        let accel = render::accel::build(&world, render::Backend::default_available());
        let settings = Settings { engine: EngineKind::Classic, spp: Some(4), ..Settings::default() };
        let (film, stats) =
            render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {});
        (film.rgba(), stats.photons)
    };
    let (plain, none) = render("", "");
    let (with_energy, off) = render("energy 100 100 100 globillum photons 1000", "caustic off globillum off");
    assert!(none.is_none() && off.is_none());
    assert_eq!(plain, with_energy);
    // And with the maps on, the photon pass runs (a lone floor stores nothing: no photon
    // comes back to it after its bounce).
    let (_, on) = render("energy 100 100 100 globillum photons 1000", "globillum on");
    assert!(on.is_some_and(|p| p.emitted > 0));
}
