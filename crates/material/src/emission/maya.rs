//! Maya lights for the path engine: what a Maya light shader emits, as the radiometric
//! quantity the path engine's base-light outputs carry (the irradiance a surface facing
//! the light receives; the path engine's Lambertian lobe is albedo/π).
//!
//! - π · `color` · `intensity` arrives undiminished with `decayRate` 0 (point, spot,
//!   directional, area), else falls off as d^−decayRate (a photometric falloff of that
//!   exponent); an area light's samples are weighted by the cosine between the light's
//!   axis (local −Z) and the direction to the lit point, as the classic shader's are. The factor π makes a lambert of albedo c·d give c·d·I·cos θ in the path
//!   engine too, as mental ray for Maya's classic shaders do (no 1/π in their light units);
//! - a spot's cone: the classic light's own factor ([`::maya::light::SpotCone`]: full
//!   light inside the inner half-angle, fading linearly in the angle across
//!   `penumbraAngle`, times cos^`dropoff` of the angle from the axis), with or without a
//!   decay, whatever the scene light's `spread` (which the classic light does not read);
//! - a volume light of sphere shape (`lightShape` 1) whose transform scales the unit
//!   sphere uniformly to radius R: a point light at its centre with a linear falloff from
//!   the centre to R when `colorRange` runs linearly from black on the boundary (position
//!   0) to a colour c at the centre (position 1) — the classic light's c·(1 − r/R) exactly
//!   —, or constant inside R when `colorRange` is one colour or empty (white);
//! - every other volume light (box, cylinder, cone, arcs, uneven scales, other ramps of
//!   up to [`MAX_RAMP_KEYS`] keys): a point light at the light's origin — for cylinders
//!   and cones at the nearest point of the central axis, as Maya's outward light — giving
//!   a point the classic light's colour there ([`VolumeEmission`]: the shape, the
//!   `colorRange` ramp and the cylinder's and cone's `penumbra` graph, read as the classic
//!   light reads them); `volumeLightDir` inward or down the axis turns the direction the
//!   light arrives from for shading, its shadow rays still going to that point (as the
//!   classic Maya materials shade it); with `emitAmbient` it is not sampled but lights as
//!   Maya's ambient light does ([`super::ambient`]);
//! - `emitDiffuse` / `emitSpecular` off: the light lights only the other part of the
//!   materials' lobes ([`light_lobes`]); ambient lights are not lights the path engine samples:
//!   see [`super::ambient`] (a message here when asked for as a light).

use super::{Emission, Power};
use crate::{color_param, first_call, scalar_param};
use bsdf::Rgb;
use glam::DMat4;
use mi::ast::{Param, Value};

/// The Maya light family a light shader declaration belongs to.
fn family(decl: &str) -> Option<&'static str> {
    let name = decl.strip_prefix("maya_").or_else(|| decl.strip_prefix("adskMaya"))?.to_ascii_lowercase();
    ["pointlight", "spotlight", "directionallight", "ambientlight", "arealight", "volumelight"]
        .into_iter()
        .find(|f| *f == name)
}

/// The emission of a Maya light shader call on a light placed by `light_to_world`, or a
/// message saying why the path engine leaves it out; `None` if the declaration is not a
/// Maya light.
pub fn emission_of(decl: &str, params: &[Param], light_to_world: DMat4) -> Option<Result<Emission, String>> {
    let family = family(decl)?;
    let scalar = |name: &str, default: f64| scalar_param(params, name).unwrap_or(default) as f32;
    let color = match color_param(params, "color") {
        Some(Ok(c)) => c,
        _ => Rgb::ONE,
    } * (std::f32::consts::PI * scalar("intensity", 1.0));
    if family == "ambientlight" {
        return Some(Err(format!("{decl} has no path-engine counterpart; the light is left out")));
    }
    if family == "volumelight" {
        return Some(volume_emission(decl, params, light_to_world, color));
    }
    let rate = if family == "directionallight" { 0 } else { (scalar("decayRate", 0.0) as i32).clamp(0, 3) };
    // An area light shines from its rectangle's front, weighted by the cosine to the
    // light's axis (its local −Z) as the classic shader weights each sample.
    let area = family == "arealight";
    let power = match rate {
        0 if !area => Power::Constant { color, falloff: None },
        r => Power::Photometric { color, exponent: r as f32, range: None },
    };
    let distribution = area.then_some(super::Distribution::Cosine(1.0));
    let cone = (family == "spotlight").then(|| {
        let half = 0.5 * scalar("coneAngle", 0.698_131_7);
        let inner = half + scalar("penumbraAngle", 0.0).min(0.0);
        inner.clamp(0.0, std::f32::consts::FRAC_PI_2).cos()
    });
    // Maya's `dropoff`: the spot's cosine power inside the cone.
    let dropoff = scalar("dropoff", 0.0);
    let spot_exponent = (family == "spotlight" && dropoff > 0.0).then_some(dropoff);
    let maya_spot = (family == "spotlight").then(|| ::maya::light::SpotCone {
        cone: scalar("coneAngle", 0.698_131_7),
        penumbra: scalar("penumbraAngle", 0.0),
        dropoff,
    });
    Some(Ok(Emission { power, spot_exponent, cone, distribution, maya_spot }))
}

/// The emission of a scene light whose shader is a Maya light (see [`emission_of`]).
pub fn light_emission(light: &scene::Light, lib: &scene::Library) -> Option<Result<Emission, String>> {
    let list = light.shader.as_ref()?;
    let (decl, params) = first_call(&list.0, lib)?;
    emission_of(decl, params, light.light_to_world)
}

/// The keys (position, value, Maya interpolation) of the ramp array parameter `name`
/// whose members are `<name>_Position`, `<name>_<member>` and `<name>_Interp`, sorted by
/// position; a member a key leaves out reads 0 (the declaration's zero: position 0, value
/// black, interpolation 0 = none), as the classic light reads the compiled struct; a value
/// may be a colour or a scalar.
fn ramp_keys(params: &[Param], name: &str, member: &str) -> Vec<(f32, Rgb, i32)> {
    let Some(Value::Array(items)) = params.iter().rev().find(|p| p.name.text == name).map(|p| &p.value) else {
        return Vec::new();
    };
    let value = format!("{name}_{member}");
    let mut keys: Vec<(f32, Rgb, i32)> = items
        .iter()
        .filter_map(|item| {
            let Value::Struct(members) = item else { return None };
            let position = scalar_param(members, &format!("{name}_Position")).unwrap_or(0.0) as f32;
            let v = match color_param(members, &value) {
                Some(Ok(c)) => c,
                _ => Rgb::splat(scalar_param(members, &value).unwrap_or(0.0) as f32),
            };
            let interp = scalar_param(members, &format!("{name}_Interp")).unwrap_or(0.0) as i32;
            Some((position, v, interp))
        })
        .collect();
    keys.sort_by(|a, b| a.0.total_cmp(&b.0));
    keys
}

/// The most keys a volume light's ramp may have in the path engine.
pub const MAX_RAMP_KEYS: usize = 8;

/// A volume light's `colorRange` ramp or `penumbra` graph, as the classic light reads it
/// (`maya::utility::curve_at`: Maya's none, linear, smooth and spline interpolations; white when
/// empty), held in place so the light stays `Copy`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeRamp {
    keys: [(f32, Rgb, i32); MAX_RAMP_KEYS],
    len: usize,
}

impl VolumeRamp {
    /// The ramp of sorted `keys` (position, value, interpolation), `None` past
    /// [`MAX_RAMP_KEYS`].
    pub fn new(keys: &[(f32, Rgb, i32)]) -> Option<VolumeRamp> {
        let mut ramp = VolumeRamp { keys: [(0.0, Rgb::ZERO, 1); MAX_RAMP_KEYS], len: keys.len() };
        ramp.keys.get_mut(..keys.len())?.copy_from_slice(keys);
        Some(ramp)
    }

    /// The ramp at position `t` (0 the volume's boundary, 1 its centre or axis).
    pub fn at(&self, t: f32) -> Rgb {
        if self.len == 0 {
            Rgb::ONE
        } else {
            ::maya::utility::curve_at(&self.keys[..self.len], t)
        }
    }
}

/// A Maya volume light in the path engine: a point light at the light's origin (a
/// cylinder's or cone's: the nearest point of its axis, [`VolumeEmission::source`]) giving a
/// lit point `color` × `range` at 1 − d, for cylinders and cones also × `penumbra` at
/// 1 − d, where d is the point's normalised distance in the light's shape
/// ([`::maya::light::VolumeShape::locate`]), nothing outside; no decay. The classic
/// light's formula exactly (its `emitted` colour times π, see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeEmission {
    /// π · `color` · `intensity`.
    pub color: Rgb,
    /// The shape, arc and cone end.
    pub shape: ::maya::light::VolumeShape,
    /// World → light-local map of offsets from the light's origin (the inverse of the
    /// linear part of the light's transform, which maps the unit shape onto the volume).
    pub to_local: glam::Mat3A,
    /// `colorRange`.
    pub range: VolumeRamp,
    /// `penumbra` (cylinders and cones).
    pub penumbra: VolumeRamp,
    /// `volumeLightDir` 1 (inward) or 2 (down the axis, the light's +y axis in world
    /// space): the direction the light arrives from for shading (the shadow ray still
    /// goes to the light's origin); `None`: from the origin (0, outward).
    pub turn: Option<::maya::light::Turn>,
}

impl VolumeEmission {
    /// Where the light arriving at world point `p` comes from, for a light centred at
    /// `origin` (world): `origin` for the box and the sphere, the nearest point of the
    /// central axis for the cylinder and the cone ([`::maya::light::VolumeShape::source`]).
    pub fn source(&self, origin: glam::Vec3A, p: glam::Vec3A) -> glam::Vec3A {
        self.shape.world_source(origin, self.to_local, p)
    }

    /// The colour arriving at the point `offset` (world space) from the light's origin.
    pub fn at(&self, offset: glam::Vec3A) -> Rgb {
        let Some(at) = self.shape.locate(self.to_local * offset) else { return Rgb::ZERO };
        let c = self.color * self.range.at(1.0 - at.distance);
        match at.radial {
            Some(r) => c * self.penumbra.at(1.0 - r).x,
            None => c,
        }
    }
}

/// A volume light (see the module doc): `color` is π · colour · intensity. The evenly
/// scaled whole sphere with a constant or black-to-colour ramp becomes a base light with
/// a linear falloff; every other shape a [`Power::Volume`].
fn volume_emission(decl: &str, params: &[Param], light_to_world: DMat4, color: Rgb) -> Result<Emission, String> {
    let range = ramp_keys(params, "colorRange", "Color");
    if scalar_param(params, "volumeLightDir").unwrap_or(0.0) as i32 == 0 {
        if let Some(e) = sphere_point_light(params, light_to_world, color, &range) {
            return Ok(e);
        }
    }
    let volume = volume_light(params, light_to_world, color).map_err(|e| format!("{decl}: {e}"))?;
    Ok(Emission {
        power: Power::Volume(Box::new(volume)),
        spot_exponent: None,
        cone: None,
        distribution: None,
        maya_spot: None,
    })
}

/// The [`VolumeEmission`] of a volume light call's `params` on a light placed by
/// `light_to_world` (any shape, the sphere too), `color` π · colour · intensity, or why
/// the path engine cannot represent it.
pub fn volume_light(params: &[Param], light_to_world: DMat4, color: Rgb) -> Result<VolumeEmission, String> {
    let to_local = shader::light::profiles::to_local(light_to_world);
    // As the classic light reads it (`maya::light`): 1 inward, 2 down the axis, any other
    // value outward.
    let turn = match scalar_param(params, "volumeLightDir").unwrap_or(0.0) as i32 {
        1 => Some(::maya::light::Turn::Inward),
        2 => Some(::maya::light::Turn::DownAxis((to_local.inverse() * glam::Vec3A::Y).normalize_or(glam::Vec3A::Y))),
        _ => None,
    };
    let range = ramp_keys(params, "colorRange", "Color");
    let too_many = |what: &str, n: usize| {
        format!("a {what} of {n} keys (more than {MAX_RAMP_KEYS}) has no path-engine counterpart; left out")
    };
    let penumbra = ramp_keys(params, "penumbra", "FloatValue");
    Ok(VolumeEmission {
        color,
        shape: ::maya::light::VolumeShape {
            shape: scalar_param(params, "lightShape").unwrap_or(1.0) as i32,
            arc: (scalar_param(params, "arc").unwrap_or(360.0) as f32).to_radians(),
            cone_end_radius: scalar_param(params, "coneEndRadius").unwrap_or(0.0) as f32,
        },
        to_local,
        range: VolumeRamp::new(&range).ok_or_else(|| too_many("colorRange", range.len()))?,
        penumbra: VolumeRamp::new(&penumbra).ok_or_else(|| too_many("penumbra graph", penumbra.len()))?,
        turn,
    })
}

/// The evenly scaled whole sphere whose `colorRange` (sorted keys `range`) is empty, one
/// colour, or linear from black on the boundary to a colour at the centre: a base light at
/// its centre with a linear falloff to the radius (the classic light's c·(1 − r/R)
/// exactly); `None` for any other volume light.
fn sphere_point_light(
    params: &[Param],
    light_to_world: DMat4,
    color: Rgb,
    range: &[(f32, Rgb, i32)],
) -> Option<Emission> {
    let whole = scalar_param(params, "lightShape").unwrap_or(1.0) as i32 == 1
        && scalar_param(params, "arc").unwrap_or(360.0) >= 360.0;
    let scales = [0, 1, 2].map(|i| light_to_world.col(i).truncate().length());
    let radius = scales[0];
    if !whole || radius.is_nan() || radius <= 0.0 || scales.iter().any(|s| (s - radius).abs() > 1e-3 * radius) {
        return None;
    }
    let radius = radius as f32;
    let (tint, start) = match range {
        [] => (Rgb::ONE, radius),
        [(_, c, _)] => (*c, radius),
        [boundary, centre] => {
            let linear = boundary.0 == 0.0 && centre.0 == 1.0 && boundary.2 == 1 && boundary.1 == Rgb::ZERO;
            if !linear {
                return None;
            }
            (centre.1, 0.0)
        }
        _ => return None,
    };
    // A constant light stops at the boundary: a falloff over the last 10⁻⁴ of the radius.
    let start = start.min(radius * (1.0 - 1e-4));
    Some(Emission {
        power: Power::Constant { color: color * tint, falloff: Some((start, radius)) },
        spot_exponent: None,
        cone: None,
        distribution: None,
        maya_spot: None,
    })
}

/// How a Maya light's raytraced shadows work in the path engine, from its shader's
/// parameters: whether it casts shadows at all (`useRayTraceShadows`; off, the classic
/// light shines through everything) and `shadowColor`, the fraction of the light a fully
/// shadowed point still receives (received = light ⊙ (f + (1 − f) ⊙ shadowColor), f the
/// fraction let through, as the classic light); `None` when `light`'s shader is not a
/// Maya light.
pub fn shadowing(light: &scene::Light, lib: &scene::Library) -> Option<(bool, Rgb)> {
    let list = light.shader.as_ref()?;
    let (decl, params) = first_call(&list.0, lib)?;
    family(crate::declaration_name(decl))?;
    let casts = scalar_param(params, "useRayTraceShadows").unwrap_or(0.0) != 0.0;
    let color = match color_param(params, "shadowColor") {
        Some(Ok(c)) => c.clamp(Rgb::ZERO, Rgb::ONE),
        _ => Rgb::ZERO,
    };
    Some((casts, color))
}

/// How a Maya light's raytraced shadows soften (the classic light's shadow rays, see
/// `maya::light`): the light itself still shines from its point or direction; only the
/// shadow rays spread.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SoftShadow {
    /// Point and spot lights' `lightRadius` (world units): shadow rays end at points
    /// uniform over the surface of the sphere of this radius around the light.
    Radius(f32),
    /// Directional lights' `lightAngle` halved (radians): shadow rays leave in
    /// directions uniform in solid angle over the cone of this half-angle around the
    /// direction towards the light.
    Angle(f32),
}

/// The soft shadows of a Maya point, spot or directional light whose `lightRadius` or
/// `lightAngle` is positive; `None` for hard shadows or any other light.
pub fn soft_shadow(light: &scene::Light, lib: &scene::Library) -> Option<SoftShadow> {
    let list = light.shader.as_ref()?;
    let (decl, params) = first_call(&list.0, lib)?;
    let size = |name: &str| scalar_param(params, name).map(|v| v as f32).filter(|v| v.is_finite() && *v > 0.0);
    match family(crate::declaration_name(decl))? {
        "pointlight" | "spotlight" => size("lightRadius").map(SoftShadow::Radius),
        // A cone wider than a hemisphere has no meaning; clamp the half-angle to π/2.
        "directionallight" => size("lightAngle").map(|a| SoftShadow::Angle((0.5 * a).min(std::f32::consts::FRAC_PI_2))),
        _ => None,
    }
}

/// Which parts of the materials' lobes a light lights: Maya's `emitDiffuse` and
/// `emitSpecular` (both on for every other light).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightLobes {
    /// It lights the diffuse lobes.
    pub diffuse: bool,
    /// It lights the highlights and other glossy lobes.
    pub specular: bool,
}

impl Default for LightLobes {
    fn default() -> LightLobes {
        LightLobes { diffuse: true, specular: true }
    }
}

/// The lobes a Maya light lights (`emitDiffuse`, `emitSpecular`); `None` when its shader
/// is not a Maya light.
pub fn light_lobes(light: &scene::Light, lib: &scene::Library) -> Option<LightLobes> {
    let list = light.shader.as_ref()?;
    let (decl, params) = first_call(&list.0, lib)?;
    family(crate::declaration_name(decl))?;
    let on = |name: &str| scalar_param(params, name).unwrap_or(1.0) != 0.0;
    Some(LightLobes { diffuse: on("emitDiffuse"), specular: on("emitSpecular") })
}

#[cfg(test)]
mod tests {
    use std::f32::consts::PI;

    use super::*;

    fn params(text: &str) -> Vec<Param> {
        let parsed = mi::parse_str("t.mi", &format!("shader \"s\" \"x\" ({text})"));
        for item in parsed.items {
            if let mi::ast::Item::Shader(def) = item {
                if let Some(mi::ast::ShaderItem::Call { params, .. }) = def.list.0.into_iter().next() {
                    return params;
                }
            }
        }
        panic!("no call");
    }

    #[test]
    fn maya_lights_become_constant_or_photometric_emission() {
        let e = emission_of("maya_pointlight", &params(r#""color" 1 0.5 0.25, "intensity" 2"#), DMat4::IDENTITY)
            .unwrap()
            .unwrap();
        assert_eq!(e.power, Power::Constant { color: Rgb::new(2.0, 1.0, 0.5) * PI, falloff: None });
        let e = emission_of("adskMayaPointLight", &params(r#""decayRate" 2, "intensity" 3"#), DMat4::IDENTITY)
            .unwrap()
            .unwrap();
        assert_eq!(e.power, Power::Photometric { color: Rgb::splat(3.0 * PI), exponent: 2.0, range: None });
        let e = emission_of("maya_spotlight", &params(r#""coneAngle" 1, "penumbraAngle" -0.2"#), DMat4::IDENTITY)
            .unwrap()
            .unwrap();
        assert!((e.cone.unwrap() - 0.3f32.cos()).abs() < 1e-6);
        // Directional lights do not decay.
        let e = emission_of("maya_directionallight", &params(r#""decayRate" 2"#), DMat4::IDENTITY).unwrap().unwrap();
        assert!(matches!(e.power, Power::Constant { .. }));
        assert!(emission_of("maya_ambientlight", &params(""), DMat4::IDENTITY).unwrap().is_err());
        assert!(emission_of("maya_pointlight", &params(r#""emitDiffuse" off"#), DMat4::IDENTITY).unwrap().is_ok());
        assert!(emission_of("mib_light_point", &params(""), DMat4::IDENTITY).is_none());
    }

    /// A sphere volume light of radius 3 with colorRange black on the boundary to white at
    /// the centre: a point light of π·colour·intensity falling off linearly from the
    /// centre (1 − r/R, the classic light's ramp at 1 − r/R); one colour: constant to R.
    #[test]
    fn sphere_volume_lights_become_point_lights_with_their_falloff() {
        let scale = DMat4::from_scale(glam::DVec3::splat(3.0));
        let linear = r#""intensity" 2, "lightShape" 1, "colorRange" [
            { "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 },
            { "colorRange_Position" 1, "colorRange_Color" 1 0.5 0.25, "colorRange_Interp" 1 } ]"#;
        let e = emission_of("maya_volumelight", &params(linear), scale).unwrap().unwrap();
        assert_eq!(e.power, Power::Constant { color: Rgb::new(2.0, 1.0, 0.5) * PI, falloff: Some((0.0, 3.0)) });
        let constant =
            r#""lightShape" 1, "colorRange" [ { "colorRange_Position" 0.5, "colorRange_Color" 0.5 0.5 0.5 } ]"#;
        let e = emission_of("adskMayaVolumeLight", &params(constant), scale).unwrap().unwrap();
        let Power::Constant { color, falloff: Some((start, stop)) } = e.power else { panic!("{:?}", e.power) };
        assert!((color - Rgb::splat(0.5 * PI)).abs().max_element() < 1e-6);
        assert!(stop == 3.0 && (3.0 - start) < 1e-3 && start < 3.0);
        // Boxes and uneven scales become volume emission; other directions are left out.
        let e = emission_of("maya_volumelight", &params(r#""lightShape" 0"#), scale).unwrap().unwrap();
        assert!(matches!(e.power, Power::Volume(ref v) if v.shape.shape == 0));
        let uneven = DMat4::from_scale(glam::DVec3::new(1.0, 2.0, 1.0));
        let e = emission_of("maya_volumelight", &params(""), uneven).unwrap().unwrap();
        assert!(matches!(e.power, Power::Volume(ref v) if v.shape.shape == 1));
        // Inward and down the axis (the light's +y, here turned to world +z): a volume
        // emission that turns the direction, even for the sphere.
        let e = emission_of("maya_volumelight", &params(r#""volumeLightDir" 1"#), scale).unwrap().unwrap();
        assert!(matches!(e.power, Power::Volume(ref v) if v.turn == Some(::maya::light::Turn::Inward)));
        let turned = DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2) * scale;
        let e = emission_of("maya_volumelight", &params(r#""volumeLightDir" 2"#), turned).unwrap().unwrap();
        let Power::Volume(v) = e.power else { panic!("{:?}", e.power) };
        let Some(::maya::light::Turn::DownAxis(axis)) = v.turn else { panic!("{:?}", v.turn) };
        assert!((axis - glam::Vec3A::Z).length() < 1e-6, "{axis}");
    }

    /// Box, cylinder and cone volume lights of scale 2 give a point the classic light's
    /// colour: the ramp (black on the boundary to white at the centre) at 1 − d, the
    /// penumbra graph at 1 − (distance from the axis), nothing outside.
    #[test]
    fn box_cylinder_and_cone_volume_lights_follow_their_shape_and_ramps() {
        let scale = DMat4::from_scale(glam::DVec3::splat(2.0));
        let ramp = r#""colorRange" [
            { "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 },
            { "colorRange_Position" 1, "colorRange_Color" 1 1 1, "colorRange_Interp" 1 } ]"#;
        let volume = |text: String| match emission_of("maya_volumelight", &params(&text), scale).unwrap().unwrap().power
        {
            Power::Volume(v) => *v,
            other => panic!("{other:?}"),
        };
        let at = |v: &VolumeEmission, x: f32, y: f32, z: f32| v.at(glam::Vec3A::new(x, y, z)).x / PI;
        // Box: d is the largest coordinate over the half-size 2.
        let b = volume(format!(r#""lightShape" 0, {ramp}"#));
        assert!((at(&b, 1.0, 0.5, -0.2) - 0.5).abs() < 1e-6);
        assert!((at(&b, 0.2, -1.5, 1.0) - 0.25).abs() < 1e-6);
        assert_eq!(at(&b, 2.1, 0.0, 0.0), 0.0);
        // Cylinder: d is the distance from the y axis over 2; a penumbra graph from 0.5 at
        // the edge to 1 on the axis multiplies it.
        let penumbra = r#""penumbra" [ { "penumbra_Position" 0, "penumbra_FloatValue" 0.5, "penumbra_Interp" 1 },
            { "penumbra_Position" 1, "penumbra_FloatValue" 1 } ]"#;
        let c = volume(format!(r#""lightShape" 2, {ramp}, {penumbra}"#));
        assert!((at(&c, 0.0, 1.9, 1.0) - 0.5 * 0.75).abs() < 1e-6);
        assert_eq!(at(&c, 0.0, 2.1, 0.0), 0.0);
        // Cone with coneEndRadius 0: the radius halves at y = 0.
        let k = volume(format!(r#""lightShape" 3, "coneEndRadius" 0, {ramp}"#));
        assert!((at(&k, 0.5, 0.0, 0.0) - 0.5).abs() < 1e-6);
        assert_eq!(at(&k, 0.0, 1.0, 1.1), 0.0);
        // An arc of 90° keeps the quarter from +x towards −z.
        let a = volume(format!(r#""lightShape" 2, "arc" 90, {ramp}"#));
        assert!(at(&a, 0.5, 0.0, -0.5) > 0.0);
        assert_eq!(at(&a, 0.5, 0.0, 0.5), 0.0);
    }
}
