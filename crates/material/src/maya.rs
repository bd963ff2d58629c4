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
//! - blinn, phong, phongE, anisotropic: a Lambertian lobe of albedo `color · diffuse`
//!   beside Maya's own highlight of tint `specularColor` (⊙ `whiteness` for phongE) —
//!   the classic formula itself, f = s · H(v, l)/(π·N·L), which under a light of π·C
//!   gives exactly the classic s ⊙ C · H (`bsdf::maya_highlight`: why a lobe of Maya's
//!   shape rather than a GGX lobe scaled to its albedo, and the bound that keeps its
//!   albedo ≤ 1 at every view). Anisotropic's grooves (dP/du turned by `angle` about the
//!   normal: Maya's rule, X is U turned counter-clockwise by the angle) are handed to the
//!   path engine as the material's tangent at each hit, the lobe's local x. The classic
//!   highlight is also kept beside it ([`MayaHighlight`]) for the one light the path
//!   engine shades by the classic formulas: volume lights with `emitAmbient` and
//!   `emitSpecular`. The classic shaders' raytraced reflection, `reflectivity` ·
//!   `specularColor` ⊙ what a mirror ray finds (× blinn's Schlick factor with
//!   `reflectionRolloff`), is the BSDF's mirror lobe of that weight, `reflectedColor`'s
//!   share of it emitted;
//! - rampShader: a Lambertian lobe whose albedo is the colour ramp at 1 (the surface
//!   facing the light or the viewer) times `diffuse` (+ `translucence` for the light-angle
//!   input, whose documented lambert recipe this reproduces exactly); its light from
//!   behind a transmission lobe: for the light-angle input the classic
//!   t · C((1 + cos θ)/2) ⊙ L from the ramp's own knots and interpolation over [0, ½]
//!   (albedo 2∫t · C((1 − u)/2) du, not capped:
//!   `bsdf::MayaGlossy::light_angle`), for the other inputs a
//!   Lambertian one of albedo C(1) · `translucence`, faded as the lit colour, with `translucenceDepth` for shadow rays ([`translucence`]); the transparency
//!   and incandescence ramps at each hit's facing ratio ([`ViewTransparency`]: the hit's
//!   coverage, cut-out tint and fade, or for one that refracts its refraction's weight;
//!   transparency fading the lit colour and incandescence only, as below); its highlight, `specularity` · `specularRollOff` ·
//!   `specularColor` ⊙ light · D with D Blinn's distribution of `eccentricity` (peak 1),
//!   is Maya's lobe of that shape and tint (`bsdf::maya_highlight::ramp_blinn`, the
//!   classic shader's own function), its reflection a mirror of weight `reflectivity`
//!   that emits the `environment` ramp by its weight; the roll-off and reflectivity
//!   ramps are evaluated at each view's facing ratio, the specular-colour ramp at the
//!   highlight's strength and the environment ramp at the world reflection direction's
//!   height (1 + R_y)/2, as the classic shader indexes them (tabulated:
//!   `bsdf::maya_highlight::ViewRamps`). Colour ramps
//!   indexed by the view angle or the brightness vary in ways a BSDF's albedo cannot (a
//!   warning says so);
//! - layeredShader: the layers' translations mixed by the share of each that shows, per
//!   channel, w_i = T_0 ⊙ ⋯ ⊙ T_(i−1) ⊙ (1 − T_i) (`compositingFlag` 0 or 1 alike): their
//!   albedos, emissions and the first reflective layer's lobe; opacity 1 − mean(Π T_i)
//!   and rays that pass tinted per channel (as a transparent lambert's, below);
//!   a layer whose material refracts (as below) is the last that shows: the stack
//!   refracts by P_k ⊙ T_k (P_k the transparencies above it) with its index and limit,
//!   as the classic layeredShader shows what that layer's refraction ray finds; rampShader
//!   layers whose transparency or incandescence ramps follow the view are read at each
//!   hit's facing ratio, the refraction's weight P_k ⊙ T_k and every layer's
//!   translucence by its share there too (`view_layers`, [`StackTranslucence`]); the
//!   first layer's highlight and mirror, every layer's translucence by its share w_i
//!   (divided by the stack's coverage as its diffuse colour is; each with its own focus,
//!   `bsdf::MayaGlossy::add_translucence`: up to four distinct foci in the BSDF's own
//!   lobes, any number held by the material past them and for a stack whose shares
//!   follow the view, `bsdf::maya_highlight::translucent_stack`) and every translucent
//!   layer's depth for shadow rays, which pass the product of the layers' passages
//!   ([`SurfaceMaterial::translucence_layers`]);
//! - surfaceShader: no scattering, `outColor` emitted (it is unlit in Maya too);
//! - Maya's ambient lights: lambert, blinn, phong, phongE and anisotropic reflect them by
//!   `color` (the diffuse colour / `diffuse`: [`SurfaceMaterial::ambient`], added at
//!   each hit by the path engine); rampShader by its colour at 1 (the diffuse colour /
//!   (`diffuse` + `translucence`) for the light-angle input, / `diffuse` for the others),
//!   as the classic shader's C(1) ⊙ ambient; layeredShader by Σ w_i ⊙ its material
//!   layers' ambient colours (a ratio of its diffuse colour per channel; plain-colour
//!   layers take none, as in the classic shader, where they are not lit);
//! - `refractions` on (lambert family, rampShader — by its transparency at each hit's
//!   facing ratio — and layeredShader layers; an index other than 1, T ≠ 0): the
//!   classic shader's T ⊙ its refraction ray, bent by Snell's law with
//!   `refractiveIndex` (no Fresnel; a mirror ray under total internal reflection) while
//!   the ray has made fewer than `refractionLimit` refraction and transparency rays (the
//!   path engine counts its delta transmissions and its passes through cut-outs), a
//!   straight transparency ray past it, is the BSDF's delta refraction of weight T
//!   (`bsdf::MayaGlossy::refraction`): every non-shadow ray hits the surface (no
//!   cut-out, the diffuse part faded by 1 − T, nothing divided by a coverage); shadow
//!   rays pass it as a cut-out tinted by T, as the classic shader filters them;
//! - transparency T (without refraction): coverage p = 1 − mean(T) (at least
//!   [`MIN_HIGHLIGHT_COVERAGE`] for a material with a highlight or a reflection), and
//!   the rays that pass carry T/(1 − p) per channel ([`SurfaceMaterial::cutout_tint`]),
//!   so that what lies behind shows by T per channel, as Maya blends them; as in the
//!   classic shaders it fades only the lambert family's diffuse part and incandescence:
//!   their hits carry (1 − T)/p of those per channel and the highlight, the mirror and
//!   `reflectedColor` divided by p, so that over all rays the highlight and the
//!   reflection are whole, even on a fully transparent material;
//! - `reflectedColor`: emitted by the mirror's weight at each hit and view
//!   (`bsdf::MayaGlossy::reflected`: blinn's roll-off at N·V, a connected
//!   `specularColor`); `reflectionLimit`: the mirror reflects on paths of fewer mirror
//!   and `mia_material` glossy reflections, as mental ray's reflection level counts
//!   reflection rays (`bsdf::MayaGlossy::reflection_limit`);
//!   `incandescence`: emitted radiance; `ambientColor` a: c ⊙ a emitted (faded by
//!   1 − T), per hit when `color` or `ambientColor` is connected ([`ambient_color`]);
//!   rampShader's C_ref ⊙ a likewise (`ramp_shader::Ambient`); `translucence` t: a
//!   transmission lobe of albedo c·t shaped by `translucenceFocus`, `translucenceDepth`
//!   the light it lets through the object's own geometry in shadow rays
//!   ([`translucence`]);
//! - useBackground: a shadow-catching matte ([`MayaMatte`]: the background darkened by
//!   `shadowMask` × the blocked share of the lights, a mirror of `reflectivity` ·
//!   `specularColor`), fully transparent to shadow rays;
//! - glow (what a camera's shader glow spreads, as the classic shaders' `outGlowColor`):
//!   `glowIntensity` × `color` for the lambert family (a connected colour is bound per
//!   hit), `glowIntensity` × the colour ramp at 1 for rampShader, `outGlowColor` for
//!   surfaceShader, and for layeredShader Σ P_i ⊙ glow_i over its layers (P_i the
//!   transparencies above layer i; a layer's glow is its constant `glowColor` or the
//!   constant glow of the material it is connected to).
//!
//! Connected colours become per-hit bindings of the shader graph's nodes (a file texture
//! driving `color` or `specularColor`, bump2d driving `normalCamera`); what cannot be
//! expressed is reported in the warnings and takes its declared default.

use std::sync::Arc;

mod matte;
mod ramp_shader;
mod translucence;
mod view_layers;
mod view_transparency;
pub use matte::MayaMatte;
pub use translucence::{translucent_passage, TranslucentLayer, CONNECTED_STAND_IN};
pub use view_layers::StackTranslucence;
pub use view_transparency::ViewTransparency;

use crate::{Binding, SurfaceMaterial, SurfaceModel, Target, Varying};
use bsdf::Rgb;
use shader::{Graph, NodeId, Slot, Value};

/// A Maya material's highlight as the classic shader computes it: `color` ⊙ light ⊙
/// `model.value(n, v, l)` (Maya's units: no π, no BSDF). The path engine adds it for the
/// lights it does not sample through the BSDF — volume lights with `emitAmbient` and
/// `emitSpecular`, which light the classic materials' highlight as a light from their
/// direction does — so that they match the classic engine; every other light's
/// highlight is the BSDF's reflection lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MayaHighlight {
    /// The highlight model and its parameters (blinn, phong or phongE).
    pub model: ::maya::specular::Highlight,
    /// `specularColor` (its constant value; 0.5 grey when connected, which the path
    /// engine multiplies by the hit's [`bsdf::MayaBsdf::tinted_by`]), divided by the
    /// material's coverage (see [`surface_material`]).
    pub color: Rgb,
}

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

/// The value of a slot without connections (arrays and structs of constants included);
/// `None` if anything in it is connected.
fn constant_value(s: &Slot) -> Option<Value> {
    Some(match s {
        Slot::Value(v) => v.clone(),
        Slot::Connect { .. } => return None,
        Slot::Array(items) => Value::Array(items.iter().map(constant_value).collect::<Option<Vec<_>>>()?.into()),
        Slot::Struct(members) => Value::Struct(
            members.iter().map(|(n, s)| Some((n.clone(), constant_value(s)?))).collect::<Option<Vec<_>>>()?.into(),
        ),
    })
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

/// anisotropic (see the module doc): Maya's anisotropic highlight of widths (α_x, α_y) =
/// [`::maya::specular::anisotropic_widths`] along the grooves (dP/du turned by `angle`,
/// handed to the path engine as the material's tangent, the local frame's x) and across
/// them, with the Fresnel ratio of `fresnelRefractiveIndex`: the classic highlight itself.
fn anisotropic(r: &mut Reader, surface: &mut SurfaceMaterial) -> bsdf::maya_highlight::Shape {
    let angle = r.scalar("angle", 0.0);
    let (alpha_x, alpha_y) = ::maya::specular::anisotropic_widths(
        r.scalar("roughness", 0.7),
        r.scalar("spreadX", 13.0),
        r.scalar("spreadY", 3.0),
    );
    let ior = r.scalar("fresnelRefractiveIndex", 6.0).max(1.0 + 1e-3);
    surface.tangent_angle = Some(angle);
    bsdf::maya_highlight::Shape::Anisotropic { alpha_x, alpha_y, ior }
}

/// The BSDF highlight (shape and tint) of a classic Maya highlight of `specularColor`
/// `specular` (phongE's `whiteness` joins the tint); `None` for anisotropic, whose
/// classic grooves are a world direction (see [`anisotropic`]).
fn glossy_shape(highlight: ::maya::specular::Highlight, specular: Rgb) -> Option<(bsdf::maya_highlight::Shape, Rgb)> {
    use ::maya::specular::Highlight;
    use bsdf::maya_highlight::Shape;
    Some(match highlight {
        Highlight::None | Highlight::Anisotropic { .. } => return None,
        Highlight::Blinn { eccentricity, rolloff, .. } => (Shape::Blinn { eccentricity, rolloff }, specular),
        Highlight::Phong { power } => (Shape::Phong { power }, specular),
        Highlight::PhongE { roughness, size, whiteness } => {
            (Shape::PhongE { roughness, size }, specular * Rgb::new(whiteness.x, whiteness.y, whiteness.z))
        }
    })
}

/// The lambert family's `ambientColor` a: the classic shader adds c ⊙ a (faded by 1 − T
/// like the rest of its diffuse part) whatever the lights, as it adds incandescence, so
/// it is emitted radiance here, faded by `fade` per channel — constant, or per hit
/// through one binding per channel when `color` or `ambientColor` is connected (both
/// connected: warned about and left out). The classic shader returns it to every ray
/// that is not a shadow or light ray, final-gather and reflection rays included, so
/// it lights other surfaces there; as emission it does so in the path engine too.
fn ambient_color(r: &mut Reader, surface: &mut SurfaceMaterial, fade: Rgb) {
    let color = connection(r.graph, r.node, "color");
    let ambient = connection(r.graph, r.node, "ambientColor");
    let (driver, weight) = match (color, ambient) {
        (None, None) => {
            surface.emission += r.color("color", Rgb::splat(0.5)) * r.color("ambientColor", Rgb::ZERO) * fade;
            return;
        }
        (Some(_), Some(_)) => {
            r.warnings.push("'color' and 'ambientColor' are both connected; the path engine leaves c ⊙ a out".into());
            return;
        }
        (Some(c), None) => (c, r.color("ambientColor", Rgb::ZERO)),
        (None, Some(a)) => (a, r.color("color", Rgb::splat(0.5))),
    };
    let (node, member) = driver;
    for (c, scale) in [weight.x * fade.x, weight.y * fade.y, weight.z * fade.z].into_iter().enumerate() {
        if scale != 0.0 {
            r.bindings.push(Binding { node, member: member.clone(), target: Target::EmissionChannel(c as u8), scale });
        }
    }
}

/// The `irradiance` illumination map M of the lambert family (the reading is
/// `maya::material`'s): light that reaches the surface whatever the lights, c·d ⊙
/// `irradianceColor` ⊙ M added to the emission — constant, or per hit through a binding
/// when M is connected (a baked map: one binding scaled by a grey `irradianceColor`, one
/// per channel for a coloured one). A constant M on a surface whose colour or
/// incandescence is connected is warned about (it takes the default colour, or is lost).
fn irradiance_map(r: &mut Reader, surface: &mut SurfaceMaterial, albedo: Rgb) {
    let g = r.color("irradianceColor", Rgb::ONE);
    match connection(r.graph, r.node, "irradiance") {
        Some((node, member)) => {
            let mean = (g.x + g.y + g.z) / 3.0;
            if (g - Rgb::splat(mean)).abs().max_element() > 1e-6 {
                for (c, scale) in [g.x, g.y, g.z].into_iter().enumerate() {
                    let target = Target::IrradianceMapChannel(c as u8);
                    r.bindings.push(Binding { node, member: member.clone(), target, scale });
                }
            } else {
                r.bindings.push(Binding { node, member, target: Target::IrradianceMap, scale: mean });
            }
        }
        None => {
            let m = r.color("irradiance", Rgb::ZERO);
            if m != Rgb::ZERO && ["color", "incandescence"].iter().any(|p| connection(r.graph, r.node, p).is_some()) {
                r.warnings.push(
                    "a constant 'irradiance' on a connected colour or incandescence: the path engine lights it with \
                     the default colour, or not at all"
                        .into(),
                );
            }
            surface.emission += albedo * g * m;
        }
    }
}

/// The least coverage of a shading engine's Maya material that shows a highlight or a
/// reflection: a more transparent one is hit by this share of the rays all the same
/// (its hits carrying the highlight, the reflection and the faded diffuse part divided
/// by it, the rays that pass T / (1 − coverage)), so that a fully transparent blinn
/// still shows its highlight, which Maya adds on top of the transparency.
pub const MIN_HIGHLIGHT_COVERAGE: f32 = 0.25;

/// Sets the coverage and cut-out tint of a material of transparency `t` (per channel):
/// coverage 1 − mean(T) — at least [`MIN_HIGHLIGHT_COVERAGE`] when `highlight` (the
/// shading engine's material shows a highlight or a reflection over its transparency)
/// — and rays that pass carry T / (1 − coverage), so that what lies behind shows by T
/// per channel over all rays, as the classic shaders filter it.
fn cut_out(surface: &mut SurfaceMaterial, t: Rgb, highlight: bool) {
    let mut opacity = 1.0 - (t.x + t.y + t.z) / 3.0;
    if highlight {
        opacity = opacity.max(MIN_HIGHLIGHT_COVERAGE);
    }
    surface.opacity = opacity;
    surface.cutout_tint = if opacity < 1.0 { t / (1.0 - opacity) } else { Rgb::ONE };
}

/// The index of refraction of a shading engine's (`alone`) Maya material of constant
/// transparency `t` that refracts — `refractions` on, `refractiveIndex` positive and not
/// 1, `t` not black, as the classic shader then traces a refraction ray — else `None`.
fn refraction_index(r: &mut Reader, t: Rgb, alone: bool) -> Option<f32> {
    let ior = r.scalar("refractiveIndex", 1.0);
    let on = constant(r.graph, r.node, "refractions").is_some_and(Value::bool);
    (alone && on && t != Rgb::ZERO && ior > 0.0 && (ior - 1.0).abs() > 1e-6).then_some(ior)
}

/// Gives `surface` the refraction of weight `t` and index `ior`: T ⊙ what the ray bent
/// by Snell's law finds, within `refractionLimit` (Maya's default 6) refractions (beside
/// its highlight and mirror, or a highlight of zero tint when it has none).
fn refract(r: &mut Reader, surface: &mut SurfaceMaterial, t: Rgb, ior: f32) {
    let limit = r.scalar("refractionLimit", 6.0).max(0.0) as u32;
    refract_within(surface, t, ior, limit);
}

/// [`refract`] with the limit given.
fn refract_within(surface: &mut SurfaceMaterial, t: Rgb, ior: f32, limit: u32) {
    let glossy = match &surface.model {
        SurfaceModel::Maya(g) => **g,
        _ => bsdf::MayaGlossy::new(bsdf::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO),
    };
    surface.model = SurfaceModel::Maya(Box::new(glossy.with_refraction(t, ior, limit)));
}

/// The index and `refractionLimit` of a layeredShader's layer material `m` of constant
/// transparency `t` when it refracts (as [`refraction_index`] decides for a shading
/// engine's material), else `None`.
fn layer_refraction(graph: &Graph, m: NodeId, t: Rgb) -> Option<(f32, u32)> {
    let mut r = Reader { graph, node: m, bindings: Vec::new(), warnings: Vec::new() };
    let ior = refraction_index(&mut r, t, true)?;
    Some((ior, r.scalar("refractionLimit", 6.0).max(0.0) as u32))
}

/// The classic highlight of the Maya material `family` (blinn, phong or phongE), read
/// with the classic shaders' defaults.
fn classic_highlight(family: &str, r: &mut Reader) -> ::maya::specular::Highlight {
    use ::maya::specular::Highlight;
    match family {
        "blinn" => Highlight::Blinn {
            eccentricity: r.scalar("eccentricity", 0.3),
            rolloff: r.scalar("specularRollOff", 0.7),
            reflection_rolloff: false,
        },
        "phong" => Highlight::Phong { power: r.scalar("cosinePower", 20.0) },
        _ => {
            let w = r.color("whiteness", Rgb::splat(0.5));
            Highlight::PhongE {
                roughness: r.scalar("roughness", 0.5),
                size: r.scalar("highlightSize", 0.5),
                whiteness: glam::Vec3A::new(w.x, w.y, w.z),
            }
        }
    }
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
    Some(translate(name, graph, node, true))
}

/// The Maya material `node` (a lambert, blinn, … node of `graph`) translated, with its
/// warnings prefixed by the material's `name`. `alone`: the material is a shading
/// engine's (the path engine lets rays through by its transparency, so its hits carry
/// what transparency does not fade divided by its coverage); not a layeredShader's
/// layer, whose transparency the layered shader mixes.
fn translate(name: &str, graph: &Graph, node: NodeId, alone: bool) -> (SurfaceMaterial, Vec<String>) {
    let material = graph.nodes[node as usize].decl.name.clone();
    let family = material.trim_start_matches("maya_").trim_start_matches("adskMaya").to_ascii_lowercase();
    let mut r = Reader { graph, node, bindings: Vec::new(), warnings: Vec::new() };
    let mut surface = SurfaceMaterial::lambert(name, Rgb::ZERO);
    match family.as_str() {
        "lambert" | "blinn" | "phong" | "phonge" | "anisotropic" => {
            let d = r.scalar("diffuse", 0.8);
            let reflective = family != "lambert";
            let t = r.color("transparency", Rgb::ZERO).clamp(Rgb::ZERO, Rgb::ONE);
            // Maya's raytraced refraction (`refractions` on, an index other than 1): the
            // rays that see the surface all hit it and refract through its BSDF by T
            // (no cut-out, nothing divided by a coverage); shadow rays still pass it as
            // a cut-out, filtered by T, as the classic shader filters them.
            let ior = refraction_index(&mut r, t, alone);
            let refracts = ior.is_some();
            cut_out(&mut surface, t, alone && reflective && !refracts);
            if connection(graph, node, "transparency").is_some() {
                r.warnings.push("'transparency' is connected; the path engine keeps the surface opaque".into());
            }
            // Transparency fades the diffuse part (and incandescence) by 1 − T per
            // channel where the path engine's hits, a share `opacity` of the rays, carry
            // (1 − T)/opacity of it (exact for a connected colour when T is grey).
            let fade = if refracts {
                Rgb::ONE - t
            } else if alone && surface.opacity > 0.0 {
                (Rgb::ONE - t) / surface.opacity
            } else {
                Rgb::ONE
            };
            if fade != Rgb::ONE && ["color", "incandescence"].iter().any(|p| connection(graph, node, p).is_some()) {
                r.warnings.push(
                    "a coloured 'transparency' on a connected colour or incandescence: the path engine fades them \
                     by its mean"
                        .into(),
                );
            }
            // A connected colour or incandescence takes the fade's mean in its binding.
            let mean = (fade.x + fade.y + fade.z) / 3.0;
            let shape = if mean > 0.0 { fade / mean } else { Rgb::ZERO };
            let albedo = r.driven("color", Target::Diffuse, d * mean, Rgb::splat(0.5)) * shape;
            surface.diffuse = albedo;
            // Ambient light goes by `color` alone: 1/d of the diffuse colour.
            surface.ambient = Rgb::splat(if d > 0.0 { 1.0 / d } else { 0.0 });
            surface.emission = r.driven("incandescence", Target::Emission, mean, Rgb::ZERO) * shape;
            ambient_color(&mut r, &mut surface, fade);
            irradiance_map(&mut r, &mut surface, albedo);
            let glow_intensity = r.scalar("glowIntensity", 0.0);
            if glow_intensity != 0.0 {
                surface.glow = r.driven("color", Target::Glow, glow_intensity, Rgb::splat(0.5));
            }
            // The highlight and the reflection are not faded: the hits carry them
            // whole over the share of rays that hit.
            let coverage = if alone && !refracts { surface.opacity.max(1e-3) } else { 1.0 };
            if let Some((bump, member)) = connection(graph, node, "normalCamera") {
                r.bindings.push(Binding { node: bump, member, target: Target::Normal, scale: 1.0 });
            }
            if reflective {
                let s = r.color("specularColor", Rgb::splat(0.5));
                // A connected specularColor: the lobe is built with 0.5 grey and tinted
                // per hit by twice the value (the classic highlight of volume lights with
                // emitSpecular too, through the hit BSDF's `tinted_by`).
                if let Some((spec, member)) = connection(graph, node, "specularColor") {
                    r.bindings.push(Binding { node: spec, member, target: Target::SpecularColor, scale: 2.0 });
                }
                let (glossy, rolloff) = if family == "anisotropic" {
                    (Some((anisotropic(&mut r, &mut surface), s)), None)
                } else {
                    let highlight = classic_highlight(&family, &mut r);
                    surface.maya_highlight = Some(MayaHighlight { model: highlight, color: s / coverage });
                    let rolloff = match highlight {
                        ::maya::specular::Highlight::Blinn { rolloff, .. }
                            if constant(graph, node, "reflectionRolloff").is_some_and(Value::bool) =>
                        {
                            Some(rolloff)
                        }
                        _ => None,
                    };
                    (glossy_shape(highlight, s), rolloff)
                };
                // The classic shader's traced mirror reflection, r·s ⊙ (reflectedColor +
                // what the ray finds) (with blinn's `reflectionRolloff`, × Schlick's
                // factor at N·V): a mirror lobe of weight r·s that emits reflectedColor by
                // its weight at each view and hit. It reflects while the path has made
                // fewer than `reflectionLimit` reflections (mirror, glossy), as the classic shader
                // traces its ray below that reflection level. (A layer's reflectedColor
                // is emitted as seen head-on: the layered shader mixes the layers'
                // emissions and keeps one lobe.)
                let reflectivity = r.scalar("reflectivity", 0.5).max(0.0);
                let reflected = r.color("reflectedColor", Rgb::ZERO);
                let limit = r.scalar("reflectionLimit", 1.0).max(0.0) as u32;
                if !alone {
                    surface.emission += s * reflectivity * rolloff.unwrap_or(1.0) * reflected;
                }
                if let Some((shape, tint)) = glossy {
                    surface.model = SurfaceModel::Maya(Box::new(
                        bsdf::MayaGlossy::new(shape, tint)
                            .with_mirror(s * reflectivity, rolloff)
                            .with_reflected(if alone { reflected } else { Rgb::ZERO })
                            .with_reflection_limit(limit)
                            .with_coverage(coverage),
                    ));
                }
            }
            translucence::translate(&mut r, &mut surface, fade);
            if let Some(ior) = ior {
                refract(&mut r, &mut surface, t, ior);
            }
        }
        "rampshader" => ramp_shader::translate(&mut r, &mut surface, alone),
        "layeredshader" => {
            let (layered, warnings) = layered_shader(name, graph, node);
            surface = layered;
            r.warnings.extend(warnings);
        }
        "surfaceshader" => {
            surface.emission = r.driven("outColor", Target::Emission, 1.0, Rgb::ZERO);
            surface.glow = r.driven("outGlowColor", Target::Glow, 1.0, Rgb::ZERO);
            let t = r.color("outTransparency", Rgb::ZERO).clamp(Rgb::ZERO, Rgb::ONE);
            cut_out(&mut surface, t, false);
        }
        "usebackground" => {
            surface.opacity = 0.0;
            let (mask, s, limit) = (
                r.scalar("shadowMask", 1.0),
                r.color("specularColor", Rgb::splat(0.5)),
                r.scalar("reflectionLimit", 1.0),
            );
            let mirror = s * r.scalar("reflectivity", 0.5).max(0.0);
            surface.maya_matte =
                Some(MayaMatte { shadow_mask: mask.clamp(0.0, 1.0), mirror, reflection_limit: limit.max(0.0) as u32 });
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
    (surface, warnings)
}

/// The glow of a layeredShader layer: its constant `glowColor`, or the constant glow of
/// the material whose `outGlowColor` it is connected to (zero otherwise).
fn layer_glow(graph: &Graph, glow: Option<Slot>) -> Rgb {
    match glow {
        Some(Slot::Value(v)) => rgb_of(&v),
        Some(Slot::Connect { node, .. })
            if graph.nodes[node as usize].decl.members().iter().any(|x| &**x == "outGlowColor") =>
        {
            translate("", graph, node, false).0.glow
        }
        _ => Rgb::ZERO,
    }
}

/// layeredShader (see the module doc): the layers of its `inputs` array mixed.
fn layered_shader(name: &str, graph: &Graph, node: NodeId) -> (SurfaceMaterial, Vec<String>) {
    let mut warnings = Vec::new();
    let mut surface = SurfaceMaterial::lambert(name, Rgb::ZERO);
    let texture = constant(graph, node, "compositingFlag").is_some_and(|v| v.int() == 1);
    let elements: &[Slot] = match slot(graph, node, "inputs") {
        Some(Slot::Array(e)) => e,
        Some(Slot::Value(Value::Array(_))) | None => &[],
        Some(_) => {
            warnings.push("'inputs' is connected as a whole; rendered grey".into());
            return (SurfaceMaterial::grey(name), warnings);
        }
    };
    let member = |e: &'_ Slot, m: &str| -> Option<Slot> {
        match e {
            Slot::Struct(members) => members.iter().find(|(n, _)| &**n == m).map(|(_, s)| s.clone()),
            _ => None,
        }
    };
    let layer_transparency = |e: &Slot| match member(e, "transparency") {
        Some(Slot::Value(v)) => rgb_of(&v).clamp(Rgb::ZERO, Rgb::ONE),
        Some(Slot::Connect { node: m, .. }) => {
            // A material's outTransparency: its own constant transparency (a
            // rampShader's ramp: its value at facing ratio 1, per channel).
            let c = match constant(graph, m, "transparency").or_else(|| constant(graph, m, "outTransparency")) {
                Some(v) if !matches!(v, Value::Array(_)) => rgb_of(v),
                _ if slot(graph, m, "transparency").is_some() => ramp_shader::transparency_at_one(graph, m)
                    .unwrap_or_else(|| Rgb::splat(1.0 - translate(name, graph, m, false).0.opacity)),
                _ => Rgb::ZERO,
            };
            c.clamp(Rgb::ZERO, Rgb::ONE)
        }
        _ => Rgb::ZERO,
    };
    let transparencies: Vec<Rgb> = elements.iter().map(layer_transparency).collect();
    // Each layer at the facing ratios k/32, for a stack whose rampShader layers' ramps
    // follow the view: transparency, diffuse colour, incandescence, plain colour.
    let mut by_view: Vec<view_layers::Layer> = Vec::new();
    let mut follows_view = false;
    // Every layer's translucence lobes by its share, and whether the stack needs them
    // held by the material (a focus past the BSDF's own lobes, or a layer that holds a
    // stack itself).
    let mut parts: Vec<bsdf::maya_highlight::translucent_stack::StackLobe> = Vec::new();
    let mut needs_stack = false;
    let mut through = Rgb::ONE;
    let mut lobe: Option<bsdf::MayaGlossy> = None;
    // What the shown layers reflect of ambient light, Σ w_i · diffuse_i ⊙ ambient_i
    // (plain colours take none).
    let mut ambient_color = Rgb::ZERO;
    // The first layer whose material refracts: P_k ⊙ T_k, its index and limit (the
    // layers below it do not show, as in the classic shader).
    let mut refraction: Option<(Rgb, f32, u32)> = None;
    // Each layer's translucence depth (0: none), for the stack's shadow rays.
    let mut depths = vec![0.0f32; elements.len()];
    // Each rampShader layer's transparency at the facing ratios k/32 where it follows the
    // view, for the stack's shadow rays.
    let mut view_transparencies: Vec<Option<Box<[Rgb; bsdf::maya_highlight::VIEW_RAMP_STEPS]>>> =
        vec![None; elements.len()];
    for (i, (e, &t)) in elements.iter().zip(&transparencies).enumerate() {
        surface.glow += through * layer_glow(graph, member(e, "glowColor"));
        // The layer's share per channel, P_i ⊙ (1 − T_i).
        let w = through * (Rgb::ONE - t);
        match member(e, "color") {
            Some(Slot::Connect { node: m, .. })
                if graph.nodes[m as usize].decl.members().iter().any(|x| &**x == "outTransparency") =>
            {
                let (layer, w_layer) = translate(name, graph, m, false);
                warnings.extend(w_layer);
                if !matches!(layer.varying, Varying::Constant) {
                    warnings.push(format!(
                        "layer '{}' varies over the surface; its constant colour is used",
                        graph.nodes[m as usize].name
                    ));
                }
                surface.diffuse += layer.diffuse * w;
                surface.emission += layer.emission * w;
                ambient_color += layer.diffuse * layer.ambient * w;
                let tables = view_layers::ramp_tables(graph, m);
                follows_view |= tables.is_some();
                view_transparencies[i] = tables.as_ref().map(|[t, _]| Box::new(*t));
                let mut by_layer = view_layers::Layer::material(t, layer.diffuse, layer.emission, tables);
                if let SurfaceModel::Maya(g) = &layer.model {
                    by_layer = by_layer.with_lobes(g);
                }
                by_view.push(by_layer);
                // Maya's highlight shows by the layer's share, as its diffuse colour (the
                // first layer's); every layer's translucence adds to the stack's by its
                // share, with its depth for the stack's shadow rays.
                if let SurfaceModel::Maya(g) = layer.model {
                    // (A translucent layer that does not show still passes shadow rays
                    // by its translucence depth, as in the classic stack.)
                    let translucent = g.translucence != Rgb::ZERO
                        || g.translucence_per_diffuse.is_some()
                        || g.translucence_stack.is_some();
                    let g = g.scaled(w);
                    if translucent {
                        depths[i] = layer.translucence_depth;
                    }
                    parts.extend(g.translucence_parts());
                    needs_stack |= g.translucence_stack.is_some();
                    lobe = Some(match lobe {
                        None => g,
                        Some(mut first) => {
                            // Each layer's translucence keeps its own focus: a lobe of its
                            // own beside the others (same focus: merged; a rampShader
                            // layer's light-angle shape mixed by albedo, each layer's ramp
                            // kept, exactly for any number of ramps). Past the BSDF's own
                            // lobes the stack's are held by the material (after the loop).
                            let mut merged =
                                first.add_translucence_interned(g.translucence, g.focus, g.light_angle).is_err();
                            for (a, n) in g.translucence_lobes().skip(1) {
                                merged |= first.add_translucence(a, n, None).is_err();
                            }
                            needs_stack |= merged;
                            first
                        }
                    });
                }
                if let Some((ior, limit)) = layer_refraction(graph, m, t) {
                    refraction = Some((through * t, ior, limit));
                    break;
                }
            }
            Some(Slot::Value(v)) => {
                // A plain colour: already weighted by its opacity in shader mode.
                let c = rgb_of(&v);
                surface.diffuse += if texture { c * w } else { c * through };
                by_view.push(view_layers::Layer::plain(t, c));
            }
            Some(_) => {
                warnings.push("a layer's colour is connected to a texture; the path engine leaves it out".into());
                by_view.push(view_layers::Layer::plain(t, Rgb::ZERO));
            }
            None => by_view.push(view_layers::Layer::plain(t, Rgb::ZERO)),
        }
        through *= t;
    }
    // Shadow rays pass the whole stack, filtered by every layer's transparency.
    cut_out(&mut surface, transparencies.iter().fold(Rgb::ONE, |p, t| p * *t), false);
    if depths.iter().any(|&d| d > 0.0) {
        surface.translucence_depth = depths.iter().fold(0.0f32, |m, &d| m.max(d));
        surface.translucence_layers = transparencies
            .iter()
            .zip(view_transparencies)
            .zip(depths)
            .map(|((&transparency, by_view), depth)| TranslucentLayer { transparency, by_view, depth })
            .collect();
    }
    // As a ratio of the stack's diffuse colour per channel (exact: the stack's colours
    // are constant).
    let ratio = |a: f32, d: f32| if d > 0.0 { a / d } else { 0.0 };
    surface.ambient = Rgb::new(
        ratio(ambient_color.x, surface.diffuse.x),
        ratio(ambient_color.y, surface.diffuse.y),
        ratio(ambient_color.z, surface.diffuse.z),
    );
    // The hits of a stack that rays pass by its transparency carry its colours divided
    // by its coverage (as a transparent lambert's, see `translate`).
    let coverage = if refraction.is_none() && surface.opacity > 0.0 { surface.opacity } else { 1.0 };
    surface.diffuse /= coverage;
    surface.emission /= coverage;
    if let (Some(g), true) = (&mut lobe, needs_stack) {
        // Every lobe exact, whatever their number (`bsdf::maya_highlight::translucent_stack`).
        *g = g.with_translucence_stack(bsdf::maya_highlight::translucent_stack::TranslucentStack::constant(parts));
    }
    if let Some(g) = lobe {
        // The translucence divided by the coverage as the diffuse colour is (the
        // highlight and the mirror by the lobe's coverage).
        let g = g.translucence_divided(coverage);
        surface.model = SurfaceModel::Maya(Box::new(g.with_coverage(coverage)));
    }
    if let Some((t, ior, limit)) = refraction {
        refract_within(&mut surface, t, ior, limit);
        if follows_view {
            // The layers down to the refracting one at each hit's facing ratio; shadow
            // rays also pass the layers below it (constant).
            let below = transparencies[by_view.len()..].iter().fold(Rgb::ONE, |p, t| p * *t);
            surface.view_transparency = Some(Box::new(view_layers::tabulate(&by_view, texture, below).refracting()));
        }
    } else if follows_view {
        surface.view_transparency = Some(Box::new(view_layers::tabulate(&by_view, texture, Rgb::ONE)));
    }
    (surface, warnings)
}
