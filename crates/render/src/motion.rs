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
//!
//! A transform that turns between `transform` and `motion transform` is moved as mental ray
//! moves it, as a rotation: [`transform_keys`] splits both matrices into translation,
//! rotation and scale, and places enough keys along the turn that the straight lines
//! between them stay close to it.

use glam::{Affine3A, Quat, Vec3, Vec3A};

/// The shutter's opening over its interval (mental ray 3.7's `"shutter full open"` and
/// `"shutter full close"`, fractions of the interval): the weight rises linearly from 0 at
/// the shutter's opening to 1 at `full_open`, stays 1 until `full_close` and falls to 0 at
/// its close. `0, 1` is the box shutter; `0.5, 0.5` the triangle. A `"shutter shape
/// function"` shader's table replaces it ([`ShutterShape::table`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ShutterShape {
    /// Shutter time (fraction of the interval) at which the shutter is fully open.
    pub full_open: f32,
    /// Shutter time at which it starts to close.
    pub full_close: f32,
    /// The shape shader's weights tabulated over the interval, as their running sums
    /// normalised to end at 1 (`cdf[i]`: the share of the shutter's opening before the end
    /// of bin `i` of `cdf.len()` equal bins, the weight constant within each bin); when
    /// set, it is the shape and `full_open`/`full_close` play no part.
    pub cdf: Option<std::sync::Arc<[f32]>>,
}

impl ShutterShape {
    /// The box shutter: fully open from the opening to the close.
    pub const BOX: ShutterShape = ShutterShape { full_open: 0.0, full_close: 1.0, cdf: None };

    /// A shape from weights at the centres of equal bins over the interval (a shutter
    /// shape shader's table); `None` if they are not finite, negative or all 0.
    pub fn tabulated(weights: &[f32]) -> Option<ShutterShape> {
        if weights.is_empty() || weights.iter().any(|w| !w.is_finite() || *w < 0.0) {
            return None;
        }
        let mut sum = 0.0f64;
        let sums: Vec<f64> = weights
            .iter()
            .map(|w| {
                sum += f64::from(*w);
                sum
            })
            .collect();
        if sum <= 0.0 {
            return None;
        }
        let cdf: Vec<f32> = sums.iter().map(|s| (s / sum) as f32).collect();
        Some(ShutterShape { cdf: Some(cdf.into()), ..ShutterShape::BOX })
    }

    /// The shutter time for `u` in `[0, 1)`, distributed as the shape's weight (its CDF
    /// inverted in closed form: quadratic ramps, linear plateau; a table's CDF is
    /// piecewise linear and inverted by search).
    pub fn sample(&self, u: f32) -> f32 {
        if let Some(cdf) = &self.cdf {
            // The first bin whose running sum passes u, then linearly within it.
            let i = cdf.partition_point(|c| *c <= u).min(cdf.len() - 1);
            let before = if i == 0 { 0.0 } else { cdf[i - 1] };
            let width = cdf[i] - before;
            let f = if width > 0.0 { ((u - before) / width).clamp(0.0, 1.0) } else { 0.5 };
            return ((i as f32 + f) / cdf.len() as f32).clamp(0.0, 1.0);
        }
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

    /// The shape's weight at shutter time `s` (1 on the plateau; a table's weight relative
    /// to its mean), for tests and documents.
    pub fn weight(&self, s: f32) -> f32 {
        if let Some(cdf) = &self.cdf {
            let n = cdf.len();
            let i = ((s * n as f32) as usize).min(n - 1);
            let before = if i == 0 { 0.0 } else { cdf[i - 1] };
            return (cdf[i] - before) * n as f32;
        }
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
#[derive(Clone, Debug, PartialEq)]
pub struct Shutter {
    /// Motion time at which the shutter opens (`shutter delay`).
    pub open: f32,
    /// Motion time at which it closes.
    pub close: f32,
    /// How far it is open in between.
    pub shape: ShutterShape,
}

impl Shutter {
    /// The scene's shutter when it renders motion (`motion on` and a shutter that closes
    /// after it opens, or a *zero-length* shutter that opens and closes at the same motion
    /// time other than 0). Its shape is the table of the `"shutter shape function"`
    /// shader when the shading has one (`shutter_weights`, see `shader::shutter`), else the
    /// `"shutter full open"`/`"shutter full close"` shape.
    ///
    /// mental ray's manual: the shutter opens at time `delay` and closes at its close, and
    /// "setting the shutter open and close times to the same value" renders without blur
    /// (it leaves the motion to output shaders); the scene is then seen at that time, so
    /// `shutter 0.3 0.3` shows everything where it is at motion time 0.3 (a shutter whose
    /// keys all lie at that time). `shutter 0 0`, the default, is motion time 0: no shutter.
    pub fn from_options(options: &scene::Options, shutter_weights: Option<&[f32]>) -> Option<Shutter> {
        let (open, close) = options.shutter;
        if !options.motion || !open.is_finite() || !close.is_finite() {
            return None;
        }
        if close == open && open != 0.0 {
            return Some(Shutter { open: open as f32, close: open as f32, shape: ShutterShape::BOX });
        }
        if close <= open {
            return None;
        }
        let number = |name: &str| options.string_options.get(name).and_then(|v| v.as_f64());
        let full_open = number("shutter full open").unwrap_or(0.0).clamp(0.0, 1.0) as f32;
        let full_close = number("shutter full close").unwrap_or(1.0).clamp(0.0, 1.0) as f32;
        let shape = shutter_weights.and_then(ShutterShape::tabulated).unwrap_or(ShutterShape {
            full_open,
            full_close: full_close.max(full_open),
            cdf: None,
        });
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

/// The largest turn (radians, 7.5°) between neighbouring keys of a rotating transform:
/// linear interpolation between keys `Δ` apart brings a point at distance `r` from the axis
/// at most `r·(1 − cos(Δ/2))` closer to it (0.214 % of `r` at 7.5°).
pub const MAX_KEY_TURN: f32 = 7.5 * std::f32::consts::PI / 180.0;

/// The most key intervals a rotating transform gets (48: a whole turn over the shutter
/// at 7.5° each); a faster turn gets coarser keys.
pub const MAX_TURN_SEGMENTS: usize = 48;

/// A transform as the parts mental ray interpolates separately: scale (along the object's
/// axes, then) rotation, then translation.
#[derive(Clone, Copy, Debug)]
struct Decomposed {
    scale: Vec3,
    rotation: Quat,
    translation: Vec3,
}

/// `m` split into scale, rotation and translation, or `None` when it is not such a product
/// (shear, a singular or non-finite matrix) to within 1e-4 of its largest column.
fn decompose(m: Affine3A) -> Option<Decomposed> {
    let det = m.matrix3.determinant();
    if !m.is_finite() || !det.is_finite() || det == 0.0 {
        return None;
    }
    let (scale, rotation, translation) = m.to_scale_rotation_translation();
    if !scale.is_finite() || !rotation.is_finite() || scale.abs().min_element() == 0.0 {
        return None;
    }
    let back = glam::Mat3A::from_quat(rotation) * glam::Mat3A::from_diagonal(scale);
    let size = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis].iter().map(|c| c.length()).fold(0.0, f32::max);
    back.abs_diff_eq(m.matrix3, 1e-4 * size).then_some(Decomposed { scale, rotation, translation })
}

/// Keys over `shutter` of a transform that is `start` at motion time 0 and `end` at
/// motion time 1 (both object → world).
///
/// When both split into scale, rotation and translation with scales of the same signs
/// and the turn between them sweeps more than [`MAX_KEY_TURN`] over the shutter, the
/// translation and scale move linearly and the rotation turns about one axis at a constant
/// rate (the shorter way, extrapolated beyond the motion interval like the rest), with one
/// key per [`MAX_KEY_TURN`] or less (at most [`MAX_TURN_SEGMENTS`] intervals). Otherwise —
/// no turn to speak of (pure translation, a small turn), shear, a change of handedness —
/// the two matrices are interpolated linearly: two keys. Since the translation moves
/// linearly, an object turns about its own origin (its object space's (0, 0, 0)).
///
/// `steps` is mental ray's `motion steps` (options): the motion path is cut into at least
/// that many segments. On a turning transform that places keys on the turn (a turn under
/// [`MAX_KEY_TURN`] with `steps` 4 gets 4 intervals instead of the two matrices' straight
/// line); where the path is a straight line anyway (no turn, or a matrix that does not
/// split) more keys on it would change nothing, and two keys are kept.
pub fn transform_keys(start: Affine3A, end: Affine3A, shutter: &Shutter, steps: usize) -> Vec<Affine3A> {
    let linear = || shutter.key_times(1).map(|tau| Affine3A::lerp(start, end, tau)).collect();
    let (Some(a), Some(b)) = (decompose(start), decompose(end)) else {
        return linear();
    };
    if (a.scale * b.scale).min_element() <= 0.0 {
        return linear();
    }
    // The turn taking the start's rotation to the end's, the shorter way.
    let mut turn = (b.rotation * a.rotation.inverse()).normalize();
    if turn.w < 0.0 {
        turn = -turn;
    }
    let (axis, angle) = turn.to_axis_angle();
    let swept = angle * (shutter.close - shutter.open).abs();
    let by_turn = if swept > MAX_KEY_TURN { (swept / MAX_KEY_TURN).ceil() as usize } else { 1 };
    let mut segments = by_turn.max(steps).min(MAX_TURN_SEGMENTS);
    if shutter.close == shutter.open && angle.is_finite() && angle > 0.0 {
        // A zero-length shutter: the turn's one point in time, as two equal keys.
        segments = 1;
    } else if !swept.is_finite() || swept <= 0.0 || segments < 2 {
        return linear();
    }
    shutter
        .key_times(segments)
        .map(|tau| {
            Affine3A::from_scale_rotation_translation(
                a.scale.lerp(b.scale, tau),
                Quat::from_axis_angle(axis, angle * tau) * a.rotation,
                a.translation.lerp(b.translation, tau),
            )
        })
        .collect()
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
            ShutterShape { full_open: 0.5, full_close: 0.5, cdf: None },
            ShutterShape { full_open: 0.2, full_close: 0.7, cdf: None },
            // A table: weight 1 + sin²(π s) at 64 bin centres, and one with closed bins.
            ShutterShape::tabulated(
                &(0..64)
                    .map(|i| 1.0 + (std::f32::consts::PI * (i as f32 + 0.5) / 64.0).sin().powi(2))
                    .collect::<Vec<_>>(),
            )
            .expect("a table"),
            ShutterShape::tabulated(&(0..64).map(|i| if i % 8 < 3 { 0.0 } else { 2.0 }).collect::<Vec<_>>())
                .expect("a table"),
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

    /// A unit quad centred on its object's origin, placed at (3, 0, 0) and turning 90°
    /// about its centre (the z axis through it) over a `shutter 0 1`: at the shutter's
    /// middle the keys put its corner (0.5, 0.5) at (3, 0.7071) — turned 45°, still 0.7071
    /// from the centre — within 1e-3, where the linear matrix interpolation puts it at
    /// (3, 0.5), shrunk by cos 45°. At every time the corner stays within 1 − cos 3.75°
    /// (0.214 %, plus 1e-5 for rounding) of its distance from the centre.
    #[test]
    fn a_turning_quad_keeps_its_size() {
        let shutter = Shutter { open: 0.0, close: 1.0, shape: ShutterShape::BOX };
        let centre = Vec3A::new(3.0, 0.0, 0.0);
        let start = Affine3A::from_translation(centre.into());
        let end = start * Affine3A::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let keys = transform_keys(start, end, &shutter, 1);
        assert_eq!(keys.len(), 13, "90° in 7.5° steps: 12 intervals");
        let corner = Vec3A::new(0.5, 0.5, 0.0);
        let mid = lerp_keys(&keys, 0.5).transform_point3a(corner);
        let want = Vec3A::new(3.0, std::f32::consts::FRAC_1_SQRT_2, 0.0);
        assert!((mid - want).length() < 1e-3, "{mid} vs {want}");
        let matrix_lerp = Affine3A::lerp(start, end, 0.5).transform_point3a(corner);
        assert!((matrix_lerp - Vec3A::new(3.0, 0.5, 0.0)).length() < 1e-5, "{matrix_lerp}");
        for i in 0..=100 {
            let s = i as f32 / 100.0;
            let p = lerp_keys(&keys, s).transform_point3a(corner);
            let r = (p - centre).length();
            let bound = 1.0 - (MAX_KEY_TURN / 2.0).cos() + 1e-5;
            assert!((r / std::f32::consts::FRAC_1_SQRT_2 - 1.0).abs() < bound, "s = {s}: r = {r}");
            // And it is on the turn: at angle 45° + 90°·s from the x axis within 0.2°.
            let a = (p.y - centre.y).atan2(p.x - centre.x).to_degrees();
            assert!((a - (45.0 + 90.0 * s)).abs() < 0.2, "s = {s}: {a}°");
        }
        // The end keys are the two matrices themselves.
        assert!(keys[0].abs_diff_eq(start, 1e-5) && keys[12].abs_diff_eq(end, 1e-5));
    }

    /// Translation and scale move linearly along with the turn; a shutter twice the motion
    /// interval extrapolates the turn to 180° (24 intervals).
    #[test]
    fn turns_extrapolate_with_translation_and_scale() {
        let shutter = Shutter { open: 0.0, close: 2.0, shape: ShutterShape::BOX };
        let start = Affine3A::from_scale(Vec3::splat(2.0));
        let end = Affine3A::from_scale_rotation_translation(
            Vec3::splat(3.0),
            Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
            Vec3::new(0.0, 4.0, 0.0),
        );
        let keys = transform_keys(start, end, &shutter, 1);
        assert_eq!(keys.len(), 25);
        // Shutter time 1 is motion time 2: scale 4, turned 180° about y, moved 8 up.
        let p = keys[24].transform_point3a(Vec3A::X);
        assert!((p - Vec3A::new(-4.0, 8.0, 0.0)).length() < 1e-4, "{p}");
    }

    /// No turn, a small turn, a shear or a change of handedness: the matrices are
    /// interpolated linearly (two keys, the same as before rotations were detected).
    #[test]
    fn transforms_without_a_large_turn_stay_linear() {
        let shutter = Shutter { open: 0.0, close: 1.0, shape: ShutterShape::BOX };
        let start = Affine3A::from_rotation_x(0.3);
        let linear = |end: Affine3A| -> Vec<Affine3A> {
            shutter.key_times(1).map(|tau| Affine3A::lerp(start, end, tau)).collect()
        };
        let moved = Affine3A::from_translation(Vec3::new(1.0, 2.0, 3.0)) * start;
        assert_eq!(transform_keys(start, moved, &shutter, 1), linear(moved));
        let small = Affine3A::from_rotation_x(0.3 + 0.1);
        assert_eq!(transform_keys(start, small, &shutter, 1), linear(small));
        let mut sheared = Affine3A::from_rotation_z(1.0);
        sheared.matrix3.y_axis += Vec3A::X;
        assert_eq!(transform_keys(start, sheared, &shutter, 1), linear(sheared));
        let mirrored = Affine3A::from_rotation_z(1.0) * Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        assert_eq!(transform_keys(start, mirrored, &shutter, 1), linear(mirrored));
        let singular = Affine3A::from_scale(Vec3::new(0.0, 1.0, 1.0));
        assert_eq!(transform_keys(start, singular, &shutter, 1).len(), 2);
    }

    /// `motion steps 4` on a 6° turn (under [`MAX_KEY_TURN`], two keys on their own): four
    /// intervals on the turn, so a corner 0.7071 from the centre stays within
    /// 1 − cos(6°/8) = 0.0086 % of that distance (plus 1e-5 for rounding) all along, where
    /// the two matrices' straight line brings it 1 − cos 3° = 0.137 % closer at mid-shutter.
    /// On a straight path (a translation) more steps keep the two keys: they would lie on
    /// the line between them.
    #[test]
    fn motion_steps_cut_a_small_turn_into_intervals() {
        let shutter = Shutter { open: 0.0, close: 1.0, shape: ShutterShape::BOX };
        let start = Affine3A::IDENTITY;
        let end = Affine3A::from_rotation_z(6f32.to_radians());
        let corner = Vec3A::new(0.5, 0.5, 0.0);
        let r = corner.length();
        let two = transform_keys(start, end, &shutter, 1);
        assert_eq!(two.len(), 2);
        let mid = lerp_keys(&two, 0.5).transform_point3a(corner).length() / r;
        assert!((mid - 3f32.to_radians().cos()).abs() < 1e-5, "{mid}");
        let four = transform_keys(start, end, &shutter, 4);
        assert_eq!(four.len(), 5);
        for i in 0..=100 {
            let s = i as f32 / 100.0;
            let d = lerp_keys(&four, s).transform_point3a(corner).length() / r;
            assert!((1.0 - d).abs() < 1.0 - 0.75f32.to_radians().cos() + 1e-5, "s = {s}: {d}");
        }
        let moved = Affine3A::from_translation(Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(transform_keys(start, moved, &shutter, 4).len(), 2);
    }

    /// A zero-length shutter at motion time ½ (`shutter 0.5 0.5`, `motion on`) is a
    /// shutter whose keys all sit at that time: a transform turning 90° is there turned
    /// 45° at its full size (not the matrices' average, shrunk by cos 45°); `shutter 0 0`
    /// is no shutter at all.
    #[test]
    fn a_zero_length_shutter_holds_one_time() {
        let mut options = scene::Options { motion: true, shutter: (0.5, 0.5), ..scene::Options::default() };
        let shutter = Shutter::from_options(&options, None).expect("a zero-length shutter");
        assert_eq!((shutter.open, shutter.close), (0.5, 0.5));
        assert!(shutter.key_times(3).all(|t| t == 0.5));
        let start = Affine3A::IDENTITY;
        let end = Affine3A::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let keys = transform_keys(start, end, &shutter, 1);
        assert_eq!(keys.len(), 2);
        let corner = lerp_keys(&keys, 0.7).transform_point3a(Vec3A::X);
        let want = Vec3A::new(std::f32::consts::FRAC_1_SQRT_2, std::f32::consts::FRAC_1_SQRT_2, 0.0);
        assert!((corner - want).length() < 1e-5, "{corner}");
        options.shutter = (0.0, 0.0);
        assert!(Shutter::from_options(&options, None).is_none());
        options.shutter = (0.5, 0.5);
        options.motion = false;
        assert!(Shutter::from_options(&options, None).is_none());
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
