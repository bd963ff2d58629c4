//! `mib_glossy_reflection` and `mib_glossy_refraction` against `mib_reflect` /
//! `mib_refract` in the sharp limit, their sample-count and distance-falloff rules.

use crate::support;

use std::cell::RefCell;

use glam::Vec3A;
use shader::{Color, RayType, State, Tracer, VertexData};
use support::{compile_with, point, run, Compiled, Empty};

/// Every reflection, refraction or transparency ray hits a wall of material `material`
/// facing it at distance `dist` (if within the ray's reach).
struct Wall {
    dist: f32,
    material: u32,
    rays: RefCell<Vec<(RayType, Vec3A)>>,
}

impl Wall {
    fn new(c: &Compiled, dist: f32) -> Wall {
        let material = c.shading.materials.iter().position(|m| m.name == "wall").expect("wall") as u32;
        Wall { dist, material, rays: RefCell::default() }
    }
}

impl Tracer for Wall {
    fn intersect(&self, ray: &mut State, max_dist: f32) -> bool {
        self.rays.borrow_mut().push((ray.ray_type, ray.dir));
        if self.dist > max_dist {
            return false;
        }
        ray.dist = self.dist;
        ray.point = ray.org + ray.dir * self.dist;
        ray.normal = -ray.dir;
        ray.normal_geom = -ray.dir;
        ray.dot_nd = -1.0;
        ray.material = Some(self.material);
        true
    }

    fn shadow_hits(&self, _ray: &State, _max_dist: f32, _visit: &mut dyn FnMut(&State) -> bool) {}

    fn triangle(&self, _hit: &State, _data: VertexData) -> Option<[Vec3A; 3]> {
        None
    }

    fn fb_put(&self, _buffer: u32, _value: Color) -> bool {
        false
    }
}

/// The wall's colour and the environment's.
const WALL: [f32; 3] = [0.9, 0.5, 0.1];
const ENV: [f32; 3] = [0.2, 0.3, 0.4];

/// Compiles materials `m` (from `body`) and `wall`, with a constant environment.
fn scene(body: &str) -> Compiled {
    let text = format!(
        r#"shader "envsh" "mib_color_mix" ("color_base" {e0} {e1} {e2} 1)
        material "wall" "mib_color_mix" ("color_base" {w0} {w1} {w2} 1) end material
        shader "basesh" "mib_color_mix" ("color_base" 0.05 0.1 0.15 1)
        {body}"#,
        e0 = ENV[0],
        e1 = ENV[1],
        e2 = ENV[2],
        w0 = WALL[0],
        w1 = WALL[1],
        w2 = WALL[2],
    );
    let c = compile_with("trace depth 4 4 8", "environment = \"envsh\"", &text, &["m", "wall"]);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    c
}

/// A point lit from 30° off the normal (+y).
fn oblique() -> State {
    let t = 30f32.to_radians();
    point(Vec3A::Y, Vec3A::new(t.sin(), -t.cos(), 0.0))
}

fn shade(c: &Compiled, tracer: &dyn Tracer, state: State) -> Color {
    run(c, tracer, c.material("m"), state).0.color()
}

fn close3(got: Color, want: [f32; 3], tol: f32) {
    let d = (got.truncate() - glam::Vec3::from_array(want)).abs().max_element();
    assert!(d <= tol, "got {got}, want {want:?}");
}

const GLOSSY: &str = r#"material "m" "mib_glossy_reflection" ("reflection_color" 0.7 0.6 0.5, "environment_color" 0.7 0.6 0.5,
    "reflection_base_weight" 1, "reflection_edge_weight" 1, "samples" {samples}, "u_spread" {spread}, "v_spread" {spread},
    "max_distance" {max}, "falloff" 2 {extra}) end material"#;

fn glossy(samples: u32, spread: f32, max: f32, extra: &str) -> String {
    GLOSSY
        .replace("{samples}", &samples.to_string())
        .replace("{spread}", &spread.to_string())
        .replace("{max}", &max.to_string())
        .replace("{extra}", extra)
}

#[test]
fn sharp_glossy_reflection_is_mib_reflect() {
    let reflect = scene(r#"material "m" "mib_reflect" ("reflect" 0.7 0.6 0.5 1) end material"#);
    let sharp = scene(&glossy(16, 0.0, 0.0, ""));
    let want = shade(&reflect, &Wall::new(&reflect, 3.0), oblique());
    let got = shade(&sharp, &Wall::new(&sharp, 3.0), oblique());
    close3(got, want.truncate().to_array(), 1e-6);
    // Nothing hit: the environment times `environment_color` (equal to the reflection
    // colour here), as mib_reflect's environment.
    let want = shade(&reflect, &Empty::default(), oblique());
    let got = shade(&sharp, &Empty::default(), oblique());
    close3(got, want.truncate().to_array(), 1e-6);
    close3(got, [0.7 * ENV[0], 0.6 * ENV[1], 0.5 * ENV[2]], 1e-6);
    // On the wall: its colour times the reflection colour.
    let got = shade(&sharp, &Wall::new(&sharp, 3.0), oblique());
    close3(got, [0.9 * 0.7, 0.5 * 0.6, 0.1 * 0.5], 1e-6);
    // A tiny spread: every ray within 1e-3 of the mirror direction, same colour.
    let tiny = scene(&glossy(16, 1e-4, 0.0, ""));
    let wall = Wall::new(&tiny, 3.0);
    let got = shade(&tiny, &wall, oblique());
    close3(got, [0.9 * 0.7, 0.5 * 0.6, 0.1 * 0.5], 1e-5);
    let s = oblique();
    let mirror = s.dir - 2.0 * s.dir.dot(s.normal) * s.normal;
    let rays = wall.rays.borrow();
    let reflections: Vec<_> = rays.iter().filter(|(t, _)| *t == RayType::Reflect).collect();
    assert_eq!(reflections.len(), 16);
    assert!(reflections.iter().all(|(_, d)| (*d - mirror).length() < 1e-3));
}

#[test]
fn glossy_spread_widens_the_rays_anisotropically() {
    let c = scene(
        &glossy(64, 0.0, 0.0, r#", "u_axis" 1 0 0, "v_axis" 0 0 1"#)
            .replace("\"u_spread\" 0", "\"u_spread\" 0.2")
            .replace("\"v_spread\" 0", "\"v_spread\" 0.02"),
    );
    let wall = Wall::new(&c, 3.0);
    let s = point(Vec3A::Y, -Vec3A::Y);
    shade(&c, &wall, s);
    let rays = wall.rays.borrow();
    assert_eq!(rays.len(), 64);
    // Reflected about a Ward half vector: slopes of the ray are ~twice the half vector's,
    // whose standard deviation is α/√2 per axis.
    let n = rays.len() as f32;
    let sx = (rays.iter().map(|(_, d)| (d.x / d.y).powi(2)).sum::<f32>() / n).sqrt();
    let sz = (rays.iter().map(|(_, d)| (d.z / d.y).powi(2)).sum::<f32>() / n).sqrt();
    let want_x = 2.0 * 0.2 / 2f32.sqrt();
    let want_z = 2.0 * 0.02 / 2f32.sqrt();
    assert!((sx - want_x).abs() < 0.25 * want_x, "u spread {sx} vs {want_x}");
    assert!((sz - want_z).abs() < 0.25 * want_z, "v spread {sz} vs {want_z}");
}

#[test]
fn no_samples_gives_the_base_material() {
    let c = scene(&glossy(0, 0.1, 0.0, r#", "base_material" "basesh""#));
    let wall = Wall::new(&c, 3.0);
    let got = shade(&c, &wall, oblique());
    close3(got, [0.05, 0.1, 0.15], 0.0);
    assert!(wall.rays.borrow().is_empty(), "no rays cast");
    // With samples the base is added to the reflection.
    let c = scene(&glossy(4, 0.0, 0.0, r#", "base_material" "basesh""#));
    let got = shade(&c, &Wall::new(&c, 3.0), oblique());
    close3(got, [0.05 + 0.9 * 0.7, 0.1 + 0.5 * 0.6, 0.15 + 0.1 * 0.5], 1e-6);
}

#[test]
fn max_distance_fades_to_the_environment() {
    // Hit at 5 of max 10 with falloff 2: t = 0.25 of the environment.
    let c = scene(&glossy(4, 0.0, 10.0, ""));
    let got = shade(&c, &Wall::new(&c, 5.0), oblique());
    let want: Vec<f32> = (0..3).map(|k| [0.7, 0.6, 0.5][k] * (0.75 * WALL[k] + 0.25 * ENV[k])).collect();
    close3(got, [want[0], want[1], want[2]], 1e-6);
    // Beyond the distance only the environment remains.
    let got = shade(&c, &Wall::new(&c, 20.0), oblique());
    close3(got, [0.7 * ENV[0], 0.6 * ENV[1], 0.5 * ENV[2]], 1e-6);
    // The edge curve: base 0.2, edge 1, factor 5 at 30°: 0.2 + 0.8·(1 − cos 30°)^5.
    let c = scene(
        &glossy(4, 0.0, 0.0, r#", "edge_factor" 5"#)
            .replace("\"reflection_base_weight\" 1", "\"reflection_base_weight\" 0.2"),
    );
    let got = shade(&c, &Wall::new(&c, 3.0), oblique());
    let w = 0.2 + 0.8 * (1.0 - 30f32.to_radians().cos()).powi(5);
    close3(got, [0.9 * 0.7 * w, 0.5 * 0.6 * w, 0.1 * 0.5 * w], 1e-6);
}

const REFRACTION: &str = r#"material "m" "mib_glossy_refraction" ("refraction_color" 1 1 1, "refraction_base_weight" 1,
    "refraction_edge_weight" 1, "ior" 1.5, "samples" 8, "u_spread" {spread}, "v_spread" {spread} {extra}) end material"#;

fn refraction(spread: f32, extra: &str) -> String {
    REFRACTION.replace("{spread}", &spread.to_string()).replace("{extra}", extra)
}

#[test]
fn sharp_glossy_refraction_is_mib_refract() {
    let refract = scene(r#"material "m" "mib_refract" ("refract" 1 1 1 1, "ior" 1.5) end material"#);
    let sharp = scene(&refraction(0.0, ""));
    let (w1, w2) = (Wall::new(&refract, 3.0), Wall::new(&sharp, 3.0));
    let want = shade(&refract, &w1, oblique());
    let got = shade(&sharp, &w2, oblique());
    close3(got, want.truncate().to_array(), 1e-6);
    let (a, b) = (w1.rays.borrow(), w2.rays.borrow());
    assert_eq!(b.len(), 1);
    assert_eq!(a[0].0, b[0].0);
    assert!((a[0].1 - b[0].1).length() < 1e-6, "same refracted direction");
    // Snell: sin θt = sin 30° / 1.5.
    assert!((b[0].1.x - 0.5 / 1.5).abs() < 1e-5);
    // From inside at 60° (past the critical 41.8°): total internal reflection, as
    // mib_refract with the relative index 1/1.5.
    let t = 60f32.to_radians();
    let mut inside = point(Vec3A::Y, Vec3A::new(t.sin(), -t.cos(), 0.0));
    inside.inv_normal = true;
    let refract = scene(r#"material "m" "mib_refract" ("refract" 1 1 1 1, "ior" 0.6666667) end material"#);
    let w1 = Wall::new(&refract, 3.0);
    let w2 = Wall::new(&sharp, 3.0);
    shade(&refract, &w1, inside.clone());
    let got = shade(&sharp, &w2, inside);
    close3(got, WALL, 1e-6);
    assert_eq!(w2.rays.borrow()[0].0, RayType::Reflect);
    assert!((w1.rays.borrow()[0].1 - w2.rays.borrow()[0].1).length() < 1e-6);
}

#[test]
fn glossy_refraction_fades_into_the_deep_material_and_adds_the_top() {
    let extra = r#", "top_material" "basesh", "deep_material" "envsh", "max_distance" 10, "falloff" 1"#;
    let c = scene(&refraction(0.05, extra));
    let got = shade(&c, &Wall::new(&c, 4.0), oblique());
    // t = 0.4: 0.6 wall + 0.4 deep, plus the top.
    let top = [0.05, 0.1, 0.15];
    let want: Vec<f32> = (0..3).map(|k| top[k] + 0.6 * WALL[k] + 0.4 * ENV[k]).collect();
    close3(got, [want[0], want[1], want[2]], 1e-6);
    let none = scene(&refraction(0.05, r#", "top_material" "basesh""#).replace("\"samples\" 8", "\"samples\" 0"));
    close3(shade(&none, &Empty::default(), oblique()), top, 0.0);
}
