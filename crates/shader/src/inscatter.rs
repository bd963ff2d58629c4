//! Single scattering in the classic engine's participating media: the light a homogeneous
//! medium (MDL's `material_volume`, [`super::shading::MaterialShaders::medium`]) scatters
//! into a ray segment towards the ray's origin, the way mental ray's volume shaders add it
//! (the base library's `parti_volume`): at points along the segment the scene's lights are
//! sampled through the light loop (their shaders, shadow rays through the media on the
//! way, see [`super::volume::ShadowMedia`]) and weighed by the phase function, the
//! scattering coefficient and the transmittance back to the ray's origin:
//!
//! S = π ∫₀ᴸ T(t) σs Σ_lights p(θ) L_light(x(t)) dt,  T(t) = exp(−σt t),
//!
//! θ between the light's travel and the ray's reversed direction, p the Henyey–Greenstein
//! phase function (normalised to 1 over the sphere; the factor π is the base shaders'
//! convention, in which a light's colour carries no 1/π, as `parti_volume`'s phase
//! function, normalised to π, and a Lambert surface lit by the same light do).
//!
//! Each light gets its own points along the segment, half drawn by *equiangular* sampling
//! (density ∝ 1/r² towards the light's position: what a point or small light near the ray
//! asks for; Kulla and Fajardo, "Importance sampling techniques for path tracing in
//! participating media", EGSR 2012) and half by *distance* sampling (density ∝ the
//! transmittance, the channels' mean extinction), combined by the balance heuristic; lights
//! without a position (directional) only by distance. A segment to infinity (a ray that left
//! an unclosed medium) counts up to where every scattering channel's transmittance is below
//! 10⁻⁴. Multiple scattering is not computed, as in mental ray's volume shaders.

use std::f32::consts::PI;

use bsdf::{Medium, Rgb};
use glam::Vec3A;
use scene::LightKind;

use super::ctx::Ctx;
use super::state::{RayType, State};

/// Points per light along one segment of an eye, reflection, refraction or transparency
/// ray (half by each strategy); the pixel's samples average further.
const POINTS: u32 = 8;
/// Points per light along one segment of a final gather ray (many rays are averaged).
const GATHER_POINTS: u32 = 2;
/// Optical depth past which a segment to infinity is taken as opaque (T = 10⁻⁴).
const OPAQUE_DEPTH: f32 = 9.21;

impl Ctx<'_> {
    /// The light `medium` scatters towards the origin of `ray` (the traced ray's state after
    /// intersection, its media those it travelled in) over the ray's first `length` units
    /// (infinite for a ray that hit nothing): see the module documentation. Zero for a
    /// medium that only absorbs or a scene without lights.
    pub fn in_scattered(&mut self, medium: &Medium, ray: &State, length: f32) -> Rgb {
        let shading = self.shading();
        if !medium.scatters() || shading.lights.is_empty() {
            return Rgb::ZERO;
        }
        let sigma_t = medium.sigma_t();
        let end = if length.is_finite() {
            length
        } else {
            // The thinnest channel that scatters decides how far light comes back from.
            let thinnest = Rgb::select(medium.sigma_s.cmpgt(Rgb::ZERO), sigma_t, Rgb::splat(f32::INFINITY));
            OPAQUE_DEPTH / thinnest.min_element()
        };
        if !(end > 0.0 && end.is_finite()) {
            return Rgb::ZERO;
        }
        let pairs = if ray.ray_type == RayType::Finalgather { GATHER_POINTS } else { POINTS } / 2;
        let distance = Exponential::new(sigma_t.element_sum() / 3.0, end);
        let mut ctx = Ctx::new(shading, self.tracer, ray.clone());
        // Not on a surface: shadow rays start at the point itself, lights on every side.
        ctx.state.normal = -ray.dir;
        ctx.state.normal_geom = Vec3A::ZERO;
        let mut total = Rgb::ZERO;
        for light in 0..shading.lights.len() as u32 {
            let Some(l) = ctx.light(light) else { continue };
            let towards =
                if l.kind == LightKind::Directional { None } else { Equiangular::new(ray.org, ray.dir, l.origin, end) };
            let site = ctx.next_site();
            let numbers = ctx.site_pairs(site, pairs);
            let mut sum = Rgb::ZERO;
            for i in 0..pairs {
                let u = numbers.pair(i);
                // Two points a pair: one by each strategy (both by distance without a position).
                let ts = match &towards {
                    Some(e) => [e.sample(u.x), distance.sample(u.y)],
                    None => [distance.sample(u.x), distance.sample(u.y)],
                };
                for t in ts {
                    let pdf = match &towards {
                        Some(e) => 0.5 * (e.pdf(t) + distance.pdf(t)),
                        None => distance.pdf(t),
                    };
                    if !(pdf > 0.0 && pdf.is_finite()) {
                        continue;
                    }
                    let lit = ctx.light_scattered_at(light, ray.org + ray.dir * t, ray.dir, medium);
                    sum += medium.transmittance(t) * medium.sigma_s * lit / pdf;
                }
            }
            total += sum / (2 * pairs) as f32;
        }
        ctx.flush_cache();
        self.counts.calls += ctx.counts.calls;
        total * PI
    }

    /// The mean over the samples of `light` at point `x` of a ray travelling along unit
    /// `dir` of the light's colour (after its shader and shadows) × `medium`'s phase
    /// function towards −`dir`.
    fn light_scattered_at(&mut self, light: u32, x: Vec3A, dir: Vec3A, medium: &Medium) -> Rgb {
        self.state.point = x;
        self.state.shadow_point = x;
        self.flush_cache();
        let mut lp = self.light_loop(light);
        lp.both_sides = true;
        let mut sum = Rgb::ZERO;
        while let Some(s) = self.sample_light(&mut lp) {
            sum += Rgb::new(s.color.x, s.color.y, s.color.z) * medium.phase.value(dir, s.dir);
        }
        if lp.samples > 0 {
            sum / lp.samples as f32
        } else {
            Rgb::ZERO
        }
    }
}

/// Equiangular sampling of distances t ∈ [0, end] along a ray towards a point c: density
/// ∝ 1 / |x(t) − c|², uniform in the angle under which the ray is seen from c.
#[derive(Clone, Copy, Debug)]
struct Equiangular {
    /// Distance along the ray to the foot of the perpendicular from c.
    foot: f32,
    /// Distance from c to the ray's line.
    height: f32,
    /// The angles (from the perpendicular) of the segment's ends, seen from c.
    angles: (f32, f32),
}

impl Equiangular {
    /// Sampling over [0, `end`] of the ray from `org` along unit `dir` towards `centre`;
    /// `None` when the centre lies (nearly) on the ray's line.
    fn new(org: Vec3A, dir: Vec3A, centre: Vec3A, end: f32) -> Option<Equiangular> {
        let to = centre - org;
        let foot = to.dot(dir);
        let height = (to - dir * foot).length();
        if !(height > 1e-5 * (end + foot.abs()) && height.is_finite()) {
            return None;
        }
        let angles = ((-foot / height).atan(), ((end - foot) / height).atan());
        (angles.1 > angles.0).then_some(Equiangular { foot, height, angles })
    }

    /// The distance for a number `u` in [0, 1).
    fn sample(&self, u: f32) -> f32 {
        let (a, b) = self.angles;
        self.foot + self.height * (a + u * (b - a)).tan()
    }

    /// The density of distance `t`.
    fn pdf(&self, t: f32) -> f32 {
        let (a, b) = self.angles;
        let r = t - self.foot;
        self.height / ((b - a) * (self.height * self.height + r * r))
    }
}

/// Distance sampling over [0, `end`]: density ∝ exp(−σ t) for one extinction σ (uniform
/// where the segment is optically thin).
#[derive(Clone, Copy, Debug)]
struct Exponential {
    sigma: f32,
    end: f32,
    /// 1 − exp(−σ end): the untruncated density's mass on the segment.
    mass: f32,
}

impl Exponential {
    /// Below this optical depth of the whole segment distances are drawn uniformly.
    const THIN: f32 = 1e-4;

    fn new(sigma: f32, end: f32) -> Exponential {
        Exponential { sigma, end, mass: -(-sigma * end).exp_m1() }
    }

    fn uniform(&self) -> bool {
        let depth = self.sigma * self.end;
        depth.is_nan() || depth <= Self::THIN
    }

    /// The distance for a number `u` in [0, 1).
    fn sample(&self, u: f32) -> f32 {
        if self.uniform() {
            return u * self.end;
        }
        (-(-u * self.mass).ln_1p() / self.sigma).min(self.end)
    }

    /// The density of distance `t` in [0, end].
    fn pdf(&self, t: f32) -> f32 {
        if self.uniform() {
            return 1.0 / self.end;
        }
        self.sigma * (-self.sigma * t).exp() / self.mass
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both densities integrate to 1 over the segment and their samples follow them: the
    /// mean of a function over the drawn distances, divided by the density, is its
    /// integral (midpoint rule, 4096 stratified numbers) within 1e-3.
    #[test]
    fn the_distance_densities_are_normalised_and_sampled_by_their_inverse() {
        let end = 2.5f32;
        let f = |t: f32| 1.0 + (3.0 * t).sin() * 0.5 + t * t;
        let exact: f64 = {
            let n = 100_000;
            (0..n).map(|i| f64::from(f((i as f32 + 0.5) / n as f32 * end))).sum::<f64>() * f64::from(end) / n as f64
        };
        let eq = Equiangular::new(Vec3A::ZERO, Vec3A::Z, Vec3A::new(0.3, 0.0, 0.8), end).unwrap();
        let ex = Exponential::new(1.3, end);
        let thin = Exponential::new(0.0, end);
        let n = 4096;
        for (name, sample, pdf) in [
            ("equiangular", &(|u| eq.sample(u)) as &dyn Fn(f32) -> f32, &(|t| eq.pdf(t)) as &dyn Fn(f32) -> f32),
            ("exponential", &|u| ex.sample(u), &|t| ex.pdf(t)),
            ("uniform", &|u| thin.sample(u), &|t| thin.pdf(t)),
        ] {
            let mass: f64 = (0..100_000).map(|i| f64::from(pdf((i as f32 + 0.5) / 100_000.0 * end))).sum::<f64>()
                * f64::from(end)
                / 100_000.0;
            assert!((mass - 1.0).abs() < 1e-3, "{name}: the density integrates to {mass}");
            let estimate: f64 = (0..n)
                .map(|i| {
                    let t = sample((i as f32 + 0.5) / n as f32);
                    assert!((0.0..=end).contains(&t), "{name}: t = {t}");
                    f64::from(f(t) / pdf(t))
                })
                .sum::<f64>()
                / f64::from(n);
            assert!((estimate / exact - 1.0).abs() < 1e-3, "{name}: {estimate} vs {exact}");
        }
        // A centre on the ray's line has no equiangular density.
        assert!(Equiangular::new(Vec3A::ZERO, Vec3A::Z, Vec3A::new(0.0, 0.0, 1.0), end).is_none());
    }
}
