//! Maya's file texture filtering: `filterType`, `filter` and `filterOffset`.
//!
//! Maya's node reference: `filterType` is "the sampling technique applied to the image
//! file during rendering": Off (0, "no filtering … view a texture's pixels without
//! interpolation"), Mipmap (1, the averaged pyramid, "fast … textures may … appear
//! blurry"), Box (2, every sample of the footprint weighs the same), Quadratic (3, the
//! default), Quartic (4) and Gaussian (5): "bell curves, in which the extreme values get
//! less weight than values toward the center", Quadratic and Quartic approximating the
//! Gaussian. `filter` "scales the size of the filter" (eye space: the blur grows with the
//! distance), `filterOffset` "controls the texture blur in texture space (not eye space)";
//! mental ray for Maya honours both for every filter type.
//!
//! mira's reading, with the filter width w (texture units, a fraction of the image's
//! larger side)
//!
//! ```text
//! w = filter · s · footprint + filterOffset
//! ```
//!
//! where footprint is the ray's footprint at the point in texture units and s the `filter`
//! scale of the `.mi` texture (mental ray filters only textures declared with `filter`;
//! without it the eye-space part is 0, as before). The kernels, on the image pyramid
//! ([`shader::texture::MipMap::kernel_lookup`]):
//! - Off: the nearest texel of the full image; `filter` and `filterOffset` are not read;
//! - Mipmap: the trilinear pyramid lookup of footprint w (mira's default image lookup);
//! - Box: the mean over the square of side w about the point;
//! - Quadratic (1 − x²), Quartic (1 − x²)² and Gaussian exp(−4.5 x²) (σ a third of the radius) of
//!   x = d/w, d the distance of a texel from the point: radius w.
//!
//! A width under half a texel is a bilinear lookup (magnification) for every type but
//! Off. The bell shapes are mira's: the reference names them, it gives no formula.

use glam::{Vec2, Vec4};
use shader::texture::MipMap;

/// Maya's `filterType`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterType {
    /// 0: the nearest texel.
    Off,
    /// 1: the trilinear pyramid lookup.
    Mipmap,
    /// 2: a box (square) average.
    Box,
    /// 3 (Maya's default): the (1 − x²) bell.
    Quadratic,
    /// 4: the (1 − x²)² bell.
    Quartic,
    /// 5: the Gaussian bell.
    Gaussian,
}

impl FilterType {
    /// From Maya's enumeration; values outside it read as Quadratic (the default).
    pub fn from_maya(value: i32) -> FilterType {
        match value {
            0 => FilterType::Off,
            1 => FilterType::Mipmap,
            2 => FilterType::Box,
            4 => FilterType::Quartic,
            5 => FilterType::Gaussian,
            _ => FilterType::Quadratic,
        }
    }

    /// The image's value at `uv` ([0, 1)², v up) for a filter width `width` (texture
    /// units; see the module doc).
    pub fn lookup(self, image: &MipMap, uv: Vec2, width: f32) -> Vec4 {
        let width = width.max(0.0);
        match self {
            FilterType::Off => {
                let (w, h) = image.size();
                let x = ((uv.x * w as f32).floor() as i64).clamp(0, w as i64 - 1) as usize;
                let y = ((uv.y * h as f32).floor() as i64).clamp(0, h as i64 - 1) as usize;
                image.texel(x, y)
            }
            FilterType::Mipmap => image.lookup(uv.x, uv.y, width),
            FilterType::Box => image.kernel_lookup(uv.x, uv.y, 0.5 * width, true, &|_| 1.0),
            FilterType::Quadratic => image.kernel_lookup(uv.x, uv.y, width, false, &|x| 1.0 - x * x),
            FilterType::Quartic => image.kernel_lookup(uv.x, uv.y, width, false, &|x| (1.0 - x * x).powi(2)),
            FilterType::Gaussian => image.kernel_lookup(uv.x, uv.y, width, false, &|x| (-4.5 * x * x).exp()),
        }
    }
}

/// The ray's footprint at the point in texture units of the first texture space (the
/// footprint over the larger of the surface's UV derivatives), 0 where it is unknown.
pub fn ray_footprint(state: &shader::State) -> f32 {
    let scale = state.derivs[0].length().max(state.derivs[1].length());
    if scale > 0.0 && state.footprint > 0.0 {
        state.footprint / scale
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An n × n float image whose texel (x, y) (y up) is `f(x, y)`.
    fn image(n: usize, f: impl Fn(usize, usize) -> f32) -> MipMap {
        let top_down: Vec<[f32; 4]> = (0..n * n)
            .map(|i| {
                let v = f(i % n, n - 1 - i / n);
                [v, v, v, 1.0]
            })
            .collect();
        MipMap::from_rgba32f(n, n, &top_down, 4)
    }

    /// Off returns the texel the point lies in, whatever the width (1e-6); Mipmap at
    /// width 0 is bilinear (the mean of two texels half way between their centres).
    #[test]
    fn off_reads_the_nearest_texel_and_mipmap_interpolates() {
        let m = image(8, |x, y| (x + 8 * y) as f32 / 64.0);
        for (u, v) in [(0.01, 0.01), (0.49, 0.26), (0.99, 0.7), (0.5, 0.5)] {
            let (x, y) = ((u * 8.0) as usize, (v * 8.0) as usize);
            let want = (x + 8 * y) as f32 / 64.0;
            for width in [0.0, 0.1, 1.0] {
                let got = FilterType::Off.lookup(&m, Vec2::new(u, v), width).x;
                assert!((got - want).abs() < 1e-6, "({u}, {v}) width {width}: {got} vs {want}");
            }
        }
        let mid = FilterType::Mipmap.lookup(&m, Vec2::new(2.0 / 8.0, 0.5 / 8.0), 0.0).x;
        assert!((mid - 1.5 / 64.0).abs() < 1e-6, "{mid}");
    }

    /// A checker of 4-texel squares: the contrast between the centres of a white and a
    /// black square starts at 1 (1e-6) and falls as the width grows (never rising by more
    /// than 1e-4) for every type but Off, over the useful range of blur — until it drops
    /// under 0.1, past which a kernel as wide as the checker's period rings (every
    /// compactly supported kernel does) — and it gets under 0.3 by width 0.25 (8 texels).
    #[test]
    fn wider_filters_lose_contrast_monotonically() {
        let n = 32;
        let m = image(n, |x, y| ((x / 4 + y / 4) % 2) as f32);
        let (white, black) = (Vec2::new(6.0 / 32.0, 2.0 / 32.0), Vec2::new(2.0 / 32.0, 2.0 / 32.0));
        for kind in
            [FilterType::Mipmap, FilterType::Box, FilterType::Quadratic, FilterType::Quartic, FilterType::Gaussian]
        {
            let contrast = |w: f32| kind.lookup(&m, white, w).x - kind.lookup(&m, black, w).x;
            assert!((contrast(0.0) - 1.0).abs() < 1e-6, "{kind:?}");
            let mut last = contrast(0.0);
            for i in 1..=25 {
                if last < 0.1 {
                    break;
                }
                let c = contrast(0.01 * i as f32);
                assert!(c <= last + 1e-4, "{kind:?}: width {}: {c} after {last}", 0.01 * i as f32);
                last = c;
            }
            assert!(last < 0.3, "{kind:?}: {last}");
        }
    }
}
