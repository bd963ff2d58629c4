//! Image pyramids: an image and its successive half-size reductions, looked up with
//! bilinear interpolation within a level and linear interpolation between levels.
//!
//! Texture space: u to the right, v up, both in [0, 1) over the image (mental ray's
//! convention: v = 0 is the bottom row of the picture). Lookups wrap around at the edges,
//! so that textures repeated by coordinate remapping tile without seams.

use glam::Vec4;

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

    #[test]
    fn odd_sizes_reduce_to_one_texel() {
        let texels = vec![[10u8, 20, 30, 255]; 5 * 3];
        let m = MipMap::from_rgba8(5, 3, &texels, 3);
        assert_eq!(m.level_count(), 3);
        let v = m.lookup(0.5, 0.5, 10.0);
        assert!((v.x - 10.0 / 255.0).abs() < 1e-3);
    }
}
