//! What lights emit: MDL light materials (`light_omni`, `light_spot`, `light_ies`) with
//! MDL's units, mental ray's base light shaders (`mib_light_point`, `mib_light_spot`,
//! `mib_light_infinite`, `mib_light_photometric`) and the Architectural library's
//! `mia_photometric_light` and `mia_portal_light`, and the physics library's
//! `physical_light`.

pub mod ambient;
pub mod maya;

use std::sync::Arc;

use scene::{Library, Light};

use crate::{color_param, declaration_name, first_call, scalar_param, string_param};
use bsdf::Rgb;
use mia::photometric::{positive_or_one, Settings};
use shader::light::ies::Profile;
pub use shader::light::profiles::Distribution;

/// How a light's colour is to be read.
#[derive(Clone, Debug, PartialEq)]
pub enum Power {
    /// Radiant exitance of the light's surface (MDL `lumen_m2`): L = E / π.
    Exitance(Rgb),
    /// Radiance of the light's surface (MDL `nit`).
    Radiance(Rgb),
    /// Total power over the whole light (MDL `lumen`).
    Flux(Rgb),
    /// Radiant intensity along the main direction (MDL `candela`; point lights).
    Intensity(Rgb),
    /// mental ray base light shaders: the colour arriving at a lit point, with no distance
    /// falloff (area lights average it over their samples); `atten` gives a linear falloff
    /// between `start` and `stop`.
    Constant {
        /// The colour.
        color: Rgb,
        /// Linear falloff distances, if `atten` is on.
        falloff: Option<(f32, f32)>,
    },
    /// Photometric point lights (`mib_light_photometric`, `mia_photometric_light`): the
    /// colour arriving is `color` × the [`Emission::distribution`] towards the point ×
    /// d^−exponent (no falloff for exponent 0, nor outside `range` when one is given).
    Photometric {
        /// The colour at unit distance along the distribution's peak.
        color: Rgb,
        /// Distance falloff exponent (2: inverse square).
        exponent: f32,
        /// `(start, stop)`: the falloff applies only between them.
        range: Option<(f32, f32)>,
    },
    /// Maya volume lights other than the evenly scaled whole sphere (box, cylinder, cone,
    /// arcs, uneven scales): a point light at the light's origin whose colour arriving at
    /// a point depends on where the point lies in the light's volume ([`maya::VolumeEmission`]).
    Volume(Box<maya::VolumeEmission>),
    /// `mia_physicalsun` on a directional light: the sun, a distant light of this
    /// irradiance on a plane facing it, arriving from directions spread uniformly over a
    /// cone of half-angle `angular_radius` (radians) around the light's direction (0: one
    /// direction, hard shadows).
    Sun {
        /// Irradiance on a plane facing the sun, in the path engine's units (see
        /// `physical_sun`).
        irradiance: Rgb,
        /// Half-angle of the cone of directions, radians.
        angular_radius: f32,
    },
    /// `mia_portal_light` (area lights over windows): the surface radiance along a
    /// direction is `scale` × the environment's radiance along it, emitted to the side of
    /// the shape's normal (the other side with `reverse`). `use_custom_environment`,
    /// `cutoff_threshold` and `shadows` are not read: the scene's environment is used, and
    /// every sample is shadowed.
    Portal {
        /// `tint_color` × `multiplier` (zero when `on` is off).
        scale: Rgb,
        /// `reverse`.
        reverse: bool,
    },
}

/// A light's emission, and whether it is a spot with an exponent distribution.
#[derive(Clone, Debug, PartialEq)]
pub struct Emission {
    /// The amount and its unit.
    pub power: Power,
    /// MDL `light_spot`: cosine power of the spot distribution around the light's −Z.
    pub spot_exponent: Option<f32>,
    /// mental ray `mib_light_spot`: cosine of the inner (full-intensity) cone.
    pub cone: Option<f32>,
    /// A Maya spot light's cone, penumbra and dropoff: the light's spot factor is the
    /// classic light's ([`::maya::light::SpotCone::factor`]) instead of `cone`'s linear
    /// fade in the cosine and `spot_exponent`.
    pub maya_spot: Option<::maya::light::SpotCone>,
    /// How a point light's intensity varies with direction in the light's local frame
    /// (a light profile or a cosine power; `None`: uniform). MDL `light_ies` and mental
    /// ray's photometric lights.
    pub distribution: Option<Distribution>,
}

/// The emission of `light`, or a message saying why it cannot be read; light profiles
/// are not available (see [`emission_with`]).
pub fn emission(light: &Light, lib: &Library) -> Result<Emission, String> {
    emission_with(light, lib, &|_| None)
}

/// The emission of `light`, with `profiles` giving the light profile of a `lightprofile`
/// element's name (`None` where it is unknown or unreadable: the light is then uniform).
/// A profile parameter that is not set falls back to the light's `lightprofile` statement.
/// `physical_light`'s flux is its `color`, whatever the scene's `"light relative scale"`:
/// mental ray scales what legacy (non-BSDF) shaders receive by it, and the path engine's
/// materials are BSDFs (`scene::options::modes`).
pub fn emission_with(
    light: &Light,
    lib: &Library,
    profiles: &dyn Fn(&str) -> Option<Arc<Profile>>,
) -> Result<Emission, String> {
    let Some(list) = &light.shader else {
        return Err(format!("light '{}' has no light shader", light.name));
    };
    let Some((decl, params)) = first_call(&list.0, lib) else {
        return Err(format!("light '{}': its shader cannot be found", light.name));
    };
    // Maya's lights (see [`maya`]).
    if let Some(maya) = maya::emission_of(declaration_name(decl), params, light.light_to_world) {
        return maya;
    }
    let color = |name: &str, default: Rgb| match color_param(params, name) {
        Some(Ok(c)) => c,
        _ => default,
    };
    let profile = || string_param(params, "profile").or(light.lightprofile.as_deref()).and_then(profiles);
    let scalar = |name: &str, default: f64| scalar_param(params, name).unwrap_or(default) as f32;
    match declaration_name(decl) {
        "mdl::nvidia::core_definitions::light_omni" | "mdl::nvidia::core_definitions::light_spot" => {
            let amount = color("tint", Rgb::ONE)
                * (scalar_param(params, "intensity").unwrap_or(1000.0)
                    * scalar_param(params, "unit_scale").unwrap_or(1.0)) as f32;
            let power = match string_param(params, "unit").unwrap_or("lumen_m2") {
                "lumen" => Power::Flux(amount),
                "candela" => Power::Intensity(amount),
                "nit" => Power::Radiance(amount),
                _ => Power::Exitance(amount),
            };
            let spot_exponent = declaration_name(decl)
                .ends_with("light_spot")
                .then(|| scalar_param(params, "spot_exponent").unwrap_or(30.0) as f32);
            Ok(Emission { power, spot_exponent, cone: None, distribution: None, maya_spot: None })
        }
        "mdl::nvidia::core_definitions::light_ies" => {
            // The profile's measured candela, times tint · intensity · unit_scale.
            let amount = color("tint", Rgb::ONE) * scalar("intensity", 1.0) * scalar("unit_scale", 1.0);
            let distribution = profile().map(|profile| Distribution::Profile { profile, scale: 1.0 });
            Ok(Emission {
                power: Power::Photometric { color: amount, exponent: 2.0, range: None },
                spot_exponent: None,
                cone: None,
                distribution,
                maya_spot: None,
            })
        }
        "mib_light_photometric" => {
            let (start, stop) = (scalar("start", 0.0), scalar("stop", 0.0));
            let distribution = profile()
                .filter(|p| p.peak() > 0.0)
                .map(|profile| Distribution::Profile { scale: 1.0 / profile.peak(), profile });
            Ok(Emission {
                power: Power::Photometric {
                    color: color("color", Rgb::ZERO),
                    exponent: light.exponent.max(0.0) as f32,
                    range: (stop > start && stop > 0.0).then_some((start, stop)),
                },
                spot_exponent: None,
                cone: None,
                distribution,
                maya_spot: None,
            })
        }
        "mia_photometric_light" => {
            let settings = Settings {
                intensity_mode: scalar("intensity_mode", 0.0) as i32,
                peak_cd: scalar("manual_peak_intensity_cd", 0.0),
                flux_lm: scalar("manual_flux_lm", 0.0),
                distribution_mode: scalar("distribution_mode", 0.0) as i32,
                cosine_bias: scalar("spotlight_cosine_bias", 0.0),
            };
            let (peak, distribution) = settings.resolve(profile());
            let on = scalar("on", 1.0) != 0.0;
            let u = positive_or_one(scalar("units_to_meter_scale", 1.0));
            let cm2 = positive_or_one(scalar("cm2_factor", 1.0));
            let k = if on { scalar("multiplier", 1.0) * peak / (u * u * cm2) } else { 0.0 };
            Ok(Emission {
                power: Power::Photometric { color: color("color", Rgb::ONE) * k, exponent: 2.0, range: None },
                spot_exponent: None,
                cone: None,
                distribution,
                maya_spot: None,
            })
        }
        "mia_portal_light" => {
            let on = scalar("on", 1.0) != 0.0;
            let scale = if on { color("tint_color", Rgb::ONE) * scalar("multiplier", 1.0) } else { Rgb::ZERO };
            Ok(Emission {
                power: Power::Portal { scale, reverse: scalar("reverse", 0.0) != 0.0 },
                spot_exponent: None,
                cone: None,
                distribution: None,
                maya_spot: None,
            })
        }
        "mia_physicalsun" => physical_sun(light, params),
        "mib_light_point" | "mib_light_spot" | "mib_light_infinite" => {
            let atten = scalar_param(params, "atten").unwrap_or(0.0) != 0.0;
            let falloff = atten.then(|| {
                (
                    scalar_param(params, "start").unwrap_or(0.0) as f32,
                    scalar_param(params, "stop").unwrap_or(0.0) as f32,
                )
            });
            let cone = (declaration_name(decl) == "mib_light_spot")
                .then(|| scalar_param(params, "cone").unwrap_or(0.0) as f32);
            Ok(Emission {
                power: Power::Constant { color: color("color", Rgb::ZERO), falloff },
                spot_exponent: None,
                cone,
                distribution: None,
                maya_spot: None,
            })
        }
        "physical_light" => {
            // mental ray gives point, spot and sphere lights color / (4π r²) — an intensity
            // of color / 4π — and each sample of a flat area light color · cos / (π r²),
            // which over the shape is a Lambertian emitter of radiance color / (π A): in
            // both cases the light's flux is `color`.
            let cos_exp = scalar("cos_exp", 0.0);
            if cos_exp > 1.0 {
                return Err(format!(
                    "light '{}': physical_light with cos_exp {cos_exp} (narrowed area lights) is not supported by the path engine yet",
                    light.name
                ));
            }
            let cone = (light.kind == scene::LightKind::Spot).then(|| scalar("cone", 0.0));
            Ok(Emission {
                power: Power::Flux(color("color", Rgb::splat(1000.0))),
                spot_exponent: None,
                cone,
                distribution: None,
                maya_spot: None,
            })
        }
        other => Err(format!("light '{}': light shader '{other}' is not supported yet", light.name)),
    }
}

/// `mia_physicalsun`'s emission for the path engine: the colour the classic engine's light
/// shader gives a lit point (`mia::sun::PhysicalSun::color`, the same model and
/// parameters, for the direction towards the sun, the opposite of the light's) × π, over
/// the cone its soft shadows spread over (`PhysicalSun::shadow_cone` when `samples` > 1,
/// as the classic shader; else one direction).
///
/// Why × π: mental ray's shaders multiply a light's colour by their diffuse colour with no
/// 1/π (`mia_material`, the base and Maya shaders alike), and `mia_physicalsky` returns π ×
/// the sky's luminance (so that its hemispherical mean is the illuminance); the path
/// engine reads the sky's value as radiance and reflects ρ/π of the irradiance, so the
/// sun's colour × π keeps the sun's share against the sky's and gives a lambert the
/// classic engine's ρ·colour·cos θ.
///
/// The sources (Autodesk's mental ray manual, "Sun and Sky",
/// <http://download.autodesk.com/us/maya/2010help/mr/shaders/architectural/arch_sunsky.html>;
/// 3ds Max's mr Sun page, <https://help.autodesk.com/cloudhelp/2015/ENU/3DSMax/files/GUID-EA1D17B0-1D25-4014-8D2F-1D0E7F888349.htm>):
/// the sun is a directional light whose shader gives the sunlight (`mi_sample_light`;
/// lux with `rgb_unit_conversion` 1, a 5900 K black body of 127 500 lux outside the
/// atmosphere); softness 1 is the real sun's shadow edge, larger is softer, 0 hard; the
/// soft shadows take `samples` shadow rays (0: none soft).
fn physical_sun(light: &Light, params: &[mi::ast::Param]) -> Result<Emission, String> {
    if light.kind != scene::LightKind::Directional {
        return Err(format!(
            "light '{}': mia_physicalsun works on directional lights only; the light is left out",
            light.name
        ));
    }
    let d = mia::sun::PhysicalSun::default();
    let scalar = |name: &str, default: f32| scalar_param(params, name).map_or(default, |v| v as f32);
    let sun = mia::sun::PhysicalSun {
        on: scalar("on", 1.0) != 0.0,
        multiplier: scalar("multiplier", d.multiplier),
        rgb_unit_conversion: match color_param(params, "rgb_unit_conversion") {
            Some(Ok(c)) => c,
            _ => d.rgb_unit_conversion,
        },
        haze: scalar("haze", d.haze),
        redblueshift: scalar("redblueshift", d.redblueshift),
        saturation: scalar("saturation", d.saturation),
        horizon_height: scalar("horizon_height", d.horizon_height),
        shadow_softness: scalar("shadow_softness", d.shadow_softness),
        samples: scalar("samples", d.samples as f32) as i32,
        y_is_up: scalar("y_is_up", 0.0) != 0.0,
        illuminance_mode: scalar("illuminance_mode", 0.0) as i32,
        direct_normal_illuminance: scalar("direct_normal_illuminance", d.direct_normal_illuminance),
    };
    let to_sun = -light.direction.as_vec3a().normalize_or_zero();
    let c = sun.color(to_sun).unwrap_or(Rgb::ZERO) * std::f32::consts::PI;
    let cone = sun.shadow_cone();
    Ok(Emission {
        power: Power::Sun { irradiance: c, angular_radius: if sun.samples > 1 && cone > 0.0 { cone } else { 0.0 } },
        spot_exponent: None,
        cone: None,
        distribution: None,
        maya_spot: None,
    })
}
