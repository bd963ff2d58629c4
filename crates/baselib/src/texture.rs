//! Texture coordinates, texture lookups and bump mapping.
//!
//! Texture coordinates are vectors (mental ray's texture spaces are 3-D); lookups use x and
//! y, with [0, 1)² covering an image once.

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Vec3A, Vec4};

use shader::{Ctx, NodeId, ShaderImpl, Tag, Value, VertexData};

fn frac(x: f32) -> f32 {
    x - x.floor()
}

/// Looks texture parameter `i` up at `coord`.
fn lookup(ctx: &mut Ctx, n: NodeId, i: usize, coord: Vec3A) -> Option<Vec4> {
    let tag = ctx.tag(n, i)?;
    ctx.lookup_color_texture(tag, coord)
}

/// `mib_texture_lookup (color texture tex, vector coord)`: the texture at `coord`;
/// transparent black (and failure) outside [0, 1)².
pub static LOOKUP: ShaderImpl =
    ShaderImpl { name: "mib_texture_lookup", params: &["tex", "coord"], run: tex_lookup, ..ShaderImpl::PLAIN };

fn tex_lookup(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let coord = ctx.vector(n, 1);
    let c = lookup(ctx, n, 0, coord);
    *out = Value::Color(c.unwrap_or(Vec4::ZERO));
    c.is_some()
}

/// `mib_texture_lookup2 (color texture tex, scalar factor)`: the texture at the first
/// texture space's coordinate times `factor` (not repeated: coordinates outside [0, 1)²
/// give transparent black).
pub static LOOKUP2: ShaderImpl =
    ShaderImpl { name: "mib_texture_lookup2", params: &["tex", "factor"], run: lookup2, ..ShaderImpl::PLAIN };

fn lookup2(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let f = ctx.scalar(n, 1);
    let t = ctx.state.tex(0);
    let coord = Vec3A::new(t.x * f, t.y * f, 0.0);
    let c = lookup(ctx, n, 0, coord);
    *out = Value::Color(c.unwrap_or(Vec4::ZERO));
    ctx.tag(n, 0).is_some()
}

/// `mib_texture_filter_lookup (color texture tex, vector coord, scalar eccmax, scalar
/// maxminor, scalar disc_r, boolean bilinear, integer space, shader remap)`: an elliptically
/// filtered (EWA) lookup of an image texture centred at `coord`. A screen disc of radius
/// `disc_r` pixels (0: 0.3) is projected into texture space `space` through the hit
/// triangle (the state's pixel differentials): three points — the hit's coordinate and
/// its steps of `disc_r` pixels along raster x and y — which the `remap` shader, if any,
/// maps (each handed to it as `state.tex_arg`, which `mib_texture_remap` takes in place of
/// its input). Their differences are the ellipse's conjugate semi-axes; it is limited to
/// eccentricity `eccmax` and filtered on the level where its minor axis spans `maxminor`
/// texels (see [`shader::texture::MipMap::ewa`]; 0: 20 and 6). `bilinear` interpolates
/// magnified footprints. Without differentials (unknown footprint), or for a texture
/// shader, the lookup is unfiltered; outside [0, 1)² transparent black (and failure).
pub static FILTER_LOOKUP: ShaderImpl = ShaderImpl {
    name: "mib_texture_filter_lookup",
    params: &["tex", "coord", "eccmax", "maxminor", "disc_r", "bilinear", "space", "remap"],
    run: filter_lookup,
    ..ShaderImpl::PLAIN
};

/// Most texture spaces `mib_texture_filter_lookup` addresses.
const MAX_FILTER_SPACE: i32 = 63;

fn filter_lookup(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let coord = ctx.vector(n, 1);
    *out = Value::Color(Vec4::ZERO);
    let tag = ctx.tag(n, 0);
    let image = match tag {
        Some(Tag::Texture(t)) => match ctx.shading().textures.get(t as usize) {
            Some(shader::texture::Texture::Image { image, .. }) => image.clone(),
            _ => return false,
        },
        Some(tag @ Tag::Shader(_)) => {
            let c = ctx.lookup_color_texture(tag, coord);
            *out = Value::Color(c.unwrap_or(Vec4::ZERO));
            return c.is_some();
        }
        _ => return false,
    };
    if !(0.0..1.0).contains(&coord.x) || !(0.0..1.0).contains(&coord.y) {
        return false;
    }
    let (eccmax, maxminor) = (ctx.scalar(n, 2), ctx.scalar(n, 3));
    let r = ctx.scalar(n, 4);
    let r = if r > 0.0 { r } else { 0.3 };
    let bilinear = ctx.bool(n, 5);
    let space = ctx.int(n, 6).clamp(0, MAX_FILTER_SPACE) as usize;
    let axes = filter_axes(ctx, n, space, r);
    let mut c = match axes {
        Some(axes) => {
            image.ewa(coord.x, coord.y, &shader::texture::mipmap::Ellipse { axes, eccmax, maxminor, bilinear })
        }
        None => image.lookup(coord.x, coord.y, 0.0),
    };
    if image.channels < 3 {
        let a = if image.channels == 2 { c.y } else { 1.0 };
        c = Vec4::new(c.x, c.x, c.x, a);
    }
    *out = Value::Color(c);
    true
}

/// The conjugate semi-axes of the projected disc of radius `r` pixels in texture space
/// `space`, after the `remap` shader; `None` without pixel differentials.
fn filter_axes(ctx: &mut Ctx, n: NodeId, space: usize, r: f32) -> Option<[glam::Vec2; 2]> {
    let s = &ctx.state;
    if s.point_derivs == [Vec3A::ZERO; 2] {
        return None;
    }
    let derivs = if space == 0 {
        (s.tex_count > 0).then_some(s.tex_derivs)?
    } else {
        let corners = ctx.tracer.triangle(s, VertexData::Point)?;
        let coords = ctx.tracer.triangle(s, VertexData::Texture(space))?;
        s.texture_derivs(corners, coords)?
    };
    let t0 = s.tex(space);
    let step = |d: glam::Vec2| Vec3A::new(d.x * r, d.y * r, 0.0);
    let mut pts = [t0, t0 + step(derivs[0]), t0 + step(derivs[1])];
    if let Some(Tag::Shader(remap)) = ctx.tag(n, 7) {
        let saved = ctx.state.tex;
        for p in &mut pts {
            ctx.flush_cache();
            ctx.state.tex_arg = Some(*p);
            ctx.state.tex = *p;
            *p = ctx.result(remap).vector();
        }
        ctx.state.tex_arg = None;
        ctx.state.tex = saved;
        ctx.flush_cache();
    }
    let axes = [pts[1] - pts[0], pts[2] - pts[0]].map(|v| glam::Vec2::new(v.x, v.y));
    axes.iter().all(|a| a.is_finite()).then_some(axes)
}

/// `mib_texture_vector (integer select, integer selspace, integer vertex, integer
/// project)`: a coordinate for texturing (numbering from mental images' source).
///
/// - `select`: ≥ 0 that texture space (zero and failure when the geometry has fewer); −1
///   the point, −2 the normal, −3 the motion vector, −4 the ray direction, −5 and −6 the
///   surface derivatives dP/du, dP/dv (−7…−9, the second derivatives, are zero), −10 the
///   raster position over the resolution, −11 the last texture coordinate computed.
/// - `selspace`: 0 internal and 2 world (the same in mira), 1 object, 3 camera, 4 the
///   raster position over the resolution (everything else ignored), 5 light (taken as
///   world).
/// - `vertex`: 0 the hit point, 1–3 that vertex of the hit triangle.
/// - `project`: 0 and 1 (UV) none, 2 xy, 3 xz, 4 yz, 5 spherical (u from +x towards −z,
///   v = asin(y/|p|)/π + ½), 6 cylindrical (u as spherical, v = y), 7 lollipop.
pub static VECTOR: ShaderImpl = ShaderImpl {
    name: "mib_texture_vector",
    params: &["select", "selspace", "vertex", "project"],
    run: tex_vector,
    ..ShaderImpl::PLAIN
};

/// mental ray's texture projections of a vector (`project` 2–7); false where the
/// projection is singular (the value is still written).
pub fn project(v: Vec3A, project: i32) -> (Vec3A, bool) {
    let around_y = |v: Vec3A| {
        if v.x == 0.0 && v.z == 0.0 {
            return (0.0, false);
        }
        let u = (-v.z).atan2(v.x) / (2.0 * PI);
        (if u < 0.0 { u + 1.0 } else { u }, true)
    };
    match project {
        2 => (Vec3A::new(v.x, v.y, 0.0), true),
        3 => (Vec3A::new(v.x, v.z, 0.0), true),
        4 => (Vec3A::new(v.y, v.z, 0.0), true),
        5 => {
            let (u, ok) = around_y(v);
            let len = v.length();
            let w = if len > 0.0 { (v.y / len).clamp(-1.0, 1.0).asin() / PI + 0.5 } else { 0.5 };
            (Vec3A::new(u, w, 0.0), ok)
        }
        6 => {
            let (u, ok) = around_y(v);
            (Vec3A::new(u, v.y, 0.0), ok)
        }
        7 => {
            let h = v.x.hypot(v.z);
            let r = if h == 0.0 && v.y == 0.0 { 0.0 } else { h.atan2(v.y) / (2.0 * PI) };
            if h > 0.0 {
                (Vec3A::new(0.5 - r / h * v.z, 0.5 - r / h * v.x, 0.0), true)
            } else {
                (Vec3A::new(0.5 + r, 0.5, 0.0), r == 0.0)
            }
        }
        _ => (v, true),
    }
}

fn tex_vector(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let select = ctx.int(n, 0);
    let mut space = ctx.int(n, 1);
    let vertex = ctx.int(n, 2);
    let proj = ctx.int(n, 3);
    let (w, h) = ctx.shading().resolution;
    let s = &ctx.state;
    let raster =
        |scale: f32| Vec3A::new(s.raster.x / w.max(1) as f32 * scale, s.raster.y / h.max(1) as f32 * scale, 0.0);
    if space == 4 {
        let r = raster(0.99999);
        ctx.state.tex = r;
        *out = Value::Vector(r);
        return true;
    }
    let from_vertex = |data: VertexData| -> Option<Vec3A> {
        let i = usize::try_from(vertex - 1).ok().filter(|i| *i < 3)?;
        ctx.tracer.triangle(s, data).map(|t| t[i])
    };
    let picked: Option<(Vec3A, bool)> = match select {
        k if k >= 0 => {
            let k = k as usize;
            if vertex > 0 {
                from_vertex(VertexData::Texture(k)).map(|v| (v, true))
            } else {
                (k < s.tex_count).then(|| (s.tex_list[k], true))
            }
        }
        -1 if vertex > 0 => from_vertex(VertexData::Point).map(|v| (v, true)),
        -1 => Some((s.point, true)),
        -2 if vertex > 0 => from_vertex(VertexData::Normal).map(|v| (v, false)),
        -2 => Some((s.normal, false)),
        -3 if vertex > 0 => from_vertex(VertexData::Motion).map(|v| (v, false)),
        -3 => Some((s.motion, false)),
        -4 => Some((s.dir, false)),
        -5 => Some((s.derivs[0], false)),
        -6 => Some((s.derivs[1], false)),
        -9..=-7 => Some((Vec3A::ZERO, false)),
        -10 => {
            space = 0;
            Some((raster(0.9999), true))
        }
        -11 => {
            space = 0;
            Some((s.tex, false))
        }
        _ => None,
    };
    let Some((v, is_point)) = picked else {
        *out = Value::Vector(Vec3A::ZERO);
        return false;
    };
    // Texture coordinates and points transform as points.
    let v = match space {
        1 if is_point => s.world_to_object.transform_point3a(v),
        1 if select == -2 => s.normal_to_object(v),
        1 => s.vector_to_object(v),
        3 => {
            let cam = &ctx.shading().world_to_camera;
            if is_point {
                cam.transform_point3a(v)
            } else {
                cam.transform_vector3a(v)
            }
        }
        _ => v,
    };
    let (v, ok) = project(v, proj);
    ctx.state.tex = v;
    *out = Value::Vector(v);
    ok
}

/// `mib_texture_remap (vector input, transform transform, vector repeat, boolean alt_x …,
/// boolean torus_x …, vector min, vector max, vector offset)`, in mental ray's order:
/// `input` times `transform` (when its last element is not 0); `torus` wraps into [0, 1);
/// on axes with a `repeat` and a value in [0, 1), the value is multiplied by it, every
/// other copy mirrored where `alt` (the first one among them), and wrapped again; axes with
/// `min` ≠ `max` are rescaled from [0, 1] to [min, max]; `offset` is added. A coordinate
/// handed over in `state.tex_arg` (by `mib_texture_filter_lookup`) replaces `input`.
pub static REMAP: ShaderImpl = ShaderImpl {
    name: "mib_texture_remap",
    params: &[
        "input",
        "transform",
        "repeat",
        "alt_x",
        "alt_y",
        "alt_z",
        "torus_x",
        "torus_y",
        "torus_z",
        "min",
        "max",
        "offset",
    ],
    run: remap,
    ..ShaderImpl::PLAIN
};

fn remap(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    // A coordinate handed over by a filtered lookup replaces the input.
    let mut p = match ctx.state.tex_arg.take() {
        Some(p) => p,
        None => ctx.vector(n, 0),
    };
    let m = ctx.eval(n, 1).transform();
    if m.w_axis.w != 0.0 {
        p = Vec3A::from(m.transform_point3(p.into()));
    }
    let repeat = ctx.vector(n, 2);
    let min = ctx.vector(n, 9);
    let max = ctx.vector(n, 10);
    let offset = ctx.vector(n, 11);
    for k in 0..3 {
        let mut c = p[k];
        if ctx.bool(n, 6 + k) {
            c = frac(c);
        }
        if repeat[k] != 0.0 && (0.0..1.0).contains(&c) {
            c *= repeat[k];
            if ctx.bool(n, 3 + k) {
                let i = c.floor();
                if i.rem_euclid(2.0) == 0.0 {
                    c = 2.0 * i + 1.0 - c;
                }
            }
            c = frac(c);
        }
        if min[k] != max[k] {
            c = min[k] + c * (max[k] - min[k]);
        }
        p[k] = c + offset[k];
    }
    ctx.state.tex = p;
    *out = Value::Vector(p);
    true
}

/// `mib_texture_rotate (vector input, scalar angle, scalar min, scalar max)` →
/// `struct { vector u, vector v }`: a brushing basis in the tangent plane: u = `input`
/// made perpendicular to the normal, v = N × u, both turned about the normal by
/// θ = 2π (min + angle (max − min)) (min = max = 0: max is ¼, so `angle` 0…1 turns 0…90°).
pub static ROTATE: ShaderImpl = ShaderImpl {
    name: "mib_texture_rotate",
    params: &["input", "angle", "min", "max"],
    run: rotate,
    ..ShaderImpl::PLAIN
};

fn rotate(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let input = ctx.vector(n, 0);
    let (angle, lo, hi) = (ctx.scalar(n, 1), ctx.scalar(n, 2), ctx.scalar(n, 3));
    let hi = if lo == 0.0 && hi == 0.0 { 0.25 } else { hi };
    let normal = ctx.state.normal;
    let u = (input - normal * input.dot(normal)).normalize_or_zero();
    let v = normal.cross(u);
    let theta = 2.0 * PI * (lo + angle * (hi - lo));
    let (sin, cos) = theta.sin_cos();
    *out = basis(u * cos + v * sin, v * cos - u * sin);
    true
}

fn basis(u: Vec3A, v: Vec3A) -> Value {
    Value::Struct(Arc::from(vec![(Arc::from("u"), Value::Vector(u)), (Arc::from("v"), Value::Vector(v))]))
}

/// `mib_bump_basis (integer project, integer ntex)` → `struct { vector u, vector v }`:
/// bump basis vectors for projection `project` (numbered as in `mib_texture_vector`): 2 xy,
/// 3 xz, 4 yz give the axes; 5–7 (spherical, cylindrical, lollipop) the directions of
/// increasing angle around the object's y axis; 0 and 1 (UV) the directions of increasing
/// u and v of texture space `ntex` across the hit triangle.
pub static BUMP_BASIS: ShaderImpl =
    ShaderImpl { name: "mib_bump_basis", params: &["project", "ntex"], run: bump_basis, ..ShaderImpl::PLAIN };

/// The (u, v) bump basis of a triangle with world-space corners `p` and texture
/// coordinates `t` for normal `normal`, as mental ray's source derives it: along an edge of
/// constant v (or u) when there is one, else along the direction of increasing v.
pub fn uv_basis(p: [Vec3A; 3], t: [Vec3A; 3], normal: Vec3A) -> Option<(Vec3A, Vec3A)> {
    const EDGES: [(usize, usize); 3] = [(0, 1), (0, 2), (1, 2)];
    let edge = |a: usize, b: usize| (p[b] - p[a], t[b] - t[a]);
    let toward = |d: Vec3A, along: f32| if along < 0.0 { -d } else { d };
    let ref_dir = |axis: usize| {
        EDGES
            .iter()
            .map(|&(a, b)| edge(a, b))
            .find(|(_, dt)| dt[axis].abs() >= 1e-4)
            .map(|(dp, dt)| toward(dp, dt[axis]))
    };
    // An edge of constant v runs along u.
    if let Some((dp, dt)) =
        EDGES.iter().map(|&(a, b)| edge(a, b)).find(|(_, dt)| dt.y.abs() < 1e-4 && dt.x.abs() >= 1e-4)
    {
        let u = toward(dp, dt.x).normalize_or_zero();
        let mut v = u.cross(normal);
        if ref_dir(1).is_some_and(|r| v.dot(r) < 0.0) {
            v = -v;
        }
        return Some((u, v));
    }
    let v_dir = if let Some((dp, dt)) =
        EDGES.iter().map(|&(a, b)| edge(a, b)).find(|(_, dt)| dt.x.abs() < 1e-4 && dt.y.abs() >= 1e-4)
    {
        toward(dp, dt.y)
    } else {
        let (d1, d2) = (t[1] - t[0], t[2] - t[0]);
        let det = d1.x * d2.y - d1.y * d2.x;
        if det.abs() <= 1e-12 {
            return None;
        }
        let k = 1.0 / det;
        (p[1] - p[0]) * (-k * d2.x) + (p[2] - p[0]) * (k * d1.x)
    };
    let v = v_dir.normalize_or_zero();
    let mut u = normal.cross(v);
    if ref_dir(0).is_some_and(|r| u.dot(r) < 0.0) {
        u = -u;
    }
    Some((u, v))
}

fn bump_basis(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let project = ctx.int(n, 0);
    let k = ctx.int(n, 1).max(0) as usize;
    let s = &ctx.state;
    let normal = s.normal;
    let (u, v, ok) = match project {
        2 => (Vec3A::X, Vec3A::Y, true),
        3 => (Vec3A::X, Vec3A::Z, true),
        4 => (Vec3A::Y, Vec3A::Z, true),
        5..=7 => {
            let p = s.point_object();
            let u = s.vector_from_object(Vec3A::new(-p.z, 0.0, p.x)).normalize_or_zero();
            let v = u.cross(normal);
            (normal.cross(v), v, true)
        }
        _ => {
            let corners = ctx.tracer.triangle(s, VertexData::Point);
            let coords = ctx.tracer.triangle(s, VertexData::Texture(k));
            match (corners, coords) {
                (Some(p), Some(t)) => match uv_basis(p, t, normal) {
                    Some((u, v)) => (u, v, true),
                    None => (Vec3A::ZERO, Vec3A::ZERO, false),
                },
                _ => (Vec3A::ZERO, Vec3A::ZERO, false),
            }
        }
    };
    *out = basis(u, v);
    ok
}

/// The height a bump map reads from a texture value: its alpha, or the mean of its colour.
fn height(c: Vec4, alpha: bool) -> f32 {
    if alpha {
        c.w
    } else {
        (c.x + c.y + c.z) / 3.0
    }
}

/// Bump mapping shared by `mib_bump_map` and `mib_passthrough_bump_map`: perturbs the
/// state's normal; false when the texture cannot be read at the point.
fn bump(ctx: &mut Ctx, n: NodeId) -> bool {
    let u = ctx.vector(n, 0);
    let v = ctx.vector(n, 1);
    let coord = ctx.vector(n, 2);
    let step = ctx.vector(n, 3);
    let factor = ctx.scalar(n, 4);
    let (torus_u, torus_v, alpha, clamp) = (ctx.bool(n, 5), ctx.bool(n, 6), ctx.bool(n, 7), ctx.bool(n, 9));
    let mut cu = coord + Vec3A::new(if step.x != 0.0 { step.x } else { 0.001 }, 0.0, 0.0);
    let mut cv = coord + Vec3A::new(0.0, if step.y != 0.0 { step.y } else { 0.001 }, 0.0);
    let unit = |x: f32| (0.0..1.0).contains(&x);
    if clamp && !(unit(coord.x) && unit(coord.y) && unit(coord.z) && unit(cu.x) && unit(cv.y)) {
        return true;
    }
    let Some(h) = lookup(ctx, n, 8, coord) else { return false };
    let h = height(h, alpha);
    let wrap = |c: Vec3A| Vec3A::new(frac(c.x), frac(c.y), frac(c.z));
    if torus_u {
        cu = wrap(cu);
    }
    if torus_v {
        cv = wrap(cv);
    }
    ctx.flush_cache();
    let hu = lookup(ctx, n, 8, cu).map_or(h, |c| height(c, alpha));
    ctx.flush_cache();
    let hv = lookup(ctx, n, 8, cv).map_or(h, |c| height(c, alpha));
    let normal = ctx.state.normal + factor * (u * (hu - h) + v * (hv - h));
    ctx.state.normal = normal.normalize_or(ctx.state.normal);
    ctx.state.dot_nd = ctx.state.normal.dot(ctx.state.dir);
    true
}

const BUMP_PARAMS: &[&str] = &["u", "v", "coord", "step", "factor", "torus_u", "torus_v", "alpha", "tex", "clamp"];

/// `mib_bump_map (vector u, vector v, vector coord, vector step, scalar factor, boolean
/// torus_u, boolean torus_v, boolean alpha, color texture tex, boolean clamp)`: perturbs
/// the normal by the texture's slope: heights (mean of r, g, b, or alpha) at `coord`, one
/// `step.x` along u and one `step.y` along v (0: 0.001; `torus` wraps those), and
/// N += factor (u (h_u − h) + v (h_v − h)), renormalised (`factor` 0: no bump). The result
/// is the new normal, which also replaces the state's. With `clamp`, points whose
/// coordinates leave [0, 1) are not bumped.
pub static BUMP_MAP: ShaderImpl =
    ShaderImpl { name: "mib_bump_map", params: BUMP_PARAMS, run: bump_map, ..ShaderImpl::PLAIN };

fn bump_map(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let ok = bump(ctx, n);
    *out = Value::Vector(ctx.state.normal);
    ok
}

/// `mib_passthrough_bump_map`: `mib_bump_map` that leaves the result as it found it, for
/// the head of a material shader list (the shaders after it see the bumped normal).
pub static PASSTHROUGH_BUMP_MAP: ShaderImpl = ShaderImpl {
    name: "mib_passthrough_bump_map",
    params: BUMP_PARAMS,
    run: passthrough_bump_map,
    ..ShaderImpl::PLAIN
};

fn passthrough_bump_map(ctx: &mut Ctx, n: NodeId, _out: &mut Value) -> bool {
    bump(ctx, n)
}

/// `mib_bump_map2 (scalar factor, scalar scale, color texture tex, color color)`: bumps the
/// normal from the texture on the first texture space — heights (mean of r, g, b) at
/// frac(uv · scale) and 0.001 further along u and v — along the bump basis (or the surface
/// derivatives, unnormalised), evaluates `color` with the bumped normal, restores the
/// normal and returns the colour.
pub static BUMP_MAP2: ShaderImpl = ShaderImpl {
    name: "mib_bump_map2",
    params: &["factor", "scale", "tex", "color"],
    run: bump_map2,
    ..ShaderImpl::PLAIN
};

fn bump_map2(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let factor = ctx.scalar(n, 0);
    let scale = ctx.scalar(n, 1);
    let t = ctx.state.tex(0) * scale;
    let c = Vec3A::new(frac(t.x), frac(t.y), 0.0);
    let normal = ctx.state.normal;
    if let Some(h) = lookup(ctx, n, 2, c) {
        let h = height(h, false);
        let hu = lookup(ctx, n, 2, c + Vec3A::new(0.001, 0.0, 0.0)).map_or(h, |x| height(x, false));
        let hv = lookup(ctx, n, 2, c + Vec3A::new(0.0, 0.001, 0.0)).map_or(h, |x| height(x, false));
        let [tu, tv] = ctx.state.bump_basis.unwrap_or(ctx.state.derivs);
        ctx.state.normal = (normal + factor * (tu * (hu - h) + tv * (hv - h))).normalize_or(normal);
        ctx.state.dot_nd = ctx.state.normal.dot(ctx.state.dir);
    }
    *out = Value::Color(ctx.color(n, 3));
    ctx.state.normal = normal;
    ctx.state.dot_nd = normal.dot(ctx.state.dir);
    true
}
