//! Cost of a filtered Ptex lookup (`Ptex::sample`, bilinear) against a level-0 one: four
//! quad faces of 16 × 16 texels around a vertex (each adjoining two others), with reduced
//! levels of 8 × 8, 4 × 4, 2 × 2 and the average, 1024 lookups a run at points spread over
//! the four faces (a fixed sequence).
//!
//! - `level0`: no width (level 0; 1/8 of the points within half a texel of an edge);
//! - `width_0.25`: level 2 (4 × 4: half the points near an edge, 1/16 in a corner);
//! - `width_1`: each face's average (one texel: every point near an edge or a corner);
//! - `width_0.35`: between levels 2 and 3 (4 × 4 and 2 × 2 texels: a blend of both, each
//!   read as its own width would read it).
//!
//! And the lookup at a hit (`Ptex::lookup_at`: the footprint's widths along u and v, then
//! `Ptex::sample_rect`) over the same points, from states on faces 1 scene unit a side
//! with a footprint of 0.25 (mdl44):
//!
//! - `at/head_on`: seen along the normal (isotropic: one lookup, as `width_0.25`);
//! - `at/75deg`: 75° off the normal, tilted along v (widths 0.25 and 0.97: 4 probes);
//! - `widths/75deg`: the widths alone (`footprint::filter_widths`).
//!
//! mdl45 (`lookup_at` reads the footprint's ellipse, `footprint::filter_ellipse`, then
//! `Ptex::sample_ellipse`):
//!
//! - `at/75deg_diagonal`: 75° off the normal, tilted along the faces' diagonal (major 0.97
//!   along (1, 1) / √2, minor 0.25: 3 probes; before mdl45 its bounding rectangle, equal
//!   widths: one isotropic lookup);
//! - `ellipse/75deg`, `ellipse/75deg_diagonal`: the ellipse alone;
//! - `rect/{head_on, 75deg, 75deg_diagonal}`: mdl44's reading at a hit (the bounding
//!   rectangle: `footprint::filter_widths`, then `Ptex::lookup_rect`), for comparison.
//!
//! Run with `cargo bench -p material --bench ptex_lookup`.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3A;
use material::mdl_modules::ptex::footprint::{filter_ellipse, filter_widths};
use material::mdl_modules::ptex::{Adjacency, FaceTexels, Filter, MeshType, Ptex};
use shader::State;

/// Four faces of 16 × 16 texels (face 0 lower left, 1 lower right, 2 upper right, 3 upper
/// left, u right, v up) with their reductions: box averages of varied texels.
fn texture() -> Ptex {
    let mut texels = Vec::new();
    let (mut faces, mut reductions) = (Vec::new(), Vec::new());
    for f in 0..4usize {
        let mut level: Vec<f32> = (0..256).map(|t| ((f * 37 + t * 13) % 29) as f32 / 28.0).collect();
        faces.push(FaceTexels { start: texels.len(), ulog2: 4, vlog2: 4 });
        texels.extend(&level);
        let mut levels = Vec::new();
        for log2 in (0..4u8).rev() {
            let n = 1usize << log2;
            let prev = std::mem::take(&mut level);
            let at = |x: usize, y: usize| prev[y * 2 * n + x];
            level = (0..n * n)
                .map(|t| {
                    let (x, y) = (2 * (t % n), 2 * (t / n));
                    (at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1)) / 4.0
                })
                .collect();
            levels.push(FaceTexels { start: texels.len(), ulog2: log2, vlog2: log2 });
            texels.extend(&level);
        }
        reductions.push(levels);
    }
    let edges = |e: [u8; 4]| e.iter().enumerate().fold(0u8, |b, (k, x)| b | x << (2 * k));
    let adjacency = vec![
        Adjacency { faces: [-1, 1, 3, -1], edges: edges([0, 3, 0, 0]) },
        Adjacency { faces: [-1, -1, 2, 0], edges: edges([0, 0, 0, 1]) },
        Adjacency { faces: [1, -1, -1, 3], edges: edges([2, 0, 0, 1]) },
        Adjacency { faces: [0, 2, -1, -1], edges: edges([2, 3, 0, 0]) },
    ];
    Ptex { mesh: MeshType::Quad, channels: 1, alpha: None, faces, reductions, adjacency, subfaces: Vec::new(), texels }
}

fn bench(c: &mut Criterion) {
    let ptex = texture();
    let mut state = 12345u32;
    let mut next = || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    let points: Vec<(u32, f32, f32)> = (0..1024).map(|k| ((k % 4) as u32, next(), next())).collect();
    for (name, width) in
        [("level0", None), ("width_0.25", Some(0.25)), ("width_1", Some(1.0)), ("width_0.35", Some(0.35))]
    {
        c.bench_function(&format!("ptex_lookup/{name}"), |b| {
            b.iter(|| {
                let mut sum = 0.0f32;
                let mut out = [0.0f32; 1];
                for &(face, u, v) in &points {
                    ptex.sample(face, u, v, width, Filter::Bilinear, 0, &mut out);
                    sum += out[0];
                }
                std::hint::black_box(sum)
            });
        });
    }
    let (sin, cos) = (75f32.to_radians().sin(), 75f32.to_radians().cos());
    let diagonal = Vec3A::new(sin * std::f32::consts::FRAC_1_SQRT_2, sin * std::f32::consts::FRAC_1_SQRT_2, -cos);
    for (name, dir) in [("head_on", -Vec3A::Z), ("75deg", Vec3A::new(0.0, sin, -cos)), ("75deg_diagonal", diagonal)] {
        let states: Vec<State> = points
            .iter()
            .map(|&at| State {
                dir,
                normal_geom: Vec3A::Z,
                camera_footprint: 0.25,
                tri_area: 0.5,
                face_edges: [Vec3A::X, Vec3A::new(1.0, 1.0, 0.0)],
                ptex_quad_jacobian: [1.0, 0.0, 1.0, 1.0],
                ptex_quad: Some(at),
                ..State::default()
            })
            .collect();
        c.bench_function(&format!("ptex_lookup/at/{name}"), |b| {
            b.iter(|| {
                let sum: f32 = states.iter().map(|s| ptex.lookup_at(s, 0).x).sum();
                std::hint::black_box(sum)
            });
        });
        c.bench_function(&format!("ptex_lookup/rect/{name}"), |b| {
            b.iter(|| {
                let sum: f32 = states
                    .iter()
                    .map(|s| {
                        let (face, u, v) = s.ptex_quad.unwrap_or_default();
                        ptex.lookup_rect(face, u, v, filter_widths(MeshType::Quad, s), 0).x
                    })
                    .sum();
                std::hint::black_box(sum)
            });
        });
        if name != "head_on" {
            c.bench_function(&format!("ptex_lookup/ellipse/{name}"), |b| {
                b.iter(|| {
                    let sum: f32 =
                        states.iter().filter_map(|s| filter_ellipse(MeshType::Quad, s)).map(|e| e.major).sum();
                    std::hint::black_box(sum)
                });
            });
        }
        if name == "75deg" {
            c.bench_function(&format!("ptex_lookup/widths/{name}"), |b| {
                b.iter(|| {
                    let sum: f32 =
                        states.iter().filter_map(|s| filter_widths(MeshType::Quad, s)).map(|(u, v)| u + v).sum();
                    std::hint::black_box(sum)
                });
            });
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
