//! Lowering a BSDF tree to bsdf's general lobe sum ([`GeneralSum`]): any constant-weight
//! sum of elemental lobes under mixes, tints and layers, each lobe weighed by the layer
//! curves (Fresnel, Schlick, thin film, sheen albedo) above and below it, in the frame of
//! its layer's own normal — a compact [`SurfaceModel::MdlLobes`] where it fits, else a wide
//! sum.

use bsdf::beckmann::Beckmann;
use bsdf::glass_multiscatter::GlassMultiScatter;
use bsdf::measured_bsdf::MeasuredLobe;
use bsdf::microfacet::Ggx;
use bsdf::multiscatter::{MultiScatter, Single};
use bsdf::rough_glass::{Halves, Microfacet, RoughGlass};
use bsdf::{CurveKind, LayerCurve, Lobe, LobeSum as GeneralSum, Lobes, Rgb, Role, WideLobes};
use glam::Vec4;

use super::diffuse_only;
use crate::mdl_modules::natives::mix_weights;
use crate::mdl_modules::value::{layer_ior, CurveValues, Df, Leaf, ScatterMode, MAX_HIT_CURVE};
use crate::SurfaceModel;

/// Adds `df` scaled by `scale` to a general sum of lobes (two glossy roughnesses,
/// Beckmann, sheen, layer curves…), each lobe weighed by the curves as `role` says;
/// `film` is a `thin_film` (thickness in nm, film index) over `df`. False if the tree has
/// anything else, or more lobes, curves or normals than `sum` holds.
///
/// A film changes the Fresnel terms of what it covers (MDL's `thin_film`): it reaches
/// through mixes, tints, weighted layers, directional factors and a sheen's base to each
/// `fresnel_layer` / `color_fresnel_layer` (whose curve becomes the film's Airy
/// reflectance over the layer's index) and `custom_curve_layer` (read as the Fresnel layer
/// whose normal reflectivity it has, index (1 + √R₀)/(1 − √R₀), R₀ the mean of
/// `normal_reflectivity`; `measured_curve_layer` likewise with its first sample);
/// elemental BSDFs in reflection have no Fresnel term for it to
/// change and are unchanged.
///
/// `frame` is the frame the lobes of `df` live in (0: the shading frame): a layer with its
/// own `normal` puts its lobes and its curve in the frame of that normal (at most `F`
/// normals a sum). `axis` is the `tangent_u` the shading frame's u axis follows (the
/// first anisotropic lobe's): an anisotropic lobe in the shading frame with another gets
/// an own frame turned about the normal to its tangent. `medium` is what a glass lobe
/// bounds.
#[allow(clippy::too_many_arguments)]
fn add_general<const N: usize, const C: usize, const F: usize, const T: usize>(
    df: &Df,
    scale: Rgb,
    hit: &[Vec4],
    medium: Medium,
    sum: &mut GeneralSum<N, C, F, T>,
    role: Role,
    film: Option<(f32, Rgb)>,
    frame: u8,
    axis: Option<Leaf>,
) -> bool {
    let alpha = |(u, v): &(Leaf, Leaf)| (u.get(hit).x.max(0.0), v.get(hit).x.max(0.0));
    let mut push = |w: Rgb, lobe: Lobe| sum.push_in_frame(w, lobe, role, frame);
    match df {
        Df::Black => true,
        Df::Diffuse { tint, roughness } => push(scale * tint.get(hit), Lobe::Diffuse(roughness.get(hit).x.max(0.0))),
        Df::DiffuseTransmission(tint) => push(scale * tint.get(hit), Lobe::Translucent),
        Df::Measured { table, multiplier, mode } => {
            let (reflect, transmit) = (*mode != ScatterMode::Transmit, *mode != ScatterMode::Reflect);
            // Measurements come interned from the module's textures: always found.
            let Some(lobe) = MeasuredLobe::new(table, reflect, transmit) else { return false };
            push(scale * *multiplier, Lobe::Measured(lobe))
        }
        Df::Specular { tint, mode: ScatterMode::Reflect } => push(scale * tint.get(hit), Lobe::Mirror),
        Df::Glossy { tint, roughness, mode: ScatterMode::Reflect, beckmann, vcavities, multiscatter, tangent } => {
            let Some(frame) = tangent_frame(*tangent, axis, hit, sum, frame) else { return false };
            let mut push = |w: Rgb, lobe: Lobe| sum.push_in_frame(w, lobe, role, frame);
            let (au, av) = alpha(roughness);
            let (lobe, single) = match (*beckmann, *vcavities) {
                (true, false) => (Lobe::Beckmann(Beckmann::new(au, av)), Single::BeckmannSmith),
                (true, true) => (Lobe::BeckmannVcavities(Beckmann::new(au, av)), Single::BeckmannVcavities),
                (false, v) => {
                    let g = Ggx { alpha_x: au, alpha_y: av };
                    match (g.is_smooth(), v) {
                        (true, _) => (Lobe::Mirror, Single::GgxSmith),
                        (false, false) => (Lobe::Ggx(g), Single::GgxSmith),
                        (false, true) => (Lobe::GgxVcavities(g), Single::GgxVcavities),
                    }
                }
            };
            let tint = scale * tint.get(hit);
            // A mirror loses nothing to give back.
            let lost = (lobe != Lobe::Mirror).then_some((single, au, av));
            push(tint, lobe) && compensate(&mut push, tint, *multiscatter, lost, hit)
        }
        // Glass (`scatter_reflect_transmit`, `scatter_transmit`), rough or smooth: the
        // dielectric lobe of the material's index, Smith's or V-cavity masking, and the
        // compensation `multiscatter_tint` asks for.
        Df::Glossy { tint, roughness, mode, beckmann, vcavities, multiscatter, .. } => {
            let (alpha_x, alpha_y) = alpha(roughness);
            let glass = glass_lobe((alpha_x, alpha_y), Microfacet::new(*beckmann, *vcavities), *mode, medium);
            let tint = scale * tint.get(hit);
            let ms = multiscatter.get(hit).clamp(Rgb::ZERO, Rgb::ONE);
            // Smooth glass loses nothing to give back.
            let compensated = ms != Rgb::ZERO && !glass.is_smooth();
            push_glass(sum, tint, glass, film, role, frame)
                && (!compensated
                    || sum.push_in_frame(
                        tint * ms,
                        Lobe::GlassMultiScatter(GlassMultiScatter::new(&glass)),
                        role,
                        frame,
                    ))
        }
        Df::Specular { tint, mode } => {
            let glass = glass_lobe((0.0, 0.0), Microfacet::Ggx, *mode, medium);
            push_glass(sum, scale * tint.get(hit), glass, film, role, frame)
        }
        Df::Backscatter { tint, roughness, multiscatter, tangent } => {
            let Some(frame) = tangent_frame(*tangent, axis, hit, sum, frame) else { return false };
            let mut push = |w: Rgb, lobe: Lobe| sum.push_in_frame(w, lobe, role, frame);
            let (au, av) = alpha(roughness);
            let g = Ggx { alpha_x: au, alpha_y: av };
            let tint = scale * tint.get(hit);
            // Turned by π about the normal, the lobe loses what GGX–Smith reflection does.
            !g.is_smooth()
                && push(tint, Lobe::Backscatter(g))
                && compensate(&mut push, tint, *multiscatter, Some((Single::GgxSmith, au, av)), hit)
        }
        Df::Ward { tint, roughness, multiscatter, tangent } => {
            let Some(frame) = tangent_frame(*tangent, axis, hit, sum, frame) else { return false };
            let mut push = |w: Rgb, lobe: Lobe| sum.push_in_frame(w, lobe, role, frame);
            let (au, av) = alpha(roughness);
            let tint = scale * tint.get(hit);
            push(tint, Lobe::Ward(Beckmann::new(au, av)))
                && compensate(&mut push, tint, *multiscatter, Some((Single::Ward, au, av)), hit)
        }
        Df::Sheen { tint, roughness, multiscatter_tint, multiscatter, reflection_tint } => {
            // The base receives what the sheen leaves: it lies under the sheen's albedo.
            let r = roughness.get(hit).x;
            let tint = tint.get(hit);
            let curve = CurveKind::SheenAlbedo { roughness: r };
            let frames = (frame, frame);
            let Some((_, under)) = layer_roles(curve, tint, multiscatter, role, hit, sum, frames) else { return false };
            // Under two tints, the lobe alone takes the reflection tint (clamped to 1, as a
            // tint's one-component mix is).
            let lobe = reflection_tint.iter().fold(tint, |l, t| l * t.get(hit).clamp(Rgb::ZERO, Rgb::ONE));
            sum.push_in_frame(scale * lobe, Lobe::Sheen(r), role, frame)
                && add_general(
                    multiscatter,
                    scale * multiscatter_tint.get(hit).clamp(Rgb::ZERO, Rgb::ONE),
                    hit,
                    medium,
                    sum,
                    under,
                    film,
                    frame,
                    axis,
                )
        }
        Df::Mix { parts, bound } => {
            let mut ok = true;
            mix_weights(parts, *bound, hit, |w, d| {
                ok = ok && add_general(d, scale * w, hit, medium, sum, role, film, frame, axis)
            });
            ok
        }
        Df::Layer { weight, fresnel_ior: None, layer, base, layer_normal } => {
            let w = weight.get(hit).clamp(Rgb::ZERO, Rgb::ONE);
            let Some(own) = own_frame(*layer_normal, hit, sum, frame) else { return false };
            add_general(layer, scale * w, hit, medium, sum, role, film, own, axis)
                && add_general(base, scale * (Rgb::ONE - w), hit, medium, sum, role, film, frame, axis)
        }
        Df::Layer { weight, fresnel_ior: Some(ior), layer, base, layer_normal } => {
            let curve = match (film, layer_ior(ior.get(hit))) {
                // A film's Airy sum has one index under it: a colour index's mean.
                (Some((thickness_nm, film_ior)), one) => {
                    let ior = one.unwrap_or_else(|c| (c.x + c.y + c.z) / 3.0);
                    CurveKind::ThinFilm { ior, film_ior, thickness_nm }
                }
                (None, Ok(ior)) => CurveKind::Fresnel { ior },
                (None, Err(ior)) => CurveKind::ColorFresnel { ior },
            };
            let Some(own) = own_frame(*layer_normal, hit, sum, frame) else { return false };
            curve_layer(curve, weight.get(hit), layer, base, scale, hit, medium, sum, role, (frame, own), axis)
        }
        Df::CurveLayer { weight, normal, grazing, exponent, layer, base, layer_normal } => {
            let normal = normal.get(hit).clamp(Rgb::ZERO, Rgb::ONE);
            let curve = match film {
                Some((thickness_nm, film_ior)) => {
                    CurveKind::ThinFilm { ior: ior_of_reflectivity(normal), film_ior, thickness_nm }
                }
                None => CurveKind::Schlick {
                    normal,
                    grazing: grazing.get(hit).clamp(Rgb::ZERO, Rgb::ONE),
                    exponent: exponent.get(hit).x.max(0.0),
                },
            };
            let Some(own) = own_frame(*layer_normal, hit, sum, frame) else { return false };
            curve_layer(curve, weight.get(hit), layer, base, scale, hit, medium, sum, role, (frame, own), axis)
        }
        Df::DirectionalFactor { normal, grazing, exponent, base } => {
            let curve = CurveKind::Schlick {
                normal: normal.get(hit).clamp(Rgb::ZERO, Rgb::ONE),
                grazing: grazing.get(hit).clamp(Rgb::ZERO, Rgb::ONE),
                exponent: exponent.get(hit).x.max(0.0),
            };
            let Some(k) = sum.add_curve_in_frame(LayerCurve::new(curve, Rgb::ONE, false), frame) else { return false };
            add_general(base, scale, hit, medium, sum, Role { factor: role.factor | 1 << k, ..role }, film, frame, axis)
        }
        Df::ThinFilm { thickness, ior, base } => {
            let film = Some((thickness.get(hit).x.max(0.0), ior.get(hit)));
            add_general(base, scale, hit, medium, sum, role, film, frame, axis)
        }
        Df::MeasuredCurveLayer { curve, weight, layer, base, layer_normal } => {
            let curve = match film {
                // Read as the Fresnel layer of the curve's reflectivity at normal incidence.
                Some((thickness_nm, film_ior)) => CurveKind::ThinFilm {
                    ior: ior_of_reflectivity(curve.first(hit).clamp(Rgb::ZERO, Rgb::ONE)),
                    film_ior,
                    thickness_nm,
                },
                None => match measured(curve, hit, sum) {
                    Some(kind) => kind,
                    None => return false,
                },
            };
            let Some(own) = own_frame(*layer_normal, hit, sum, frame) else { return false };
            curve_layer(curve, weight.get(hit), layer, base, scale, hit, medium, sum, role, (frame, own), axis)
        }
        Df::FresnelFactor { .. } | Df::MeasuredCurveFactor { .. } | Df::MeasuredFactor { .. } => {
            let (curve, base) = match df {
                Df::FresnelFactor { ior, extinction, base } => (
                    CurveKind::Conductor { eta: ior.get(hit).max(Rgb::ZERO), k: extinction.get(hit).max(Rgb::ZERO) },
                    base,
                ),
                Df::MeasuredCurveFactor { curve, base } => match measured(curve, hit, sum) {
                    Some(kind) => (kind, base),
                    None => return false,
                },
                Df::MeasuredFactor { table, base } => (CurveKind::MeasuredFactor(table), base),
                _ => return false,
            };
            let Some(k) = sum.add_curve_in_frame(LayerCurve::new_in(curve, Rgb::ONE, false, sum.table()), frame) else {
                return false;
            };
            add_general(base, scale, hit, medium, sum, Role { factor: role.factor | 1 << k, ..role }, film, frame, axis)
        }
    }
}

/// The medium a glass lobe bounds: the material's index of refraction (inside over
/// outside) and whether it is thin-walled (no inside: transmission straight through).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Medium {
    /// `ior` (the mean of its channels).
    pub ior: f32,
    /// `thin_walled`.
    pub thin: bool,
}

/// The glass lobe of roughness `alpha` (of distribution and masking `micro`) in
/// transmission mode `mode` bounding `medium`.
fn glass_lobe(alpha: (f32, f32), micro: Microfacet, mode: ScatterMode, medium: Medium) -> RoughGlass {
    RoughGlass {
        alpha_x: alpha.0,
        alpha_y: alpha.1,
        eta: medium.ior,
        micro,
        halves: match mode {
            ScatterMode::Transmit => Halves::Transmit,
            ScatterMode::GlassReflect => Halves::Reflect,
            // A plain `scatter_reflect` lobe is no glass (never lowered here).
            ScatterMode::ReflectTransmit | ScatterMode::Reflect => Halves::Both,
        },
        thin: medium.thin,
        film: 0,
    }
}

/// Pushes `glass` of weight `weight` (as `role` says, in `frame`); under `film` (thickness
/// in nm, film index), the film's Airy reflectance over the glass's index on its Fresnel
/// term, a curve of the sum the lobe names. False when the sum is full or the lobe is none
/// (a solid of index 1).
fn push_glass<const N: usize, const C: usize, const F: usize, const T: usize>(
    sum: &mut GeneralSum<N, C, F, T>,
    weight: Rgb,
    glass: RoughGlass,
    film: Option<(f32, Rgb)>,
    role: Role,
    frame: u8,
) -> bool {
    if !glass.is_valid() {
        return false;
    }
    let film = match film {
        None => 0,
        Some((thickness_nm, film_ior)) => {
            let curve = CurveKind::ThinFilm { ior: glass.eta, film_ior, thickness_nm };
            match sum.add_curve_in_frame(LayerCurve::new(curve, Rgb::ONE, false), frame) {
                Some(k) => k + 1,
                None => return false,
            }
        }
    };
    sum.push_in_frame(weight, Lobe::Glass(RoughGlass { film, ..glass }), role, frame)
}

/// Pushes the compensation of a micro-mirror lobe of weight `tint` (`lost`: its model and
/// roughnesses; `None` for a mirror) with `push`, tinted by `multiscatter` (clamped to
/// [0, 1]; black or a mirror: nothing to push). False when the sum is full.
fn compensate(
    push: &mut impl FnMut(Rgb, Lobe) -> bool,
    tint: Rgb,
    multiscatter: Leaf,
    lost: Option<(Single, f32, f32)>,
    hit: &[Vec4],
) -> bool {
    let ms = multiscatter.get(hit).clamp(Rgb::ZERO, Rgb::ONE);
    match lost {
        Some((single, au, av)) if ms != Rgb::ZERO => {
            push(tint * ms, Lobe::MultiScatter(MultiScatter::new(single, au, av)))
        }
        _ => true,
    }
}

/// The frame an anisotropic lobe of `tangent` lives in, inside `frame`: when its
/// `tangent_u` is not `axis` (the shading frame's), an own frame (added to `sum`) turned
/// about `frame`'s normal — the shading normal, or a layer's own — so that its x axis is
/// the tangent made orthogonal to that normal; else `frame` (an isotropic lobe or the
/// axis's own). `None` when the sum holds no more frames.
fn tangent_frame<const N: usize, const C: usize, const F: usize, const T: usize>(
    tangent: Option<Leaf>,
    axis: Option<Leaf>,
    hit: &[Vec4],
    sum: &mut GeneralSum<N, C, F, T>,
    frame: u8,
) -> Option<u8> {
    match tangent {
        Some(t) if Some(t) != axis => {
            let c = t.get(hit);
            let t = glam::Vec3A::new(c.x, c.y, c.z);
            // A tangent of no direction leaves the lobe in the frame around it.
            if t.length_squared() > 0.0 && t.is_finite() {
                sum.add_tangent_in(t, frame)
            } else {
                Some(frame)
            }
        }
        _ => Some(frame),
    }
}

/// The index of refraction of the dielectric whose Fresnel reflectance at normal incidence
/// is the mean of `r0` (channels in [0, 1]): (1 + √R₀)/(1 − √R₀), at most 100.
fn ior_of_reflectivity(r0: Rgb) -> f32 {
    let s = ((r0.x + r0.y + r0.z) / 3.0).clamp(0.0, 1.0).sqrt();
    ((1.0 + s) / (1.0 - s).max(1e-6)).min(100.0)
}

/// The frame a layer's lobes live in: its own normal's (added to `sum`), or `frame` (the
/// frame around it) without one; `None` when the sum holds no more frames.
fn own_frame<const N: usize, const C: usize, const F: usize, const T: usize>(
    layer_normal: Option<Leaf>,
    hit: &[Vec4],
    sum: &mut GeneralSum<N, C, F, T>,
    frame: u8,
) -> Option<u8> {
    match layer_normal {
        None => Some(frame),
        Some(n) => {
            let n = n.get(hit);
            // A normal of no direction leaves the layer in the frame around it.
            if n.length_squared() > 0.0 && n.is_finite() {
                sum.add_normal(n)
            } else {
                Some(frame)
            }
        }
    }
}

/// Adds the curve of a layer of weight `weight` over `base` to `sum`: the roles of the
/// layer's and the base's lobes (`role` plus the curve's bit in `over`, `under`). `frames`
/// are the base's frame and the layer's (whose normal the curve measures its angles
/// from). The base's share is normalised when it is Lambertian, under no other curve and
/// in the layer's frame (then a white base stays lossless).
fn layer_roles<const N: usize, const C: usize, const F: usize, const T: usize>(
    curve: CurveKind,
    weight: Rgb,
    base: &Df,
    role: Role,
    hit: &[Vec4],
    sum: &mut GeneralSum<N, C, F, T>,
    (frame, own): (u8, u8),
) -> Option<(Role, Role)> {
    let lambertian = role.under == 0 && frame == own && diffuse_only(base, hit).is_some_and(|(_, sigma)| sigma == 0.0);
    let k = sum.add_curve_in_frame(LayerCurve::new_in(curve, weight, lambertian, sum.table()), own)?;
    Some((Role { over: role.over | 1 << k, ..role }, Role { under: role.under | 1 << k, ..role }))
}

/// Adds a layer weighed by `curve` (`custom_curve_layer`, `fresnel_layer`, a film on one):
/// the base in `frames.0`, the layer and its curve in `frames.1` (`axis`: see
/// [`add_general`]).
#[allow(clippy::too_many_arguments)]
fn curve_layer<const N: usize, const C: usize, const F: usize, const T: usize>(
    curve: CurveKind,
    weight: Rgb,
    layer: &Df,
    base: &Df,
    scale: Rgb,
    hit: &[Vec4],
    medium: Medium,
    sum: &mut GeneralSum<N, C, F, T>,
    role: Role,
    frames: (u8, u8),
    axis: Option<Leaf>,
) -> bool {
    let Some((over, under)) = layer_roles(curve, weight, base, role, hit, sum, frames) else { return false };
    add_general(layer, scale, hit, medium, sum, over, None, frames.1, axis)
        && add_general(base, scale, hit, medium, sum, under, None, frames.0, axis)
}

/// The tree as a lobe sum and its diffuse colour, if it is one: a compact
/// [`SurfaceModel::MdlLobes`] where it fits (the common case, copied into each hit's BSDF),
/// else a [`SurfaceModel::MdlWide`] (shared by the hits' BSDFs) or, lowered at a hit
/// (`per_hit`), a [`SurfaceModel::MdlWideAt`] in the thread's ring of wide sums.
pub(super) fn general(df: &Df, hit: &[Vec4], medium: Medium, per_hit: bool) -> Option<(Rgb, SurfaceModel)> {
    let axis = super::tangents::first(df);
    let mut sum = Lobes::default();
    if add_general(df, Rgb::ONE, hit, medium, &mut sum, Role::default(), None, 0, axis) {
        return Some((diffuse_of(&sum), SurfaceModel::MdlLobes(Box::new(sum))));
    }
    if !filled(&sum) {
        return None;
    }
    let mut wide = WideLobes::default();
    if !add_general(df, Rgb::ONE, hit, medium, &mut wide, Role::default(), None, 0, axis) {
        return None;
    }
    let model = if per_hit {
        SurfaceModel::MdlWideAt(crate::wide_slots::WideSlot::store(&wide))
    } else {
        SurfaceModel::MdlWide(Box::new(bsdf::SharedLobes::new(wide)))
    };
    Some((diffuse_of(&wide), model))
}

/// A measured curve's samples at `hit` as a curve of `sum`: a constant table as it is, one
/// that varies kept in the sum's own table (`None` when that is full — a compact sum keeps
/// none — after marking the sum's curves full for [`filled`]). A varying curve of more
/// than [`MAX_HIT_CURVE`] samples is resampled to that many ([`resample`]).
fn measured<const N: usize, const C: usize, const F: usize, const T: usize>(
    curve: &CurveValues,
    hit: &[Vec4],
    sum: &mut GeneralSum<N, C, F, T>,
) -> Option<CurveKind> {
    match curve {
        CurveValues::Const(table) => Some(CurveKind::Measured(table)),
        CurveValues::Hit(samples) => {
            let mut values = [Rgb::ZERO; MAX_HIT_CURVE];
            let values = resample(samples, hit, &mut values);
            let kind = sum.add_table(values);
            if kind.is_none() {
                // The table is full (a compact sum has none): the sum, whose lowering
                // stops here, reads as full to `filled` (a wide sum is tried next).
                sum.curve_count = C as u8;
            }
            kind
        }
    }
}

/// The samples of a curve at `hit` into `out`: all of them when they fit, else the curve
/// (linear in the angle between its samples, [`bsdf::measured_curve::eval`]) read at
/// `out.len()` uniform steps of the angle from 0 to π/2 — the resampled curve, linear
/// between those, differs from the curve by at most the largest distance of a sample from
/// it (both are linear between the samples and the new steps, and agree at the steps).
fn resample<'a>(samples: &[Leaf], hit: &[Vec4], out: &'a mut [Rgb]) -> &'a [Rgb] {
    let (n, m) = (samples.len(), out.len());
    if n <= m {
        for (v, s) in out.iter_mut().zip(samples) {
            *v = s.get(hit);
        }
        return &out[..n];
    }
    for (j, v) in out.iter_mut().enumerate() {
        // Step j of m − 1 lies at sample position j (n − 1)/(m − 1).
        let num = j * (n - 1);
        let (i, rest) = (num / (m - 1), num % (m - 1));
        let t = rest as f32 / (m - 1) as f32;
        *v =
            if rest == 0 { samples[i].get(hit) } else { samples[i].get(hit) * (1.0 - t) + samples[i + 1].get(hit) * t };
    }
    out
}

/// The most samples of a measured curve in `df` that varies over the surface and has more
/// than a lobe sum keeps ([`MAX_HIT_CURVE`]: such a curve is resampled, [`resample`]); for
/// a warning.
pub(super) fn resampled_curve(df: &Df) -> Option<usize> {
    let own = match df {
        Df::MeasuredCurveLayer { curve: CurveValues::Hit(s), .. }
        | Df::MeasuredCurveFactor { curve: CurveValues::Hit(s), .. }
            if s.len() > MAX_HIT_CURVE =>
        {
            Some(s.len())
        }
        _ => None,
    };
    let children = match df {
        Df::Mix { parts, .. } => parts.iter().filter_map(|(_, d)| resampled_curve(d)).max(),
        Df::Layer { layer, base, .. }
        | Df::CurveLayer { layer, base, .. }
        | Df::MeasuredCurveLayer { layer, base, .. } => resampled_curve(layer).max(resampled_curve(base)),
        Df::Sheen { multiscatter: b, .. }
        | Df::DirectionalFactor { base: b, .. }
        | Df::ThinFilm { base: b, .. }
        | Df::FresnelFactor { base: b, .. }
        | Df::MeasuredCurveFactor { base: b, .. }
        | Df::MeasuredFactor { base: b, .. } => resampled_curve(b),
        _ => None,
    };
    own.max(children)
}

/// The sum of a lobe sum's diffuse reflection weights, clamped to [0, 1].
fn diffuse_of<const N: usize, const C: usize, const F: usize, const T: usize>(sum: &GeneralSum<N, C, F, T>) -> Rgb {
    let diffuse = sum.parts().filter(|(_, l)| matches!(l, Lobe::Diffuse(_))).fold(Rgb::ZERO, |s, (w, _)| s + w);
    diffuse.clamp(Rgb::ZERO, Rgb::ONE)
}

/// Whether a sum whose lowering stopped is full (a lobe, curve or normal more than it
/// holds: [`GeneralSum::push_in_frame`], [`GeneralSum::add_curve_in_frame`] and
/// [`GeneralSum::add_normal`] refuse only then).
fn filled<const N: usize, const C: usize, const F: usize, const T: usize>(sum: &GeneralSum<N, C, F, T>) -> bool {
    sum.len() == N || usize::from(sum.curve_count) == C || usize::from(sum.normal_count) == F
}

/// Whether lowering `df` as a wide lobe sum stopped with the sum full.
pub(super) fn filled_up(df: &Df, hit: &[Vec4], medium: Medium) -> bool {
    let mut sum = WideLobes::default();
    let axis = super::tangents::first(df);
    !add_general(df, Rgb::ONE, hit, medium, &mut sum, Role::default(), None, 0, axis) && filled(&sum)
}
