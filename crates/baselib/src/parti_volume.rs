//! `parti_volume` (physics library): a participating medium with extinction, scattering,
//! a two-lobe Schlick phase function and single scattering of the scene's lights, as a
//! volume shader ([`shader::volume`]).

use glam::Vec3A;

use shader::volume::segment_length;
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Value};

/// `parti_volume (integer mode, color scatter, scalar extinction, scalar r, scalar g1,
/// scalar g2, scalar nonuniform, scalar height, scalar min_step_len, scalar max_step_len,
/// scalar light_dist, integer min_level, boolean no_globil_where_direct, array light
/// lights)`.
///
/// The medium fills all space (`mode` 0) or, `mode` 1, the half-space below world y =
/// `height`. Coefficients per scene unit: extinction σt = `extinction`, scattering σs =
/// `scatter` (per channel; σt is raised to σs's largest channel where it is smaller, so
/// the medium never scatters more than it extinguishes). `nonuniform` ∈ [0, 1] scales both
/// by a density 1 − u + 2u·noise(p) (the base shaders' lattice noise at the world-space
/// point, features of one scene unit; mean ≈ 1), `nonuniform` 0 a homogeneous medium.
///
/// An eye (or secondary) ray's colour is attenuated by the transmittance T = e^−τ over the
/// part of the segment inside the medium (τ = ∫σt) and gains the single-scattered light
/// ∫ T(t) σs(t) Σ_lights p(θ) L_light dt, marched in steps of `max_step_len` (0: the
/// medium's part of the segment in 32 steps), no shorter than `min_step_len`, at most
/// 1024, each step integrating the transmittance exactly for the light found at its
/// middle. A segment to infinity is marched until T < 10⁻⁴ and then counts as opaque.
/// Lights: the `lights` array, all lights when it is empty, each sampled through the
/// light loop at the step's point (light shaders, shadows, and this volume on the light
/// ray). Alpha becomes α T + (1 − T). Light rays are attenuated by T only.
///
/// Phase function: Schlick's two lobes p = r k(g1) + (1 − r) k(g2) with
/// k(g) = (1 − g²) / (4 (1 − g cos θ)²), θ between the light's travel and the scattered
/// ray towards the viewer (g > 0 forward). It is normalised to π over the sphere, not 1,
/// as the base shaders' convention is (a Lambert surface returns diffuse × light colour ×
/// cos θ, π times the physical radiance), so fog and surfaces lit by the same light keep
/// their physical ratio. `light_dist`, `min_level` and `no_globil_where_direct` concern
/// photon maps and are ignored; multiple scattering is not computed.
pub static PARTI_VOLUME: ShaderImpl = ShaderImpl {
    name: "parti_volume",
    params: &[
        "mode",
        "scatter",
        "extinction",
        "r",
        "g1",
        "g2",
        "nonuniform",
        "height",
        "min_step_len",
        "max_step_len",
        "lights",
    ],
    run: parti_volume,
    ..ShaderImpl::PLAIN
};

/// Most march steps along one segment.
const MAX_STEPS: usize = 1024;
/// Optical depth at which a segment to infinity counts as opaque (T = 10⁻⁴).
const OPAQUE_DEPTH: f32 = 9.21;

/// The medium of one `parti_volume` node.
#[derive(Clone, Copy, Debug)]
pub struct Medium {
    /// 1: only below `height`.
    pub layered: bool,
    /// World-space y of the layer's top.
    pub height: f32,
    /// Extinction coefficient (per scene unit).
    pub sigma_t: f32,
    /// Scattering coefficients (per scene unit).
    pub sigma_s: Vec3A,
    /// Density variation ∈ [0, 1].
    pub nonuniform: f32,
}

impl Medium {
    /// The part [t0, t1] of the ray `start + t d`, 0 ≤ t ≤ `len` (may be infinite), inside
    /// the medium; `None` if it never enters.
    pub fn clip(&self, start: Vec3A, d: Vec3A, len: f32) -> Option<(f32, f32)> {
        if !self.layered {
            return Some((0.0, len));
        }
        let below = start.y < self.height;
        if d.y == 0.0 {
            return below.then_some((0.0, len));
        }
        let cross = (self.height - start.y) / d.y;
        let (t0, t1) = if d.y > 0.0 { (0.0, cross.min(len)) } else { (cross.max(0.0), len) };
        (t1 > t0).then_some((t0, t1))
    }

    /// The density multiplier at `p` (1 in a homogeneous medium).
    pub fn density(&self, p: Vec3A) -> f32 {
        if self.nonuniform <= 0.0 {
            return 1.0;
        }
        let u = self.nonuniform.min(1.0);
        (1.0 - u + 2.0 * u * super::procedural::lattice_noise(p)).max(0.0)
    }
}

/// Schlick's phase lobe for asymmetry `g` at cos θ (θ from the forward direction),
/// normalised to π over the sphere.
pub fn schlick(g: f32, cos: f32) -> f32 {
    let g = g.clamp(-0.999, 0.999);
    let d = 1.0 - g * cos;
    (1.0 - g * g) / (4.0 * d * d)
}

fn parti_volume(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let scatter = ctx.color(n, 1);
    let sigma_s = Vec3A::new(scatter.x, scatter.y, scatter.z).max(Vec3A::ZERO);
    let medium = Medium {
        layered: ctx.int(n, 0) == 1,
        height: ctx.scalar(n, 7),
        sigma_t: ctx.scalar(n, 2).max(sigma_s.max_element()).max(0.0),
        sigma_s,
        nonuniform: ctx.scalar(n, 6).clamp(0.0, 1.0),
    };
    if !(medium.sigma_t > 0.0 && medium.sigma_t.is_finite()) {
        return true;
    }
    let len = segment_length(&ctx.state);
    let c = out.color();
    if matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow) {
        // From the illuminated point back towards the light.
        let (start, d) = (ctx.state.point, -ctx.state.dir);
        let t = transmittance(&medium, start, d, len, ctx.scalar(n, 9));
        *out = Value::Color(Color::new(c.x * t, c.y * t, c.z * t, c.w));
        return true;
    }
    let (start, d) = (ctx.state.org, ctx.state.dir);
    let Some((t0, t1)) = medium.clip(start, d, len) else { return true };
    let phase = (ctx.scalar(n, 3), ctx.scalar(n, 4), ctx.scalar(n, 5));
    let steps = (ctx.scalar(n, 8), ctx.scalar(n, 9));
    let lights = ctx.eval(n, 10);
    let lights = ctx.light_list(if lights.array().is_empty() { 3 } else { 0 }, &lights);
    let (t, inscatter) = march(ctx, &medium, (start, d), (t0, t1), steps, phase, &lights);
    *out = Value::Color(Color::new(
        c.x * t + inscatter.x,
        c.y * t + inscatter.y,
        c.z * t + inscatter.z,
        c.w * t + (1.0 - t),
    ));
    true
}

/// The far end of the medium's part [t0, t1] for marching: t1, or where a segment to
/// infinity becomes opaque.
fn march_end(medium: &Medium, t0: f32, t1: f32) -> f32 {
    if t1.is_finite() {
        return t1;
    }
    let thinnest = if medium.nonuniform > 0.0 { (1.0 - medium.nonuniform).max(0.05) } else { 1.0 };
    t0 + OPAQUE_DEPTH / (medium.sigma_t * thinnest)
}

/// Step count and length over [t0, t1] for the step limits `(min, max)`.
fn steps_of(t0: f32, t1: f32, (min_step, max_step): (f32, f32)) -> (usize, f32) {
    let len = t1 - t0;
    let mut step = if max_step > 0.0 { max_step } else { len / 32.0 };
    if min_step > 0.0 {
        step = step.max(min_step);
    }
    let count = if step > 0.0 { (len / step).ceil() as usize } else { 1 };
    let count = count.clamp(1, MAX_STEPS);
    (count, len / count as f32)
}

/// The transmittance along the ray `start + t d`, 0 ≤ t ≤ `len`, through the medium.
pub fn transmittance(medium: &Medium, start: Vec3A, d: Vec3A, len: f32, max_step: f32) -> f32 {
    let Some((t0, t1)) = medium.clip(start, d, len) else { return 1.0 };
    if !t1.is_finite() {
        return 0.0;
    }
    if medium.nonuniform <= 0.0 {
        return (-medium.sigma_t * (t1 - t0)).exp();
    }
    let (count, dt) = steps_of(t0, t1, (0.0, max_step));
    let tau: f32 = (0..count).map(|i| medium.density(start + d * (t0 + (i as f32 + 0.5) * dt))).sum::<f32>();
    (-medium.sigma_t * tau * dt).exp()
}

/// Marches the eye segment's part [t0, t1] inside the medium: (its transmittance, the
/// single-scattered light it gains).
fn march(
    ctx: &mut Ctx,
    medium: &Medium,
    (start, d): (Vec3A, Vec3A),
    (t0, t1): (f32, f32),
    limits: (f32, f32),
    phase: (f32, f32, f32),
    lights: &[u32],
) -> (f32, Vec3A) {
    let infinite = !t1.is_finite();
    let end = march_end(medium, t0, t1);
    let (count, dt) = steps_of(t0, end, limits);
    let albedo = medium.sigma_s / medium.sigma_t;
    let scatters = albedo.max_element() > 0.0 && !lights.is_empty();
    let saved = (ctx.state.point, ctx.state.shadow_point, ctx.state.normal, ctx.state.normal_geom);
    let mut tau = 0.0f32;
    let mut sum = Vec3A::ZERO;
    for i in 0..count {
        let x = start + d * (t0 + (i as f32 + 0.5) * dt);
        let step_tau = medium.sigma_t * medium.density(x) * dt;
        if scatters {
            // ∫ σs e^−τ dt over the step = albedo (e^−τa − e^−τb).
            let weight = (-tau).exp() - (-(tau + step_tau)).exp();
            if weight > 0.0 {
                sum += albedo * weight * in_light(ctx, x, d, phase, lights);
            }
        }
        tau += step_tau;
    }
    (ctx.state.point, ctx.state.shadow_point, ctx.state.normal, ctx.state.normal_geom) = saved;
    ctx.flush_cache();
    (if infinite { 0.0 } else { (-tau).exp() }, sum)
}

/// The light scattered towards the viewer at `x` on a ray along `d`: Σ over `lights` of
/// the mean over each light's samples of p(θ) × the light's colour.
fn in_light(ctx: &mut Ctx, x: Vec3A, d: Vec3A, (r, g1, g2): (f32, f32, f32), lights: &[u32]) -> Vec3A {
    ctx.state.point = x;
    ctx.state.shadow_point = x;
    ctx.state.normal = -d;
    // Not on a surface: shadow rays start at the point itself.
    ctx.state.normal_geom = Vec3A::ZERO;
    ctx.flush_cache();
    let mut total = Vec3A::ZERO;
    for &light in lights {
        let mut lp = ctx.light_loop(light);
        lp.both_sides = true;
        let mut sum = Vec3A::ZERO;
        while let Some(s) = ctx.sample_light(&mut lp) {
            let cos = s.dir.dot(d);
            let p = r * schlick(g1, cos) + (1.0 - r) * schlick(g2, cos);
            sum += Vec3A::new(s.color.x, s.color.y, s.color.z) * p;
        }
        if lp.samples > 0 {
            total += sum / lp.samples as f32;
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schlick_lobes_integrate_to_pi() {
        for g in [-0.65f32, 0.0, 0.46, 0.91] {
            // ∫ p dω = 2π ∫ p(μ) dμ, midpoint rule.
            let n = 200_000;
            let sum: f64 = (0..n)
                .map(|i| {
                    let mu = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
                    f64::from(schlick(g, mu as f32))
                })
                .sum::<f64>()
                * 2.0
                / n as f64;
            let total = 2.0 * std::f64::consts::PI * sum;
            assert!((total - std::f64::consts::PI).abs() < 1e-3, "g {g}: {total}");
        }
        assert!(schlick(0.5, 1.0) > schlick(0.5, -1.0));
        assert!((schlick(0.0, 0.3) - 0.25).abs() < 1e-7);
    }

    #[test]
    fn a_layer_clips_rays_to_below_its_height() {
        let m = Medium { layered: true, height: 1.0, sigma_t: 1.0, sigma_s: Vec3A::ZERO, nonuniform: 0.0 };
        // Rising from below: leaves at y = 1.
        let (a, b) = m.clip(Vec3A::ZERO, Vec3A::Y, 5.0).unwrap();
        assert!((a - 0.0).abs() < 1e-6 && (b - 1.0).abs() < 1e-6);
        // Falling from above: enters at y = 1, to the end.
        let (a, b) = m.clip(Vec3A::new(0.0, 3.0, 0.0), -Vec3A::Y, f32::INFINITY).unwrap();
        assert!((a - 2.0).abs() < 1e-6 && b.is_infinite());
        // Level above the layer: never.
        assert!(m.clip(Vec3A::new(0.0, 2.0, 0.0), Vec3A::X, 10.0).is_none());
        // Rising at 45° from 1.5 below the top: 1.5 √2 inside.
        let d = Vec3A::new(1.0, 1.0, 0.0).normalize();
        let t = transmittance(&m, Vec3A::new(0.0, -0.5, 0.0), d, 10.0, 0.0);
        assert!((t - (-1.5 * 2f32.sqrt()).exp()).abs() < 1e-5, "{t}");
        // Falling into the half-space: everything past the top, 10 − 0.5 √2.
        let t = transmittance(&m, Vec3A::new(0.0, 1.5, 0.0), -d, 10.0, 0.0);
        assert!((t - (-(10.0 - 0.5 * 2f32.sqrt())).exp()).abs() < 1e-6, "{t}");
    }

    #[test]
    fn nonuniform_density_keeps_its_mean_near_one() {
        let m = Medium { layered: false, height: 0.0, sigma_t: 1.0, sigma_s: Vec3A::ZERO, nonuniform: 1.0 };
        let n = 20_000;
        let mean: f32 = (0..n)
            .map(|i| m.density(Vec3A::new(i as f32 * 0.37, (i % 97) as f32 * 0.51, (i % 13) as f32 * 0.77)))
            .sum::<f32>()
            / n as f32;
        assert!((mean - 1.0).abs() < 0.1, "{mean}");
    }
}
