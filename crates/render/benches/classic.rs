//! Speed of the classic engine, for each backend compiled in:
//! - samples per second on `scenes/classic_reflections.mi` (Ward and Phong highlights, a
//!   mirror floor, a refracting glass ball with transparent shadows, two lights with
//!   shadows, trace depth 4) at 96×64 with 4 samples per pixel;
//! - shadow-ray-heavy scenes: the seed Cornell box lit by a 4×4-sample area light with
//!   hard shadows ([`area_light_cornell`]), 64×64 at 4 samples per pixel, without and with
//!   final gathering (most of its rays are shadow rays).
//!
//! Run with `cargo bench -p render --bench classic`.

use std::sync::atomic::AtomicBool;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::accel::{self, Backend};
use render::{EngineKind, Settings, World};
use shader::{Shading, ShadingOptions};

/// The seed Cornell box (`scenes/iray_cornell_box.mi`) as a classic-engine scene: its three
/// MDL materials become `mib_illum_lambert` materials of the same colours and its lamp a
/// `mib_light_point` rectangle sampled 4×4 with hard shadows (`factor` 0); `finalgather`
/// adds final gathering (64 rays per point).
fn area_light_cornell(finalgather: bool) -> String {
    let text = include_str!("../../../scenes/iray_cornell_box.mi");
    let start = text.find("shader \"white\"").expect("the scene's first material");
    let end = text.find("#\n# Instance of the light source").expect("the light's instance");
    let lambert = |name: &str, rgb: &str| {
        format!("material \"{name}\" \"mib_illum_lambert\" (\"ambient\" 0 0 0 1, \"diffuse\" {rgb} 1, \"mode\" 3) end material\n")
    };
    let head = [lambert("white", "0.7 0.7 0.7"), lambert("green", "0.15 0.7 0.15"), lambert("red", "0.7 0.15 0.15")]
        .concat()
        + "light \"Light_lgt\" \"mib_light_point\" (\"color\" 0.8 0.8 0.8, \"shadow\" on, \"factor\" 0)\n\
           origin 0 0 0 rectangle 130 0 0  0 105 0  4 4\nend light\n";
    let options =
        if finalgather { "shadow on\n    finalgather on\n    finalgather accuracy 64 20" } else { "shadow on" };
    [&text[..start], &head, &text[end..]]
        .concat()
        .replace("$include \"base.mdl\"\n", "$include \"base.mi\"\n")
        .replace("$include \"::nvidia::core_definitions.mdl\"\n", "")
        .replace("shadow on", options)
}

/// Benchmarks the scene `text` (named `file` in messages) in the classic engine at 4 samples
/// per pixel, `pixels` pixels, on each backend compiled in, as the group `name`.
fn bench_scene(c: &mut Criterion, name: &str, file: &str, text: &str, pixels: u64) {
    let parsed = mi::parse_str(file, text);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("scene builds");
    let world = World::from_scene(&scene);
    let (shading, _) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    let settings = Settings { engine: EngineKind::Classic, spp: Some(4), ..Settings::default() };
    let mut group = c.benchmark_group(name);
    group.throughput(Throughput::Elements(pixels * 4));
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

fn bench(c: &mut Criterion) {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/classic_reflections.mi"))
        .expect("the scene")
        .replace("resolution 600 400", "resolution 96 64");
    bench_scene(c, "classic_reflections_96x64_4spp", "classic_reflections.mi", &text, 96 * 64);
    for finalgather in [false, true] {
        let text = area_light_cornell(finalgather).replace("resolution 1024 1024", "resolution 64 64");
        let name = if finalgather { "area_light_cornell_fg_64x64_4spp" } else { "area_light_cornell_64x64_4spp" };
        bench_scene(c, name, "area_light_cornell.mi", &text, 64 * 64);
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
