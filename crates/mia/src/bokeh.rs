//! `mia_lens_bokeh`: depth of field through a thin lens with a shaped aperture.
//!
//! Each eye sample casts `samples` rays (at least one). Ray k starts on the aperture, a
//! shape of radius `radius` (scene units) in the camera's XY plane around the eye ray's
//! origin, and passes through the point where the pinhole eye ray meets the focal plane at
//! distance `plane` in front of the camera (camera-space −Z), so that everything at that
//! distance stays where the pinhole camera puts it and a point at distance z spreads over
//! the aperture's shape scaled by `|1 − plane / z|` (on the focal plane): the thin-lens
//! circle of confusion. The sample's colour is the mean of its rays.
//!
//! **The aperture.** `blade_count` < 3: a disc (sampled with the concentric map);
//! otherwise a regular polygon inscribed in the disc with a corner at angle `blade_angle`
//! (degrees, from camera +X towards +Y; mira's reading, the manual gives no unit), sampled
//! uniformly sector by sector. `bias` remaps the sample's fraction ρ of the way to the rim
//! (the shape's own gauge: radius for the disc, scale of the polygon through the point)
//! to ρ^(1/bias): 1 is uniform, below 1 crowds the samples towards the centre, above 1
//! towards the rim. With `use_bokeh` and a `bokeh` texture the aperture is the square
//! around the disc and each ray is weighted by the texture at its place on it (u, v in
//! [0, 1]² across the square, +u along camera +X) per colour channel: the channel's
//! weighted mean, so that a white map changes nothing, a shape painted in it shapes the
//! blur and a coloured one blurs the channels differently (chromatic aberration). Alpha
//! is weighted by the mean of the three weights.
//!
//! Off (`on` off), with a radius or focal plane that is not positive, or for rays
//! nearly parallel to the focal plane the eye ray is cast as it is.

use std::f32::consts::PI;

use glam::{Vec2, Vec3A, Vec4};

use shader::rgb;
use shader::{Color, Ctx, NodeId, ShaderImpl, Value};

/// `mia_lens_bokeh (boolean on, scalar plane, scalar radius, integer samples, scalar bias,
/// integer blade_count, scalar blade_angle, boolean use_bokeh, color texture bokeh)` →
/// colour (lens shader). See the module documentation.
pub static MIA_LENS_BOKEH: ShaderImpl = ShaderImpl {
    name: "mia_lens_bokeh",
    params: &["on", "plane", "radius", "samples", "bias", "blade_count", "blade_angle", "use_bokeh", "bokeh"],
    run: bokeh,
    ..ShaderImpl::PLAIN
};

/// The shape rays leave the lens through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aperture {
    /// Corners of the polygon (< 3: a disc; the square of a bokeh map is 4 at 45°).
    pub blades: u32,
    /// Angle of the first corner from +X, radians.
    pub angle: f32,
    /// Rim bias (1: uniform).
    pub bias: f32,
}

impl Aperture {
    /// A point of the unit-radius aperture for `u` ∈ [0, 1)².
    pub fn sample(&self, u: Vec2) -> Vec2 {
        let exponent = if self.bias > 0.0 && self.bias.is_finite() { 1.0 / self.bias } else { 1.0 };
        if self.blades < 3 {
            let p = bsdf::concentric_disc(u);
            let r = p.length();
            return if r > 0.0 && exponent != 1.0 { p * r.powf(exponent - 1.0) } else { p };
        }
        let n = self.blades as f32;
        let x = u.x * n;
        let sector = x.floor().min(n - 1.0);
        // ρ² is uniform over a sector for uniform points: ρ = √x', then the bias.
        let rho = (x - sector).clamp(0.0, 1.0).powf(0.5 * exponent);
        let corner = |k: f32| {
            let a = self.angle + 2.0 * PI * k / n;
            Vec2::new(a.cos(), a.sin())
        };
        (corner(sector) * (1.0 - u.y) + corner(sector + 1.0) * u.y) * rho
    }
}

fn bokeh(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (org, dir) = (ctx.state.org, ctx.state.dir);
    let on = ctx.bool(n, 0);
    let plane = ctx.scalar(n, 1);
    let radius = ctx.scalar(n, 2);
    let to_camera = ctx.shading().world_to_camera;
    let cos = -to_camera.transform_vector3a(dir).z;
    let usable = radius > 0.0 && radius.is_finite() && plane > 0.0 && cos > 1e-4;
    if !on || !usable {
        *out = Value::Color(ctx.trace_eye(org, dir));
        return true;
    }
    let samples = ctx.int(n, 3).clamp(1, 4096) as u32;
    let bias = ctx.scalar(n, 4);
    let map = if ctx.bool(n, 7) { ctx.tag(n, 8) } else { None };
    let aperture = match map {
        Some(_) => Aperture { blades: 4, angle: PI / 4.0, bias },
        None => Aperture { blades: ctx.int(n, 5).max(0) as u32, angle: ctx.scalar(n, 6).to_radians(), bias },
    };
    let focus = org + dir * (plane / cos);
    let to_world = to_camera.inverse();
    let site = ctx.next_site();
    let mut sum = Vec4::ZERO;
    let mut weights = Vec4::ZERO;
    for i in 0..samples {
        let u = ctx.sample2(site, i, samples);
        let mut p = aperture.sample(u);
        if map.is_some() {
            // The polygon sampler's square has corners on the unit circle: stretch it to
            // the square around the disc.
            p *= 2f32.sqrt();
        }
        let weight = match map {
            Some(tag) => {
                let coord = Vec3A::new(0.5 + 0.5 * p.x, 0.5 + 0.5 * p.y, 0.0);
                let w = rgb(ctx.lookup_color_texture(tag, coord).unwrap_or(Vec4::ZERO)).max(Vec3A::ZERO);
                w.extend((w.x + w.y + w.z) / 3.0)
            }
            None => Vec4::ONE,
        };
        if weight == Vec4::ZERO {
            continue;
        }
        let lens = org + to_world.transform_vector3a(Vec3A::new(p.x * radius, p.y * radius, 0.0));
        let d = (focus - lens).normalize_or(dir);
        let c = ctx.trace_eye(lens, d);
        sum += c * weight;
        weights += weight;
    }
    let safe = |s: f32, w: f32| if w > 0.0 { s / w } else { 0.0 };
    let result =
        Color::new(safe(sum.x, weights.x), safe(sum.y, weights.y), safe(sum.z, weights.z), safe(sum.w, weights.w));
    *out = Value::Color(result);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: u32) -> impl Iterator<Item = Vec2> {
        (0..n * n).map(move |i| Vec2::new(((i % n) as f32 + 0.5) / n as f32, ((i / n) as f32 + 0.5) / n as f32))
    }

    #[test]
    fn six_blades_make_a_hexagon() {
        let hex = Aperture { blades: 6, angle: 0.0, bias: 1.0 };
        let (mut ex, mut ey) = (0.0f32, 0.0f32);
        for u in grid(200) {
            let p = hex.sample(u);
            assert!(p.length() <= 1.0 + 1e-5);
            ex = ex.max(p.x.abs());
            ey = ey.max(p.y.abs());
        }
        // Corners along x reach the circle; along y the flat sides are at cos 30°.
        assert!((ex - 1.0).abs() < 0.01, "{ex}");
        assert!((ey / ex - (PI / 6.0).cos()).abs() < 0.01, "{ey} / {ex}");
        // Rotated by 30° (90° in the hexagon's symmetry: a corner up) the extents swap.
        let turned = Aperture { blades: 6, angle: 30f32.to_radians(), bias: 1.0 };
        let ey: f32 = grid(200).map(|u| turned.sample(u).y.abs()).fold(0.0, f32::max);
        assert!((ey - 1.0).abs() < 0.01);
    }

    #[test]
    fn uniform_apertures_fill_their_area_evenly_and_bias_moves_samples() {
        for blades in [0, 5] {
            let a = Aperture { blades, angle: 0.3, bias: 1.0 };
            // Uniform: half the points inside ρ = √½ (as a fraction of the shape's scale).
            let inner = grid(100).filter(|&u| a.sample(u).length() < 0.5f32.sqrt() * gauge_scale(blades, a, u)).count();
            assert!((inner as f32 / 10_000.0 - 0.5).abs() < 0.02, "{blades}: {inner}");
        }
        let mean_r = |bias: f32| {
            let a = Aperture { blades: 0, angle: 0.0, bias };
            grid(100).map(|u| a.sample(u).length()).sum::<f32>() / 10_000.0
        };
        // Uniform disc: mean radius 2/3.
        assert!((mean_r(1.0) - 2.0 / 3.0).abs() < 0.005);
        assert!(mean_r(0.5) < mean_r(1.0) - 0.1 && mean_r(2.0) > mean_r(1.0) + 0.05);
    }

    /// The length of the shape's boundary point in the direction of the sample (1 for the
    /// disc).
    fn gauge_scale(blades: u32, a: Aperture, u: Vec2) -> f32 {
        if blades < 3 {
            return 1.0;
        }
        let p = a.sample(u);
        let n = blades as f32;
        let rel = (p.y.atan2(p.x) - a.angle).rem_euclid(2.0 * PI / n) - PI / n;
        (PI / n).cos() / rel.cos()
    }
}
