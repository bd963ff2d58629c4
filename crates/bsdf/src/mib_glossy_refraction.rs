//! mental ray's `mib_glossy_refraction` as a path-tracing lobe over its top material.
//!
//! The classic shader adds to its top material the average of the radiance along
//! `samples` directions, each the refraction of the view through a micro-normal h drawn
//! from Ward's distribution of widths `u_spread`, `v_spread` (the anisotropic Beckmann
//! distribution D of α = the spreads: density D(h) cos θh) by the relative index η = n₁/n₂
//! (1/`ior` entering the front, `ior` leaving through the back), the mirror about h under
//! total internal reflection, discarding the directions that end on the wrong side, times
//! `refraction_color` c and the view-angle curve w(θo) (as `mib_glossy_reflection`'s).
//! Its estimate converges to ∫ L(ωi) c·w·p(ωi | ωo) / A(ωo) dωi, with p the density of the
//! resulting direction and A(ωo) the share of directions kept. For a refracted direction
//! ωt (Walter et al. 2007's half-vector relation h ∥ −(η ωo + ωt), flipped onto +z),
//!
//! p(ωt | ωo) = D(h) cos θh |ωt·h| / (η ωo·h + ωt·h)²,
//!
//! and for a totally reflected one D(h) cos θh / (4 |ωo·h|) (h ∥ ωo + ωi, where h totally
//! reflects). So f(ωo, ωi) = c·w(θo)·p(ωi | ωo) / (|cos θi| A(ωo)): its albedo is c·w at
//! every view whatever the spread, as the classic estimate's, and no η² radiance scaling
//! (mental ray has none). Spreads below 10⁻³ give the sharp refraction of `mib_refract`;
//! an `ior` within 10⁻⁴ of 1 passes straight through (the classic shader's refraction then
//! bends only about micro-normals facing away from the view: mira's reading). The top
//! material is a Lambertian albedo on the front (ωo above) only, as the classic shader
//! adds its top material there. Seen from the back the classic shader adds its
//! `back_material` instead, shaded with the normal turned towards the view (a Lambertian
//! albedo reflecting light from the back's side) or, with
//! `render_reverse_of_back_material`, with the normal facing out (light from the front's
//! side reaching the back: a Lambertian diffuse transmission, f = albedo/π for ωo below
//! and ωi above). Directions are in the local shading frame (z = the surface's front
//! normal: the lobe knows inside from outside).
//!
//! The top or back material is a layer of what the glossy lobe leaves: its albedo is
//! capped per channel at 1 − c·max w (the lobe's largest albedo over all views), so that
//! the two never scatter more than all the light, from either side. mira's departure from
//! the classic shader, which adds its top or back material whole: there that material
//! takes direct light alone, here its Lambertian layer also takes indirect light, and
//! inside a closed object a back material beside the totally reflected glossy lobe would
//! otherwise reflect more than it receives, bounce after bounce. Where the layer's albedo
//! plus c·max w is at most 1 (the common glass: a faint top, a dark back) nothing changes.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3A};

use crate::beckmann::Beckmann;
use crate::mib_glossy::{edge_weight, ward_normal, UpperFraction, MIRROR_SPREAD};
use crate::{cosine_hemisphere, luminance, BsdfSample, Rgb};

/// `ior` this close to 1 passes light straight through.
const STRAIGHT_IOR: f32 = 1e-4;

/// The direction the view `o` (upper side, unit) takes at micro-normal `h` (upper side)
/// for relative index `eta` = n₁/n₂: the refraction (`true`) or, under total internal
/// reflection, the mirror (`false`), as the classic shader computes it.
fn scatter(o: Vec3A, h: Vec3A, eta: f32) -> (Vec3A, bool) {
    let cos_i = o.dot(h);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t > 1.0 {
        return ((2.0 * cos_i * h - o).normalize(), false);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    ((-eta * o + h * (eta * cos_i - cos_t)).normalize(), true)
}

/// Whether the classic shader keeps direction `i` (refracted: below; reflected: above).
fn kept(i: Vec3A, refracted: bool) -> bool {
    if refracted {
        i.z < 0.0
    } else {
        i.z > 0.0
    }
}

/// The density p(ωi | ωo) of the classic shader's directions (upper `o`, relative index
/// `eta`), 0 where no micro-normal leads, or where the direction is not kept.
fn density(dist: &Beckmann, o: Vec3A, i: Vec3A, eta: f32) -> f32 {
    if i.z < 0.0 {
        let mut h = (-eta * o - i).normalize_or_zero();
        if h.z < 0.0 {
            h = -h;
        }
        let (oh, ih) = (o.dot(h), i.dot(h));
        if h == Vec3A::ZERO || ih >= 0.0 {
            return 0.0;
        }
        let denom = eta * oh + ih;
        if denom == 0.0 {
            return 0.0;
        }
        dist.d(h) * h.z * ih.abs() / (denom * denom)
    } else if i.z > 0.0 {
        let mut h = (o + i).normalize_or_zero();
        if h.z < 0.0 {
            h = -h;
        }
        let oh = o.dot(h);
        let total = eta * eta * (1.0 - oh * oh) > 1.0;
        if h == Vec3A::ZERO || oh == 0.0 || !total {
            return 0.0;
        }
        dist.d(h) * h.z / (4.0 * oh.abs())
    } else {
        0.0
    }
}

/// A(ωo): the share of the classic shader's directions kept (upper `o`, relative index
/// `eta`), by an `n`×`n` midpoint rule over its mapping.
pub fn kept_fraction(dist: &Beckmann, o: Vec3A, eta: f32, n: u32) -> f32 {
    let mut count = 0u32;
    for a in 0..n {
        for b in 0..n {
            let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
            let (i, refracted) = scatter(o, ward_normal(dist, u), eta);
            count += u32::from(kept(i, refracted));
        }
    }
    count as f32 / (n * n) as f32
}

/// The glossy refraction of `mib_glossy_refraction` over a Lambertian top, seen from one
/// direction (its weight already holds the view-angle curve and 1/A(ωo)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MibGlossyRefraction {
    /// Lambertian albedo of the material added on the side seen: the top material from
    /// the front, the back material from the back.
    pub base: Rgb,
    /// Whether `base` seen from the back transmits light from the front's side (the back
    /// material rendered reversed) rather than reflecting the back's.
    pub base_through: bool,
    /// The glossy lobe's weight: `refraction_color` × the view-angle curve / A(ωo).
    pub tint: Rgb,
    /// Ward's distribution of micro-normals; `None`: sharp.
    pub dist: Option<Beckmann>,
    /// n₁/n₂ for this view (1/`ior` from the front, `ior` from the back).
    pub eta: f32,
}

impl MibGlossyRefraction {
    /// The probability of sampling the glossy lobe (by the two lobes' albedos).
    fn glossy_probability(&self) -> f32 {
        let (g, b) = (luminance(self.tint).max(0.0), luminance(self.base).max(0.0));
        if g + b > 0.0 {
            g / (g + b)
        } else {
            0.0
        }
    }

    /// Whether light passes straight through (`ior` 1).
    fn straight(&self) -> bool {
        (self.eta - 1.0).abs() < STRAIGHT_IOR
    }

    /// Whether the glossy lobe is a delta (sharp, or straight through).
    fn delta_lobe(&self) -> bool {
        self.dist.is_none() || self.straight()
    }

    /// `wo` and `wi` flipped together so that `wo` is above.
    fn flipped(wo: Vec3A, wi: Vec3A) -> (Vec3A, Vec3A) {
        if wo.z < 0.0 {
            (Vec3A::new(wo.x, wo.y, -wo.z), Vec3A::new(wi.x, wi.y, -wi.z))
        } else {
            (wo, wi)
        }
    }

    /// f(ωo, ωi) of the glossy lobe alone (0 when it is a delta).
    fn eval_glossy(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        match self.dist {
            Some(dist) if !self.straight() && wi.z != 0.0 => {
                let (o, i) = Self::flipped(wo, wi);
                self.tint * (density(&dist, o, i, self.eta) / i.z.abs())
            }
            _ => Rgb::ZERO,
        }
    }

    /// Whether the top (or back) material's Lambertian lobe scatters from `wo` to `wi`:
    /// reflection on the front; on the back reflection, or transmission from the front's
    /// side where `base_through`.
    fn base_pair(&self, wo: Vec3A, wi: Vec3A) -> bool {
        if wo.z > 0.0 {
            wi.z > 0.0
        } else if wo.z < 0.0 {
            if self.base_through {
                wi.z > 0.0
            } else {
                wi.z < 0.0
            }
        } else {
            false
        }
    }

    /// The top's (or back's) part of f(ωo, ωi).
    fn eval_base(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if self.base_pair(wo, wi) {
            self.base * FRAC_1_PI
        } else {
            Rgb::ZERO
        }
    }

    /// f(ωo, ωi) of the non-delta lobes: the top's albedo/π plus the glossy lobe.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        self.eval_base(wo, wi) + self.eval_glossy(wo, wi)
    }

    /// Density of [`MibGlossyRefraction::sample`] (non-delta lobes).
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let pg = self.glossy_probability();
        let base = if self.base_pair(wo, wi) { (1.0 - pg) * wi.z.abs() * FRAC_1_PI } else { 0.0 };
        let glossy = match self.dist {
            Some(dist) if !self.straight() && wo.z != 0.0 => {
                let (o, i) = Self::flipped(wo, wi);
                density(&dist, o, i, self.eta)
            }
            _ => 0.0,
        };
        base + pg * glossy
    }

    /// Samples the glossy lobe (the classic shader's direction about a micro-normal of
    /// D(h) cos θh; `None` where it discards it, which the weight 1/A(ωo) of the others
    /// makes up for) or the top (cosine-weighted), chosen by `u_lobe`.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let pg = self.glossy_probability();
        let o = Vec3A::new(wo.x, wo.y, wo.z.abs());
        let back = |i: Vec3A| if wo.z < 0.0 { Vec3A::new(i.x, i.y, -i.z) } else { i };
        let wi = if u_lobe < pg {
            let h = match self.dist {
                _ if self.straight() => {
                    let wi = -wo;
                    return Some(BsdfSample { wi, f: self.tint / wo.z.abs(), pdf: pg, delta: true });
                }
                None => Vec3A::Z,
                Some(dist) => dist.sample(u),
            };
            let (i, refracted) = scatter(o, h, self.eta);
            if !kept(i, refracted) {
                return None;
            }
            if self.dist.is_none() {
                return Some(BsdfSample { wi: back(i), f: self.tint / i.z.abs(), pdf: pg, delta: true });
            }
            back(i)
        } else {
            if wo.z < 0.0 && self.base == Rgb::ZERO {
                return None;
            }
            let w = cosine_hemisphere(u);
            // On the back: reflected below, or transmitted above.
            if wo.z < 0.0 && !self.base_through {
                Vec3A::new(w.x, w.y, -w.z)
            } else {
                w
            }
        };
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }

    /// Whether every lobe is a delta (a sharp or straight lobe without a top).
    pub fn is_delta(&self) -> bool {
        self.delta_lobe() && (self.base == Rgb::ZERO)
    }

    /// Whether a transmitted sample is a refraction (mental ray's refraction level): all
    /// but the sharp straight pass of `ior` 1, which the classic shader casts as a
    /// transparency ray.
    pub fn refracts(&self) -> bool {
        !(self.straight() && self.dist.is_none())
    }

    /// Whether a transmitted sample seen from `wo` may be the back material's diffuse
    /// transmission rather than the glossy lobe's (then [`MibGlossyRefraction::glossy_share`]
    /// tells them apart).
    pub fn base_transmits(&self, wo: Vec3A) -> bool {
        wo.z < 0.0 && self.base_through && self.base != Rgb::ZERO
    }

    /// The glossy lobe's share of f(ωo, ωi) (luminance) for a non-delta sample: the
    /// probability that it (a totally reflected ray, on ωo's side, or a refracted one
    /// beside a back material's diffuse transmission) rather than the top or back gave it.
    pub fn glossy_share(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let all = luminance(self.eval(wo, wi));
        if all > 0.0 {
            (luminance(self.eval_glossy(wo, wi)) / all).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The top's part of f(ωo, ωi) (diffuse) and the glossy lobe's (specular).
    pub fn eval_split(&self, wo: Vec3A, wi: Vec3A) -> (Rgb, Rgb) {
        (self.eval_base(wo, wi), self.eval_glossy(wo, wi))
    }
}

/// A `mib_glossy_refraction` lobe's constant parameters: what [`MibGlossyRefraction`] is
/// built from at each view.
#[derive(Clone, Debug, PartialEq)]
pub struct MibGlossyRefractionLobe {
    /// `refraction_color`.
    pub color: Rgb,
    /// The view-angle curve: (`refraction_base_weight`, `refraction_edge_weight`,
    /// `edge_factor`).
    pub curve: (f32, f32, f32),
    /// `ior` (the inside's index; the outside's is 1).
    pub ior: f32,
    /// Ward's distribution (`u_spread`, `v_spread` along the frame's x, y); `None`: sharp.
    pub dist: Option<Beckmann>,
    /// A(ωo) entering from the front and leaving from the back.
    kept: Option<(UpperFraction, UpperFraction)>,
    /// The back material's Lambertian albedo (`back_material`: what the classic shader
    /// adds seen from the back, in place of the top material).
    pub back: Rgb,
    /// `render_reverse_of_back_material`: the back material is lit from the front's side
    /// (a diffuse transmission) rather than from the back's.
    pub back_through: bool,
    /// `max_distance`: the glossy rays (refracted and totally reflected) fade towards the
    /// deep material by (d / max_distance)^`falloff` over a distance d, wholly past it; 0:
    /// no limit (the integrator splits the segments, `render`'s `integrator::glossy_reach`).
    pub max_distance: f32,
    /// `falloff`: the power of the fade.
    pub falloff: f32,
    /// [`MibGlossyRefractionLobe::layer_room`].
    room: Rgb,
}

/// What a glossy lobe of `color` and view-angle `curve` leaves at the view where it takes
/// most, per channel: 1 − c·max w (the curve is monotonic in cos θ, so its largest value
/// is at the normal or at grazing); unbounded in channels the lobe does not take from.
fn room_left(color: Rgb, curve: (f32, f32, f32)) -> Rgb {
    let w = edge_weight(0.0, curve).max(edge_weight(1.0, curve)).max(0.0);
    let room = |c: f32| if c * w > 0.0 { (1.0 - c * w).max(0.0) } else { f32::INFINITY };
    Rgb::new(room(color.x), room(color.y), room(color.z))
}

impl MibGlossyRefractionLobe {
    /// The lobe of `color`, view-angle `curve`, `ior` (≤ 0 counts as 1) and spreads
    /// (radians, along x and y).
    pub fn new(color: Rgb, curve: (f32, f32, f32), ior: f32, spreads: (f32, f32)) -> MibGlossyRefractionLobe {
        let ior = if ior > 0.0 { ior } else { 1.0 };
        let (su, sv) = (spreads.0.max(0.0), spreads.1.max(0.0));
        let dist = (su >= MIRROR_SPREAD || sv >= MIRROR_SPREAD).then(|| Beckmann::new(su, sv));
        let n = UpperFraction::QUADRATURE;
        let kept = dist.filter(|_| (ior - 1.0).abs() >= STRAIGHT_IOR).map(|d| {
            (
                UpperFraction::of(&d, |o| kept_fraction(&d, o, 1.0 / ior, n)),
                UpperFraction::of(&d, |o| kept_fraction(&d, o, ior, n)),
            )
        });
        let room = room_left(color, curve);
        MibGlossyRefractionLobe {
            color,
            curve,
            ior,
            dist,
            kept,
            back: Rgb::ZERO,
            back_through: false,
            max_distance: 0.0,
            falloff: 2.0,
            room,
        }
    }

    /// The lobe with a back material of Lambertian albedo `back`, lit from the front's
    /// side (`through`, mental ray's `render_reverse_of_back_material`) or the back's.
    pub fn with_back(self, back: Rgb, through: bool) -> MibGlossyRefractionLobe {
        MibGlossyRefractionLobe { back, back_through: through, ..self }
    }

    /// The lobe whose glossy rays fade into the deep material over `max_distance` (≤ 0:
    /// none) by the power `falloff`.
    pub fn with_reach(self, max_distance: f32, falloff: f32) -> MibGlossyRefractionLobe {
        MibGlossyRefractionLobe { max_distance: max_distance.max(0.0), falloff, ..self }
    }

    /// Whether the glossy rays fade into the deep material (a `max_distance`, and a lobe
    /// that casts rays: mental ray's shader casts none of `refraction_color` black).
    pub fn reaches(&self) -> bool {
        self.max_distance > 0.0 && self.color != Rgb::ZERO
    }

    /// The most the Lambertian layer (top or back material) may reflect per channel: what
    /// the glossy lobe leaves at the view where it takes most, 1 − c·max w over all views
    /// (unbounded in channels the lobe does not take from: there the layer keeps its albedo).
    pub fn layer_room(&self) -> Rgb {
        self.room
    }

    /// The BSDF seen from `wo` (local frame, z = the front normal) over a top of Lambertian
    /// albedo `base` (the back material's albedo seen from the back).
    ///
    /// The Lambertian layer is capped at [`MibGlossyRefractionLobe::layer_room`], so that
    /// the layer and the glossy lobe together scatter at most all the light from either
    /// side (white furnace ≤ 1; a constant cap keeps the layer reciprocal). The classic
    /// shader adds its top or back material uncapped (it takes direct light alone, the
    /// path engine's layer also indirect light, which inside a closed object would grow
    /// without bound); where the layer's albedo and the lobe's largest albedo sum to at
    /// most 1 nothing changes.
    pub fn bsdf(&self, base: Rgb, wo: Vec3A) -> MibGlossyRefraction {
        let front = wo.z > 0.0;
        let w = edge_weight(wo.z.abs(), self.curve);
        let a = self.kept.as_ref().map_or(1.0, |(f, b)| if front { f.at(wo) } else { b.at(wo) });
        let layer = if front { base } else { self.back };
        MibGlossyRefraction {
            base: layer.min(self.room),
            base_through: !front && self.back_through,
            tint: self.color * (w.max(0.0) / a),
            dist: self.dist,
            eta: if front { 1.0 / self.ior } else { self.ior },
        }
    }
}

#[cfg(test)]
mod tests;
