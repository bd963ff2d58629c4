//! The `tangent_u`s of a tree's anisotropic microfacet lobes: the first is the shading
//! frame's u axis (the hit's tangent); a lobe whose `tangent_u` differs gets an own frame
//! turned about the shading normal to it ([`bsdf::LobeSum::add_tangent`]) — except inside
//! a layer with its own `normal`, whose frame it keeps (its u axis the shading frame's laid
//! into that layer's tangent plane: a warning).

use crate::mdl_modules::value::{Df, Leaf};

/// Calls `f` with the `tangent_u` of every anisotropic microfacet lobe of a tree, in
/// order, and whether the lobe lies inside a layer with its own normal.
pub(super) fn visit(df: &Df, in_own_normal: bool, f: &mut impl FnMut(Leaf, bool)) {
    match df {
        Df::Glossy { tangent, .. } | Df::Ward { tangent, .. } | Df::Backscatter { tangent, .. } => {
            if let Some(t) = tangent {
                f(*t, in_own_normal)
            }
        }
        Df::Black | Df::Diffuse { .. } | Df::DiffuseTransmission(_) | Df::Specular { .. } | Df::Measured { .. } => {}
        Df::Sheen { multiscatter: b, .. }
        | Df::DirectionalFactor { base: b, .. }
        | Df::ThinFilm { base: b, .. }
        | Df::FresnelFactor { base: b, .. }
        | Df::MeasuredCurveFactor { base: b, .. }
        | Df::MeasuredFactor { base: b, .. } => visit(b, in_own_normal, f),
        Df::Mix { parts, .. } => parts.iter().for_each(|(_, d)| visit(d, in_own_normal, f)),
        Df::Layer { layer, base, layer_normal, .. }
        | Df::CurveLayer { layer, base, layer_normal, .. }
        | Df::MeasuredCurveLayer { layer, base, layer_normal, .. } => {
            visit(layer, in_own_normal || layer_normal.is_some(), f);
            visit(base, in_own_normal, f);
        }
    }
}

/// The first anisotropic lobe's `tangent_u` (the shading frame's axis), if any.
pub(super) fn first(df: &Df) -> Option<Leaf> {
    let mut first = None;
    visit(df, false, &mut |t, _| {
        first.get_or_insert(t);
    });
    first
}

/// Whether a lobe's `tangent_u` differs from the first's.
pub(super) fn differ(df: &Df) -> bool {
    let (mut first, mut differ) = (None, false);
    visit(df, false, &mut |t, _| differ |= *first.get_or_insert(t) != t);
    differ
}

/// Whether a lobe inside a layer with its own normal has a `tangent_u` other than the
/// first's (it follows the layer's frame instead: not compiled).
pub(super) fn differ_under_own_normal(df: &Df) -> bool {
    let (mut first, mut differ) = (None, false);
    visit(df, false, &mut |t, own| differ |= *first.get_or_insert(t) != t && own);
    differ
}
