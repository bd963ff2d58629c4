//! Measured isotropic BSDFs (MDL's `df::measured_bsdf` of a `bsdf_measurement`, NVIDIA's
//! MBSDF files, [`reader`]): a reflection and a transmission part, each a grid of BSDF
//! values f (1/sr) over θ_in, θ_out (from the normal, `res_θ` samples at k·π/(2 res_θ),
//! k = 0 … res_θ − 1) and the azimuth difference Δφ ∈ [0, π] (`res_φ` samples at k·π/res_φ),
//! as the MDL SDK lays the samples out. Between samples the grid is read trilinearly; past
//! the last sample of an axis it is constant. The grid is made symmetric in θ_in and θ_out
//! on reading (the mean of the two entries, as the MDL SDK's runtime does), so the lobe is
//! reciprocal. The transmission part measures θ_out from the opposite side's normal.
//!
//! Sampling: at ωo's nearest θ_in row, a cell (θ_out interval, Δφ interval) is chosen from a
//! tabulated marginal/conditional distribution — each cell weighed by its corners' mean
//! value (over channels) plus 5 % of the row's mean, times its projected solid angle — and
//! a direction uniform in projected solid angle inside the cell, with a random sign of
//! Δφ; the part (reflection or transmission) by the two rows' albedos. The density is that
//! distribution's, exactly; the 5 % floor keeps it positive wherever the surface side can
//! scatter.

pub mod reader;

use std::f32::consts::{FRAC_PI_2, PI};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

use glam::{Vec2, Vec3A};

use crate::Rgb;

/// The share of a row's mean value every sampling cell gets on top of its own (a cosine
/// distribution mixed in: sampling never misses where the grid is non-zero).
const FLOOR: f32 = 0.05;

/// One part (reflection or transmission) of a measurement: the symmetric grid and its
/// sampling tables.
#[derive(Clone, PartialEq)]
pub struct Part {
    /// Samples of θ (θ_in and θ_out).
    res_theta: usize,
    /// Samples of Δφ.
    res_phi: usize,
    /// 1 (scalar) or 3 (RGB).
    channels: usize,
    /// f at ((i_in · res_θ + i_out) · res_φ + k) · channels + c, symmetric in i_in, i_out.
    values: Vec<f32>,
    /// Per θ_in row r: the cumulative distribution over θ_out cells (`res_θ` entries at
    /// r · res_θ, the last 1).
    marginal: Vec<f32>,
    /// Per θ_in row r and θ_out cell j: the cumulative distribution over Δφ cells
    /// (`res_φ` entries at (r · res_θ + j) · res_φ, the last 1).
    conditional: Vec<f32>,
    /// Per θ_in row: the albedo ∫ f cos θ dω the grid's cells give (channel mean).
    albedo: Vec<f32>,
}

impl std::fmt::Debug for Part {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Part({}² × {} × {})", self.res_theta, self.res_phi, self.channels)
    }
}

/// sin² of the start of θ cell `j` of `n` (cell j spans [j, j + 1] · π/(2n)).
fn sin2_at(j: usize, n: usize) -> f32 {
    (j as f32 * FRAC_PI_2 / n as f32).sin().powi(2)
}

/// A grid coordinate: `x` scaled to sample units, its lower sample, the next (itself at
/// the last) and the fraction between them.
#[inline]
fn coord(x: f32, scale: f32, n: usize) -> (usize, usize, f32) {
    let s = (x * scale).max(0.0);
    let i = (s as usize).min(n - 1);
    let j = if i + 1 < n { i + 1 } else { i };
    (i, j, (s - i as f32).clamp(0.0, 1.0))
}

/// Where a cumulative distribution `cdf` puts `u`: the chosen entry and `u` rescaled to
/// [0, 1) inside it.
fn pick(cdf: &[f32], u: f32) -> (usize, f32) {
    let k = cdf.partition_point(|&c| c <= u).min(cdf.len() - 1);
    let lo = if k == 0 { 0.0 } else { cdf[k - 1] };
    let p = cdf[k] - lo;
    let t = if p > 0.0 { ((u - lo) / p).clamp(0.0, 1.0 - f32::EPSILON) } else { 0.5 };
    (k, t)
}

/// The probability of entry `k` of cumulative distribution `cdf`.
fn mass(cdf: &[f32], k: usize) -> f32 {
    cdf[k] - if k == 0 { 0.0 } else { cdf[k - 1] }
}

impl Part {
    /// The part of grid `values` (as the file lays it out; made symmetric here) and its
    /// sampling tables. `values.len()` must be res_θ² · res_φ · channels.
    pub fn new(res_theta: usize, res_phi: usize, channels: usize, values: Vec<f32>) -> Part {
        let (nt, np, nc) = (res_theta, res_phi, channels);
        assert_eq!(values.len(), nt * nt * np * nc, "an MBSDF grid of the wrong size");
        let at = |a: usize, b: usize, k: usize, c: usize| ((a * nt + b) * np + k) * nc + c;
        let mut sym = values.clone();
        for a in 0..nt {
            for b in 0..nt {
                for k in 0..np {
                    for c in 0..nc {
                        sym[at(a, b, k, c)] = 0.5 * (values[at(a, b, k, c)] + values[at(b, a, k, c)]);
                    }
                }
            }
        }
        let mut part = Part {
            res_theta: nt,
            res_phi: np,
            channels: nc,
            values: sym,
            marginal: vec![0.0; nt * nt],
            conditional: vec![0.0; nt * nt * np],
            albedo: vec![0.0; nt],
        };
        let dphi = PI / np as f32;
        let mut cell = vec![0.0f32; nt * np];
        for r in 0..nt {
            // Each cell's mean corner value (channel mean).
            for j in 0..nt {
                let j1 = (j + 1).min(nt - 1);
                for k in 0..np {
                    let k1 = (k + 1).min(np - 1);
                    let mut s = 0.0;
                    for (b, q) in [(j, k), (j1, k), (j, k1), (j1, k1)] {
                        s += (0..nc).map(|c| part.values[at(r, b, q, c)]).sum::<f32>();
                    }
                    cell[j * np + k] = s / (4 * nc) as f32;
                }
            }
            let mean = cell.iter().sum::<f32>() / cell.len() as f32;
            let floor = FLOOR * mean + 1e-20;
            let mut albedo = 0.0f64;
            let mut total = 0.0f64;
            for j in 0..nt {
                // Projected solid angle of the cell, one sign of Δφ.
                let area = 0.5 * (sin2_at(j + 1, nt) - sin2_at(j, nt)) * dphi;
                let mut row = 0.0f64;
                for k in 0..np {
                    let v = cell[j * np + k];
                    albedo += 2.0 * f64::from(v * area);
                    row += f64::from((v + floor) * area);
                    part.conditional[(r * nt + j) * np + k] = row as f32;
                }
                for k in 0..np {
                    part.conditional[(r * nt + j) * np + k] /= row as f32;
                }
                part.conditional[(r * nt + j) * np + np - 1] = 1.0;
                total += row;
                part.marginal[r * nt + j] = total as f32;
            }
            for j in 0..nt {
                part.marginal[r * nt + j] /= total as f32;
            }
            part.marginal[r * nt + nt - 1] = 1.0;
            part.albedo[r] = albedo as f32;
        }
        part
    }

    /// f at θ_in `ti`, θ_out `to` (radians from the normal, [0, π/2]) and azimuth
    /// difference `dphi` ([0, π]), trilinear between the samples.
    pub fn value(&self, ti: f32, to: f32, dphi: f32) -> Rgb {
        let (nt, np, nc) = (self.res_theta, self.res_phi, self.channels);
        let st = nt as f32 / FRAC_PI_2;
        let (a0, a1, ta) = coord(ti, st, nt);
        let (b0, b1, tb) = coord(to, st, nt);
        let (k0, k1, tk) = coord(dphi, np as f32 / PI, np);
        let mut out = [0.0f32; 3];
        for (c, o) in out.iter_mut().enumerate().take(nc) {
            let v = |a: usize, b: usize, k: usize| self.values[((a * nt + b) * np + k) * nc + c];
            let lerp = |x: f32, y: f32, t: f32| x + (y - x) * t;
            let along_k = |a: usize, b: usize| lerp(v(a, b, k0), v(a, b, k1), tk);
            let along_b = |a: usize| lerp(along_k(a, b0), along_k(a, b1), tb);
            *o = lerp(along_b(a0), along_b(a1), ta);
        }
        if nc == 1 {
            Rgb::splat(out[0])
        } else {
            Rgb::new(out[0], out[1], out[2])
        }
    }

    /// The θ_in row sampling uses for θ_in `ti`: the nearest sample.
    fn row(&self, ti: f32) -> usize {
        ((ti * self.res_theta as f32 / FRAC_PI_2).round() as usize).min(self.res_theta - 1)
    }

    /// A direction (θ_out, Δφ ∈ [0, π] and a sign) from the row of θ_in `ti`: cos θ_out,
    /// sin θ_out, Δφ with its sign.
    fn sample(&self, ti: f32, u: Vec2) -> (f32, f32, f32) {
        let (nt, np) = (self.res_theta, self.res_phi);
        let r = self.row(ti);
        let (j, t) = pick(&self.marginal[r * nt..(r + 1) * nt], u.x);
        let (k, s) = pick(&self.conditional[(r * nt + j) * np..(r * nt + j + 1) * np], u.y);
        let (s0, s1) = (sin2_at(j, nt), sin2_at(j + 1, nt));
        let sin2 = (s0 + (s1 - s0) * t).clamp(0.0, 1.0);
        let (sign, s) = if s < 0.5 { (1.0, 2.0 * s) } else { (-1.0, 2.0 * s - 1.0) };
        let dphi = (k as f32 + s) * PI / np as f32;
        ((1.0 - sin2).sqrt(), sin2.sqrt(), sign * dphi)
    }

    /// The density (per solid angle, of the part once chosen) of sampling θ_out `to` and
    /// Δφ `dphi` from θ_in `ti`, `cos_out` = cos θ_out.
    fn pdf(&self, ti: f32, to: f32, dphi: f32, cos_out: f32) -> f32 {
        let (nt, np) = (self.res_theta, self.res_phi);
        let r = self.row(ti);
        let j = ((to * nt as f32 / FRAC_PI_2) as usize).min(nt - 1);
        let k = ((dphi * np as f32 / PI) as usize).min(np - 1);
        let pj = mass(&self.marginal[r * nt..(r + 1) * nt], j);
        let pk = mass(&self.conditional[(r * nt + j) * np..(r * nt + j + 1) * np], k);
        let area = (sin2_at(j + 1, nt) - sin2_at(j, nt)) * PI / np as f32;
        if area <= 0.0 {
            return 0.0;
        }
        pj * pk * cos_out / area
    }

    /// The albedo of the row sampling uses at θ_in `ti`.
    fn row_albedo(&self, ti: f32) -> f32 {
        self.albedo[self.row(ti)]
    }
}

/// A measurement: its reflection and transmission parts (either may be absent).
#[derive(Clone, Debug, PartialEq)]
pub struct MeasuredBsdf {
    /// The reflection part.
    pub reflection: Option<Part>,
    /// The transmission part.
    pub transmission: Option<Part>,
}

/// The most distinct measurements one process interns (a slot each in [`SLOTS`]).
pub const MAX_MEASUREMENTS: usize = 4096;

/// Every distinct measurement interned so far, in the order interned (kept for the life of
/// the process: one per distinct file a scene's materials use). Interning takes the lock;
/// lobes read [`SLOTS`] without it.
static TABLES: Mutex<Vec<&'static MeasuredBsdf>> = Mutex::new(Vec::new());

/// The interned measurements by index, readable without a lock: slot k is set once, when
/// the k-th distinct measurement is interned.
static SLOTS: [OnceLock<&'static MeasuredBsdf>; MAX_MEASUREMENTS] = [const { OnceLock::new() }; MAX_MEASUREMENTS];

/// How many slots of [`SLOTS`] are set.
static COUNT: AtomicUsize = AtomicUsize::new(0);

/// The interned copy of `m`: an equal measurement interned before, or `m` itself; `Err`
/// when [`MAX_MEASUREMENTS`] distinct ones are interned already.
pub fn intern(m: MeasuredBsdf) -> Result<&'static MeasuredBsdf, String> {
    let mut tables = TABLES.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(t) = tables.iter().find(|t| ***t == m) {
        return Ok(t);
    }
    if tables.len() >= MAX_MEASUREMENTS {
        return Err(format!("more than {MAX_MEASUREMENTS} distinct bsdf measurements in one process"));
    }
    let table: &'static MeasuredBsdf = Box::leak(Box::new(m));
    // Set under the lock, so slots fill in order and `COUNT` only grows past set slots.
    let _ = SLOTS[tables.len()].set(table);
    tables.push(table);
    COUNT.store(tables.len(), Ordering::Release);
    Ok(table)
}

/// A measured lobe: an interned measurement and the parts it uses (MDL's `mode`), at unit
/// weight (the `multiplier` is the lobe sum's weight). The measurement is held by its
/// index among the interned ones, not a pointer, so that the lobe is 4-byte aligned and
/// [`crate::Lobe`] stays 16 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasuredLobe {
    /// The measurement's index in the interned ones.
    table: u32,
    /// Whether the reflection part is used.
    pub reflect: bool,
    /// Whether the transmission part is used.
    pub transmit: bool,
}

/// θ of a direction from the normal on its own side, [0, π/2].
#[inline]
fn theta(w: Vec3A) -> f32 {
    w.z.abs().min(1.0).acos()
}

/// The azimuth difference of two directions, [0, π] (0 where either is the normal).
#[inline]
fn azimuth_difference(a: Vec3A, b: Vec3A) -> f32 {
    (a.x * b.y - a.y * b.x).abs().atan2(a.x * b.x + a.y * b.y)
}

impl MeasuredLobe {
    /// The lobe of the interned measurement `table` (from [`intern`]) using its reflection
    /// and/or transmission part; `None` if `table` was not interned.
    pub fn new(table: &'static MeasuredBsdf, reflect: bool, transmit: bool) -> Option<MeasuredLobe> {
        let count = COUNT.load(Ordering::Acquire);
        let index = SLOTS[..count].iter().position(|slot| slot.get().is_some_and(|t| std::ptr::eq(*t, table)))?;
        Some(MeasuredLobe { table: index as u32, reflect, transmit })
    }

    /// The measurement.
    #[inline]
    pub fn table(&self) -> &'static MeasuredBsdf {
        // Only `new` makes lobes, from slots that are set.
        SLOTS[self.table as usize].get().expect("an interned measurement")
    }

    /// The part that scatters from ωo to ωi (reflection on ωo's side, transmission
    /// through), if used and present.
    fn part(&self, wo: Vec3A, wi: Vec3A) -> Option<&'static Part> {
        if wo.z * wi.z > 0.0 {
            self.table().reflection.as_ref().filter(|_| self.reflect)
        } else if wo.z * wi.z < 0.0 {
            self.table().transmission.as_ref().filter(|_| self.transmit)
        } else {
            None
        }
    }

    /// f(ωo, ωi), local frame.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        self.part(wo, wi).map_or(Rgb::ZERO, |p| p.value(theta(wo), theta(wi), azimuth_difference(wo, wi)))
    }

    /// The probability of choosing the reflection part at ωo (the two rows' albedos).
    fn reflect_share(&self, wo: Vec3A) -> f32 {
        let ti = theta(wo);
        let r = self.table().reflection.as_ref().filter(|_| self.reflect).map(|p| p.row_albedo(ti));
        let t = self.table().transmission.as_ref().filter(|_| self.transmit).map(|p| p.row_albedo(ti));
        match (r, t) {
            (Some(_), None) => 1.0,
            (None, _) => 0.0,
            (Some(r), Some(t)) if r + t > 0.0 => r / (r + t),
            (Some(_), Some(_)) => 0.5,
        }
    }

    /// The density of [`MeasuredLobe::sample`] per solid angle.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let Some(part) = self.part(wo, wi) else { return 0.0 };
        let share = self.reflect_share(wo);
        let share = if wo.z * wi.z > 0.0 { share } else { 1.0 - share };
        share * part.pdf(theta(wo), theta(wi), azimuth_difference(wo, wi), wi.z.abs())
    }

    /// A direction drawn from the lobe's density (see the module's doc).
    pub fn sample(&self, wo: Vec3A, u: Vec2) -> Option<Vec3A> {
        if wo.z == 0.0 {
            return None;
        }
        let share = self.reflect_share(wo);
        let (reflect, ux) = if u.x < share {
            (true, u.x / share)
        } else {
            (false, ((u.x - share) / (1.0 - share)).min(1.0 - f32::EPSILON))
        };
        let part = if reflect { self.table().reflection.as_ref()? } else { self.table().transmission.as_ref()? };
        let (cos, sin, dphi) = part.sample(theta(wo), Vec2::new(ux, u.y));
        let phi_o = wo.y.atan2(wo.x);
        let phi = phi_o + dphi;
        let side = if reflect { wo.z.signum() } else { -wo.z.signum() };
        Some(Vec3A::new(sin * phi.cos(), sin * phi.sin(), side * cos.max(1e-7)))
    }
}
