//! What the per-hit tests (`mdl_per_hit`, `mdl_per_hit_curves`) share: a shading point
//! driven by the texture coordinate u, a material evaluated there, and the direction
//! pairs their BSDFs are compared at, and the `.mi` text of a varying material and its
//! constant twins.

use glam::Vec3A;
use material::{HitMaterial, SurfaceMaterial, Varying};
use shader::State;

/// A shading point with texture coordinate (u, 0.5), world position (u, 0.5, 0), normal +z.
pub fn uv(u: f32) -> State {
    let mut s = State {
        tex_count: 1,
        normal: Vec3A::Z,
        normal_geom: Vec3A::Z,
        dir: -Vec3A::Z,
        point: Vec3A::new(u, 0.5, 0.0),
        ..State::default()
    };
    s.tex_list[0] = Vec3A::new(u, 0.5, 0.0);
    s
}

/// The material `m` evaluated at texture coordinate u.
pub fn at(m: &SurfaceMaterial, u: f32) -> HitMaterial<'_> {
    let Varying::Evaluated(hit) = &m.varying else { panic!("{} is not evaluated per hit: {:?}", m.name, m.varying) };
    let mut h = m.constant();
    hit.0.apply(&uv(u), &mut h);
    h
}

/// Directions for comparing BSDFs: 23 on the sphere, every pair.
pub fn direction_pairs() -> Vec<(Vec3A, Vec3A)> {
    let dirs: Vec<Vec3A> = (1..24)
        .map(|i| {
            let u = bsdf::testing::r2(i);
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * u.y;
            Vec3A::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect();
    dirs.iter().flat_map(|a| dirs.iter().map(move |b| (*a, *b))).collect()
}

/// The `.mi` text of shader "v", module `module`'s material `varying`, and shaders "c0",
/// "c1", … of its material `constant` with the parameters of each twin (u, parameters).
pub fn twins_text(module: &str, varying: &str, constant: &str, twins: &[(f32, &str)]) -> String {
    let mut text = format!("shader \"v\" \"mdl::{module}::{varying}\" ()\n");
    for (k, (_, params)) in twins.iter().enumerate() {
        text += &format!("shader \"c{k}\" \"mdl::{module}::{constant}\" ({params})\n");
    }
    text
}
