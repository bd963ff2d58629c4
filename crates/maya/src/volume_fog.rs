//! Maya's volumeFog material (`maya_volumefog` / `adskMayaVolumeFog`): fog of a colour and
//! a transparency filling the inside of the object whose shading group's volume it is,
//! optionally fading towards the edge of a shape.
//!
//! It returns Maya's volume output struct for the segment the state describes (the ray
//! from `state.org` to `state.point` inside the object); the shading group's volume
//! sampler ([`crate::volume`]) composites it: behind ⊙ `outTransparency` + `outColor`.
//!
//! Parameters (Maya's volumeFog attributes; the defaults are those of Maya's node
//! reference where it gives them): `color` (white), `transparency` (0.5: the reference
//! calls it the volume's colour transparency), `incandescence` (black), `glowIntensity`
//! (0), `density` (1), `densityMode` (1), `dropoffShape` (0), `edgeDropoff` (0.5),
//! `dropoffMethod` (0), `dropoffSubtract` (1), `illuminated` (off), `lightScatter` (1),
//! `lightList` (every light when empty), `axialDropoff` (0.3, the reference's default:
//! "how quickly the density drops off down the axis of a cone").
//!
//! mira's reading (the reference describes the attributes, not the formulas):
//! - the fog lets `transparency`^τ through per channel, τ = ∫ ρ dl the density crossed:
//!   one scene unit of density 1 passes `transparency`, so a longer path or a denser fog
//!   passes exponentially less (Beer–Lambert with σ = −ln `transparency` per unit of
//!   density); lengths in object space with `densityMode` 1 (the reference: object-space
//!   density keeps the look when the object is scaled), world space with 0;
//! - ρ = `density` × the dropoff d(p) at each point (in the object space of the surface the
//!   ray reached) with `dropoffMethod` 0 (Scale Opacity), max(`density` − (1 − d)·
//!   `dropoffSubtract`, 0) with 1 (Subtract Density), as the reference describes them;
//! - `dropoffShape`: the reference lists Cone, Sphere, Cube and Light Cone but not their
//!   numbers; mira reads 0 off (no dropoff: the node's default, and the case of fog in
//!   arbitrary geometry), 1 Sphere (r = |p|, radius 1 as Maya's volume primitives), 2 Cube
//!   (r = max |pᵢ|, side 2), 3 Cone and 4 Light Cone. The edge fade of a measure r (1 on
//!   the shape's boundary) is 1 inside r ≤ 1 − `edgeDropoff`, 0 outside r ≥ 1, a
//!   smoothstep between (`edgeDropoff` 0: a hard edge, 1: a fade from the edge to the
//!   centre, as the reference says);
//! - the cones (mira's reading; the reference says only that the cone's density drops
//!   off down its axis by `axialDropoff` and that Light Cone's fade occurs near the
//!   cone's point): the unit cone of Maya's cone primitive's proportions, apex (0, 1, 0),
//!   base of radius 1 at y = −1; with a = (1 − y)/2 the share of the way from the apex
//!   down the axis and ρ the distance from the axis, the side measure is r = ρ / a (the
//!   cone's outside: a ∉ (0, 1] or ρ ≥ a). Cone: d = fade(r) · (1 − `axialDropoff`·a)
//!   (linear down the axis, full at the apex); Light Cone (the fog of a light at the apex):
//!   the same times the fade over the part of the axis nearest the apex,
//!   smoothstep(a / `edgeDropoff`);
//! - it shows `color` (× the light its lights deliver at the segment's middle when
//!   `illuminated`, each light's weighted by the Henyey–Greenstein phase of g = 1 −
//!   `lightScatter` at the angle between the ray and the light, normalised to 1 for
//!   uniform scattering: `lightScatter` 1 scatters in all directions, towards 0 forwards,
//!   the halos around lights the reference describes) plus `incandescence`, over the
//!   share it covers: `outColor` = (1 − T) ⊙ shown, `outTransparency` = T,
//!   `outGlowColor` = `glowIntensity` · (1 − T) ⊙ `color`, `outMatteOpacity` = 1 − mean T.
//!
//! The integral runs in [`STEPS`] steps, exact where the density is constant.

use glam::{Affine3A, Vec3A};
use shader::volume::segment_length;
use shader::{Ctx, NodeId, RayType, Value};

use crate::fog::received_light;
use crate::maya_shader;
use crate::values::{rgb, rgba, write_struct};

/// Steps of the integration along the segment.
pub const STEPS: usize = 32;

/// The shape the density fades towards the edge of (`dropoffShape`; see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Dropoff {
    /// No dropoff (0).
    Off,
    /// The unit sphere (1).
    Sphere,
    /// The cube [−1, 1]³ (2).
    Cube,
    /// The unit cone, apex (0, 1, 0), base radius 1 at y = −1 (3), with its axial dropoff.
    Cone {
        /// `axialDropoff`.
        axial: f32,
    },
    /// The unit cone faded near its apex too (4), with its axial dropoff.
    LightCone {
        /// `axialDropoff`.
        axial: f32,
    },
}

/// The fade of a measure `r` that is 1 on a shape's boundary over an edge band of width
/// `edge` inside it: 0 for r ≥ 1, 1 for r ≤ 1 − `edge`, a smoothstep between.
fn edge_fade(r: f32, edge: f32) -> f32 {
    if r >= 1.0 {
        return 0.0;
    }
    if edge <= 0.0 {
        return 1.0;
    }
    smoothstep((1.0 - r) / edge)
}

/// 3x² − 2x³ on x clamped to [0, 1].
fn smoothstep(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

impl Dropoff {
    /// The shape of `dropoffShape` `v` with axial dropoff `axial` (the cones').
    pub fn from_param(v: i32, axial: f32) -> Dropoff {
        match v {
            1 => Dropoff::Sphere,
            2 => Dropoff::Cube,
            3 => Dropoff::Cone { axial },
            4 => Dropoff::LightCone { axial },
            _ => Dropoff::Off,
        }
    }

    /// The dropoff d at object-space point `p` with edge width `edge` (see the module doc).
    pub fn at(self, p: Vec3A, edge: f32) -> f32 {
        match self {
            Dropoff::Off => 1.0,
            Dropoff::Sphere => edge_fade(p.length(), edge),
            Dropoff::Cube => edge_fade(p.abs().max_element(), edge),
            Dropoff::Cone { axial } | Dropoff::LightCone { axial } => {
                // The share of the way down the axis from the apex, and the side measure.
                let a = (1.0 - p.y) * 0.5;
                if a <= 0.0 || a > 1.0 {
                    return 0.0;
                }
                let rho = (p.x * p.x + p.z * p.z).sqrt();
                let along = (1.0 - axial * a).max(0.0);
                let d = edge_fade(rho / a, edge) * along;
                match self {
                    Dropoff::LightCone { .. } if edge > 0.0 => d * smoothstep(a / edge),
                    _ => d,
                }
            }
        }
    }
}

maya_shader!(
    /// Maya's volumeFog (see the module doc).
    VOLUMEFOG,
    ADSK_VOLUMEFOG,
    "maya_volumefog",
    "adskMayaVolumeFog",
    &[
        "color",
        "transparency",
        "incandescence",
        "glowIntensity",
        "density",
        "densityMode",
        "dropoffShape",
        "edgeDropoff",
        "dropoffMethod",
        "dropoffSubtract",
        "illuminated",
        "lightScatter",
        "lightList",
        "axialDropoff"
    ],
    volume_fog
);

/// The density crossed (τ) along the segment from `org` along unit `dir` over `length`
/// (world units), with the points and lengths taken through `world_to_object` when
/// `object_space`: `density` shaped by `dropoff` (`edge`) and the dropoff method
/// (`subtract`: `Some(dropoffSubtract)` for Subtract Density).
#[allow(clippy::too_many_arguments)]
pub fn density_crossed(
    org: Vec3A,
    dir: Vec3A,
    length: f32,
    world_to_object: &Affine3A,
    object_space: bool,
    density: f32,
    dropoff: Dropoff,
    edge: f32,
    subtract: Option<f32>,
) -> f32 {
    if length.is_nan() || length <= 0.0 || density <= 0.0 {
        return 0.0;
    }
    if !length.is_finite() {
        // A ray inside a volume that never leaves it: saturated where there is fog.
        return if dropoff == Dropoff::Off { f32::INFINITY } else { 0.0 };
    }
    let scale = if object_space { world_to_object.transform_vector3a(dir).length() } else { 1.0 };
    let dt = length / STEPS as f32;
    let mut tau = 0.0;
    for i in 0..STEPS {
        let p = org + dir * ((i as f32 + 0.5) * dt);
        let d = dropoff.at(world_to_object.transform_point3a(p), edge);
        let rho = match subtract {
            None => density * d,
            Some(s) => (density - (1.0 - d) * s).max(0.0),
        };
        tau += rho * dt * scale;
    }
    tau
}

/// `transparency`^τ per channel (a transparency of 0 passes nothing through any fog).
pub fn transmittance(transparency: Vec3A, tau: f32) -> Vec3A {
    if tau <= 0.0 {
        return Vec3A::ONE;
    }
    transparency.clamp(Vec3A::ZERO, Vec3A::ONE).to_array().map(|t| if t <= 0.0 { 0.0 } else { t.powf(tau) }).into()
}

fn volume_fog(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let length = segment_length(&ctx.state);
    let dropoff = Dropoff::from_param(ctx.int(n, 6), ctx.scalar(n, 13));
    let subtract = (ctx.int(n, 8) == 1).then(|| ctx.scalar(n, 9));
    let (object_space, density, edge) = (ctx.int(n, 5) != 0, ctx.scalar(n, 4), ctx.scalar(n, 7));
    let (org, dir, world_to_object) = (ctx.state.org, ctx.state.dir, ctx.state.world_to_object);
    let tau = density_crossed(org, dir, length, &world_to_object, object_space, density, dropoff, edge, subtract);
    let t = transmittance(rgb(ctx.color(n, 1)), tau);
    let cover = Vec3A::ONE - t;
    let color = rgb(ctx.color(n, 0));
    let light_ray = matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow);
    let shown = if light_ray || cover == Vec3A::ZERO {
        Vec3A::ZERO
    } else {
        let lit = if ctx.bool(n, 10) {
            let scatter = ctx.scalar(n, 11);
            received_light(ctx, n, 12, length, Some(scatter))
        } else {
            Vec3A::ONE
        };
        color * lit + rgb(ctx.color(n, 2))
    };
    let t_mean = (t.x + t.y + t.z) / 3.0;
    let glow = ctx.scalar(n, 3) * cover * color;
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(cover * shown, 1.0 - t_mean))),
            ("outTransparency", Value::Color(rgba(t, t_mean))),
            ("outGlowColor", Value::Color(rgba(glow, 1.0))),
            ("outMatteOpacity", Value::Color(rgba(Vec3A::splat(1.0 - t_mean), 1.0 - t_mean))),
        ],
    );
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dropoff is 1 inside the edge band, 0 outside the shape, a smoothstep across the
    /// band (½ in its middle); a hard edge without a band.
    #[test]
    fn dropoff_fades_across_the_edge_band() {
        let s = Dropoff::Sphere;
        assert_eq!(s.at(Vec3A::new(0.4, 0.0, 0.0), 0.5), 1.0);
        assert!((s.at(Vec3A::new(0.0, 0.75, 0.0), 0.5) - 0.5).abs() < 1e-6);
        assert_eq!(s.at(Vec3A::new(0.0, 0.0, 1.2), 0.5), 0.0);
        assert_eq!(s.at(Vec3A::new(0.0, 0.0, 0.99), 0.0), 1.0);
        let c = Dropoff::Cube;
        assert_eq!(c.at(Vec3A::new(0.9, 0.9, 0.9), 0.0), 1.0);
        assert_eq!(s.at(Vec3A::new(0.9, 0.9, 0.9), 0.0), 0.0);
        assert_eq!(Dropoff::from_param(0, 0.3).at(Vec3A::splat(5.0), 0.5), 1.0);
    }

    /// The cone (apex (0, 1, 0), base radius 1 at y = −1) at known points: on the axis
    /// a = (1 − y)/2 of the way down, the axial dropoff 1 − axial·a; across the side band
    /// the smoothstep of (1 − ρ/a)/edge; outside (above the apex, below the base, beyond
    /// the side) 0. The light cone fades over the edge band nearest the apex too.
    #[test]
    fn cone_dropoffs_at_known_points() {
        let cone = Dropoff::from_param(3, 0.3);
        let close = |a: f32, b: f32| (a - b).abs() < 1e-6;
        // On the axis at y = 0 (a = ½): 1 − 0.3·½.
        assert!(close(cone.at(Vec3A::ZERO, 0.5), 0.85));
        // Half way across the side band at a = ½ (edge 0.5: band r ∈ [0.5, 1]): r = 0.75.
        assert!(close(cone.at(Vec3A::new(0.375, 0.0, 0.0), 0.5), 0.5 * 0.85));
        // Inside the band's inner edge: full side fade.
        assert!(close(cone.at(Vec3A::new(0.0, 0.0, 0.2), 0.5), 0.85));
        for outside in [Vec3A::new(0.0, 1.5, 0.0), Vec3A::new(0.0, -1.2, 0.0), Vec3A::new(0.6, 0.0, 0.0)] {
            assert_eq!(cone.at(outside, 0.5), 0.0, "{outside:?}");
        }
        // Without axial dropoff and edge, the whole inside is 1 (a hard cone).
        assert_eq!(Dropoff::from_param(3, 0.0).at(Vec3A::new(0.0, 0.9, 0.0), 0.0), 1.0);
        // The light cone near its apex: on the axis at a = 0.1, edge 0.5 — smoothstep(0.2).
        let light = Dropoff::from_param(4, 0.0);
        let a = 0.1f32;
        let x = a / 0.5;
        assert!(close(light.at(Vec3A::new(0.0, 1.0 - 2.0 * a, 0.0), 0.5), x * x * (3.0 - 2.0 * x)));
        // Far from the apex it is the cone's.
        assert!(close(
            light.at(Vec3A::new(0.0, -0.5, 0.0), 0.5),
            Dropoff::from_param(3, 0.0).at(Vec3A::new(0.0, -0.5, 0.0), 0.5)
        ));
    }

    /// Through the middle of the unit sphere with a hard edge the fog crossed is density ×
    /// 2 (the chord), × the object's scale in object space; Subtract Density takes
    /// dropoffSubtract off where the dropoff is 0 (here: all of the outside part). Within
    /// one step's share at each edge (a step is 6/32 of the segment).
    #[test]
    fn density_crossed_follows_shape_and_space() {
        let id = Affine3A::IDENTITY;
        let org = Vec3A::new(0.0, 0.0, -3.0);
        let tau = density_crossed(org, Vec3A::Z, 6.0, &id, true, 0.5, Dropoff::Sphere, 0.0, None);
        let step = 6.0 / STEPS as f32;
        assert!((tau - 1.0).abs() <= 0.5 * step, "{tau}");
        let half = Affine3A::from_scale(glam::Vec3::splat(0.5));
        let tau = density_crossed(org * 2.0, Vec3A::Z, 12.0, &half, true, 0.5, Dropoff::Sphere, 0.0, None);
        assert!((tau - 1.0).abs() <= 0.5 * step, "object space: {tau}");
        let tau = density_crossed(org * 2.0, Vec3A::Z, 12.0, &half, false, 0.5, Dropoff::Sphere, 0.0, None);
        assert!((tau - 2.0).abs() <= step, "world space: {tau}");
        let tau = density_crossed(org, Vec3A::Z, 6.0, &id, true, 1.0, Dropoff::Off, 0.0, Some(1.0));
        assert!((tau - 6.0).abs() < 1e-4, "{tau}");
        let tau = density_crossed(org, Vec3A::Z, 6.0, &id, true, 1.5, Dropoff::Sphere, 0.0, Some(1.0));
        // Inside (2 units) 1.5, outside (4 units) 0.5.
        assert!((tau - 5.0).abs() <= step, "{tau}");
    }

    /// One unit of density 1 passes the transparency; twice as much passes its square.
    #[test]
    fn transmittance_is_transparency_to_the_density_crossed() {
        let t = transmittance(Vec3A::new(0.5, 0.25, 0.0), 2.0);
        assert!((t - Vec3A::new(0.25, 0.0625, 0.0)).length() < 1e-6, "{t:?}");
        assert_eq!(transmittance(Vec3A::splat(0.3), 0.0), Vec3A::ONE);
    }
}
