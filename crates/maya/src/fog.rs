//! Maya's fog materials as mental ray volume shaders: environment fog (`maya_envfog`,
//! Maya's envFog node, simple and physical fog) and light fog (`maya_lightfog`, the lightFog
//! node). Exports name Maya's shading nodes `maya_` and the node type in lower case (the
//! open-source mrLiquid exporter lists envFog and lightFog among the Maya shaders it
//! writes so); the `adskMaya*` names are this crate's guess in the family's pattern.
//!
//! Both run where a volume shader runs ([`shader::volume`]: the camera's `volume`, a
//! material's `volume`): the result arrives holding the colour the ray brought back over
//! the segment from `state.org` to `state.point` (length L; an infinite one for a ray that
//! left the scene) and leaves holding what reaches the ray's origin. The fog covers a
//! share α of what lies behind it. With `colorBasedTransparency` on (Maya's default) the
//! fog's transparency follows its colour: result ← result ⊙ (1 − α·c) + α·c ⊙ E, where c
//! is `color` and E the light the fog shows (below); with it off the fog hides what lies
//! behind alike in every channel (a dark fog then leaves dark silhouettes, as Maya
//! describes): result ← result · (1 − α) + α·c ⊙ E. Light and shadow rays pass unchanged
//! (Maya's environment fog casts no shadows, and its light fog is not a shadow caster in
//! mira either).
//!
//! - `maya_envfog` (`color` white, `colorBasedTransparency` on, `saturationDistance` 100:
//!   Maya's "distance at which the fog becomes fully saturated"; `useHeight` off,
//!   `minHeight` −1, `maxHeight` 1): α = min(L_f / `saturationDistance`, 1), L_f the
//!   length of the segment inside the fog — all of it, or with `useHeight` the part
//!   whose world height lies between `minHeight` and `maxHeight` (above `minHeight`
//!   when `maxHeight` is below it, as Maya documents); an infinite segment in the fog is
//!   saturated (α = 1). The fog shows its own colour (E = 1). The fog fills the ray
//!   between the camera's clip planes (`distanceClipPlanes` 1, mira's reading of the
//!   default: all of the segment, as before) or between its own clip distances
//!   (`distanceClipPlanes` 0, Maya's "Fog Near/Far": `fogNearDistance` 0 and
//!   `fogFarDistance` 200 from the ray's origin — the camera for eye rays, as Maya's
//!   "distances from the camera"; the enumeration's numbers and the far default are
//!   mira's reading, the reference names the attributes without them); simple and
//!   physical fog alike. With `physicalFog` on,
//!   Maya's physically based fog replaces all this (the parameters after `physicalFog`:
//!   fog type, fog and air media, planet, axis, sun, the `lightList` of the uniform
//!   type and the water of the Water types; see [`crate::physical_fog`]);
//!   `colorBasedTransparency` does not apply to it. `useLayer` (off) and `layer` (1): the
//!   reference says that with `useLayer` a texture on `layer` varies the fog's density
//!   across the camera's view, in two dimensions (patchy fog); mira scales the length in
//!   the fog by the layer's value, α = min(`layer`·L_f / `saturationDistance`, 1) (simple
//!   fog; no fog where the layer is 0 or less). Nothing says how the view maps onto the
//!   layer's texture; mira evaluates it at the screen position of the ray (u, v ∈ [0, 1]
//!   across the render camera's image from its lower left, as a texture's uv; for an eye
//!   ray its pixel's place, for other rays the place of the point one unit along them).
//! - `maya_lightfog` (`color` white, `density` 1, `colorBasedTransparency` on,
//!   `fastDropOff` off, `lightList`): with `fastDropOff` on, what lies behind is obscured
//!   by the fog between — α = 1 − exp(−`density` · L), the transmittance of a medium of
//!   extinction `density` per scene unit; off, everything inside or behind the fog is
//!   obscured by the same amount (Maya's description), mira's reading the fog of one
//!   scene unit: α = 1 − exp(−`density`). The fog shows the light it receives: E is the
//!   sum of what the lights of `lightList` (all the scene's lights when empty) deliver
//!   at the segment's middle (their light shaders run there; at the segment's origin
//!   for an infinite one).
//!
//! Each fog's effect is affine in the colour it receives (result ← keep ⊙ result + add),
//! and it tells the two terms to the path engine ([`shader::ShaderImpl::volume_terms`]),
//! which applies a volume made of fogs — the camera's, or a material's inside that
//! material's objects — to each segment of its paths (see `render`'s integrator); a fog
//! in a volume list with other shaders is left out there, and [`fog_warnings`] says so.

use glam::{Affine3A, Vec2, Vec3A};
use shader::volume::{segment_length, VolumeTerms};
use shader::{Ctx, NodeId, RayType, Value};

use crate::physical_fog::{self, Medium, PhysicalFog, Profile, Water};
use crate::values::{rgb, rgba};

/// The fog's effect as affine terms (see the module doc): `alpha` the share α, `color` the
/// fog's colour c, `shown` E, `color_based` `colorBasedTransparency`: keep 1 − α·c (1 − α
/// alike in every channel without colour-based transparency), add α·c ⊙ E.
fn terms(alpha: f32, color: Vec3A, shown: Vec3A, color_based: bool) -> VolumeTerms {
    let cover = if color_based { alpha * color } else { Vec3A::splat(alpha) };
    VolumeTerms { keep: Vec3A::ONE - cover, add: alpha * color * shown }
}

/// Applies the fog's `terms` to `out`, the colour arriving from behind; its alpha grows
/// by the mean share covered.
fn apply(out: &mut Value, terms: VolumeTerms) {
    let behind = out.color();
    let cover = Vec3A::ONE - terms.keep;
    let coverage = (cover.x + cover.y + cover.z) / 3.0;
    *out = Value::Color(rgba(terms.apply(rgb(behind)), behind.w + (1.0 - behind.w) * coverage.clamp(0.0, 1.0)));
}

/// Whether the ray carries light to a point rather than colour to an eye (those pass
/// unchanged).
fn carries_light(ctx: &Ctx) -> bool {
    matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow)
}

/// A fog's two statics (Maya and `adskMaya` names): a volume shader that applies its
/// affine terms `$terms` to the colour it receives and tells them to the path engine
/// ([`shader::ShaderImpl::volume_terms`]).
macro_rules! maya_volume {
    ($(#[$doc:meta])* $maya:ident, $adsk:ident, $maya_name:literal, $adsk_name:literal, $params:expr, $terms:expr) => {
        $(#[$doc])*
        pub static $maya: shader::ShaderImpl = maya_volume!(@shader $maya_name, $params, $terms);
        $(#[$doc])*
        pub static $adsk: shader::ShaderImpl = maya_volume!(@shader $adsk_name, $params, $terms);
    };
    (@shader $name:literal, $params:expr, $terms:expr) => {
        shader::ShaderImpl {
            name: $name,
            params: $params,
            run: |ctx, n, out| {
                let t = $terms(ctx, n);
                apply(out, t);
                true
            },
            volume_terms: Some($terms),
            ..shader::ShaderImpl::PLAIN
        }
    };
}

maya_volume!(
    /// Environment fog, simple mode (see the module doc).
    ENVFOG,
    ADSK_ENVFOG,
    "maya_envfog",
    "adskMayaEnvFog",
    &[
        "color",
        "colorBasedTransparency",
        "saturationDistance",
        "useHeight",
        "minHeight",
        "maxHeight",
        "physicalFog",
        "fogType",
        "fogDensity",
        "fogColor",
        "fogOpacity",
        "fogMinHeight",
        "fogMaxHeight",
        "fogDecay",
        "fogLightScatter",
        "airDensity",
        "airColor",
        "airOpacity",
        "airMinHeight",
        "airMaxHeight",
        "airDecay",
        "airLightScatter",
        "planetRadius",
        "fogAxis",
        "sunIntensity",
        "sunAzimuth",
        "sunElevation",
        "sunColor",
        "lightList",
        "distanceClipPlanes",
        "fogNearDistance",
        "fogFarDistance",
        "waterDensity",
        "waterColor",
        "waterOpacity",
        "waterLevel",
        "waterDepth",
        "waterLightDecay",
        "waterLightScatter",
        "useLayer",
        "layer"
    ],
    env_fog_terms
);

/// The length of the part of the segment from `org` along unit `dir` over `length`
/// (infinite allowed) whose height (world y) lies in [`lo`, `hi`] (`hi` < `lo`: [`lo`, ∞)).
pub fn length_in_band(org: Vec3A, dir: Vec3A, length: f32, lo: f32, hi: f32) -> f32 {
    let hi = if hi < lo { f32::INFINITY } else { hi };
    let (t0, t1) = if dir.y == 0.0 {
        if (lo..=hi).contains(&org.y) {
            (0.0, length)
        } else {
            return 0.0;
        }
    } else {
        let (a, b) = ((lo - org.y) / dir.y, (hi - org.y) / dir.y);
        (a.min(b).max(0.0), a.max(b).min(length))
    };
    (t1 - t0).max(0.0)
}

/// The environment fog's share α over a segment of which `inside` lies in the fog:
/// min(inside / `saturation`, 1) (1 for an infinite part; 0 for a saturation distance of
/// 0 or less, which names no fog).
pub fn env_fog_share(inside: f32, saturation: f32) -> f32 {
    if saturation <= 0.0 || inside <= 0.0 {
        return 0.0;
    }
    (inside / saturation).min(1.0)
}

/// The part [t0, t1] of a segment of `length` (infinite allowed) that lies between the
/// fog's clip distances `near` and `far` from the segment's origin; `None` when none does.
pub fn clip_span(length: f32, near: f32, far: f32) -> Option<(f32, f32)> {
    let (t0, t1) = (near.max(0.0), far.min(length));
    (t1 > t0).then_some((t0, t1))
}

/// The part of the state's segment the environment fog fills: all of it with the camera's
/// clip planes (`distanceClipPlanes` 1, the default), the part between `fogNearDistance`
/// and `fogFarDistance` along the ray with the fog's own (0); `None` when empty.
fn env_fog_span(ctx: &mut Ctx, n: NodeId) -> Option<(f32, f32)> {
    let length = segment_length(&ctx.state);
    if ctx.int(n, 29) != 0 {
        return Some((0.0, length));
    }
    clip_span(length, ctx.scalar(n, 30), ctx.scalar(n, 31))
}

fn env_fog_terms(ctx: &mut Ctx, n: NodeId) -> VolumeTerms {
    if carries_light(ctx) {
        return VolumeTerms::NONE;
    }
    let Some((t0, t1)) = env_fog_span(ctx, n) else { return VolumeTerms::NONE };
    if ctx.bool(n, 6) {
        return physical_fog_terms(ctx, n, (t0, t1));
    }
    let org = ctx.state.org + ctx.state.dir * t0;
    let length = t1 - t0;
    let inside = if ctx.bool(n, 3) {
        length_in_band(org, ctx.state.dir, length, ctx.scalar(n, 4), ctx.scalar(n, 5))
    } else {
        length
    };
    let alpha = if ctx.bool(n, USE_LAYER) {
        let layer = env_fog_layer(ctx, n);
        if layer > 0.0 {
            env_fog_share(inside * layer, ctx.scalar(n, 2))
        } else {
            0.0
        }
    } else {
        env_fog_share(inside, ctx.scalar(n, 2))
    };
    let color = rgb(ctx.color(n, 0));
    terms(alpha, color, Vec3A::ONE, ctx.bool(n, 1))
}

/// The index of envFog's `useLayer`; `layer` follows it.
const USE_LAYER: usize = 39;

/// The position of world point `q` across the render camera's image: (u, v) ∈ [0, 1]²
/// over the image, (0, 0) at its lower left (v up, as a texture's v). `world_to_camera`
/// and `image_plane` (the half extents at distance 1; orthographic: of the view) are the
/// shading's camera. A point behind a perspective camera takes the place of its mirror
/// image in front (x, y over |z|), so that a ray leaving backwards still finds a place.
pub fn screen_uv(world_to_camera: &Affine3A, image_plane: Vec2, orthographic: bool, q: Vec3A) -> Vec2 {
    let p = world_to_camera.transform_point3a(q);
    let s = if orthographic { Vec2::new(p.x, p.y) } else { Vec2::new(p.x, p.y) / p.z.abs().max(1e-12) };
    let uv = Vec2::splat(0.5) + 0.5 * s / image_plane.max(Vec2::splat(1e-12));
    if uv.is_finite() {
        uv
    } else {
        Vec2::splat(0.5)
    }
}

/// envFog's `layer` for the state's ray: the constant, or the connected texture evaluated
/// at the screen position of the point one unit along the ray ([`screen_uv`]: for an eye
/// ray, its pixel's place in the image).
fn env_fog_layer(ctx: &mut Ctx, n: NodeId) -> f32 {
    let layer = USE_LAYER + 1;
    if !ctx.is_connected(n, layer) {
        return ctx.scalar(n, layer);
    }
    let shading = ctx.shading();
    let uv =
        screen_uv(&shading.world_to_camera, shading.image_plane, shading.orthographic, ctx.state.org + ctx.state.dir);
    crate::texture::at_uv(ctx, Vec3A::new(uv.x, uv.y, 0.0), |c| c.scalar(n, layer))
}

/// envFog's physical fog (the parameters from index 7 on; see [`crate::physical_fog`])
/// over the part `span` of the state's segment (distances from its origin).
fn physical_fog_terms(ctx: &mut Ctx, n: NodeId, span: (f32, f32)) -> VolumeTerms {
    let fog_type = ctx.int(n, 7);
    let profile = match fog_type {
        1 | 5 => Profile::Atmospheric,
        2 | 6 => Profile::Sky,
        _ => Profile::Uniform,
    };
    let water = (3..=6).contains(&fog_type).then(|| {
        Water::new(
            ctx.scalar(n, 32),
            rgb(ctx.color(n, 33)),
            rgb(ctx.color(n, 34)),
            ctx.scalar(n, 35),
            ctx.scalar(n, 36),
            ctx.scalar(n, 37),
            ctx.scalar(n, 38),
        )
    });
    let mut medium = |first: usize| {
        Medium::new(
            ctx.scalar(n, first),
            rgb(ctx.color(n, first + 1)),
            rgb(ctx.color(n, first + 2)),
            ctx.scalar(n, first + 3),
            ctx.scalar(n, first + 4),
            ctx.scalar(n, first + 5),
            ctx.scalar(n, first + 6),
        )
    };
    let media = [medium(8), medium(15)];
    let up = physical_fog::axis(ctx.int(n, 23));
    let fog = PhysicalFog {
        profile,
        media,
        up,
        planet_radius: ctx.scalar(n, 22),
        sun_dir: physical_fog::sun_direction(up, ctx.scalar(n, 26), ctx.scalar(n, 25)),
        sun: ctx.scalar(n, 24) * rgb(ctx.color(n, 27)),
        water,
        air: fog_type != 3,
    };
    let length = segment_length(&ctx.state);
    let lit = if profile == Profile::Uniform && fog_type != 3 {
        received_light(ctx, n, 28, length, None)
    } else {
        Vec3A::ZERO
    };
    fog.terms(ctx.state.org + ctx.state.dir * span.0, ctx.state.dir, span.1 - span.0, lit)
}

maya_volume!(
    /// Light fog (see the module doc).
    LIGHTFOG,
    ADSK_LIGHTFOG,
    "maya_lightfog",
    "adskMayaLightFog",
    &["color", "density", "colorBasedTransparency", "fastDropOff", "lightList"],
    light_fog_terms
);

/// The light fog's share α over a segment of length `length` (infinite allowed) of
/// density `density`: 1 − exp(−density · length) with `fast_drop_off`, else
/// 1 − exp(−density) (see the module doc).
pub fn light_fog_share(density: f32, length: f32, fast_drop_off: bool) -> f32 {
    let density = density.max(0.0);
    let through = if fast_drop_off { density * length } else { density };
    if through.is_nan() {
        return 0.0;
    }
    1.0 - (-through).exp()
}

fn light_fog_terms(ctx: &mut Ctx, n: NodeId) -> VolumeTerms {
    if carries_light(ctx) {
        return VolumeTerms::NONE;
    }
    let length = segment_length(&ctx.state);
    let alpha = light_fog_share(ctx.scalar(n, 1), length, ctx.bool(n, 3));
    let color = rgb(ctx.color(n, 0));
    let shown = if alpha > 0.0 && color != Vec3A::ZERO { received_light(ctx, n, 4, length, None) } else { Vec3A::ZERO };
    terms(alpha, color, shown, ctx.bool(n, 2))
}

/// What the fog's lights (light array parameter `list`; every light when it is empty)
/// deliver at the middle of the segment of `length` (at its origin for an infinite one),
/// from every side; with `light_scatter` each light's light is weighted by the
/// Henyey–Greenstein phase of g = 1 − `light_scatter` at the angle between the ray and
/// the direction towards the light ([`physical_fog::phase`], 1 for uniform scattering),
/// so that a fog that scatters directionally glows around the lights it is seen against.
pub(crate) fn received_light(ctx: &mut Ctx, n: NodeId, list: usize, length: f32, light_scatter: Option<f32>) -> Vec3A {
    let saved = ctx.state.clone();
    let at = if length.is_finite() { saved.org + saved.dir * (0.5 * length) } else { saved.org };
    ctx.state.point = at;
    ctx.state.shadow_point = at;
    ctx.state.normal = -saved.dir;
    ctx.state.normal_geom = -saved.dir;
    let listed = ctx.array(n, list);
    let lights = ctx.light_list(if listed.array().is_empty() { 3 } else { 0 }, &listed);
    let mut sum = Vec3A::ZERO;
    for light in lights {
        let mut lp = ctx.light_loop(light);
        lp.both_sides = true;
        let mut got = Vec3A::ZERO;
        while let Some(s) = ctx.sample_light(&mut lp) {
            let weight = light_scatter.map_or(1.0, |ls| physical_fog::phase(ls, saved.dir.dot(s.dir)));
            got += rgb(s.color) * weight;
        }
        if lp.samples > 0 {
            sum += got / lp.samples as f32;
        }
    }
    ctx.state = saved;
    sum
}

/// The nodes the path engine applies as volumes: those of the camera's and the
/// materials' volume shader lists that are affine ([`shader::volume::is_affine`]), and
/// the nodes Maya's volume samplers among them are connected to.
fn applied_volume_nodes(shading: &shader::Shading) -> Vec<shader::NodeId> {
    let heads = std::iter::once(shading.volume).chain(shading.materials.iter().map(|m| m.volume)).flatten();
    let mut applied = Vec::new();
    for head in heads.filter(|&v| shader::volume::is_affine(shading, v)) {
        let mut node = Some(head);
        let mut guard = 0;
        while let Some(n) = node.filter(|_| guard < 1024) {
            applied.push(n);
            let x = &shading.graph.nodes[n as usize];
            if let Some(shader::Slot::Connect { node: source, .. }) =
                x.slots.first().filter(|_| x.imp.is_some_and(|i| i.volume_affine.is_some()))
            {
                applied.push(*source);
            }
            node = x.next;
            guard += 1;
        }
    }
    applied
}

/// The warnings, at the shader's position, about the fogs of `shading`: each fog the path
/// engine leaves out (it applies the camera's and the materials' volumes when every
/// shader in them is a fog, see [`applied_volume_nodes`]).
pub fn fog_warnings(shading: &shader::Shading) -> Vec<mi::Diagnostic> {
    let applied = applied_volume_nodes(shading);
    let mut warnings = Vec::new();
    for (i, node) in shading.graph.nodes.iter().enumerate() {
        let name = node.decl.name.as_str();
        if !matches!(
            name,
            "maya_envfog"
                | "adskMayaEnvFog"
                | "maya_lightfog"
                | "adskMayaLightFog"
                | "maya_volumefog"
                | "adskMayaVolumeFog"
        ) {
            continue;
        }
        if !applied.contains(&(i as shader::NodeId)) {
            warnings.push(mi::Diagnostic::warning(
                node.span,
                format!(
                    "'{name}': the path engine applies fogs only in volumes made of fogs (the camera's or a material's); it renders without this one"
                ),
            ));
        }
    }
    warnings
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The height band clips a segment to the part between the two heights, in either
    /// direction, open above when the top is below the bottom; a level segment is all in
    /// or all out.
    #[test]
    fn the_height_band_clips_the_segment() {
        let down = Vec3A::new(0.0, -1.0, 0.0);
        let close = |a: f32, b: f32| (a - b).abs() < 1e-6;
        assert!(close(length_in_band(Vec3A::new(0.0, 4.0, 0.0), down, 4.0, 1.0, 3.0), 2.0));
        assert!(close(length_in_band(Vec3A::new(0.0, 4.0, 0.0), down, 2.0, 1.0, 3.0), 1.0));
        assert!(close(length_in_band(Vec3A::new(0.0, 0.0, 0.0), -down, 10.0, 1.0, 3.0), 2.0));
        assert!(close(length_in_band(Vec3A::new(0.0, 4.0, 0.0), down, f32::INFINITY, 1.0, -5.0), 3.0));
        assert_eq!(length_in_band(Vec3A::new(0.0, 4.0, 0.0), -down, f32::INFINITY, 1.0, -5.0), f32::INFINITY);
        assert!(close(length_in_band(Vec3A::new(0.0, 4.0, 0.0), down, 4.0, 1.0, -5.0), 3.0));
        let slanted = Vec3A::new(0.6, -0.8, 0.0);
        assert!(close(length_in_band(Vec3A::new(0.0, 4.0, 0.0), slanted, 5.0, 1.0, 3.0), 2.5));
        assert_eq!(length_in_band(Vec3A::new(0.0, 2.0, 0.0), Vec3A::X, 7.0, 1.0, 3.0), 7.0);
        assert_eq!(length_in_band(Vec3A::new(0.0, 5.0, 0.0), Vec3A::X, 7.0, 1.0, 3.0), 0.0);
    }

    /// The clip distances cut a segment to the part between them; an infinite one ends at
    /// the far distance; a segment ending before the near distance has none.
    #[test]
    fn clip_distances_cut_the_segment() {
        assert_eq!(clip_span(4.0, 1.0, 2.5), Some((1.0, 2.5)));
        assert_eq!(clip_span(2.0, 1.0, 2.5), Some((1.0, 2.0)));
        assert_eq!(clip_span(f32::INFINITY, 1.0, 2.5), Some((1.0, 2.5)));
        assert_eq!(clip_span(0.5, 1.0, 2.5), None);
        assert_eq!(clip_span(4.0, -3.0, 2.5), Some((0.0, 2.5)));
        assert_eq!(clip_span(4.0, 2.0, 1.0), None);
    }

    /// The shares against their formulas: linear up to saturation, exponential in the
    /// distance with fast drop-off, one unit's worth without.
    #[test]
    fn fog_shares() {
        assert!((env_fog_share(4.0, 10.0) - 0.4).abs() < 1e-7);
        assert_eq!(env_fog_share(40.0, 10.0), 1.0);
        assert_eq!(env_fog_share(f32::INFINITY, 10.0), 1.0);
        assert_eq!(env_fog_share(4.0, 0.0), 0.0);
        assert!((light_fog_share(0.2, 4.0, true) - (1.0 - (-0.8f32).exp())).abs() < 1e-7);
        assert!((light_fog_share(0.2, 4.0, false) - (1.0 - (-0.2f32).exp())).abs() < 1e-7);
        assert_eq!(light_fog_share(0.2, f32::INFINITY, true), 1.0);
        assert_eq!(light_fog_share(0.0, f32::INFINITY, true), 0.0);
    }

    /// Colour-based transparency covers by the fog's colour, the other mode alike in all
    /// channels; the fog's own light is added in both.
    #[test]
    fn covering_with_and_without_colour_based_transparency() {
        let fog = Vec3A::new(1.0, 0.5, 0.0);
        let mut out = Value::Color(shader::Color::new(0.8, 0.8, 0.8, 1.0));
        apply(&mut out, terms(0.5, fog, Vec3A::splat(2.0), true));
        let c = out.color();
        let want = [0.8 * 0.5 + 1.0, 0.8 * 0.75 + 0.5, 0.8];
        assert!((c.x - want[0]).abs() < 1e-6 && (c.y - want[1]).abs() < 1e-6 && (c.z - want[2]).abs() < 1e-6, "{c:?}");
        let mut out = Value::Color(shader::Color::new(0.8, 0.8, 0.8, 1.0));
        apply(&mut out, terms(0.5, fog, Vec3A::ZERO, false));
        let c = out.color();
        assert!((c.x - 0.4).abs() < 1e-6 && (c.y - 0.4).abs() < 1e-6 && (c.z - 0.4).abs() < 1e-6, "{c:?}");
    }

    /// The screen position by hand: a camera at the origin looking down −Z with an image
    /// plane of half extents (1, ½) at distance 1 puts (0, 0, −1) at the centre, (1, ½, −1)
    /// at the top right, (−½, −¼, −2) at (0.375, 0.375); orthographic with half extents
    /// (4, 2) puts (2, 1, −5) at (0.75, 0.75); a point behind takes its mirror's place.
    #[test]
    fn screen_positions_by_hand() {
        let id = Affine3A::IDENTITY;
        let plane = Vec2::new(1.0, 0.5);
        let close = |a: Vec2, b: Vec2| assert!((a - b).length() < 1e-6, "{a} vs {b}");
        close(screen_uv(&id, plane, false, Vec3A::new(0.0, 0.0, -1.0)), Vec2::splat(0.5));
        close(screen_uv(&id, plane, false, Vec3A::new(1.0, 0.5, -1.0)), Vec2::ONE);
        close(screen_uv(&id, plane, false, Vec3A::new(-0.5, -0.25, -2.0)), Vec2::splat(0.375));
        close(screen_uv(&id, Vec2::new(4.0, 2.0), true, Vec3A::new(2.0, 1.0, -5.0)), Vec2::splat(0.75));
        close(screen_uv(&id, plane, false, Vec3A::new(0.5, 0.0, 1.0)), Vec2::new(0.75, 0.5));
        // A camera moved to (0, 0, 5): the world origin is straight ahead.
        let moved = Affine3A::from_translation(glam::Vec3::new(0.0, 0.0, -5.0));
        close(screen_uv(&moved, plane, false, Vec3A::ZERO), Vec2::splat(0.5));
        // At the camera itself: the centre, not a NaN.
        close(screen_uv(&id, plane, false, Vec3A::ZERO), Vec2::splat(0.5));
    }
}
