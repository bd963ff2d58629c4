//! The mental ray shader model: shaders are code that reads a [`State`], evaluates its
//! parameters on demand through a [`Ctx`] (mental ray's `mi_eval`), loops over lights and
//! traces rays through a [`Tracer`].
//!
//! - [`decl`]: what a shader's parameters and result are (declarations).
//! - [`graph`]: every shader instance of a scene as a node whose parameters are constants or
//!   connections, phenomena expanded.
//! - [`ctx`]: lazy, cached evaluation of parameters; the ray-tracing and light-loop services
//!   shaders call.
//! - [`state`]: the shading point.
//! - [`lights`]: light lists, the light sample loop, shadows.
//! - [`trace`]: reflection, refraction, environment and final gather rays.
//! - [`fgcache`]: the final gather interpolation cache.
//! - [`photonmap`]: caustic and global illumination photon maps and their estimates.
//! - [`shading`]: a scene's shading compiled (graph, textures, materials, lights, options).
//! - [`sobol`]: the Owen-scrambled Sobol numbers shaders sample with; [`site`]: a sampling
//!   loop's numbers.
//! - [`tracer`]: the contract with the renderer's ray casting.
//! - [`volume`]: volume shaders on the segments rays travel (camera and material volumes);
//!   [`inscatter`]: the light a material's participating medium scatters into them.
//! - [`photon`]: how surfaces scatter photons.
//! - [`registry`]: the libraries that implement shaders ([`Library`], [`Registry`]).
//! - [`texture`]: image textures and their pyramids; [`light`]: light shapes and profiles.
//!
//! A shader implementation is a plain function registered by name ([`ShaderImpl`]); the
//! graph stores each node's parameters in the order the implementation lists them, so the
//! code reads parameter `i` directly whatever order a scene's own `declare` uses.

pub mod ctx;
pub mod decl;
pub mod fgcache;
pub mod graph;
pub mod inscatter;
pub mod light;
pub mod light_list;
pub mod lights;
pub mod media_chain;
pub mod photon;
pub mod photonmap;
pub mod precomputed;
pub mod registry;
pub mod shading;
pub mod shutter;
pub mod simd;
pub mod site;
pub mod sobol;
pub mod state;
pub mod texture;
pub mod trace;
pub mod tracer;
pub mod user_data;
pub mod value;
pub mod volume;

pub use ctx::Ctx;
pub use graph::{Graph, NodeId, Slot};
pub use registry::{Library, Registry};
pub use shading::{MaterialShaders, Shading, ShadingOptions};
pub use state::{RayType, State};
pub use tracer::{Hit, NoScene, ShadowQuery, SurfaceScatter, Tracer, VertexData};
pub use value::{Color, Tag, Value};

/// What a shader does: reads parameters of node `node` through the context, writes its
/// result (which arrives holding the previous result of a shader list, or zero) and
/// returns whether it succeeded (mental ray's `miBoolean`).
pub type Run = fn(ctx: &mut Ctx, node: NodeId, result: &mut Value) -> bool;

/// How a shader scatters photons at the state's hit, as a photon shader or as a material
/// shader without one (see [`photon`]).
pub type PhotonRun = fn(ctx: &mut Ctx, node: NodeId) -> photon::Scatter;

/// What a volume shader whose effect is affine in the colour it receives (a fog) does to
/// the segment the context's state describes, as [`volume::VolumeTerms`]: what the path
/// engine applies to its segments (see [`Ctx::volume_terms`]).
pub type VolumeTermsRun = fn(ctx: &mut Ctx, node: NodeId) -> volume::VolumeTerms;

/// Whether node `node` of a shader with [`ShaderImpl::volume_terms`] is affine in
/// `shading` (see [`ShaderImpl::volume_affine`]).
pub type VolumeAffine = fn(shading: &Shading, node: NodeId) -> bool;

/// Reads a light shader's constant parameters from its node's slots (see
/// [`ShaderImpl::simple_light`]).
pub type SimpleLightRead = fn(slots: &[Slot]) -> Option<light::SimpleLight>;

/// A shader mira implements.
#[derive(Debug)]
pub struct ShaderImpl {
    /// The declared name (`mib_illum_phong`).
    pub name: &'static str,
    /// The parameters the code reads, in the order it indexes them.
    pub params: &'static [&'static str],
    /// The code.
    pub run: Run,
    /// How it scatters photons; `None`: photons are absorbed.
    pub photon: Option<PhotonRun>,
    /// A light shader of a portal: final gather rays that cross the light's shape find
    /// nothing, the light brings what lies beyond in directly (`mia_portal_light`).
    pub portal: bool,
    /// For a volume shader that turns the colour c it receives into keep ⊙ c + add (per
    /// channel, the same for every c): those terms over the state's segment. `None`: the
    /// shader is no such volume.
    pub volume_terms: Option<VolumeTermsRun>,
    /// For a shader with `volume_terms` whose effect is affine only for some of its
    /// connections (Maya's volume sampler: affine over a fog or a volume material, not
    /// over a mental ray volume shader it runs): whether the node is affine in the compiled
    /// shading. `None`: always.
    pub volume_affine: Option<VolumeAffine>,
    /// For a light shader whose result is a constant colour, optionally ramped over
    /// distance, through shadows ([`light::SimpleLight`]): that light read from a node's
    /// parameter slots, `None` where a parameter is not a constant. The light loop then
    /// evaluates the light in place of calling the shader per sample. `None`: no such
    /// shader.
    pub simple_light: Option<SimpleLightRead>,
}

impl ShaderImpl {
    /// The defaults of the optional behaviours (no photon scattering, not a portal, no
    /// affine volume terms), for `ShaderImpl { name, params, run, ..ShaderImpl::PLAIN }`.
    pub const PLAIN: ShaderImpl = ShaderImpl {
        name: "",
        params: &[],
        run: |_, _, _| false,
        photon: None,
        portal: false,
        volume_terms: None,
        volume_affine: None,
        simple_light: None,
    };
}

/// A registered implementation.
pub type Implementation = &'static ShaderImpl;

/// A phenomenon instance: runs the shader list at its `root` (its only parameter).
pub static PHENOMENON: ShaderImpl =
    ShaderImpl { name: "(phenomenon)", params: &["root"], run: phenomenon_root, ..ShaderImpl::PLAIN };

fn phenomenon_root(ctx: &mut Ctx, node: NodeId, result: &mut Value) -> bool {
    match ctx.shading().graph.nodes[node as usize].slots.first() {
        Some(Slot::Connect { node: root, member: None }) => ctx.run_list(*root, result),
        Some(_) => {
            *result = ctx.eval(node, 0);
            true
        }
        None => false,
    }
}

/// RGB of a colour.
#[inline]
pub fn rgb(c: Color) -> glam::Vec3A {
    glam::Vec3A::new(c.x, c.y, c.z)
}

/// A colour from RGB and alpha.
#[inline]
pub fn rgba(c: glam::Vec3A, a: f32) -> Color {
    Color::new(c.x, c.y, c.z, a)
}

/// Whether all four components are zero.
#[inline]
pub fn is_zero(c: Color) -> bool {
    c == Color::ZERO
}

/// Whether all four components are one.
#[inline]
pub fn is_one(c: Color) -> bool {
    c == Color::ONE
}
