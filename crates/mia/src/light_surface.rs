//! `mia_light_surface`: a material/texture helper that makes geometry glow
//! (`shared/spec/mia.md` §4.2), with a brightness that depends on who looks.

use glam::Vec3A;

use shader::{rgb, rgba};
use shader::{Ctx, NodeId, RayType, ShaderImpl, Value};

/// `mia_light_surface (color color, scalar intensity, scalar fg_contrib, scalar
/// refl_contrib, boolean use_lights, scalar lights_multiplier, integer lights_eval_point,
/// array light lights)`.
///
/// The glow G is `color` × `intensity`, or with `use_lights` on the light the listed
/// lights bring to the shaded point (each light's mean sample colour, from both sides of
/// the surface, no cosine) × `lights_multiplier` — mira's reading; `lights_eval_point` is
/// not read (the shaded point is used). The result is G for eye rays (and rays that pass
/// straight or refracted on to the eye), G × `fg_contrib` for final gather rays and
/// G × `refl_contrib` for reflection rays, so that the geometry looks bright without
/// counting twice the light that real lights next to it already bring. Alpha is 1.
pub static LIGHT_SURFACE: ShaderImpl = ShaderImpl {
    name: "mia_light_surface",
    params: &["color", "intensity", "fg_contrib", "refl_contrib", "use_lights", "lights_multiplier", "lights"],
    run: light_surface,
    ..ShaderImpl::PLAIN
};

fn light_surface(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let weight = match ctx.state.ray_type {
        RayType::Finalgather => ctx.scalar(n, 2),
        RayType::Reflect => ctx.scalar(n, 3),
        _ => 1.0,
    };
    if weight == 0.0 {
        *out = Value::Color(rgba(Vec3A::ZERO, 1.0));
        return true;
    }
    let glow = if ctx.bool(n, 4) {
        let lights = ctx.array(n, 6);
        let mut sum = Vec3A::ZERO;
        for light in ctx.light_list(0, &lights) {
            let mut lp = ctx.light_loop(light);
            lp.both_sides = true;
            let mut s = Vec3A::ZERO;
            while let Some(sample) = ctx.sample_light(&mut lp) {
                s += rgb(sample.color);
            }
            if lp.samples > 0 {
                sum += s / lp.samples as f32;
            }
        }
        sum * ctx.scalar(n, 5)
    } else {
        rgb(ctx.color(n, 0)) * ctx.scalar(n, 1)
    };
    *out = Value::Color(rgba(glow * weight, 1.0));
    true
}
