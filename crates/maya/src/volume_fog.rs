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
//! "how quickly the density drops off down the axis of a cone"), `colorRampInput` (0) and
//! `colorRamp` (an array of {`colorRamp_Position`, `colorRamp_Color`,
//! `colorRamp_Interp`}, interpolation 0 none, 1 linear, 2 smooth, 3 spline; empty: the
//! fog keeps `color`).
//!
//! **The colour ramp.** The reference: `colorRampInput` chooses the input to the ramp —
//! Transparency (0, the default): the colour follows the transparency within the volume,
//! more transparent regions taking the ramp's left end, wholly opaque ones its right end;
//! Concentric (1): the distance to the volume's centre; Y Gradient (2): the position
//! along the y axis; Ignore (3): `color` instead of the ramp (the reference gives the
//! modes in this order, not their numbers; mira numbers them so). mira's reading, at each
//! point p of the segment (object space, where the dropoff is measured): Transparency's
//! x = 1 − mean(`transparency`^ρ(p)), the transparency of one unit of the fog's local
//! density ρ (so a fading edge runs from the ramp's left end inwards); Concentric's
//! x = |p| (0 at the centre, 1 on the unit sphere of Maya's volume primitives); Y
//! Gradient's x = (p_y + 1)/2 (the bottom of the unit cube or sphere at 0, its top at 1).
//! The colour the fog shows is then the ramp's colour where it is, each step weighted by
//! the share of the ray it covers there: Σ T_i ⊙ (1 − t_i) ⊙ C(x_i), T_i what passes
//! the fog before step i and t_i step i's transmittance (for a constant colour exactly
//! (1 − T) ⊙ `color`, the case without a ramp); `outColor` is that × the light received
//! when `illuminated` plus (1 − T) ⊙ `incandescence`, and the glow follows that colour.
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
use crate::utility::Ramp;
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
        "axialDropoff",
        "colorRampInput",
        "colorRamp"
    ],
    volume_fog
);

/// The fog along a segment: where it is and how dense (see [`density_crossed`]).
#[derive(Clone, Copy, Debug)]
pub struct Segment<'a> {
    /// The segment's origin (world).
    pub org: Vec3A,
    /// Its unit direction (world).
    pub dir: Vec3A,
    /// Its length (world units).
    pub length: f32,
    /// World → the volume object's space.
    pub world_to_object: &'a Affine3A,
    /// Lengths in object space (`densityMode` 1) rather than world space.
    pub object_space: bool,
    /// `density`.
    pub density: f32,
    /// The shape the density fades towards the edge of.
    pub dropoff: Dropoff,
    /// `edgeDropoff`.
    pub edge: f32,
    /// `Some(dropoffSubtract)` for Subtract Density.
    pub subtract: Option<f32>,
}

impl Segment<'_> {
    /// The integration steps of a finite segment: each step's middle in object space, the
    /// local density ρ there and the density crossed over the step (ρ × its length).
    fn steps(&self) -> impl Iterator<Item = (Vec3A, f32, f32)> + '_ {
        let scale = if self.object_space { self.world_to_object.transform_vector3a(self.dir).length() } else { 1.0 };
        let dt = self.length / STEPS as f32;
        (0..STEPS).map(move |i| {
            let p = self.world_to_object.transform_point3a(self.org + self.dir * ((i as f32 + 0.5) * dt));
            let d = self.dropoff.at(p, self.edge);
            let rho = match self.subtract {
                None => self.density * d,
                Some(s) => (self.density - (1.0 - d) * s).max(0.0),
            };
            (p, rho, rho * dt * scale)
        })
    }

    /// Whether the segment holds no fog (no length or no density).
    fn is_empty(&self) -> bool {
        self.length.is_nan() || self.length <= 0.0 || self.density <= 0.0
    }
}

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
    let seg = Segment { org, dir, length, world_to_object, object_space, density, dropoff, edge, subtract };
    seg_density_crossed(&seg)
}

fn seg_density_crossed(seg: &Segment) -> f32 {
    if seg.is_empty() {
        return 0.0;
    }
    if !seg.length.is_finite() {
        // A ray inside a volume that never leaves it: saturated where there is fog.
        return if seg.dropoff == Dropoff::Off { f32::INFINITY } else { 0.0 };
    }
    seg.steps().map(|(_, _, dtau)| dtau).sum()
}

/// What indexes volumeFog's colour ramp (`colorRampInput`; see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RampInput {
    /// 0: the local transparency (transparent: the left end, opaque: the right end).
    Transparency,
    /// 1: the distance from the volume's centre.
    Concentric,
    /// 2: the height along the volume's y axis, bottom to top.
    YGradient,
    /// 3 (and unknown values): `color`, no ramp.
    Ignore,
}

impl RampInput {
    /// Maya's enumeration (see the module doc).
    pub fn from_maya(v: i32) -> RampInput {
        match v {
            0 => RampInput::Transparency,
            1 => RampInput::Concentric,
            2 => RampInput::YGradient,
            _ => RampInput::Ignore,
        }
    }

    /// The ramp position at object-space point `p` of local density `rho` in a fog of
    /// `transparency` (`None` for Ignore).
    pub fn position(self, p: Vec3A, rho: f32, transparency: Vec3A) -> Option<f32> {
        let x = match self {
            RampInput::Transparency => {
                let t = transmittance(transparency, rho);
                1.0 - (t.x + t.y + t.z) / 3.0
            }
            RampInput::Concentric => p.length(),
            RampInput::YGradient => 0.5 * (p.y + 1.0),
            RampInput::Ignore => return None,
        };
        Some(x)
    }
}

/// The colour a fog of `transparency` shows along `seg` with its colour from `ramp` at
/// the positions `input` gives: Σ T_i ⊙ (1 − t_i) ⊙ C(x_i) (see the module doc), and the
/// segment's transmittance T. `None` for Ignore.
pub fn ramp_colour_crossed(
    seg: &Segment,
    transparency: Vec3A,
    input: RampInput,
    ramp: impl Fn(f32) -> Vec3A,
) -> Option<(Vec3A, Vec3A)> {
    input.position(Vec3A::ZERO, 0.0, transparency)?;
    if seg.is_empty() {
        return Some((Vec3A::ZERO, Vec3A::ONE));
    }
    if !seg.length.is_finite() {
        // A segment that never ends: all it shows is the fog where it starts.
        let tau = seg_density_crossed(seg);
        let t = transmittance(transparency, tau);
        let p = seg.world_to_object.transform_point3a(seg.org);
        let d = seg.dropoff.at(p, seg.edge);
        let x = input.position(p, seg.density * d, transparency).unwrap_or(0.0);
        return Some(((Vec3A::ONE - t) * ramp(x), t));
    }
    let (mut shown, mut passed) = (Vec3A::ZERO, Vec3A::ONE);
    for (p, rho, dtau) in seg.steps() {
        let t = transmittance(transparency, dtau);
        let x = input.position(p, rho, transparency).unwrap_or(0.0);
        shown += passed * (Vec3A::ONE - t) * ramp(x);
        passed *= t;
    }
    Some((shown, passed))
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
    let seg =
        Segment { org, dir, length, world_to_object: &world_to_object, object_space, density, dropoff, edge, subtract };
    let transparency = rgb(ctx.color(n, 1));
    let color = rgb(ctx.color(n, 0));
    let input = RampInput::from_maya(ctx.int(n, 14));
    let ramp = Ramp::read(&ctx.array(n, 15), "colorRamp", "Color", color);
    // With a ramp: the colour shown before lighting (its share of the ray included) and
    // the transmittance.
    let ramped = if ramp.is_empty() { None } else { ramp_colour_crossed(&seg, transparency, input, |x| ramp.at(x)) };
    let t = match ramped {
        Some((_, t)) => t,
        None => transmittance(transparency, seg_density_crossed(&seg)),
    };
    let cover = Vec3A::ONE - t;
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
        let incandescence = rgb(ctx.color(n, 2));
        match ramped {
            Some((fog_colour, _)) => fog_colour * lit + cover * incandescence,
            None => cover * (color * lit + incandescence),
        }
    };
    let t_mean = (t.x + t.y + t.z) / 3.0;
    let glow = match ramped {
        Some((fog_colour, _)) => ctx.scalar(n, 3) * fog_colour,
        None => ctx.scalar(n, 3) * cover * color,
    };
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(shown, 1.0 - t_mean))),
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

    /// A plain fog (no dropoff, density 1, world space) of transparency ½ along `length`
    /// from `org` along `dir`.
    fn plain<'a>(org: Vec3A, dir: Vec3A, length: f32, id: &'a Affine3A) -> Segment<'a> {
        Segment {
            org,
            dir,
            length,
            world_to_object: id,
            object_space: false,
            density: 1.0,
            dropoff: Dropoff::Off,
            edge: 0.0,
            subtract: None,
        }
    }

    /// A two-colour ramp without interpolation: red below ½, green from ½.
    fn red_green(x: f32) -> Vec3A {
        let points = vec![(0.0, Vec3A::X, 0), (0.5, Vec3A::Y, 0)];
        Ramp::new(points, Vec3A::ZERO).at(x)
    }

    /// Each ramp input against its hand-computed colour (the step boundaries fall on the
    /// ramp's: exact up to rounding, 1e-5). Transparency ½, density 1: a unit of fog
    /// passes ½, so what passes after a length l is 0.5^l.
    #[test]
    fn each_ramp_input_colours_the_fog_as_computed_by_hand() {
        let id = Affine3A::IDENTITY;
        let half = Vec3A::splat(0.5);
        let close = |a: Vec3A, b: Vec3A| assert!((a - b).length() < 1e-5, "{a} vs {b}");
        // Transparency: the local transparency of density 1 is ½ everywhere → x = ½, on a
        // black-to-white linear ramp grey ½; over 2 units the fog covers 1 − ¼.
        let grey = |x: f32| Ramp::new(vec![(0.0, Vec3A::ZERO, 1), (1.0, Vec3A::ONE, 1)], Vec3A::ZERO).at(x);
        let seg = plain(Vec3A::new(0.3, 0.2, -1.0), Vec3A::Z, 2.0, &id);
        let (c, t) = ramp_colour_crossed(&seg, half, RampInput::Transparency, grey).unwrap();
        close(t, Vec3A::splat(0.25));
        close(c, Vec3A::splat(0.75 * 0.5));
        // Density 2: x = 1 − ¼ = ¾; over 1 unit the fog covers 1 − ¼.
        let seg = Segment { density: 2.0, length: 1.0, ..seg };
        let (c, _) = ramp_colour_crossed(&seg, half, RampInput::Transparency, grey).unwrap();
        close(c, Vec3A::splat(0.75 * 0.75));
        // Concentric: from the centre out along z for 2 units; red while |p| < ½ (the
        // first ½ unit: covers 1 − 0.5^0.5), green after (0.5^0.5 − 0.5^2).
        let seg = plain(Vec3A::ZERO, Vec3A::Z, 2.0, &id);
        let (c, t) = ramp_colour_crossed(&seg, half, RampInput::Concentric, red_green).unwrap();
        close(c, Vec3A::new(1.0 - 0.5f32.sqrt(), 0.5f32.sqrt() - 0.25, 0.0));
        close(t, Vec3A::splat(0.25));
        // Y gradient: up the y axis from −1 to 1; red below y = 0 (x < ½): 1 − ½, green
        // above: ½ − ¼.
        let seg = plain(Vec3A::new(0.2, -1.0, 0.1), Vec3A::Y, 2.0, &id);
        let (c, _) = ramp_colour_crossed(&seg, half, RampInput::YGradient, red_green).unwrap();
        close(c, Vec3A::new(0.5, 0.25, 0.0));
        // Downwards the order turns: green first (½), red after (¼).
        let seg = plain(Vec3A::new(0.2, 1.0, 0.1), -Vec3A::Y, 2.0, &id);
        let (c, _) = ramp_colour_crossed(&seg, half, RampInput::YGradient, red_green).unwrap();
        close(c, Vec3A::new(0.25, 0.5, 0.0));
        // Ignore: no ramp.
        assert!(ramp_colour_crossed(&seg, half, RampInput::Ignore, red_green).is_none());
        assert_eq!(RampInput::from_maya(3), RampInput::Ignore);
        assert_eq!(RampInput::from_maya(7), RampInput::Ignore);
        // A constant ramp is the plain fog: (1 − T) ⊙ colour, T as density_crossed gives.
        let seg =
            Segment { dropoff: Dropoff::Sphere, edge: 0.5, ..plain(Vec3A::new(0.1, 0.0, -1.5), Vec3A::Z, 3.0, &id) };
        let colour = Vec3A::new(0.9, 0.4, 0.2);
        let (c, t) = ramp_colour_crossed(&seg, half, RampInput::Concentric, |_| colour).unwrap();
        let tau = density_crossed(seg.org, seg.dir, seg.length, &id, false, 1.0, Dropoff::Sphere, 0.5, None);
        close(t, transmittance(half, tau));
        close(c, (Vec3A::ONE - t) * colour);
        // No fog: nothing shown, everything passes.
        let (c, t) =
            ramp_colour_crossed(&Segment { density: 0.0, ..seg }, half, RampInput::Concentric, red_green).unwrap();
        assert_eq!((c, t), (Vec3A::ZERO, Vec3A::ONE));
    }
}
