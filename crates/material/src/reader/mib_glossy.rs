//! mental ray's `mib_glossy_reflection` in the path engine: its glossy reflection as a
//! lobe over its base material ([`bsdf::MibGlossy`]).
//!
//! The lobe has the albedo and spread the classic shader's estimate converges to:
//! `reflection_color` × the view-angle curve (`reflection_base_weight`,
//! `reflection_edge_weight`, `edge_factor`) spread by Ward's distribution of `u_spread`,
//! `v_spread` (radians; along the surface's dP/du and the normal × dP/du), the mirror of
//! `mib_reflect` below 10⁻³. The base material (`base_material`, a shader the path engine
//! translates: `mib_illum_*`, `mia_material`, …) is added under it as the classic shader
//! adds its colour: its diffuse colour as a Lambertian base, its emission; a base that is
//! not Lambertian (a `mia_material`'s layers) keeps only its diffuse colour (warned).
//!
//! Parameters without a path-tracing counterpart: `samples` only sets the classic
//! shader's noise (the path engine's samples do that), except that 0 casts nothing (the
//! base alone, as in the classic shader); `dispersion` and `spectrum` are ignored by both
//! engines. `u_axis` (constant, or connected: evaluated at each hit) lays the spreads
//! along it ([`lobe_axes`]); the shader's
//! own `environment` is what every ray leaving the material sees where it finds nothing
//! (`render`'s `integrator::material_env`, as a material's own environment: its base's
//! rays included). `max_distance`, `falloff` and `environment_color` are the lobe's: its
//! rays take the environment past the distance and fade towards it nearer, and weigh it
//! by `environment_color` where `reflection_color` weighs what they find (`render`'s
//! `integrator::glossy_reach`); in channels where `reflection_color` is 0 the lobe carries
//! `environment_color` and reflects nothing it finds (`bsdf::MibGlossyLobe::carried`,
//! `seen`). Not honoured, warned where they change the result: `single_env_sample` with
//! a spread lobe and an environment colour (a per-pixel economy of the classic shader, one environment lookup along the mirror
//! direction for all its rays; a path has one ray per bounce, which looks the environment
//! up along its own direction: there is nothing to share), a connected
//! `reflection_color` or spread (their defaults).

use mi::ast::{Param, Value};
use scene::Library;

use super::Reader;
use crate::{color_param, first_call, SurfaceMaterial, SurfaceModel, Target};
use bsdf::{MibGlossyLobe, Rgb};

/// The surface of a `mib_glossy_reflection` with `params` (`depth` counts nested base
/// materials).
pub(super) fn glossy_reflection(r: &mut Reader, params: &[Param], lib: &Library, depth: u32) -> SurfaceMaterial {
    let name = r.material();
    let mut surface = match params.iter().rev().find(|p| p.name.text == "base_material").map(|p| &p.value) {
        Some(Value::Connect(target) | Value::Str(target)) if depth < 8 => {
            match lib.shaders.get(&target.text).and_then(|d| first_call(&d.list.0, lib)) {
                Some((decl, inner)) => r.call(decl, inner, lib, depth + 1),
                None => {
                    r.warn(format!(
                        "mib_glossy_reflection's base_material '{}' is not a shader mira knows; black",
                        target.text
                    ));
                    SurfaceMaterial::lambert(name, Rgb::ZERO)
                }
            }
        }
        _ => SurfaceMaterial::lambert(name, Rgb::ZERO),
    };
    if surface.model != SurfaceModel::Lambert {
        r.warn(
            "mib_glossy_reflection's base material is kept as its diffuse colour under the glossy reflection".into(),
        );
    }
    let color = r.color(params, "reflection_color", Rgb::ZERO);
    let env_color = r.color(params, "environment_color", Rgb::ZERO);
    let curve = (
        r.scalar(params, "reflection_base_weight", 0.6),
        r.scalar(params, "reflection_edge_weight", 1.0),
        r.scalar(params, "edge_factor", 5.0),
    );
    let spreads = (r.scalar(params, "u_spread", 0.1), r.scalar(params, "v_spread", 0.1));
    let samples = r.scalar(params, "samples", 16.0);
    if samples <= 0.0 || (color == Rgb::ZERO && env_color == Rgb::ZERO) {
        // Nothing cast (or nothing reflected): the base alone.
        return surface;
    }
    let max_distance = r.scalar(params, "max_distance", 0.0);
    let falloff = r.scalar(params, "falloff", 2.0);
    let lobe = MibGlossyLobe::new(color, curve, spreads).with_reach(env_color, max_distance, falloff);
    if lobe.dist.is_some() && env_color != Rgb::ZERO && r.flag(params, "single_env_sample", true) {
        r.warn(
            "mib_glossy_reflection's single_env_sample is not honoured by the path engine (the environment is looked \
             up along each reflected direction)"
                .into(),
        );
    }
    if lobe.dist.is_some_and(|d| d.alpha_x != d.alpha_y) {
        lobe_axes(r, params, "mib_glossy_reflection", &mut surface);
    }
    surface.model = SurfaceModel::MibGlossy(Box::new(lobe));
    surface
}

/// Lays an anisotropic lobe's spreads along `u_axis` (world space, projected onto the
/// tangent plane at each hit, as the classic shaders read it; a connected `u_axis` is
/// evaluated at each hit) and the normal × that axis, or along dP/du and the normal ×
/// dP/du where `u_axis` is not given (zero). `v_axis` changes nothing: the classic shaders
/// take the tangent that is perpendicular to u as v, which is ± normal × u, and Ward's
/// distribution is the same mirrored across u.
pub(super) fn lobe_axes(r: &mut Reader, params: &[Param], shader: &str, surface: &mut SurfaceMaterial) {
    // dP/du where the axis is not given (or a connected one gives zero at a hit).
    surface.tangent_angle = Some(0.0);
    if r.bind(params, "u_axis", Some((Target::TangentAxis, 1.0))) {
        return;
    }
    match color_param(params, "u_axis") {
        Some(Ok(axis)) if axis != Rgb::ZERO => {
            surface.tangent_axis = Some(axis);
            surface.tangent_angle = None;
        }
        Some(Err(why)) => {
            r.warn(format!("{shader}'s u_axis is not honoured by the path engine ({why}; dP/du is the axis)"))
        }
        _ => {}
    }
}
