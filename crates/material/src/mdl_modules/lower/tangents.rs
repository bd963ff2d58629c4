//! The `tangent_u`s of a tree's anisotropic microfacet lobes: the first is the shading
//! frame's u axis (the hit's tangent); a lobe whose `tangent_u` differs gets an own frame
//! turned to it about the shading normal ([`bsdf::LobeSum::add_tangent`]) or, inside a
//! layer with its own `normal`, about that normal ([`bsdf::LobeSum::add_tangent_in`]: its
//! x axis the tangent made orthogonal to the layer's normal).

use crate::mdl_modules::value::{Df, Leaf};

/// Calls `f` with the `tangent_u` of every anisotropic microfacet lobe of a tree, in
/// order.
fn visit(df: &Df, f: &mut impl FnMut(Leaf)) {
    match df {
        Df::Glossy { tangent, .. } | Df::Ward { tangent, .. } | Df::Backscatter { tangent, .. } => {
            if let Some(t) = tangent {
                f(*t)
            }
        }
        Df::Black | Df::Diffuse { .. } | Df::DiffuseTransmission(_) | Df::Specular { .. } | Df::Measured { .. } => {}
        Df::Sheen { multiscatter: b, .. }
        | Df::DirectionalFactor { base: b, .. }
        | Df::ThinFilm { base: b, .. }
        | Df::FresnelFactor { base: b, .. }
        | Df::MeasuredCurveFactor { base: b, .. }
        | Df::MeasuredFactor { base: b, .. } => visit(b, f),
        Df::Mix { parts, .. } => parts.iter().for_each(|(_, d)| visit(d, f)),
        Df::Layer { layer, base, .. }
        | Df::CurveLayer { layer, base, .. }
        | Df::MeasuredCurveLayer { layer, base, .. } => {
            visit(layer, f);
            visit(base, f);
        }
    }
}

/// The first anisotropic lobe's `tangent_u` (the shading frame's axis), if any.
pub(super) fn first(df: &Df) -> Option<Leaf> {
    let mut first = None;
    visit(df, &mut |t| {
        first.get_or_insert(t);
    });
    first
}

/// Whether a lobe's `tangent_u` differs from the first's.
pub(super) fn differ(df: &Df) -> bool {
    let (mut first, mut differ) = (None, false);
    visit(df, &mut |t| differ |= *first.get_or_insert(t) != t);
    differ
}
