//! `mia_roundcorners`: rounds sharp edges and creases at render time by bending the
//! shading normal near them, as if the edge were a fillet; the geometry stays as it is.
//!
//! **Finding the edges.** Probe rays (ray type [`RayType::Probe`], which every instance
//! answers) leave the shading point along a ring of [`RING`] directions in the geometric
//! tangent plane, once from a little above the surface (on the side that faces the viewer)
//! and once from a little below it. Above-rays find the other side of concave creases (a
//! box standing on a floor); below-rays travel inside the solid and find the other face of
//! a convex edge from behind. A face hit from above keeps the normal facing the ray (it
//! faces the viewer's side), one hit from below is flipped (its outside is away from the
//! inside of the solid). With `allow_different_materials` off only faces of the shading
//! point's material count. Each face found defines a plane; the edge is where it meets the
//! plane of the shading point's face, and its distance `d` along that face is exact
//! whichever ring ray found it (the rays reach `radius / cos(π/RING)`, so every edge within
//! `radius` is seen by the ray nearest to its perpendicular). One face is counted once: a
//! plane seen from both sides (a box's bottom lying on a table) counts as seen from above.
//!
//! **The rounded normal.** For a face whose normal makes angle θ with the shading point's
//! face normal N, the normal turns towards it by
//! `α = θ/2 − asin((d / radius) · sin(θ/2))`: nothing at `d = radius`, the bisector of the
//! two faces on the edge (`d = 0`), continuous across the edge since the other face turns
//! towards this one the same way. That is the normal of a circular arc tangent to both faces
//! at distance `radius` from the edge, taken at the point whose projection across the
//! chord matches `d` (mira's reading of "rounds edges within `radius`": the manual gives no
//! profile). Several faces (near a box corner) add their turns: `normalize(N + Σ(Rᵢ − N))`,
//! kept in the hemisphere of the geometric normal. Far from edges (no face within
//! `radius`) the normal is returned untouched, bit for bit.
//!
//! **Modes** (`bump_mode`, as the manual lists them): 0 is the compatible mode: the `bump`
//! shader runs first (it perturbs the state's normal), the rounded normal replaces the
//! state's normal, and the shader returns 0 0 0. 1–4 "add" in internal (world for mira),
//! world, object, camera space: `bump_vector` (a perturbation in that space) is added to
//! the normal, the result rounded, and the difference from the unperturbed normal returned
//! in that space. 5–8 "set" in the same spaces: `bump_vector` (when not zero) is the normal
//! to start from and the rounded normal itself is returned. Pair the mode with the
//! material's (`mia_material_x`'s `bump_mode` for `overall_bump`/`bump`).

use std::f32::consts::PI;

use glam::Vec3A;

use bsdf::Frame;
use shader::{Ctx, NodeId, RayType, ShaderImpl, Tag, Value};

/// Probe directions in the tangent plane (each cast from above and from below).
pub const RING: usize = 16;

/// Height of the probe rays' origins above and below the surface, as a fraction of the
/// radius.
const LIFT: f32 = 0.02;

/// `mia_roundcorners (scalar radius, boolean allow_different_materials, shader bump,
/// integer bump_mode, vector bump_vector)` → vector. See the module documentation.
pub static MIA_ROUNDCORNERS: ShaderImpl = ShaderImpl {
    name: "mia_roundcorners",
    params: &["radius", "allow_different_materials", "bump", "bump_mode", "bump_vector"],
    run: roundcorners,
    ..ShaderImpl::PLAIN
};

fn roundcorners(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let radius = ctx.scalar(n, 0);
    let allow = ctx.bool(n, 1);
    let mode = ctx.int(n, 3);
    if mode <= 0 || mode > 8 {
        if let Some(Tag::Shader(b)) = ctx.tag(n, 2) {
            let mut tmp = Value::Null;
            ctx.call(b, &mut tmp);
        }
        let start = ctx.state.normal;
        let rounded = rounded_normal(ctx, radius, allow, start);
        ctx.state.normal = rounded;
        ctx.state.dot_nd = rounded.dot(ctx.state.dir);
        *out = Value::Vector(Vec3A::ZERO);
        return true;
    }
    let space = Space::of_mode(mode);
    let set = mode >= 5;
    let base = ctx.state.normal;
    let v = ctx.vector(n, 4);
    let start = if v == Vec3A::ZERO {
        base
    } else {
        let w = space.to_world(ctx, v);
        let s = if set { w } else { base + w };
        let s = s.normalize_or(base);
        if s.dot(ctx.state.normal_geom) < 0.0 && set {
            -s
        } else {
            s
        }
    };
    let rounded = rounded_normal(ctx, radius, allow, start);
    let world = if set { rounded } else { rounded - base };
    *out = Value::Vector(space.world_to(ctx, world));
    true
}

/// The space of a bump mode's vectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Space {
    /// mira's internal space (world).
    Internal,
    World,
    Object,
    Camera,
}

impl Space {
    fn of_mode(mode: i32) -> Space {
        match (mode - 1).rem_euclid(4) {
            0 => Space::Internal,
            1 => Space::World,
            2 => Space::Object,
            _ => Space::Camera,
        }
    }

    /// A normal (or normal perturbation) given in this space, in world space (transformed
    /// as normals are, as `mia_material_x` reads its bump vectors).
    fn to_world(self, ctx: &Ctx, v: Vec3A) -> Vec3A {
        match self {
            Space::Internal | Space::World => v,
            Space::Object => ctx.state.world_to_object.matrix3.transpose() * v,
            Space::Camera => ctx.shading().world_to_camera.matrix3.transpose() * v,
        }
    }

    /// The inverse of [`Space::to_world`].
    fn world_to(self, ctx: &Ctx, v: Vec3A) -> Vec3A {
        match self {
            Space::Internal | Space::World => v,
            Space::Object => ctx.state.object_to_world.matrix3.transpose() * v,
            Space::Camera => ctx.shading().world_to_camera.matrix3.transpose().inverse() * v,
        }
    }
}

/// A face found near the shading point.
#[derive(Clone, Copy, Debug)]
struct Face {
    /// Its outward normal (towards the viewer's side of the shading point), world space.
    normal: Vec3A,
    /// Distance from the shading point to the edge, along the shading point's face.
    dist: f32,
    /// The unit direction in the shading point's tangent plane towards which the normal
    /// turns (the face normal's projection).
    toward: Vec3A,
}

/// The normal `start` rounded against the faces within `radius` of the shading point; `start`
/// itself when there are none (or `radius` is not positive).
pub fn rounded_normal(ctx: &mut Ctx, radius: f32, allow_different_materials: bool, start: Vec3A) -> Vec3A {
    if !(radius > 0.0 && radius.is_finite()) {
        return start;
    }
    let faces = find_faces(ctx, radius, allow_different_materials);
    if faces.is_empty() {
        return start;
    }
    let ng = ctx.state.normal_geom;
    let mut sum = start;
    for f in &faces {
        let cos = f.normal.dot(ng).clamp(-1.0, 1.0);
        let half = 0.5 * cos.acos();
        let alpha = half - ((f.dist / radius).min(1.0) * half.sin()).asin();
        let turned = ng * alpha.cos() + f.toward * alpha.sin();
        sum += turned - ng;
    }
    let mut n = sum.normalize_or(start);
    // Stay in the geometric normal's hemisphere (only very sharp multi-face corners could
    // leave it).
    const MIN_COS: f32 = 0.05;
    let c = n.dot(ng);
    if c < MIN_COS {
        n = (n + ng * (MIN_COS - c)).normalize_or(ng);
    }
    n
}

/// The faces within `radius` of the shading point (see the module documentation).
fn find_faces(ctx: &mut Ctx, radius: f32, allow_different_materials: bool) -> Vec<Face> {
    let s = &ctx.state;
    let (p, ng, material) = (s.point, s.normal_geom, s.material);
    let frame = Frame::from_normal(ng);
    let lift = radius * LIFT;
    // Rays start a little behind the point so that a face right at it (closer than a
    // renderer's minimum hit distance) is still found.
    let back = radius * 1e-4;
    let reach = radius / (PI / RING as f32).cos() * 1.001 + back;
    let mut faces: Vec<Face> = Vec::new();
    for side in [1.0f32, -1.0] {
        let org = p + ng * (lift * side);
        for k in 0..RING {
            let phi = 2.0 * PI * k as f32 / RING as f32;
            let dir = frame.tangent * phi.cos() + frame.bitangent * phi.sin();
            let mut ray = ctx.state.child(RayType::Probe, org - dir * back, dir);
            if !ctx.tracer.intersect(&mut ray, reach) {
                continue;
            }
            if !allow_different_materials && ray.material != material {
                continue;
            }
            let normal = ray.normal_geom * side;
            let across = normal - ng * normal.dot(ng);
            let len = across.length();
            // (Nearly) parallel to the shading point's face: no edge to round.
            if len < 1e-3 {
                continue;
            }
            let dist = (normal.dot(ray.point - p) / len).abs();
            if dist.is_nan() || dist > radius {
                continue;
            }
            let same_plane = |f: &Face| f.normal.dot(normal).abs() > 0.9995 && (f.dist - dist).abs() <= 1e-3 * radius;
            if faces.iter().any(same_plane) {
                continue;
            }
            faces.push(Face { normal, dist, toward: across / len });
        }
    }
    faces
}

#[cfg(test)]
mod tests {
    use super::*;
    use shader::{Color, Shading, State, Tracer, VertexData};

    /// Axis-aligned boxes, each with a material: exact ray casting for probe rays.
    struct Boxes(Vec<(Vec3A, Vec3A, u32)>);

    impl Tracer for Boxes {
        fn intersect(&self, ray: &mut State, max_dist: f32) -> bool {
            let mut best: Option<(f32, Vec3A, u32)> = None;
            for &(lo, hi, m) in &self.0 {
                let inv = ray.dir.recip();
                let t0 = (lo - ray.org) * inv;
                let t1 = (hi - ray.org) * inv;
                let (near, far) = (t0.min(t1), t0.max(t1));
                let (tn, tf) = (near.max_element(), far.min_element());
                if tn > tf {
                    continue;
                }
                let (t, v) = if tn > 1e-6 { (tn, near) } else { (tf, far) };
                if t <= 1e-6 || t > max_dist || best.is_some_and(|b| b.0 <= t) {
                    continue;
                }
                let axis = if v.x == t {
                    Vec3A::X
                } else if v.y == t {
                    Vec3A::Y
                } else {
                    Vec3A::Z
                };
                best = Some((t, axis, m));
            }
            let Some((t, axis, m)) = best else { return false };
            let facing = if ray.dir.dot(axis) > 0.0 { -axis } else { axis };
            ray.dist = t;
            ray.point = ray.org + ray.dir * t;
            ray.normal = facing;
            ray.normal_geom = facing;
            ray.material = Some(m);
            true
        }
        fn shadow_hits(&self, _: &State, _: f32, _: &mut dyn FnMut(&State) -> bool) {}
        fn triangle(&self, _: &State, _: VertexData) -> Option<[Vec3A; 3]> {
            None
        }
        fn fb_put(&self, _: u32, _: Color) -> bool {
            false
        }
    }

    /// The unit cube [−1, 1]³ of material 0.
    fn cube() -> Boxes {
        Boxes(vec![(Vec3A::splat(-1.0), Vec3A::splat(1.0), 0)])
    }

    /// The rounded normal at `p` on a surface of normal `n` (facing the viewer), material 0.
    fn round_at(tracer: &Boxes, p: Vec3A, n: Vec3A, radius: f32, allow: bool) -> Vec3A {
        let shading = Shading::default();
        let state =
            State { point: p, normal: n, normal_geom: n, dir: -n, org: p + n, material: Some(0), ..State::default() };
        let mut ctx = Ctx::new(&shading, tracer, state);
        rounded_normal(&mut ctx, radius, allow, n)
    }

    #[test]
    fn far_from_edges_and_at_radius_zero_the_normal_is_untouched() {
        let cube = cube();
        for p in [Vec3A::new(0.0, 0.0, 1.0), Vec3A::new(0.5, -0.6, 1.0), Vec3A::new(0.89, 0.0, 1.0)] {
            assert_eq!(round_at(&cube, p, Vec3A::Z, 0.1, false), Vec3A::Z, "at {p}");
        }
        // Right at an edge, radius 0 (and nonsense radii) change nothing either.
        for r in [0.0, -1.0, f32::NAN] {
            assert_eq!(round_at(&cube, Vec3A::new(0.999, 0.0, 1.0), Vec3A::Z, r, false), Vec3A::Z);
        }
    }

    #[test]
    fn at_a_convex_edge_the_normal_is_the_bisector() {
        let cube = cube();
        // 0.001 from the edge x = 1 of the top face: α = 45° − asin(0.01 · sin 45°).
        let n = round_at(&cube, Vec3A::new(0.999, 0.3, 1.0), Vec3A::Z, 0.1, false);
        let bisector = Vec3A::new(1.0, 0.0, 1.0).normalize();
        assert!((n - bisector).length() < 0.01, "{n}");
        assert!((n.length() - 1.0).abs() < 1e-5);
        // The side face turns the same way: the two meet continuously.
        let m = round_at(&cube, Vec3A::new(1.0, 0.3, 0.999), Vec3A::X, 0.1, false);
        assert!((m - bisector).length() < 0.01, "{m}");
    }

    #[test]
    fn the_turn_follows_the_fillet_profile_and_is_monotone() {
        let cube = cube();
        let r = 0.2;
        let mut last = 0.0;
        for k in (0..=20).rev() {
            // From the radius to just off the edge (a point exactly on it is degenerate).
            let d = r * (0.002 + 0.998 * k as f32 / 20.0);
            let n = round_at(&cube, Vec3A::new(1.0 - d, 0.1, 1.0), Vec3A::Z, r, false);
            assert!((n.length() - 1.0).abs() < 1e-5 && n.z > 0.0, "unit, same hemisphere: {n}");
            let alpha = n.x.atan2(n.z);
            let want = PI / 4.0 - ((d / r) * (PI / 4.0).sin()).asin();
            assert!((alpha - want).abs() < 2e-3, "d {d}: α {alpha}, want {want}");
            assert!(alpha >= last - 1e-6, "turns more towards the edge");
            last = alpha;
        }
    }

    #[test]
    fn concave_creases_turn_away_from_the_wall_and_materials_can_be_told_apart() {
        // A floor (top at z = 0, material 0) and a wall standing on it at x ≥ 1 (material 1).
        let scene = Boxes(vec![
            (Vec3A::new(-5.0, -5.0, -1.0), Vec3A::new(5.0, 5.0, 0.0), 0),
            (Vec3A::new(1.0, -5.0, 0.0), Vec3A::new(2.0, 5.0, 5.0), 1),
        ]);
        let p = Vec3A::new(0.95, 0.0, 0.0);
        let n = round_at(&scene, p, Vec3A::Z, 0.1, true);
        // d = 0.05 of r = 0.1: α = 45° − asin(0.5 sin 45°) ≈ 24.3°, towards −x.
        let alpha = (-n.x).atan2(n.z);
        let want = PI / 4.0 - (0.5 * (PI / 4.0).sin()).asin();
        assert!((alpha - want).abs() < 2e-3, "α {alpha}, want {want}");
        assert!(n.z > 0.0 && (n.length() - 1.0).abs() < 1e-5);
        // The wall has another material: off, it does not count.
        assert_eq!(round_at(&scene, p, Vec3A::Z, 0.1, false), Vec3A::Z);
    }

    #[test]
    fn near_a_corner_both_edges_turn_the_normal() {
        let cube = cube();
        let n = round_at(&cube, Vec3A::new(0.97, 0.97, 1.0), Vec3A::Z, 0.1, false);
        assert!(n.x > 0.1 && (n.x - n.y).abs() < 1e-5 && n.z > 0.0, "{n}");
        assert!((n.length() - 1.0).abs() < 1e-5);
    }
}
