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
//! alpha). In shadow rays it filters the arriving light by the material's
//! `outTransparency`: the engine serves as the shading group's shadow shader too.

use glam::Vec3A;
use shader::{Color, Ctx, NodeId, RayType, Value};

use crate::maya_shader;
use crate::values::{connected_result, member_color, rgb, rgba};

/// The material's colour and transparency from the shading engine's `surfaceShader`.
fn material_output(ctx: &mut Ctx, n: NodeId) -> (Color, Vec3A) {
    match connected_result(ctx, n, 0) {
        Some(v @ Value::Struct(_)) => {
            let color = member_color(&v, "outColor").unwrap_or_else(|| v.color());
            let t = member_color(&v, "outTransparency").map_or(Vec3A::ZERO, rgb);
            (color, t)
        }
        Some(v) => (v.color(), Vec3A::ZERO),
        None => (ctx.color(n, 0), Vec3A::ZERO),
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
    let (color, transparency) = material_output(ctx, n);
    if ctx.state.ray_type == RayType::Shadow {
        return filter_light(out, transparency);
    }
    let cut = ctx.scalar(n, 1);
    let opacity = 1.0 - (transparency.x + transparency.y + transparency.z) / 3.0;
    if cut > 0.0 && opacity < cut {
        *out = Value::Color(ctx.trace_transparent().unwrap_or(Color::ZERO));
        return true;
    }
    *out = Value::Color(color);
    true
}

maya_shader!(
    /// Shadow shader of a shading group: filters the light by the `outTransparency` of
    /// the material its `surfaceShader` is connected to (black: opaque).
    SHADOW,
    ADSK_SHADOW,
    "maya_shadow",
    "adskMayaShadow",
    &["surfaceShader"],
    shadow
);

fn shadow(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (_, transparency) = material_output(ctx, n);
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
