//! Light shaders whose result at a light sample is a constant colour, optionally ramped
//! linearly over distance, for a spot limited to its cone, passed through hard or partial
//! shadows: `mib_light_point`, `mib_light_spot` and `mib_light_infinite` with constant
//! parameters. The light loop evaluates such a light
//! ([`SimpleLight`]) in place, without a light state or a shader call per sample; the
//! shaders themselves use the same functions ([`attenuation`], [`shadowed`]), so both give
//! the same colour bit for bit.

use crate::graph::Slot;
use crate::value::{Color, Value};

/// A light shader's constant parameters, as [`crate::ShaderImpl::simple_light`] reads them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimpleLight {
    /// The colour (`color`).
    pub color: Color,
    /// The linear ramp's `(start, stop)` distances (scene units) when `atten` is on.
    pub atten: Option<(f32, f32)>,
    /// `shadow`: whether the light asks for shadow rays.
    pub shadow: bool,
    /// `factor`: the share of an occluded light let through (0 hard shadows, 1 none).
    pub factor: f32,
    /// For `mib_light_spot`: its inner `cone` (a cosine); the light's own `spread` (a
    /// cosine) bounds the lit cone ([`spot_factor`]). `None`: not a spot shader.
    pub cone: Option<f32>,
}

impl SimpleLight {
    /// Whether the shader traces a shadow ray (`shadow` on and `factor` < 1).
    pub fn casts_shadows(&self) -> bool {
        self.shadow && self.factor < 1.0
    }

    /// The colour arriving from distance `dist` before shadows; `None`: no light (past
    /// the ramp's `stop`, or outside a spot's cone). For a spot, `axis_cos` is the cosine
    /// between the light's axis and the direction from the light to the point and `spread`
    /// the light's spread cosine (both unread for other lights).
    pub fn unshadowed(&self, dist: f32, axis_cos: f32, spread: f32) -> Option<Color> {
        let mut c = self.color;
        if let Some(cone) = self.cone {
            c *= spot_factor(axis_cos, spread, cone)?;
        }
        if let Some((start, stop)) = self.atten {
            c *= attenuation(dist, start, stop)?;
        }
        Some(c)
    }
}

/// Parameter `i` of a node with parameter slots `slots` when it is a constant (a missing
/// slot reads as [`Value::Null`], as [`crate::Ctx`] reads it: zero, false); `None` when it
/// is connected to a shader or built of parts.
pub fn constant(slots: &[Slot], i: usize) -> Option<Value> {
    match slots.get(i) {
        Some(Slot::Value(v)) => Some(v.clone()),
        None => Some(Value::Null),
        Some(_) => None,
    }
}

/// Linear distance attenuation of the base lights: 1 before `start`, 0 from `stop` on
/// (`None`: no light, as for any distance when `stop` is 0).
pub fn attenuation(dist: f32, start: f32, stop: f32) -> Option<f32> {
    if dist >= stop {
        None
    } else if dist > start && (stop - start).abs() > 1e-4 {
        Some(1.0 - (dist - start) / (stop - start))
    } else {
        Some(1.0)
    }
}

/// The spot factor of `mib_light_spot` for cosine `c` between the spot axis and the
/// direction from the light to the point: `None` (no light) outside the `spread` cone (a
/// cosine) or behind the light, 1 inside the inner `cone` (a cosine), falling off linearly
/// in the cosine between them.
pub fn spot_factor(c: f32, spread: f32, cone: f32) -> Option<f32> {
    if c <= 0.0 || c < spread {
        return None;
    }
    if c < cone && cone > spread {
        Some(1.0 - (c - cone) / (spread - cone))
    } else {
        Some(1.0)
    }
}

/// `color` after a shadow ray that got `through` (with the occluders' shadow shaders'
/// `filter`) for a light with shadow `factor`: what an occluder blocks is let through in
/// proportion `factor`. `None`: nothing arrives (blocked, `factor` ≤ 0).
pub fn shadowed(color: Color, factor: f32, through: bool, filter: Color) -> Option<Color> {
    if !through {
        return (factor > 0.0).then(|| color * factor);
    }
    let f = Color::splat(factor);
    Some(color * (f + (Color::ONE - f) * filter))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ramp is exact at its ends and halfway (tolerance 1e-6).
    #[test]
    fn attenuation_ramps_linearly_between_start_and_stop() {
        assert_eq!(attenuation(1.0, 2.0, 4.0), Some(1.0));
        assert!((attenuation(3.0, 2.0, 4.0).unwrap() - 0.5).abs() < 1e-6);
        assert_eq!(attenuation(4.0, 2.0, 4.0), None);
        assert_eq!(attenuation(1.0, 0.0, 0.0), None);
    }

    /// Hard shadows stop the light; a factor lets its share through; an unblocked ray with
    /// a filter tints by factor + (1 − factor) · filter (exact in binary fractions).
    #[test]
    fn shadow_factor_lets_its_share_through() {
        let c = Color::new(0.5, 1.0, 2.0, 1.0);
        assert_eq!(shadowed(c, 0.0, false, Color::ZERO), None);
        assert_eq!(shadowed(c, 0.25, false, Color::ZERO), Some(c * 0.25));
        assert_eq!(shadowed(c, 0.0, true, Color::ONE), Some(c));
        let tinted = shadowed(c, 0.5, true, Color::new(0.0, 0.5, 1.0, 1.0)).unwrap();
        assert_eq!(tinted, Color::new(0.25, 0.75, 2.0, 1.0));
    }

    /// Constant slots are read, a missing one is null (zero), a connection is not constant.
    #[test]
    fn constants_are_values_and_missing_slots() {
        let slots = [Slot::Value(Value::Scalar(2.0)), Slot::Connect { node: 0, member: None }];
        assert_eq!(constant(&slots, 0).map(|v| v.scalar()), Some(2.0));
        assert!(constant(&slots, 1).is_none());
        assert_eq!(constant(&slots, 2).map(|v| v.scalar()), Some(0.0));
    }
}
