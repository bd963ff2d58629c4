//! Maya's ambient light (`maya_ambientlight`, `adskMayaAmbientLight`) for the path engine.
//!
//! The classic Maya materials (`maya::material`) add, for each ambient light of colour C
//! and intensity I, `color` ⊙ C·I · ((1 − s) + s · max(cos θ, 0)) to what they reflect,
//! s = `ambientShade` (0.45 by default) and θ the angle between the shading normal and
//! the direction to the light's position: a part (1 − s) that arrives from all sides
//! alike and a part s that arrives from the light like a point light without decay.
//! Maya's node reference describes ambientShade this way (0: light from all directions,
//! 1: from the light's position only). Nothing in it passes through a BSDF: the
//! path engine adds it at each hit of a material that takes ambient light
//! ([`crate::SurfaceMaterial::ambient`]), the same formula. With `useRayTraceShadows` the
//! classic light shader first shadows its directional share: it returns C·I · ((1 − s) +
//! s · t), t = f + (1 − f) ⊙ `shadowColor` and f the fraction of shadow rays (towards
//! points over the sphere of `lightRadius` around the light) let through; the material's
//! factor ((1 − s) + s · cos θ) then applies to that. The path engine traces one such
//! shadow ray per hit ([`AmbientLight::shadow`]). A Maya volume light with `emitAmbient`
//! lights the materials the same way, and with `emitSpecular` it lights their highlight
//! too, as a light from its direction ([`AmbientLight::highlight_at`]; the path engine
//! adds it with the material's classic highlight formula, `crate::maya::MayaHighlight`).

use crate::{color_param, first_call, scalar_param};
use bsdf::Rgb;
use glam::Vec3A;

/// A Maya ambient light in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmbientLight {
    /// `color` · `intensity` (the classic shader's colour; no π: the materials use it
    /// as it is, see the module doc).
    pub color: Rgb,
    /// `ambientShade`, clamped to [0, 1].
    pub shade: f32,
    /// The light's position, world space.
    pub position: Vec3A,
    /// With `useRayTraceShadows` (and `ambientShade` > 0): how its directional share is
    /// shadowed; `None`: unshadowed.
    pub shadow: Option<AmbientShadow>,
    /// A Maya volume light with `emitAmbient` (Maya: it lights as the ambient light
    /// does): `color` is then the volume's colour at each point (its
    /// [`VolumeEmission::at`](super::maya::VolumeEmission::at) without the π), θ is taken
    /// from the direction its `volumeLightDir` turns to, and its shadows darken all of it
    /// (the classic volume light shadows its whole colour before the material splits it).
    pub volume: Option<super::maya::VolumeEmission>,
    /// A volume light with `emitSpecular` too: it also lights the material's highlight,
    /// as a light from its (turned) direction does ([`AmbientLight::highlight_at`]).
    pub highlight: bool,
}

/// The raytraced shadows of a Maya ambient light (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmbientShadow {
    /// `shadowColor`, clamped to [0, 1]: what a fully shadowed point still receives.
    pub color: Rgb,
    /// `lightRadius` (world units; 0: shadow rays to the light's position).
    pub radius: f32,
}

impl AmbientLight {
    /// The ambient light a surface at `p` with unit shading normal `n` (facing the
    /// viewer) receives: C·I · ((1 − s) + s · max(n · l, 0)), l towards the light.
    pub fn at(&self, p: Vec3A, n: Vec3A) -> Rgb {
        let (color, towards) = self.colour_and_direction(p);
        color * ((1.0 - self.shade) + self.shade * towards.dot(n).max(0.0))
    }

    /// The light's colour at `p` (a volume light's at that point, without the π) and the
    /// unit direction it arrives from (a volume light's as its `volumeLightDir` turns it).
    fn colour_and_direction(&self, p: Vec3A) -> (Rgb, Vec3A) {
        let towards = (self.source(p) - p).normalize_or_zero();
        match &self.volume {
            Some(v) => (
                v.at(p - self.position) / std::f32::consts::PI,
                match v.turn {
                    None => towards,
                    Some(::maya::light::Turn::Inward) => -towards,
                    Some(::maya::light::Turn::DownAxis(axis)) => axis,
                },
            ),
            None => (self.color, towards),
        }
    }

    /// The light of a volume light with `emitSpecular` ([`AmbientLight::highlight`]) on
    /// the highlight at `p`, with the fraction `through` of its shadow ray(s) let through:
    /// the unit direction it arrives from and its irradiance there, π · colour ⊙ (f + (1 −
    /// f) ⊙ `shadowColor`) — the units of a path-engine light, whose reflected radiance is
    /// f_glossy · irradiance · cos θ, as the classic materials add the highlight of the
    /// volume light's shadowed colour; `None` for any other light.
    pub fn highlight_at(&self, p: Vec3A, through: Rgb) -> Option<(Vec3A, Rgb)> {
        if !self.highlight || self.volume.is_none() {
            return None;
        }
        let (color, towards) = self.colour_and_direction(p);
        let filter = match self.shadow {
            Some(shadow) => through + (Rgb::ONE - through) * shadow.color,
            None => Rgb::ONE,
        };
        let irradiance = color * filter * std::f32::consts::PI;
        (towards != Vec3A::ZERO && irradiance.max_element() > 0.0).then_some((towards, irradiance))
    }

    /// Where the light arriving at `p` (world) comes from, and where its shadow rays go:
    /// the light's position, or for a cylinder or cone volume light the nearest point of
    /// its axis ([`VolumeEmission::source`](super::maya::VolumeEmission::source)).
    pub fn source(&self, p: Vec3A) -> Vec3A {
        match &self.volume {
            Some(v) => v.source(self.position, p),
            None => self.position,
        }
    }

    /// [`AmbientLight::at`] with the fraction `through` of the shadow ray(s) let through:
    /// × ((1 − s) + s · (f + (1 − f) ⊙ `shadowColor`)) when the light casts shadows.
    pub fn shadowed_at(&self, p: Vec3A, n: Vec3A, through: Rgb) -> Rgb {
        let unshadowed = self.at(p, n);
        match self.shadow {
            Some(shadow) => {
                let filter = through + (Rgb::ONE - through) * shadow.color;
                if self.volume.is_some() {
                    unshadowed * filter
                } else {
                    unshadowed * (Rgb::splat(1.0 - self.shade) + self.shade * filter)
                }
            }
            None => unshadowed,
        }
    }
}

/// The ambient light of scene light `light`: a Maya ambient light, or a Maya volume light
/// with `emitAmbient` (`ambientShade` ½ with `emitDiffuse` on, else 0, as the classic
/// materials read it; with `emitSpecular` it lights the highlight too,
/// [`AmbientLight::highlight_at`]); `None` for any other light.
pub fn maya_ambient(light: &scene::Light, lib: &scene::Library) -> Option<AmbientLight> {
    let list = light.shader.as_ref()?;
    let (decl, params) = first_call(&list.0, lib)?;
    let name = crate::declaration_name(decl);
    let scalar = |n: &str, default: f64| scalar_param(params, n).unwrap_or(default) as f32;
    if matches!(name, "maya_volumelight" | "adskMayaVolumeLight") && scalar("emitAmbient", 0.0) != 0.0 {
        let color = match color_param(params, "color") {
            Some(Ok(c)) => c,
            _ => Rgb::ONE,
        } * (std::f32::consts::PI * scalar("intensity", 1.0));
        let volume = super::maya::volume_light(params, light.light_to_world, color).ok()?;
        let shadow = (scalar("useRayTraceShadows", 0.0) != 0.0)
            .then(|| AmbientShadow { color: shadow_color(params), radius: 0.0 });
        let shade = if scalar("emitDiffuse", 1.0) != 0.0 { 0.5 } else { 0.0 };
        return Some(AmbientLight {
            color: volume.color / std::f32::consts::PI,
            shade,
            position: light.position.as_vec3a(),
            shadow,
            volume: Some(volume),
            highlight: scalar("emitSpecular", 1.0) != 0.0,
        });
    }
    if name != "maya_ambientlight" && name != "adskMayaAmbientLight" {
        return None;
    }
    let color = match color_param(params, "color") {
        Some(Ok(c)) => c,
        _ => Rgb::ONE,
    } * scalar("intensity", 1.0);
    let shade = scalar("ambientShade", 0.45).clamp(0.0, 1.0);
    let shadows = scalar("useRayTraceShadows", 0.0) != 0.0 && shade > 0.0;
    let shadow =
        shadows.then(|| AmbientShadow { color: shadow_color(params), radius: scalar("lightRadius", 0.0).max(0.0) });
    Some(AmbientLight { color, shade, position: light.position.as_vec3a(), shadow, volume: None, highlight: false })
}

/// A Maya light's `shadowColor`, clamped to [0, 1] (black when absent).
fn shadow_color(params: &[mi::ast::Param]) -> Rgb {
    match color_param(params, "shadowColor") {
        Some(Ok(c)) => c.clamp(Rgb::ZERO, Rgb::ONE),
        _ => Rgb::ZERO,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_uniform_part_everywhere_and_the_directional_part_by_the_cosine() {
        let light = AmbientLight {
            color: Rgb::new(1.0, 0.5, 0.25),
            shade: 0.4,
            position: Vec3A::new(0.0, 2.0, 0.0),
            shadow: None,
            volume: None,
            highlight: false,
        };
        let p = Vec3A::ZERO;
        // Facing the light: all of it; facing away: the uniform part (1 − s).
        assert!((light.at(p, Vec3A::Y) - light.color).abs().max_element() < 1e-6);
        assert!((light.at(p, -Vec3A::Y) - light.color * 0.6).abs().max_element() < 1e-6);
        // 60° off: (1 − s) + s/2.
        let n = Vec3A::new(3f32.sqrt() / 2.0, 0.5, 0.0);
        assert!((light.at(p, n) - light.color * 0.8).abs().max_element() < 1e-6);
    }
}
