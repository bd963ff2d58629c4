//! `mira_bsdf_material`: the classic engine's form of a material that has a path-engine
//! BSDF but no mental ray shader (materials of MDL modules). The renderer gives the BSDF at
//! each hit ([`shader::Tracer::surface_scatter`]); the shader lights it as mental ray's
//! BSDF illumination does (see [`crate::bsdf_builtin`], same units): the light loop over
//! the BSDF's non-delta part (π · f · cos θi · light colour, the base shaders' light units),
//! final gathering's irradiance E on its diffuse reflectance ρ as ρ E / π (the physically
//! correct Lambertian term: an MDL emitter lights a module material as in the path
//! engine), and one BSDF-sampled ray for
//! what is left — specular reflection and refraction always, glossy lobes (less their
//! diffuse part) — traced by the classic tracer, weighted f · |cos θi| / pdf. Where the
//! renderer has no BSDF for the hit it shades as [`crate::illum::MIRA_DIFFUSE`] does.

use std::f32::consts::{FRAC_1_PI, PI};

use bsdf::Rgb;
use shader::{rgb, rgba, Ctx, NodeId, ShaderImpl, Value};

/// `mira_bsdf_material (color diffuse, color emission)`: the parameters are the stand-in's
/// (`mira_diffuse`), used where the renderer has no BSDF for the hit.
pub static MIRA_BSDF_MATERIAL: ShaderImpl = ShaderImpl {
    name: "mira_bsdf_material",
    params: &["diffuse", "emission"],
    run: bsdf_material,
    photon: Some(crate::photon::stand_in_diffuse),
    ..ShaderImpl::PLAIN
};

fn bsdf_material(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let Some(scatter) = ctx.tracer.surface_scatter(&ctx.state) else {
        return (crate::illum::MIRA_DIFFUSE.run)(ctx, n, out);
    };
    let (bsdf, frame) = (scatter.bsdf, scatter.frame);
    let wo = frame.to_local(-ctx.state.dir);
    let mut result = scatter.emission;
    if !bsdf.is_delta() {
        for light in ctx.light_list(3, &Value::Null) {
            let mut lp = ctx.light_loop(light);
            // Light from behind reaches transmitting BSDFs (translucency, glass).
            lp.both_sides = true;
            let mut sum = Rgb::ZERO;
            while let Some(s) = ctx.sample_light(&mut lp) {
                let wi = frame.to_local(s.dir);
                sum += bsdf.eval(wo, wi) * (PI * wi.z.abs()) * rgb(s.color);
            }
            if lp.samples > 0 {
                result += sum / lp.samples as f32;
            }
        }
        if scatter.diffuse != Rgb::ZERO {
            // The gathered irradiance E = ∫ L cos θ dω of what the scene's surfaces emit and
            // reflect (radiances, in the same units as the path engine's) reflects as the
            // Lambertian term ρ E / π. (The base shaders use mental ray's ρ E; for a module
            // material that would show an MDL emitter's light π times brighter than the
            // path engine does.)
            result += scatter.diffuse * rgb(ctx.compute_irradiance()) * FRAC_1_PI;
        }
    }
    // One sampled direction for the rest: delta lobes always, glossy ones less the
    // diffuse part final gathering lit.
    let site = ctx.next_site();
    let u = ctx.sample2(site, 0, 1);
    let u_lobe = ctx.sample2(site + 1000, 0, 1).x;
    if let Some(s) = bsdf.sample(wo, u, u_lobe) {
        let f = if s.delta { s.f } else { (s.f - scatter.diffuse * FRAC_1_PI).max(Rgb::ZERO) };
        let dir = frame.to_world(s.wi);
        if s.pdf > 0.0 && f != Rgb::ZERO {
            // Below the surface seen from the ray's side: a refraction ray.
            let through = dir.dot(ctx.state.normal) < 0.0;
            let traced = if through { ctx.trace_refraction(dir) } else { ctx.trace_reflection(dir) };
            // Past the depth limits a reflection sees the environment, a refraction nothing.
            let traced =
                traced.unwrap_or_else(|| if through { Default::default() } else { ctx.trace_environment(dir) });
            result += f * (s.wi.z.abs() / s.pdf) * rgb(traced);
        }
    }
    *out = Value::Color(rgba(result, 1.0));
    true
}
