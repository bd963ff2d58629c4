//! mental ray's `mib_glossy_reflection` as a path-tracing lobe over its base material.
//!
//! The classic shader adds to its base material the average of the radiance along
//! `samples` directions, each the mirror of the view about a micro-normal h drawn from
//! Ward's distribution of widths `u_spread`, `v_spread` (the anisotropic Beckmann
//! distribution D of α = the spreads: density D(h) cos θh), discarding directions below
//! the surface, times `reflection_color` c and the view-angle curve
//! w(θo) = base + (edge − base)·(1 − cos θo)^factor. Its estimate converges to
//! ∫ L(ωi) c·w·p(ωi | ωo) / A(ωo) dωi, with p(ωi | ωo) = D(h) cos θh / (4 ωo·h) the density
//! of the reflected direction and A(ωo) = ∫ over the upper hemisphere of p the share of
//! directions kept. So the lobe is
//!
//! f(ωo, ωi) = c·w(θo) · D(h) cos θh / (4 (ωo·h) cos θi A(ωo))
//!
//! whose albedo is c·w(θo) at every view: that of the classic estimate, whatever the
//! spread. It is not reciprocal (nor is the classic estimate): f(ωo, ωi) cos θi A(ωo) / w(θo)
//! is symmetric instead. Spreads below 10⁻³ give the mirror of weight c·w (`mib_reflect`).
//! The base material is a Lambertian albedo added under it, as the classic shader adds its
//! base material's colour. Directions are in the local shading frame (z = normal); the
//! lobe is two-sided (a view from below is mirrored onto the upper side).

use std::f32::consts::{FRAC_1_PI, FRAC_PI_2};

use glam::{Vec2, Vec3A};

use crate::beckmann::Beckmann;
use crate::{cosine_hemisphere, luminance, BsdfSample, Rgb};

/// Spreads below this (radians) make the lobe a mirror.
pub const MIRROR_SPREAD: f32 = 1e-3;

/// The glossy reflection of `mib_glossy_reflection` over a Lambertian base, seen from one
/// direction (its weight already holds the view-angle curve and 1/A(ωo)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MibGlossy {
    /// Lambertian albedo of the base material under the lobe.
    pub base: Rgb,
    /// The glossy lobe's weight for the view it was made for: the colour its rays carry
    /// ([`MibGlossyLobe::carried`]: `reflection_color`, or `environment_color` where that
    /// is 0) × the view-angle curve / A(ωo) (the albedo of the lobe is then `tint`·A(ωo)).
    /// Sampled rays carry it; what they find is weighed by `seen` on top.
    pub tint: Rgb,
    /// Ward's distribution of micro-normals; `None`: a mirror.
    pub dist: Option<Beckmann>,
    /// The share of `tint` the lobe reflects of what its rays find, per channel (1; 0
    /// where only `environment_color` is carried): [`MibGlossy::eval`] (light found by
    /// next-event estimation) holds it, [`MibGlossy::sample`]'s weight does not (the path
    /// engine applies it along the segment, `render`'s `integrator::glossy_reach`).
    pub seen: Rgb,
}

/// ωo and ωi flipped onto +z together when ωo is below; `None` across the surface.
fn upper(wo: Vec3A, wi: Vec3A) -> Option<(Vec3A, Vec3A)> {
    if wo.z * wi.z <= 0.0 {
        return None;
    }
    let flip = |w: Vec3A| if wo.z < 0.0 { Vec3A::new(w.x, w.y, -w.z) } else { w };
    Some((flip(wo), flip(wi)))
}

/// The density p(ωi | ωo) = D(h) cos θh / (4 ωo·h) of the mirror direction about a
/// micro-normal drawn from D(h) cos θh (upper side, ωo·h > 0), 0 elsewhere.
fn reflected_density(dist: &Beckmann, o: Vec3A, i: Vec3A) -> f32 {
    let h = (o + i).normalize_or_zero();
    let oh = o.dot(h);
    if h == Vec3A::ZERO || oh <= 0.0 {
        return 0.0;
    }
    dist.d(h) * h.z / (4.0 * oh)
}

impl MibGlossy {
    /// The probability of sampling the glossy lobe (by the two lobes' albedos).
    fn glossy_probability(&self) -> f32 {
        let (g, b) = (luminance(self.tint).max(0.0), luminance(self.base).max(0.0));
        if g + b > 0.0 {
            g / (g + b)
        } else {
            0.0
        }
    }

    /// f(ωo, ωi) of the glossy lobe alone (0 for a mirror).
    fn eval_glossy(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        let (Some(dist), Some((o, i))) = (self.dist, upper(wo, wi)) else { return Rgb::ZERO };
        self.tint * (reflected_density(&dist, o, i) / i.z)
    }

    /// f(ωo, ωi) of the non-delta lobes: the base's albedo/π plus the glossy lobe (its
    /// `seen` share).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        self.base * FRAC_1_PI + self.eval_glossy(wo, wi) * self.seen
    }

    /// f(ωo, ωi) with the glossy lobe's whole carried colour (the weight of its samples).
    fn eval_carried(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        self.base * FRAC_1_PI + self.eval_glossy(wo, wi)
    }

    /// Density of [`MibGlossy::sample`] (non-delta lobes).
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let Some((o, i)) = upper(wo, wi) else { return 0.0 };
        let pg = self.glossy_probability();
        let glossy = self.dist.map_or(0.0, |d| reflected_density(&d, o, i));
        (1.0 - pg) * i.z * FRAC_1_PI + pg * glossy
    }

    /// Samples the glossy lobe (the mirror direction about a micro-normal of D(h) cos θh;
    /// `None` below the surface, which the weight 1/A(ωo) of the others makes up for) or
    /// the base (cosine-weighted), chosen by `u_lobe`.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let pg = self.glossy_probability();
        if pg <= 0.0 && self.base == Rgb::ZERO {
            return None;
        }
        let o = if wo.z < 0.0 { Vec3A::new(wo.x, wo.y, -wo.z) } else { wo };
        let back = |i: Vec3A| if wo.z < 0.0 { Vec3A::new(i.x, i.y, -i.z) } else { i };
        let i = if u_lobe < pg {
            match self.dist {
                None => {
                    let wi = back(Vec3A::new(-o.x, -o.y, o.z));
                    return Some(BsdfSample { wi, f: self.tint / o.z, pdf: pg, delta: true });
                }
                Some(dist) => {
                    let h = dist.sample(u);
                    let oh = o.dot(h);
                    let i = 2.0 * oh * h - o;
                    if oh <= 0.0 || i.z <= 0.0 {
                        return None;
                    }
                    i
                }
            }
        } else {
            cosine_hemisphere(u)
        };
        let wi = back(i);
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval_carried(wo, wi), pdf, delta: false })
    }

    /// Whether every lobe is a delta (a mirror without a base).
    pub fn is_delta(&self) -> bool {
        self.dist.is_none() && self.base == Rgb::ZERO
    }

    /// The glossy lobe's share of f(ωo, ωi) (luminance), for a non-delta sample: the
    /// probability that the glossy lobe rather than the base gave it.
    pub fn reflection_share(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let all = luminance(self.eval_carried(wo, wi));
        if all > 0.0 {
            (luminance(self.eval_glossy(wo, wi)) / all).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The base's part of f(ωo, ωi) (diffuse) and the glossy lobe's (specular, its `seen`
    /// share: what lights light).
    pub fn eval_split(&self, wo: Vec3A, wi: Vec3A) -> (Rgb, Rgb) {
        let (b, g) = self.carried_split(wo, wi);
        (b, g * self.seen)
    }

    /// The base's part of a sample's f(ωo, ωi) and the glossy lobe's (its whole carried
    /// colour): the shares of a sampled bounce's weight.
    pub fn carried_split(&self, wo: Vec3A, wi: Vec3A) -> (Rgb, Rgb) {
        if wo.z * wi.z <= 0.0 {
            return (Rgb::ZERO, Rgb::ZERO);
        }
        (self.base * FRAC_1_PI, self.eval_glossy(wo, wi))
    }
}

/// The view-angle curve of mental ray's glossy shaders: base + (edge − base)·(1 − cos θ)^factor
/// (`cos` = |cos θo|; a negative factor counts as 0).
pub fn edge_weight(cos: f32, (base, edge, factor): (f32, f32, f32)) -> f32 {
    base + (edge - base) * (1.0 - cos.clamp(0.0, 1.0)).powf(factor.max(0.0))
}

/// A micro-normal of Ward's distribution by the classic shader's mapping (Walter 2005's
/// form of Ward 1992): φ from the aspect of the spreads, tan²θ = −ln(1 − u.x) /
/// (cos²φ/αx² + sin²φ/αy²). The same distribution as [`Beckmann::sample`].
pub(crate) fn ward_normal(dist: &Beckmann, u: Vec2) -> Vec3A {
    let (ax, ay) = (dist.alpha_x, dist.alpha_y);
    let a = std::f32::consts::TAU * u.y;
    let phi = (ay * a.sin()).atan2(ax * a.cos());
    let (s, c) = phi.sin_cos();
    let tan2 = -(1.0 - u.x).max(1e-12).ln() / (c * c / (ax * ax) + s * s / (ay * ay));
    let cos_t = 1.0 / (1.0 + tan2).sqrt();
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    Vec3A::new(sin_t * c, sin_t * s, cos_t)
}

/// A(ωo): the share of mirror directions about micro-normals of `dist` (D(h) cos θh) that
/// lie above the surface, by an `n`×`n` midpoint rule over the classic shader's mapping.
pub fn upper_fraction(dist: &Beckmann, wo: Vec3A, n: u32) -> f32 {
    let o = Vec3A::new(wo.x, wo.y, wo.z.abs());
    let mut kept = 0u32;
    for a in 0..n {
        for b in 0..n {
            let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
            let h = ward_normal(dist, u);
            let oh = o.dot(h);
            if oh > 0.0 && 2.0 * oh * h.z - o.z > 0.0 {
                kept += 1;
            }
        }
    }
    kept as f32 / (n * n) as f32
}

/// Nodes of [`UpperFraction`] along cos θo (0 to 1) and along φo (0 to π/2).
const COS_NODES: usize = 33;
const PHI_NODES: usize = 17;
/// The quadrature's side per node (64² micro-normals).
const QUADRATURE: u32 = 64;

/// A(ωo) of one distribution, tabulated over cos θo and φo (D is symmetric about both
/// axes, so φo in [0, π/2] covers every view; one column when isotropic) and interpolated
/// bilinearly (the midpoint rule's and the interpolation's error: ≈ 10⁻³).
#[derive(Clone, Debug, PartialEq)]
pub struct UpperFraction {
    values: Vec<f32>,
    phis: usize,
}

impl UpperFraction {
    /// The table of `dist`.
    pub fn new(dist: &Beckmann) -> UpperFraction {
        let phis = if dist.alpha_x == dist.alpha_y { 1 } else { PHI_NODES };
        let alpha = dist.alpha_x.max(dist.alpha_y);
        let mut values = Vec::with_capacity(COS_NODES * phis);
        for c in 0..COS_NODES {
            let cos = c as f32 / (COS_NODES - 1) as f32;
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            // A direction leaves the upper side only about micro-normals tilted by at
            // least (π/2 − θo)/2, which Ward's distribution draws with probability at
            // most exp(−tan²/α²).
            let tilt = (FRAC_PI_2 - cos.acos()) / 2.0;
            let bound = (-(tilt.tan() / alpha).powi(2)).exp();
            for p in 0..phis {
                let phi = if phis > 1 { FRAC_PI_2 * p as f32 / (phis - 1) as f32 } else { 0.0 };
                let wo = Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos);
                values.push(if bound < 1e-7 { 1.0 } else { upper_fraction(dist, wo, QUADRATURE) });
            }
        }
        UpperFraction { values, phis }
    }

    /// A table of `share(ωo)` (upper views; a share of micro-normals, as A) at the
    /// nodes of [`UpperFraction::new`], for another lobe of `dist`.
    pub fn of(dist: &Beckmann, share: impl Fn(Vec3A) -> f32) -> UpperFraction {
        let phis = if dist.alpha_x == dist.alpha_y { 1 } else { PHI_NODES };
        let mut values = Vec::with_capacity(COS_NODES * phis);
        for c in 0..COS_NODES {
            let cos = c as f32 / (COS_NODES - 1) as f32;
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            for p in 0..phis {
                let phi = if phis > 1 { FRAC_PI_2 * p as f32 / (phis - 1) as f32 } else { 0.0 };
                values.push(share(Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos)));
            }
        }
        UpperFraction { values, phis }
    }

    /// The quadrature's side per node of the tables.
    pub const QUADRATURE: u32 = QUADRATURE;

    /// A(ωo), interpolated.
    pub fn at(&self, wo: Vec3A) -> f32 {
        let cos = wo.z.abs().min(1.0);
        let x = cos * (COS_NODES - 1) as f32;
        let c0 = (x as usize).min(COS_NODES - 2);
        let tc = x - c0 as f32;
        let (p0, tp) = if self.phis > 1 {
            let phi = wo.y.abs().atan2(wo.x.abs());
            let y = phi / FRAC_PI_2 * (self.phis - 1) as f32;
            let p0 = (y as usize).min(self.phis - 2);
            (p0, y - p0 as f32)
        } else {
            (0, 0.0)
        };
        let v = |c: usize, p: usize| self.values[c * self.phis + p.min(self.phis - 1)];
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let row = |c: usize| lerp(v(c, p0), v(c, p0 + 1), tp);
        lerp(row(c0), row(c0 + 1), tc).max(1e-3)
    }
}

/// A `mib_glossy_reflection` lobe's constant parameters: what [`MibGlossy`] is built from
/// at each view.
#[derive(Clone, Debug, PartialEq)]
pub struct MibGlossyLobe {
    /// `reflection_color`.
    pub color: Rgb,
    /// The view-angle curve: (`reflection_base_weight`, `reflection_edge_weight`,
    /// `edge_factor`).
    pub curve: (f32, f32, f32),
    /// Ward's distribution (`u_spread`, `v_spread` along the frame's x, y); `None`: mirror.
    pub dist: Option<Beckmann>,
    /// A(ωo) of `dist`.
    upper: Option<UpperFraction>,
    /// `environment_color`: what the lobe's rays that take the environment (leaving the
    /// scene, or past `max_distance`) weigh it by instead of `color` (the path engine
    /// applies the ratio per channel: see [`MibGlossyLobe::environment_ratio`]).
    pub env_color: Rgb,
    /// `max_distance` (scene units): the lobe's rays that travel farther take the
    /// environment; a hit at distance d nearer fades towards it by (d / max)^`falloff`.
    /// 0: no limit.
    pub max_distance: f32,
    /// `falloff`: the power of that fade.
    pub falloff: f32,
}

impl MibGlossyLobe {
    /// The lobe of `color`, view-angle `curve` and spreads (radians, along x and y).
    pub fn new(color: Rgb, curve: (f32, f32, f32), spreads: (f32, f32)) -> MibGlossyLobe {
        let (su, sv) = (spreads.0.max(0.0), spreads.1.max(0.0));
        let dist = (su >= MIRROR_SPREAD || sv >= MIRROR_SPREAD).then(|| Beckmann::new(su, sv));
        let upper = dist.as_ref().map(UpperFraction::new);
        MibGlossyLobe { color, curve, dist, upper, env_color: color, max_distance: 0.0, falloff: 2.0 }
    }

    /// The lobe whose rays weigh the environment by `env_color` and take it past
    /// `max_distance` (0: no limit), fading towards it by (d / max)^`falloff` nearer.
    pub fn with_reach(self, env_color: Rgb, max_distance: f32, falloff: f32) -> MibGlossyLobe {
        MibGlossyLobe { env_color, max_distance: max_distance.max(0.0), falloff, ..self }
    }

    /// Whether the lobe's rays see the environment otherwise than a path's other rays do
    /// (an `environment_color` other than `color`, or a `max_distance`).
    pub fn reaches(&self) -> bool {
        self.max_distance > 0.0 || self.env_color != self.color
    }

    /// The colour the lobe's rays carry, per channel: `color`, or `env_color` where
    /// `color` is 0 (or less) and `env_color` is not (the classic shader's rays there see
    /// the environment alone).
    pub fn carried(&self) -> Rgb {
        let pick = |c: f32, e: f32| if c <= 0.0 && e > 0.0 { e } else { c };
        Rgb::new(
            pick(self.color.x, self.env_color.x),
            pick(self.color.y, self.env_color.y),
            pick(self.color.z, self.env_color.z),
        )
    }

    /// `color` / [`MibGlossyLobe::carried`] per channel: 1, or 0 where the rays carry
    /// `env_color` alone (what they find is not reflected there).
    pub fn seen(&self) -> Rgb {
        let k = self.carried();
        let share = |c: f32, k: f32| if c == k { 1.0 } else { 0.0 };
        Rgb::new(share(self.color.x, k.x), share(self.color.y, k.y), share(self.color.z, k.z))
    }

    /// `env_color` / [`MibGlossyLobe::carried`] per channel (0 where nothing is carried).
    pub fn environment_ratio(&self) -> Rgb {
        let ratio = |e: f32, c: f32| if c > 0.0 { e / c } else { 0.0 };
        let k = self.carried();
        Rgb::new(ratio(self.env_color.x, k.x), ratio(self.env_color.y, k.y), ratio(self.env_color.z, k.z))
    }

    /// The BSDF seen from `wo` (local frame) over a base of Lambertian albedo `base`.
    pub fn bsdf(&self, base: Rgb, wo: Vec3A) -> MibGlossy {
        let w = edge_weight(wo.z.abs(), self.curve);
        let a = self.upper.as_ref().map_or(1.0, |u| u.at(wo));
        MibGlossy { base, tint: self.carried() * (w.max(0.0) / a), dist: self.dist, seen: self.seen() }
    }
}

#[cfg(test)]
mod tests;
