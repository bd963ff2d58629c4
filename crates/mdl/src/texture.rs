//! MDL `::base` texturing functions: texture coordinates, their transforms, file
//! textures, normal and bump maps, and colour layer blending.
//!
//! A texture coordinate is MDL's `texture_coordinate_info`: a `position` in texture space
//! (x, y select the image; [0, 1)² covers it once) and the world-space directions
//! `tangent_u`, `tangent_v` in which u and v grow on the surface. A `uvw` parameter that is
//! not connected is MDL's default, texture space 0.

use glam::{Mat4, Vec3A, Vec4};

use bsdf::color::luminance;
use bsdf::Rgb;
use shader::{Ctx, NodeId, ShaderImpl, Tag, Value};

/// A texture coordinate with its surface tangents (world space, unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coordinate {
    /// Position in texture space.
    pub position: Vec3A,
    /// Direction of growing u on the surface.
    pub tangent_u: Vec3A,
    /// Direction of growing v on the surface.
    pub tangent_v: Vec3A,
}

impl Coordinate {
    fn to_value(self) -> Value {
        Value::Struct(
            vec![
                ("position".into(), Value::Vector(self.position)),
                ("tangent_u".into(), Value::Vector(self.tangent_u)),
                ("tangent_v".into(), Value::Vector(self.tangent_v)),
            ]
            .into(),
        )
    }

    /// Reads a `texture_coordinate_info` value; an unset one (zero tangents) is `None`.
    fn from_value(v: &Value) -> Option<Coordinate> {
        let get = |name: &str| v.member(name).map(Value::vector).unwrap_or(Vec3A::ZERO);
        let c = Coordinate { position: get("position"), tangent_u: get("tangent_u"), tangent_v: get("tangent_v") };
        (c.tangent_u != Vec3A::ZERO || c.tangent_v != Vec3A::ZERO).then_some(c)
    }
}

/// Surface tangents at the shading point `state` (world space, unit, perpendicular to its
/// normal): the first texture space's dP/du and dP/dv when the geometry has them, else any
/// frame around the normal. MDL's `state::texture_tangent_u`/`_v`.
pub fn surface_tangents(state: &shader::State) -> (Vec3A, Vec3A) {
    let n = state.normal.normalize_or(Vec3A::Z);
    let [du, dv] = state.derivs;
    let u = (du - n * n.dot(du)).normalize_or_zero();
    if u == Vec3A::ZERO {
        let frame = bsdf::Frame::from_normal(n);
        return (frame.tangent, frame.bitangent);
    }
    let v = if dv.cross(n).length_squared() > 0.0 { n.cross(u) * n.cross(u).dot(dv).signum() } else { n.cross(u) };
    (u, v.normalize_or(n.cross(u)))
}

/// MDL's default coordinate: texture space `space` with the surface tangents.
fn uvw_space(ctx: &Ctx, space: usize) -> Coordinate {
    let (tangent_u, tangent_v) = surface_tangents(&ctx.state);
    Coordinate { position: ctx.state.tex(space), tangent_u, tangent_v }
}

/// Parameter `i` as a coordinate (texture space 0 when unset).
fn coordinate(ctx: &mut Ctx, n: NodeId, i: usize) -> Coordinate {
    let v = ctx.eval(n, i);
    Coordinate::from_value(&v).unwrap_or_else(|| uvw_space(ctx, 0))
}

/// `coordinate_source (coordinate_system, texture_space)`: `texture_coordinate_uvw` (the
/// texture space), `_world` (the world-space point), `_object` (the object-space point).
pub static COORDINATE_SOURCE: ShaderImpl = ShaderImpl {
    name: "mdl::base::coordinate_source",
    params: &["coordinate_system", "texture_space"],
    run: coordinate_source,
    ..ShaderImpl::PLAIN
};

fn coordinate_source(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let system = ctx.eval(n, 0);
    let space = ctx.int(n, 1).max(0) as usize;
    let mut c = uvw_space(ctx, space);
    match system.str().unwrap_or("texture_coordinate_uvw") {
        "texture_coordinate_world" => {
            c = Coordinate { position: ctx.state.point, tangent_u: Vec3A::X, tangent_v: Vec3A::Y };
        }
        "texture_coordinate_object" => {
            let to_world = ctx.state.object_to_world;
            c = Coordinate {
                position: ctx.state.world_to_object.transform_point3a(ctx.state.point),
                tangent_u: to_world.transform_vector3a(Vec3A::X).normalize_or(Vec3A::X),
                tangent_v: to_world.transform_vector3a(Vec3A::Y).normalize_or(Vec3A::Y),
            };
        }
        _ => {}
    }
    *out = c.to_value();
    true
}

/// `transform_coordinate (transform, coordinate)`: the position through the 4×4 matrix
/// (MDL's column-vector convention: the 16 numbers are its columns in order, so the
/// translation is the last four), the tangents through its 3×3 part.
pub static TRANSFORM_COORDINATE: ShaderImpl = ShaderImpl {
    name: "mdl::base::transform_coordinate",
    params: &["transform", "coordinate"],
    run: transform_coordinate,
    ..ShaderImpl::PLAIN
};

fn transform_coordinate(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let m = match ctx.eval(n, 0) {
        Value::Transform(m) if m != Mat4::ZERO => m,
        _ => Mat4::IDENTITY,
    };
    let c = coordinate(ctx, n, 1);
    let p = m * c.position.extend(1.0);
    let position = if p.w != 0.0 && p.w != 1.0 { p.truncate() / p.w } else { p.truncate() };
    let t = |v: Vec3A| Vec3A::from(m.transform_vector3(v.into())).normalize_or(v);
    *out = Coordinate { position: position.into(), tangent_u: t(c.tangent_u), tangent_v: t(c.tangent_v) }.to_value();
    true
}

/// `rotation_translation_scale (rotation, translation, scaling)`: the matrix that scales,
/// then rotates about x, y and z in that order (radians), then translates.
pub static ROTATION_TRANSLATION_SCALE: ShaderImpl = ShaderImpl {
    name: "mdl::base::rotation_translation_scale",
    params: &["rotation", "translation", "scaling"],
    run: rotation_translation_scale,
    ..ShaderImpl::PLAIN
};

fn rotation_translation_scale(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (r, t, s) = (ctx.vector(n, 0), ctx.vector(n, 1), ctx.vector(n, 2));
    let rotation = glam::Quat::from_euler(glam::EulerRot::ZYX, r.z, r.y, r.x);
    *out = Value::Transform(Mat4::from_scale_rotation_translation(s.into(), rotation, t.into()));
    true
}

/// MDL's `texture_wrap_mode` (by its enumerator's name) on one coordinate: `None` where the
/// texture is clipped away.
pub fn wrap(x: f32, mode: &str) -> Option<f32> {
    const BELOW_ONE: f32 = 1.0 - f32::EPSILON;
    match mode {
        "wrap_clamp" => Some(x.clamp(0.0, BELOW_ONE)),
        "wrap_mirrored_repeat" => {
            let t = x.rem_euclid(2.0);
            Some(if t < 1.0 { t } else { (2.0 - t).min(BELOW_ONE) })
        }
        "wrap_clip" => (0.0..1.0).contains(&x).then_some(x),
        _ => Some(x - x.floor()),
    }
}

/// The texture `tex` at `c` with the wrap modes; `None` when clipped (or no texture).
fn sample(ctx: &mut Ctx, tex: Option<Tag>, c: Vec3A, wrap_u: &str, wrap_v: &str, clip: bool) -> Option<Vec4> {
    let tex = tex?;
    if clip && !((0.0..1.0).contains(&c.x) && (0.0..1.0).contains(&c.y)) {
        return None;
    }
    let coord = Vec3A::new(wrap(c.x, wrap_u)?, wrap(c.y, wrap_v)?, 0.0);
    ctx.lookup_color_texture(tex, coord)
}

/// MDL's `mono_mode` (by its enumerator's name): how a colour with alpha becomes one number.
pub fn mono(c: Vec4, mode: &str) -> f32 {
    match mode {
        "mono_alpha" => c.w,
        "mono_luminance" => luminance(Rgb::new(c.x, c.y, c.z)),
        "mono_maximum" => c.x.max(c.y).max(c.z),
        _ => (c.x + c.y + c.z) / 3.0,
    }
}

fn texture_return(tint: Vec4, mono: f32) -> Value {
    Value::Struct(vec![("tint".into(), Value::Color(tint)), ("mono".into(), Value::Scalar(mono))].into())
}

/// A string parameter (an enumerator's name).
fn enumerator(ctx: &mut Ctx, n: NodeId, i: usize, default: &'static str) -> String {
    ctx.eval(n, i).str().map_or_else(|| default.to_string(), str::to_string)
}

/// `file_texture (texture, color_offset, color_scale, mono_source, uvw, wrap_u, wrap_v,
/// clip)`: `texture_return { tint, mono }` with tint = texel · color_scale + color_offset
/// and mono from the texel by `mono_source`; black where clipped.
pub static FILE_TEXTURE: ShaderImpl = ShaderImpl {
    name: "mdl::base::file_texture",
    params: &["texture", "color_offset", "color_scale", "mono_source", "uvw", "wrap_u", "wrap_v", "clip"],
    run: file_texture,
    ..ShaderImpl::PLAIN
};

fn file_texture(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let tex = ctx.tag(n, 0);
    let c = coordinate(ctx, n, 4);
    let (wrap_u, wrap_v) = (enumerator(ctx, n, 5, "wrap_repeat"), enumerator(ctx, n, 6, "wrap_repeat"));
    let clip = ctx.bool(n, 7);
    let texel = sample(ctx, tex, c.position, &wrap_u, &wrap_v, clip).unwrap_or(Vec4::ZERO);
    let (offset, scale) = (ctx.color(n, 1), ctx.color(n, 2));
    let tint = (texel * scale + offset).truncate().extend(1.0);
    let mode = enumerator(ctx, n, 3, "mono_alpha");
    *out = texture_return(tint, mono(texel, &mode));
    true
}

/// `tangent_space_normal_texture (texture, factor, flip_tangent_u, flip_tangent_v, uvw,
/// wrap_u, wrap_v, clip, scale, offset)`: a world-space shading normal from a tangent-space
/// normal map. The texel t becomes (t − offset)·2/scale − 1 per channel (RGB 0…1 → −1…1
/// with the defaults); x and y, scaled by `factor`, lean the normal along the tangents.
pub static TANGENT_SPACE_NORMAL: ShaderImpl = ShaderImpl {
    name: "mdl::base::tangent_space_normal_texture",
    params: &[
        "texture",
        "factor",
        "flip_tangent_u",
        "flip_tangent_v",
        "uvw",
        "wrap_u",
        "wrap_v",
        "clip",
        "scale",
        "offset",
    ],
    run: tangent_space_normal,
    ..ShaderImpl::PLAIN
};

fn tangent_space_normal(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let normal = ctx.state.normal;
    let tex = ctx.tag(n, 0);
    let c = coordinate(ctx, n, 4);
    let (wrap_u, wrap_v) = (enumerator(ctx, n, 5, "wrap_repeat"), enumerator(ctx, n, 6, "wrap_repeat"));
    let clip = ctx.bool(n, 7);
    let Some(texel) = sample(ctx, tex, c.position, &wrap_u, &wrap_v, clip) else {
        *out = Value::Vector(normal);
        return true;
    };
    let (factor, scale, offset) = (ctx.scalar(n, 1), ctx.scalar(n, 8), ctx.scalar(n, 9));
    let scale = if scale != 0.0 { scale } else { 1.0 };
    let t = (Vec3A::new(texel.x, texel.y, texel.z) - Vec3A::splat(offset)) * (2.0 / scale) - Vec3A::ONE;
    let su = if ctx.bool(n, 2) { -1.0 } else { 1.0 };
    let sv = if ctx.bool(n, 3) { -1.0 } else { 1.0 };
    let bent = c.tangent_u * (t.x * su * factor) + c.tangent_v * (t.y * sv * factor) + normal * t.z.max(0.0);
    *out = Value::Vector(bent.normalize_or(normal));
    true
}

/// `file_bump_texture (texture, factor, bump_source, uvw, wrap_u, wrap_v, clip)`: a
/// world-space shading normal tilted by the slope of a height map. The heights (the
/// texels by `bump_source`) are differenced over one texel in u and in v; the normal leans
/// against the rise by `factor` times those differences.
pub static FILE_BUMP: ShaderImpl = ShaderImpl {
    name: "mdl::base::file_bump_texture",
    params: &["texture", "factor", "bump_source", "uvw", "wrap_u", "wrap_v", "clip"],
    run: file_bump,
    ..ShaderImpl::PLAIN
};

fn file_bump(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let normal = ctx.state.normal;
    *out = Value::Vector(normal);
    let Some(tex) = ctx.tag(n, 0) else { return true };
    let texel = match tex {
        Tag::Texture(i) => match ctx.shading().textures.get(i as usize) {
            Some(shader::texture::Texture::Image { image, .. }) => {
                let (w, h) = image.size();
                Vec3A::new(1.0 / w.max(1) as f32, 1.0 / h.max(1) as f32, 0.0)
            }
            _ => return true,
        },
        _ => Vec3A::new(1.0 / 256.0, 1.0 / 256.0, 0.0),
    };
    let c = coordinate(ctx, n, 3);
    let (wrap_u, wrap_v) = (enumerator(ctx, n, 4, "wrap_repeat"), enumerator(ctx, n, 5, "wrap_repeat"));
    let mode = enumerator(ctx, n, 2, "mono_average");
    let clip = ctx.bool(n, 6);
    let height = |ctx: &mut Ctx, d: Vec3A| {
        sample(ctx, Some(tex), c.position + d, &wrap_u, &wrap_v, clip).map(|t| mono(t, &mode))
    };
    let (Some(h0), Some(hu), Some(hv)) =
        (height(ctx, Vec3A::ZERO), height(ctx, Vec3A::X * texel.x), height(ctx, Vec3A::Y * texel.y))
    else {
        return true;
    };
    let factor = ctx.scalar(n, 1);
    let bent = normal - (c.tangent_u * (hu - h0) + c.tangent_v * (hv - h0)) * factor;
    *out = Value::Vector(bent.normalize_or(normal));
    true
}

/// One colour layer's blend of `top` (weighted by `w`) over `below`, by MDL's
/// `color_layer_mode` name (unknown modes blend).
pub fn blend_layer(mode: &str, below: Vec3A, top: Vec3A, w: f32) -> Vec3A {
    let mixed = match mode {
        "color_layer_add" => below + top,
        "color_layer_multiply" => below * top,
        "color_layer_screen" => Vec3A::ONE - (Vec3A::ONE - below) * (Vec3A::ONE - top),
        "color_layer_overlay" => {
            let f = |b: f32, t: f32| if b < 0.5 { 2.0 * b * t } else { 1.0 - 2.0 * (1.0 - b) * (1.0 - t) };
            Vec3A::new(f(below.x, top.x), f(below.y, top.y), f(below.z, top.z))
        }
        "color_layer_lighten" => below.max(top),
        "color_layer_darken" => below.min(top),
        "color_layer_average" => (below + top) * 0.5,
        "color_layer_subtract" => below - top,
        "color_layer_difference" => (below - top).abs(),
        _ => top,
    };
    below + (mixed - below) * w
}

/// `blend_color_layers (layers, base, mono_source)`: each layer in order blended over the
/// result so far (starting at `base`) by its weight and mode; `texture_return`.
pub static BLEND_COLOR_LAYERS: ShaderImpl = ShaderImpl {
    name: "mdl::base::blend_color_layers",
    params: &["layers", "base", "mono_source"],
    run: blend_color_layers,
    ..ShaderImpl::PLAIN
};

fn blend_color_layers(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let layers = ctx.array(n, 0);
    let mut c = ctx.color(n, 1).truncate();
    for layer in layers.array() {
        let top = layer.member("layer_color").map_or(Vec3A::ZERO, Value::vector);
        let w = layer.member("weight").map_or(0.0, Value::scalar).clamp(0.0, 1.0);
        let mode = layer.member("mode").and_then(Value::str).unwrap_or("color_layer_blend");
        c = blend_layer(mode, c.into(), top, w).into();
    }
    let mode = enumerator(ctx, n, 2, "mono_average");
    let tint = c.extend(1.0);
    *out = texture_return(tint, mono(tint, &mode));
    true
}

/// `architectural_gloss_to_rough (glossiness)`: Iray's Arch & Design glossiness →
/// roughness, `sqrt(2 · 2^(−4 − 14 g))`, 0 from g = 1 on.
pub static GLOSS_TO_ROUGH: ShaderImpl = ShaderImpl {
    name: "mdl::base::architectural_gloss_to_rough",
    params: &["glossiness"],
    run: gloss_to_rough,
    ..ShaderImpl::PLAIN
};

fn gloss_to_rough(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    *out = Value::Scalar(bsdf::mia::gloss_to_roughness(ctx.scalar(n, 0)));
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_modes() {
        assert!((wrap(1.25, "wrap_repeat").unwrap() - 0.25).abs() < 1e-6);
        assert!((wrap(-0.25, "wrap_repeat").unwrap() - 0.75).abs() < 1e-6);
        assert!((wrap(1.25, "wrap_mirrored_repeat").unwrap() - 0.75).abs() < 1e-6);
        assert!(wrap(1.5, "wrap_clamp").unwrap() < 1.0);
        assert_eq!(wrap(-0.5, "wrap_clamp"), Some(0.0));
        assert_eq!(wrap(1.5, "wrap_clip"), None);
    }

    #[test]
    fn layer_modes() {
        let (b, t) = (Vec3A::splat(0.25), Vec3A::splat(0.5));
        assert!((blend_layer("color_layer_blend", b, t, 0.5) - Vec3A::splat(0.375)).length() < 1e-6);
        assert!((blend_layer("color_layer_multiply", b, t, 1.0) - Vec3A::splat(0.125)).length() < 1e-6);
        assert!((blend_layer("color_layer_screen", b, t, 1.0) - Vec3A::splat(0.625)).length() < 1e-6);
        assert!((blend_layer("color_layer_add", b, t, 0.0) - b).length() < 1e-6);
    }
}
