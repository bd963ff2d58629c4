//! Lowering an evaluated `material` struct to a path-engine [`SurfaceMaterial`]: the BSDF
//! tree onto mira's BSDF families, the emission to radiance, `thin_walled`, `ior` and the
//! cutout opacity read.
//!
//! The families used are exact for what they cover:
//! - any tree of diffuse reflection lobes under mixes, tints and weighted layers is one
//!   Lambert (or Oren–Nayar) lobe whose albedo is the weighted sum of their tints (a mix
//!   of Lambert lobes is a Lambert lobe);
//! - a glossy or specular reflection layered over such a diffuse base by `fresnel_layer`
//!   (a dielectric coat) is the unified material's dielectric: specular weight, GGX
//!   roughness √α, index of refraction;
//! - a constant-weight sum (mixes, tints, weighted layers) of diffuse reflection, one
//!   glossy or specular reflection distribution and diffuse transmission is
//!   [`SurfaceModel::Lobes`]: Oren–Nayar, GGX reflection weighted by its tint (MDL's glossy
//!   BSDFs have no Fresnel term), Lambert translucency;
//! - a specular or glossy `scatter_reflect_transmit` lobe with the material's `ior` is the
//!   unified material's glass, thin when the material is `thin_walled`.
//!
//! Other combinations are approximated by their diffuse part, with a warning naming the
//! construct.

use bsdf::microfacet::Ggx;
use bsdf::{MiaBsdf, OrenNayar, Rgb, Unified, UnifiedParams};

use super::value::{Df, Edf, ScatterMode, Value};
use crate::{SurfaceMaterial, SurfaceModel};

/// The diffuse part of a tree: total albedo and mean Oren–Nayar σ (weighted by albedo);
/// `None` if the tree has anything else.
fn diffuse_only(df: &Df) -> Option<(Rgb, f32)> {
    match df {
        Df::Black => Some((Rgb::ZERO, 0.0)),
        Df::Diffuse { tint, roughness } => Some((*tint, *roughness)),
        Df::Mix(parts) => {
            let (mut albedo, mut sigma, mut weight) = (Rgb::ZERO, 0.0, 0.0);
            for (w, d) in parts {
                let (a, s) = diffuse_only(d)?;
                let part = *w * a;
                albedo += part;
                sigma += s * bsdf::color::luminance(part);
                weight += bsdf::color::luminance(part);
            }
            Some((albedo, if weight > 0.0 { sigma / weight } else { 0.0 }))
        }
        Df::Layer { weight, fresnel_ior: None, layer, base } => {
            let mix = Df::Mix(vec![(*weight, (**layer).clone()), (Rgb::ONE - *weight, (**base).clone())]);
            diffuse_only(&mix)
        }
        _ => None,
    }
}

/// The weights of a tree's lobes when it is a constant-weight sum of diffuse reflection,
/// one glossy reflection distribution and diffuse transmission.
#[derive(Default)]
struct LobeSum {
    diffuse: Rgb,
    /// Σ σ · luminance of the diffuse parts (σ averaged by the diffuse luminance).
    sigma: f32,
    glossy: Rgb,
    alpha: Option<(f32, f32)>,
    transl: Rgb,
}

/// Adds `df` scaled by `scale` to `sum`; false if it is not such a sum.
fn add_lobes(df: &Df, scale: Rgb, sum: &mut LobeSum) -> bool {
    match df {
        Df::Black => true,
        Df::Diffuse { tint, roughness } => {
            sum.diffuse += scale * *tint;
            sum.sigma += roughness * bsdf::color::luminance(scale * *tint);
            true
        }
        Df::DiffuseTransmission(tint) => {
            sum.transl += scale * *tint;
            true
        }
        Df::Specular { tint, mode: ScatterMode::Reflect } => add_glossy(*tint, (0.0, 0.0), scale, sum),
        Df::Glossy { tint, roughness, mode: ScatterMode::Reflect } => add_glossy(*tint, *roughness, scale, sum),
        Df::Mix(parts) => parts.iter().all(|(w, d)| add_lobes(d, scale * *w, sum)),
        Df::Layer { weight, fresnel_ior: None, layer, base } => {
            add_lobes(layer, scale * *weight, sum) && add_lobes(base, scale * (Rgb::ONE - *weight), sum)
        }
        _ => false,
    }
}

fn add_glossy(tint: Rgb, alpha: (f32, f32), scale: Rgb, sum: &mut LobeSum) -> bool {
    if sum.alpha.is_some_and(|a| a != alpha) {
        return false;
    }
    sum.alpha = Some(alpha);
    sum.glossy += scale * tint;
    true
}

/// The tree as a [`SurfaceModel::Lobes`] material, if it is a constant-weight sum of
/// diffuse reflection, one glossy reflection and diffuse transmission.
fn lobes(name: &str, df: &Df) -> Option<SurfaceMaterial> {
    let mut sum = LobeSum::default();
    if !add_lobes(df, Rgb::ONE, &mut sum) {
        return None;
    }
    let lum = bsdf::color::luminance(sum.diffuse);
    let sigma = if lum > 0.0 { sum.sigma / lum } else { 0.0 };
    let (ax, ay) = sum.alpha.unwrap_or((0.0, 0.0));
    let clamp = |c: Rgb| c.clamp(Rgb::ZERO, Rgb::ONE);
    let lobes = MiaBsdf {
        diffuse: OrenNayar::new(clamp(sum.diffuse), sigma),
        reflect: clamp(sum.glossy),
        reflect_ggx: Ggx { alpha_x: ax, alpha_y: ay },
        transmit: Rgb::ZERO,
        transmit_ggx: Ggx::isotropic(0.0),
        eta: 1.0,
        thin: true,
        transl: clamp(sum.transl),
    };
    Some(SurfaceMaterial {
        model: SurfaceModel::Lobes(Box::new(lobes)),
        ..SurfaceMaterial::lambert(name, clamp(sum.diffuse))
    })
}

/// The albedo of a tree's diffuse reflection lobes, ignoring the rest (the approximation of
/// what cannot be lowered).
fn diffuse_part(df: &Df) -> Rgb {
    match df {
        Df::Diffuse { tint, .. } => *tint,
        Df::Mix(parts) => parts.iter().fold(Rgb::ZERO, |s, (w, d)| s + *w * diffuse_part(d)),
        Df::Layer { weight, fresnel_ior: None, layer, base } => {
            *weight * diffuse_part(layer) + (Rgb::ONE - *weight) * diffuse_part(base)
        }
        Df::Layer { base, .. } => diffuse_part(base),
        _ => Rgb::ZERO,
    }
}

/// A glossy or specular lobe as (tint, α, mode), looking through tints.
fn glossy(df: &Df) -> Option<(Rgb, f32, ScatterMode)> {
    match df {
        Df::Specular { tint, mode } => Some((*tint, 0.0, *mode)),
        Df::Glossy { tint, roughness: (u, v), mode } => Some((*tint, (u * v).sqrt(), *mode)),
        Df::Mix(parts) if parts.len() == 1 => glossy(&parts[0].1).map(|(t, a, m)| (t * parts[0].0, a, m)),
        _ => None,
    }
}

/// The surface of an evaluated `material` value named `name` (warnings appended).
pub fn surface(name: &str, material: &Value, warnings: &mut Vec<String>) -> SurfaceMaterial {
    let field = |v: &Value, f: &str| v.field(f).cloned();
    let thin = matches!(field(material, "thin_walled"), Some(Value::Bool(true)));
    let ior = field(material, "ior").and_then(|v| v.color()).map_or(1.5, |c| (c.x + c.y + c.z) / 3.0);
    let surf = field(material, "surface");
    let scattering = match surf.as_ref().and_then(|s| s.field("scattering")) {
        Some(Value::Bsdf(d)) => d.clone(),
        _ => Df::Black,
    };
    let mut out = lower_bsdf(name, &scattering, ior, thin, warnings);
    if let Some(emission) = surf.as_ref().and_then(|s| s.field("emission")) {
        let edf = emission.field("emission");
        let intensity = emission.field("intensity").and_then(Value::color).unwrap_or(Rgb::ZERO);
        let power = matches!(emission.field("mode"), Some(Value::Enum(_, 1)));
        match edf {
            Some(Value::Edf(Edf::Diffuse)) => {
                // Lambertian: radiant exitance E gives radiance E/π; a power Φ over the
                // whole surface gives Φ/π per area, divided by the area once it is known.
                out.emission = intensity / std::f32::consts::PI;
                out.emission_over_area = power;
            }
            Some(Value::Edf(Edf::Black)) | None => {}
            Some(_) => warnings.push(format!("material '{name}': this edf is not compiled yet; no emission")),
        }
    }
    if let Some(geometry) = field(material, "geometry") {
        match geometry.field("cutout_opacity").and_then(Value::float) {
            Some(o) => out.opacity = o.clamp(0.0, 1.0) as f32,
            None => warnings.push(format!(
                "material '{name}': its cutout_opacity depends on the shading point (not compiled yet); opaque"
            )),
        }
        match geometry.field("normal") {
            Some(Value::State(s)) if s == "normal" => {}
            _ => warnings.push(format!(
                "material '{name}': its geometry normal is not compiled yet; the shading normal is used"
            )),
        }
    }
    if let Some(Value::Struct(_, vol)) = field(material, "volume") {
        let absorbs = vol.iter().any(|(f, v)| f.ends_with("coefficient") && v.color().is_some_and(|c| c != Rgb::ZERO));
        if absorbs {
            warnings.push(format!("material '{name}': volume absorption and scattering are not compiled yet; ignored"));
        }
    }
    out
}

fn lower_bsdf(name: &str, df: &Df, ior: f32, thin: bool, warnings: &mut Vec<String>) -> SurfaceMaterial {
    let unified = |p: UnifiedParams| SurfaceMaterial {
        diffuse: p.base_color,
        model: SurfaceModel::Unified(Box::new(Unified::new(&p))),
        ..SurfaceMaterial::lambert(name, Rgb::ZERO)
    };
    if let Some((albedo, sigma)) = diffuse_only(df) {
        let albedo = albedo.clamp(Rgb::ZERO, Rgb::ONE);
        let model = if sigma > 0.0 { SurfaceModel::OrenNayar(sigma) } else { SurfaceModel::Lambert };
        return SurfaceMaterial { model, ..SurfaceMaterial::lambert(name, albedo) };
    }
    if let Some((tint, alpha, mode)) = glossy(df) {
        return match mode {
            ScatterMode::Reflect => lobes(name, df).unwrap_or_else(|| {
                unified(UnifiedParams {
                    base_color: tint,
                    metallic: 1.0,
                    roughness: alpha.sqrt(),
                    ..Default::default()
                })
            }),
            ScatterMode::ReflectTransmit | ScatterMode::Transmit => {
                if mode == ScatterMode::Transmit {
                    warnings.push(format!(
                        "material '{name}': a transmit-only lobe is rendered as glass that also reflects"
                    ));
                }
                unified(UnifiedParams {
                    base_color: Rgb::ONE,
                    roughness: alpha.sqrt(),
                    ior: ior.max(1e-3),
                    spec_trans: 1.0,
                    thin,
                    transmission_color: Some(tint.clamp(Rgb::ZERO, Rgb::ONE)),
                    ..Default::default()
                })
            }
        };
    }
    if let Df::Layer { weight, fresnel_ior: Some(coat_ior), layer, base } = df {
        if let (Some((tint, alpha, ScatterMode::Reflect)), Some((albedo, _))) = (glossy(layer), diffuse_only(base)) {
            if tint != Rgb::ONE {
                warnings.push(format!("material '{name}': the coat's tint is not compiled yet; a white coat is used"));
            }
            return unified(UnifiedParams {
                base_color: albedo.clamp(Rgb::ZERO, Rgb::ONE),
                roughness: alpha.sqrt(),
                ior: coat_ior.max(1e-3),
                specular: bsdf::color::luminance(*weight).clamp(0.0, 1.0),
                ..Default::default()
            });
        }
    }
    if let Some(surface) = lobes(name, df) {
        return surface;
    }
    let albedo = diffuse_part(df).clamp(Rgb::ZERO, Rgb::ONE);
    warnings.push(format!(
        "material '{name}': its bsdf ({}) has no path-engine form yet; rendered as its diffuse part {:.3} {:.3} {:.3}",
        describe(df),
        albedo.x,
        albedo.y,
        albedo.z
    ));
    SurfaceMaterial::lambert(name, albedo)
}

/// The constructs of a tree, for messages (`fresnel_layer(diffuse_transmission_bsdf, …)`).
pub fn describe(df: &Df) -> String {
    match df {
        Df::Black => "bsdf()".into(),
        Df::Diffuse { .. } => "diffuse_reflection_bsdf".into(),
        Df::DiffuseTransmission(_) => "diffuse_transmission_bsdf".into(),
        Df::Specular { .. } => "specular_bsdf".into(),
        Df::Glossy { .. } => "glossy bsdf".into(),
        Df::Mix(parts) => format!("mix({})", parts.iter().map(|(_, d)| describe(d)).collect::<Vec<_>>().join(", ")),
        Df::Layer { fresnel_ior, layer, base, .. } => format!(
            "{}({}, {})",
            if fresnel_ior.is_some() { "fresnel_layer" } else { "weighted_layer" },
            describe(layer),
            describe(base)
        ),
    }
}
