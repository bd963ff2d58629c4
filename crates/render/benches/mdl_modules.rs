//! Speed of MDL module materials against the equivalent built-in definitions, rendered by
//! the path engine (the issue's budget: within 10 %):
//! - `constant`: the Cornell box of scenes/mdl/cornell_mdl.mi, walls of the module's
//!   `matte`, against the same box with `::nvidia::core_definitions::diffuse` walls;
//! - `textured`: a square painted by a 4×4 texture under a directional light, the module
//!   material scenes/mdl/painted.mdl's `painted` (a `base::file_texture` inside the module,
//!   evaluated per hit as compiled expressions) against the built-in `diffuse` whose
//!   `diffuse_color` is connected to `mdl::base::file_texture` (run through the shader
//!   graph per hit).
//!
//! Run with `cargo bench -p render --bench mdl_modules`.

#[path = "../tests/it/support/mod.rs"]
mod support;

use std::sync::atomic::AtomicBool;

use criterion::{criterion_group, criterion_main, Criterion};
use render::{EngineKind, Settings};
use support::QUADRANTS;

/// The scene `text` built for the path engine at `res`², with MDL modules from scenes/mdl.
fn build(text: &str, res: u32) -> render::pipeline::Built {
    let b = support::build_parsed(&mi::parse_str("bench.mi", text), res, &[support::mdl_modules()]);
    assert!(b.built.world.warnings.is_empty(), "{:?}", b.built.world.warnings);
    b.built
}

/// The lit square of [`support::lit_square`] painted by the quadrants texture through
/// `material` (which defines "mat").
fn textured(material: &str) -> String {
    support::lit_square(&format!("{QUADRANTS}\n{material}"), "mat")
}

fn bench(c: &mut Criterion) {
    let cornell = include_str!("../../../scenes/mdl/cornell_mdl.mi").replace("$include \"export_multi.mdl\"", "");
    let module_box = format!("$include \"export_multi.mdl\"\n{cornell}");
    let builtin_box = cornell
        .replace("mdl::export_multi::matte", "mdl::nvidia::core_definitions::diffuse")
        .replace("\"tint\"", "\"diffuse_color\"");
    let module_square = textured(r#"shader "mat" "mdl::painted::painted" ("tex" "quadrants")"#);
    let builtin_square = textured(
        r#"shader "uvw" "mdl::base::coordinate_source" ("texture_space" 0)
shader "tex" "mdl::base::file_texture" ("texture" "quadrants", "uvw" = "uvw")
shader "mat" "mdl::nvidia::core_definitions::diffuse" ("diffuse_color" = "tex.tint")"#,
    );
    let cases = [
        ("constant/module", build(&module_box, 64)),
        ("constant/builtin", build(&builtin_box, 64)),
        ("textured/module", build(&module_square, 64)),
        ("textured/builtin", build(&builtin_square, 64)),
    ];
    let mut group = c.benchmark_group("mdl_modules");
    group.sample_size(20);
    let settings = Settings { engine: EngineKind::Path, spp: Some(4), ..Settings::default() };
    for (name, built) in &cases {
        let accel = render::accel::build(&built.world, render::Backend::default_available());
        group.bench_function(*name, |b| {
            b.iter(|| {
                render::render(
                    &built.world,
                    accel.as_ref(),
                    Some(&built.shading),
                    &settings,
                    &AtomicBool::new(false),
                    &|_| {},
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
