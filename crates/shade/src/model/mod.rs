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
//! - [`tracer`]: the contract with the renderer's ray casting.
//! - [`volume`]: volume shaders on the segments rays travel (camera and material volumes).
//!
//! A shader implementation is a plain function registered by name ([`ShaderImpl`]); the
//! graph stores each node's parameters in the order the implementation lists them, so the
//! code reads parameter `i` directly whatever order a scene's own `declare` uses.

pub mod ctx;
pub mod decl;
pub mod fgcache;
pub mod graph;
pub mod lights;
pub mod photonmap;
pub mod precomputed;
pub mod shading;
pub mod state;
pub mod trace;
pub mod tracer;
pub mod value;
pub mod volume;

pub use ctx::Ctx;
pub use graph::{Graph, NodeId, Slot};
pub use shading::{MaterialShaders, Shading, ShadingOptions};
pub use state::{RayType, State};
pub use tracer::{Hit, Tracer, VertexData};
pub use value::{Color, Tag, Value};

/// What a shader does: reads parameters of node `node` through the context, writes its
/// result (which arrives holding the previous result of a shader list, or zero) and
/// returns whether it succeeded (mental ray's `miBoolean`).
pub type Run = fn(ctx: &mut Ctx, node: NodeId, result: &mut Value) -> bool;

/// A shader mira implements.
#[derive(Debug)]
pub struct ShaderImpl {
    /// The declared name (`mib_illum_phong`).
    pub name: &'static str,
    /// The parameters the code reads, in the order it indexes them.
    pub params: &'static [&'static str],
    /// The code.
    pub run: Run,
}

/// A registered implementation.
pub type Implementation = &'static ShaderImpl;

/// The implementation of the declared shader `name`, if mira has one.
pub fn implementation(name: &str) -> Option<Implementation> {
    let name = crate::material::declaration_name(name);
    crate::base::REGISTRY.iter().chain(crate::mdl::REGISTRY).copied().find(|s| s.name == name)
}

/// A phenomenon instance: runs the shader list at its `root` (its only parameter).
pub static PHENOMENON: ShaderImpl = ShaderImpl { name: "(phenomenon)", params: &["root"], run: phenomenon_root };

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
