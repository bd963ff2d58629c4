//! What motion blur costs: the path engine on a field of 100 tessellated tiles (200
//! triangles each, 20 000 in all) lit by a point light, at 64×48 with 4 samples per pixel,
//! once with every tile still and once with 10 of them (10 % of the triangles) moving
//! under `motion transform`s over a box shutter, for each backend compiled in. The issue's
//! budget: the moving scene within 1.3× the static one's time.
//!
//! Run with `cargo bench -p render --bench motion`.

use std::fmt::Write;
use std::sync::atomic::AtomicBool;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::accel::{self, Backend};
use render::{EngineKind, Settings, World};

/// Tiles per side of the field, cells per side of a tile.
const TILES: usize = 10;
const CELLS: usize = 10;

/// The scene: `moving` tiles (every tenth) carry a motion transform 0.3 units sideways.
fn scene_text(moving: bool) -> String {
    let mut s = String::from(
        r#"options "opt" filter box 1 1 shadow on motion on shutter 0 1 end options
camera "cam" focal 1 aperture 1 aspect 1.333333 resolution 64 48 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0.8 0.6 0  0 -0.6 0.8 0  0 0 -14 1 end instance
light "key" "mib_light_point" ("color" 40 40 40, "shadow" on) origin 0 0 0 end light
instance "key_inst" "key" transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 -3 -6 1 end instance
material "m" "mib_illum_lambert" ("diffuse" 0.7 0.7 0.7, "lights" ["key_inst"]) end material
"#,
    );
    let mut members = String::from(r#""cam_inst" "key_inst""#);
    for t in 0..TILES * TILES {
        let (tx, ty) = ((t % TILES) as f32 - TILES as f32 / 2.0, (t / TILES) as f32 - TILES as f32 / 2.0);
        let _ = writeln!(s, r#"object "tile{t}" group"#);
        for j in 0..=CELLS {
            for i in 0..=CELLS {
                let (x, y) = (i as f32 / CELLS as f32 * 0.9, j as f32 / CELLS as f32 * 0.9);
                // A gentle bump so that the tiles are not flat.
                let z = 0.1 * ((x * 7.0).sin() * (y * 5.0).cos());
                let _ = writeln!(s, "    {} {} {z}", tx + x, ty + y);
            }
        }
        for v in 0..(CELLS + 1) * (CELLS + 1) {
            let _ = write!(s, " v {v}");
        }
        s.push('\n');
        for j in 0..CELLS {
            for i in 0..CELLS {
                let a = j * (CELLS + 1) + i;
                let _ = writeln!(s, r#"    c "m" {a} {} {} {}"#, a + 1, a + CELLS + 2, a + CELLS + 1);
            }
        }
        s.push_str("end group end object\n");
        let motion = if moving && t % 10 == 0 { "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -0.3 0 0 1" } else { "" };
        let _ = writeln!(s, r#"instance "tile{t}_inst" "tile{t}" material "m" {motion} end instance"#);
        let _ = write!(members, r#" "tile{t}_inst""#);
    }
    let _ = writeln!(s, r#"instgroup "root" {members} end instgroup"#);
    s.push_str(r#"render "root" "cam_inst" "opt""#);
    s
}

fn world(moving: bool) -> World {
    let parsed = mi::parse_str("motion.mi", &scene_text(moving));
    assert!(parsed.diagnostics.list.is_empty(), "parse diagnostics");
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("scene builds");
    let world = World::from_scene(&scene);
    assert_eq!(world.shutter.is_some(), moving);
    world
}

fn bench(c: &mut Criterion) {
    let settings = Settings { engine: EngineKind::Path, spp: Some(4), ..Settings::default() };
    let mut group = c.benchmark_group("tiles_64x48_4spp");
    group.throughput(Throughput::Elements(64 * 48 * 4));
    group.sample_size(10);
    for moving in [false, true] {
        let world = world(moving);
        for backend in [Backend::Rust, Backend::Embree] {
            if !backend.available() {
                continue;
            }
            let accel = accel::build(&world, backend);
            let name = format!("{}_{backend:?}", if moving { "moving10pct" } else { "static" });
            group.bench_function(name, |b| {
                b.iter(|| render::render(&world, accel.as_ref(), None, &settings, &AtomicBool::new(false), &|_| {}).1)
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
