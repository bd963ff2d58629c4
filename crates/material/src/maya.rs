//! Maya materials for the path engine: a shading engine's surface material translated to
//! BSDF lobes with the same diffuse albedo as the classic shaders.
//!
//! The classic shaders above are what the classic engine runs; the path engine needs a
//! BSDF instead. [`surface_material`] reads the material a shading engine's
//! `surfaceShader` is connected to, in the compiled shader graph:
//!
//! - lambert: a Lambertian lobe of albedo `color · diffuse` — the classic lambert's
//!   c·d·I·cos θ (no 1/π in mental ray's light units) is this lobe's reflected radiance
//!   under the same light in radiometric units;
//! - blinn, phong, phongE: the unified BSDF with base colour `color · diffuse`, a GGX
//!   highlight whose α is blinn's `eccentricity` (Blinn's distribution is GGX's), or the
//!   α of the Blinn–Phong lobe of exponent n = `cosinePower`, √(2/(n + 2)), or phongE's
//!   `roughness`; the dielectric specular weight is the luminance of `specularColor`
//!   (0.5, Maya's default, is the unified BSDF's default 0.5 too). Maya's non-physical
//!   highlight strengths (`specularRollOff`, `highlightSize`) and `reflectivity` have no
//!   lobe of their own: the reflection is the specular lobe's;
//! - surfaceShader: no scattering, `outColor` emitted (it is unlit in Maya too);
//! - transparency T (without refraction): coverage 1 − mean(T), so that the surface is
//!   seen in proportion 1 − T and what lies behind in proportion T, as Maya blends them;
//!   `incandescence`: emitted radiance;
//! - useBackground: fully transparent (the path engine has no shadow-catching matte; a
//!   warning says so).
//!
//! Connected colours become per-hit bindings of the shader graph's nodes (a file texture
//! driving `color`, bump2d driving `normalCamera`); what cannot be expressed is reported
//! in the warnings and takes its declared default.

use std::sync::Arc;

use crate::{Binding, SurfaceMaterial, SurfaceModel, Target, Varying};
use bsdf::Rgb;
use bsdf::{Unified, UnifiedParams};
use shader::{Graph, NodeId, Slot, Value};

/// A parameter of a node, by name, whatever order its slots are in.
fn slot<'a>(graph: &'a Graph, node: NodeId, name: &str) -> Option<&'a Slot> {
    let n = &graph.nodes[node as usize];
    let i = match n.imp {
        Some(imp) => imp.params.iter().position(|p| *p == name)?,
        None => n.decl.param(name)?,
    };
    n.slots.get(i)
}

/// A constant parameter's value, `None` when connected or absent.
fn constant<'a>(graph: &'a Graph, node: NodeId, name: &str) -> Option<&'a Value> {
    match slot(graph, node, name)? {
        Slot::Value(v) => Some(v),
        _ => None,
    }
}

/// The node and member a parameter is connected to.
fn connection(graph: &Graph, node: NodeId, name: &str) -> Option<(NodeId, Option<Arc<str>>)> {
    match slot(graph, node, name)? {
        Slot::Connect { node, member } => Some((*node, member.clone())),
        _ => None,
    }
}

fn rgb_of(v: &Value) -> Rgb {
    let c = v.color();
    Rgb::new(c.x, c.y, c.z)
}

/// Reads a material node's parameters, collecting bindings and warnings.
struct Reader<'a> {
    graph: &'a Graph,
    node: NodeId,
    bindings: Vec<Binding>,
    warnings: Vec<String>,
}

impl Reader<'_> {
    fn scalar(&mut self, name: &str, default: f32) -> f32 {
        if connection(self.graph, self.node, name).is_some() {
            self.warnings.push(format!("'{name}' is connected; the path engine uses {default}"));
            return default;
        }
        constant(self.graph, self.node, name).map_or(default, Value::scalar)
    }

    fn color(&self, name: &str, default: Rgb) -> Rgb {
        constant(self.graph, self.node, name).map_or(default, rgb_of)
    }

    /// A colour parameter driving `target` scaled by `scale`: its constant value (times
    /// `scale`), or a binding of what it is connected to (then the default colour
    /// stands for it in the constant model).
    fn driven(&mut self, name: &str, target: Target, scale: f32, default: Rgb) -> Rgb {
        match connection(self.graph, self.node, name) {
            Some((node, member)) => {
                self.bindings.push(Binding { node, member, target, scale });
                default * scale
            }
            None => self.color(name, default) * scale,
        }
    }
}

/// The GGX α of a Maya highlight.
fn highlight_alpha(decl: &str, r: &mut Reader) -> f32 {
    let alpha = if decl.contains("blinn") || decl.contains("Blinn") {
        r.scalar("eccentricity", 0.3)
    } else if decl.ends_with("phong") || decl.ends_with("Phong") {
        let n = r.scalar("cosinePower", 20.0).max(0.0);
        (2.0 / (n + 2.0)).sqrt()
    } else {
        r.scalar("roughness", 0.5)
    };
    alpha.clamp(1e-3, 1.0)
}

/// The path engine's material for the Maya shading engine `engine` (a node of `graph`)
/// of material `name`, with warnings about what was approximated; `None` if `engine` is
/// not a Maya shading engine connected to a Maya material.
pub fn surface_material(name: &str, graph: &Graph, engine: NodeId) -> Option<(SurfaceMaterial, Vec<String>)> {
    let decl = graph.nodes.get(engine as usize)?.decl.name.as_str();
    if decl != "maya_shadingengine" && decl != "adskMayaShadingEngine" {
        return None;
    }
    let (node, _) = connection(graph, engine, "surfaceShader")?;
    let material = graph.nodes[node as usize].decl.name.clone();
    let family = material.trim_start_matches("maya_").trim_start_matches("adskMaya").to_ascii_lowercase();
    let mut r = Reader { graph, node, bindings: Vec::new(), warnings: Vec::new() };
    let mut surface = SurfaceMaterial::lambert(name, Rgb::ZERO);
    match family.as_str() {
        "lambert" | "blinn" | "phong" | "phonge" => {
            let d = r.scalar("diffuse", 0.8);
            let reflective = family != "lambert";
            let target = if reflective { Target::BaseColor } else { Target::Diffuse };
            let albedo = r.driven("color", target, d, Rgb::splat(0.5));
            surface.diffuse = albedo;
            surface.emission = r.driven("incandescence", Target::Emission, 1.0, Rgb::ZERO);
            let t = r.color("transparency", Rgb::ZERO).clamp(Rgb::ZERO, Rgb::ONE);
            surface.opacity = 1.0 - (t.x + t.y + t.z) / 3.0;
            if connection(graph, node, "transparency").is_some() {
                r.warnings.push("'transparency' is connected; the path engine keeps the surface opaque".into());
            }
            if let Some((bump, member)) = connection(graph, node, "normalCamera") {
                r.bindings.push(Binding { node: bump, member, target: Target::Normal, scale: 1.0 });
            }
            if reflective {
                let alpha = highlight_alpha(&material, &mut r);
                let s = r.color("specularColor", Rgb::splat(0.5));
                let params = UnifiedParams {
                    base_color: albedo,
                    roughness: alpha.sqrt(),
                    specular: bsdf::luminance(s).clamp(0.0, 1.0),
                    ..UnifiedParams::default()
                };
                surface.model = SurfaceModel::Unified(Box::new(Unified::new(&params)));
            }
        }
        "surfaceshader" => {
            surface.emission = r.driven("outColor", Target::Emission, 1.0, Rgb::ZERO);
            let t = r.color("outTransparency", Rgb::ZERO).clamp(Rgb::ZERO, Rgb::ONE);
            surface.opacity = 1.0 - (t.x + t.y + t.z) / 3.0;
        }
        "usebackground" => {
            surface.opacity = 0.0;
            r.warnings.push("useBackground has no shadow-catching matte in the path engine; it is left out".into());
        }
        _ => {
            r.warnings.push(format!("'{material}' has no path-engine translation; rendered grey"));
            surface = SurfaceMaterial::grey(name);
        }
    }
    if !r.bindings.is_empty() {
        surface.varying = Varying::Bindings(r.bindings);
    }
    let warnings = r.warnings.into_iter().map(|w| format!("material '{name}' ({material}): {w}")).collect();
    Some((surface, warnings))
}
