//! The shading group's volume shader: `maya_volumesampler` / `adskMayaVolumeSampler`.
//!
//! Exports put it in a material's `volume` slot with its one parameter `volumeShader`
//! connected to the volume material of Maya's shading group (`"volumeShader" =
//! "fog1.outColor"`). It runs as a mental ray volume shader ([`shader::volume`]): the
//! result arrives holding the colour the ray brought back over the segment from
//! `state.org` to `state.point`, and leaves holding what reaches the ray's origin.
//!
//! What it does with the connected node:
//! - a node whose result is Maya's output struct (`outColor`, `outTransparency`, as
//!   Maya's volume materials give them): the struct is the whole segment's, so the
//!   colour behind passes in proportion to `outTransparency` T and the volume's own
//!   colour is added, already weighted by its opacity as Maya's `outColor` is:
//!   result = behind ⊙ T + outColor; light and shadow rays keep light ⊙ T;
//! - any other node (a mental ray volume shader such as `mib_volume` or `parti_volume`,
//!   connected directly): called as the volume shader itself, on the same result;
//! - nothing connected (a volume node no library declares was dropped, with the shader
//!   model's warning naming its line): the ray passes unchanged.

use glam::Vec3A;
use shader::{Ctx, NodeId, RayType, Slot, Value};

use crate::maya_shader;
use crate::values::{member_color, rgb, rgba};

maya_shader!(
    /// The shading group's volume shader (see the module doc).
    VOLUMESAMPLER,
    ADSK_VOLUMESAMPLER,
    "maya_volumesampler",
    "adskMayaVolumeSampler",
    &["volumeShader"],
    volume_sampler
);

fn volume_sampler(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(Slot::Connect { node: source, .. }) = ctx.node(n).slots.first() else { return true };
    let source = *source;
    let declares_struct = ctx.node(source).decl.members().iter().any(|m| &**m == "outTransparency");
    if !declares_struct {
        // A volume shader of mental ray's own contract: it works on the result itself.
        let mut result = out.clone();
        if ctx.call(source, &mut result) {
            *out = result;
        }
        return true;
    }
    let material = ctx.result(source);
    let transparency = member_color(&material, "outTransparency").map_or(Vec3A::ZERO, rgb);
    let t = transparency.clamp(Vec3A::ZERO, Vec3A::ONE);
    let behind = out.color();
    let passed = rgb(behind) * t;
    *out = Value::Color(if matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow) {
        rgba(passed, behind.w)
    } else {
        let color = member_color(&material, "outColor").map_or(Vec3A::ZERO, rgb);
        let coverage = 1.0 - (t.x + t.y + t.z) / 3.0;
        rgba(passed + color, behind.w + (1.0 - behind.w) * coverage)
    });
    true
}
