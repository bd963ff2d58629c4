//! `mia_envblur`: an environment looked up pre-blurred, for cheap smooth reflections of
//! an HDRI or a sky.
//!
//! On first use in a render (kept in [`shader::Shading::precomputed`]) the
//! `environment` shader list (none: the camera's environment) is rasterised into a
//! latitude–longitude map of `resolution`² texels (+Y up; 2×2 directions averaged per
//! texel), and a pyramid of blurred copies is built from it: level k ≥ 1 is the map
//! convolved on the sphere with the von Mises–Fisher kernel `exp((cos γ − 1)/σₖ²)` (≈ a
//! Gaussian of angular standard deviation σₖ for small σ), σ₁ two texels and each level
//! twice the last up to one radian, each sampled on a grid of about three texels per σ.
//! The convolution gathers over a coarsened copy of the map whose texels keep their exact
//! solid-angle weights, normalised per output texel (a constant stays constant to rounding;
//! the mean over the sphere is kept to within a fraction of a percent).
//!
//! A lookup with `blur` b (0 … 1) wants σ = b radians: it interpolates bilinearly in the two
//! levels around σ and linearly in log σ between them (below σ₁ between the unblurred map
//! and level 1; above the last level, the last level). `blur` 0 bypasses the map: the
//! `environment` shader runs for the ray's direction, exactly as without `mia_envblur`.
//!
//! Not done: the extra blur mental ray derived from a glossy reflection ray's glossiness
//! (`mia_material`'s `single_env_sample`); mira's reading of `blur` as σ in radians is its
//! own (the manual only says 0 is none and 1 is very wide).

use std::f32::consts::PI;

use glam::{Vec3A, Vec4};

use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Tag, Value};

/// Kernel width (radians) of `blur` 1.
pub const MAX_SIGMA: f32 = 1.0;

/// `mia_envblur (shader environment, scalar blur, integer resolution)` → colour.
pub static MIA_ENVBLUR: ShaderImpl = ShaderImpl {
    name: "mia_envblur",
    params: &["environment", "blur", "resolution"],
    run: envblur,
    ..ShaderImpl::PLAIN
};

fn envblur(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let shading = ctx.shading();
    let input = match ctx.tag(n, 0) {
        Some(Tag::Shader(s)) => Some(s),
        _ => shading.environment.filter(|&e| e != n),
    };
    let Some(input) = input else {
        *out = Value::Color(Color::ZERO);
        return true;
    };
    let blur = ctx.scalar(n, 1);
    let dir = ctx.state.dir;
    if blur.is_nan() || blur <= 0.0 {
        let mut result = Value::Color(Color::ZERO);
        let ok = ctx.run_list(input, &mut result);
        *out = Value::Color(result.color());
        return ok;
    }
    let res = match ctx.int(n, 2) {
        r if r <= 0 => 200,
        r => r.clamp(8, 2048) as usize,
    };
    let tracer = ctx.tracer;
    let base = ctx.state.child(RayType::Environment, ctx.state.point, dir);
    let map = shading.precomputed.get_or_init(n, || {
        BlurredMap::build(res, |d| {
            let mut state = base.clone();
            state.dir = d;
            state.org = base.point;
            let mut c = Ctx::new(shading, tracer, state);
            let mut result = Value::Color(Color::ZERO);
            c.run_list(input, &mut result);
            result.color()
        })
    });
    *out = Value::Color(map.map_or(Color::ZERO, |m| m.lookup(dir, blur)));
    true
}

/// A latitude–longitude map (rows from +Y down to −Y, columns around Y from +X towards +Z).
#[derive(Clone, Debug)]
struct LatLong {
    res: usize,
    texels: Vec<Color>,
}

/// Polar angle and azimuth of the centre of texel (row, column) of a `res`² map.
fn texel_angles(res: usize, row: usize, col: usize) -> (f32, f32) {
    ((row as f32 + 0.5) * PI / res as f32, (col as f32 + 0.5) * 2.0 * PI / res as f32)
}

fn direction(theta: f32, phi: f32) -> Vec3A {
    Vec3A::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
}

/// Solid angle of one texel of row `row`.
fn texel_solid_angle(res: usize, row: usize) -> f32 {
    let t0 = row as f32 * PI / res as f32;
    let t1 = (row + 1) as f32 * PI / res as f32;
    (t0.cos() - t1.cos()) * 2.0 * PI / res as f32
}

impl LatLong {
    /// Bilinear lookup along unit direction `d`.
    fn lookup(&self, d: Vec3A) -> Color {
        let r = self.res;
        let theta = d.y.clamp(-1.0, 1.0).acos();
        let phi = d.z.atan2(d.x);
        let x = phi / (2.0 * PI) * r as f32 - 0.5;
        let y = theta / PI * r as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let col = |c: f32| (c as i64).rem_euclid(r as i64) as usize;
        let row = |c: f32| (c.max(0.0) as usize).min(r - 1);
        let at = |i: usize, j: usize| self.texels[i * r + j];
        let (i0, i1, j0, j1) = (row(y0), row(y0 + 1.0), col(x0), col(x0 + 1.0));
        let top = at(i0, j0) * (1.0 - fx) + at(i0, j1) * fx;
        let bottom = at(i1, j0) * (1.0 - fx) + at(i1, j1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

/// A source point of a blur: direction, solid angle, mean value over it.
#[derive(Clone, Copy)]
struct Patch {
    dir: Vec3A,
    weight: f32,
    value: Color,
}

/// An environment rasterised and pre-blurred (see the module documentation).
#[derive(Clone, Debug)]
pub struct BlurredMap {
    /// The unblurred map, then levels of growing blur.
    levels: Vec<LatLong>,
    /// Kernel σ of each level (0 for the unblurred map), radians.
    sigmas: Vec<f32>,
}

impl BlurredMap {
    /// Rasterises `env` (colour for a unit direction) into a `res`² map and blurs it.
    pub fn build(res: usize, mut env: impl FnMut(Vec3A) -> Color) -> BlurredMap {
        let res = res.max(4);
        let mut texels = Vec::with_capacity(res * res);
        for i in 0..res {
            for j in 0..res {
                let mut sum = Vec4::ZERO;
                for (a, b) in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)] {
                    let theta = (i as f32 + a) * PI / res as f32;
                    let phi = (j as f32 + b) * 2.0 * PI / res as f32;
                    sum += env(direction(theta, phi));
                }
                texels.push(sum * 0.25);
            }
        }
        let raw = LatLong { res, texels };
        let mut levels = vec![raw];
        let mut sigmas = vec![0.0];
        let mut sigma = 2.0 * PI / res as f32;
        loop {
            let target = ((3.0 * PI / sigma).ceil() as usize).clamp(8, res);
            let factor = (res / target).max(1);
            let patches = coarsen(&levels[0], factor);
            levels.push(convolve(&patches, res / factor, target, sigma));
            sigmas.push(sigma);
            if sigma >= MAX_SIGMA {
                break;
            }
            sigma *= 2.0;
        }
        BlurredMap { levels, sigmas }
    }

    /// The map blurred by `blur` (σ = `blur` radians) along unit direction `d`.
    pub fn lookup(&self, d: Vec3A, blur: f32) -> Color {
        let sigma = blur.max(0.0) * MAX_SIGMA;
        let last = self.sigmas.len() - 1;
        if sigma >= self.sigmas[last] {
            return self.levels[last].lookup(d);
        }
        let k = self.sigmas.iter().rposition(|&s| s <= sigma).unwrap_or(0);
        let t = if k == 0 {
            sigma / self.sigmas[1]
        } else {
            (sigma / self.sigmas[k]).log2() / (self.sigmas[k + 1] / self.sigmas[k]).log2()
        };
        let a = self.levels[k].lookup(d);
        if t <= 0.0 {
            return a;
        }
        a * (1.0 - t) + self.levels[k + 1].lookup(d) * t
    }
}

/// The texels of `map` merged `factor`² at a time (the last row and column of patches take
/// the leftovers): rows of patches with exact solid angles and weighted mean values.
fn coarsen(map: &LatLong, factor: usize) -> Vec<Vec<Patch>> {
    let res = map.res;
    let n = (res / factor).max(1);
    let mut acc = vec![vec![(Vec3A::ZERO, 0.0f32, Vec4::ZERO); n]; n];
    for i in 0..res {
        let w = texel_solid_angle(res, i);
        let pi = (i / factor).min(n - 1);
        for j in 0..res {
            let pj = (j / factor).min(n - 1);
            let (theta, phi) = texel_angles(res, i, j);
            let a = &mut acc[pi][pj];
            a.0 += direction(theta, phi) * w;
            a.1 += w;
            a.2 += map.texels[i * res + j] * w;
        }
    }
    acc.into_iter()
        .map(|row| {
            row.into_iter()
                .map(|(d, w, v)| Patch { dir: d.normalize_or(Vec3A::Y), weight: w, value: v / w.max(1e-30) })
                .collect()
        })
        .collect()
}

/// The patches convolved with the kernel of width `sigma`, sampled at the texel centres of a
/// `target`² map. `rows` patch rows span the sphere's polar angle evenly.
fn convolve(patches: &[Vec<Patch>], rows: usize, target: usize, sigma: f32) -> LatLong {
    let kappa = 1.0 / (sigma * sigma);
    // Beyond 4σ the kernel is below e⁻⁸ of its peak.
    let reach = 4.0 * sigma;
    let row_height = PI / rows as f32;
    let cols = patches.first().map_or(1, Vec::len);
    let col_width = 2.0 * PI / cols as f32;
    let mut texels = Vec::with_capacity(target * target);
    for i in 0..target {
        for j in 0..target {
            let (theta, phi) = texel_angles(target, i, j);
            let d = direction(theta, phi);
            let mut sum = Vec4::ZERO;
            let mut norm = 0.0f32;
            for (pi, row) in patches.iter().enumerate() {
                let (lo, hi) = (pi as f32 * row_height, (pi + 1) as f32 * row_height);
                // Rows wholly outside the kernel's reach.
                if reach < PI && (lo > theta + reach + row_height || hi < theta - reach - row_height) {
                    continue;
                }
                let span = azimuth_span(theta, lo, hi, reach + row_height + col_width);
                let (first, count) = match span {
                    Some(half) => {
                        let c0 = ((phi - half) / col_width).floor() as i64;
                        let c1 = ((phi + half) / col_width).ceil() as i64;
                        (c0, ((c1 - c0 + 1) as usize).min(cols))
                    }
                    None => (0, cols),
                };
                for c in 0..count {
                    let p = &row[(first + c as i64).rem_euclid(cols as i64) as usize];
                    let k = ((p.dir.dot(d) - 1.0) * kappa).exp() * p.weight;
                    sum += p.value * k;
                    norm += k;
                }
            }
            texels.push(if norm > 0.0 { sum / norm } else { Vec4::ZERO });
        }
    }
    LatLong { res: target, texels }
}

/// Half the azimuth range of the band of polar angles [lo, hi] within angle `reach` of a
/// direction at polar angle `theta`; `None` when it is the whole band (a pole within reach).
fn azimuth_span(theta: f32, lo: f32, hi: f32, reach: f32) -> Option<f32> {
    if reach >= PI || theta - reach <= 0.0 || theta + reach >= PI {
        return None;
    }
    // The widest azimuth over the band is at one of its ends or where the reach circle is
    // tangent to a meridian (cos t = cos θ / cos reach).
    let tangent = (reach < PI / 2.0).then(|| (theta.cos() / reach.cos()).clamp(-1.0, 1.0).acos());
    let mut widest = 0.0f32;
    for t in [lo, hi, tangent.unwrap_or(lo).clamp(lo, hi)] {
        let s = theta.sin() * t.sin();
        if s <= 1e-6 {
            return None;
        }
        let c = (reach.cos() - theta.cos() * t.cos()) / s;
        if c <= -1.0 {
            return None;
        }
        widest = widest.max(c.min(1.0).acos());
    }
    Some(widest)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` directions spread evenly over the sphere (a Fibonacci lattice).
    fn sphere(n: usize) -> Vec<Vec3A> {
        let golden = PI * (3.0 - 5f32.sqrt());
        (0..n)
            .map(|i| {
                let y = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
                let r = (1.0 - y * y).max(0.0).sqrt();
                let phi = golden * i as f32;
                Vec3A::new(r * phi.cos(), y, r * phi.sin())
            })
            .collect()
    }

    /// A bright disc of angular radius 8° around `axis` over a dim gradient.
    fn spot(axis: Vec3A) -> impl Fn(Vec3A) -> Color {
        move |d: Vec3A| {
            let v = if d.dot(axis) > 8f32.to_radians().cos() { 20.0 } else { 0.2 + 0.1 * d.y };
            Vec4::new(v, 0.5 * v, 0.25, 1.0)
        }
    }

    #[test]
    fn a_constant_environment_stays_constant_at_any_blur() {
        let c = Vec4::new(0.3, 0.6, 1.7, 1.0);
        let map = BlurredMap::build(64, |_| c);
        for blur in [0.001, 0.03, 0.1, 0.37, 0.7, 1.0, 3.0] {
            for d in sphere(500) {
                let got = map.lookup(d, blur);
                assert!((got - c).abs().max_element() < 1e-4, "blur {blur} at {d}: {got}");
            }
        }
    }

    #[test]
    fn blurring_keeps_the_mean_over_the_sphere() {
        for axis in [Vec3A::new(0.3, 0.2, 0.93).normalize(), Vec3A::new(0.1, 0.97, 0.2).normalize()] {
            let env = spot(axis);
            let map = BlurredMap::build(100, &env);
            let dirs = sphere(40_000);
            let mean = |f: &dyn Fn(Vec3A) -> Color| dirs.iter().map(|&d| f(d)).sum::<Vec4>() / dirs.len() as f32;
            let truth = mean(&env);
            for blur in [0.02, 0.1, 0.3, 0.6, 1.0] {
                let m = mean(&|d| map.lookup(d, blur));
                let err = ((m - truth) / truth).abs();
                assert!(err.x < 0.01 && err.y < 0.01 && err.z < 0.01, "axis {axis} blur {blur}: {m} vs {truth}");
            }
        }
    }

    #[test]
    fn a_bright_spot_spreads_wider_with_more_blur() {
        let axis = Vec3A::new(0.0, 0.6, 0.8);
        let map = BlurredMap::build(100, spot(axis));
        let dirs = sphere(40_000);
        // Mean squared angle from the spot, weighted by the excess over the background.
        let spread = |blur: f32| {
            let (mut m2, mut w) = (0.0f32, 0.0f32);
            for &d in &dirs {
                let v = (map.lookup(d, blur).x - 0.3).max(0.0);
                let a = d.dot(axis).clamp(-1.0, 1.0).acos();
                m2 += v * a * a;
                w += v;
            }
            (m2 / w).sqrt()
        };
        let mut last = 0.0;
        for blur in [0.01, 0.05, 0.1, 0.2, 0.4, 0.8] {
            let s = spread(blur);
            assert!(s > last * 1.05, "blur {blur}: spread {s} after {last}");
            last = s;
        }
        // Unblurred, the disc's own spread: √(½)·8° for a uniform disc.
        let s = spread(0.001);
        assert!((s - 8f32.to_radians() * 0.5f32.sqrt()).abs() < 0.01, "{s}");
    }
}
