//! Lens shaders: they run for each eye ray, cast it on (`trace_eye`) and change what comes
//! back.

use glam::{Vec3A, Vec4};

use super::{rgb, rgba};
use crate::color::INTENSITY_WEIGHTS;
use shader::{Color, Ctx, NodeId, ShaderImpl, Value};

fn eye(ctx: &mut Ctx) -> Color {
    let (org, dir) = (ctx.state.org, ctx.state.dir);
    ctx.trace_eye(org, dir)
}

/// `mib_lens_clamp (scalar floor, scalar ceiling, boolean luminance, color floor_color,
/// color ceil_color)`: maps [floor, ceiling] (ceiling 0: 1; equal bounds: floor 0) to
/// [0, 1] per colour channel, clamped, alpha kept; with `luminance`, samples darker than
/// `floor` become `floor_color`, brighter than `ceiling` `ceil_color`, and the others are
/// scaled by their normalised luminance (L − floor)/(ceiling − floor).
pub static CLAMP: ShaderImpl = ShaderImpl {
    name: "mib_lens_clamp",
    params: &["floor", "ceiling", "luminance", "floor_color", "ceil_color"],
    run: clamp,
    ..ShaderImpl::PLAIN
};

fn clamp(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (mut lo, mut hi) = (ctx.scalar(n, 0), ctx.scalar(n, 1));
    if hi == 0.0 {
        hi = 1.0;
    }
    if lo == hi {
        lo = 0.0;
    }
    let c = eye(ctx);
    let range = hi - lo;
    let result = if ctx.bool(n, 2) {
        let lum = rgb(c).dot(INTENSITY_WEIGHTS);
        if lum < lo {
            ctx.color(n, 3)
        } else if lum > hi {
            ctx.color(n, 4)
        } else {
            rgba(rgb(c) * ((lum - lo) / range), c.w)
        }
    } else {
        let m = |x: f32| ((x - lo) / range).clamp(0.0, 1.0);
        Vec4::new(m(c.x), m(c.y), m(c.z), c.w)
    };
    *out = Value::Color(result);
    true
}

/// `mib_lens_stencil (scalar floor, scalar ceiling, color floor_color, color ceil_color,
/// scalar texture stencil)`: a screen-space stencil s at the raster position over the
/// resolution, normalised as (s − floor)/(ceiling − floor) (ceiling 0: 1): below 0 the
/// sample is `floor_color` and no ray is cast, above 1 `ceil_color`; in between the eye
/// ray's colour blended towards `floor_color`: s·E + (1 − s)·floor_color, alpha the ray's.
pub static STENCIL: ShaderImpl = ShaderImpl {
    name: "mib_lens_stencil",
    params: &["floor", "ceiling", "floor_color", "ceil_color", "stencil"],
    run: stencil,
    ..ShaderImpl::PLAIN
};

fn stencil(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (lo, mut hi) = (ctx.scalar(n, 0), ctx.scalar(n, 1));
    if hi == 0.0 {
        hi = 1.0;
    }
    let (w, h) = ctx.shading().resolution;
    let coord = Vec3A::new(ctx.state.raster.x / w.max(1) as f32, ctx.state.raster.y / h.max(1) as f32, 0.0);
    let s = match ctx.tag(n, 4) {
        Some(tag) if lo < hi => ctx.lookup_scalar_texture(tag, coord),
        _ => None,
    };
    let Some(s) = s else {
        *out = Value::Color(eye(ctx));
        return true;
    };
    let s = (s - lo) / (hi - lo);
    let result = if s < 0.0 {
        ctx.color(n, 2)
    } else if s > 1.0 {
        ctx.color(n, 3)
    } else {
        let e = eye(ctx);
        let f = ctx.color(n, 2);
        rgba(rgb(e) * s + rgb(f) * (1.0 - s), e.w)
    };
    *out = Value::Color(result);
    true
}

/// `physical_lens_dof (scalar plane, scalar radius)` from the physics library: a thin lens
/// of aperture `radius` (scene units) focused at distance `plane` in front of the camera
/// (along −Z in camera space): each eye ray starts on a point of the lens disc and passes
/// through the point where the pinhole ray meets the focal plane.
pub static DOF: ShaderImpl =
    ShaderImpl { name: "physical_lens_dof", params: &["plane", "radius"], run: dof, ..ShaderImpl::PLAIN };

fn dof(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let plane = ctx.scalar(n, 0).abs();
    let radius = ctx.scalar(n, 1);
    let (org, dir) = (ctx.state.org, ctx.state.dir);
    let to_camera = ctx.shading().world_to_camera;
    let cos = -to_camera.transform_vector3a(dir).z;
    if radius <= 0.0 || plane <= 0.0 || cos <= 0.0 {
        *out = Value::Color(eye(ctx));
        return true;
    }
    let focus = org + dir * (plane / cos);
    let site = ctx.next_site();
    let u = ctx.sample2(site, 0, 1);
    let d = bsdf::concentric_disc(u) * radius;
    let to_world = to_camera.inverse();
    let lens = org + to_world.transform_vector3a(Vec3A::new(d.x, d.y, 0.0));
    let new_dir = (focus - lens).normalize_or(dir);
    *out = Value::Color(ctx.trace_eye(lens, new_dir));
    true
}
