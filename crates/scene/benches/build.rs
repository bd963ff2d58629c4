//! World building speed (parsing excluded): a 1 M-triangle object, and 1 000 instances of a
//! 10 k-triangle object. Target: under a second each on one core.
//!
//! Run with `cargo bench -p scene --bench build`.

use std::fmt::Write;

use criterion::{criterion_group, criterion_main, Criterion};

const HEADER: &str =
    "options \"o\" end options\ncamera \"c\" resolution 64 64 end camera\ninstance \"ci\" \"c\" end instance\n";

/// A `side`×`side` grid of quads as a trilist object named `name`.
fn grid(name: &str, side: usize) -> String {
    let mut s = format!(
        "object \"{name}\" visible on trilist vertex {} p n triangle {}\n[\n",
        (side + 1) * (side + 1),
        side * side * 2
    );
    for j in 0..=side {
        for i in 0..=side {
            let _ = writeln!(
                s,
                "{} {} {} 0 0 1",
                i as f32 / side as f32,
                j as f32 / side as f32,
                ((i * 7 + j * 3) % 11) as f32 * 0.01
            );
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
    s.push_str("]\nend trilist end object\nmaterial \"m\" \"x\" () end material\n");
    s
}

fn one_big_object() -> String {
    let mut s = HEADER.to_string();
    s.push_str(&grid("big", 708));
    s.push_str("instance \"bi\" \"big\" material \"m\" end instance\ninstgroup \"root\" \"ci\" \"bi\" end instgroup\nrender \"root\" \"ci\" \"o\"\n");
    s
}

fn many_instances() -> String {
    let mut s = HEADER.to_string();
    s.push_str(&grid("tile", 71));
    let mut group = String::from("instgroup \"root\" \"ci\"");
    for k in 0..1000 {
        let _ = writeln!(
            s,
            "instance \"t{k}\" \"tile\" material \"m\" transform 1 0 0 0 0 1 0 0 0 0 1 0 {} {} 0 1 end instance",
            -(k % 32) as f32,
            -(k / 32) as f32
        );
        let _ = write!(group, " \"t{k}\"");
    }
    s.push_str(&group);
    s.push_str(" end instgroup\nrender \"root\" \"ci\" \"o\"\n");
    s
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    group.sample_size(10);
    for (name, text, triangles) in
        [("object_1M_triangles", one_big_object(), 1_002_528), ("instances_1000x10k", many_instances(), 10_082_000)]
    {
        let parsed = mi::parse_str("bench.mi", &text);
        assert!(!parsed.diagnostics.has_errors());
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut diags = Vec::new();
                let s = scene::Scene::build(&parsed, 0, &mut diags).unwrap();
                assert_eq!(s.instanced_triangles(), triangles);
                s
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
