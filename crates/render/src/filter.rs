//! Pixel filters. The path engine applies them by filter importance sampling: each
//! sample's position within the filter's footprint is drawn from the filter's own
//! (absolute) shape, and its weight is the filter's sign there; every pixel is the
//! weighted mean of its own samples, which keeps tiles independent and the image the same
//! for any thread count. The classic engine, which takes few and adaptive samples, splats
//! each sample into all pixels its footprint covers with weight [`PixelFilter::eval`], as
//! mental ray filtered (a ratio of signed weights over one pixel's one or two samples
//! would be unstable).
//!
//! Radii follow mental ray: `filter kind w h` gives the full footprint, so the radius is
//! half of it (Iray, which writes a radius, halves the `.mi` value for the same reason).

use scene::options::{Filter, FilterKind};

const TABLE: usize = 256;

/// Entries of the inverse-CDF table: a sample costs one lookup and one interpolation.
const INVERSE: usize = 1024;

/// One axis of a separable filter, tabulated for sampling.
#[derive(Clone, Debug)]
struct Axis {
    radius: f32,
    /// Cumulative |f| over [−radius, radius] in TABLE steps, normalised to 1.
    cdf: Vec<f32>,
    /// Sign of f in each step.
    sign: Vec<f32>,
    /// Whether f is negative anywhere (else every sample's sign is 1, not looked up).
    signed: bool,
    /// Offsets at u = k / INVERSE, k = 0..=INVERSE (the inverse of `cdf`); a fixed-size
    /// table, so that a sample's two reads need no bounds checks.
    inverse: Box<[f32; INVERSE + 1]>,
}

/// A 2-D filter, separable into x and y.
#[derive(Clone, Debug)]
pub struct PixelFilter {
    x: Axis,
    y: Axis,
    kind: FilterKind,
    clip: bool,
}

/// The 1-D profile of a filter at distance `d` from the centre (radius `r`).
fn profile(kind: FilterKind, d: f32, r: f32) -> f32 {
    let a = d.abs();
    if a > r {
        return 0.0;
    }
    match kind {
        FilterKind::Box => 1.0,
        FilterKind::Triangle => 1.0 - a / r,
        FilterKind::Gauss => {
            // mental ray's Gaussian: falls to ~1% at the radius.
            let s = r / 2.0;
            (-(a * a) / (2.0 * s * s) * 2.0).exp()
        }
        FilterKind::Mitchell => {
            // Mitchell–Netravali (B = C = 1/3) stretched over the radius.
            let x = 2.0 * a / r;
            let (b, c) = (1.0 / 3.0, 1.0 / 3.0);
            if x < 1.0 {
                ((12.0 - 9.0 * b - 6.0 * c) * x * x * x + (-18.0 + 12.0 * b + 6.0 * c) * x * x + (6.0 - 2.0 * b)) / 6.0
            } else {
                ((-b - 6.0 * c) * x * x * x
                    + (6.0 * b + 30.0 * c) * x * x
                    + (-12.0 * b - 48.0 * c) * x
                    + (8.0 * b + 24.0 * c))
                    / 6.0
            }
        }
        FilterKind::Lanczos => {
            let x = a / r * 2.0;
            let sinc =
                |v: f32| if v == 0.0 { 1.0 } else { (std::f32::consts::PI * v).sin() / (std::f32::consts::PI * v) };
            sinc(x) * sinc(x / 2.0)
        }
    }
}

impl Axis {
    fn new(kind: FilterKind, radius: f32, clip: bool) -> Axis {
        let radius = radius.max(1e-3);
        let mut cdf = Vec::with_capacity(TABLE + 1);
        let mut sign = Vec::with_capacity(TABLE);
        let mut acc = 0.0;
        cdf.push(0.0);
        for i in 0..TABLE {
            let d = -radius + (i as f32 + 0.5) / TABLE as f32 * 2.0 * radius;
            let mut f = profile(kind, d, radius);
            if clip {
                f = f.max(0.0);
            }
            sign.push(if f < 0.0 { -1.0 } else { 1.0 });
            acc += f.abs();
            cdf.push(acc);
        }
        for c in &mut cdf {
            *c /= acc;
        }
        let signed = sign.iter().any(|&s| s < 0.0);
        let mut axis = Axis { radius, cdf, sign, signed, inverse: Box::new([0.0; INVERSE + 1]) };
        for k in 0..=INVERSE {
            axis.inverse[k] = axis.search(k as f32 / INVERSE as f32);
        }
        axis
    }

    /// The offset where the CDF reaches `u` (binary search).
    fn search(&self, u: f32) -> f32 {
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, TABLE) - 1;
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let frac = if c1 > c0 { ((u - c0) / (c1 - c0)).clamp(0.0, 1.0) } else { 0.5 };
        -self.radius + (i as f32 + frac) / TABLE as f32 * 2.0 * self.radius
    }

    /// An offset in [−radius, radius] distributed like |f|, and the sign of f there.
    #[inline]
    fn sample(&self, u: f32) -> (f32, f32) {
        let x = u * INVERSE as f32;
        let k = inverse_cell(x);
        let d = self.inverse[k] + (self.inverse[k + 1] - self.inverse[k]) * (x - k as f32);
        if !self.signed {
            return (d, 1.0);
        }
        let cell = (((d + self.radius) / (2.0 * self.radius)) * TABLE as f32) as usize;
        (d, self.sign[cell.min(TABLE - 1)])
    }
}

/// `(x as usize).min(INVERSE − 1)` for any `x` (NaN and negative numbers give 0), with the
/// float clamped first so that the conversion needs none of the saturating cast's checks.
#[inline(always)]
fn inverse_cell(x: f32) -> usize {
    // `max` returns 0 for NaN; the clamped float's integer part is the clamped integer.
    (x.max(0.0).min((INVERSE - 1) as f32) as i32 as usize).min(INVERSE - 1)
}

impl PixelFilter {
    /// The filter of the options.
    pub fn new(f: &Filter) -> PixelFilter {
        let (rx, ry) = f.radius();
        PixelFilter {
            x: Axis::new(f.kind, rx as f32, f.clip),
            y: Axis::new(f.kind, ry as f32, f.clip),
            kind: f.kind,
            clip: f.clip,
        }
    }

    /// The filter's radii in pixels (x, y).
    pub fn radius(&self) -> (f32, f32) {
        (self.x.radius, self.y.radius)
    }

    /// The filter's weight at offset (dx, dy) pixels from a pixel centre.
    pub fn eval(&self, dx: f32, dy: f32) -> f32 {
        self.eval_x(dx) * self.eval_y(dy)
    }

    /// The horizontal factor of [`PixelFilter::eval`].
    pub fn eval_x(&self, dx: f32) -> f32 {
        self.profile(dx, self.x.radius)
    }

    /// The vertical factor of [`PixelFilter::eval`].
    pub fn eval_y(&self, dy: f32) -> f32 {
        self.profile(dy, self.y.radius)
    }

    fn profile(&self, d: f32, r: f32) -> f32 {
        let v = profile(self.kind, d, r);
        if self.clip {
            v.max(0.0)
        } else {
            v
        }
    }

    /// The filter kind.
    pub fn kind(&self) -> FilterKind {
        self.kind
    }

    /// An offset from the pixel centre for uniform numbers `u`, and the sample's weight.
    pub fn sample(&self, u: glam::Vec2) -> (glam::Vec2, f32) {
        let (dx, sx) = self.x.sample(u.x);
        let (dy, sy) = self.y.sample(u.y);
        (glam::Vec2::new(dx, dy), sx * sy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`inverse_cell`] equals the saturating cast it replaces for every float of the unit
    /// interval's 2²⁴ steps scaled to the table, and at the edges (negative, NaN, ±∞,
    /// huge, just below 1024).
    #[test]
    fn inverse_cell_equals_the_saturating_cast() {
        let edges = [-1.0, -0.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e30, 1023.9999, 1024.0, 1e-40];
        let steps = (0..1u32 << 24).map(|i| i as f32 / (1u32 << 24) as f32 * INVERSE as f32);
        for x in steps.chain(edges) {
            assert_eq!(inverse_cell(x), (x as usize).min(INVERSE - 1), "{x}");
        }
    }

    #[test]
    fn one_pixel_box_stays_in_its_pixel_and_samples_uniformly() {
        let f = PixelFilter::new(&Filter { kind: FilterKind::Box, width: 1.0, height: 1.0, clip: false });
        let mut hist = [0u32; 10];
        for i in 0..10_000 {
            let (o, w) = f.sample(glam::Vec2::new((i as f32 + 0.5) / 10_000.0, 0.5));
            assert!(o.x.abs() <= 0.5 && w == 1.0);
            hist[((o.x + 0.5) * 10.0).min(9.0) as usize] += 1;
        }
        assert!(hist.iter().all(|&n| (n as i32 - 1000).abs() <= 2), "{hist:?}");
    }

    #[test]
    fn gauss_is_centred_and_mitchell_has_negative_lobes() {
        let g = PixelFilter::new(&Filter { kind: FilterKind::Gauss, width: 3.0, height: 3.0, clip: false });
        let mean: f32 =
            (0..1000).map(|i| g.sample(glam::Vec2::new((i as f32 + 0.5) / 1000.0, 0.5)).0.x).sum::<f32>() / 1000.0;
        assert!(mean.abs() < 1e-3);
        let m = PixelFilter::new(&Filter { kind: FilterKind::Mitchell, width: 4.0, height: 4.0, clip: false });
        let negative = (0..1000).filter(|i| m.sample(glam::Vec2::new((*i as f32 + 0.5) / 1000.0, 0.5)).1 < 0.0).count();
        assert!(negative > 0 && negative < 100, "{negative}");
        let clipped = PixelFilter::new(&Filter { kind: FilterKind::Mitchell, width: 4.0, height: 4.0, clip: true });
        assert!((0..1000).all(|i| clipped.sample(glam::Vec2::new((i as f32 + 0.5) / 1000.0, 0.3)).1 > 0.0));
    }
}
