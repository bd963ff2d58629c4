//! rampShader translated for the path engine (see `crate::maya`'s module doc).

use bsdf::Rgb;

use super::{connection, constant_value, cut_out, refract, refraction_index, slot, Reader, ViewTransparency};
use crate::{Binding, SurfaceMaterial, SurfaceModel, Target};

/// A constant ramp parameter of the reader's node (`None` when the ramp is connected or
/// has connected points, with a warning).
pub(super) fn ramp_of(r: &mut Reader, name: &str, member: &str, empty: Rgb) -> Option<::maya::utility::Ramp> {
    if connection(r.graph, r.node, name).is_some() {
        r.warnings.push(format!("the ramp '{name}' is connected; the path engine uses its default"));
        return None;
    }
    let Some(v) = slot(r.graph, r.node, name).and_then(constant_value) else {
        r.warnings.push(format!("the ramp '{name}' has connected points; the path engine uses its default"));
        return None;
    };
    Some(::maya::utility::Ramp::read(&v, name, member, glam::Vec3A::new(empty.x, empty.y, empty.z)))
}

/// rampShader (see `crate::maya`'s module doc).
pub(super) fn translate(r: &mut Reader, surface: &mut SurfaceMaterial, alone: bool) {
    use ::maya::ramp_shader::ColorInput;
    let input = ColorInput::from_maya(r.scalar("colorInput", 0.0) as i32);
    let (d, t) = (r.scalar("diffuse", 0.8), r.scalar("translucence", 0.0));
    let color = ramp_of(r, "color", "Color", Rgb::splat(0.5));
    let color_at = |x: f32| {
        color.as_ref().map_or(Rgb::splat(0.5), |ramp| {
            let c = ramp.at(x);
            Rgb::new(c.x, c.y, c.z)
        })
    };
    let c = color_at(1.0);
    // The light from behind (`translucence` t), a transmission lobe of this albedo
    // before the fade. The light-angle input's classic P(u) ⊙ L = t · C((1 − u)/2) ⊙ L
    // for a light behind at |cos θ| = u (no cosine factor) is the ramp itself, all its knots
    // in [0, ½] and the next with their interpolation
    // (`bsdf::maya_highlight::translucence::LightAngle`): a lobe of albedo A = 2∫P du,
    // not capped (where the classic shader passes more light than it receives, so does
    // the lobe). The other inputs' C ⊙ L · t · |cos θ| is a Lambertian transmission
    // taking C at 1, as their albedo does.
    let (behind, light_angle) = if input == ColorInput::LightAngle {
        let knots: Vec<(f32, Rgb, i32)> = color.as_ref().map_or_else(Vec::new, |ramp| {
            ramp.points().iter().map(|&(x, c, interp)| (x, Rgb::new(c.x, c.y, c.z), interp)).collect()
        });
        let (a, shape) = bsdf::maya_highlight::translucence::LightAngle::from_ramp(&knots, color_at(0.5), t.max(0.0));
        (a, Some(shape))
    } else {
        (c * t.max(0.0), None)
    };
    let albedo = if input == ColorInput::LightAngle {
        c * (d + t)
    } else {
        r.warnings.push(format!("the colour ramp indexed by {input:?} is taken at 1 (albedo = colour at 1 · diffuse)"));
        c * d
    };
    // The classic highlight, specularity · rolloff(f) · S(h) ⊙ light · h with h Blinn's
    // D, is Maya's lobe `RampBlinn` of tint specularity, coloured by the `specularColor`
    // ramp at the highlight's strength and scaled by the roll-off ramp at the facing
    // ratio f; the reflection, reflectivity(f) · (environment(R) + traced), a mirror of
    // weight reflectivity(f) that emits the environment ramp at the world reflection
    // direction's height — `bsdf::MayaGlossy`'s ramps, tabulated. A ramp the same all
    // along is taken as its constant.
    use bsdf::maya_highlight::{ViewRamps, VIEW_RAMP_STEPS};
    let specularity = r.scalar("specularity", 0.0).max(0.0);
    let read = |r: &mut Reader, name: &str, member: &str, empty: Rgb| {
        ramp_of(r, name, member, empty)
            .unwrap_or_else(|| ::maya::utility::Ramp::new(Vec::new(), glam::Vec3A::new(empty.x, empty.y, empty.z)))
    };
    let at = |ramp: &::maya::utility::Ramp, x: f32| {
        let c = ramp.at(x);
        Rgb::new(c.x, c.y, c.z)
    };
    let varies = |ramp: &::maya::utility::Ramp| {
        (0..VIEW_RAMP_STEPS)
            .any(|k| (at(ramp, k as f32 / (VIEW_RAMP_STEPS - 1) as f32) - at(ramp, 1.0)).abs().max_element() > 1e-6)
    };
    let specular = (specularity > 0.0).then(|| read(r, "specularColor", "Color", Rgb::splat(0.5)));
    let rolloff = read(r, "specularRollOff", "FloatValue", Rgb::ONE);
    let reflectivity = read(r, "reflectivity", "FloatValue", Rgb::ZERO);
    let environment = read(r, "environment", "Color", Rgb::ZERO);
    let reflects = (0..VIEW_RAMP_STEPS).any(|k| at(&reflectivity, k as f32 / (VIEW_RAMP_STEPS - 1) as f32).x > 0.0);
    let by_view = varies(&rolloff) || reflects && (varies(&reflectivity) || varies(&environment));
    let tint = match &specular {
        Some(s) if varies(s) => Rgb::splat(specularity),
        Some(s) => at(s, 1.0) * specularity,
        None => Rgb::ZERO,
    };
    let tint = if by_view { tint } else { tint * at(&rolloff, 1.0).x.max(0.0) };
    let transparency = read(r, "transparency", "Color", Rgb::ZERO);
    let incandescence = read(r, "incandescence", "Color", Rgb::ZERO);
    let tr = at(&transparency, 1.0).clamp(Rgb::ZERO, Rgb::ONE);
    // Refraction as for the lambert family (see `translate`) where the transparency ramp
    // is not black somewhere, by T(1) — or by T at each hit's facing ratio when it varies
    // (`ViewTransparency::refracting`).
    let t_most = (0..VIEW_RAMP_STEPS)
        .map(|k| at(&transparency, k as f32 / (VIEW_RAMP_STEPS - 1) as f32).clamp(Rgb::ZERO, Rgb::ONE))
        .fold(tr, Rgb::max);
    let ior = refraction_index(r, t_most, alone);
    cut_out(surface, tr, alone && (tint != Rgb::ZERO || reflects) && ior.is_none());
    // Transparency fades the lit colour and incandescence, not the highlight and the
    // reflection (as for the lambert family, see `translate`).
    let fade = if ior.is_some() {
        Rgb::ONE - tr
    } else if alone && surface.opacity > 0.0 {
        (Rgb::ONE - tr) / surface.opacity
    } else {
        Rgb::ONE
    };
    let coverage = if alone && ior.is_none() { surface.opacity.max(1e-3) } else { 1.0 };
    surface.diffuse = albedo * fade;
    // Ambient light goes by the colour at the ramp's reference index (C(1) for the light
    // angle; the other inputs' reference is taken at 1 as their albedo is): 1/(d + t) or
    // 1/d of the diffuse colour.
    let share = if input == ColorInput::LightAngle { d + t } else { d };
    surface.ambient = Rgb::splat(if share > 0.0 { 1.0 / share } else { 0.0 });
    // `ambientColor` a: C_ref ⊙ a emitted beside the incandescence, faded alike.
    let ambient = Ambient::read(r);
    surface.emission = (at(&incandescence, 1.0) + ambient.at(1.0)) * fade;
    ambient.bind(r, fade);
    // Transparency and incandescence ramps (and the facing-angle colour ramp of the
    // ambient colour) that vary with the view: read at each hit's facing ratio, as the
    // classic shader does (for a refracting one, the refraction's weight too).
    if alone && (varies(&transparency) || varies(&incandescence) || ambient.varies()) {
        let view = ViewTransparency::tabulate(
            |f| at(&transparency, f),
            |f| at(&incandescence, f) + ambient.at(f),
            albedo,
            tint != Rgb::ZERO || reflects,
        )
        .with_translucence(behind);
        surface.view_transparency = Some(Box::new(if ior.is_some() { view.refracting() } else { view }));
    }
    let glow_intensity = r.scalar("glowIntensity", 0.0);
    if glow_intensity != 0.0 {
        surface.glow = c * glow_intensity;
    }
    if let Some((bump, member)) = connection(r.graph, r.node, "normalCamera") {
        r.bindings.push(Binding { node: bump, member, target: Target::Normal, scale: 1.0 });
    }
    if tint != Rgb::ZERO || reflects {
        let shape = bsdf::maya_highlight::Shape::RampBlinn { eccentricity: r.scalar("eccentricity", 0.3) };
        let mut g = bsdf::MayaGlossy::new(shape, tint)
            .with_reflection_limit(r.scalar("reflectionLimit", 1.0).max(0.0) as u32)
            .with_coverage(coverage);
        if let Some(s) = specular.as_ref().filter(|s| varies(s)) {
            g = g.with_specular_ramp(|h| at(s, h));
        }
        if by_view {
            g = g.with_mirror(Rgb::ONE, None).with_view_ramps(ViewRamps::tabulate(
                |f| at(&rolloff, f).x,
                |f| if reflects { at(&reflectivity, f).x } else { 0.0 },
                |y| at(&environment, y),
            ));
        } else if reflects {
            // A constant environment: emitted by the mirror's weight (a layer's emission
            // is mixed by the layered shader).
            let (weight, env) = (at(&reflectivity, 1.0).x.max(0.0), at(&environment, 1.0));
            g = g.with_mirror(Rgb::splat(weight), None);
            if alone {
                g = g.with_reflected(env);
            } else {
                surface.emission += env * weight;
            }
        }
        surface.model = SurfaceModel::Maya(Box::new(g));
    }
    super::translucence::translate_ramp(r, surface, behind * fade, light_angle);
    if let Some(ior) = ior {
        refract(r, surface, tr, ior);
    }
}

/// rampShader's `ambientColor` a as the classic shader adds it whatever the lights:
/// C_ref ⊙ a (faded by 1 − T like the incandescence), C_ref the colour ramp at the
/// facing ratio f for the facing-angle input and at 1 for the light-angle input (its
/// reference index); the brightness inputs' reference, the lit colour itself, is taken
/// at 1 as their albedo is (the translation warns about it). Emitted radiance in the
/// path engine, as the lambert family's c ⊙ a (`super::ambient_color`).
pub(super) struct Ambient {
    /// The colour ramp (its default, 0.5 grey, when connected).
    color: ::maya::utility::Ramp,
    /// The constant `ambientColor` (black when connected: see [`Ambient::bind`]).
    a: Rgb,
    /// The colour input is the facing angle: C_ref = C(f).
    facing: bool,
}

impl Ambient {
    /// The ambient colour of the reader's rampShader.
    pub(super) fn read(r: &mut Reader) -> Ambient {
        use ::maya::ramp_shader::ColorInput;
        let facing = ColorInput::from_maya(r.scalar("colorInput", 0.0) as i32) == ColorInput::FacingAngle;
        let grey = glam::Vec3A::splat(0.5);
        let color = if connection(r.graph, r.node, "color").is_some() {
            ::maya::utility::Ramp::new(Vec::new(), grey)
        } else {
            slot(r.graph, r.node, "color").and_then(constant_value).map_or_else(
                || ::maya::utility::Ramp::new(Vec::new(), grey),
                |v| ::maya::utility::Ramp::read(&v, "color", "Color", grey),
            )
        };
        let a = if connection(r.graph, r.node, "ambientColor").is_some() {
            Rgb::ZERO
        } else {
            r.color("ambientColor", Rgb::ZERO)
        };
        Ambient { color, a, facing }
    }

    /// C_ref ⊙ a at facing ratio `f` (before the fade).
    pub(super) fn at(&self, f: f32) -> Rgb {
        let c = self.color.at(if self.facing { f } else { 1.0 });
        Rgb::new(c.x, c.y, c.z) * self.a
    }

    /// Whether C_ref ⊙ a changes with the facing ratio.
    pub(super) fn varies(&self) -> bool {
        use bsdf::maya_highlight::VIEW_RAMP_STEPS;
        (0..VIEW_RAMP_STEPS)
            .any(|k| (self.at(k as f32 / (VIEW_RAMP_STEPS - 1) as f32) - self.at(1.0)).abs().max_element() > 1e-6)
    }

    /// A connected `ambientColor`: C(1) ⊙ the value ⊙ `fade` emitted per hit (one
    /// binding per channel; C taken at 1 for the facing-angle input too, with a warning
    /// when the colour ramp varies).
    fn bind(&self, r: &mut Reader, fade: Rgb) {
        let Some((node, member)) = connection(r.graph, r.node, "ambientColor") else { return };
        let at = |f: f32| {
            let c = self.color.at(f);
            Rgb::new(c.x, c.y, c.z)
        };
        let steps = bsdf::maya_highlight::VIEW_RAMP_STEPS;
        if self.facing && (0..steps).any(|k| (at(k as f32 / (steps - 1) as f32) - at(1.0)).abs().max_element() > 1e-6) {
            r.warnings
                .push("a connected 'ambientColor' is lit by the colour ramp at 1, not at the facing ratio".into());
        }
        let weight = at(1.0) * fade;
        for (c, scale) in [weight.x, weight.y, weight.z].into_iter().enumerate() {
            if scale != 0.0 {
                r.bindings.push(Binding {
                    node,
                    member: member.clone(),
                    target: Target::EmissionChannel(c as u8),
                    scale,
                });
            }
        }
    }
}

/// The `transparency` ramp of the rampShader `m` (a node of `graph`) at facing ratio 1,
/// per channel; `None` when it is connected or has connected points.
pub(super) fn transparency_at_one(graph: &shader::Graph, m: shader::NodeId) -> Option<Rgb> {
    if connection(graph, m, "transparency").is_some() {
        return None;
    }
    let v = slot(graph, m, "transparency").and_then(constant_value)?;
    let c = ::maya::utility::Ramp::read(&v, "transparency", "Color", glam::Vec3A::ZERO).at(1.0);
    Some(Rgb::new(c.x, c.y, c.z))
}
