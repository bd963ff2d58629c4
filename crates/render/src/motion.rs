//! Where time lives: the shutter, the sample times drawn over it, and moving things stored
//! as keys over it.
//!
//! mental ray's motion time runs over the *motion interval*: at time 0 everything sits
//! where its `transform` (and vertex positions) put it, at time 1 where its `motion
//! transform` (and vertex positions plus motion vectors) put it; in between and beyond the
//! path is interpolated and extrapolated linearly (piecewise linearly over `motion steps`).
//! The shutter opens at `shutter delay` and closes at `shutter` (options `shutter delay
//! close`), both motion times; a shutter longer than the interval makes longer trails.
//!
//! A ray's `time` is the *shutter time* `s` in `[0, 1]` (0: shutter open, 1: shutter
//! close), which is also Embree's `ray.time`. Everything that moves is stored as `K + 1`
//! keys at the shutter times `j / K` (`j = 0..=K`) and interpolated linearly between them
//! ([`lerp_keys`]), the same way by both acceleration backends and by shading.

use glam::{Affine3A, Vec3A};

/// The shutter's opening over its interval (mental ray 3.7's `"shutter full open"` and
/// `"shutter full close"`, fractions of the interval): the weight rises linearly from 0 at
/// the shutter's opening to 1 at `full_open`, stays 1 until `full_close` and falls to 0 at
/// its close. `0, 1` is the box shutter; `0.5, 0.5` the triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShutterShape {
    /// Shutter time (fraction of the interval) at which the shutter is fully open.
    pub full_open: f32,
    /// Shutter time at which it starts to close.
    pub full_close: f32,
}

impl ShutterShape {
    /// The box shutter: fully open from the opening to the close.
    pub const BOX: ShutterShape = ShutterShape { full_open: 0.0, full_close: 1.0 };

    /// The shutter time for `u` in `[0, 1)`, distributed as the shape's weight (its CDF
    /// inverted in closed form: quadratic ramps, linear plateau).
    pub fn sample(&self, u: f32) -> f32 {
        let (a, b) = (self.full_open, self.full_close);
        if a <= 0.0 && b >= 1.0 {
            return u;
        }
        // Areas under the weight: the ramp up (a/2), the plateau (b − a), the ramp down.
        let total = 0.5 * a + (b - a) + 0.5 * (1.0 - b);
        let target = u * total;
        let s = if target < 0.5 * a {
            (2.0 * a * target).sqrt()
        } else if target < 0.5 * a + (b - a) {
            a + (target - 0.5 * a)
        } else {
            1.0 - (2.0 * (1.0 - b) * (total - target)).max(0.0).sqrt()
        };
        s.clamp(0.0, 1.0)
    }

    /// The shape's weight at shutter time `s` (1 on the plateau), for tests and documents.
    pub fn weight(&self, s: f32) -> f32 {
        let (a, b) = (self.full_open, self.full_close);
        if s < a {
            s / a
        } else if s > b {
            (1.0 - s) / (1.0 - b)
        } else {
            1.0
        }
    }
}

/// The shutter interval in motion time and its shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shutter {
    /// Motion time at which the shutter opens (`shutter delay`).
    pub open: f32,
    /// Motion time at which it closes.
    pub close: f32,
    /// How far it is open in between.
    pub shape: ShutterShape,
}

impl Shutter {
    /// The scene's shutter when it renders motion blur (`motion on` and a shutter that
    /// closes after it opens), with the warnings of what it could not take.
    pub fn from_options(options: &scene::Options, warnings: &mut Vec<String>) -> Option<Shutter> {
        let (open, close) = options.shutter;
        if !options.motion || close <= open || !open.is_finite() || !close.is_finite() {
            return None;
        }
        let number = |name: &str| options.string_options.get(name).and_then(|v| v.as_f64());
        let full_open = number("shutter full open").unwrap_or(0.0).clamp(0.0, 1.0) as f32;
        let full_close = number("shutter full close").unwrap_or(1.0).clamp(0.0, 1.0) as f32;
        if options.string_options.contains_key("shutter shape function") {
            warnings.push(
                "string option \"shutter shape function\": shutter shape shaders are not run; the shape of \
                 \"shutter full open\"/\"shutter full close\" is used"
                    .into(),
            );
        }
        let shape = ShutterShape { full_open, full_close: full_close.max(full_open) };
        Some(Shutter { open: open as f32, close: close as f32, shape })
    }

    /// The motion time of shutter time `s`.
    pub fn motion_time(&self, s: f32) -> f32 {
        self.open + (self.close - self.open) * s
    }

    /// The motion times of `keys + 1` keys spread evenly over the shutter.
    pub fn key_times(&self, keys: usize) -> impl Iterator<Item = f32> + '_ {
        (0..=keys).map(move |j| self.motion_time(j as f32 / keys.max(1) as f32))
    }
}

/// Values that keys interpolate: matrices and points.
pub trait Lerp: Copy {
    /// `a + (b − a)·f`.
    fn lerp(a: Self, b: Self, f: f32) -> Self;
}

impl Lerp for Vec3A {
    fn lerp(a: Self, b: Self, f: f32) -> Self {
        a + (b - a) * f
    }
}

impl Lerp for Affine3A {
    fn lerp(a: Self, b: Self, f: f32) -> Self {
        Affine3A {
            matrix3: glam::Mat3A::from_cols(
                Vec3A::lerp(a.matrix3.x_axis, b.matrix3.x_axis, f),
                Vec3A::lerp(a.matrix3.y_axis, b.matrix3.y_axis, f),
                Vec3A::lerp(a.matrix3.z_axis, b.matrix3.z_axis, f),
            ),
            translation: Vec3A::lerp(a.translation, b.translation, f),
        }
    }
}

/// The segment of `count` keys (spread evenly over shutter times 0…1) that shutter time
/// `s` falls in, and the fraction within it.
#[inline]
pub fn key_segment(count: usize, s: f32) -> (usize, f32) {
    let segments = count.saturating_sub(1).max(1);
    let x = (s.clamp(0.0, 1.0) * segments as f32).min(segments as f32);
    let j = (x as usize).min(segments - 1);
    (j, x - j as f32)
}

/// The value of `keys` (spread evenly over shutter times 0…1) at shutter time `s`.
#[inline]
pub fn lerp_keys<T: Lerp>(keys: &[T], s: f32) -> T {
    if keys.len() == 1 {
        return keys[0];
    }
    let (j, f) = key_segment(keys.len(), s);
    T::lerp(keys[j], keys[j + 1], f)
}

/// A point on mental ray's motion path at motion time `tau`: `p` at time 0 moved by
/// `vectors` (the offsets from `p` at times `1/n, 2/n, … 1` of `n = vectors.len()` motion
/// steps), linear between them and extrapolated beyond.
pub fn motion_path(p: Vec3A, vectors: &[Vec3A], tau: f32) -> Vec3A {
    let n = vectors.len();
    if n == 0 {
        return p;
    }
    let x = tau * n as f32;
    // Segment k runs from time k/n to (k+1)/n; the first and last extend outwards.
    let k = (x.floor().max(0.0) as usize).min(n - 1);
    let from = if k == 0 { Vec3A::ZERO } else { vectors[k - 1] };
    let to = vectors[k];
    p + from + (to - from) * (x - k as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sampled shutter times follow the shape's weight: a histogram of 64 000
    /// stratified numbers in 16 bins matches the weight's integral over each bin within
    /// 0.2 % of the total (triangle, trapezoid and box).
    #[test]
    fn sampled_times_follow_the_shape() {
        for shape in [
            ShutterShape::BOX,
            ShutterShape { full_open: 0.5, full_close: 0.5 },
            ShutterShape { full_open: 0.2, full_close: 0.7 },
        ] {
            let n = 64_000;
            let mut bins = [0u32; 16];
            for i in 0..n {
                let s = shape.sample((i as f32 + 0.5) / n as f32);
                bins[((s * 16.0) as usize).min(15)] += 1;
            }
            // The weight's integral over each bin by the midpoint rule on a fine grid.
            let fine = 4096;
            let w: Vec<f64> = (0..fine).map(|i| f64::from(shape.weight((i as f32 + 0.5) / fine as f32))).collect();
            let total: f64 = w.iter().sum();
            for (b, &count) in bins.iter().enumerate() {
                let expect: f64 = w[b * fine / 16..(b + 1) * fine / 16].iter().sum::<f64>() / total;
                let got = f64::from(count) / f64::from(n);
                assert!((got - expect).abs() < 0.002, "{shape:?} bin {b}: {got} vs {expect}");
            }
        }
    }

    #[test]
    fn keys_interpolate_linearly() {
        let keys = [Vec3A::ZERO, Vec3A::X, Vec3A::X + Vec3A::Y];
        assert_eq!(lerp_keys(&keys, 0.0), Vec3A::ZERO);
        assert_eq!(lerp_keys(&keys, 0.25), Vec3A::X * 0.5);
        assert_eq!(lerp_keys(&keys, 0.75), Vec3A::X + Vec3A::Y * 0.5);
        assert_eq!(lerp_keys(&keys, 1.0), Vec3A::X + Vec3A::Y);
    }

    #[test]
    fn motion_paths_are_piecewise_linear_and_extrapolate() {
        let p = Vec3A::new(1.0, 0.0, 0.0);
        // One step: p + τ·m, beyond 1 too.
        assert_eq!(motion_path(p, &[Vec3A::Y * 2.0], 0.5), p + Vec3A::Y);
        assert_eq!(motion_path(p, &[Vec3A::Y * 2.0], 2.0), p + Vec3A::Y * 4.0);
        // Two steps: offsets at ½ and 1.
        let v = [Vec3A::X, Vec3A::X + Vec3A::Y];
        assert_eq!(motion_path(p, &v, 0.25), p + Vec3A::X * 0.5);
        assert_eq!(motion_path(p, &v, 0.75), p + Vec3A::X + Vec3A::Y * 0.5);
    }
}
