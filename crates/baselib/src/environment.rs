//! Environment and background lookups: spherical, cubic and cylindrical projections of
//! textures around the scene, and the screen-space background plate.

use std::f32::consts::PI;

use glam::{Vec3A, Vec4};

use shader::{Color, Ctx, NodeId, ShaderImpl, Value};

/// Looks texture parameter `i` up at (u, v); transparent black if it has no value there.
fn lookup(ctx: &mut Ctx, n: NodeId, i: usize, u: f32, v: f32) -> Color {
    match ctx.tag(n, i) {
        Some(tag) => ctx.lookup_color_texture(tag, Vec3A::new(u, v, 0.0)).unwrap_or(Vec4::ZERO),
        None => Vec4::ZERO,
    }
}

/// `mib_lookup_spherical (vector dir, scalar rotate, color texture tex)`: a latitude–
/// longitude map around the scene. The direction is `dir`, or the ray's when `dir` is
/// zero; u = frac(−atan2(x, z)/2π + rotate/π) (so u = 0 lies along +Z, and rotate = π
/// is a full turn, as mental ray's source has it), v = asin(y)/π + ½ (v = 0 straight down).
pub static SPHERICAL: ShaderImpl =
    ShaderImpl { name: "mib_lookup_spherical", params: &["dir", "rotate", "tex"], run: spherical, ..ShaderImpl::PLAIN };

/// The (u, v) of direction `d` in mental ray's spherical environment mapping.
pub fn spherical_uv(d: Vec3A, rotate: f32) -> (f32, f32) {
    let len = d.length();
    let u = -d.x.atan2(d.z) / (2.0 * PI) + rotate / PI;
    let u = u - u.floor();
    let v = (d.y / len).clamp(-1.0, 1.0).asin() / PI + 0.5;
    (u, v.min(0.999_999))
}

fn spherical(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let d = ctx.vector(n, 0);
    let d = if d == Vec3A::ZERO { ctx.state.dir } else { d };
    if d == Vec3A::ZERO {
        return false;
    }
    let (u, v) = spherical_uv(d, ctx.scalar(n, 1));
    *out = Value::Color(lookup(ctx, n, 2, u, v));
    true
}

/// `mib_lookup_background (vector zoom, vector pan, boolean torus_u, boolean torus_v,
/// color texture tex)`: a plate behind the scene in screen space: u, v are the raster
/// position over the resolution (× 0.9999), then `pan + zoom ⊙ (u, v)` (zero zoom: 1);
/// `torus` repeats the plate, otherwise it ends at its edges.
pub static BACKGROUND: ShaderImpl = ShaderImpl {
    name: "mib_lookup_background",
    params: &["zoom", "pan", "torus_u", "torus_v", "tex"],
    run: background,
    ..ShaderImpl::PLAIN
};

fn background(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (w, h) = ctx.shading().resolution;
    let zoom = ctx.vector(n, 0);
    let pan = ctx.vector(n, 1);
    let zx = if zoom.x == 0.0 { 1.0 } else { zoom.x };
    let zy = if zoom.y == 0.0 { 1.0 } else { zoom.y };
    let mut u = pan.x + zx * ctx.state.raster.x / w.max(1) as f32 * 0.9999;
    let mut v = pan.y + zy * ctx.state.raster.y / h.max(1) as f32 * 0.9999;
    if ctx.bool(n, 2) {
        u -= u.floor();
    }
    if ctx.bool(n, 3) {
        v -= v.floor();
    }
    *out = Value::Color(if (0.0..1.0).contains(&u) && (0.0..1.0).contains(&v) {
        lookup(ctx, n, 4, u, v)
    } else {
        Vec4::ZERO
    });
    true
}

/// Where a ray from `org` along `dir` meets the box of half-size `half` centred at the
/// origin, as mental ray's cube lookups test it (+x, −x, then y, then z planes, each
/// needing the matching sign of `dir`): the face (0 −x, 1 +x, 2, 3 the z planes, 4, 5 the
/// y planes — the source's z-up names) and (u, v) in [0, 1)² on it.
pub fn cube_face(org: Vec3A, dir: Vec3A, half: Vec3A) -> Option<(usize, f32, f32)> {
    let (sx, sy, sz) = (half.x, half.y, half.z);
    let unit = |a: f32, s: f32| 0.5 * (a / s + 1.0);
    let inside = |a: f32, s: f32| a.abs() <= s;
    let hit = |axis: usize, wall: f32| {
        let t = (wall - org[axis]) / dir[axis];
        (t >= 0.0).then(|| org + dir * t)
    };
    let f = |x: f32| x - x.floor();
    if dir.x > 0.0 {
        if let Some(p) = hit(0, sx).filter(|p| inside(p.y, sy) && inside(p.z, sz)) {
            return Some((1, f(1.0 - unit(p.y, sy)), f(unit(p.z, sz))));
        }
    }
    if dir.x < 0.0 {
        if let Some(p) = hit(0, -sx).filter(|p| inside(p.y, sy) && inside(p.z, sz)) {
            return Some((0, f(unit(p.y, sy)), f(unit(p.z, sz))));
        }
    }
    if dir.y < 0.0 {
        if let Some(p) = hit(1, -sy).filter(|p| inside(p.x, sx) && inside(p.z, sz)) {
            return Some((4, f(1.0 - unit(p.x, sx)), f(unit(p.z, sz))));
        }
    }
    if dir.y > 0.0 {
        if let Some(p) = hit(1, sy).filter(|p| inside(p.x, sx) && inside(p.z, sz)) {
            return Some((5, f(unit(p.x, sx)), f(unit(p.z, sz))));
        }
    }
    if dir.z > 0.0 {
        if let Some(p) = hit(2, sz).filter(|p| inside(p.x, sx) && inside(p.y, sy)) {
            return Some((3, f(unit(p.x, sx)), f(unit(p.y, sy))));
        }
    }
    if dir.z < 0.0 {
        if let Some(p) = hit(2, -sz).filter(|p| inside(p.x, sx) && inside(p.y, sy)) {
            return Some((2, f(unit(p.x, sx)), f(unit(p.y, sy))));
        }
    }
    None
}

fn cube_lookup(ctx: &mut Ctx, n: NodeId) -> Option<(usize, f32, f32)> {
    let point = ctx.vector(n, 0);
    let dir = ctx.vector(n, 1).normalize_or_zero();
    let half = ctx.vector(n, 2) * 0.5;
    if half.x <= 0.0 || half.y <= 0.0 || half.z <= 0.0 {
        return None;
    }
    cube_face(point, dir, half)
}

/// `mib_lookup_cube1 (vector point, vector dir, vector size, color texture tex)`: where
/// the ray from `point` along `dir` meets the box of `size` around the origin, in one
/// texture holding the six faces side by side (face k over u in [k/6, (k+1)/6)).
pub static CUBE1: ShaderImpl =
    ShaderImpl { name: "mib_lookup_cube1", params: &["point", "dir", "size", "tex"], run: cube1, ..ShaderImpl::PLAIN };

fn cube1(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some((face, u, v)) = cube_lookup(ctx, n) else {
        *out = Value::Color(Vec4::ZERO);
        return false;
    };
    *out = Value::Color(lookup(ctx, n, 3, (u + face as f32) / 6.0, v));
    true
}

/// `mib_lookup_cube6 (vector point, vector dir, vector size, color texture tex_mx …
/// tex_pz)`: as `mib_lookup_cube1` with one texture per face.
pub static CUBE6: ShaderImpl = ShaderImpl {
    name: "mib_lookup_cube6",
    params: &["point", "dir", "size", "tex_mx", "tex_px", "tex_my", "tex_py", "tex_mz", "tex_pz"],
    run: cube6,
    ..ShaderImpl::PLAIN
};

fn cube6(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some((face, u, v)) = cube_lookup(ctx, n) else {
        *out = Value::Color(Vec4::ZERO);
        return false;
    };
    *out = Value::Color(lookup(ctx, n, 3 + face, u, v));
    true
}

/// `mib_lookup_cylindrical (transform xform, scalar begin, scalar end, color texture
/// tex)`: the cylinder x² + y² = 1, z in [−1, 1], of the space `xform` maps the point and
/// direction into; u is the angle around z over 2π (counter-clockwise from +x), v = (z +
/// 1)/2. With `begin`/`end` (radians) not both 0, only angles between them are textured.
/// A ray that misses leaves the result as it was and fails.
pub static CYLINDRICAL: ShaderImpl = ShaderImpl {
    name: "mib_lookup_cylindrical",
    params: &["xform", "begin", "end", "tex"],
    run: cylindrical,
    ..ShaderImpl::PLAIN
};

fn cylindrical(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let m = ctx.eval(n, 0).transform();
    let m = if m == glam::Mat4::ZERO { glam::Mat4::IDENTITY } else { m };
    let o = m.transform_point3(ctx.state.point.into());
    let d = m.transform_vector3(ctx.state.dir.into()).normalize_or_zero();
    let a = d.x * d.x + d.y * d.y;
    if a == 0.0 {
        return false;
    }
    let b = o.x * d.x + o.y * d.y;
    let c = o.x * o.x + o.y * o.y - 1.0;
    let disc = b * b - a * c;
    if disc < 0.0 {
        return false;
    }
    let (t0, t1) = ((-b - disc.sqrt()) / a, (-b + disc.sqrt()) / a);
    let in_z = |t: f32| (-1.0..=1.0).contains(&(o.z + d.z * t));
    let t = if t0 > 0.0 && in_z(t0) {
        t0
    } else if t1 > 0.0 && in_z(t1) {
        t1
    } else {
        return false;
    };
    let p = o + d * t;
    let phi = p.y.atan2(p.x).rem_euclid(2.0 * PI);
    let (begin, end) = (ctx.scalar(n, 1), ctx.scalar(n, 2));
    let restricted = begin != 0.0 || end != 0.0;
    if restricted && !(begin..=end).contains(&phi) {
        return false;
    }
    let (u, v) = (phi / (2.0 * PI), (p.z + 1.0) * 0.5);
    let Some(tag) = ctx.tag(n, 3) else { return false };
    match ctx.lookup_color_texture(tag, Vec3A::new(u.min(0.999_999), v.min(0.999_999), 0.0)) {
        Some(c) => {
            *out = Value::Color(c);
            true
        }
        None => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spherical_mapping_puts_u0_along_z_and_v_up() {
        let (u, v) = spherical_uv(Vec3A::Z, 0.0);
        assert!(u.abs() < 1e-6 && (v - 0.5).abs() < 1e-6);
        let (_, v) = spherical_uv(Vec3A::Y, 0.0);
        assert!((v - 1.0).abs() < 1e-5);
        let (_, v) = spherical_uv(-Vec3A::Y, 0.0);
        assert!(v.abs() < 1e-6);
        // −X is a quarter turn: u = −atan2(−1, 0)/2π = 0.25.
        let (u, _) = spherical_uv(-Vec3A::X, 0.0);
        assert!((u - 0.25).abs() < 1e-6);
        // rotate = π/2 adds half a turn.
        let (u, _) = spherical_uv(Vec3A::Z, PI / 2.0);
        assert!((u - 0.5).abs() < 1e-6);
    }

    #[test]
    fn cube_faces_follow_mental_rays_table() {
        let half = Vec3A::splat(1.0);
        assert_eq!(cube_face(Vec3A::ZERO, Vec3A::X, half).unwrap().0, 1);
        assert_eq!(cube_face(Vec3A::ZERO, -Vec3A::X, half).unwrap().0, 0);
        assert_eq!(cube_face(Vec3A::ZERO, Vec3A::Y, half).unwrap().0, 5);
        assert_eq!(cube_face(Vec3A::ZERO, -Vec3A::Y, half).unwrap().0, 4);
        assert_eq!(cube_face(Vec3A::ZERO, Vec3A::Z, half).unwrap().0, 3);
        assert_eq!(cube_face(Vec3A::ZERO, -Vec3A::Z, half).unwrap().0, 2);
        // On +z at (x, y) = (0.5, 0.5): u = v = 0.75.
        let (face, u, v) = cube_face(Vec3A::ZERO, Vec3A::new(0.5, 0.5, 1.0), half).unwrap();
        assert_eq!(face, 3);
        assert!((u - 0.75).abs() < 1e-6 && (v - 0.75).abs() < 1e-6);
        // On +x the u axis runs against y.
        let (_, u, _) = cube_face(Vec3A::ZERO, Vec3A::new(1.0, 0.5, 0.0), half).unwrap();
        assert!((u - 0.25).abs() < 1e-6);
    }
}
