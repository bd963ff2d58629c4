//! `mia_physicalsky`: the Architectural library's daylight sky as an environment shader —
//! the sky's radiance for a direction, a ground plane below a blurred horizon, and the
//! visible sun disk with its glow.
//!
//! **The sky** is the analytic daylight model of Preetham, Shirley and Smits, "A Practical
//! Analytic Model for Daylight" (SIGGRAPH 1999): the luminance Y and the chromaticities x, y
//! each follow the all-weather distribution of Perez, Seals and Michalsky (1993),
//! `F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ)` (θ from the zenith, γ from
//! the sun), relative to the zenith: `Y = Y_z F(θ, γ) / F(0, θ_s)`, with the paper's
//! turbidity-linear coefficients A … E and its fits for the zenith luminance `Y_z` (kcd/m²)
//! and chromaticity `x_z`, `y_z`. xyY goes to linear Rec.709 RGB through CIE XYZ (D65
//! white, so that `redblueshift` 0 is neutral for 6500 K as the manual says).
//!
//! **Units** follow the manual: with `rgb_unit_conversion` 1 1 1 the sky's value is its
//! luminance × π (so that its mean over a hemisphere, mental ray's average radiance, is the
//! illuminance in lux) and the sun's is lux; 0 0 0 means 1/80 000 (a sunny day's 80 000 lux
//! is 1); `multiplier` scales everything.
//!
//! **Parameters onto the model**, as the public sources describe mental ray's shader (the
//! manual, and the MDL port `base::sun_and_sky` whose behaviour NVIDIA's open-source
//! renderers reproduce): turbidity = 2 + `haze`; `y_is_up` swaps Y and Z; `horizon_height`
//! / 10 is subtracted from the up component of every direction (sun included) before it is
//! renormalised, so ±10 put the horizon at the zenith or nadir; below the horizon lies a
//! Lambertian ground of albedo `ground_color` lit by the sun and the sky (no shadows),
//! blended into the sky over `horizon_blur` / 10 of the up component; directions at or
//! below the horizon see the sky as it is just above it (up component 0.001), and so does
//! the model for a sun below it, the whole sky dimming as `((z_sun + s)/s)⁴` with
//! s = sin 18° (dark when the sun is 18° down: astronomical twilight); `night_color` is a
//! floor under the result (faded out below the horizon as the ground takes over);
//! `saturation` mixes each colour with its Rec.709 luminance (below 1 it is lowered further
//! with haze: s(1 − h) + s³h, h = (haze/15)³), `redblueshift` scales red by 1 + shift and
//! blue by 1 − shift. The sun disk and glow: within 10 × the disk's radius (the real sun's
//! 0.00465 rad × `sun_disk_scale`) of the sun, with k = 10 (1 − angle / that radius), the
//! sun's illuminance is added × (k/10)³ · 2 · `sun_glow_intensity` (the glow) +
//! smoothstep(8.5, 9.5 + T/50, k) · 100 · `sun_disk_intensity` (the disk); with
//! `physically_scaled_sun` the two are rescaled so that disk and glow together deliver
//! `sun_disk_intensity` × the sun's illuminance, the glow at most half of it.
//!
//! mira's choices where the sources stop: the Perez coefficients and zenith formulas are
//! the paper's published values (mental ray's own tuning of them is not public); a zenith
//! luminance the fit makes negative (very hazy skies with a low sun) is taken as 0; the
//! disk and glow dim with the rest of the sky after sunset; the ground uses the model's
//! turbidity. Not done: `flags`.
//!
//! **Aerial perspective** (`visibility_distance`, the shader in a camera's lens list):
//! see [`super::aerial`].

use shader::{rgb, Color, Ctx, NodeId, RayType, ShaderImpl, Tag, Value};
pub use sky::sky::*;

/// `mia_physicalsky` as an environment (camera or material) or texture shader: the sky,
/// ground, sun disk and glow in the ray's direction ([`PhysicalSky::radiance`]), alpha 1.
/// The sun's direction comes from the `sun` light (the opposite of the way it shines), else
/// `sun_direction`. `use_background` shows the `background` shader (or transparent black)
/// instead for rays from the eye (reflection and gather depth 0). Off: transparent black.
/// In a camera's lens list it passes the eye ray through, with aerial perspective when
/// `visibility_distance` is positive ([`super::aerial`]).
pub static MIA_PHYSICALSKY: ShaderImpl = ShaderImpl {
    name: "mia_physicalsky",
    params: &[
        "on",
        "multiplier",
        "rgb_unit_conversion",
        "haze",
        "redblueshift",
        "saturation",
        "horizon_height",
        "horizon_blur",
        "ground_color",
        "night_color",
        "sun_direction",
        "sun",
        "sun_disk_intensity",
        "sun_disk_scale",
        "sun_glow_intensity",
        "use_background",
        "background",
        "y_is_up",
        "sky_luminance_mode",
        "zenith_luminance",
        "diffuse_horizontal_illuminance",
        "a",
        "b",
        "c",
        "d",
        "e",
        "physically_scaled_sun",
        "visibility_distance",
    ],
    run: physicalsky,
    ..ShaderImpl::PLAIN
};

/// The sky parameters of node `n`.
pub fn sky_of(ctx: &mut Ctx, n: NodeId) -> PhysicalSky {
    let sun_light = match ctx.tag(n, 11) {
        Some(Tag::Light(l)) => ctx.light(l).map(|l| -l.direction),
        _ => None,
    };
    PhysicalSky {
        multiplier: ctx.scalar(n, 1),
        rgb_unit_conversion: rgb(ctx.color(n, 2)),
        haze: ctx.scalar(n, 3),
        redblueshift: ctx.scalar(n, 4),
        saturation: ctx.scalar(n, 5),
        horizon_height: ctx.scalar(n, 6),
        horizon_blur: ctx.scalar(n, 7),
        ground_color: rgb(ctx.color(n, 8)),
        night_color: rgb(ctx.color(n, 9)),
        sun_direction: sun_light.unwrap_or_else(|| ctx.vector(n, 10)),
        sun_disk_intensity: ctx.scalar(n, 12),
        sun_disk_scale: ctx.scalar(n, 13),
        sun_glow_intensity: ctx.scalar(n, 14),
        y_is_up: ctx.bool(n, 17),
        sky_luminance_mode: ctx.int(n, 18),
        zenith_luminance: ctx.scalar(n, 19),
        diffuse_horizontal_illuminance: ctx.scalar(n, 20),
        perez: [ctx.scalar(n, 21), ctx.scalar(n, 22), ctx.scalar(n, 23), ctx.scalar(n, 24), ctx.scalar(n, 25)],
        physically_scaled_sun: ctx.bool(n, 26),
    }
}

fn physicalsky(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if ctx.state.ray_type == RayType::Eye && ctx.shading().lens.contains(&n) {
        let (org, dir) = (ctx.state.org, ctx.state.dir);
        let c = ctx.trace_eye(org, dir);
        let (dist, visibility) = (ctx.state.child_dist, ctx.scalar(n, 27));
        let c = if visibility > 0.0 && dist.is_finite() && ctx.bool(n, 0) {
            super::aerial::aerial_perspective(&sky_of(ctx, n), c, dir, dist, visibility)
        } else {
            c
        };
        *out = Value::Color(c);
        return true;
    }
    if !ctx.bool(n, 0) {
        *out = Value::Color(Color::ZERO);
        return true;
    }
    let from_eye = ctx.state.reflection_level == 0 && ctx.state.finalgather_level == 0;
    if from_eye && ctx.bool(n, 15) {
        *out = Value::Color(match ctx.tag(n, 16) {
            Some(Tag::Shader(b)) => ctx.result(b).color(),
            _ => Color::ZERO,
        });
        return true;
    }
    let mut sky = sky_of(ctx, n);
    if ctx.state.finalgather_level > 0 && linked_physical_sun(ctx, n) {
        // Light-gathering rays do not see the disk and glow: the linked sun light
        // delivers the sun's light (see [`linked_physical_sun`]).
        sky.sun_disk_intensity = 0.0;
        sky.sun_glow_intensity = 0.0;
    }
    let c = sky.radiance(ctx.state.dir);
    *out = Value::Color(Color::new(c.x, c.y, c.z, 1.0));
    true
}

/// Whether the sky of node `n` takes its sun from a light (its `sun` parameter) whose light
/// shader is `mia_physicalsun`: the sun's light then reaches surfaces as that light's
/// (`mi_sample_light`), and rays that gather light — final gather rays here, the path
/// engine's scattered rays and environment samples (it asks with `finalgather_level` 1) —
/// see the sky without the disk and glow, so that the sun is not counted twice.
///
/// The sources: Autodesk's mental ray manual, "Sun and Sky"
/// (<http://download.autodesk.com/us/maya/2010help/mr/shaders/architectural/arch_sunsky.html>):
/// the sun is `mia_physicalsun` on a directional light and its light is what
/// `mi_sample_light` returns (lux with `rgb_unit_conversion` 1); the sky is the camera's
/// environment and lights the scene through final gathering. 3ds Max's mr Physical Sky page
/// (Autodesk's 3ds Max 2009 manual, "Sun Disk Appearance" group) calls the disk intensity,
/// glow intensity and scale settings of the visible appearance of the sun in the sky. No
/// stored page says in so many words which rays see the disk; hiding it from gathering rays
/// when a sun light exists is mira's reading of that split (verify against mental ray). A
/// sky without a sun light (`sun_direction` only) keeps its disk for every ray: it is then
/// the only sun.
pub fn linked_physical_sun(ctx: &mut Ctx, n: NodeId) -> bool {
    let Some(Tag::Light(l)) = ctx.tag(n, 11) else { return false };
    let Some(light) = ctx.light(l) else { return false };
    let Some(head) = light.shader else { return false };
    let graph = &ctx.shading().graph;
    graph.nodes.get(head as usize).and_then(|node| node.imp).is_some_and(|imp| imp.name == "mia_physicalsun")
}
