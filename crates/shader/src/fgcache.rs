//! The final gather interpolation cache (mental ray's final gather points; Ward and
//! Heckbert's irradiance cache).
//!
//! A final gather point is the irradiance gathered at one surface point with many rays,
//! with the harmonic mean distance of what those rays hit. That distance says how fast the
//! irradiance may change around the point, so it sets the point's validity radius
//! R = [`RADIUS_PER_DISTANCE`] × harmonic mean distance, clamped to the options' minimum
//! and maximum radius (`finalgather accuracy … max min`). A lookup at position x with
//! normal n uses the points i with
//!
//! e_i = |x − x_i| / R_i + √(1 − n·n_i) / √(1 − cos [`MAX_NORMAL_ANGLE`]) < 1
//!
//! that do not lie in front of x (Ward's test), weighted by w_i = 1 − e_i, which falls to
//! zero at the edge of validity so that the interpolated irradiance Σ w_i E_i / Σ w_i is
//! continuous. In [`FgMode::Strict`] every valid point contributes; in the automatic modes
//! the `finalgather points` nearest valid ones do.
//!
//! The renderer fills the cache in a pre-pass over the image (`render::fgcache`) and then
//! only reads it; where no point is valid, [`super::Ctx::compute_irradiance`] gathers by
//! brute force. Points are indexed by a multi-level hashed grid: a point goes into the
//! level whose cell size is the smallest power-of-two multiple of the smallest radius at
//! least as large as its own radius, into each of the (at most 8) cells its sphere of
//! validity overlaps; a lookup reads one cell per level.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use glam::Vec3A;

use super::value::Color;

/// Validity radius per unit of harmonic mean distance to the gather rays' hits (Ward's
/// accuracy `a`).
pub const RADIUS_PER_DISTANCE: f32 = 0.15;

/// Largest angle (radians) between a lookup's normal and a point's for the point to be
/// valid at all.
pub const MAX_NORMAL_ANGLE: f32 = 0.35;

/// Largest change of a point's irradiance, relative to itself, that its gradient may
/// make across its radius.
pub const MAX_GRADIENT_CHANGE: f32 = 0.5;

/// Total weight of valid points at which the pre-pass counts a position as covered (so
/// that most lookups blend more than one point).
pub const COVERED_WEIGHT: f32 = 0.6;

/// How final gather points' validity radii are chosen (`finalgather mode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FgMode {
    /// mental ray 3.4's semantics (`strict 3.4`, `compatible`, `3.4`): the radii of
    /// `finalgather accuracy` (world units, or pixels with `view`), by default 10 % and 1 %
    /// of the scene's extent; every valid point contributes.
    #[default]
    Strict,
    /// `automatic`: radii from the scene's extent (at most 10 %, at least 0.1 %), whatever
    /// `finalgather accuracy` says; the `finalgather points` nearest valid points are
    /// interpolated.
    Automatic,
    /// `multiframe`: as automatic (mira keeps no final gather map across frames).
    Multiframe,
}

impl FgMode {
    /// The mode a `finalgather mode` word names (`strict`, `strict 3.4`, `3.4`,
    /// `compatible`, `automatic`, `multiframe`; `force` is taken as strict).
    pub fn from_word(w: &str) -> Option<FgMode> {
        let w = w.trim().to_ascii_lowercase();
        match w.split_whitespace().next()? {
            "strict" | "compatible" | "3.4" | "3.5" | "force" => Some(FgMode::Strict),
            "automatic" | "auto" => Some(FgMode::Automatic),
            "multiframe" => Some(FgMode::Multiframe),
            _ => None,
        }
    }
}

/// The interpolation cache's settings, from the options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CacheSettings {
    /// Gather rays per final gather point (`finalgather accuracy`'s ray count).
    pub point_rays: u32,
    /// (maximum, minimum) radius of `finalgather accuracy`, if it gave one: world units, or
    /// pixels when `view` is set.
    pub radius: Option<(f32, f32)>,
    /// The radii are in pixels (`finalgather accuracy view …`).
    pub view: bool,
    /// Points interpolated in the automatic modes (`finalgather points`).
    pub points: u32,
    /// Radius semantics.
    pub mode: FgMode,
    /// `finalgather presample density`: pre-pass eye rays per pixel area, relative to one
    /// per 2×2 pixels.
    pub density: f32,
}

/// Validity radii resolved for a scene: world units, or pixels with `view`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Radii {
    /// Largest radius.
    pub max: f32,
    /// Smallest radius.
    pub min: f32,
    /// In pixels (convert at each point with its pixel footprint).
    pub view: bool,
}

impl CacheSettings {
    /// The settings of the scene's final gather options; `None` when they ask for brute
    /// force (`finalgather points 0`). An unknown `finalgather mode` is taken as strict.
    pub fn of_options(fg: &scene::options::FinalGather) -> Option<CacheSettings> {
        (fg.points > 0).then(|| CacheSettings {
            point_rays: fg.rays.clamp(1, 1 << 14),
            radius: fg.radius.map(|(max, min)| (max as f32, min as f32)),
            view: fg.view,
            points: fg.points,
            mode: FgMode::from_word(&fg.mode).unwrap_or_default(),
            density: (fg.presample_density as f32).clamp(0.01, 16.0),
        })
    }

    /// The radii for a scene whose bounding box diagonal is `extent` (world units).
    pub fn radii(&self, extent: f32) -> Radii {
        let extent = if extent.is_finite() && extent > 0.0 { extent } else { 1.0 };
        match (self.mode, self.radius) {
            (FgMode::Strict, Some((max, min))) if max > 0.0 => {
                Radii { max, min: if min > 0.0 { min.min(max) } else { 0.1 * max }, view: self.view }
            }
            (FgMode::Strict, _) => Radii { max: 0.1 * extent, min: 0.01 * extent, view: false },
            // The automatic modes let the gathered distances set the radii: the minimum
            // only keeps them off zero.
            _ => Radii { max: 0.1 * extent, min: 0.001 * extent, view: false },
        }
    }

    /// How many valid points a lookup blends (`None`: all of them).
    pub fn nearest(&self) -> Option<usize> {
        match self.mode {
            FgMode::Strict => None,
            FgMode::Automatic | FgMode::Multiframe => Some(self.points.max(1) as usize),
        }
    }
}

/// One final gather point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FgPoint {
    /// Where it was gathered (world space).
    pub position: Vec3A,
    /// The shading normal there (unit, world space).
    pub normal: Vec3A,
    /// The gathered irradiance (before `finalgather scale`).
    pub irradiance: Color,
    /// Validity radius (world units).
    pub radius: f32,
    /// Translational gradient of each of the irradiance's red, green and blue (per world
    /// unit, in the point's tangent plane), estimated from its neighbours when the cache is
    /// built; zero where they do not determine it.
    pub gradient: [Vec3A; 3],
}

impl FgPoint {
    /// A point gathered at `position` with `normal`, irradiance `irradiance` and harmonic
    /// mean hit distance `mean_dist` (infinite when every ray escaped), its radius clamped
    /// to `[min, max]` (world units).
    pub fn new(position: Vec3A, normal: Vec3A, irradiance: Color, mean_dist: f32, min: f32, max: f32) -> FgPoint {
        let r = RADIUS_PER_DISTANCE * mean_dist;
        let radius = if r.is_nan() { max } else { r.clamp(min.min(max), max) };
        FgPoint { position, normal, irradiance, radius: radius.max(f32::MIN_POSITIVE), gradient: [Vec3A::ZERO; 3] }
    }

    /// The point's irradiance carried to `p` along its gradient (never below zero).
    fn extrapolate(&self, p: Vec3A) -> Color {
        let d = p - self.position;
        let e = self.irradiance;
        let g = |k: usize, v: f32| (v + self.gradient[k].dot(d)).max(0.0);
        Color::new(g(0, e.x), g(1, e.y), g(2, e.z), e.w)
    }

    /// Ward's error of using this point at `p` with normal `n` (valid below 1), or `None`
    /// when the point lies in front of `p` or its normal is too far off.
    fn error(&self, p: Vec3A, n: Vec3A) -> Option<f32> {
        let d = p - self.position;
        let cos = n.dot(self.normal);
        let normal_term = (1.0 - cos).max(0.0).sqrt() / (1.0 - MAX_NORMAL_ANGLE.cos()).sqrt();
        if cos <= 0.0 || normal_term >= 1.0 {
            return None;
        }
        // In front: p lies behind the point's surface (a concave corner between them).
        if d.dot(n + self.normal) < -0.05 * self.radius {
            return None;
        }
        let e = d.length() / self.radius + normal_term;
        (e < 1.0).then_some(e)
    }
}

/// Hashes a grid cell's key (its three cell coordinates) with a multiply per word: the
/// std `HashMap`'s SipHash, made to resist crafted keys, cost as much as the rest of a
/// lookup. Which points a cell holds, and their order, do not depend on the hash.
#[derive(Default)]
struct CellHasher(u64);

impl CellHasher {
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        // Fold the high bits, where the multiplies mix, into the low ones the table uses.
        (self.0 ^ (self.0 >> 32)).wrapping_mul(0x9e37_79b9_7f4a_7c15)
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(word));
        }
    }

    fn write_usize(&mut self, n: usize) {
        self.add(n as u64);
    }
}

/// One level of the grid: cell size and the points overlapping each cell.
#[derive(Debug, Default)]
struct Level {
    cell: f32,
    cells: HashMap<[i32; 3], Vec<u32>, BuildHasherDefault<CellHasher>>,
}

impl Level {
    fn key(&self, p: Vec3A) -> [i32; 3] {
        let c = (p / self.cell).floor();
        [c.x as i32, c.y as i32, c.z as i32]
    }
}

/// Final gather points with a spatial index, read by many threads.
#[derive(Debug, Default)]
pub struct FgCache {
    points: Vec<FgPoint>,
    levels: Vec<Level>,
    nearest: Option<usize>,
}

/// Most grid levels (radii spanning a factor 2^30).
const MAX_LEVELS: usize = 31;

impl FgCache {
    /// Indexes `points`; lookups blend all valid points, or the `nearest` nearest of them.
    pub fn new(points: Vec<FgPoint>, nearest: Option<usize>) -> FgCache {
        let finite = |p: &&FgPoint| p.radius.is_finite() && p.position.is_finite();
        // Levels double in cell size from the smallest radius; radii spanning more than the
        // levels can hold start the levels higher (the smallest points then share cells), so
        // that no point covers more than 3 cells a side (a radius 2^100 times another's
        // covered 2^32 cells a side of the finest level: a hang, then an abort).
        let largest = points.iter().filter(finite).map(|p| p.radius).fold(0.0, f32::max);
        let smallest = points.iter().filter(finite).map(|p| p.radius).fold(f32::INFINITY, f32::min);
        let smallest = smallest.max(largest / (1u64 << (MAX_LEVELS - 1)) as f32);
        let mut levels: Vec<Level> = Vec::new();
        if smallest.is_finite() {
            for (i, p) in points.iter().enumerate() {
                if !finite(&p) {
                    continue;
                }
                let k = ((p.radius / smallest).log2().ceil().max(0.0) as usize).min(MAX_LEVELS - 1);
                while levels.len() <= k {
                    let cell = smallest * (1u64 << levels.len()) as f32;
                    levels.push(Level { cell, cells: HashMap::default() });
                }
                let level = &mut levels[k];
                let lo = level.key(p.position - Vec3A::splat(p.radius));
                let hi = level.key(p.position + Vec3A::splat(p.radius));
                for x in lo[0]..=hi[0] {
                    for y in lo[1]..=hi[1] {
                        for z in lo[2]..=hi[2] {
                            level.cells.entry([x, y, z]).or_default().push(i as u32);
                        }
                    }
                }
            }
        }
        let mut cache = FgCache { points, levels, nearest };
        cache.estimate_gradients();
        cache
    }

    /// Estimates each point's translational gradient by weighted least squares over the
    /// points valid at its position (differences of irradiance against offsets in its
    /// tangent plane), limited so that the irradiance changes by at most
    /// [`MAX_GRADIENT_CHANGE`] of itself across the point's radius.
    fn estimate_gradients(&mut self) {
        let gradients: Vec<[Vec3A; 3]> = (0..self.points.len())
            .map(|i| {
                let p = self.points[i];
                let (t, b) = p.normal.any_orthonormal_pair();
                // Normal equations of the 2D fit: A g = r per channel.
                let (mut a00, mut a01, mut a11) = (0.0f32, 0.0f32, 0.0f32);
                let mut r = [[0.0f32; 2]; 3];
                let mut count = 0;
                self.valid(p.position, p.normal, |j, e| {
                    if j as usize == i {
                        return;
                    }
                    let q = &self.points[j as usize];
                    let d = q.position - p.position;
                    let (u, v) = (d.dot(t), d.dot(b));
                    let w = 1.0 - e;
                    a00 += w * u * u;
                    a01 += w * u * v;
                    a11 += w * v * v;
                    let de = q.irradiance - p.irradiance;
                    for (k, rk) in r.iter_mut().enumerate() {
                        rk[0] += w * u * de[k];
                        rk[1] += w * v * de[k];
                    }
                    count += 1;
                });
                let det = a00 * a11 - a01 * a01;
                let scale = (a00 + a11).max(f32::MIN_POSITIVE);
                if count < 2 || det <= 1e-4 * scale * scale {
                    return [Vec3A::ZERO; 3];
                }
                [0, 1, 2].map(|k| {
                    let gu = (a11 * r[k][0] - a01 * r[k][1]) / det;
                    let gv = (a00 * r[k][1] - a01 * r[k][0]) / det;
                    let g = t * gu + b * gv;
                    let limit = MAX_GRADIENT_CHANGE * p.irradiance[k].abs() / p.radius;
                    if g.length() > limit {
                        g.normalize_or_zero() * limit
                    } else {
                        g
                    }
                })
            })
            .collect();
        for (p, g) in self.points.iter_mut().zip(gradients) {
            p.gradient = g;
        }
    }

    /// The points, in the order they were given.
    pub fn points(&self) -> &[FgPoint] {
        &self.points
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Calls `f` with (index, Ward's error) for each point valid at `p` with normal `n`.
    fn valid(&self, p: Vec3A, n: Vec3A, mut f: impl FnMut(u32, f32)) {
        if !p.is_finite() {
            return;
        }
        for level in &self.levels {
            let Some(list) = level.cells.get(&level.key(p)) else { continue };
            for &i in list {
                if let Some(e) = self.points[i as usize].error(p, n) {
                    f(i, e);
                }
            }
        }
    }

    /// Sum of the weights of the points valid at `p` with normal `n`.
    pub fn weight(&self, p: Vec3A, n: Vec3A) -> f32 {
        let mut sum = 0.0;
        self.valid(p, n, |_, e| sum += 1.0 - e);
        sum
    }

    /// Whether the pre-pass needs no new point at `p` with normal `n`: the valid points'
    /// weights add up to [`COVERED_WEIGHT`].
    pub fn covers(&self, p: Vec3A, n: Vec3A) -> bool {
        self.weight(p, n) >= COVERED_WEIGHT
    }

    /// The irradiance interpolated at `p` (world space) with unit normal `n`, or `None`
    /// when no point is valid there.
    pub fn lookup(&self, p: Vec3A, n: Vec3A) -> Option<Color> {
        let mut sum = Color::ZERO;
        let mut total = 0.0f32;
        match self.nearest {
            None => self.valid(p, n, |i, e| {
                let w = 1.0 - e;
                sum += self.points[i as usize].extrapolate(p) * w;
                total += w;
            }),
            Some(k) => {
                let mut found: Vec<(f32, u32, f32)> = Vec::new();
                self.valid(p, n, |i, e| found.push(((p - self.points[i as usize].position).length_squared(), i, e)));
                if found.len() > k {
                    found.select_nth_unstable_by(k - 1, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                    found.truncate(k);
                }
                for (_, i, e) in found {
                    let w = 1.0 - e;
                    sum += self.points[i as usize].extrapolate(p) * w;
                    total += w;
                }
            }
        }
        (total > 1e-6).then(|| sum / total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(x: f32, e: f32, radius: f32) -> FgPoint {
        FgPoint {
            position: Vec3A::new(x, 0.0, 0.0),
            normal: Vec3A::Z,
            irradiance: Color::splat(e),
            radius,
            gradient: [Vec3A::ZERO; 3],
        }
    }

    #[test]
    fn lookups_blend_valid_points_continuously_and_reject_bad_normals() {
        let cache = FgCache::new(vec![point(0.0, 1.0, 1.0), point(1.0, 3.0, 1.0), point(10.0, 5.0, 0.01)], None);
        // At a point: its own value. Halfway: the mean (equal weights).
        assert!((cache.lookup(Vec3A::ZERO, Vec3A::Z).unwrap().x - 1.0).abs() < 1e-6);
        assert!((cache.lookup(Vec3A::new(0.5, 0.0, 0.0), Vec3A::Z).unwrap().x - 2.0).abs() < 1e-6);
        // Monotone in between (no jumps): samples increase by at most 0.1 per 0.01 step.
        let mut last = 1.0;
        for k in 0..=100 {
            let v = cache.lookup(Vec3A::new(k as f32 * 0.01, 0.0, 0.0), Vec3A::Z).unwrap().x;
            assert!(v >= last - 1e-5 && v - last < 0.1, "step {k}: {last} → {v}");
            last = v;
        }
        // Out of every radius, or a normal turned by 45°: nothing valid.
        assert!(cache.lookup(Vec3A::new(5.0, 0.0, 0.0), Vec3A::Z).is_none());
        let tilted = Vec3A::new(1.0, 0.0, 1.0).normalize();
        assert!(cache.lookup(Vec3A::ZERO, tilted).is_none());
        // The small point far away is found through its own grid level.
        assert!((cache.lookup(Vec3A::new(10.005, 0.0, 0.0), Vec3A::Z).unwrap().x - 5.0).abs() < 1e-6);
    }

    /// Radii 10^60 apart (a point gathered into the void, clamped to a huge strict radius,
    /// beside one in a corner; or a crafted pre-pass file) index in a few cells each: this
    /// hung, covering 2^32 cells a side, before the levels were started higher. Both points
    /// are still found where they are valid.
    #[test]
    fn radii_far_apart_index_in_bounded_cells() {
        let cache = FgCache::new(vec![point(-1e30, 2.0, 1e30), point(5.0, 7.0, 1e-30)], None);
        let cells: usize = cache.levels.iter().map(|l| l.cells.values().map(Vec::len).sum::<usize>()).sum();
        assert!(cells <= 2 * 27, "{cells} cell entries");
        assert!((cache.lookup(Vec3A::new(5.0, 0.0, 0.0), Vec3A::Z).unwrap().x - 7.0).abs() < 1e-3);
        assert!((cache.lookup(Vec3A::new(-1e30, 0.0, 0.0), Vec3A::Z).unwrap().x - 2.0).abs() < 1e-3);
    }

    #[test]
    fn nearest_mode_uses_only_the_nearest_points() {
        let pts = vec![point(0.0, 1.0, 4.0), point(0.1, 1.0, 4.0), point(3.0, 100.0, 4.0)];
        let all = FgCache::new(pts.clone(), None).lookup(Vec3A::ZERO, Vec3A::Z).unwrap().x;
        let two = FgCache::new(pts, Some(2)).lookup(Vec3A::ZERO, Vec3A::Z).unwrap().x;
        assert!(all > 5.0, "all valid points: {all}");
        assert!((two - 1.0).abs() < 1e-6, "two nearest: {two}");
    }

    #[test]
    fn radius_follows_the_mean_distance_within_the_clamps() {
        let p = |d| FgPoint::new(Vec3A::ZERO, Vec3A::Z, Color::ZERO, d, 0.1, 2.0).radius;
        assert!((p(4.0) - RADIUS_PER_DISTANCE * 4.0).abs() < 1e-6);
        assert_eq!(p(f32::INFINITY), 2.0);
        assert_eq!(p(1e-3), 0.1);
        let s = CacheSettings {
            point_rays: 100,
            radius: Some((3.0, 0.0)),
            view: false,
            points: 30,
            mode: FgMode::Strict,
            density: 1.0,
        };
        assert_eq!(s.radii(50.0), Radii { max: 3.0, min: 0.3, view: false });
        let auto = CacheSettings { mode: FgMode::Automatic, ..s };
        assert_eq!(auto.radii(50.0), Radii { max: 5.0, min: 0.05, view: false });
        assert_eq!(FgMode::from_word("strict 3.4"), Some(FgMode::Strict));
        assert_eq!(FgMode::from_word("multiframe"), Some(FgMode::Multiframe));
        assert_eq!(FgMode::from_word("bogus"), None);
    }
}
