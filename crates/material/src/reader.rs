//! Reading a material shader's parameters into a [`SurfaceMaterial`]: the mapping of
//! each supported shader (MDL materials, `unified_material`, `mia_material`, the
//! `mib_illum_*` shaders) onto mira's BSDFs.
//!
//! Constants are read here once. A parameter connected to a shader that the scene's graph
//! holds becomes a [`Binding`] evaluated at each hit; without a graph, or for parameters
//! whose connection cannot be followed, the default is used and a warning says so.

use std::sync::Arc;

use mi::ast::{Param, Value};
use scene::Library;

use super::inputs::{Binding, Target, Varying};
use super::{color_param, declaration_name, first_call, scalar_param, string_param, SurfaceMaterial, SurfaceModel};
use bsdf::Rgb;
use bsdf::{Unified, UnifiedParams};
use mia::params::Mia;
use shader::{Graph, NodeId};

mod mib_glossy;
mod mib_glossy_refraction;

const CORE: &str = "mdl::nvidia::core_definitions::";

/// Reads constant parameters and records the connected ones, warning about what it
/// cannot read.
pub(super) struct Reader<'a> {
    material: &'a str,
    warnings: &'a mut Vec<String>,
    graph: Option<&'a Graph>,
    bindings: Vec<Binding>,
    /// The whole shader node is evaluated per hit (connections need no binding).
    node_evaluated: bool,
}

/// A resolved connection: the node and the member of its result.
type Source = (NodeId, Option<Arc<str>>);

/// The node and member a connection `"shader"` or `"shader.member"` names in `graph`.
pub(super) fn resolve(graph: &Graph, target: &str) -> Option<Source> {
    if let Some(&n) = graph.named.get(target) {
        return Some((n, None));
    }
    let (head, member) = target.rsplit_once('.')?;
    graph.named.get(head).map(|&n| (n, Some(Arc::from(member))))
}

impl<'a> Reader<'a> {
    /// A reader for material `material`, resolving connections in `graph`.
    pub(super) fn new(material: &'a str, warnings: &'a mut Vec<String>, graph: Option<&'a Graph>) -> Reader<'a> {
        Reader { material, warnings, graph, bindings: Vec::new(), node_evaluated: false }
    }

    /// The material's name.
    fn material(&self) -> &'a str {
        self.material
    }

    /// Records a warning about the material (prefixed by its name).
    fn warn(&mut self, message: String) {
        self.warnings.push(format!("material '{}': {message}", self.material));
    }

    /// What is varying per hit: the bindings recorded.
    pub(super) fn finish(self) -> Varying {
        if self.bindings.is_empty() {
            Varying::Constant
        } else {
            Varying::Bindings(self.bindings)
        }
    }

    /// The connection of parameter `name`, if it is connected: (target text, resolved).
    fn connection(&self, params: &[Param], name: &str) -> Option<(String, Option<Source>)> {
        let p = params.iter().rev().find(|p| p.name.text == name)?;
        match &p.value {
            Value::Connect(c) => Some((c.text.clone(), self.graph.and_then(|g| resolve(g, &c.text)))),
            _ => None,
        }
    }

    /// Records parameter `name` as driving `target` (scaled by `scale`) if it is connected;
    /// returns whether it is. Connections that cannot be followed are warned about.
    fn bind(&mut self, params: &[Param], name: &str, target: Option<(Target, f32)>) -> bool {
        let Some((text, resolved)) = self.connection(params, name) else { return false };
        match (resolved, target) {
            _ if self.node_evaluated => {}
            (Some((node, member)), Some((target, scale))) => {
                self.bindings.push(Binding { node, member, target, scale });
            }
            (Some(_), None) => self.warnings.push(format!(
                "material '{}': '{name}' is connected to '{text}', which the path engine does not follow for this parameter; its default is used",
                self.material
            )),
            (None, _) => self.warnings.push(format!(
                "material '{}': '{name}' is connected to '{text}'{}; its default is used",
                self.material,
                if self.graph.is_some() { ", which is not a shader mira knows" } else { "" }
            )),
        }
        true
    }

    /// A colour parameter driving `target`.
    fn color_to(&mut self, params: &[Param], name: &str, default: Rgb, target: Option<(Target, f32)>) -> Rgb {
        if self.bind(params, name, target) {
            return default;
        }
        match color_param(params, name) {
            None => default,
            Some(Ok(c)) => c,
            Some(Err(why)) => {
                self.warnings.push(format!("material '{}': {why}; its default is used", self.material));
                default
            }
        }
    }

    /// A colour parameter that is only read as a constant.
    fn color(&mut self, params: &[Param], name: &str, default: Rgb) -> Rgb {
        self.color_to(params, name, default, None)
    }

    /// A scalar parameter driving `target`.
    fn scalar_to(&mut self, params: &[Param], name: &str, default: f32, target: Option<(Target, f32)>) -> f32 {
        if self.bind(params, name, target) {
            return default;
        }
        scalar_param(params, name).map_or(default, |v| v as f32)
    }

    /// A scalar parameter that is only read as a constant.
    fn scalar(&mut self, params: &[Param], name: &str, default: f32) -> f32 {
        self.scalar_to(params, name, default, None)
    }

    /// A boolean parameter (a number: non-zero is on).
    fn flag(&mut self, params: &[Param], name: &str, default: bool) -> bool {
        self.scalar(params, name, f32::from(u8::from(default))) != 0.0
    }

    /// An MDL `normal` input (a float3 function such as a normal or bump map).
    fn normal(&mut self, params: &[Param]) {
        self.bind(params, "normal", Some((Target::Normal, 1.0)));
    }

    /// `mia_material`'s constant parameters (declaration defaults where unset) and its
    /// `refr_gloss`.
    fn mia(&mut self, decl: &str, params: &[Param]) -> (Mia, f32) {
        let decls = crate::registry().builtin_decls();
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
    pub(super) fn call(&mut self, decl: &str, params: &[Param], lib: &Library, depth: u32) -> SurfaceMaterial {
        let name = self.material;
        let decl = declaration_name(decl);
        let unified = |p: UnifiedParams| SurfaceMaterial {
            diffuse: p.base_color,
            model: SurfaceModel::Unified(Box::new(Unified::new(&p))),
            ..SurfaceMaterial::lambert(name, Rgb::ZERO)
        };
        let mdl = decl.strip_prefix(CORE);
        let base = |t: Target| Some((t, 1.0));
        match (decl, mdl) {
            ("unified_material", _) => {
                let d = UnifiedParams::default();
                if !self.bind(params, "normal", base(Target::Normal)) {
                    self.bind(params, "bump", base(Target::Bump));
                }
                let transmission = params.iter().any(|p| p.name.text == "transmission_color");
                let edge = params.iter().any(|p| p.name.text == "edge_tint");
                let mut surface = unified(UnifiedParams {
                    base_color: self.color_to(params, "base_color", d.base_color, base(Target::BaseColor)),
                    metallic: self.scalar_to(params, "metallic", d.metallic, base(Target::Metallic)),
                    roughness: self.scalar_to(params, "roughness", d.roughness, base(Target::Roughness)),
                    anisotropic: self.scalar_to(params, "anisotropic", d.anisotropic, base(Target::Anisotropic)),
                    spec_trans: self.scalar_to(params, "spec_trans", d.spec_trans, base(Target::SpecTrans)),
                    ior: self.scalar_to(params, "ior", d.ior, base(Target::Ior)),
                    specular: self.scalar_to(params, "specular", d.specular, base(Target::Specular)),
                    specular_tint: self.scalar_to(params, "specular_tint", d.specular_tint, base(Target::SpecularTint)),
                    sheen: self.scalar_to(params, "sheen", d.sheen, base(Target::Sheen)),
                    sheen_tint: self.scalar_to(params, "sheen_tint", d.sheen_tint, base(Target::SheenTint)),
                    clearcoat: self.scalar_to(params, "clearcoat", d.clearcoat, base(Target::Clearcoat)),
                    clearcoat_gloss: self.scalar_to(
                        params,
                        "clearcoat_gloss",
                        d.clearcoat_gloss,
                        base(Target::ClearcoatGloss),
                    ),
                    thin: self.flag(params, "thin", d.thin),
                    transmission_color: transmission.then(|| {
                        self.color_to(params, "transmission_color", Rgb::ONE, base(Target::TransmissionColor))
                    }),
                    edge_tint: edge.then(|| self.color_to(params, "edge_tint", Rgb::ONE, base(Target::EdgeTint))),
                });
                surface.opacity = self.scalar_to(params, "opacity", 1.0, base(Target::Opacity));
                surface
            }
            (_, Some(m @ ("flex_material" | "flex_material_v2"))) => {
                let v2 = m == "flex_material_v2";
                self.normal(params);
                let metallic = self.scalar_to(params, "is_metal", 0.0, base(Target::Metallic)).clamp(0.0, 1.0);
                // The reflection layer's weight: the dielectric's `specular`, and a scale
                // on the metal's colour.
                let reflectivity = self.scalar_to(params, "reflectivity", 1.0, base(Target::Specular)).clamp(0.0, 1.0);
                let metal_scale = 1.0 - metallic + metallic * reflectivity;
                let colour = self.connection(params, "base_color").is_some();
                let base_color = self.color_to(params, "base_color", Rgb::splat(0.5), Some((Target::Diffuse, 1.0)));
                if colour {
                    self.bind(params, "base_color", Some((Target::BaseColor, metal_scale)));
                }
                let transparency = self.scalar_to(params, "transparency", 0.0, base(Target::SpecTrans));
                let mut surface = unified(UnifiedParams {
                    base_color: base_color * metal_scale,
                    metallic,
                    roughness: self.scalar_to(
                        params,
                        "reflection_roughness",
                        if v2 { 0.3 } else { 0.1 },
                        base(Target::Roughness),
                    ),
                    anisotropic: self.scalar_to(params, "anisotropy", 0.0, base(Target::Anisotropic)),
                    spec_trans: transparency,
                    ior: self.scalar_to(params, "ior", 1.5, base(Target::Ior)),
                    specular: reflectivity,
                    thin: self.flag(params, "thin_walled", false),
                    transmission_color: Some(self.color_to(
                        params,
                        "transmission_color",
                        Rgb::ONE,
                        base(Target::TransmissionColor),
                    )),
                    ..Default::default()
                });
                surface.diffuse = base_color;
                // The volume inside: absorption reaching `volume_color` after
                // `base_thickness`, σa = −ln(volume_color) / base_thickness.
                let volume_color = self.color(params, "volume_color", Rgb::ONE).clamp(Rgb::splat(1e-6), Rgb::ONE);
                let thickness = self.scalar(params, "base_thickness", 0.1);
                if volume_color != Rgb::ONE && thickness > 0.0 && surface.has_inside() {
                    let sigma_a = -Rgb::from(volume_color.to_array().map(f32::ln));
                    surface.medium = Some(bsdf::Medium::new(sigma_a / thickness, Rgb::ZERO, 0.0));
                }
                // Without reflection, transparency or metal the layers reduce to the
                // diffuse base (Oren–Nayar, Lambert at roughness 0): cheaper, and exactly so.
                let layered =
                    ["reflectivity", "is_metal", "transparency"].iter().any(|p| self.connection(params, p).is_some());
                if reflectivity == 0.0 && metallic == 0.0 && transparency == 0.0 && !layered {
                    let sigma = self.scalar_to(params, "diffuse_roughness", 0.0, base(Target::DiffuseRoughness));
                    surface.model = if sigma > 0.0 { SurfaceModel::OrenNayar(sigma) } else { SurfaceModel::Lambert };
                }
                surface
            }
            (_, Some("diffuse")) => {
                self.normal(params);
                let diffuse = self
                    .color_to(params, "diffuse_color", Rgb::splat(0.8), base(Target::Diffuse))
                    .clamp(Rgb::ZERO, Rgb::ONE);
                let sigma = self.scalar_to(params, "roughness", 0.0, base(Target::DiffuseRoughness));
                let rough = sigma > 0.0 || self.connection(params, "roughness").is_some();
                SurfaceMaterial {
                    model: if rough { SurfaceModel::OrenNayar(sigma) } else { SurfaceModel::Lambert },
                    ..SurfaceMaterial::lambert(name, diffuse)
                }
            }
            (_, Some("metal")) => {
                self.normal(params);
                let weight = self.scalar(params, "glossy_weight", 0.9);
                let color = self.color_to(params, "metal_color", Rgb::splat(0.9), Some((Target::BaseColor, weight)));
                unified(UnifiedParams {
                    base_color: color * weight,
                    metallic: 1.0,
                    roughness: self.scalar_to(params, "roughness", 0.05, base(Target::Roughness)),
                    ..Default::default()
                })
            }
            (_, Some("plastic")) => {
                self.normal(params);
                unified(UnifiedParams {
                    base_color: self.color_to(params, "diffuse_color", Rgb::splat(0.5), base(Target::BaseColor)),
                    roughness: self.scalar_to(params, "roughness", 0.25, base(Target::Roughness)),
                    ior: self.scalar_to(params, "ior", 1.4, base(Target::Ior)),
                    ..Default::default()
                })
            }
            (_, Some("thin_glass")) => {
                self.normal(params);
                let glass = self.color_to(params, "glass_color", Rgb::splat(0.95), base(Target::BaseColor));
                if self.connection(params, "glass_color").is_some() {
                    // The colour also tints transmission.
                    self.bind(params, "glass_color", base(Target::TransmissionColor));
                }
                unified(UnifiedParams {
                    base_color: glass,
                    roughness: self.scalar_to(params, "roughness", 0.0, base(Target::Roughness)),
                    ior: self.scalar_to(params, "ior", 1.4, base(Target::Ior)),
                    spec_trans: 1.0,
                    thin: true,
                    transmission_color: Some(glass),
                    ..Default::default()
                })
            }
            (_, Some("thick_glass")) => {
                // As core_definitions defines it: the surface transmits tinted by
                // `transmission_color` at every crossing, the glass body absorbs
                // σa = −ln(glass_color) / base_thickness (`glass_color` is reached after
                // `base_thickness` metres; none for a thickness ≤ 0).
                self.normal(params);
                let transmission =
                    self.color_to(params, "transmission_color", Rgb::ONE, base(Target::TransmissionColor));
                // A uniform parameter in MDL: only read as a constant (a connection is
                // warned about, its default used).
                let glass = self.color(params, "glass_color", Rgb::splat(0.95)).clamp(Rgb::splat(1e-6), Rgb::ONE);
                let thickness = self.scalar(params, "base_thickness", 0.1);
                let mut surface = unified(UnifiedParams {
                    base_color: glass,
                    roughness: self.scalar_to(params, "roughness", 0.0, base(Target::Roughness)),
                    ior: self.scalar_to(params, "ior", 1.4, base(Target::Ior)),
                    spec_trans: 1.0,
                    thin: false,
                    transmission_color: Some(transmission),
                    ..Default::default()
                });
                if glass != Rgb::ONE && thickness > 0.0 {
                    let sigma_a = -Rgb::from(glass.to_array().map(f32::ln));
                    surface.medium = Some(bsdf::Medium::new(sigma_a / thickness, Rgb::ZERO, 0.0));
                }
                surface
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
                let amount = self.scalar(params, "intensity", 1000.0) * self.scalar(params, "unit_scale", 1.0);
                // A Lambertian emitter of radiance L and area A has exitance πL, flux πLA
                // and peak intensity LA: `lumen` and `candela` give L·A, divided by the
                // material's area once the world knows it.
                let unit = string_param(params, "unit").unwrap_or("lumen_m2");
                let radiance = match unit {
                    "nit" | "candela" => amount,
                    "lumen_m2" | "lumen" => amount / std::f32::consts::PI,
                    other => {
                        self.warnings.push(format!(
                            "material '{name}': add_emission in unknown unit '{other}'; read as lumen_m2"
                        ));
                        amount / std::f32::consts::PI
                    }
                };
                surface.emission_over_area = matches!(unit, "lumen" | "candela");
                let tint = self.color_to(params, "tint", Rgb::ONE, Some((Target::Emission, radiance)));
                surface.emission = tint * radiance;
                surface
            }
            (m @ ("mia_material" | "mia_material_x" | "mia_material_x_passes"), _) => {
                // Connected parameters: the whole node is evaluated per hit when the graph
                // holds it (see `inputs::bind_material_shaders`).
                self.node_evaluated = self.graph.is_some();
                let mia = self.mia(m, params);
                let opacity = self.scalar(params, "cutout_opacity", 1.0);
                self.node_evaluated = false;
                SurfaceMaterial {
                    diffuse: mia.0.diffuse,
                    model: SurfaceModel::Mia(Box::new(mia)),
                    opacity,
                    ..SurfaceMaterial::lambert(name, Rgb::ZERO)
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
                let diffuse =
                    self.color_to(params, "diffuse", Rgb::ZERO, base(Target::Diffuse)).clamp(Rgb::ZERO, Rgb::ONE);
                SurfaceMaterial::lambert(name, diffuse)
            }
            ("mib_glossy_reflection", _) => mib_glossy::glossy_reflection(self, params, lib, depth),
            ("mib_glossy_refraction", _) => mib_glossy_refraction::glossy_refraction(self, params, lib, depth),
            (other, _) => {
                self.warnings.push(format!(
                    "material '{name}': shader '{other}' is not supported by the path integrator yet; rendered grey"
                ));
                SurfaceMaterial::grey(name)
            }
        }
    }
}
