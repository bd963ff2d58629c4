//! mental ray's `mib_glossy_refraction` in the path engine: its glossy refraction as a
//! lobe under its top material ([`bsdf::MibGlossyRefraction`]).
//!
//! The lobe has the albedo and spread the classic shader's estimate converges to:
//! `refraction_color` × the view-angle curve (`refraction_base_weight`,
//! `refraction_edge_weight`, `edge_factor`) refracted by `ior` (the inside's index: the
//! surface's front faces the outside) about micro-normals of Ward's distribution of
//! `u_spread`, `v_spread` (radians; along the surface's dP/du and the normal × dP/du), the
//! sharp refraction of `mib_refract` below 10⁻³, the mirror under total internal
//! reflection. The top material (`top_material`, a shader the path engine translates) is
//! added over it on the front as the classic shader adds its colour: its diffuse colour as
//! a Lambertian top, its emission; a top that is not Lambertian keeps only its diffuse
//! colour (warned).
//!
//! Parameters without a path-tracing counterpart: `samples` only sets the classic
//! shader's noise, except that 0 casts nothing (the top alone); `dispersion` and
//! `spectrum` are ignored by both engines. `back_material` (a shader the path engine
//! translates, kept as its diffuse colour as the top is) is added seen from the back, in
//! place of the top: a Lambertian reflection of the light on the back's side, or with
//! `render_reverse_of_back_material` (the classic shader then shades it with the normal
//! facing out) a Lambertian transmission of the light on the front's side; its
//! connected parameters keep their constant values and its emission is not shown
//! (warned). Both layers are capped at what the glossy lobe leaves
//! ([`bsdf::MibGlossyRefractionLobe::layer_room`]). `max_distance` and `falloff` are the
//! lobe's: the path engine fades the segment after a glossy bounce into `deep_material`
//! as mental ray's shader does (not a physical medium: the deep material's shader run
//! once at the entry point, `render`'s `integrator::glossy_reach`). `u_axis` (constant
//! or connected) lays the spreads along it, as `mib_glossy_reflection`'s.

use mi::ast::{Param, Value};
use scene::Library;

use super::Reader;
use crate::{first_call, SurfaceMaterial, SurfaceModel};
use bsdf::{MibGlossyRefractionLobe, Rgb};

/// The surface of a `mib_glossy_refraction` with `params` (`depth` counts nested
/// materials).
pub(super) fn glossy_refraction(r: &mut Reader, params: &[Param], lib: &Library, depth: u32) -> SurfaceMaterial {
    let name = r.material();
    let shader = |p: &str| params.iter().rev().find(|q| q.name.text == p).map(|q| &q.value);
    let mut surface = match shader("top_material") {
        Some(Value::Connect(target) | Value::Str(target)) if depth < 8 => {
            match lib.shaders.get(&target.text).and_then(|d| first_call(&d.list.0, lib)) {
                Some((decl, inner)) => r.call(decl, inner, lib, depth + 1),
                None => {
                    r.warn(format!(
                        "mib_glossy_refraction's top_material '{}' is not a shader mira knows; black",
                        target.text
                    ));
                    SurfaceMaterial::lambert(name, Rgb::ZERO)
                }
            }
        }
        _ => SurfaceMaterial::lambert(name, Rgb::ZERO),
    };
    if surface.model != SurfaceModel::Lambert {
        r.warn("mib_glossy_refraction's top material is kept as its diffuse colour over the glossy refraction".into());
    }
    let color = r.color(params, "refraction_color", Rgb::ONE);
    let curve = (
        r.scalar(params, "refraction_base_weight", 1.0),
        r.scalar(params, "refraction_edge_weight", 0.6),
        r.scalar(params, "edge_factor", 5.0),
    );
    let ior = r.scalar(params, "ior", 1.0);
    let spreads = (r.scalar(params, "u_spread", 0.1), r.scalar(params, "v_spread", 0.1));
    let samples = r.scalar(params, "samples", 16.0);
    let back = match shader("back_material") {
        Some(Value::Connect(target) | Value::Str(target)) => back_albedo(r, &target.text, lib, depth)
            .map(|albedo| (albedo, r.flag(params, "render_reverse_of_back_material", false))),
        _ => None,
    };
    let refracts = samples > 0.0 && color != Rgb::ZERO;
    if !refracts && back.is_none() {
        // Nothing cast (or nothing refracted): the top alone.
        return surface;
    }
    // (Without refraction, a lobe of colour 0: the top on the front, the back behind.)
    let mut lobe = MibGlossyRefractionLobe::new(if refracts { color } else { Rgb::ZERO }, curve, ior, spreads);
    if let Some((albedo, through)) = back {
        lobe = lobe.with_back(albedo, through);
    }
    lobe = lobe.with_reach(r.scalar(params, "max_distance", 0.0), r.scalar(params, "falloff", 2.0));
    if lobe.dist.is_some_and(|d| d.alpha_x != d.alpha_y) {
        super::mib_glossy::lobe_axes(r, params, "mib_glossy_refraction", &mut surface);
    }
    surface.model = SurfaceModel::MibGlossyRefraction(Box::new(lobe));
    surface
}

/// The Lambertian albedo of the back material `target` (its diffuse colour, as the top
/// material's), warning where the path engine keeps less of it: a model that is not
/// Lambertian, parameters connected to shaders (their constant values), emission.
fn back_albedo(r: &mut Reader, target: &str, lib: &Library, depth: u32) -> Option<Rgb> {
    if depth >= 8 {
        return None;
    }
    let Some((decl, inner)) = lib.shaders.get(target).and_then(|d| first_call(&d.list.0, lib)) else {
        r.warn(format!("mib_glossy_refraction's back_material '{target}' is not a shader mira knows; black"));
        return None;
    };
    // The back material's connections would drive the top's parameters: dropped.
    let bound = r.bindings.len();
    let back = r.call(decl, inner, lib, depth + 1);
    if r.bindings.len() > bound {
        r.bindings.truncate(bound);
        r.warn(format!(
            "mib_glossy_refraction's back_material '{target}' has connected parameters; the path engine keeps their \
             constant values"
        ));
    }
    if back.model != SurfaceModel::Lambert {
        r.warn(
            "mib_glossy_refraction's back material is kept as its diffuse colour under the glossy refraction".into(),
        );
    }
    if back.emission != Rgb::ZERO {
        r.warn(format!(
            "mib_glossy_refraction's back_material '{target}' emits; the path engine does not show its emission"
        ));
    }
    Some(back.diffuse)
}
