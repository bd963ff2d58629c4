//! Maya's useBackground: a matte that shows the background, catches shadows and
//! reflects the scene, for compositing rendered objects over a background plate.
//!
//! Parameters (see `mayabase.mi`): `specularColor` s (white), `reflectivity` r (0.5),
//! `reflectionLimit` (1), `shadowMask` m (1), `matteOpacityMode`, `matteOpacity`.
//!
//! ```text
//! shadow   = Σ_lights (N·L) (1 − f_L) / Σ_lights (N·L)   (lights in front of the point;
//!            f_L the fraction of the light the occluders let through, by luminance)
//! outColor = background ⊙ (1 − m · shadow) + r s ⊙ reflection,  alpha = m · shadow
//! ```
//!
//! The background is the environment seen along the ray (what the camera would show
//! there without the matte); the shadow also goes to the alpha (and `outMatteOpacity`), so
//! that the matte composited over a plate darkens it where the shadows fall. mira's
//! reading of Maya's description (the shadow weighting over several lights is not
//! documented).

use glam::Vec3A;
use scene::LightKind;
use shader::{Color, Ctx, NodeId, RayType, Value};

use crate::maya_shader;
use crate::values::{luma, rgb, rgba, write_struct};

maya_shader!(
    /// Maya's useBackground (see the module doc).
    USEBACKGROUND,
    ADSK_USEBACKGROUND,
    "maya_usebackground",
    "adskMayaUseBackground",
    &["specularColor", "reflectivity", "reflectionLimit", "shadowMask"],
    use_background
);

/// The N·L-weighted fraction of the instance's lights that occluders block at the point.
pub fn shadow_fraction(ctx: &mut Ctx) -> f32 {
    let lights = ctx.instance_lights();
    let (p, n) = (ctx.state.point, ctx.state.normal);
    let saved = ctx.state.clone();
    let (mut blocked, mut total) = (0.0, 0.0);
    for l in lights {
        let Some(light) = ctx.light(l) else { continue };
        let (to_light, dist) = match light.kind {
            LightKind::Directional => (-light.direction, f32::INFINITY),
            _ => {
                let d = light.origin - p;
                let dist = d.length();
                (d / dist, dist)
            }
        };
        let cos = n.dot(to_light);
        if !(cos > 0.0 && to_light.is_finite()) {
            continue;
        }
        ctx.state.dir = -to_light;
        ctx.state.dist = dist;
        ctx.state.light = Some(l);
        let mut f = Color::ONE;
        ctx.trace_shadow(&mut f);
        blocked += cos * (1.0 - luma(rgb(f)).clamp(0.0, 1.0));
        total += cos;
        ctx.state = saved.clone();
    }
    if total > 0.0 {
        blocked / total
    } else {
        0.0
    }
}

fn use_background(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if ctx.state.ray_type == RayType::Shadow {
        // The matte casts no shadow of its own: light passes (reported as full
        // transparency when a shading engine asks).
        if let Value::Struct(_) = out {
            write_struct(out, &[("outTransparency", Value::Color(Color::ONE))]);
        }
        return true;
    }
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let background = rgb(ctx.trace_environment(ctx.state.dir));
    let mask = ctx.scalar(n, 3).clamp(0.0, 1.0);
    let shadow = mask * shadow_fraction(ctx);
    let mut c = background * (1.0 - shadow);
    let r = ctx.scalar(n, 1);
    if r > 0.0 && ctx.state.reflection_level < ctx.int(n, 2).max(0) as u32 {
        if let Some(t) = ctx.trace_reflection(ctx.reflection_dir()) {
            c += r * rgb(ctx.color(n, 0)) * rgb(t);
        }
    }
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(c, shadow))),
            ("outTransparency", Value::Color(rgba(Vec3A::splat(1.0 - shadow), 1.0))),
            ("outMatteOpacity", Value::Color(Color::new(shadow, shadow, shadow, 1.0))),
        ],
    );
    true
}
