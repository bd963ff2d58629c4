//! Maya's rampShader: a material whose colours are ramps over the light and view angles.
//!
//! Parameters (`mayabase.mi`, Maya's attribute names): `colorInput` (what indexes the
//! colour ramp: 0 light angle, 1 facing angle, 2 brightness, 3 normalized brightness);
//! the ramps `color` (Maya's default: 0.5 grey), `transparency` (black), `incandescence`
//! (black), `specularColor` (0.5 grey), `specularRollOff` (1), `reflectivity` (0) and
//! `environment` (black) — arrays of {`<name>_Position`, `<name>_Color` or
//! `<name>_FloatValue`, `<name>_Interp`}, interpolation 0 none, 1 linear, 2 smooth,
//! 3 spline (`bsdf::maya_highlight::ramp_curve`), an empty ramp taking the value in brackets;
//! `ambientColor`, `normalCamera`, `diffuse` (0.8), `translucence` (0), `specularity`
//! (0), `eccentricity` (0.3), `reflectionLimit` (1), `refractions`, `refractiveIndex`,
//! `refractionLimit`, `matteOpacity`, `glowIntensity`, `lightList` (the lights, as the
//! other materials read it: see [`crate::material`]).
//!
//! With f = N·V (the facing ratio, 0 at the silhouette, 1 facing the viewer), each light
//! of colour L at cos θ = N·L, and C(x) the colour ramp at x:
//!
//! ```text
//! light angle (0):      lit = Σ C((1 + cos θ)/2) ⊙ L · (d · max(cos θ, 0) + t)
//! facing angle (1):     lit = C(f) ⊙ Σ L · (d · max(cos θ, 0) + t · max(−cos θ, 0))
//! brightness (2):       E = Σ L · (d · max(cos θ, 0) + t · max(−cos θ, 0)),  lit = C(luma E)
//! normalized (3):       lit = C(luma E / luma Σ L)   (independent of the lights' strength)
//! ambient:              + C_ref ⊙ (ambientColor + ambient lights + d · E_fg/π)
//! specular:             + specularity · rolloff(f) · Σ S(h) ⊙ L · h,  h = Blinn's D (peak 1)
//! reflection:           + reflectivity(f) · (environment(R) + traced reflection)
//! out = (lit + incandescence(f)) ⊙ (1 − T(f)) + specular + reflection + T(f) ⊙ behind
//! ```
//!
//! C_ref is the colour at the ramp's index for the ambient and final-gather light (C(1)
//! for light angle, C(f) for facing angle, C(luma E) for brightness), S the
//! `specularColor` ramp indexed by the highlight's own strength h ∈ [0, 1] (0 at its edge,
//! 1 at its centre), `environment` indexed by the world reflection direction's height,
//! (1 + R_y)/2, and `transparency`, `incandescence`, `specularRollOff` and
//! `reflectivity` by f. Maya's documentation says the light-angle ramp with black at 0.5
//! and the surface colour at 1, `diffuse` 0 and `translucence` 1 is a lambert falloff:
//! the light-angle row above is built so (C((1 + cos θ)/2) = c·cos θ for cos θ > 0). The
//! other rows, the indices of the specular and reflection ramps and Blinn's distribution
//! for the highlight are mira's reading of Maya's description.
//!
//! `translucenceDepth` D (0.5): as the lambert family's (see [`crate::material`]), a
//! shadow ray that leaves the object's own geometry from inside after a stretch s passes
//! T + (1 − T)·max(1 − s/D, 0) of it where `translucence` > 0 (T the transparency ramp at
//! the shadow ray's facing ratio).
//!
//! Not read: `forwardScatter`, `translucenceFocus`,
//! `reflectionSpecularity`, `lightAbsorbance`, `surfaceThickness`, `shadowAttenuation`,
//! `chromaticAberration`, `matteOpacityMode`, `hideSource`.

use glam::Vec3A;
use shader::{Ctx, NodeId, RayType, Value};

use crate::light::light_role;
use crate::material::{behind_with, material_lights, passage, shadow_filter};
use crate::maya_shader;
use crate::utility::Ramp;
use crate::values::{luma, rgb, rgba, write_struct};

const COLOR_INPUT: usize = 0;
const COLOR: usize = 1;
const TRANSPARENCY: usize = 2;
const INCANDESCENCE: usize = 3;
const AMBIENT_COLOR: usize = 4;
const NORMAL_CAMERA: usize = 5;
const DIFFUSE: usize = 6;
const TRANSLUCENCE: usize = 7;
const SPECULARITY: usize = 8;
const ECCENTRICITY: usize = 9;
const SPECULAR_COLOR: usize = 10;
const SPECULAR_ROLLOFF: usize = 11;
const REFLECTIVITY: usize = 12;
const ENVIRONMENT: usize = 13;
const REFLECTION_LIMIT: usize = 14;
const REFRACTIONS: usize = 15;
const REFRACTIVE_INDEX: usize = 16;
const REFRACTION_LIMIT: usize = 17;
const MATTE_OPACITY: usize = 18;
const GLOW_INTENSITY: usize = 19;
const LIGHT_LIST: usize = 20;
const TRANSLUCENCE_DEPTH: usize = 21;

/// What indexes the colour ramp (`colorInput`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorInput {
    /// 0: (1 + N·L)/2, per light.
    LightAngle,
    /// 1: the facing ratio N·V.
    FacingAngle,
    /// 2: the luminance of the diffuse light received.
    Brightness,
    /// 3: that luminance over the luminance of the lights' colours.
    NormalizedBrightness,
}

impl ColorInput {
    /// Maya's enumeration; other values read as light angle (Maya's default).
    pub fn from_maya(v: i32) -> ColorInput {
        match v {
            1 => ColorInput::FacingAngle,
            2 => ColorInput::Brightness,
            3 => ColorInput::NormalizedBrightness,
            _ => ColorInput::LightAngle,
        }
    }
}

/// Blinn's distribution of eccentricity `ecc` at N·H (1 at the peak): the strength of the
/// ramp shader's highlight.
pub fn blinn_distribution(ecc: f32, nh: f32) -> f32 {
    bsdf::maya_highlight::blinn_distribution(ecc, nh)
}

/// The diffuse part of the ramp shader's colour for the lights received, as the module
/// doc's first four rows: `lights` holds (colour, N·L) per light sample (weighted by the
/// caller), `color` the colour ramp, `facing` N·V.
pub fn lit_color(
    input: ColorInput,
    color: &Ramp,
    lights: &[(Vec3A, f32)],
    diffuse: f32,
    translucence: f32,
    facing: f32,
) -> Vec3A {
    let received = |(l, cos): &(Vec3A, f32)| *l * (diffuse * cos.max(0.0) + translucence * (-cos).max(0.0));
    match input {
        ColorInput::LightAngle => lights
            .iter()
            .map(|(l, cos)| color.at(0.5 * (1.0 + cos)) * *l * (diffuse * cos.max(0.0) + translucence))
            .sum(),
        ColorInput::FacingAngle => color.at(facing) * lights.iter().map(received).sum::<Vec3A>(),
        ColorInput::Brightness => color.at(luma(lights.iter().map(received).sum())),
        ColorInput::NormalizedBrightness => {
            let total = luma(lights.iter().map(|(l, _)| *l).sum());
            let e = luma(lights.iter().map(received).sum());
            color.at(if total > 0.0 { e / total } else { 0.0 })
        }
    }
}

maya_shader!(
    /// Maya's rampShader (see the module doc).
    RAMPSHADER,
    ADSK_RAMPSHADER,
    "maya_rampshader",
    "adskMayaRampShader",
    &[
        "colorInput",
        "color",
        "transparency",
        "incandescence",
        "ambientColor",
        "normalCamera",
        "diffuse",
        "translucence",
        "specularity",
        "eccentricity",
        "specularColor",
        "specularRollOff",
        "reflectivity",
        "environment",
        "reflectionLimit",
        "refractions",
        "refractiveIndex",
        "refractionLimit",
        "matteOpacity",
        "glowIntensity",
        "lightList",
        "translucenceDepth",
    ],
    ramp_shader
);

fn ramp_shader(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let saved_normal = ctx.state.normal;
    if ctx.is_connected(n, NORMAL_CAMERA) && ctx.state.ray_type != RayType::Shadow {
        if let Some(bumped) = ctx.vector(n, NORMAL_CAMERA).try_normalize() {
            ctx.state.normal = if bumped.dot(ctx.state.dir) > 0.0 { -bumped } else { bumped };
        }
    }
    let (normal, view) = (ctx.state.normal, -ctx.state.dir);
    let facing = normal.dot(view).clamp(0.0, 1.0);
    let transparency = Ramp::read(&ctx.array(n, TRANSPARENCY), "transparency", "Color", Vec3A::ZERO)
        .at(facing)
        .clamp(Vec3A::ZERO, Vec3A::ONE);
    if ctx.state.ray_type == RayType::Shadow {
        let transparency = match ctx.state.inside_own {
            Some(inside) => {
                passage(transparency, ctx.scalar(n, TRANSLUCENCE), ctx.scalar(n, TRANSLUCENCE_DEPTH), inside)
            }
            None => transparency,
        };
        return shadow_filter(out, transparency);
    }
    if !ctx.state.ray_type.is_visible() {
        ctx.state.normal = saved_normal;
        return false;
    }
    let input = ColorInput::from_maya(ctx.int(n, COLOR_INPUT));
    let color = Ramp::read(&ctx.array(n, COLOR), "color", "Color", Vec3A::splat(0.5));
    let (diffuse, translucence) = (ctx.scalar(n, DIFFUSE), ctx.scalar(n, TRANSLUCENCE));
    let (specularity, eccentricity) = (ctx.scalar(n, SPECULARITY), ctx.scalar(n, ECCENTRICITY));
    let spec_ramp = Ramp::read(&ctx.array(n, SPECULAR_COLOR), "specularColor", "Color", Vec3A::splat(0.5));

    // The lights: diffuse samples (colour, cos θ), ambient light, specular.
    let mut samples: Vec<(Vec3A, f32)> = Vec::new();
    let (mut ambient, mut specular) = (Vec3A::ZERO, Vec3A::ZERO);
    for light in material_lights(ctx, n, LIGHT_LIST) {
        let role = light_role(ctx, light);
        let mut lp = ctx.light_loop(light);
        lp.both_sides = true;
        let mut got: Vec<(Vec3A, f32)> = Vec::new();
        let (mut amb, mut spec) = (Vec3A::ZERO, Vec3A::ZERO);
        while let Some(s) = ctx.sample_light(&mut lp) {
            let c = rgb(s.color);
            // The direction the light is shaded with (a volume light may turn it).
            let (dir, dot_nl) = role.shading_direction(ctx.state.point, normal, s.dir);
            let specular_too = match role.ambient_shade {
                Some(shade) => {
                    amb += c * ((1.0 - shade) + shade * dot_nl.max(0.0));
                    role.ambient_specular
                }
                None => {
                    if role.diffuse {
                        got.push((c, dot_nl));
                    }
                    role.specular
                }
            };
            if specular_too && specularity > 0.0 && dot_nl > 0.0 && normal.dot(view) > 0.0 {
                if let Some(h) = (view + dir).try_normalize() {
                    let d = blinn_distribution(eccentricity, normal.dot(h));
                    spec += spec_ramp.at(d) * c * d;
                }
            }
        }
        if lp.samples > 0 {
            let k = 1.0 / lp.samples as f32;
            samples.extend(got.into_iter().map(|(c, cos)| (c * k, cos)));
            ambient += amb * k;
            specular += spec * k;
        }
    }
    let lit = lit_color(input, &color, &samples, diffuse, translucence, facing);
    let reference = match input {
        ColorInput::LightAngle => color.at(1.0),
        ColorInput::FacingAngle => color.at(facing),
        _ => lit,
    };
    // Final gathering's irradiance over π, as the lambert family takes it (crate::material).
    let fg = if diffuse > 0.0 { rgb(ctx.compute_irradiance()) * std::f32::consts::FRAC_1_PI } else { Vec3A::ZERO };
    let ambient_light = rgb(ctx.color(n, AMBIENT_COLOR)) + ambient + diffuse * fg;
    let incandescence = Ramp::read(&ctx.array(n, INCANDESCENCE), "incandescence", "Color", Vec3A::ZERO).at(facing);
    let mut result = (lit + reference * ambient_light + incandescence) * (Vec3A::ONE - transparency);
    let rolloff = Ramp::read(&ctx.array(n, SPECULAR_ROLLOFF), "specularRollOff", "FloatValue", Vec3A::ONE).at(facing).x;
    result += specularity * rolloff * specular;
    let reflectivity = Ramp::read(&ctx.array(n, REFLECTIVITY), "reflectivity", "FloatValue", Vec3A::ZERO).at(facing).x;
    if reflectivity > 0.0 {
        let dir = ctx.reflection_dir();
        let env = Ramp::read(&ctx.array(n, ENVIRONMENT), "environment", "Color", Vec3A::ZERO).at(0.5 * (1.0 + dir.y));
        let limit = ctx.int(n, REFLECTION_LIMIT).max(0) as u32;
        let traced = if ctx.state.reflection_level < limit {
            ctx.trace_reflection(dir).map_or(Vec3A::ZERO, rgb)
        } else {
            Vec3A::ZERO
        };
        result += reflectivity * (env + traced);
    }
    let t_mean = (transparency.x + transparency.y + transparency.z) / 3.0;
    let mut alpha = 1.0;
    if transparency != Vec3A::ZERO {
        let (refract, ior) = (ctx.bool(n, REFRACTIONS), ctx.scalar(n, REFRACTIVE_INDEX));
        let limit = ctx.int(n, REFRACTION_LIMIT).max(0) as u32;
        let b = behind_with(ctx, refract, ior, limit);
        result += transparency * rgb(b);
        alpha = 1.0 - t_mean + t_mean * b.w;
    }
    ctx.state.normal = saved_normal;
    let glow = color.at(1.0) * ctx.scalar(n, GLOW_INTENSITY);
    let matte = ctx.scalar(n, MATTE_OPACITY);
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(result, alpha))),
            ("outTransparency", Value::Color(rgba(transparency, t_mean))),
            ("outGlowColor", Value::Color(rgba(glow, 1.0))),
            ("outMatteOpacity", Value::Color(shader::Color::new(matte, matte, matte, 1.0))),
        ],
    );
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(points: &[(f32, Vec3A)], interp: i32) -> Ramp {
        Ramp::new(points.iter().map(|&(p, c)| (p, c, interp)).collect(), Vec3A::ZERO)
    }

    /// Maya's documented recipe: black at 0.5, colour c at 1, linear, diffuse 0,
    /// translucence 1 under the light-angle input is lambert's c·L·cos θ.
    #[test]
    fn the_light_angle_recipe_is_a_lambert_falloff() {
        let c = Vec3A::new(0.9, 0.5, 0.2);
        let r = ramp(&[(0.5, Vec3A::ZERO), (1.0, c)], 1);
        let l = Vec3A::new(1.0, 0.8, 0.6);
        for deg in [0.0f32, 30.0, 60.0, 85.0, 120.0] {
            let cos = deg.to_radians().cos();
            let got = lit_color(ColorInput::LightAngle, &r, &[(l, cos)], 0.0, 1.0, 1.0);
            let want = c * l * cos.max(0.0);
            assert!((got - want).abs().max_element() < 1e-5, "{deg}°: {got} vs {want}");
        }
    }

    #[test]
    fn facing_and_brightness_inputs_index_the_ramp() {
        let r = ramp(&[(0.0, Vec3A::new(1.0, 0.0, 0.0)), (1.0, Vec3A::new(0.0, 0.0, 1.0))], 1);
        let l = [(Vec3A::splat(2.0), 0.5)];
        // Facing 0.25: colour (0.75, 0, 0.25) lit like lambert, d·L·cos = 0.8·2·0.5.
        let got = lit_color(ColorInput::FacingAngle, &r, &l, 0.8, 0.0, 0.25);
        assert!((got - Vec3A::new(0.75, 0.0, 0.25) * 0.8).abs().max_element() < 1e-6, "{got}");
        // Brightness: luma of 0.8 received = 0.8 → the ramp at 0.8, not multiplied again.
        let got = lit_color(ColorInput::Brightness, &r, &l, 1.0, 0.0, 0.0);
        assert!((got - Vec3A::new(0.0, 0.0, 1.0)).abs().max_element() < 1e-6, "{got}");
        let got = lit_color(ColorInput::Brightness, &r, &[(Vec3A::splat(0.5), 0.5)], 1.0, 0.0, 0.0);
        assert!((got - Vec3A::new(0.75, 0.0, 0.25)).abs().max_element() < 1e-6, "{got}");
        // Normalized brightness: cos θ whatever the light's strength.
        for strength in [0.5, 2.0, 40.0] {
            let got = lit_color(ColorInput::NormalizedBrightness, &r, &[(Vec3A::splat(strength), 0.5)], 1.0, 0.0, 0.0);
            assert!((got - Vec3A::new(0.5, 0.0, 0.5)).abs().max_element() < 1e-6, "{strength}: {got}");
        }
    }

    #[test]
    fn an_empty_ramp_takes_its_default_and_blinn_peaks_at_one() {
        let r = Ramp::read(&Value::Array(Vec::new().into()), "color", "Color", Vec3A::splat(0.5));
        assert_eq!(r.at(0.3), Vec3A::splat(0.5));
        assert!((blinn_distribution(0.3, 1.0) - 1.0).abs() < 1e-6);
        assert!(blinn_distribution(0.3, 0.95) < blinn_distribution(0.5, 0.95));
        assert_eq!(blinn_distribution(0.3, -0.1), 0.0);
    }
}
