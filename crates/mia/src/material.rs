//! `mia_material` and `mia_material_x` in the classic engine: the material shader (also its
//! own shadow shader) as the author describes it.
//!
//! Layers and their results (`X_result = X_raw ⊙ X_level`):
//! - diffuse: Oren–Nayar with the smoothed terminator over the lights (mental ray's light
//!   convention, no 1/π), plus indirect light: `mi_compute_avg_radiance` (irradiance / π)
//!   × `indirect_multiplier`, optionally darkened by ambient occlusion;
//! - highlights: three Ward lobes per light, level `hl_vs_refl_balance × reflection level`;
//!   visible area lights give none with `no_visible_area_hl`;
//! - reflection: rays from jittered normals, flipped above the surface, `refl_gloss_samples`
//!   of them for eye hits (one deeper down), limited by `refl_depth`, `refl_cutoff` and the
//!   falloff distance; with `refl_hl_only` (or past the depth) the reflection is the final
//!   gather average instead;
//! - refraction: glossy rays around the refracted direction (straight through when
//!   `thin_walled`), total internal reflection reflected, absorption or fade with distance;
//! - translucency: Lambert from the back side;
//! - `additional_color` on top, all of it blended with what lies behind by
//!   `cutout_opacity`;
//! - with `refl_interpolate` / `refr_interpolate`, glossy layers of eye-ray hits are
//!   interpolated from a per-render lattice cache ([`super::interpolate`]).
//!
//! As a shadow shader it lets through the transparency's share of the light (tinted by
//! `refr_color`, after the reflection took its part), or nothing with
//! `do_refractive_caustics`; cut-out parts let everything through.

use std::sync::Arc;

use glam::{Vec3A, Vec4};

use super::interpolate::{interpolated, Layer};
use super::params::{Mia, P};
use bsdf::color::luminance;
use bsdf::mia::lobes::{
    anisotropic_shininess, base_shininess, highlight, jittered_reflection, oren_nayar, sample_ward_half,
};
use bsdf::Frame;
use shader::{rgb, rgba};
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Tag, Value};

/// `mia_material` (the 3.5 interface: one colour).
pub static MIA_MATERIAL: ShaderImpl = ShaderImpl {
    name: "mia_material",
    params: super::params::LEGACY_NAMES,
    run: |c, n, o| mia(c, n, o, false),
    photon: Some(crate::photon::scatter),
    ..ShaderImpl::PLAIN
};

/// `mia_material_x` (every component as a struct member).
pub static MIA_MATERIAL_X: ShaderImpl = ShaderImpl {
    name: "mia_material_x",
    params: super::params::NAMES,
    run: |c, n, o| mia(c, n, o, true),
    photon: Some(crate::photon::scatter),
    ..ShaderImpl::PLAIN
};

/// `mia_material_x_passes` (as `mia_material_x`; mira writes no render passes from it).
pub static MIA_MATERIAL_X_PASSES: ShaderImpl = ShaderImpl {
    name: "mia_material_x_passes",
    params: super::params::NAMES,
    run: |c, n, o| mia(c, n, o, true),
    photon: Some(crate::photon::scatter),
    ..ShaderImpl::PLAIN
};

/// Every component of one shading, for `mia_material_x`'s outputs.
#[derive(Clone, Copy, Debug, Default)]
struct Parts {
    diffuse_raw: Vec3A,
    diffuse_level: Vec3A,
    spec_raw: Vec3A,
    spec_level: Vec3A,
    refl_raw: Vec3A,
    refl_level: Vec3A,
    refr_raw: Vec3A,
    refr_level: Vec3A,
    tran_raw: Vec3A,
    tran_level: Vec3A,
    indirect_raw: Vec3A,
    indirect_post_ao: Vec3A,
    indirect_result: Vec3A,
    ao_raw: f32,
    add: Vec4,
    opacity_raw: Vec4,
    opacity: f32,
    alpha: f32,
}

impl Parts {
    fn sum(&self) -> Vec3A {
        self.diffuse_raw * self.diffuse_level
            + self.spec_raw * self.spec_level
            + self.refl_raw * self.refl_level
            + self.refr_raw * self.refr_level
            + self.tran_raw * self.tran_level
            + self.indirect_result
            + rgb(self.add)
    }

    /// The beauty result, cut-out blended.
    fn result(&self) -> Color {
        let o = self.opacity;
        let shaded = rgba(self.sum(), self.alpha);
        if o >= 1.0 {
            shaded
        } else {
            shaded * o + self.opacity_raw * (1.0 - o)
        }
    }

    fn outputs(&self) -> Value {
        let c = |v: Vec3A| Value::Color(rgba(v, 1.0));
        let members: Vec<(&str, Value)> = vec![
            ("result", Value::Color(self.result())),
            ("diffuse_result", c(self.diffuse_raw * self.diffuse_level)),
            ("diffuse_raw", c(self.diffuse_raw)),
            ("diffuse_level", c(self.diffuse_level)),
            ("spec_result", c(self.spec_raw * self.spec_level)),
            ("spec_raw", c(self.spec_raw)),
            ("spec_level", c(self.spec_level)),
            ("refl_result", c(self.refl_raw * self.refl_level)),
            ("refl_raw", c(self.refl_raw)),
            ("refl_level", c(self.refl_level)),
            ("refr_result", c(self.refr_raw * self.refr_level)),
            ("refr_raw", c(self.refr_raw)),
            ("refr_level", c(self.refr_level)),
            ("tran_result", c(self.tran_raw * self.tran_level)),
            ("tran_raw", c(self.tran_raw)),
            ("tran_level", c(self.tran_level)),
            ("indirect_result", c(self.indirect_result)),
            ("indirect_raw", c(self.indirect_raw)),
            ("indirect_post_ao", c(self.indirect_post_ao)),
            ("ao_raw", c(Vec3A::splat(self.ao_raw))),
            ("add_result", Value::Color(self.add)),
            ("opacity_result", Value::Color(self.opacity_raw * (1.0 - self.opacity))),
            ("opacity_raw", Value::Color(self.opacity_raw)),
            ("opacity", Value::Scalar(self.opacity)),
        ];
        Value::Struct(members.into_iter().map(|(n, v)| (Arc::from(n), v)).collect::<Vec<_>>().into())
    }
}

fn finish(out: &mut Value, parts: &Parts, extended: bool) -> bool {
    *out = if extended { parts.outputs() } else { Value::Color(parts.result()) };
    true
}

fn mia(ctx: &mut Ctx, n: NodeId, out: &mut Value, extended: bool) -> bool {
    match ctx.state.ray_type {
        RayType::Shadow => return shadow(ctx, n, out),
        RayType::Light => return false,
        _ => {}
    }
    let opacity = ctx.scalar(n, P::CutoutOpacity as usize).clamp(0.0, 1.0);
    let mut parts = Parts { opacity, alpha: 1.0, ..Parts::default() };
    if opacity < 1.0 {
        parts.opacity_raw = ctx.trace_transparent().unwrap_or(Vec4::ZERO);
        if opacity <= 0.0 {
            return finish(out, &parts, extended);
        }
    }
    if ctx.bool(n, P::BackfaceCull as usize) && ctx.state.inv_normal {
        parts.opacity = 0.0;
        parts.opacity_raw = ctx.trace_transparent().unwrap_or(Vec4::ZERO);
        return finish(out, &parts, extended);
    }
    let m = Mia::read(ctx, n);
    let unbumped = ctx.state.normal;
    bump(ctx, n, extended);
    let bumped = ctx.state.normal;
    let diffuse_normal = if ctx.bool(n, P::NoDiffuseBump as usize) { unbumped } else { bumped };
    let view = -ctx.state.dir;
    let cos_nv = bumped.dot(view).max(0.0);
    // Inside the object (the ray hit the back side): no reflections with skip_inside_refl.
    let inside = ctx.state.inv_normal && !m.thin_walled;
    let reflect = !(inside && ctx.bool(n, P::SkipInsideRefl as usize));
    let w = m.weights(cos_nv, reflect);
    parts.diffuse_level = w.diffuse;
    parts.refl_level = w.reflect;
    parts.spec_level = w.reflect * m.hl_balance;
    parts.refr_level = w.refract;
    parts.tran_level = w.transl;
    parts.add = ctx.color(n, P::AdditionalColor as usize);

    let frame = anisotropy_frame(ctx, n, &m, bumped);
    let (su, sv) = anisotropic_shininess(base_shininess(m.refl_gloss), m.anisotropy);
    direct(ctx, n, &m, &frame, diffuse_normal, &mut parts, (su, sv));
    let density = ctx.int(n, P::IntrGridDensity as usize);
    if parts.refl_level != Vec3A::ZERO {
        let glossy = m.refl_gloss < 1.0 && ctx.bool(n, P::ReflInterpolate as usize);
        let cached = glossy
            .then(|| {
                interpolated(ctx, n, Layer::Reflection, density, |c| (reflection(c, n, &m, &frame, (su, sv)), 1.0))
            })
            .flatten();
        parts.refl_raw = cached.map_or_else(|| reflection(ctx, n, &m, &frame, (su, sv)), |v| v.0);
    }
    if parts.refr_level != Vec3A::ZERO {
        let glossy = ctx.scalar(n, P::RefrGloss as usize) < 1.0 && ctx.bool(n, P::RefrInterpolate as usize);
        let cached = glossy
            .then(|| interpolated(ctx, n, Layer::Refraction, density, |c| refraction(c, n, &m, &frame)))
            .flatten();
        let (raw, behind_alpha) = cached.unwrap_or_else(|| refraction(ctx, n, &m, &frame));
        parts.refr_raw = raw;
        if ctx.bool(n, P::PropagateAlpha as usize) {
            // What lies behind shows through the transparent share.
            let t = luminance(parts.refr_level).clamp(0.0, 1.0);
            parts.alpha = 1.0 - t * (1.0 - behind_alpha);
        }
    }
    indirect(ctx, n, diffuse_normal, &mut parts);
    ctx.state.normal = unbumped;
    ctx.state.dot_nd = unbumped.dot(ctx.state.dir);
    finish(out, &parts, extended)
}

/// Runs the bump shader (and, for `mia_material_x`, the bump vectors) on the state's
/// normal.
pub fn bump(ctx: &mut Ctx, n: NodeId, extended: bool) {
    if let Some(Tag::Shader(b)) = ctx.tag(n, P::Bump as usize) {
        let mut tmp = Value::Null;
        ctx.call(b, &mut tmp);
    }
    if !extended {
        return;
    }
    let mode = ctx.int(n, P::BumpMode as usize);
    for p in [P::OverallBump, P::StandardBump] {
        let v = ctx.vector(n, p as usize);
        if v == Vec3A::ZERO || mode <= 0 {
            continue;
        }
        let s = &ctx.state;
        // Modes 1–4 add the vector, 5–8 set the normal, in internal (world), world, object
        // and camera space.
        let world = match (mode - 1) % 4 {
            2 => s.world_to_object.matrix3.transpose() * v,
            3 => ctx.shading().world_to_camera.matrix3.transpose() * v,
            _ => v,
        };
        let normal = if mode >= 5 { world } else { s.normal + world };
        let mut normal = normal.normalize_or(s.normal);
        if normal.dot(s.normal_geom) < 0.0 && mode >= 5 {
            normal = -normal;
        }
        ctx.state.normal = normal;
        ctx.state.dot_nd = normal.dot(ctx.state.dir);
    }
}

/// The tangent frame of the highlights and glossy rays: `anisotropy_channel` −1 follows
/// the object's x axis, ≥ 0 that texture space's derivative (the first one's in mira),
/// turned by `anisotropy_rotation` full turns.
fn anisotropy_frame(ctx: &mut Ctx, n: NodeId, m: &Mia, normal: Vec3A) -> Frame {
    if m.anisotropy == 1.0 {
        return Frame::from_normal(normal);
    }
    let channel = ctx.int(n, P::AnisotropyChannel as usize);
    let s = &ctx.state;
    let base = if channel >= 0 { s.derivs[0] } else { s.vector_from_object(Vec3A::X) };
    let u = (base - normal * base.dot(normal)).try_normalize().unwrap_or_else(|| Frame::from_normal(normal).tangent);
    let theta = 2.0 * std::f32::consts::PI * m.rotation;
    let u = u * theta.cos() + normal.cross(u) * theta.sin();
    Frame { tangent: u, bitangent: normal.cross(u), normal }
}

/// The light loop: diffuse, highlights and translucency.
fn direct(ctx: &mut Ctx, n: NodeId, m: &Mia, frame: &Frame, diffuse_normal: Vec3A, parts: &mut Parts, s: (f32, f32)) {
    let mode = ctx.int(n, P::Mode as usize);
    let lights = ctx.eval(n, P::Lights as usize);
    // An empty list in modes 0 and 1 means every light (exporters write mia_material
    // without a list and expect the scene's lights).
    let mode = if lights.array().is_empty() && (mode == 0 || mode == 1) { 3 } else { mode };
    let no_area_hl = ctx.bool(n, P::NoVisibleAreaHl as usize);
    let view = -ctx.state.dir;
    let translucent = parts.tran_level != Vec3A::ZERO;
    let want_spec = parts.spec_level != Vec3A::ZERO;
    for light in ctx.light_list(mode, &lights) {
        let visible_area = {
            let l = &ctx.shading().lights[light as usize];
            l.visible && l.shape.is_some()
        };
        let mut lp = ctx.light_loop(light);
        lp.both_sides = translucent;
        let (mut d, mut sp, mut tr) = (Vec3A::ZERO, Vec3A::ZERO, Vec3A::ZERO);
        while let Some(sample) = ctx.sample_light(&mut lp) {
            let c = rgb(sample.color);
            if sample.dot_nl > 0.0 {
                d += c * oren_nayar(diffuse_normal, view, sample.dir, m.roughness);
                if want_spec && !(no_area_hl && visible_area) {
                    sp += c * highlight(frame, view, sample.dir, s.0, s.1);
                }
            } else {
                tr += c * bsdf::mia::lobes::smooth_cos(-sample.dot_nl);
            }
        }
        if lp.samples > 0 {
            let k = 1.0 / lp.samples as f32;
            parts.diffuse_raw += d * k;
            parts.spec_raw += sp * k;
            parts.tran_raw += tr * k;
        }
    }
}

/// Samples for a glossy layer: the parameter's count for eye hits, one deeper down, one
/// for perfect gloss or a count of 0.
fn samples(ctx: &mut Ctx, n: NodeId, p: P, gloss: f32) -> u32 {
    let count = ctx.int(n, p as usize);
    let s = &ctx.state;
    if gloss >= 1.0 || count <= 0 || s.reflection_level + s.refraction_level > 0 {
        1
    } else {
        count as u32
    }
}

/// A traced colour faded with distance: `dist` over `limit` linearly towards `fade`.
fn faded(c: Color, dist: f32, limit: f32, fade: Vec3A) -> Vec3A {
    if dist.is_infinite() {
        return fade;
    }
    let t = (dist / limit).clamp(0.0, 1.0);
    rgb(c) * (1.0 - t) + fade * t
}

/// The reflection layer's raw colour.
fn reflection(ctx: &mut Ctx, n: NodeId, m: &Mia, frame: &Frame, s: (f32, f32)) -> Vec3A {
    let hl_only = ctx.bool(n, P::ReflHlOnly as usize);
    let depth = ctx.int(n, P::ReflDepth as usize);
    let cutoff = ctx.scalar(n, P::ReflCutoff as usize);
    let level = m.refl_color * m.reflectivity;
    if luminance(level) < cutoff {
        return Vec3A::ZERO;
    }
    let too_deep = ctx.state.reflection_level as i32 >= depth || !ctx.may_trace(RayType::Reflect);
    if hl_only || too_deep {
        // Highlights with the final gather standing in for reflections.
        return rgb(ctx.compute_irradiance()) / std::f32::consts::PI;
    }
    let falloff = ctx.bool(n, P::ReflFalloffOn as usize).then(|| ctx.scalar(n, P::ReflFalloffDist as usize));
    let fade_color =
        ctx.bool(n, P::ReflFalloffColorOn as usize).then(|| rgb(ctx.color(n, P::ReflFalloffColor as usize)));
    let count = samples(ctx, n, P::ReflGlossSamples, m.refl_gloss);
    let site = ctx.next_site();
    let ng = ctx.state.normal_geom;
    let dir = ctx.state.dir;
    let mut sum = Vec3A::ZERO;
    for i in 0..count {
        let r = if m.refl_gloss >= 1.0 || count == 1 && ctx.int(n, P::ReflGlossSamples as usize) <= 0 {
            let mirror = dir - 2.0 * dir.dot(frame.normal) * frame.normal;
            if mirror.dot(ng) < 0.0 {
                mirror - 2.0 * mirror.dot(ng) * ng
            } else {
                mirror
            }
        } else {
            jittered_reflection(frame, ng, dir, s.0, s.1, ctx.sample2(site, i, count))
        };
        sum += match falloff {
            Some(limit) if limit > 0.0 => match ctx.cast(RayType::Reflect, r, limit) {
                Some((c, d)) => {
                    let fade = fade_color.unwrap_or_else(|| rgb(ctx.trace_environment(r)));
                    faded(c, d, limit, fade)
                }
                None => Vec3A::ZERO,
            },
            _ => ctx.trace_reflection(r).map_or(Vec3A::ZERO, rgb),
        };
    }
    sum / count as f32
}

/// The refraction layer's raw colour and the mean alpha of what it saw.
fn refraction(ctx: &mut Ctx, n: NodeId, m: &Mia, frame: &Frame) -> (Vec3A, f32) {
    let depth = ctx.int(n, P::RefrDepth as usize);
    let cutoff = ctx.scalar(n, P::RefrCutoff as usize);
    if luminance(m.refr_color * m.transparency) < cutoff
        || ctx.state.refraction_level as i32 >= depth
        || !ctx.may_trace(RayType::Refract)
    {
        // mental ray "refracts black" past the depth.
        return (Vec3A::ZERO, 0.0);
    }
    let gloss = ctx.scalar(n, P::RefrGloss as usize);
    let count = samples(ctx, n, P::RefrGlossSamples, gloss);
    let sharp = gloss >= 1.0 || ctx.int(n, P::RefrGlossSamples as usize) <= 0;
    let falloff_on = ctx.bool(n, P::RefrFalloffOn as usize);
    let limit = ctx.scalar(n, P::RefrFalloffDist as usize);
    let absorb = ctx.bool(n, P::RefrFalloffColorOn as usize).then(|| rgb(ctx.color(n, P::RefrFalloffColor as usize)));
    let dir = ctx.state.dir;
    let normal = frame.normal;
    // The ray leaves the object when it hit the back side.
    let eta = if ctx.state.inv_normal { m.ior } else { 1.0 / m.ior.max(1e-3) };
    let straight = m.thin_walled || m.ior == 1.0;
    ctx.state.ior = if ctx.state.inv_normal { 1.0 } else { m.ior };
    let center = if straight { Some(dir) } else { shader::trace::refract(dir, normal, eta) };
    let site = ctx.next_site();
    let shiny = base_shininess(gloss);
    let mut sum = Vec4::ZERO;
    for i in 0..count {
        let Some(t) = center else {
            // Total internal reflection.
            let r = ctx.reflection_dir();
            sum += ctx.trace_reflection(r).unwrap_or(Vec4::ZERO);
            continue;
        };
        let d = if sharp {
            t
        } else {
            let lobe = Frame::from_normal(t);
            let mut d = sample_ward_half(&lobe, shiny, shiny, ctx.sample2(site, i, count));
            // Transmitted rays stay on the far side.
            let side = d.dot(ctx.state.normal_geom);
            if side > 0.0 {
                d -= 2.0 * side * ctx.state.normal_geom;
            }
            d
        };
        let kind = if straight { RayType::Transparent } else { RayType::Refract };
        let c = match (falloff_on, absorb) {
            (true, None) if limit > 0.0 => {
                ctx.cast(kind, d, limit).map(|(c, dist)| rgba(faded(c, dist, limit, Vec3A::ZERO), c.w))
            }
            (true, Some(color)) if limit > 0.0 => ctx.cast(kind, d, f32::INFINITY).map(|(c, dist)| {
                // Beer–Lambert: the falloff colour is what is left after `limit` of glass.
                let k = if dist.is_finite() { dist / limit } else { 0.0 };
                rgba(rgb(c) * Vec3A::new(color.x.powf(k), color.y.powf(k), color.z.powf(k)), c.w)
            }),
            _ => ctx.cast(kind, d, f32::INFINITY).map(|(c, _)| c),
        };
        sum += c.unwrap_or(Vec4::ZERO);
    }
    let mean = sum / count as f32;
    (rgb(mean), mean.w)
}

/// Indirect light and ambient occlusion.
fn indirect(ctx: &mut Ctx, n: NodeId, normal: Vec3A, parts: &mut Parts) {
    let multiplier = ctx.scalar(n, P::IndirectMultiplier as usize);
    let saved = ctx.state.normal;
    ctx.state.normal = normal;
    let avg = if parts.diffuse_level != Vec3A::ZERO && multiplier != 0.0 {
        rgb(ctx.compute_irradiance()) / std::f32::consts::PI
    } else {
        Vec3A::ZERO
    };
    parts.indirect_raw = avg;
    parts.indirect_post_ao = avg;
    parts.ao_raw = 1.0;
    let mut ambient = Vec3A::ZERO;
    if ctx.bool(n, P::AoOn as usize) {
        let samples = ctx.int(n, P::AoSamples as usize).max(1) as u32;
        let dist = ctx.scalar(n, P::AoDistance as usize);
        let ao = occlusion(ctx, samples, dist);
        let dark = rgb(ctx.color(n, P::AoDark as usize));
        let f = dark + (Vec3A::ONE - dark) * ao;
        parts.ao_raw = ao;
        if ctx.int(n, P::AoDoDetails as usize) != 0 {
            parts.indirect_post_ao = avg * f;
        }
        ambient = rgb(ctx.color(n, P::AoAmbient as usize)) * f;
    }
    ctx.state.normal = saved;
    parts.indirect_result = (parts.indirect_post_ao * multiplier + ambient) * parts.diffuse_level;
}

/// The unoccluded fraction of `samples` cosine-distributed probes within `max_dist`, hits
/// weighted by their distance over `max_dist`.
fn occlusion(ctx: &mut Ctx, samples: u32, max_dist: f32) -> f32 {
    let site = ctx.next_site();
    let limit = if max_dist > 0.0 { max_dist } else { f32::INFINITY };
    let mut open = 0.0;
    let mut counted = 0;
    for i in 0..samples {
        let d = ctx.cosine_dir(site, i, samples);
        if d.dot(ctx.state.normal_geom) <= 0.0 {
            continue;
        }
        counted += 1;
        open += match ctx.probe(d, limit) {
            None => 1.0,
            Some(hit) if limit.is_finite() => hit / limit,
            Some(_) => 0.0,
        };
    }
    if counted == 0 {
        1.0
    } else {
        open / counted as f32
    }
}

/// mia as its own shadow shader.
fn shadow(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let opacity = ctx.scalar(n, P::CutoutOpacity as usize).clamp(0.0, 1.0);
    let through = if ctx.bool(n, P::DoRefractiveCaustics as usize) {
        Vec3A::ZERO
    } else {
        let m = Mia::read(ctx, n);
        let cos = ctx.state.normal.dot(-ctx.state.dir).abs();
        m.weights(cos, true).refract
    };
    let t = Vec3A::splat(1.0 - opacity) + through * opacity;
    let light = out.color();
    let passed = rgba(rgb(light) * t, light.w);
    *out = Value::Color(passed);
    passed.x > 0.0 || passed.y > 0.0 || passed.z > 0.0
}
