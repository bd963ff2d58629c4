//! Maya's light shaders: point, spot, directional, ambient, area and volume lights.
//!
//! A light shader runs in the light state of `shader::lights`: `org` is the point
//! on the light, `dir` runs from the light to the illuminated point, `dist` between them.
//! Every Maya light delivers `color · intensity`, divided by `dist^decayRate` for the
//! lights that decay (Maya's `nonAmbientLightShapeNode`: 0 none, 1 linear, 2 quadratic,
//! 3 cubic; the division applies below one unit too, where it brightens, as in Maya).
//!
//! Parameters shared by all (see `mayabase.mi`):
//! - `color` (colour, 1 1 1), `intensity` (scalar, 1);
//! - `useRayTraceShadows` (boolean): shadow rays filtered by the occluders' shadow
//!   shaders; `shadowColor` (colour, black): what a fully shadowed point receives, as a
//!   fraction of the light (Maya tints shadows with it: received = light ⊙ (f + (1 − f) ⊙
//!   shadowColor), f the fraction let through);
//! - `shadowRays` (integer, 1): shadow rays per light sample, to soften the shadows of a
//!   light of `lightRadius` > 0 (point, spot, ambient: a sphere of that radius around the
//!   light) or `lightAngle` > 0 (directional: the angular diameter, radians);
//! - `emitDiffuse`, `emitSpecular` (booleans, on): read by the Maya materials
//!   ([`light_role`]), which leave out the diffuse or specular part of such a light.
//!
//! The spot penumbra fades linearly in the angle across its width (mira's reading: Maya
//! documents the penumbra's extent, not its profile). The ambient light's split into an
//! omnidirectional part and a part from the light's position follows Maya's description
//! of `ambientShade`; the materials apply it ([`LightRole`]).

use glam::Vec3A;
use scene::LightKind;
use shader::{Color, Ctx, NodeId, Value};

use crate::maya_shader;

/// Whether the light being sampled is a directional (infinite) light.
fn is_directional(ctx: &Ctx) -> bool {
    ctx.state.light.and_then(|l| ctx.light(l)).is_some_and(|l| l.kind == LightKind::Directional)
}

/// Parameters every Maya light but the ambient one reads first, in this order.
const COMMON: [&str; 7] =
    ["color", "intensity", "useRayTraceShadows", "shadowColor", "shadowRays", "emitDiffuse", "emitSpecular"];

const I_COLOR: usize = 0;
const I_INTENSITY: usize = 1;
const I_SHADOWS: usize = 2;
const I_SHADOW_COLOR: usize = 3;
const I_SHADOW_RAYS: usize = 4;

/// `dist^-rate` for Maya's decay rate `rate` (clamped to 0–3).
pub fn decay(dist: f32, rate: i32) -> f32 {
    match rate.clamp(0, 3) {
        0 => 1.0,
        r => 1.0 / dist.max(1e-6).powi(r),
    }
}

/// How a light takes part in a Maya material's shading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightRole {
    /// Contributes to the diffuse term (`emitDiffuse`).
    pub diffuse: bool,
    /// Contributes to the specular term (`emitSpecular`).
    pub specular: bool,
    /// An ambient light with this `ambientShade` (0: light from all sides, 1: from the
    /// light's position only); also a volume light with `emitAmbient` (see [`VOLUME`]).
    pub ambient_shade: Option<f32>,
    /// Whether a light in the ambient role (`ambient_shade`) also lights the highlight: a
    /// volume light with `emitAmbient` and `emitSpecular` (never an ambient light).
    pub ambient_specular: bool,
    /// How a volume light turns the direction the material shades with
    /// (`volumeLightDir`); `None`: the direction towards the sampled point on the light.
    pub turn: Option<Turn>,
    /// A cylinder or cone volume light: its light comes from the nearest point of its
    /// central axis, not from its centre, where the light loop's samples point (see
    /// [`VolumeShape::source`]).
    pub axis: Option<VolumeAxis>,
}

/// A cylinder or cone volume light's placement, from which the point of its central axis
/// a lit point receives its light from follows ([`VolumeShape::source`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeAxis {
    /// The light's centre, world space.
    pub origin: Vec3A,
    /// World → light-local map of offsets from `origin`.
    pub to_local: glam::Mat3A,
}

impl VolumeAxis {
    /// The point of the axis the light arriving at world point `p` comes from (world).
    pub fn source(&self, p: Vec3A) -> Vec3A {
        CYLINDER.world_source(self.origin, self.to_local, p)
    }
}

/// A whole cylinder, standing for every shape that shines from its axis.
const CYLINDER: VolumeShape = VolumeShape { shape: 2, arc: std::f32::consts::TAU, cone_end_radius: 1.0 };

/// A volume light's direction for shading other than outwards from its centre (Maya's
/// `volumeLightDir`; see [`VOLUME`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Turn {
    /// 1, inward: the light arrives from the side away from the light's centre (the
    /// direction towards the centre reversed).
    Inward,
    /// 2, down the axis: the light arrives from this world direction (unit; the light's
    /// +y axis), as from a directional light travelling down its central axis.
    DownAxis(Vec3A),
}

impl LightRole {
    /// The direction (unit, world) the material shades a light sample with and its
    /// cosine to the unit normal `normal`, from the sample's direction towards the light
    /// `dir` at the shaded point `point` (world): towards the light's axis for a cylinder
    /// or cone volume light ([`LightRole::axis`]), then turned (see [`Turn`]).
    pub fn shading_direction(&self, point: Vec3A, normal: Vec3A, dir: Vec3A) -> (Vec3A, f32) {
        let dir = match self.axis {
            Some(axis) => (axis.source(point) - point).normalize_or(dir),
            None => dir,
        };
        let dir = match self.turn {
            None => dir,
            Some(Turn::Inward) => -dir,
            Some(Turn::DownAxis(axis)) => axis,
        };
        (dir, normal.dot(dir))
    }

    /// Whether the light loop must also return samples behind the surface (the material
    /// decides with the turned direction, or lights from all sides).
    pub fn needs_both_sides(&self) -> bool {
        self.ambient_shade.is_some() || self.turn.is_some() || self.axis.is_some()
    }
}

/// The role of light `light` (an index into the scene's lights): from its Maya light
/// shader's flags, or diffuse and specular for any other light shader.
pub fn light_role(ctx: &mut Ctx, light: u32) -> LightRole {
    let mut role = LightRole {
        diffuse: true,
        specular: true,
        ambient_shade: None,
        ambient_specular: false,
        turn: None,
        axis: None,
    };
    let Some(node) = ctx.shading().lights.get(light as usize).and_then(|l| l.shader) else { return role };
    let n = ctx.node(node);
    let param = |name: &str| -> Option<usize> {
        match n.imp {
            Some(imp) => imp.params.iter().position(|p| *p == name),
            None => n.decl.param(name),
        }
    };
    let (d, s, a) = (param("emitDiffuse"), param("emitSpecular"), param("ambientShade"));
    let ambient = n.decl.name.ends_with("ambientlight") || n.decl.name.ends_with("AmbientLight");
    let volume = matches!(n.decl.name.as_str(), "maya_volumelight" | "adskMayaVolumeLight");
    if let Some(i) = d {
        role.diffuse = ctx.bool(node, i);
    }
    if let Some(i) = s {
        role.specular = ctx.bool(node, i);
    }
    if ambient {
        role.ambient_shade = Some(a.map_or(0.45, |i| ctx.scalar(node, i)).clamp(0.0, 1.0));
    }
    if volume {
        volume_role(ctx, node, light, &mut role);
    }
    role
}

/// A volume light's `volumeLightDir` and `emitAmbient` in `role` (see [`VOLUME`]).
fn volume_role(ctx: &mut Ctx, node: NodeId, light: u32, role: &mut LightRole) {
    role.turn = match ctx.int(node, I_VOLUME_DIR) {
        1 => Some(Turn::Inward),
        2 => {
            // The light's +y axis in world space: the inverse of its world → local map
            // applied to local +y.
            let axis = ctx.light(light).map_or(Vec3A::Y, |l| (l.to_local.inverse() * Vec3A::Y).normalize_or(Vec3A::Y));
            Some(Turn::DownAxis(axis))
        }
        _ => None,
    };
    if matches!(ctx.int(node, I_SHAPE), 2 | 3) {
        role.axis = ctx.light(light).map(|l| VolumeAxis { origin: l.origin, to_local: l.to_local });
    }
    if ctx.bool(node, I_EMIT_AMBIENT) {
        // Half from the light's direction with emitDiffuse, else from all sides alike.
        role.ambient_shade = Some(if role.diffuse { 0.5 } else { 0.0 });
        role.ambient_specular = role.specular;
    }
}

/// Where shadow rays start their way to the light: jittered over a sphere of `radius`
/// around the light's point (`radius` 0: the point itself).
enum Spread {
    Radius(f32),
    /// Half the angular diameter of a directional light, radians.
    Angle(f32),
}

/// Applies raytraced shadows to `color` (in the light state): the fraction let through,
/// averaged over `shadowRays` rays when the light is soft, mixed with `shadowColor`.
fn shadows(ctx: &mut Ctx, n: NodeId, color: Color, spread: Spread) -> Color {
    if !ctx.bool(n, I_SHADOWS) {
        return color;
    }
    let soft = match spread {
        Spread::Radius(r) => r > 0.0,
        Spread::Angle(a) => a > 0.0,
    };
    let rays = if soft { ctx.int(n, I_SHADOW_RAYS).clamp(1, 1024) as u32 } else { 1 };
    let saved = ctx.state.clone();
    let point = saved.point;
    let site = ctx.next_site();
    let mut through = Color::ZERO;
    for i in 0..rays {
        let u = if soft { ctx.sample2(site, i, rays) } else { glam::Vec2::splat(0.5) };
        match spread {
            Spread::Radius(r) if r > 0.0 => {
                let q = saved.org + r * uniform_sphere(u);
                let d = point - q;
                let dist = d.length();
                if dist > 0.0 {
                    ctx.state.dir = d / dist;
                    ctx.state.dist = dist;
                }
            }
            Spread::Angle(a) if a > 0.0 => {
                ctx.state.dir = cone_dir(saved.dir, a, u);
            }
            _ => {}
        }
        let mut f = Color::ONE;
        ctx.trace_shadow(&mut f);
        through += f;
        ctx.state.dir = saved.dir;
        ctx.state.dist = saved.dist;
    }
    let f = through / rays as f32;
    let shadow = ctx.color(n, I_SHADOW_COLOR);
    let filter = f + (Color::ONE - f) * shadow;
    let mut out = color * filter;
    out.w = color.w;
    out
}

/// A point on the unit sphere from two uniform numbers.
fn uniform_sphere(u: glam::Vec2) -> Vec3A {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * u.y;
    Vec3A::new(r * phi.cos(), r * phi.sin(), z)
}

/// A direction within the cone of half-angle `half` around the unit `axis`, uniform in
/// solid angle.
fn cone_dir(axis: Vec3A, half: f32, u: glam::Vec2) -> Vec3A {
    let cos_max = half.cos();
    let c = 1.0 - u.x * (1.0 - cos_max);
    let s = (1.0 - c * c).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * u.y;
    let f = bsdf::Frame::from_normal(axis);
    (f.tangent * (s * phi.cos()) + f.bitangent * (s * phi.sin()) + axis * c).normalize()
}

/// `color · intensity` of light shader `n`, alpha 1.
fn emitted(ctx: &mut Ctx, n: NodeId) -> Color {
    let c = ctx.color(n, I_COLOR) * ctx.scalar(n, I_INTENSITY);
    Color::new(c.x, c.y, c.z, 1.0)
}

fn finish(out: &mut Value, c: Color) -> bool {
    *out = Value::Color(c);
    c.x != 0.0 || c.y != 0.0 || c.z != 0.0
}

const POINT_PARAMS: &[&str] =
    &[COMMON[0], COMMON[1], COMMON[2], COMMON[3], COMMON[4], COMMON[5], COMMON[6], "decayRate", "lightRadius"];

maya_shader!(
    /// Point light: `color · intensity / dist^decayRate`, raytraced shadows softened by
    /// `lightRadius`.
    POINT,
    ADSK_POINT,
    "maya_pointlight",
    "adskMayaPointLight",
    POINT_PARAMS,
    point
);

fn point(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = emitted(ctx, n) * decay(ctx.state.dist, ctx.int(n, 7));
    let radius = ctx.scalar(n, 8);
    let c = shadows(ctx, n, c, Spread::Radius(radius));
    finish(out, c)
}

const SPOT_PARAMS: &[&str] = &[
    COMMON[0],
    COMMON[1],
    COMMON[2],
    COMMON[3],
    COMMON[4],
    COMMON[5],
    COMMON[6],
    "decayRate",
    "lightRadius",
    "coneAngle",
    "penumbraAngle",
    "dropoff",
];

maya_shader!(
    /// Spot light: a point light limited to a cone about the light's direction.
    /// `coneAngle` (radians, 40° by default) is the full opening; `penumbraAngle` widens
    /// (> 0) or narrows (< 0) it with a linear fade across the penumbra; `dropoff` is the
    /// exponent of cos α (α from the axis) that dims the light away from the axis.
    SPOT,
    ADSK_SPOT,
    "maya_spotlight",
    "adskMayaSpotLight",
    SPOT_PARAMS,
    spot
);

/// A Maya spot light's cone as its shader's parameters give it (radians): what
/// [`spot_factor`] reads, shared by the classic light and the path engine's spot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// `coneAngle`: the full opening.
    pub cone: f32,
    /// `penumbraAngle`: widens (> 0) or narrows (< 0) the cone by a linear fade in the angle.
    pub penumbra: f32,
    /// `dropoff`: the exponent of cos α inside the cone (0: none).
    pub dropoff: f32,
}

impl SpotCone {
    /// The spot factor at angle `alpha` (radians) from the axis: [`spot_factor`].
    pub fn factor(&self, alpha: f32) -> f32 {
        spot_factor(alpha, self.cone, self.penumbra, self.dropoff)
    }
}

/// The spot factor at angle `alpha` from the axis (radians).
pub fn spot_factor(alpha: f32, cone: f32, penumbra: f32, dropoff: f32) -> f32 {
    let half = 0.5 * cone;
    let (inner, outer) = if penumbra >= 0.0 { (half, half + penumbra) } else { (half + penumbra, half) };
    let edge = if alpha <= inner {
        1.0
    } else if alpha >= outer {
        0.0
    } else {
        (outer - alpha) / (outer - inner)
    };
    if edge.is_nan() || edge <= 0.0 {
        return 0.0;
    }
    let c = alpha.cos().max(0.0);
    edge * if dropoff > 0.0 { c.powf(dropoff) } else { 1.0 }
}

fn spot(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let axis = light.direction;
    let alpha = axis.dot(ctx.state.dir).clamp(-1.0, 1.0).acos();
    let f = spot_factor(alpha, ctx.scalar(n, 9), ctx.scalar(n, 10), ctx.scalar(n, 11));
    if f <= 0.0 {
        return false;
    }
    let c = emitted(ctx, n) * (f * decay(ctx.state.dist, ctx.int(n, 7)));
    let radius = ctx.scalar(n, 8);
    let c = shadows(ctx, n, c, Spread::Radius(radius));
    finish(out, c)
}

const DIRECTIONAL_PARAMS: &[&str] =
    &[COMMON[0], COMMON[1], COMMON[2], COMMON[3], COMMON[4], COMMON[5], COMMON[6], "lightAngle"];

maya_shader!(
    /// Directional light: `color · intensity` from one direction, no decay; `lightAngle`
    /// (radians) is the angular diameter its soft shadows are sampled over.
    DIRECTIONAL,
    ADSK_DIRECTIONAL,
    "maya_directionallight",
    "adskMayaDirectionalLight",
    DIRECTIONAL_PARAMS,
    directional
);

fn directional(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = emitted(ctx, n);
    let angle = ctx.scalar(n, 7);
    let c = shadows(ctx, n, c, Spread::Angle(0.5 * angle));
    finish(out, c)
}

const AMBIENT_PARAMS: &[&str] =
    &["color", "intensity", "useRayTraceShadows", "shadowColor", "shadowRays", "ambientShade", "lightRadius"];

maya_shader!(
    /// Ambient light: `color · intensity`, no decay. How much of it comes from the
    /// light's position rather than from all sides (`ambientShade`, 0.45 by default) is
    /// applied by the materials ([`light_role`]); shadows only darken that directional
    /// part.
    AMBIENT,
    ADSK_AMBIENT,
    "maya_ambientlight",
    "adskMayaAmbientLight",
    AMBIENT_PARAMS,
    ambient
);

fn ambient(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = emitted(ctx, n);
    let shade = ctx.scalar(n, 5).clamp(0.0, 1.0);
    let radius = ctx.scalar(n, 6);
    let lit = if shade > 0.0 && !is_directional(ctx) { shadows(ctx, n, c, Spread::Radius(radius)) } else { c };
    // Only the directional share is shadowed.
    let c = c * (1.0 - shade) + lit * shade;
    finish(out, Color::new(c.x, c.y, c.z, 1.0))
}

const AREA_PARAMS: &[&str] =
    &[COMMON[0], COMMON[1], COMMON[2], COMMON[3], COMMON[4], COMMON[5], COMMON[6], "decayRate"];

maya_shader!(
    /// Area light: at each point the scene's area light samples, `color · intensity /
    /// dist^decayRate` times the cosine at the emitter (the light faces its direction,
    /// which is its −z axis in Maya), raytraced shadows to that point.
    AREA,
    ADSK_AREA,
    "maya_arealight",
    "adskMayaAreaLight",
    AREA_PARAMS,
    area
);

fn area(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let cos_emit = light.direction.dot(ctx.state.dir);
    if cos_emit <= 0.0 {
        return false;
    }
    let c = emitted(ctx, n) * (cos_emit * decay(ctx.state.dist, ctx.int(n, 7)));
    let c = shadows(ctx, n, c, Spread::Radius(0.0));
    finish(out, c)
}

const VOLUME_PARAMS: &[&str] = &[
    COMMON[0],
    COMMON[1],
    COMMON[2],
    COMMON[3],
    COMMON[4],
    COMMON[5],
    COMMON[6],
    "lightShape",
    "colorRange",
    "arc",
    "coneEndRadius",
    "penumbra",
    "volumeLightDir",
    "emitAmbient",
];

const I_SHAPE: usize = 7;
const I_VOLUME_DIR: usize = 12;
const I_EMIT_AMBIENT: usize = 13;

/// A volume light's shape in its own space (the light's transform maps the unit shape
/// onto the volume). Maya's node reference: `lightShape` 0 box, 1 sphere (the default),
/// 2 cylinder, 3 cone; `arc` an angular slice about the light's y axis (degrees, 360 the
/// whole shape; not for the box); `coneEndRadius` the relative radius of one end of the
/// cone (1 a cylinder, 0 a cone); the light's central axis is its y axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeShape {
    /// `lightShape` (other values read as the sphere).
    pub shape: i32,
    /// `arc` in radians.
    pub arc: f32,
    /// `coneEndRadius`.
    pub cone_end_radius: f32,
}

/// Where a point lies in a volume light's shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumePoint {
    /// The normalised distance from the shape's centre (box, sphere) or axis (cylinder,
    /// cone): 0 there, 1 on the boundary; `colorRange` is read at 1 − this.
    pub distance: f32,
    /// For the cylinder and cone, the same distance from the axis, where the `penumbra`
    /// graph is read (at 1 − this: its left end the outer edge, its right end the axis).
    pub radial: Option<f32>,
}

impl VolumeShape {
    /// Where `local` (a point in the light's own space) lies, `None` outside. The box is
    /// [−1, 1]³, the sphere of radius 1, the cylinder of radius 1 about the y axis for y
    /// in [−1, 1], the cone the same with its radius going linearly from 1 at y = −1 to
    /// `coneEndRadius` at y = 1. The arc starts at the +x axis and turns towards −z
    /// (counter-clockwise seen from +y). mira's reading: Maya names the axis and the
    /// ends' relative size, not which end is which nor where the arc starts.
    pub fn locate(&self, local: Vec3A) -> Option<VolumePoint> {
        let radial = (local.x * local.x + local.z * local.z).sqrt();
        let point = match self.shape {
            0 => VolumePoint { distance: local.abs().max_element(), radial: None },
            2 | 3 => {
                if local.y.abs() > 1.0 {
                    return None;
                }
                let end = if self.shape == 3 { self.cone_end_radius.clamp(0.0, 1.0) } else { 1.0 };
                let r = 1.0 + (end - 1.0) * 0.5 * (local.y + 1.0);
                let d = if radial == 0.0 { 0.0 } else { radial / r };
                VolumePoint { distance: d, radial: Some(d) }
            }
            _ => VolumePoint { distance: local.length(), radial: None },
        };
        // Outside, or not a number (a hostile transform).
        if point.distance.is_nan() || point.distance > 1.0 {
            return None;
        }
        if self.shape != 0 && self.arc < std::f32::consts::TAU && radial > 0.0 {
            let azimuth = (-local.z).atan2(local.x).rem_euclid(std::f32::consts::TAU);
            if azimuth > self.arc.max(0.0) {
                return None;
            }
        }
        Some(point)
    }

    /// Where the light a point receives comes from, in the light's own space, for the
    /// point `local` (light-local): the centre for the box and the sphere, the nearest
    /// point (0, y, 0) of the central axis for the cylinder and the cone. Maya's node
    /// reference: with `volumeLightDir` outward the light "moves away from the center of
    /// a box or sphere and away from the central axis of a cylinder or cone".
    pub fn source(&self, local: Vec3A) -> Vec3A {
        match self.shape {
            2 | 3 => Vec3A::new(0.0, local.y, 0.0),
            _ => Vec3A::ZERO,
        }
    }

    /// [`VolumeShape::source`] in world space, for the world point `p` of a light
    /// centred at `origin` whose world → local map of offsets is `to_local`: `origin`
    /// itself for the box and the sphere. A map that cannot be inverted (a hostile
    /// transform) gives `origin`.
    pub fn world_source(&self, origin: Vec3A, to_local: glam::Mat3A, p: Vec3A) -> Vec3A {
        let local = self.source(to_local * (p - origin));
        if local == Vec3A::ZERO {
            return origin;
        }
        let det = to_local.determinant();
        if det == 0.0 || !det.is_finite() {
            return origin;
        }
        let q = origin + to_local.inverse() * local;
        if q.is_finite() {
            q
        } else {
            origin
        }
    }
}

maya_shader!(
    /// Volume light: `color · intensity` inside the light's volume (see
    /// [`VolumeShape::locate`]) times the `colorRange` ramp (array of
    /// {`colorRange_Position`, `colorRange_Color`, `colorRange_Interp`}; empty: white) at
    /// 1 − d (position 0 on the boundary, 1 at the centre or axis), for cylinders and
    /// cones also times the `penumbra` graph ({`penumbra_Position`,
    /// `penumbra_FloatValue`, `penumbra_Interp`}; empty: 1) at the same place; nothing
    /// outside; no decay (the ramp is the falloff). The light shines from the centre of a
    /// box or sphere and from the nearest point of the central axis of a cylinder or cone
    /// ([`VolumeShape::source`]; the shader moves the light state's `org`, `dir` and
    /// `dist` there), and its raytraced shadows go to that point. `volumeLightDir` (Maya's
    /// node reference) sets the direction the Maya materials shade with
    /// ([`LightRole::turn`]): 0 outward (the default), from that point; 1 inward, the
    /// reverse (Maya: "a simple change in direction used for
    /// the light computation"); 2 down the axis, as a directional light along the light's
    /// central (y) axis (mira's reading: travelling towards −y). `emitAmbient` makes the
    /// light light the materials as Maya's ambient light does: half from its direction,
    /// half from all sides with `emitDiffuse` on, wholly from all sides with it off
    /// (Maya's description), with a highlight still where `emitSpecular` is on.
    VOLUME,
    ADSK_VOLUME,
    "maya_volumelight",
    "adskMayaVolumeLight",
    VOLUME_PARAMS,
    volume
);

fn volume(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let (origin, to_local) = (light.origin, light.to_local);
    let local = to_local * (ctx.state.point - origin);
    let shape = VolumeShape {
        shape: ctx.int(n, I_SHAPE),
        arc: ctx.scalar(n, 9).to_radians(),
        cone_end_radius: ctx.scalar(n, 10),
    };
    let Some(at) = shape.locate(local) else { return false };
    let range = crate::utility::Ramp::read(&ctx.array(n, 8), "colorRange", "Color", Vec3A::ONE).at(1.0 - at.distance);
    let penumbra = match at.radial {
        Some(r) => crate::utility::Ramp::read(&ctx.array(n, 11), "penumbra", "FloatValue", Vec3A::ONE).at(1.0 - r).x,
        None => 1.0,
    };
    // A cylinder or cone shines from the nearest point of its axis: the light state (and
    // the shadow ray, and the light ray through media after the shader) starts there.
    let source = shape.world_source(origin, to_local, ctx.state.point);
    if source != origin {
        let d = ctx.state.point - source;
        let dist = d.length();
        if dist > 0.0 && dist.is_finite() {
            (ctx.state.org, ctx.state.dir, ctx.state.dist) = (source, d / dist, dist);
        }
    }
    let c = emitted(ctx, n) * (range * penumbra).extend(1.0);
    let c = shadows(ctx, n, c, Spread::Radius(0.0));
    finish(out, c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decay_rates_divide_by_powers_of_the_distance() {
        for (rate, want) in [(0, 1.0), (1, 0.25), (2, 0.0625), (3, 0.015625)] {
            assert!((decay(4.0, rate) - want).abs() < 1e-7, "rate {rate}");
        }
        // Out-of-range rates are clamped.
        assert_eq!(decay(2.0, 7), decay(2.0, 3));
        assert_eq!(decay(2.0, -1), 1.0);
    }

    #[test]
    fn spot_cone_penumbra_and_dropoff() {
        let cone = 40f32.to_radians();
        // Inside the half-angle: full; outside: none.
        assert_eq!(spot_factor(0.0, cone, 0.0, 0.0), 1.0);
        assert_eq!(spot_factor(21f32.to_radians(), cone, 0.0, 0.0), 0.0);
        // A 10° penumbra: halfway across it (25°) half the light.
        let pen = 10f32.to_radians();
        assert!((spot_factor(25f32.to_radians(), cone, pen, 0.0) - 0.5).abs() < 1e-5);
        // Negative penumbra fades inside the cone: at 15° (halfway from 10° to 20°).
        assert!((spot_factor(15f32.to_radians(), cone, -pen, 0.0) - 0.5).abs() < 1e-5);
        // Dropoff 2 at 10°: cos² 10°.
        let a = 10f32.to_radians();
        assert!((spot_factor(a, cone, 0.0, 2.0) - a.cos().powi(2)).abs() < 1e-6);
        // A NaN cone (a hostile file) gives no light rather than NaN.
        assert_eq!(spot_factor(a, f32::NAN, 0.0, 0.0), 0.0);
    }

    #[test]
    fn volume_shapes_and_distances() {
        let full = |shape| VolumeShape { shape, arc: std::f32::consts::TAU, cone_end_radius: 0.0 };
        let d = |shape: VolumeShape, p: Vec3A| shape.locate(p).map(|v| v.distance);
        // Sphere: the distance from the centre; outside beyond 1.
        assert_eq!(d(full(1), Vec3A::new(0.0, 0.5, 0.0)), Some(0.5));
        assert_eq!(d(full(1), Vec3A::new(0.8, 0.8, 0.0)), None);
        // Box: the largest coordinate.
        assert_eq!(d(full(0), Vec3A::new(0.8, -0.9, 0.2)), Some(0.9));
        assert_eq!(d(full(0), Vec3A::new(0.8, -1.1, 0.2)), None);
        // Cylinder about y: the distance from the axis, y within [−1, 1].
        let cyl = full(2).locate(Vec3A::new(0.6, 0.9, 0.0)).expect("inside");
        assert_eq!((cyl.distance, cyl.radial), (0.6, Some(0.6)));
        assert_eq!(d(full(2), Vec3A::new(0.1, 1.5, 0.0)), None);
        // Cone: radius 1 at y = −1 narrowing to coneEndRadius at y = 1; at y = 0 it is
        // (1 + end)/2: 0.5 for a sharp cone, 0.75 with an end radius of ½.
        assert!((d(full(3), Vec3A::new(0.25, 0.0, 0.0)).unwrap() - 0.5).abs() < 1e-6);
        assert_eq!(d(full(3), Vec3A::new(0.6, 0.0, 0.0)), None);
        let blunt = VolumeShape { cone_end_radius: 0.5, ..full(3) };
        assert!((d(blunt, Vec3A::new(0.6, 0.0, 0.0)).unwrap() - 0.8).abs() < 1e-6);
        assert_eq!(d(full(3), Vec3A::new(0.0, 1.0, 0.0)), Some(0.0));
        // A half arc keeps the slice from +x towards −z (azimuth up to 180°).
        let half = VolumeShape { arc: std::f32::consts::PI, ..full(1) };
        assert!(d(half, Vec3A::new(0.3, 0.0, -0.4)).is_some());
        assert!(d(half, Vec3A::new(0.3, 0.0, 0.4)).is_none());
        // The box ignores the arc.
        assert!(d(VolumeShape { arc: 0.1, ..full(0) }, Vec3A::new(0.3, 0.0, 0.4)).is_some());
        // NaN (a hostile transform) is outside.
        assert_eq!(d(full(1), Vec3A::splat(f32::NAN)), None);
    }

    #[test]
    fn cylinders_and_cones_shine_from_their_axis_boxes_and_spheres_from_their_centre() {
        let full = |shape| VolumeShape { shape, arc: std::f32::consts::TAU, cone_end_radius: 0.0 };
        // A light centred at (1, 1, 0) whose axis (local y) lies along world x, halved:
        // local = (½ y, ½ x, ½ z) of the offset from the centre.
        let origin = Vec3A::new(1.0, 1.0, 0.0);
        let to_local = glam::Mat3A::from_cols(Vec3A::new(0.0, 0.5, 0.0), Vec3A::new(0.5, 0.0, 0.0), Vec3A::Z * 0.5);
        let p = Vec3A::new(3.0, 0.0, 0.5);
        // The nearest point of the axis (the world line y = 1, z = 0) is (3, 1, 0).
        for shape in [2, 3] {
            let q = full(shape).world_source(origin, to_local, p);
            assert!((q - Vec3A::new(3.0, 1.0, 0.0)).length() < 1e-6, "shape {shape}: {q}");
        }
        for shape in [0, 1] {
            assert_eq!(full(shape).world_source(origin, to_local, p), origin);
        }
        // In the light's own space: (0, y, 0).
        assert_eq!(full(2).source(Vec3A::new(0.3, -0.7, 0.2)), Vec3A::new(0.0, -0.7, 0.0));
        // A map that cannot be inverted gives the centre.
        assert_eq!(full(2).world_source(origin, glam::Mat3A::ZERO, p), origin);
        // The role's direction: from the point towards the axis point, then turned.
        let axis = VolumeAxis { origin, to_local };
        let mut role = LightRole {
            diffuse: true,
            specular: true,
            ambient_shade: None,
            ambient_specular: false,
            turn: None,
            axis: Some(axis),
        };
        let towards_centre = (origin - p).normalize();
        let (dir, cos) = role.shading_direction(p, Vec3A::Y, towards_centre);
        assert!((dir - Vec3A::new(0.0, 1.0, -0.5).normalize()).length() < 1e-6, "{dir}");
        assert!((cos - 1.0 / 1.25f32.sqrt()).abs() < 1e-6);
        assert!(role.needs_both_sides());
        role.turn = Some(Turn::Inward);
        let (inward, _) = role.shading_direction(p, Vec3A::Y, towards_centre);
        assert!((inward + dir).length() < 1e-6);
    }
}
