//! Material parameters driven by shaders, evaluated at each hit of the path engine.
//!
//! A material whose parameters are connected (to MDL `::base` textures, mental ray
//! texture shaders, bump or normal maps) keeps, besides its constant model, the list of
//! what drives what ([`Varying`]). At a hit the integrator describes the point as a shader
//! [`State`](shader::State) and calls [`SurfaceMaterial::at`], which runs the
//! connected shaders through the shader graph (lazily and cached, as in the classic
//! engine) and returns the material at that point ([`HitMaterial`]).

use std::borrow::Cow;
use std::sync::Arc;

use glam::Vec3A;

use super::{SurfaceMaterial, SurfaceModel};
use bsdf::Rgb;
use bsdf::{Unified, UnifiedParams};
use mia::params::{Mia, P};
use shader::{Ctx, Graph, NodeId, Slot, Tag, Value};

/// What a connected parameter drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The diffuse colour (Lambert, Oren–Nayar; also what the classic stand-in shows).
    Diffuse,
    /// Oren–Nayar roughness σ (radians).
    DiffuseRoughness,
    /// The unified material's base colour.
    BaseColor,
    /// The unified material's transmission colour.
    TransmissionColor,
    /// The unified material's metal edge tint.
    EdgeTint,
    /// Emitted radiance (the binding's scale converts MDL's units).
    Emission,
    /// Unified `metallic`.
    Metallic,
    /// Unified `roughness`.
    Roughness,
    /// Unified `anisotropic`.
    Anisotropic,
    /// Unified `spec_trans`.
    SpecTrans,
    /// Unified `ior`.
    Ior,
    /// Unified `specular`.
    Specular,
    /// Unified `specular_tint`.
    SpecularTint,
    /// Unified `sheen`.
    Sheen,
    /// Unified `sheen_tint`.
    SheenTint,
    /// Unified `clearcoat`.
    Clearcoat,
    /// Unified `clearcoat_gloss`.
    ClearcoatGloss,
    /// Coverage (cutouts): 1 solid, 0 absent.
    Opacity,
    /// A world-space shading normal (MDL normal and bump maps).
    Normal,
    /// A mental ray bump shader, run for its change of the state's normal.
    Bump,
    /// The glow a camera sees (Maya's `outGlowColor`; the binding's scale is the
    /// material's `glowIntensity`).
    Glow,
    /// Light from an illumination map (Maya's `irradiance`, in Maya's light units): the
    /// hit's diffuse colour ⊙ the value × the scale (`irradianceColor`) is added to its
    /// emission. Bind it after the diffuse colour and the emission.
    IrradianceMap,
    /// [`Target::IrradianceMap`] for one channel (0 red, 1 green, 2 blue): that channel
    /// of the hit's diffuse colour × the value's × the scale (that channel of a
    /// non-grey `irradianceColor`) is added to the emission's.
    IrradianceMapChannel(u8),
    /// One channel (0 red, 1 green, 2 blue) of the value × the scale added to that of the
    /// emission (a Maya material's `ambientColor` ⊙ a connected `color`, or a connected
    /// `ambientColor` ⊙ a constant `color`). Bind it after the emission.
    EmissionChannel(u8),
    /// A Maya material's `specularColor`: its highlight's tint and its mirror's weight
    /// (a [`SurfaceModel::Maya`] built with the colour 1/scale) are multiplied by the
    /// value × the scale per channel.
    SpecularColor,
    /// The direction the BSDF's local x axis follows (world space; mental ray's
    /// `mib_glossy_*` `u_axis` connected to a shader): projected onto the plane of the
    /// normal at the hit, as the classic shaders build their frame; a zero (or normal)
    /// value leaves the material's own tangent rule.
    TangentAxis,
    /// A Maya material's `translucence` t (the value as a number, as the classic engine
    /// reads it: a colour's red): the Maya model's translucence — its albedo, or its share
    /// of each hit's diffuse colour — is multiplied by the value × the scale (the model
    /// built with [`crate::maya::CONNECTED_STAND_IN`], the scale its inverse). Bind it
    /// after [`Target::TranslucenceColor`].
    Translucence,
    /// A Maya material's connected `color` where `diffuse` is 0: the Maya model's
    /// translucence albedo is the value × the scale (t ⊙ the fade's mean) per channel.
    TranslucenceColor,
}

/// One connected parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Binding {
    /// The shader node whose result drives it.
    pub node: NodeId,
    /// The member of a struct result (`"tex.tint"`); `None`: the whole result.
    pub member: Option<Arc<str>>,
    /// What it drives.
    pub target: Target,
    /// A factor on the value (the mapping's own scale, such as MDL emission units).
    pub scale: f32,
}

/// What of a material varies over its surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Varying {
    /// Nothing: the constant model is the material everywhere.
    #[default]
    Constant,
    /// Connected parameters.
    Bindings(Vec<Binding>),
    /// A `mia_material` node with connections: all its parameters are read per hit, its
    /// bump shaders run, as the classic engine does.
    Mia {
        /// The `mia_material` node.
        node: NodeId,
        /// A passthrough bump shader before it in the material's shader list.
        bump: Option<NodeId>,
    },
    /// A material that evaluates itself at each hit (an MDL module material whose
    /// expressions depend on the shading point: lowered again from their values).
    Evaluated(Evaluated),
}

/// A material's own evaluation at each hit, without the shader graph.
pub trait HitEvaluator: std::fmt::Debug + Send + Sync {
    /// Sets what of `hit` (the material's constants) varies, at the shading point `state`.
    fn apply(&self, state: &shader::State, hit: &mut HitMaterial<'_>);
    /// Whether its opacity may be below 1 somewhere.
    fn may_cut_out(&self) -> bool;
    /// The evaluator with its emission scaled by `scale` (an emission given for the
    /// whole surface divided by its area), if its emission varies; `None`: nothing to scale.
    fn with_emission_scaled(&self, _scale: f32) -> Option<Arc<dyn HitEvaluator>> {
        None
    }
}

/// A shared [`HitEvaluator`] (equal only to itself).
#[derive(Clone, Debug)]
pub struct Evaluated(pub Arc<dyn HitEvaluator>);

impl PartialEq for Evaluated {
    fn eq(&self, other: &Evaluated) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// A participating medium that depends on the shading point (an MDL volume whose
/// coefficients, weights or biases vary over the surface): a medium is homogeneous inside
/// its object, so it is evaluated where a path enters the object.
pub trait MediumEvaluator: std::fmt::Debug + Send + Sync {
    /// The medium at the shading point `state` (the surface point a path enters through).
    fn medium(&self, state: &shader::State) -> bsdf::Medium;
}

/// A shared [`MediumEvaluator`] (equal only to itself).
#[derive(Clone, Debug)]
pub struct VaryingMedium(pub Arc<dyn MediumEvaluator>);

impl PartialEq for VaryingMedium {
    fn eq(&self, other: &VaryingMedium) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// A material at one shading point (borrowing the material's model where nothing varies).
#[derive(Clone, Debug, PartialEq)]
pub struct HitMaterial<'a> {
    /// Diffuse colour.
    pub diffuse: Rgb,
    /// Emitted radiance (towards the normal for a spot: see `emission_shape`).
    pub emission: Rgb,
    /// The directional spread of the emission, if not Lambertian (the material's own,
    /// borrowed; owned where it varies over the surface: a mix of edfs whose weights
    /// depend on the hit).
    pub emission_shape: Option<Cow<'a, crate::edf::EmissionShape>>,
    /// The scattering model with the point's parameters.
    pub model: Cow<'a, SurfaceModel>,
    /// Coverage.
    pub opacity: f32,
    /// What a ray that passes the surface is multiplied by, per channel (see
    /// [`SurfaceMaterial::cutout_tint`]).
    pub cutout_tint: Rgb,
    /// The shading normal the material asks for (world space, unit), if it bends it.
    pub normal: Option<Vec3A>,
    /// The direction (world space, unit, in the tangent plane of the state's normal) the
    /// BSDF's local x axis follows, for anisotropic lobes; `None`: any tangent.
    pub tangent: Option<Vec3A>,
    /// The glow a camera sees at the point (see [`SurfaceMaterial::glow`]).
    pub glow: Rgb,
}

/// A value as a colour: a `texture_return` struct gives its `tint`.
fn as_rgb(v: &Value) -> Rgb {
    let c = v.member("tint").unwrap_or(v).color();
    Rgb::new(c.x, c.y, c.z)
}

/// A value as a number: a `texture_return` struct gives its `mono`, a colour its average.
fn as_scalar(v: &Value) -> f32 {
    match v.member("mono").unwrap_or(v) {
        Value::Color(c) => (c.x + c.y + c.z) / 3.0,
        other => other.scalar(),
    }
}

/// Finds the shaders of a material's shader list (starting at `head`) that the path
/// engine evaluates per hit: a `mia_material` with connected parameters (and a passthrough
/// bump shader before it), or a passthrough bump shader before another shader.
pub(super) fn bind_material_shaders(surface: &mut SurfaceMaterial, graph: &Graph, head: NodeId) {
    let mut bump = None;
    let mut node = Some(head);
    let mut guard = 0;
    while let Some(n) = node {
        let entry = &graph.nodes[n as usize];
        let name = entry.imp.map_or("", |i| i.name);
        if name == "mib_passthrough_bump_map" {
            bump = Some(n);
        } else if name.starts_with("mia_material") {
            let connected = entry.slots.iter().enumerate().any(|(i, s)| {
                matches!(s, Slot::Connect { .. } | Slot::Array(_) | Slot::Struct(_))
                    || (i == P::Bump as usize && matches!(s, Slot::Value(Value::Tag(Tag::Shader(_)))))
                    || (i == P::OverallBump as usize || i == P::StandardBump as usize)
                        && matches!(s, Slot::Value(Value::Vector(v)) if *v != Vec3A::ZERO)
            });
            if connected || bump.is_some() {
                surface.varying = Varying::Mia { node: n, bump };
            }
            return;
        }
        guard += 1;
        node = entry.next.filter(|_| guard < 64);
    }
    if let Some(b) = bump {
        let binding = Binding { node: b, member: None, target: Target::Bump, scale: 1.0 };
        match &mut surface.varying {
            Varying::Bindings(list) => list.insert(0, binding),
            other => *other = Varying::Bindings(vec![binding]),
        }
    }
}

impl SurfaceMaterial {
    /// Whether anything of the material varies over its surface.
    #[inline]
    pub fn is_varying(&self) -> bool {
        self.varying != Varying::Constant || self.tangent_angle.is_some() || self.tangent_axis.is_some()
    }

    /// The material with its constant parameters (what it is where nothing varies).
    #[inline]
    pub fn constant(&self) -> HitMaterial<'_> {
        HitMaterial {
            diffuse: self.diffuse,
            emission: self.emission,
            emission_shape: self.emission_shape.as_ref().map(Cow::Borrowed),
            model: Cow::Borrowed(&self.model),
            opacity: self.opacity,
            cutout_tint: self.cutout_tint,
            normal: None,
            tangent: None,
            glow: self.glow,
        }
    }

    /// Whether rays may pass through the material somewhere (a constant opacity below 1,
    /// or an opacity driven by a shader of `graph`).
    pub fn may_cut_out(&self, graph: Option<&Graph>) -> bool {
        self.opacity < 1.0
            || self.view_transparency.is_some()
            || match &self.varying {
                Varying::Constant => false,
                Varying::Bindings(b) => b.iter().any(|b| b.target == Target::Opacity),
                Varying::Evaluated(e) => e.0.may_cut_out(),
                Varying::Mia { node, .. } => graph.is_some_and(|g| {
                    matches!(g.nodes[*node as usize].slots.get(P::CutoutOpacity as usize), Some(Slot::Connect { .. }))
                }),
            }
    }

    /// The material at the shading point `ctx.state` (its normal facing the viewer, its
    /// texture coordinates and derivatives filled in), running the connected shaders.
    pub fn at(&self, ctx: &mut Ctx) -> HitMaterial<'_> {
        let mut hit = self.constant();
        match &self.varying {
            Varying::Constant => {}
            Varying::Bindings(bindings) => self.apply(bindings, ctx, &mut hit),
            Varying::Evaluated(e) => e.0.apply(&ctx.state, &mut hit),
            Varying::Mia { node, bump } => {
                let unbumped = ctx.state.normal;
                if let Some(b) = bump {
                    let mut ignored = Value::Null;
                    ctx.call(*b, &mut ignored);
                }
                let mia = Mia::read(ctx, *node);
                let refr_gloss = ctx.scalar(*node, P::RefrGloss as usize);
                let extended = ctx.node(*node).imp.is_some_and(|i| i.name != "mia_material");
                mia::material::bump(ctx, *node, extended);
                hit.opacity = ctx.scalar(*node, P::CutoutOpacity as usize);
                hit.diffuse = mia.diffuse;
                hit.model = Cow::Owned(SurfaceModel::Mia(Box::new((mia, refr_gloss))));
                if ctx.state.normal != unbumped {
                    hit.normal = Some(ctx.state.normal);
                }
            }
        }
        if hit.tangent.is_none() {
            hit.tangent = self.tangent_at(ctx.state.normal, ctx.state.derivs[0]);
        }
        hit
    }

    /// The BSDF's local x axis (world space) at a hit of shading normal `normal` and
    /// surface derivative `dpdu` (dP/du of the first texture space): the projected
    /// `tangent_axis` where given, else `dpdu` turned by `tangent_angle` (the rule is
    /// Maya's, its anisotropic material's grooves); `None` where neither is set.
    pub fn tangent_at(&self, normal: Vec3A, dpdu: Vec3A) -> Option<Vec3A> {
        if let Some(axis) = self.tangent_axis {
            // As the classic `mib_glossy_*` shaders build their frame.
            return Some(
                (axis - normal * axis.dot(normal))
                    .try_normalize()
                    .unwrap_or_else(|| bsdf::Frame::from_normal(normal).tangent),
            );
        }
        self.tangent_angle.map(|angle| ::maya::specular::groove_direction(normal, dpdu, angle))
    }

    fn apply(&self, bindings: &[Binding], ctx: &mut Ctx, hit: &mut HitMaterial<'_>) {
        let mut unified: Option<UnifiedParams> = match &self.model {
            SurfaceModel::Unified(u) => Some(*u.params()),
            _ => None,
        };
        let unbumped = ctx.state.normal;
        for b in bindings {
            let result = ctx.result(b.node);
            let value = match &b.member {
                Some(m) => result.member(m).cloned().unwrap_or(Value::Null),
                None => result,
            };
            let rgb = || as_rgb(&value) * b.scale;
            let num = || as_scalar(&value) * b.scale;
            let set = |f: &mut dyn FnMut(&mut UnifiedParams), u: &mut Option<UnifiedParams>| {
                if let Some(p) = u {
                    f(p);
                }
            };
            match b.target {
                Target::Diffuse => hit.diffuse = rgb(),
                Target::DiffuseRoughness => {
                    if let SurfaceModel::OrenNayar(_) = *hit.model {
                        hit.model = Cow::Owned(SurfaceModel::OrenNayar(num()));
                    }
                }
                Target::Emission => hit.emission = rgb(),
                Target::Glow => hit.glow = rgb(),
                Target::IrradianceMap => hit.emission += hit.diffuse * rgb(),
                Target::IrradianceMapChannel(c) => {
                    let c = usize::from(c.min(2));
                    hit.emission[c] += hit.diffuse[c] * rgb()[c];
                }
                Target::EmissionChannel(c) => {
                    let c = usize::from(c.min(2));
                    hit.emission[c] += rgb()[c];
                }
                Target::Opacity => hit.opacity = num().clamp(0.0, 1.0),
                Target::SpecularColor => {
                    let tinted = match &*hit.model {
                        SurfaceModel::Maya(g) => Some(g.tinted(rgb())),
                        _ => None,
                    };
                    if let Some(g) = tinted {
                        hit.model = Cow::Owned(SurfaceModel::Maya(Box::new(g)));
                    }
                }
                Target::TangentAxis => {
                    let (axis, n) = (value.vector() * b.scale, ctx.state.normal);
                    hit.tangent = (axis - n * axis.dot(n)).try_normalize();
                }
                Target::Translucence | Target::TranslucenceColor => {
                    let lit = match &*hit.model {
                        SurfaceModel::Maya(g) if b.target == Target::Translucence => {
                            Some(g.translucence_scaled((value.scalar() * b.scale).max(0.0)))
                        }
                        SurfaceModel::Maya(g) => Some(g.with_translucence(rgb(), g.focus)),
                        _ => None,
                    };
                    if let Some(g) = lit {
                        hit.model = Cow::Owned(SurfaceModel::Maya(Box::new(g)));
                    }
                }
                Target::Normal => {
                    let n = value.vector();
                    if n.length_squared() > 0.0 {
                        hit.normal = Some(n.normalize());
                    }
                }
                Target::Bump => {
                    if ctx.state.normal != unbumped {
                        hit.normal = Some(ctx.state.normal);
                    } else if let Value::Vector(n) = value {
                        if n.length_squared() > 0.0 && n.normalize() != unbumped {
                            hit.normal = Some(n.normalize());
                        }
                    }
                }
                Target::BaseColor => {
                    let c = rgb();
                    set(&mut |p| p.base_color = c, &mut unified);
                    if unified.is_none() {
                        hit.diffuse = c;
                    }
                }
                Target::TransmissionColor => set(&mut |p| p.transmission_color = Some(rgb()), &mut unified),
                Target::EdgeTint => set(&mut |p| p.edge_tint = Some(rgb()), &mut unified),
                Target::Metallic => set(&mut |p| p.metallic = num(), &mut unified),
                Target::Roughness => set(&mut |p| p.roughness = num(), &mut unified),
                Target::Anisotropic => set(&mut |p| p.anisotropic = num(), &mut unified),
                Target::SpecTrans => set(&mut |p| p.spec_trans = num(), &mut unified),
                Target::Ior => set(&mut |p| p.ior = num(), &mut unified),
                Target::Specular => set(&mut |p| p.specular = num(), &mut unified),
                Target::SpecularTint => set(&mut |p| p.specular_tint = num(), &mut unified),
                Target::Sheen => set(&mut |p| p.sheen = num(), &mut unified),
                Target::SheenTint => set(&mut |p| p.sheen_tint = num(), &mut unified),
                Target::Clearcoat => set(&mut |p| p.clearcoat = num(), &mut unified),
                Target::ClearcoatGloss => set(&mut |p| p.clearcoat_gloss = num(), &mut unified),
            }
        }
        if let (Some(p), SurfaceModel::Unified(u)) = (unified, &self.model) {
            if p != *u.params() {
                hit.model = Cow::Owned(SurfaceModel::Unified(Box::new(Unified::new(&p))));
            }
        }
    }
}
