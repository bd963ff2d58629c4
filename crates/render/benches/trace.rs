//! Speed of the renderer, for each backend compiled in:
//! - incoherent rays: the same 200 000 random rays in the seed Cornell box and in a
//!   generated 1 M-triangle scene (closest hit), reported as rays per second;
//! - path tracing: samples per second on the Cornell box at 64×64 (a 256×256 render is
//!   16 times the work per sample count).
//!
//! Run with `cargo bench -p render --bench trace` (Mrays/s = elements/s ÷ 10⁶).

use std::fmt::Write;
use std::sync::atomic::AtomicBool;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3A;
use render::accel::{self, Backend};
use render::ray::Ray;
use render::World;

fn world(text: &str) -> World {
    let parsed = mi::parse_str("bench.mi", text);
    let mut diags = Vec::new();
    World::from_scene(&scene::Scene::build(&parsed, 0, &mut diags).expect("scene builds"))
}

/// A wavy 1 M-triangle terrain seen from above, with a point light.
fn big_scene() -> String {
    let side = 708;
    let mut s = String::from(
        "options \"o\" end options\ncamera \"c\" focal 1 aperture 1 resolution 64 64 end camera\n\
         instance \"ci\" \"c\" transform 1 0 0 0 0 0 -1 0 0 1 0 0 -0.5 -0.5 -3 1 end instance\n",
    );
    let _ = write!(s, "object \"t\" trilist vertex {} p triangle {}\n[\n", (side + 1) * (side + 1), side * side * 2);
    for j in 0..=side {
        for i in 0..=side {
            let (u, v) = (i as f32 / side as f32, j as f32 / side as f32);
            let _ = writeln!(s, "{u} {v} {}", 0.02 * ((u * 40.0).sin() + (v * 31.0).cos()));
        }
    }
    s.push_str("]\n[\n");
    let row = side + 1;
    for j in 0..side {
        for i in 0..side {
            let a = j * row + i;
            let _ = writeln!(s, "{} {} {} {} {} {}", a, a + 1, a + row + 1, a, a + row + 1, a + row);
        }
    }
    s.push_str("]\nend trilist end object\ninstance \"ti\" \"t\" end instance\ninstgroup \"root\" \"ci\" \"ti\" end instgroup\nrender \"root\" \"ci\" \"o\"\n");
    s
}

/// Random rays from points inside `lo..hi` in all directions.
fn rays(lo: Vec3A, hi: Vec3A, n: usize) -> Vec<Ray> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..n)
        .map(|_| {
            let o = lo + (hi - lo) * Vec3A::new(rnd(), rnd(), rnd());
            let z = 2.0 * rnd() - 1.0;
            let r = (1.0 - z * z).sqrt();
            let phi = std::f32::consts::TAU * rnd();
            Ray::new(o, Vec3A::new(r * phi.cos(), r * phi.sin(), z))
        })
        .collect()
}

fn backends() -> Vec<Backend> {
    [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()).collect()
}

fn bench(c: &mut Criterion) {
    let cornell = world(include_str!("../../../scenes/iray_cornell_box.mi"));
    let terrain = world(&big_scene());
    let cases = [
        ("cornell", &cornell, rays(Vec3A::new(20.0, 10.0, 10.0), Vec3A::new(530.0, 530.0, 550.0), 200_000)),
        ("terrain_1M", &terrain, rays(Vec3A::new(0.0, 0.0, 0.05), Vec3A::new(1.0, 1.0, 0.5), 200_000)),
    ];
    let mut group = c.benchmark_group("incoherent_rays");
    group.sample_size(10);
    for (name, w, rays) in &cases {
        for backend in backends() {
            let accel = accel::build(w, backend);
            group.throughput(Throughput::Elements(rays.len() as u64));
            group.bench_function(format!("{name}/{backend:?}"), |b| {
                b.iter(|| rays.iter().filter(|r| accel.intersect(r).is_some()).count())
            });
        }
    }
    group.finish();

    let mut small = cornell;
    small.camera.resize(64, 64);
    let mut group = c.benchmark_group("path_tracing");
    group.sample_size(10);
    for backend in backends() {
        let accel = accel::build(&small, backend);
        let settings = render::Settings { spp: Some(16), ..render::Settings::default() };
        group.throughput(Throughput::Elements(64 * 64 * 16));
        group.bench_function(format!("cornell_64x64_16spp/{backend:?}"), |b| {
            b.iter(|| render::render(&small, accel.as_ref(), None, &settings, &AtomicBool::new(false), &|_| {}).1)
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
