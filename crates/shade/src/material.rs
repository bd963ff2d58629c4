//! Surface materials for the path integrator, translated from the scene's materials.
//!
//! Each material becomes a [`SurfaceModel`] — a BSDF family with constant parameters — and
//! an emission:
//! - mira's `unified_material` shader: the unified material with its own parameters;
//! - MDL (`::nvidia::core_definitions`): `flex_material` and `flex_material_v2`, `metal`,
//!   `plastic`, `thin_glass` and `thick_glass` become unified materials; `diffuse` an
//!   Oren–Nayar surface; `add_emission` its base material plus emission in MDL's units;
//! - `mia_material` and `mia_material_x`: [`crate::mia::bsdf::MiaBsdf`], whose layer
//!   weights come from the author's curve and conservation at each viewing angle;
//! - the mental ray illumination shaders (`mib_illum_*`) their `diffuse` colour (Lambert).
//!
//! Anything else — and parameters connected to shaders, which need the shader graph — is
//! rendered as a grey diffuse surface or with the parameter's default, with a warning
//! naming what was not understood.

use mi::ast::{Num, Param, ShaderItem, Value};
use scene::{Library, Material, MaterialKind};

use crate::bsdf::microfacet::Ggx;
use crate::bsdf::{Bsdf, Lambert, OrenNayar, Unified, UnifiedParams};
use crate::mia::bsdf::{anisotropic_roughness, gloss_to_roughness, MiaBsdf};
use crate::mia::params::Mia;
use crate::Rgb;

/// The scattering model of a surface, with constant parameters.
#[derive(Clone, Debug, PartialEq)]
pub enum SurfaceModel {
    /// Lambertian reflection of the material's `diffuse` colour.
    Lambert,
    /// Oren–Nayar reflection of the `diffuse` colour with roughness σ (radians).
    OrenNayar(f32),
    /// The unified material (built once: its constants, such as the Fresnel average, are
    /// not recomputed per hit).
    Unified(Box<Unified>),
    /// `mia_material`: its parameters and `refr_gloss`.
    Mia(Box<(Mia, f32)>),
}

/// A surface's scattering and emission.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceMaterial {
    /// The material's name.
    pub name: String,
    /// The diffuse colour (the Lambert and Oren–Nayar models' reflectance, and the colour
    /// the classic engine's stand-in shades with).
    pub diffuse: Rgb,
    /// Emitted radiance (W·m⁻²·sr⁻¹ in scene units), both sides.
    pub emission: Rgb,
    /// How the surface scatters.
    pub model: SurfaceModel,
}

impl SurfaceMaterial {
    /// A grey diffuse surface (the fallback for what is not understood).
    pub fn grey(name: &str) -> SurfaceMaterial {
        SurfaceMaterial::lambert(name, Rgb::splat(0.5))
    }

    /// A Lambertian surface of reflectance `diffuse`.
    pub fn lambert(name: &str, diffuse: Rgb) -> SurfaceMaterial {
        SurfaceMaterial { name: name.to_string(), diffuse, emission: Rgb::ZERO, model: SurfaceModel::Lambert }
    }

    /// The BSDF at a shading point seen from `wo` (local shading frame: some layer
    /// weights depend on the viewing angle).
    pub fn bsdf(&self, wo: glam::Vec3A) -> Bsdf {
        match &self.model {
            SurfaceModel::Lambert => Bsdf::Lambert(Lambert { albedo: self.diffuse }),
            SurfaceModel::OrenNayar(sigma) => Bsdf::OrenNayar(OrenNayar::new(self.diffuse, *sigma)),
            SurfaceModel::Unified(u) => Bsdf::Unified(**u),
            SurfaceModel::Mia(m) => {
                let (mia, refr_gloss) = &**m;
                let w = mia.weights(wo.z.abs(), true);
                let (ax, ay) = anisotropic_roughness(gloss_to_roughness(mia.refl_gloss), mia.anisotropy);
                Bsdf::Mia(MiaBsdf {
                    diffuse: OrenNayar::new(w.diffuse, mia.roughness),
                    reflect: w.reflect,
                    reflect_ggx: Ggx { alpha_x: ax, alpha_y: ay },
                    transmit: w.refract,
                    transmit_ggx: Ggx::isotropic(gloss_to_roughness(*refr_gloss)),
                    eta: mia.ior.max(1e-3),
                    thin: mia.thin_walled,
                    transl: w.transl,
                })
            }
        }
    }

    /// Whether light can enter the surface (then its two sides differ: the path tracer
    /// keeps the geometric orientation instead of facing the normal towards the ray).
    pub fn has_inside(&self) -> bool {
        match &self.model {
            SurfaceModel::Unified(u) => u.params().spec_trans > 0.0 && !u.params().thin,
            SurfaceModel::Mia(m) => m.0.transparency > 0.0 && !m.0.thin_walled,
            _ => false,
        }
    }
}

/// The declaration name without an MDL signature (`mdl::base::x(float,…)` → `mdl::base::x`).
pub fn declaration_name(decl: &str) -> &str {
    decl.split('(').next().unwrap_or(decl)
}

/// A constant colour parameter (`"p" r g b [a]` or a single grey value).
pub fn color_param(params: &[Param], name: &str) -> Option<Result<Rgb, String>> {
    let p = params.iter().rev().find(|p| p.name.text == name)?;
    Some(match &p.value {
        Value::Tuple(v) if v.len() >= 3 => {
            Ok(Rgb::new(v[0].as_f64() as f32, v[1].as_f64() as f32, v[2].as_f64() as f32))
        }
        Value::Num(n) => Ok(Rgb::splat(n.as_f64() as f32)),
        Value::Connect(c) => Err(format!("'{name}' is connected to '{}'", c.text)),
        _ => Err(format!("'{name}' is not a colour")),
    })
}

/// A constant scalar parameter.
pub fn scalar_param(params: &[Param], name: &str) -> Option<f64> {
    params.iter().rev().find(|p| p.name.text == name).and_then(|p| match &p.value {
        Value::Num(n) => Some(n.as_f64()),
        Value::Tuple(v) => v.first().map(|n: &Num| n.as_f64()),
        Value::Bool(b) => Some(f64::from(u8::from(*b))),
        _ => None,
    })
}

/// A string parameter.
pub fn string_param<'a>(params: &'a [Param], name: &str) -> Option<&'a str> {
    params.iter().rev().find(|p| p.name.text == name).and_then(|p| match &p.value {
        Value::Str(s) => Some(s.text.as_str()),
        _ => None,
    })
}

/// The declaration and parameters of a shader list's first shader (following one `= "x"`).
pub fn first_call<'a>(items: &'a [ShaderItem], lib: &'a Library) -> Option<(&'a str, &'a [Param])> {
    match items.first()? {
        ShaderItem::Call { decl, params, .. } => Some((decl.text.as_str(), params.as_slice())),
        ShaderItem::Ref(name) => {
            let def = lib.shaders.get(&name.text)?;
            match def.list.0.first()? {
                ShaderItem::Call { decl, params, .. } => Some((decl.text.as_str(), params.as_slice())),
                _ => None,
            }
        }
        ShaderItem::Define { list, .. } => match list.0.first()? {
            ShaderItem::Call { decl, params, .. } => Some((decl.text.as_str(), params.as_slice())),
            _ => None,
        },
    }
}

/// Translates a scene material; the strings are warnings about what was approximated.
pub fn translate(m: &Material, lib: &Library) -> (SurfaceMaterial, Vec<String>) {
    let mut warnings = Vec::new();
    let call = match &m.kind {
        MaterialKind::Shader(def) => first_call(&def.list.0, lib),
        MaterialKind::Material(defs) => defs.iter().rev().find_map(|d| d.shaders.as_ref()).and_then(|l| {
            // In a shader list the last shader's result is the material's; a passthrough
            // bump shader comes first.
            let illum = l.0.iter().rev().find_map(|item| first_call(std::slice::from_ref(item), lib));
            illum.or_else(|| first_call(&l.0, lib))
        }),
    };
    let Some((decl, params)) = call else {
        warnings.push(format!("material '{}' has no shader mira understands; rendered grey", m.name));
        return (SurfaceMaterial::grey(&m.name), warnings);
    };
    let mut reader = Reader { material: &m.name, warnings: &mut warnings };
    let surface = reader.call(decl, params, lib, 0);
    (surface, warnings)
}

const CORE: &str = "mdl::nvidia::core_definitions::";

/// Reads constant parameters, warning about what it cannot read.
struct Reader<'a> {
    material: &'a str,
    warnings: &'a mut Vec<String>,
}

impl Reader<'_> {
    fn color(&mut self, params: &[Param], name: &str, default: Rgb) -> Rgb {
        match color_param(params, name) {
            None => default,
            Some(Ok(c)) => c,
            Some(Err(why)) => {
                self.warnings.push(format!("material '{}': {why}; its default is used", self.material));
                default
            }
        }
    }

    fn scalar(&mut self, params: &[Param], name: &str, default: f32) -> f32 {
        if let Some(p) = params.iter().rev().find(|p| p.name.text == name) {
            if let Value::Connect(c) = &p.value {
                self.warnings.push(format!(
                    "material '{}': '{name}' is connected to '{}'; its default is used",
                    self.material, c.text
                ));
                return default;
            }
        }
        scalar_param(params, name).map_or(default, |v| v as f32)
    }

    fn flag(&mut self, params: &[Param], name: &str, default: bool) -> bool {
        self.scalar(params, name, f32::from(u8::from(default))) != 0.0
    }

    /// `mia_material`'s constant parameters (declaration defaults where unset) and its
    /// `refr_gloss`.
    fn mia(&mut self, decl: &str, params: &[Param]) -> (Mia, f32) {
        let decls = crate::model::decl::Decls::default();
        let declared = decls.get(decl);
        let default = |name: &str| -> Vec<f32> {
            let value = declared.as_ref().and_then(|d| d.param(name).and_then(|i| d.params[i].default.clone()));
            match value {
                Some(Value::Num(n)) => vec![n.as_f64() as f32],
                Some(Value::Bool(b)) => vec![f32::from(u8::from(b))],
                Some(Value::Tuple(v)) if !v.is_empty() => v.iter().map(|n| n.as_f64() as f32).collect(),
                _ => vec![0.0],
            }
        };
        let mut s = |name: &str| {
            let d = default(name)[0];
            self.scalar(params, name, d)
        };
        let (weight, roughness, reflectivity, gloss) =
            (s("diffuse_weight"), s("diffuse_roughness"), s("reflectivity"), s("refl_gloss"));
        let (metal, transparency, refr_gloss, ior) =
            (s("refl_is_metal"), s("transparency"), s("refr_gloss"), s("refr_ior"));
        let (translucency, transl_weight, anisotropy) =
            (s("refr_translucency"), s("refr_trans_weight"), s("anisotropy"));
        let (fresnel, r0, r90, curve) =
            (s("brdf_fresnel"), s("brdf_0_degree_refl"), s("brdf_90_degree_refl"), s("brdf_curve"));
        let (conserve, balance, thin) = (s("brdf_conserve_energy"), s("hl_vs_refl_balance"), s("thin_walled"));
        let rotation = s("anisotropy_rotation");
        let mut c = |name: &str| {
            let d = default(name);
            let d = Rgb::new(d[0], *d.get(1).unwrap_or(&d[0]), *d.get(2).unwrap_or(&d[0]));
            self.color(params, name, d)
        };
        let (diffuse, refl_color, refr_color, transl_color) =
            (c("diffuse"), c("refl_color"), c("refr_color"), c("refr_trans_color"));
        let mia = Mia {
            diffuse: diffuse * weight,
            roughness,
            reflectivity,
            refl_color,
            refl_gloss: gloss,
            metal: metal != 0.0,
            transparency,
            refr_color,
            ior,
            transl: if translucency != 0.0 { transl_color * transl_weight } else { Rgb::ZERO },
            anisotropy,
            rotation,
            fresnel: fresnel != 0.0,
            curve: (r0, r90, curve),
            conserve: conserve != 0.0,
            hl_balance: balance,
            thin_walled: thin != 0.0,
        };
        (mia, refr_gloss)
    }

    /// The surface of shader `decl` with `params`; `depth` counts nested `base` materials.
    fn call(&mut self, decl: &str, params: &[Param], lib: &Library, depth: u32) -> SurfaceMaterial {
        let name = self.material;
        let decl = declaration_name(decl);
        let unified = |p: UnifiedParams| SurfaceMaterial {
            name: name.to_string(),
            diffuse: p.base_color,
            emission: Rgb::ZERO,
            model: SurfaceModel::Unified(Box::new(Unified::new(&p))),
        };
        let mdl = decl.strip_prefix(CORE);
        match (decl, mdl) {
            ("unified_material", _) => {
                let d = UnifiedParams::default();
                let normal = params.iter().any(|p| p.name.text == "normal" || p.name.text == "bump");
                if normal {
                    self.warnings.push(format!(
                        "material '{name}': unified_material's normal/bump input needs the shader graph; ignored by the path engine"
                    ));
                }
                let transmission = params.iter().any(|p| p.name.text == "transmission_color");
                let edge = params.iter().any(|p| p.name.text == "edge_tint");
                unified(UnifiedParams {
                    base_color: self.color(params, "base_color", d.base_color),
                    metallic: self.scalar(params, "metallic", d.metallic),
                    roughness: self.scalar(params, "roughness", d.roughness),
                    anisotropic: self.scalar(params, "anisotropic", d.anisotropic),
                    spec_trans: self.scalar(params, "spec_trans", d.spec_trans),
                    ior: self.scalar(params, "ior", d.ior),
                    specular: self.scalar(params, "specular", d.specular),
                    specular_tint: self.scalar(params, "specular_tint", d.specular_tint),
                    sheen: self.scalar(params, "sheen", d.sheen),
                    sheen_tint: self.scalar(params, "sheen_tint", d.sheen_tint),
                    clearcoat: self.scalar(params, "clearcoat", d.clearcoat),
                    clearcoat_gloss: self.scalar(params, "clearcoat_gloss", d.clearcoat_gloss),
                    thin: self.flag(params, "thin", d.thin),
                    transmission_color: transmission.then(|| self.color(params, "transmission_color", Rgb::ONE)),
                    edge_tint: edge.then(|| self.color(params, "edge_tint", Rgb::ONE)),
                })
            }
            (_, Some(m @ ("flex_material" | "flex_material_v2"))) => {
                let v2 = m == "flex_material_v2";
                let metallic = self.scalar(params, "is_metal", 0.0).clamp(0.0, 1.0);
                let base = self.color(params, "base_color", Rgb::splat(0.5));
                // The reflection layer's weight: the dielectric's `specular`, and a scale
                // on the metal's colour.
                let reflectivity = self.scalar(params, "reflectivity", 1.0).clamp(0.0, 1.0);
                let metal_base = base * reflectivity;
                let mut surface = unified(UnifiedParams {
                    base_color: base * (1.0 - metallic) + metal_base * metallic,
                    metallic,
                    roughness: self.scalar(params, "reflection_roughness", if v2 { 0.3 } else { 0.1 }),
                    anisotropic: self.scalar(params, "anisotropy", 0.0),
                    spec_trans: self.scalar(params, "transparency", 0.0),
                    ior: self.scalar(params, "ior", 1.5),
                    specular: reflectivity,
                    thin: self.flag(params, "thin_walled", false),
                    transmission_color: Some(self.color(params, "transmission_color", Rgb::ONE)),
                    ..Default::default()
                });
                surface.diffuse = base;
                // Without reflection, transparency or metal the layers reduce to the
                // diffuse base (Oren–Nayar, Lambert at roughness 0): cheaper, and exactly so.
                if reflectivity == 0.0 && metallic == 0.0 && self.scalar(params, "transparency", 0.0) == 0.0 {
                    let sigma = self.scalar(params, "diffuse_roughness", 0.0);
                    surface.model = if sigma > 0.0 { SurfaceModel::OrenNayar(sigma) } else { SurfaceModel::Lambert };
                }
                surface
            }
            (_, Some("diffuse")) => {
                let diffuse = self.color(params, "diffuse_color", Rgb::splat(0.8)).clamp(Rgb::ZERO, Rgb::ONE);
                let sigma = self.scalar(params, "roughness", 0.0);
                SurfaceMaterial {
                    model: if sigma > 0.0 { SurfaceModel::OrenNayar(sigma) } else { SurfaceModel::Lambert },
                    ..SurfaceMaterial::lambert(name, diffuse)
                }
            }
            (_, Some("metal")) => {
                let color = self.color(params, "metal_color", Rgb::splat(0.9));
                let weight = self.scalar(params, "glossy_weight", 0.9);
                unified(UnifiedParams {
                    base_color: color * weight,
                    metallic: 1.0,
                    roughness: self.scalar(params, "roughness", 0.05),
                    ..Default::default()
                })
            }
            (_, Some("plastic")) => unified(UnifiedParams {
                base_color: self.color(params, "diffuse_color", Rgb::splat(0.5)),
                roughness: self.scalar(params, "roughness", 0.25),
                ior: self.scalar(params, "ior", 1.4),
                ..Default::default()
            }),
            (_, Some(g @ ("thin_glass" | "thick_glass"))) => {
                let thin = g == "thin_glass";
                let glass = self.color(params, "glass_color", Rgb::splat(0.95));
                let transmission = if thin { Rgb::ONE } else { self.color(params, "transmission_color", Rgb::ONE) };
                unified(UnifiedParams {
                    base_color: glass,
                    roughness: self.scalar(params, "roughness", 0.0),
                    ior: self.scalar(params, "ior", 1.4),
                    spec_trans: 1.0,
                    thin,
                    transmission_color: Some(glass * transmission),
                    ..Default::default()
                })
            }
            (_, Some("add_emission")) => {
                let mut surface = match params.iter().rev().find(|p| p.name.text == "base").map(|p| &p.value) {
                    Some(Value::Connect(target)) if depth < 8 => {
                        match lib.shaders.get(&target.text).and_then(|d| first_call(&d.list.0, lib)) {
                            Some((decl, inner)) => self.call(decl, inner, lib, depth + 1),
                            None => {
                                self.warnings.push(format!(
                                    "material '{name}': add_emission's base '{}' is not a shader mira knows; black",
                                    target.text
                                ));
                                SurfaceMaterial::lambert(name, Rgb::ZERO)
                            }
                        }
                    }
                    // MDL's default base is diffuse(black).
                    _ => SurfaceMaterial::lambert(name, Rgb::ZERO),
                };
                let tint = self.color(params, "tint", Rgb::ONE);
                let amount = self.scalar(params, "intensity", 1000.0) * self.scalar(params, "unit_scale", 1.0);
                let radiance = match string_param(params, "unit").unwrap_or("lumen_m2") {
                    "nit" => amount,
                    "lumen_m2" => amount / std::f32::consts::PI,
                    other => {
                        self.warnings.push(format!(
                            "material '{name}': add_emission in '{other}' needs the emitter's area; read as lumen_m2"
                        ));
                        amount / std::f32::consts::PI
                    }
                };
                surface.emission = tint * radiance;
                surface
            }
            (m @ ("mia_material" | "mia_material_x" | "mia_material_x_passes"), _) => {
                let mia = self.mia(m, params);
                SurfaceMaterial {
                    name: name.to_string(),
                    diffuse: mia.0.diffuse,
                    emission: Rgb::ZERO,
                    model: SurfaceModel::Mia(Box::new(mia)),
                }
            }
            (
                "mib_illum_lambert"
                | "mib_illum_phong"
                | "mib_illum_blinn"
                | "mib_illum_cooktorr"
                | "mib_illum_ward"
                | "mib_illum_ward_deriv"
                | "mib_illum_hair",
                _,
            ) => {
                let diffuse = self.color(params, "diffuse", Rgb::ZERO).clamp(Rgb::ZERO, Rgb::ONE);
                SurfaceMaterial::lambert(name, diffuse)
            }
            (other, _) => {
                self.warnings.push(format!(
                    "material '{name}': shader '{other}' is not supported by the path integrator yet; rendered grey"
                ));
                SurfaceMaterial::grey(name)
            }
        }
    }
}
