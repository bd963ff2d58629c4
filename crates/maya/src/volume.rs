//! The shading group's volume shader: `maya_volumesampler` / `adskMayaVolumeSampler`.
//!
//! Exports put it in a material's `volume` slot with its one parameter `volumeShader`
//! connected to the volume material of Maya's shading group (`"volumeShader" =
//! "fog1.outColor"`). It runs as a mental ray volume shader ([`shader::volume`]): the
//! result arrives holding the colour the ray brought back over the segment from
//! `state.org` to `state.point`, and leaves holding what reaches the ray's origin.
//!
//! What it does with the connected node:
//! - a node whose result is Maya's output struct (`outColor`, `outTransparency`, as
//!   Maya's volume materials give them): the struct is the whole segment's, so the
//!   colour behind passes in proportion to `outTransparency` T and the volume's own
//!   colour is added, already weighted by its opacity as Maya's `outColor` is:
//!   result = behind ⊙ T + outColor; light and shadow rays keep light ⊙ T;
//! - any other node (a mental ray volume shader such as `mib_volume` or `parti_volume`,
//!   connected directly): called as the volume shader itself, on the same result;
//! - nothing connected (a volume node no library declares was dropped, with the shader
//!   model's warning naming its line): the ray passes unchanged.
//!
//! Over a volume material or a fog the sampler's effect is affine in the colour behind
//! (keep T, add `outColor`; the fog's own terms), and it tells those terms to the path
//! engine ([`shader::ShaderImpl::volume_terms`]); over a mental ray volume shader it is
//! not ([`shader::ShaderImpl::volume_affine`]).

use glam::Vec3A;
use shader::volume::VolumeTerms;
use shader::{Ctx, NodeId, RayType, Shading, Slot, Value};

use crate::values::{member_color, rgb, rgba};

/// The shading group's volume shader (see the module doc).
pub static VOLUMESAMPLER: shader::ShaderImpl = shader::ShaderImpl {
    name: "maya_volumesampler",
    params: &["volumeShader"],
    run: volume_sampler,
    volume_terms: Some(sampler_terms),
    volume_affine: Some(sampler_is_affine),
    ..shader::ShaderImpl::PLAIN
};

/// The shading group's volume shader (see the module doc).
pub static ADSK_VOLUMESAMPLER: shader::ShaderImpl = shader::ShaderImpl {
    name: "adskMayaVolumeSampler",
    params: &["volumeShader"],
    run: volume_sampler,
    volume_terms: Some(sampler_terms),
    volume_affine: Some(sampler_is_affine),
    ..shader::ShaderImpl::PLAIN
};

/// What the sampler's `volumeShader` is connected to.
enum Source {
    /// Nothing: the ray passes unchanged.
    None,
    /// A node with Maya's volume output struct.
    Material(NodeId),
    /// A mental ray volume shader, run on the result.
    Volume(NodeId),
}

fn source(graph: &shader::Graph, n: NodeId) -> Source {
    let Some(Slot::Connect { node: source, .. }) = graph.nodes[n as usize].slots.first() else { return Source::None };
    let source = *source;
    if graph.nodes[source as usize].decl.members().iter().any(|m| &**m == "outTransparency") {
        Source::Material(source)
    } else {
        Source::Volume(source)
    }
}

/// The sampler is affine over nothing, a volume material, or a fog whose terms are its
/// own (a shader with [`shader::ShaderImpl::volume_terms`] that is always affine).
fn sampler_is_affine(shading: &Shading, n: NodeId) -> bool {
    match source(&shading.graph, n) {
        Source::None | Source::Material(_) => true,
        Source::Volume(v) => shading.graph.nodes[v as usize]
            .imp
            .is_some_and(|imp| imp.volume_terms.is_some() && imp.volume_affine.is_none()),
    }
}

/// The volume material `source`'s effect over the state's segment: keep its
/// `outTransparency` T (clamped to [0, 1]); add its `outColor` except on light and shadow
/// rays.
fn material_terms(ctx: &mut Ctx, source: NodeId) -> VolumeTerms {
    let material = ctx.result(source);
    let t = member_color(&material, "outTransparency").map_or(Vec3A::ZERO, rgb).clamp(Vec3A::ZERO, Vec3A::ONE);
    let add = if matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow) {
        Vec3A::ZERO
    } else {
        member_color(&material, "outColor").map_or(Vec3A::ZERO, rgb)
    };
    VolumeTerms { keep: t, add }
}

fn sampler_terms(ctx: &mut Ctx, n: NodeId) -> VolumeTerms {
    match source(&ctx.shading().graph, n) {
        Source::None => VolumeTerms::NONE,
        Source::Material(m) => material_terms(ctx, m),
        Source::Volume(v) => match ctx.node(v).imp.and_then(|imp| imp.volume_terms) {
            Some(run) => run(ctx, v),
            None => VolumeTerms::NONE,
        },
    }
}

fn volume_sampler(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let source = match source(&ctx.shading().graph, n) {
        Source::None => return true,
        Source::Volume(v) => {
            // A volume shader of mental ray's own contract: it works on the result itself.
            let mut result = out.clone();
            if ctx.call(v, &mut result) {
                *out = result;
            }
            return true;
        }
        Source::Material(m) => m,
    };
    let terms = material_terms(ctx, source);
    let behind = out.color();
    let coverage = if matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow) {
        0.0
    } else {
        1.0 - (terms.keep.x + terms.keep.y + terms.keep.z) / 3.0
    };
    *out = Value::Color(rgba(terms.apply(rgb(behind)), behind.w + (1.0 - behind.w) * coverage));
    true
}
