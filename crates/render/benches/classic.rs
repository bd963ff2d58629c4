//! Speed of the classic engine: samples per second on `scenes/classic_reflections.mi`
//! (Ward and Phong highlights, a mirror floor, a refracting glass ball with transparent
//! shadows, two lights with shadows, trace depth 4) at 96×64 with 4 samples per pixel,
//! for each backend compiled in.
//!
//! Run with `cargo bench -p render --bench classic`.

use std::sync::atomic::AtomicBool;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::accel::{self, Backend};
use render::{EngineKind, Settings, World};
use shader::{Shading, ShadingOptions};

fn bench(c: &mut Criterion) {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/classic_reflections.mi"))
        .expect("the scene")
        .replace("resolution 600 400", "resolution 96 64");
    let parsed = mi::parse_str("classic_reflections.mi", &text);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("scene builds");
    let world = World::from_scene(&scene);
    let (shading, _) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    let settings = Settings { engine: EngineKind::Classic, spp: Some(4), ..Settings::default() };
    let mut group = c.benchmark_group("classic_reflections_96x64_4spp");
    group.throughput(Throughput::Elements(96 * 64 * 4));
    group.sample_size(10);
    for backend in [Backend::Rust, Backend::Embree] {
        if !backend.available() {
            continue;
        }
        let accel = accel::build(&world, backend);
        group.bench_function(format!("{backend:?}"), |b| {
            b.iter(|| {
                render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {}).1
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
