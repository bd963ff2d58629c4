//! rampShader's light-angle translucence (`maya::ramp_shader`): the classic shader adds
//! P(u) ⊙ L for a light of colour L behind the surface at |N·l| = u, P(u) = t · C((1 − u)/2)
//! (C the colour ramp), with no cosine factor.
//!
//! mira's path lobe evaluates the ramp itself — all its knots that the light from behind
//! reads (those in [0, ½] and the first after), with their interpolation, as
//! `maya::utility::curve_at` reads a ramp — in the shape S = P/A, A = 2∫P du its albedo
//! (per channel, in closed form, not capped: where the classic shader passes more light
//! than it receives, so does the lobe; 2∫S du = 1); f = A/π ⊙ S(u)/u. It depends on the
//! light's direction only, as the classic formula (not reciprocal: the classic shaders
//! evaluate it towards the lights, as the path engine's camera paths do). It is sampled
//! uniformly over the far hemisphere (`translucence::uniform_opposite`), whose weight
//! f · u/pdf = 2A ⊙ S(u) stays bounded at the factor's pole at the horizon (u is clamped
//! to 1e-4 there).
//!
//! Each ramp's knots live in an interned [`RampShape`] (kept for the life of the process,
//! as `crate::measured_factor` interns its tables), so that the BSDF holds only a
//! reference to it, whatever the number of knots. A layeredShader stack's lobe is the
//! albedo-weighted sum of its layers' shapes: [`LightAngle`] holds up to
//! [`LIGHT_ANGLE_PARTS`] shapes and their weights, each evaluated from its own ramp.

use std::sync::Mutex;

use crate::Rgb;

/// How many distinct shapes (ramps, or diffuse translucence) one [`LightAngle`] sums:
/// a layeredShader stack's lobe keeps its layers' own ramps up to this many.
pub const LIGHT_ANGLE_PARTS: usize = 4;

/// How a ramp's segment runs from its knot to the next, as Maya's `<ramp>_Interp`
/// (and the classic shaders' `maya::utility::curve_at`) reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Interp {
    /// 0, none: the knot's value up to the next knot.
    Step,
    /// 1, linear.
    Linear,
    /// 2, smooth, and 3, spline (read as smooth, as the classic shaders do): the
    /// smoothstep 3τ² − 2τ³ of the segment's parameter τ.
    Smooth,
}

impl Interp {
    /// Maya's interpolation code: 0 none, 1 linear, anything else smooth.
    pub fn from_maya(code: i32) -> Interp {
        match code {
            0 => Interp::Step,
            1 => Interp::Linear,
            _ => Interp::Smooth,
        }
    }

    /// The segment's blend at its parameter `tau` ∈ [0, 1].
    fn blend(self, tau: f32) -> f32 {
        match self {
            Interp::Step => 0.0,
            Interp::Linear => tau,
            Interp::Smooth => tau * tau * (3.0 - 2.0 * tau),
        }
    }

    /// ∫_0^τ of [`Interp::blend`].
    fn integral(self, tau: f64) -> f64 {
        match self {
            Interp::Step => 0.0,
            Interp::Linear => 0.5 * tau * tau,
            Interp::Smooth => tau * tau * tau - 0.5 * tau * tau * tau * tau,
        }
    }
}

/// A ramp knot: position on the ramp, value per channel, its segment's interpolation.
type Knot = (f32, [f32; 3], Interp);

/// The value of the sorted knots at `x`, as `maya::utility::curve_at` reads a ramp: the
/// first knot's value before it, the last one's after it, each segment by its first
/// knot's interpolation.
fn ramp_at(knots: &[Knot], x: f32) -> [f32; 3] {
    let Some(first) = knots.first() else { return [0.0; 3] };
    if x <= first.0 {
        return first.1;
    }
    for w in knots.windows(2) {
        let ((p0, v0, interp), (p1, v1, _)) = (w[0], w[1]);
        if x < p1 {
            let tau = if p1 > p0 { (x - p0) / (p1 - p0) } else { 1.0 };
            let s = interp.blend(tau);
            return [v0[0] + (v1[0] - v0[0]) * s, v0[1] + (v1[1] - v0[1]) * s, v0[2] + (v1[2] - v0[2]) * s];
        }
    }
    knots[knots.len() - 1].1
}

/// ∫ over x ∈ [0, ½] of the knots' ramp ([`ramp_at`]), per channel, in closed form.
fn ramp_integral(knots: &[Knot]) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    let Some(first) = knots.first() else { return sum };
    let add = |sum: &mut [f64; 3], len: f64, v: [f32; 3]| {
        for c in 0..3 {
            sum[c] += len * f64::from(v[c]);
        }
    };
    // Before the first knot and after the last: their values.
    add(&mut sum, f64::from(first.0.clamp(0.0, 0.5)), first.1);
    let last = knots[knots.len() - 1];
    add(&mut sum, f64::from(0.5 - last.0.clamp(0.0, 0.5)), last.1);
    for w in knots.windows(2) {
        let ((p0, v0, interp), (p1, v1, _)) = (w[0], w[1]);
        let (a, b) = (f64::from(p0.clamp(0.0, 0.5)), f64::from(p1.clamp(0.0, 0.5)));
        if b <= a {
            continue;
        }
        let (p0, len) = (f64::from(p0), f64::from(p1 - p0));
        let rise = (interp.integral((b - p0) / len) - interp.integral((a - p0) / len)) * len;
        for c in 0..3 {
            sum[c] += (b - a) * f64::from(v0[c]) + f64::from(v1[c] - v0[c]) * rise;
        }
    }
    sum
}

/// One normalised shape S(u) (2∫S du = 1 per channel): `scale` ⊙ the ramp of `knots` at
/// x = (1 − u)/2 plus `linear` · u (the diffuse shape, S(u) = u, in a channel of albedo 0
/// or less, or for diffuse translucence).
#[derive(Debug, PartialEq)]
pub struct RampShape {
    /// The ramp's knots the light from behind reads (those in [0, ½] and the first after),
    /// sorted.
    knots: Vec<Knot>,
    /// t / A per channel (0 where the channel is diffuse).
    scale: [f32; 3],
    /// The linear part's slope per channel.
    linear: [f32; 3],
}

impl RampShape {
    /// Whether `self` and `other` hold the same numbers bit for bit (NaNs included).
    fn same_bits(&self, other: &RampShape) -> bool {
        let bits = |c: &[f32; 3]| c.map(f32::to_bits);
        self.knots.len() == other.knots.len()
            && self
                .knots
                .iter()
                .zip(&other.knots)
                .all(|(a, b)| a.0.to_bits() == b.0.to_bits() && bits(&a.1) == bits(&b.1) && a.2 == b.2)
            && bits(&self.scale) == bits(&other.scale)
            && bits(&self.linear) == bits(&other.linear)
    }

    /// S(u) per channel (`u` in [0, 1]).
    fn at(&self, u: f32) -> [f32; 3] {
        let r = ramp_at(&self.knots, 0.5 * (1.0 - u));
        std::array::from_fn(|c| self.scale[c] * r[c] + self.linear[c] * u)
    }
}

/// Diffuse translucence's shape, S(u) = u.
static DIFFUSE_SHAPE: RampShape = RampShape { knots: Vec::new(), scale: [0.0; 3], linear: [1.0; 3] };

/// Every distinct shape interned so far (kept for the life of the process).
static SHAPES: Mutex<Vec<&'static RampShape>> = Mutex::new(Vec::new());

/// The interned copy of `shape`: an equal one interned before, or a new one.
fn intern(shape: RampShape) -> &'static RampShape {
    if shape == DIFFUSE_SHAPE {
        return &DIFFUSE_SHAPE;
    }
    let mut shapes = SHAPES.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    // Compared bit for bit: a NaN in a knot or scale (which `==` never matches) finds its
    // earlier copy too, so the same ramp is never leaked twice.
    if let Some(s) = shapes.iter().find(|s| s.same_bits(&shape)) {
        return s;
    }
    let shape: &'static RampShape = Box::leak(Box::new(shape));
    shapes.push(shape);
    shape
}

/// The light-angle shape of a translucence lobe: the sum of up to [`LIGHT_ANGLE_PARTS`]
/// interned normalised shapes ([`RampShape`]) weighted per channel (the weights of a
/// channel sum to 1, so the sum keeps 2∫S du = 1). A part of zero weight is unused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightAngle {
    /// The parts' shapes (unused ones: the diffuse shape).
    parts: [&'static RampShape; LIGHT_ANGLE_PARTS],
    /// Each part's weight per channel.
    weight: [[f32; 3]; LIGHT_ANGLE_PARTS],
}

impl LightAngle {
    /// Diffuse translucence, S(u) = u: the factor is 1 at every angle.
    pub const DIFFUSE: LightAngle =
        LightAngle { parts: [&DIFFUSE_SHAPE; LIGHT_ANGLE_PARTS], weight: [[1.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]] };

    /// The shape of P(u) = `t` · C((1 − u)/2) for the colour ramp C of sorted `knots`
    /// (position, linear RGB, Maya interpolation code; none: C = `empty`) and its albedo
    /// A = 2∫P du (a channel of albedo 0 or less takes the diffuse shape). Exact for any
    /// number of knots.
    pub fn from_ramp(knots: &[(f32, Rgb, i32)], empty: Rgb, t: f32) -> (Rgb, LightAngle) {
        let full: Vec<Knot> = if knots.is_empty() {
            vec![(0.0, empty.into(), Interp::Linear)]
        } else {
            knots.iter().map(|&(x, c, i)| (x, c.into(), Interp::from_maya(i))).collect()
        };
        // The knots the classic shader reads for a light behind: those in [0, ½] and
        // the first after ½.
        let inside = full.iter().filter(|k| k.0 <= 0.5).count();
        let kept = full[..(inside + 1).min(full.len())].to_vec();
        let integral = ramp_integral(&kept);
        let albedo: [f32; 3] = std::array::from_fn(|c| (4.0 * f64::from(t) * integral[c]) as f32);
        let linear = albedo.map(|a| if a > 0.0 { 0.0 } else { 1.0 });
        let scale = albedo.map(|a| if a > 0.0 { t / a } else { 0.0 });
        let knots = if scale == [0.0; 3] { Vec::new() } else { kept };
        let shape = intern(RampShape { knots, scale, linear });
        let mut out = LightAngle::DIFFUSE;
        out.parts[0] = shape;
        (Rgb::from(albedo).max(Rgb::ZERO), out)
    }

    /// The parts in use: shape and weight.
    fn used(&self) -> impl Iterator<Item = (&'static RampShape, [f32; 3])> + '_ {
        self.parts.iter().zip(self.weight).filter(|(_, w)| *w != [0.0; 3]).map(|(p, w)| (*p, w))
    }

    /// How many distinct shapes [`LightAngle::mixed`] of these two would sum.
    fn parts_of_mix(&self, other: &LightAngle) -> usize {
        let mine = self.used().count();
        mine + other.used().filter(|(p, _)| !self.used().any(|(q, _)| std::ptr::eq(*p, q))).count()
    }

    /// Whether [`LightAngle::mixed`] of these two shapes is exact: together they sum at
    /// most [`LIGHT_ANGLE_PARTS`] distinct shapes (a layeredShader stack of more distinct
    /// ramps is warned).
    pub fn mixes_exactly(&self, other: &LightAngle) -> bool {
        self.parts_of_mix(other) <= LIGHT_ANGLE_PARTS
    }

    /// The shape of the sum of a lobe of albedo `a` and shape `self` and one of albedo
    /// `b` and shape `other` (per channel by their albedos; the sum's albedo is a + b):
    /// each part keeps its own ramp. Exact where [`LightAngle::mixes_exactly`]; a part
    /// past [`LIGHT_ANGLE_PARTS`] adds its weight to the part of the largest weight (whose
    /// shape it then takes).
    pub fn mixed(&self, a: Rgb, other: &LightAngle, b: Rgb) -> LightAngle {
        let (a, b) = (a.max(Rgb::ZERO), b.max(Rgb::ZERO));
        let mut wa = [0.0f32; 3];
        let mut wb = [0.0f32; 3];
        for c in 0..3 {
            let total = a[c] + b[c];
            (wa[c], wb[c]) = if total > 0.0 { (a[c] / total, b[c] / total) } else { (1.0, 0.0) };
        }
        let mut out = LightAngle { weight: [[0.0; 3]; LIGHT_ANGLE_PARTS], ..LightAngle::DIFFUSE };
        let mut add = |shape: &'static RampShape, w: [f32; 3]| {
            let same = out.parts.iter().zip(&out.weight).position(|(p, ow)| *ow != [0.0; 3] && std::ptr::eq(*p, shape));
            let slot = same.or_else(|| {
                let free = out.weight.iter().position(|ow| *ow == [0.0; 3])?;
                out.parts[free] = shape;
                Some(free)
            });
            // No room: the part of the largest weight takes it (keeping its own shape).
            let size = |w: &[f32; 3]| w[0] + w[1] + w[2];
            let slot = slot.unwrap_or_else(|| {
                (0..LIGHT_ANGLE_PARTS)
                    .max_by(|&i, &j| size(&out.weight[i]).total_cmp(&size(&out.weight[j])))
                    .unwrap_or(0)
            });
            for (o, x) in out.weight[slot].iter_mut().zip(w) {
                *o += x;
            }
        };
        for (p, w) in self.used() {
            add(p, std::array::from_fn(|c| w[c] * wa[c]));
        }
        for (p, w) in other.used() {
            add(p, std::array::from_fn(|c| w[c] * wb[c]));
        }
        if out.used().next().is_none() {
            return LightAngle::DIFFUSE;
        }
        out
    }

    /// S(u) per channel (`u` clamped to [0, 1]).
    pub fn shape_at(&self, u: f32) -> Rgb {
        let u = u.clamp(0.0, 1.0);
        let mut s = [0.0f32; 3];
        for (p, w) in self.used() {
            let v = p.at(u);
            for c in 0..3 {
                s[c] += w[c] * v[c];
            }
        }
        Rgb::from(s)
    }

    /// The factor S(u)/u that multiplies the albedo's A/π at the light's cosine `u`
    /// (clamped to 1e-4, the pole at the horizon).
    pub fn factor(&self, u: f32) -> Rgb {
        let u = u.clamp(1e-4, 1.0);
        self.shape_at(u) / u
    }
}

#[cfg(test)]
#[path = "light_angle_tests.rs"]
mod tests;
