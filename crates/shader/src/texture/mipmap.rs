//! Image pyramids: an image and its successive half-size reductions, looked up with
//! bilinear interpolation within a level and linear interpolation between levels.
//!
//! Texture space: u to the right, v up, both in [0, 1) over the image (mental ray's
//! convention: v = 0 is the bottom row of the picture). Lookups wrap around at the edges,
//! so that textures repeated by coordinate remapping tile without seams.

use glam::{Vec2, Vec4};

/// Texels of one level, kept at the precision of the source.
#[derive(Clone, Debug)]
enum Texels {
    /// 8-bit sources (scaled to [0, 1] on lookup).
    U8(Vec<[u8; 4]>),
    /// 16-bit, float and HDR sources.
    F32(Vec<[f32; 4]>),
}

/// One level of the pyramid, rows stored bottom to top.
#[derive(Clone, Debug)]
struct Level {
    width: usize,
    height: usize,
    texels: Texels,
}

impl Level {
    #[inline]
    fn texel(&self, x: usize, y: usize) -> Vec4 {
        let i = y * self.width + x;
        match &self.texels {
            Texels::U8(t) => {
                let [r, g, b, a] = t[i];
                Vec4::new(f32::from(r), f32::from(g), f32::from(b), f32::from(a)) * (1.0 / 255.0)
            }
            Texels::F32(t) => Vec4::from_array(t[i]),
        }
    }

    /// Bilinear lookup at texture coordinates (u, v), wrapping.
    fn bilinear(&self, u: f32, v: f32) -> Vec4 {
        let (w, h) = (self.width as f32, self.height as f32);
        let x = u * w - 0.5;
        let y = v * h - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let wrap = |i: f32, n: usize| (i as i64).rem_euclid(n as i64) as usize;
        let (xa, xb) = (wrap(x0, self.width), wrap(x0 + 1.0, self.width));
        let (ya, yb) = (wrap(y0, self.height), wrap(y0 + 1.0, self.height));
        let top = self.texel(xa, ya) * (1.0 - fx) + self.texel(xb, ya) * fx;
        let bottom = self.texel(xa, yb) * (1.0 - fx) + self.texel(xb, yb) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// Gaussian-weighted mean of the texels around texture coordinates (u, v), wrapping:
    /// texel centres at offset d (this level's texels) weigh exp(−2 dᵀ Σ⁻¹ d) for
    /// dᵀ Σ⁻¹ d < 4, where Σ = [`sxx`, `sxy`; `sxy`, `syy`] (this level's texels²) holds the
    /// footprint ellipse's semi-axes as ±√eigenvalues. The Gaussian's standard deviation is
    /// half of each semi-axis; the cut at twice the semi-axis drops 0.03 % of its weight.
    fn gaussian(&self, u: f32, v: f32, [sxx, sxy, syy]: [f32; 3]) -> Vec4 {
        let det = sxx * syy - sxy * sxy;
        if !(det.is_finite() && det > 0.0) {
            return self.bilinear(u, v);
        }
        let (qxx, qxy, qyy) = (syy / det, -sxy / det, sxx / det);
        let cx = u * self.width as f32 - 0.5;
        let cy = v * self.height as f32 - 0.5;
        // Where dᵀ Σ⁻¹ d = 4 reaches furthest along x and y: 2 √Σxx and 2 √Σyy.
        let (ex, ey) = (2.0 * sxx.sqrt(), 2.0 * syy.sqrt());
        let wrap = |i: i64, n: usize| i.rem_euclid(n as i64) as usize;
        let mut sum = Vec4::ZERO;
        let mut total = 0.0;
        for y in (cy - ey).ceil() as i64..=(cy + ey).floor() as i64 {
            let dy = y as f32 - cy;
            let row = wrap(y, self.height);
            for x in (cx - ex).ceil() as i64..=(cx + ex).floor() as i64 {
                let dx = x as f32 - cx;
                let q = qxx * dx * dx + 2.0 * qxy * dx * dy + qyy * dy * dy;
                if q < 4.0 {
                    let w = (-2.0 * q).exp();
                    sum += self.texel(wrap(x, self.width), row) * w;
                    total += w;
                }
            }
        }
        if total > 0.0 {
            sum / total
        } else {
            self.bilinear(u, v)
        }
    }

    /// Mean of the texels around texture coordinates (u, v), wrapping, each weighted by
    /// `kernel(x)` where x is its centre's distance from the point in units of the radius
    /// (`rx`, `ry`: the radius in this level's texels along x and y): Euclidean, or the
    /// larger of the two axis distances when `square` (a square footprint). Texels at x ≥ 1
    /// are left out.
    fn kernel_mean(&self, u: f32, v: f32, (rx, ry): (f32, f32), square: bool, kernel: &dyn Fn(f32) -> f32) -> Vec4 {
        if self.width == 1 && self.height == 1 {
            // One texel: every kernel's mean is that texel, however wide the kernel (a
            // radius of millions of texels would otherwise loop over it millions of times).
            return self.texel(0, 0);
        }
        let cx = u * self.width as f32 - 0.5;
        let cy = v * self.height as f32 - 0.5;
        let wrap = |i: i64, n: usize| i.rem_euclid(n as i64) as usize;
        let mut sum = Vec4::ZERO;
        let mut total = 0.0;
        for y in (cy - ry).ceil() as i64..=(cy + ry).floor() as i64 {
            let dy = (y as f32 - cy) / ry;
            let row = wrap(y, self.height);
            for x in (cx - rx).ceil() as i64..=(cx + rx).floor() as i64 {
                let dx = (x as f32 - cx) / rx;
                let d = if square { dx.abs().max(dy.abs()) } else { (dx * dx + dy * dy).sqrt() };
                if d < 1.0 {
                    let w = kernel(d);
                    sum += self.texel(wrap(x, self.width), row) * w;
                    total += w;
                }
            }
        }
        if total > 0.0 {
            sum / total
        } else {
            self.bilinear(u, v)
        }
    }

    /// The next smaller level: 2×2 box filter (a 1-texel edge is kept when a side is odd
    /// or 1).
    fn reduce(&self) -> Level {
        let width = (self.width / 2).max(1);
        let height = (self.height / 2).max(1);
        let sx = if self.width > 1 { 2 } else { 1 };
        let sy = if self.height > 1 { 2 } else { 1 };
        let mut out = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let mut sum = Vec4::ZERO;
                for dy in 0..sy {
                    for dx in 0..sx {
                        sum += self.texel((x * sx + dx).min(self.width - 1), (y * sy + dy).min(self.height - 1));
                    }
                }
                out.push(sum / (sx * sy) as f32);
            }
        }
        let texels = match self.texels {
            Texels::U8(_) => Texels::U8(
                out.iter()
                    .map(|c| (*c * 255.0 + Vec4::splat(0.5)).to_array().map(|x| x.clamp(0.0, 255.0) as u8))
                    .collect(),
            ),
            Texels::F32(_) => Texels::F32(out.iter().map(|c| c.to_array()).collect()),
        };
        Level { width, height, texels }
    }
}

/// An image and its reductions.
#[derive(Clone, Debug)]
pub struct MipMap {
    levels: Vec<Level>,
    /// Components of the source (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA).
    pub channels: u8,
}

impl MipMap {
    /// From 8-bit RGBA texels, rows top to bottom (as image files store them).
    pub fn from_rgba8(width: usize, height: usize, top_down: &[[u8; 4]], channels: u8) -> MipMap {
        let texels = flip_rows(top_down, width, height);
        MipMap::build(Level { width, height, texels: Texels::U8(texels) }, channels)
    }

    /// From float RGBA texels, rows top to bottom.
    pub fn from_rgba32f(width: usize, height: usize, top_down: &[[f32; 4]], channels: u8) -> MipMap {
        let texels = flip_rows(top_down, width, height);
        MipMap::build(Level { width, height, texels: Texels::F32(texels) }, channels)
    }

    fn build(base: Level, channels: u8) -> MipMap {
        let mut levels = vec![base];
        while let Some(last) = levels.last() {
            if last.width == 1 && last.height == 1 {
                break;
            }
            let next = last.reduce();
            levels.push(next);
        }
        MipMap { levels, channels }
    }

    /// Width and height of the full-resolution image.
    pub fn size(&self) -> (usize, usize) {
        (self.levels[0].width, self.levels[0].height)
    }

    /// Number of levels.
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// Bytes held by all levels.
    pub fn memory_bytes(&self) -> usize {
        self.levels
            .iter()
            .map(|l| match &l.texels {
                Texels::U8(t) => t.len() * 4,
                Texels::F32(t) => t.len() * 16,
            })
            .sum()
    }

    /// The texel at integer position (x, y) of the full image, y up.
    pub fn texel(&self, x: usize, y: usize) -> Vec4 {
        self.levels[0].texel(x, y)
    }

    /// The filtered value at (u, v) for a footprint `width` (in texture-space units, 0:
    /// sharpest): bilinear within the two levels whose texel size brackets the footprint,
    /// linear between them.
    pub fn lookup(&self, u: f32, v: f32, width: f32) -> Vec4 {
        let (w, h) = self.size();
        let texels = width * w.max(h) as f32;
        let level = if texels > 1.0 { texels.log2() } else { 0.0 };
        let last = (self.levels.len() - 1) as f32;
        let level = level.min(last);
        let l0 = level.floor();
        let t = level - l0;
        let a = self.levels[l0 as usize].bilinear(u, v);
        if t == 0.0 {
            return a;
        }
        let b = self.levels[(l0 as usize + 1).min(self.levels.len() - 1)].bilinear(u, v);
        a * (1.0 - t) + b * t
    }
}

/// The footprint of an elliptical (EWA) lookup: a screen-space disc projected into texture
/// space, and mental ray's limits on it (`mib_texture_filter_lookup`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipse {
    /// Two conjugate semi-axes of the ellipse in texture-space units ([0, 1) over the image
    /// in u and v): the images of two perpendicular radii of the screen disc. The ellipse is
    /// { a·cos t + b·sin t }, whatever pair of perpendicular radii was projected.
    pub axes: [Vec2; 2],
    /// Largest ratio of major to minor axis; longer ellipses get a longer minor axis
    /// (≤ 1: [`DEFAULT_ECCMAX`]).
    pub eccmax: f32,
    /// Largest minor semi-axis in texels of the level filtered: the level is the one on
    /// which the minor semi-axis spans at most this many texels, linearly between the two
    /// nearest (≤ 0: [`DEFAULT_MAXMINOR`]).
    pub maxminor: f32,
    /// Footprints smaller than a texel (magnification): bilinear interpolation if set, else
    /// the nearest texel.
    pub bilinear: bool,
}

/// Eccentricity limit when the lookup gives none.
pub const DEFAULT_ECCMAX: f32 = 20.0;
/// Minor-axis limit (texels) when the lookup gives none.
pub const DEFAULT_MAXMINOR: f32 = 6.0;
/// The longest major semi-axis (texels of the level filtered) mira sums over; longer
/// ellipses are filtered on a coarser level (bounds the work of one lookup).
const MAX_MAJOR: f32 = 128.0;

/// Eigenvalues (larger first) of the symmetric 2×2 matrix [a, b; b, c].
fn eigenvalues(a: f32, b: f32, c: f32) -> (f32, f32) {
    let mean = 0.5 * (a + c);
    let d = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    (mean + d, (mean - d).max(0.0))
}

impl MipMap {
    /// The elliptically filtered value at (u, v) (Heckbert's EWA): the ellipse's semi-axes
    /// are found in texels, its eccentricity limited to `eccmax` (by lengthening the minor
    /// axis), the level chosen where the minor semi-axis spans `maxminor` texels, and there
    /// the texels are averaged with Gaussian weights over the ellipse (σ = half of each
    /// semi-axis; each semi-axis is made at least one texel of the level). Levels are
    /// blended linearly.
    pub fn ewa(&self, u: f32, v: f32, e: &Ellipse) -> Vec4 {
        let (w0, h0) = self.size();
        let scale = Vec2::new(w0 as f32, h0 as f32);
        let [a, b] = e.axes.map(|x| x * scale);
        let (sxx, sxy, syy) = (a.x * a.x + b.x * b.x, a.x * a.y + b.x * b.y, a.y * a.y + b.y * b.y);
        let (l1, l2) = eigenvalues(sxx, sxy, syy);
        let (major, mut minor) = (l1.sqrt(), l2.sqrt());
        if !major.is_finite() || major <= 1.0 {
            return if !major.is_finite() || e.bilinear {
                self.levels[0].bilinear(u, v)
            } else {
                let x = ((u * w0 as f32).floor() as i64).rem_euclid(w0 as i64) as usize;
                let y = ((v * h0 as f32).floor() as i64).rem_euclid(h0 as i64) as usize;
                self.levels[0].texel(x, y)
            };
        }
        // Direction of the major axis.
        let dir = if sxy.abs() > 1e-12 * (sxx + syy) {
            Vec2::new(l1 - syy, sxy).normalize()
        } else if sxx >= syy {
            Vec2::X
        } else {
            Vec2::Y
        };
        let eccmax = if e.eccmax > 1.0 { e.eccmax } else { DEFAULT_ECCMAX };
        let maxminor = if e.maxminor > 0.0 { e.maxminor } else { DEFAULT_MAXMINOR };
        minor = minor.max(major / eccmax);
        let level = (minor / maxminor).log2().max((major / MAX_MAJOR).log2()).max(0.0);
        let level = level.min((self.levels.len() - 1) as f32);
        let across = dir.perp();
        let at = |k: usize| {
            let l = &self.levels[k];
            let s = Vec2::new(l.width as f32 / w0 as f32, l.height as f32 / h0 as f32);
            let (p, q) = (dir * major * s, across * minor * s);
            let (mut xx, xy, mut yy) = (p.x * p.x + q.x * q.x, p.x * p.y + q.x * q.y, p.y * p.y + q.y * q.y);
            // At least a texel across: raise the smaller eigenvalue to 1.
            let small = eigenvalues(xx, xy, yy).1;
            if small < 1.0 {
                xx += 1.0 - small;
                yy += 1.0 - small;
            }
            l.gaussian(u, v, [xx, xy, yy])
        };
        let l0 = level.floor();
        let t = level - l0;
        let lo = at(l0 as usize);
        if t < 1e-4 {
            return lo;
        }
        lo * (1.0 - t) + at((l0 as usize + 1).min(self.levels.len() - 1)) * t
    }
}

/// Texels the radius of a [`MipMap::kernel_mean`] spans at most on the level it filters.
const KERNEL_TEXELS: f32 = 4.0;

impl MipMap {
    /// The value at (u, v) filtered by a radial `kernel` of `radius` (texture units, the
    /// same fraction of both sides): the mean of the texels within the radius, each
    /// weighted by `kernel(d / radius)` for its centre's distance d (Euclidean, or the
    /// larger axis distance when `square`: a box). Filtered on the level where the radius
    /// spans at most [`KERNEL_TEXELS`] texels, linearly between the two nearest; a radius
    /// under half a texel of the full image is a bilinear lookup of it.
    pub fn kernel_lookup(&self, u: f32, v: f32, radius: f32, square: bool, kernel: &dyn Fn(f32) -> f32) -> Vec4 {
        let (w0, h0) = self.size();
        let texels = radius * w0.max(h0) as f32;
        if !texels.is_finite() || texels < 0.5 {
            return self.levels[0].bilinear(u, v);
        }
        let level = (texels / KERNEL_TEXELS).log2().max(0.0).min((self.levels.len() - 1) as f32);
        let at = |k: usize| {
            let l = &self.levels[k];
            let r = (radius * l.width as f32, radius * l.height as f32);
            // At least half a texel: a coarse level's radius can shrink below its texels.
            l.kernel_mean(u, v, (r.0.max(0.5), r.1.max(0.5)), square, kernel)
        };
        let l0 = level.floor();
        let t = level - l0;
        let lo = at(l0 as usize);
        if t < 1e-4 {
            return lo;
        }
        lo * (1.0 - t) + at((l0 as usize + 1).min(self.levels.len() - 1)) * t
    }
}

fn flip_rows<T: Copy>(top_down: &[T], width: usize, height: usize) -> Vec<T> {
    let mut out = Vec::with_capacity(width * height);
    for row in (0..height).rev() {
        out.extend_from_slice(&top_down[row * width..(row + 1) * width]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker(n: usize) -> MipMap {
        let texels: Vec<[u8; 4]> =
            (0..n * n).map(|i| if (i % n + i / n) % 2 == 0 { [255, 255, 255, 255] } else { [0, 0, 0, 255] }).collect();
        MipMap::from_rgba8(n, n, &texels, 4)
    }

    #[test]
    fn texel_centres_return_texels_and_v_points_up() {
        // 2×2, top row red green, bottom row blue white.
        let t = [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]];
        let m = MipMap::from_rgba8(2, 2, &t, 4);
        assert_eq!(m.lookup(0.25, 0.25, 0.0), Vec4::new(0.0, 0.0, 1.0, 1.0));
        assert_eq!(m.lookup(0.75, 0.75, 0.0), Vec4::new(0.0, 1.0, 0.0, 1.0));
        // Half way between two texel centres: the mean.
        let mid = m.lookup(0.5, 0.25, 0.0);
        assert!((mid - Vec4::new(0.5, 0.5, 1.0, 1.0)).length() < 1e-6);
    }

    #[test]
    fn levels_preserve_the_mean_and_wide_footprints_average() {
        let m = checker(64);
        assert_eq!(m.level_count(), 7);
        let coarse = m.lookup(0.3, 0.7, 1.0);
        assert!((coarse.x - 0.5).abs() < 2.0 / 255.0, "{coarse}");
        // A footprint of one texel reads the full-resolution level.
        let sharp = m.lookup(0.5 / 64.0, 0.5 / 64.0, 1.0 / 64.0);
        assert_eq!(sharp, m.texel(0, 0));
        assert!(sharp.x == 0.0 || sharp.x == 1.0);
    }

    /// A float texture n×n whose texel (x, y) (y up) is `f(x, y)` in all colour channels.
    fn float_texture(n: usize, f: impl Fn(usize, usize) -> f32) -> MipMap {
        let top_down: Vec<[f32; 4]> = (0..n * n)
            .map(|i| {
                let v = f(i % n, n - 1 - i / n);
                [v, v, v, 1.0]
            })
            .collect();
        MipMap::from_rgba32f(n, n, &top_down, 4)
    }

    fn ellipse(a: (f32, f32), b: (f32, f32), n: usize) -> Ellipse {
        let s = 1.0 / n as f32;
        Ellipse { axes: [Vec2::new(a.0, a.1) * s, Vec2::new(b.0, b.1) * s], eccmax: 0.0, maxminor: 0.0, bilinear: true }
    }

    #[test]
    fn ewa_keeps_a_constant_texture_constant() {
        let m = float_texture(64, |_, _| 0.37);
        for (a, b) in [
            ((0.3, 0.0), (0.0, 0.2)),
            ((3.0, 0.0), (0.0, 2.0)),
            ((20.0, 20.0), (-0.5, 0.5)),
            ((500.0, 3.0), (1.0, 40.0)),
        ] {
            for (u, v) in [(0.5, 0.5), (0.01, 0.99), (0.999, 0.3)] {
                let c = m.ewa(u, v, &ellipse(a, b, 64));
                assert!((c.x - 0.37).abs() < 1e-5 && (c.w - 1.0).abs() < 1e-5, "{a:?} {b:?} at {u},{v}: {c}");
            }
        }
    }

    #[test]
    fn ewa_at_grazing_angles_is_sharp_across_and_averages_along() {
        // A grazing footprint: 1 texel across (u), 40 texels along (v).
        let n = 256;
        let e = ellipse((1.0, 0.0), (0.0, 40.0), n);
        let checker = float_texture(n, |x, y| ((x / 4 + y / 4) % 2) as f32);
        let u_stripes = float_texture(n, |x, _| ((x / 4) % 2) as f32);
        let v_stripes = float_texture(n, |_, y| ((y / 4) % 2) as f32);
        for k in [3usize, 10, 31] {
            let (u, v) = ((4 * k + 2) as f32 / n as f32, 0.37 + k as f32 * 0.01);
            let c = checker.ewa(u, v, &e).x;
            assert!((c - 0.5).abs() < 0.01, "checkerboard at column {k}: {c}");
            let along = v_stripes.ewa(u, v, &e).x;
            assert!((along - 0.5).abs() < 0.01, "stripes along the footprint average: {along}");
            // Across the footprint the stripes stay sharp...
            let across = u_stripes.ewa(u, v, &e).x;
            let expected = (k % 2) as f32;
            assert!((across - expected).abs() < 0.06, "stripe {k}: {across}");
            // ... where an isotropic lookup as wide as the footprint's long axis blurs them.
            let iso = u_stripes.lookup(u, v, 2.0 * 40.0 / n as f32).x;
            assert!((iso - 0.5).abs() < 0.1, "isotropic: {iso}");
        }
        // Limiting the eccentricity lengthens the minor axis: the stripes blur.
        let loose = u_stripes.ewa(10.0 / n as f32, 0.5, &Ellipse { eccmax: 4.0, ..e }).x;
        assert!((loose - 0.5).abs() < 0.25, "eccmax 4: {loose}");
    }

    #[test]
    fn ewa_of_an_axis_aligned_footprint_is_the_gaussian_mean() {
        // cos(2π k x / n) under a Gaussian of deviation σ: attenuated by exp(−2π²σ²k²/n²).
        let (n, k) = (256usize, 8.0f32);
        let f = |x: f32| 0.5 + 0.5 * (2.0 * std::f32::consts::PI * k * x / n as f32).cos();
        let m = float_texture(n, |x, _| f(x as f32 + 0.5));
        // Semi-axes 6 and 3 texels: σ = 3 along u (level 0, as maxminor allows 3 texels).
        let e = Ellipse { maxminor: 3.0, ..ellipse((6.0, 0.0), (0.0, 3.0), n) };
        let atten = (-2.0 * std::f32::consts::PI.powi(2) * 9.0 * k * k / (n * n) as f32).exp();
        for x in [0.0f32, 5.0, 8.5, 13.25, 100.0] {
            let u = x / n as f32;
            let expected = 0.5 + (f(x) - 0.5) * atten;
            let got = m.ewa(u, 0.5, &e).x;
            assert!((got - expected).abs() < 2e-3, "x {x}: {got} vs {expected}");
        }
        // Turned 90°, the same footprint along v reads the texture's constant direction:
        // σ = 1.5 along u.
        let e = Ellipse { maxminor: 3.0, ..ellipse((0.0, 6.0), (3.0, 0.0), n) };
        let atten = (-2.0 * std::f32::consts::PI.powi(2) * 2.25 * k * k / (n * n) as f32).exp();
        let got = m.ewa(5.0 / n as f32, 0.5, &e).x;
        assert!((got - (0.5 + (f(5.0) - 0.5) * atten)).abs() < 2e-3, "{got}");
    }

    #[test]
    fn odd_sizes_reduce_to_one_texel() {
        let texels = vec![[10u8, 20, 30, 255]; 5 * 3];
        let m = MipMap::from_rgba8(5, 3, &texels, 3);
        assert_eq!(m.level_count(), 3);
        let v = m.lookup(0.5, 0.5, 10.0);
        assert!((v.x - 10.0 / 255.0).abs() < 1e-3);
    }

    /// A constant texture stays constant under every kernel and radius (1e-5); a radius
    /// under half a texel is the bilinear lookup, bit for bit.
    #[test]
    fn kernel_lookups_keep_a_constant_and_small_radii_are_bilinear() {
        let m = float_texture(32, |_, _| 0.61);
        for radius in [0.001, 0.02, 0.1, 0.7] {
            for square in [false, true] {
                let c = m.kernel_lookup(0.3, 0.8, radius, square, &|x| 1.0 - x * x);
                assert!((c.x - 0.61).abs() < 1e-5, "{radius} {square}: {c}");
            }
        }
        let ramp = float_texture(32, |x, _| x as f32 / 31.0);
        assert_eq!(ramp.kernel_lookup(0.41, 0.5, 0.01, true, &|_| 1.0), ramp.lookup(0.41, 0.5, 0.0));
    }

    /// A radius far past the image (a hostile `filterOffset`) reads the 1×1 level once: the
    /// image's mean (1e-5), with no loop over millions of texels.
    #[test]
    fn huge_kernel_radii_read_the_image_mean() {
        let m = checker(8);
        for radius in [1e3, 1e9, 1e30] {
            let c = m.kernel_lookup(0.3, 0.8, radius, false, &|x| 1.0 - x * x);
            assert!((c.x - 0.5).abs() < 1e-2, "{radius}: {c}");
        }
    }
}
