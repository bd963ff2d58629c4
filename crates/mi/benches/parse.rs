//! Parse speed on generated ASCII geometry: a 1 M-triangle `trilist` and a 1 M-polygon
//! `group` (the targets: at least 300 MB/s on one core).
//!
//! Run with `cargo bench -p mi --bench parse`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

mod gen;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("parse");
    group.sample_size(10);
    for (name, text) in
        [("trilist_1M_triangles", gen::trilist_scene(1_000_000)), ("group_1M_polygons", gen::group_scene(1_000_000))]
    {
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_function(name, |b| {
            b.iter(|| {
                let parsed = mi::parse_str("generated.mi", &text);
                assert!(!parsed.diagnostics.has_errors());
                parsed
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
