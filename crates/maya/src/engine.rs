//! The shading engine (Maya's shading group) and the shadow shaders exports attach.
//!
//! `maya_shadingengine` / `adskMayaShadingEngine` parameters:
//! - `surfaceShader` (colour): connected to the surface material, usually to its
//!   `outColor` member (`"surfaceShader" = "lambert1.outColor"`); the engine reads the
//!   material's whole output struct, so its `outTransparency` is known too;
//! - `cutAwayOpacity` (scalar, 0): where the material's opacity (1 − mean transparency)
//!   falls below this, the surface is cut away: the ray continues as if nothing was hit;
//! - `alphaMode` (integer): read by mental ray for Maya's frame-buffer bookkeeping; mira
//!   keeps the material's alpha (coverage) whatever it says.
//!
//! In eye and secondary rays the engine returns the material's `outColor` (with its
//! alpha). Where the camera sees the surface directly and runs a shader glow, the
//! material's `outGlowColor` goes to the glow buffer the glow's post pass spreads
//! ([`crate::glow::BUFFER`]). In shadow rays it filters the arriving light by the material's
//! `outTransparency`: the engine serves as the shading group's shadow shader too.

use glam::Vec3A;
use shader::{Color, Ctx, NodeId, RayType, Value};

use crate::maya_shader;
use crate::values::{connected_result, member_color, rgb, rgba};

/// What the shading engine takes of its material's output struct.
struct MaterialOutput {
    /// `outColor`.
    color: Color,
    /// `outTransparency` (RGB).
    transparency: Vec3A,
    /// `outGlowColor` (RGB; zero when the material does not glow).
    glow: Vec3A,
}

/// The material's colour, transparency and glow from the shading engine's `surfaceShader`.
fn material_output(ctx: &mut Ctx, n: NodeId) -> MaterialOutput {
    match connected_result(ctx, n, 0) {
        Some(v @ Value::Struct(_)) => MaterialOutput {
            color: member_color(&v, "outColor").unwrap_or_else(|| v.color()),
            transparency: member_color(&v, "outTransparency").map_or(Vec3A::ZERO, rgb),
            glow: member_color(&v, "outGlowColor").map_or(Vec3A::ZERO, rgb),
        },
        Some(v) => MaterialOutput { color: v.color(), transparency: Vec3A::ZERO, glow: Vec3A::ZERO },
        None => MaterialOutput { color: ctx.color(n, 0), transparency: Vec3A::ZERO, glow: Vec3A::ZERO },
    }
}

/// Stores the glow of a surface the camera sees directly into the materials' glow buffer
/// ([`crate::glow::BUFFER`], present when the camera runs a shader glow), zero included,
/// so that the buffer's per-pixel mean weighs the glow by the surface's coverage.
fn write_glow(ctx: &Ctx, glow: Vec3A) {
    let seen_directly =
        ctx.state.ray_type == RayType::Eye && ctx.state.reflection_level == 0 && ctx.state.refraction_level == 0;
    if seen_directly {
        if let Some(buffer) = ctx.fb_named(crate::glow::BUFFER) {
            ctx.fb_put(buffer, rgba(glow.max(Vec3A::ZERO), 1.0));
        }
    }
}

/// Filters the light arriving in `out` (a shadow ray) by `transparency`.
fn filter_light(out: &mut Value, transparency: Vec3A) -> bool {
    let light = out.color();
    let f = rgb(light) * transparency.clamp(Vec3A::ZERO, Vec3A::ONE);
    *out = Value::Color(rgba(f, light.w));
    f != Vec3A::ZERO
}

maya_shader!(
    /// Maya's shading group as a mental ray material shader (see the module doc).
    SHADINGENGINE,
    ADSK_SHADINGENGINE,
    "maya_shadingengine",
    "adskMayaShadingEngine",
    &["surfaceShader", "cutAwayOpacity", "alphaMode"],
    shading_engine
);

fn shading_engine(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let MaterialOutput { color, transparency, glow } = material_output(ctx, n);
    if ctx.state.ray_type == RayType::Shadow {
        return filter_light(out, transparency);
    }
    let cut = ctx.scalar(n, 1);
    let opacity = 1.0 - (transparency.x + transparency.y + transparency.z) / 3.0;
    if cut > 0.0 && opacity < cut {
        *out = Value::Color(ctx.trace_transparent().unwrap_or(Color::ZERO));
        return true;
    }
    write_glow(ctx, glow);
    *out = Value::Color(color);
    true
}

maya_shader!(
    /// Shadow shader of a shading group: filters the light by the `outTransparency` of
    /// the material its `surfaceShader` is connected to (black: opaque); without that
    /// connection, by `transparency`, which older translators connect to the material's
    /// `outTransparency` instead (github.com/ggarra13/mrliquid,
    /// `mrLiquid/src/mrShaderMayaShadow.cpp`, which also writes `shadowAttenuation` and
    /// `translucenceDepth`: accepted, not read — how mental ray for Maya uses them is not
    /// published; the material's own `translucenceDepth` acts through the
    /// `outTransparency` it reports in a shadow ray, `crate::material`).
    SHADOW,
    ADSK_SHADOW,
    "maya_shadow",
    "adskMayaShadow",
    &["surfaceShader", "transparency", "shadowAttenuation", "translucenceDepth"],
    shadow
);

fn shadow(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let transparency = if ctx.is_connected(n, 0) { material_output(ctx, n).transparency } else { rgb(ctx.color(n, 1)) };
    filter_light(out, transparency)
}

maya_shader!(
    /// Shadow shader of particles: lets the light through unchanged.
    TRANSPARENT,
    ADSK_TRANSPARENT,
    "maya_transparent",
    "adskMayaTransparent",
    &[],
    transparent
);

fn transparent(_ctx: &mut Ctx, _n: NodeId, _out: &mut Value) -> bool {
    true
}

maya_shader!(
    /// Displacement shader of a shading group (its `displacementShader` connection): the
    /// scalar connected to `displacement` (a displacementShader's output, a texture's
    /// `outAlpha`), object-space units along the normal (see the renderer's displacement
    /// stage).
    MATERIAL_DISPLACE,
    ADSK_MATERIAL_DISPLACE,
    "maya_material_displace",
    "adskMayaMaterialDisplace",
    &["displacement"],
    material_displace
);

fn material_displace(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    *out = Value::Scalar(ctx.scalar(n, 0));
    true
}
