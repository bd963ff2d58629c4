//! Surface materials for the path integrator, translated from the scene's materials.
//!
//! Each material becomes a [`SurfaceModel`] — a BSDF family — and an emission:
//! - mira's `unified_material` shader: the unified material with its own parameters;
//! - MDL (`::nvidia::core_definitions`): `flex_material` and `flex_material_v2`, `metal`,
//!   `plastic`, `thin_glass` and `thick_glass` become unified materials; `diffuse` an
//!   Oren–Nayar surface; `add_emission` its base material plus emission in MDL's units;
//! - `mia_material` and `mia_material_x`: [`bsdf::mia::MiaBsdf`], whose layer
//!   weights come from the author's curve and conservation at each viewing angle;
//! - the mental ray illumination shaders (`mib_illum_*`) their `diffuse` colour (Lambert);
//! - `mib_glossy_reflection`: its glossy reflection over its base material (`reader::mib_glossy`);
//! - `mib_glossy_refraction`: its glossy refraction under its top material (`reader::mib_glossy_refraction`);
//! - materials of MDL modules on the search path: compiled by [`mdl_modules`] (see
//!   [`translate_with`]).
//!
//! Constant parameters are read once (`reader`). Parameters connected to shaders —
//! MDL `::base` textures, mental ray texture and bump shaders — are evaluated at every
//! hit through the scene's shader graph ([`inputs`]), when the graph is given. Anything
//! else is rendered as a grey diffuse surface or with the parameter's default, with a
//! warning naming what was not understood.

pub mod edf;
pub mod edf_tree;
pub mod emission;
pub mod inputs;
pub mod maya;
pub mod mdl_modules;
pub mod measured_edf;
mod reader;
pub mod spot_edf;
pub mod wide_slots;

use mi::ast::{Num, Param, ShaderItem, Value};
use scene::{Library, Material, MaterialKind};

use bsdf::mia::{anisotropic_roughness, gloss_to_roughness, MiaBsdf};
use bsdf::microfacet::Ggx;
use bsdf::Rgb;
use bsdf::{Bsdf, Lambert, OrenNayar, Unified};
pub use inputs::{Binding, Evaluated, HitEvaluator, HitMaterial, MediumEvaluator, Target, Varying, VaryingMedium};
use mia::params::Mia;
use reader::Reader;
use shader::Shading;

use std::sync::{Arc, OnceLock};

/// Every shader library mira has, in lookup order: the base and physics libraries, the
/// Architectural library, Maya's libraries, MDL's `::base` functions.
pub static LIBRARIES: &[&shader::Library] = &[&baselib::LIBRARY, &mia::LIBRARY, &::maya::LIBRARY, &mdl::LIBRARY];

/// The registry of [`LIBRARIES`], with this crate's translation as the classic engine's
/// stand-in for materials without mental ray shaders; built once.
pub fn registry() -> Arc<shader::Registry> {
    static REGISTRY: OnceLock<Arc<shader::Registry>> = OnceLock::new();
    REGISTRY.get_or_init(|| Arc::new(shader::Registry::new(LIBRARIES).with_stand_in(stand_in))).clone()
}

/// Compiles the shading of `scene` with every library mira has ([`registry`]), then gives
/// each material shader that no library implements (a third-party plug-in's shader the
/// scene declares) a stand-in showing the colour among its parameters a user would expect
/// (`color`, `diffuse_color`, `base_color`, …, `outColor`; see `maya::standin`), with a
/// warning naming it at its line: never a silent black. What `mira render` and `mira check`
/// compile scenes with.
pub fn compile_shading(scene: &scene::Scene, options: &shader::ShadingOptions) -> (Shading, Vec<mi::Diagnostic>) {
    let (mut shading, mut diags) = Shading::build(scene, options, &registry());
    let stand_ins = ::maya::standin::attach_stand_ins(&mut shading);
    // The stand-in's warning replaces the model's "not implemented" one for that shader.
    diags.retain(|d| !(d.message.contains("is not implemented by mira") && stand_ins.iter().any(|s| s.span == d.span)));
    diags.extend(stand_ins);
    diags.extend(::maya::fog::fog_warnings(&shading));
    (shading, diags)
}

/// The classic engine's stand-in colours of material `m` (diffuse, emission): what the path
/// engine's translation finds (module materials get theirs from
/// [`module_stand_ins`] once they are compiled).
fn stand_in(m: &Material, lib: &Library) -> (glam::Vec3A, glam::Vec3A) {
    let (surface, _) = translate(m, lib, None);
    (surface.diffuse, surface.emission)
}

/// Turns the classic engine's stand-ins (`mira_diffuse` nodes of `shading`) of the
/// instances of module materials in `scene` into `mira_bsdf_material` nodes: the classic
/// engine shades a module material through the same compiled BSDF the path engine uses
/// (given per hit by the renderer, see `baselib::bsdf_material`), lit by the classic light
/// loop, final gathering and traced rays. The diffuse colour (averaged over the texture
/// space where it varies) and emission of the compiled material in `mdl` stay in the node
/// as its fallback.
pub fn module_stand_ins(shading: &mut Shading, scene: &scene::Scene, mdl: &mdl_modules::MdlMaterials) {
    for (i, m) in scene.materials.iter().enumerate() {
        let items: Option<&[ShaderItem]> = match &m.kind {
            MaterialKind::Shader(def) => Some(&def.list.0),
            MaterialKind::Material(defs) => {
                defs.iter().rev().find_map(|d| d.shaders.as_ref()).map(|l| &l.0[l.0.len().saturating_sub(1)..])
            }
        };
        let Some(compiled) = items.and_then(|items| mdl.get(call_span(items, &scene.library)?)) else { continue };
        let Some(node) = shading.materials.get(i).and_then(|ms| ms.surface) else { continue };
        let node = &mut shading.graph.nodes[node as usize];
        if node.imp.is_some_and(|imp| imp.name == "mira_diffuse") && node.slots.len() >= 2 {
            let c = |c: Rgb| shader::Slot::Value(shader::Value::Color(shader::Color::new(c.x, c.y, c.z, 1.0)));
            node.slots[0] = c(compiled.diffuse);
            node.slots[1] = c(compiled.emission);
            // Shaded through the compiled BSDF the renderer gives per hit; the colours are
            // its fallback.
            node.imp = Some(&::baselib::bsdf_material::MIRA_BSDF_MATERIAL);
        }
    }
}

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
    /// A mental ray built-in BSDF (a material's `bsdf` slot, `builtin_bsdf_*`).
    Builtin(Box<bsdf::BuiltinBsdf>),
    /// A sum of lobes with constant weights (MDL mixes and weighted layers of diffuse,
    /// glossy reflection and diffuse transmission): Oren–Nayar, GGX reflection without
    /// Fresnel, Lambert translucency.
    Lobes(Box<MiaBsdf>),
    /// A sum of up to four elemental lobes (MDL mixes and weighted layers of diffuse,
    /// diffuse transmission, GGX and Beckmann reflection of any roughness, sheen).
    MdlLobes(Box<bsdf::Lobes>),
    /// A sum of more lobes, layer curves or layer normals than [`SurfaceModel::MdlLobes`]
    /// holds (up to [`bsdf::lobes::WIDE_LOBES`], [`bsdf::lobes::WIDE_CURVES`] and
    /// [`bsdf::lobes::WIDE_FRAMES`]), shared with the BSDFs made of it. Boxed like the
    /// other large models: dropping a model then never takes the address of the value
    /// itself, which let the compiler keep hit materials in registers in the path tracer's
    /// loop (a `SharedLobes` in place made it copy them through memory: +3.4 % instructions
    /// on the Cornell box).
    MdlWide(Box<bsdf::SharedLobes>),
    /// A wide sum lowered at one hit of a material that varies over the surface, kept in
    /// the thread's ring ([`wide_slots`]: no allocation per hit).
    MdlWideAt(wide_slots::WideSlot),
    /// A Maya material with a highlight (blinn, phong, phongE, anisotropic, rampShader):
    /// Lambertian reflection of the `diffuse` colour plus Maya's own highlight, bounded per
    /// view, and its mirror ([`bsdf::MayaGlossy`]).
    Maya(Box<bsdf::MayaGlossy>),
    /// mental ray's `mib_glossy_reflection`: its Ward-spread reflection (or mirror) over a
    /// Lambertian base of the `diffuse` colour (its base material's).
    MibGlossy(Box<bsdf::MibGlossyLobe>),
    /// mental ray's `mib_glossy_refraction`: its Ward-spread (or sharp) refraction under a
    /// Lambertian top of the `diffuse` colour (its top material's) on the front, and the
    /// lobe's back material on the back.
    MibGlossyRefraction(Box<bsdf::MibGlossyRefractionLobe>),
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
    /// Coverage: 1 is solid, 0 lets rays through untouched (cutouts).
    pub opacity: f32,
    /// What a ray that passes through the surface (a share 1 − `opacity` of them) is
    /// multiplied by, per channel: a Maya material's coloured transparency T / (1 −
    /// `opacity`), so that over all rays T of what lies behind shows, per channel, as the
    /// classic shaders filter it; 1 for every other material (and where a shader drives
    /// the opacity).
    pub cutout_tint: Rgb,
    /// `emission` is for the whole emitting surface (radiance × area, from MDL's `lumen`
    /// and `candela` units): the renderer divides it by the material's total area.
    pub emission_over_area: bool,
    /// How the emission is spread over directions when it is not Lambertian (MDL's
    /// `spot_edf`, `measured_edf`): the radiance towards a direction is `emission` times
    /// its factor.
    pub emission_shape: Option<edf::EmissionShape>,
    /// Parameters driven by shaders, evaluated at each hit.
    pub varying: Varying,
    /// The participating medium inside the surface (MDL's `material_volume`), when light
    /// can enter it ([`SurfaceMaterial::has_inside`]) and it absorbs or scatters.
    pub medium: Option<bsdf::Medium>,
    /// The medium where it depends on the shading point: evaluated where a path enters
    /// the object ([`SurfaceMaterial::medium_at`]; `medium` is then its value at a default
    /// point). `None` for a medium that is the same everywhere.
    pub varying_medium: Option<inputs::VaryingMedium>,
    /// The BSDF's local x axis at a hit: the surface's dP/du of its first texture space
    /// turned by this angle (radians, counter-clockwise about the shading normal), for
    /// anisotropic lobes (Maya's anisotropic material); `None`: any tangent of the normal.
    pub tangent_angle: Option<f32>,
    /// A fixed direction the BSDF's local x axis follows instead (world space, as the
    /// classic engine reads mental ray's `mib_glossy_*` `u_axis`): at each hit, projected
    /// onto the plane of the shading normal (a tangent of the normal where it is
    /// parallel to it). It takes the place of `tangent_angle`.
    pub tangent_axis: Option<glam::Vec3A>,
    /// The glow a camera sees on the surface (linear RGB; Maya materials' `outGlowColor`,
    /// `glowIntensity` × their colour): what the path engine stores in the glow frame
    /// buffer a shader glow spreads (zero for materials that do not glow).
    pub glow: Rgb,
    /// How much of Maya's ambient light the surface reflects per unit of its diffuse
    /// colour (`diffuse` here, per hit), per channel: Maya's materials reflect ambient
    /// light by their `color` c where direct light goes by c·d (`diffuse` d), so Maya's
    /// lambert, blinn, phong, phongE and anisotropic carry 1/d, rampShader
    /// 1/(d + translucence) (light angle) or 1/d, layeredShader its layers' mix (see
    /// `crate::maya`); 0: the material takes no ambient light (every other material, as
    /// in the classic engine, where only Maya's materials read ambient lights as such).
    /// See `render::ambient`.
    pub ambient: Rgb,
    /// A Maya material's own highlight, for the light the path engine gives by the
    /// classic formula (Maya volume lights with `emitAmbient` and `emitSpecular`; see
    /// [`maya::MayaHighlight`]); `None` for every other material.
    pub maya_highlight: Option<maya::MayaHighlight>,
    /// A rampShader's transparency and incandescence ramps by the view's facing ratio:
    /// the path engine sets each hit's coverage, cut-out tint, diffuse colour and
    /// emission from them ([`maya::ViewTransparency::apply`]); `None` for every other
    /// material (and for a rampShader whose ramps are the same all along).
    pub view_transparency: Option<Box<maya::ViewTransparency>>,
    /// Maya's useBackground: the shadow-catching matte the path engine shades it as
    /// ([`maya::MayaMatte`]); `None` for every other material.
    pub maya_matte: Option<maya::MayaMatte>,
    /// Maya's `translucenceDepth` D of a lambert-family material with translucence (world
    /// units; 0: none): a shadow ray that leaves the receiving point's own object through
    /// this surface after a stretch s inside it passes T + (1 − T)·max(1 − s/D, 0)
    /// ([`maya::translucent_passage`]).
    pub translucence_depth: f32,
    /// A layeredShader stack whose layers carry translucence depths: each layer's
    /// transparency T_i (per channel; by the shadow ray's facing ratio where a rampShader
    /// layer's ramp follows the view) and translucence depth D_i (0: none), top first. Its
    /// shadow passage is the hit's transparency raised by
    /// Π_i (T_i + (1 − T_i)·max(1 − s/D_i, 0)) − Π_i T_i, as the classic stack multiplies
    /// its layers' passages ([`maya::translucent_passage`]); empty for a material on its
    /// own ([`SurfaceMaterial::translucence_depth`] is then its own).
    pub translucence_layers: Box<[maya::TranslucentLayer]>,
}

impl SurfaceMaterial {
    /// A grey diffuse surface (the fallback for what is not understood).
    pub fn grey(name: &str) -> SurfaceMaterial {
        SurfaceMaterial::lambert(name, Rgb::splat(0.5))
    }

    /// A Lambertian surface of reflectance `diffuse`.
    pub fn lambert(name: &str, diffuse: Rgb) -> SurfaceMaterial {
        SurfaceMaterial {
            name: name.to_string(),
            diffuse,
            emission: Rgb::ZERO,
            model: SurfaceModel::Lambert,
            opacity: 1.0,
            cutout_tint: Rgb::ONE,
            emission_over_area: false,
            emission_shape: None,
            varying: Varying::Constant,
            medium: None,
            varying_medium: None,
            tangent_angle: None,
            tangent_axis: None,
            glow: Rgb::ZERO,
            ambient: Rgb::ZERO,
            maya_highlight: None,
            view_transparency: None,
            maya_matte: None,
            translucence_depth: 0.0,
            translucence_layers: Box::new([]),
        }
    }

    /// The BSDF at a shading point seen from `wo` (local shading frame: some layer
    /// weights depend on the viewing angle), for the material's constant parameters.
    pub fn bsdf(&self, wo: glam::Vec3A) -> Bsdf {
        self.model.bsdf(self.diffuse, wo)
    }

    /// The medium a path entering the object at the shading point `state` travels in:
    /// the varying medium evaluated there, else the constant one.
    pub fn medium_at(&self, state: &shader::State) -> Option<bsdf::Medium> {
        match &self.varying_medium {
            Some(v) => Some(v.0.medium(state)),
            None => self.medium,
        }
    }

    /// Whether light can enter the surface (then its two sides differ: the path tracer
    /// keeps the geometric orientation instead of facing the normal towards the ray).
    pub fn has_inside(&self) -> bool {
        self.model.has_inside()
    }
}

impl SurfaceModel {
    /// The BSDF seen from `wo` (local shading frame `frame`, world space), with diffuse
    /// colour `diffuse`: [`SurfaceModel::bsdf`] with the world-space layer normals of an
    /// MDL lobe sum brought into the frame.
    #[inline]
    pub fn bsdf_in(&self, diffuse: Rgb, wo: glam::Vec3A, frame: &bsdf::Frame) -> Bsdf {
        self.bsdf_placed(diffuse, wo, Some(frame))
    }

    /// The BSDF seen from `wo` (local shading frame), with diffuse colour `diffuse` (an MDL
    /// lobe sum's layer normals taken as local: see [`SurfaceModel::bsdf_in`]).
    #[inline]
    pub fn bsdf(&self, diffuse: Rgb, wo: glam::Vec3A) -> Bsdf {
        self.bsdf_placed(diffuse, wo, None)
    }

    /// The BSDF seen from `wo`, an MDL lobe sum's layer normals placed in `frame` when
    /// given. One `match` building each variant in place (a `Bsdf` is up to 320 bytes: a
    /// second function's result would be copied).
    #[inline]
    fn bsdf_placed(&self, diffuse: Rgb, wo: glam::Vec3A, frame: Option<&bsdf::Frame>) -> Bsdf {
        match self {
            SurfaceModel::Lambert => Bsdf::Lambert(Lambert { albedo: diffuse }),
            SurfaceModel::OrenNayar(sigma) => Bsdf::OrenNayar(OrenNayar::new(diffuse, *sigma)),
            SurfaceModel::Unified(u) => Bsdf::Unified(**u),
            SurfaceModel::Builtin(b) => Bsdf::Builtin(**b),
            SurfaceModel::Lobes(l) => Bsdf::Mia(**l),
            SurfaceModel::MdlLobes(l) => match frame {
                Some(frame) if l.normal_count > 0 => {
                    let mut l = **l;
                    l.place(frame);
                    Bsdf::Lobes(l)
                }
                _ => Bsdf::Lobes(**l),
            },
            SurfaceModel::MdlWide(l) => Bsdf::Wide(bsdf::WideBsdf::new((**l).clone(), frame)),
            SurfaceModel::MdlWideAt(slot) => match slot.lobes() {
                Some(l) => Bsdf::Wide(bsdf::WideBsdf::new(l, frame)),
                // The slot was reused before this hit's BSDF was built (both engines build
                // it first): the diffuse colour rather than another hit's sum.
                None => Bsdf::Lambert(Lambert { albedo: diffuse }),
            },
            SurfaceModel::Maya(g) => Bsdf::Maya(g.bsdf_seen(diffuse, wo, frame)),
            SurfaceModel::MibGlossy(g) => Bsdf::MibGlossy(g.bsdf(diffuse, wo)),
            SurfaceModel::MibGlossyRefraction(g) => Bsdf::MibGlossyRefraction(g.bsdf(diffuse, wo)),
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

    /// The tint of light crossing the surface straight on, when it is an index-matched
    /// boundary (smooth transmission with index of refraction 1, no reflection, no coat):
    /// rays keep their direction through it, so shadow rays may cross it too.
    pub fn index_matched(&self) -> Option<Rgb> {
        let SurfaceModel::Unified(u) = self else { return None };
        let p = u.params();
        let matched = (p.ior - 1.0).abs() < 1e-6
            && p.spec_trans >= 1.0
            && p.metallic <= 0.0
            && p.clearcoat <= 0.0
            && !p.thin
            && u.is_delta();
        matched.then(|| p.transmission_color.unwrap_or(p.base_color).clamp(Rgb::ZERO, Rgb::ONE))
    }

    /// Whether rays that see the surface refract through its BSDF rather than pass it as
    /// a cut-out (a Maya material with `refractions` on: [`bsdf::MayaGlossy::refraction`]);
    /// shadow rays still pass by its opacity and [`SurfaceMaterial::cutout_tint`], as the
    /// classic shader filters them by its transparency. (Inlined: every hit of the path
    /// engine asks it.)
    #[inline]
    pub fn refracts(&self) -> bool {
        matches!(self, SurfaceModel::Maya(g) if g.refraction != Rgb::ZERO)
    }

    /// Whether light can enter the surface.
    pub fn has_inside(&self) -> bool {
        match self {
            SurfaceModel::Unified(u) => u.params().spec_trans > 0.0 && !u.params().thin,
            SurfaceModel::Mia(m) => m.0.transparency > 0.0 && !m.0.thin_walled,
            SurfaceModel::Lobes(l) => l.transmit != Rgb::ZERO && !l.thin,
            SurfaceModel::MdlLobes(l) => l.has_inside(),
            SurfaceModel::MdlWide(l) => l.has_inside(),
            SurfaceModel::MdlWideAt(slot) => slot.has_inside(),
            SurfaceModel::MibGlossyRefraction(_) => true,
            _ => false,
        }
    }
}

pub use shader::decl::declaration_name;

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
/// Parameters connected to shaders are evaluated per hit when `shading` (the scene's
/// compiled shader graph, with `m` as its material `index`) is given, else they take their
/// defaults.
pub fn translate(m: &Material, lib: &Library, shading: Option<(&Shading, usize)>) -> (SurfaceMaterial, Vec<String>) {
    translate_with(m, lib, shading, None)
}

/// The span of the shader call behind a material, following one named reference.
fn call_span(items: &[ShaderItem], lib: &Library) -> Option<mi::Span> {
    let first = |items: &[ShaderItem]| match items.first()? {
        ShaderItem::Call { span, .. } => Some(*span),
        _ => None,
    };
    match items.first()? {
        ShaderItem::Call { span, .. } => Some(*span),
        ShaderItem::Ref(name) => first(&lib.shaders.get(&name.text)?.list.0),
        ShaderItem::Define { list, .. } => first(&list.0),
    }
}

/// [`translate`] with the scene's compiled MDL module materials: a material that is an
/// instance of one of them is that compiled material.
pub fn translate_with(
    m: &Material,
    lib: &Library,
    shading: Option<(&Shading, usize)>,
    mdl: Option<&mdl_modules::MdlMaterials>,
) -> (SurfaceMaterial, Vec<String>) {
    let items: Option<&[ShaderItem]> = match &m.kind {
        MaterialKind::Shader(def) => Some(&def.list.0),
        MaterialKind::Material(defs) => {
            defs.iter().rev().find_map(|d| d.shaders.as_ref()).map(|l| &l.0[l.0.len().saturating_sub(1)..])
        }
    };
    if let Some(compiled) = mdl.zip(items).and_then(|(mdl, items)| mdl.get(call_span(items, lib)?)) {
        // Its problems were reported by the compiler, at the `.mi` instance.
        let mut surface = compiled.clone();
        surface.name = m.name.clone();
        return (surface, Vec::new());
    }
    // A Maya shading engine: its surface shader's material (see [`maya`]).
    let maya_engine = shading.and_then(|(s, i)| Some((&s.graph, s.materials.get(i)?.surface?)));
    if let Some(found) = maya_engine.and_then(|(graph, head)| maya::surface_material(&m.name, graph, head)) {
        return found;
    }
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
        if let Some(surface) = shading.and_then(|(s, i)| builtin_bsdf(m, s, i)) {
            return (surface, warnings);
        }
        warnings.push(format!("material '{}' has no shader mira understands; rendered grey", m.name));
        return (SurfaceMaterial::grey(&m.name), warnings);
    };
    let graph = shading.map(|(s, _)| &s.graph);
    let head = shading.and_then(|(s, i)| s.materials.get(i)).and_then(|ms| ms.surface);
    let mut reader = Reader::new(&m.name, &mut warnings, graph);
    let mut surface = reader.call(decl, params, lib, 0);
    surface.varying = reader.finish();
    if let (Some(graph), Some(head)) = (graph, head) {
        inputs::bind_material_shaders(&mut surface, graph, head);
    }
    (surface, warnings)
}

/// The material of a `bsdf` slot holding one of mental ray's built-in BSDFs, with its
/// constant parameters (connected ones take their defaults).
fn builtin_bsdf(m: &Material, shading: &Shading, index: usize) -> Option<SurfaceMaterial> {
    let node = &shading.graph.nodes[shading.materials.get(index)?.bsdf? as usize];
    let imp = node.imp?;
    let param = |name: &str| {
        let i = imp.params.iter().position(|p| *p == name)?;
        match node.slots.get(i)? {
            shader::Slot::Value(v) => Some(v.clone()),
            _ => None,
        }
    };
    let bsdf = baselib::bsdf_builtin::builtin_bsdf_surface(imp.name, &param)?;
    let diffuse = match &bsdf {
        bsdf::BuiltinBsdf::Lambert(l) => l.albedo,
        _ => Rgb::splat(0.5),
    };
    Some(SurfaceMaterial { model: SurfaceModel::Builtin(Box::new(bsdf)), ..SurfaceMaterial::lambert(&m.name, diffuse) })
}

impl SurfaceMaterial {
    /// Divides an emission given for the whole surface by the surface's `area` (scene
    /// units²), also in emission driven by shaders; nothing when the emission is per area.
    pub fn spread_emission_over(&mut self, area: f32) {
        if !self.emission_over_area {
            return;
        }
        let scale = if area > 0.0 { 1.0 / area } else { 0.0 };
        self.emission *= scale;
        match &mut self.varying {
            Varying::Bindings(bindings) => {
                for b in bindings.iter_mut().filter(|b| b.target == Target::Emission) {
                    b.scale *= scale;
                }
            }
            Varying::Evaluated(e) => {
                if let Some(scaled) = e.0.with_emission_scaled(scale) {
                    e.0 = scaled;
                }
            }
            _ => {}
        }
        self.emission_over_area = false;
    }
}
