//! rampShader's light-angle translucence (`maya::ramp_shader`): the classic shader adds
//! P(u) ⊙ L for a light of colour L behind the surface at |N·l| = u, P(u) = t · C((1 − u)/2)
//! (C the colour ramp), with no cosine factor.
//!
//! mira's path lobe evaluates the ramp itself — all its knots that the light from behind
//! reads (those in [0, ½] and the first after, one more for a spline), with their
//! interpolation, as the classic shaders read a ramp ([`super::ramp_curve`]) — in the shape S = P/A, A = 2∫P du its albedo
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
//! [`LIGHT_ANGLE_PARTS`] shapes and their weights, each evaluated from its own ramp; a
//! material's translation folds any further ones into interned composite shapes
//! ([`LightAngle::mixed_interned`], exact); [`LightAngle::mixed`] adds them to the largest
//! part instead (a stack whose layers' shares follow the view is not mixed per hit: its
//! lobes are held by the material, `super::translucent_stack`).

use std::sync::Mutex;

use super::ramp_curve::{self, ramp_value, Interp, Knot};
use crate::Rgb;

/// How many distinct shapes (ramps, or diffuse translucence) one [`LightAngle`] sums:
/// a layeredShader stack's lobe keeps its layers' own ramps up to this many.
pub const LIGHT_ANGLE_PARTS: usize = 4;

/// ∫ over x ∈ [0, ½] of the knots' ramp ([`ramp_value`]), per channel, in closed form.
fn ramp_integral(knots: &[Knot]) -> [f64; 3] {
    ramp_curve::ramp_integral(knots, 0.0, 0.5)
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
    /// Further interned shapes summed in with their per-channel weights (a composite of
    /// a stack's parts past [`LIGHT_ANGLE_PARTS`], [`LightAngle::mixed_interned`]; the
    /// weights of a channel sum to 1, the own ramp and linear part then being 0).
    sum: Vec<(&'static RampShape, [f32; 3])>,
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
                .all(|(a, b)| a.0.to_bits() == b.0.to_bits() && bits(&a.1.into()) == bits(&b.1.into()) && a.2 == b.2)
            && bits(&self.scale) == bits(&other.scale)
            && bits(&self.linear) == bits(&other.linear)
            && self.sum.len() == other.sum.len()
            && self.sum.iter().zip(&other.sum).all(|(a, b)| std::ptr::eq(a.0, b.0) && bits(&a.1) == bits(&b.1))
    }

    /// S(u) per channel (`u` in [0, 1]).
    fn at(&self, u: f32) -> [f32; 3] {
        let r = ramp_value(&self.knots, 0.5 * (1.0 - u));
        let mut s: [f32; 3] = std::array::from_fn(|c| self.scale[c] * r[c] + self.linear[c] * u);
        for (part, w) in &self.sum {
            let v = part.at(u);
            for c in 0..3 {
                s[c] += w[c] * v[c];
            }
        }
        s
    }
}

/// Diffuse translucence's shape, S(u) = u.
static DIFFUSE_SHAPE: RampShape = RampShape { knots: Vec::new(), scale: [0.0; 3], linear: [1.0; 3], sum: Vec::new() };

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
        let full: Vec<Knot> = if knots.is_empty() { vec![(0.0, empty, 1)] } else { knots.to_vec() };
        // The knots the classic shader reads for a light behind: those in [0, ½] and
        // the first after ½ (and the one after that where a spline segment crosses ½:
        // its slope at the first knot after ½ reads it).
        let inside = full.iter().filter(|k| k.0 <= 0.5).count();
        let spline_crosses = inside > 0 && Interp::from_maya(full[inside - 1].2) == Interp::Spline;
        let kept = full[..(inside + 1 + usize::from(spline_crosses)).min(full.len())].to_vec();
        let integral = ramp_integral(&kept);
        let albedo: [f32; 3] = std::array::from_fn(|c| (4.0 * f64::from(t) * integral[c]) as f32);
        let linear = albedo.map(|a| if a > 0.0 { 0.0 } else { 1.0 });
        let scale = albedo.map(|a| if a > 0.0 { t / a } else { 0.0 });
        let knots = if scale == [0.0; 3] { Vec::new() } else { kept };
        let shape = intern(RampShape { knots, scale, linear, sum: Vec::new() });
        let mut out = LightAngle::DIFFUSE;
        out.parts[0] = shape;
        (Rgb::from(albedo).max(Rgb::ZERO), out)
    }

    /// Whether `self` and `other` sum the same interned shapes by the same weights, bit
    /// for bit.
    pub fn same_parts(&self, other: &LightAngle) -> bool {
        let bits = |w: &[[f32; 3]; LIGHT_ANGLE_PARTS]| w.map(|c| c.map(f32::to_bits));
        self.parts.iter().zip(&other.parts).all(|(a, b)| std::ptr::eq(*a, *b))
            && bits(&self.weight) == bits(&other.weight)
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
        self.mix(a, other, b, false)
    }

    /// [`LightAngle::mixed`], exact for any number of distinct shapes: past
    /// [`LIGHT_ANGLE_PARTS`] the two parts of the smallest weights are folded into one
    /// interned composite shape (their per-channel weighted mean, kept for the life of
    /// the process) until four remain. For a material's translation only (a mix per hit
    /// would intern a composite per hit).
    pub fn mixed_interned(&self, a: Rgb, other: &LightAngle, b: Rgb) -> LightAngle {
        self.mix(a, other, b, true)
    }

    /// [`LightAngle::mixed`] (`exact` false) or [`LightAngle::mixed_interned`].
    fn mix(&self, a: Rgb, other: &LightAngle, b: Rgb, exact: bool) -> LightAngle {
        let (a, b) = (a.max(Rgb::ZERO), b.max(Rgb::ZERO));
        let mut wa = [0.0f32; 3];
        let mut wb = [0.0f32; 3];
        for c in 0..3 {
            let total = a[c] + b[c];
            (wa[c], wb[c]) = if total > 0.0 { (a[c] / total, b[c] / total) } else { (1.0, 0.0) };
        }
        if exact && !self.mixes_exactly(other) {
            return self.folded(wa, other, wb);
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

    /// The mix of `self` by per-channel share `wa` and `other` by `wb` with every
    /// distinct shape kept: the two parts of the smallest total weight folded into an
    /// interned composite until [`LIGHT_ANGLE_PARTS`] remain.
    fn folded(&self, wa: [f32; 3], other: &LightAngle, wb: [f32; 3]) -> LightAngle {
        let mut parts: Vec<(&'static RampShape, [f32; 3])> = Vec::new();
        let scaled = self
            .used()
            .map(|(p, w)| (p, std::array::from_fn(|c| w[c] * wa[c])))
            .chain(other.used().map(|(p, w)| (p, std::array::from_fn(|c| w[c] * wb[c]))));
        for (p, w) in scaled {
            match parts.iter_mut().find(|(q, _)| std::ptr::eq(*q, p)) {
                Some((_, ow)) => (0..3).for_each(|c| ow[c] += w[c]),
                None => parts.push((p, w)),
            }
        }
        let size = |w: &[f32; 3]| w[0] + w[1] + w[2];
        while parts.len() > LIGHT_ANGLE_PARTS {
            parts.sort_by(|x, y| size(&y.1).total_cmp(&size(&x.1)));
            let (y, x) = (parts.pop().expect("parts"), parts.pop().expect("parts"));
            let total: [f32; 3] = std::array::from_fn(|c| x.1[c] + y.1[c]);
            let share = |w: [f32; 3]| -> [f32; 3] {
                std::array::from_fn(|c| if total[c] > 0.0 { w[c] / total[c] } else { 0.0 })
            };
            let composite = RampShape {
                knots: Vec::new(),
                scale: [0.0; 3],
                linear: [0.0; 3],
                sum: vec![(x.0, share(x.1)), (y.0, share(y.1))],
            };
            parts.push((intern(composite), total));
        }
        let mut out = LightAngle { weight: [[0.0; 3]; LIGHT_ANGLE_PARTS], ..LightAngle::DIFFUSE };
        for (k, (p, w)) in parts.into_iter().enumerate() {
            out.parts[k] = p;
            out.weight[k] = w;
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
