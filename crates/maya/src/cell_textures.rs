//! Maya's leather and granite 3D textures: cells (spheres) suspended in a medium.
//!
//! Both share the 3D textures' placement, `wrap` and colour balance
//! ([`crate::texture3d`]). Maya's node reference documents their attributes' meanings,
//! ranges and defaults (granite is leather with three cell colours); the cell pattern
//! below is mira's reading of those descriptions, on mira's own lattice hash
//! ([`crate::noise::lattice`]), not Maya's pattern.
//!
//! The texture is laid out in cell units q = p / `cellSize` (p in placement space). Each
//! unit lattice cell k holds one sphere centred at k + ½ + `randomness` · (ξ − ½), ξ a
//! hashed point of the unit cube (randomness 0: a regular lattice, 1: anywhere in the
//! cell), of radius R = ½ · `density` (1: neighbours touch, fully packed). With d1 and d2
//! the distances to the nearest and second-nearest centres, a point's place in its cell
//! is f = d1 / R, and with `creases` on f = max(d1 / R, 2 d1 / (d1 + d2)) — the cells
//! meet in a crease where they are equally near (d1 = d2); off, they diffuse into each
//! other. The cell's share is w = clamp((1 − f) / (1 − `threshold`), 0, 1): all cell at
//! its centre, none at f = 1, the blend widest at threshold 0 and a hard dot at threshold
//! 1 ("no mixing, cells appear as solid colour dots"). Each cell's colour is scaled by
//! 1 − `spottyness` · η (η hashed in [0, 1): spottyness 0 gives every cell the same
//! intensity, 1 entirely random ones).
//!
//! - leather: `cellColor` (0.373 0.157 0.059), `creaseColor` (0.235 0.118 0), `cellSize`
//!   (0.5), `density` (1), `spottyness` (0.1), `randomness` (0.5), `threshold` (0.83),
//!   `creases` (on): `outColor` = creaseColor + w · (cell colour − creaseColor), `outAlpha`
//!   = w;
//! - granite: `color1` (black), `color2` (0.549 0.784 0.392), `color3` (0.627 0.824
//!   0.824), `fillerColor` (0.588 0.294 0.196), `cellSize` (0.15), `density` (1),
//!   `mixRatio` (0.5), `spottyness` (0.3), `randomness` (1), `threshold` (0.5), `creases`
//!   (on): each cell takes colour i = round(2 · mixRatio + 1.5 · (ζ − ½)) clamped to 0..2
//!   (ζ hashed in [0, 1)), so that mixRatio 0 makes color1 the most common (5/6 of the
//!   cells), 0.5 color2 (2/3) and 1 color3 (5/6), as Maya describes it; the medium is
//!   `fillerColor`.

use glam::Vec3A;
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::noise::lattice;
use crate::texture::{balance, outside};
use crate::texture3d::{placement_point, texture3d_params, EXTRA};
use crate::values::rgb;

/// Where a point lies among the cells (cell units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellPoint {
    /// The distance to the nearest cell's centre.
    pub d1: f32,
    /// The distance to the second-nearest cell's centre.
    pub d2: f32,
    /// The nearest cell's hash (its colour and intensity are drawn from it).
    pub id: u32,
}

/// A number in [0, 1) drawn from the hash `h` for purpose `n`.
pub fn unit(h: u32, n: i32) -> f32 {
    (lattice(h as i32, n, 0x2545_f491) >> 8) as f32 / (1u32 << 24) as f32
}

/// The nearest two cell centres to `q` (cell units) for `randomness` (clamped to 0..1;
/// see the module doc).
pub fn nearest_cells(q: Vec3A, randomness: f32) -> CellPoint {
    let r = if randomness.is_nan() { 0.0 } else { randomness.clamp(0.0, 1.0) };
    let mut best = CellPoint { d1: f32::INFINITY, d2: f32::INFINITY, id: 0 };
    if !q.is_finite() {
        return best;
    }
    let base = q.floor();
    let (i0, j0, k0) = (base.x as i32, base.y as i32, base.z as i32);
    for dz in -1..=1 {
        for dy in -1..=1 {
            for dx in -1..=1 {
                let (i, j, k) = (i0.wrapping_add(dx), j0.wrapping_add(dy), k0.wrapping_add(dz));
                let h = lattice(i, j, k);
                let xi = Vec3A::new(unit(h, 1), unit(h, 2), unit(h, 3));
                let centre =
                    Vec3A::new(i as f32, j as f32, k as f32) + Vec3A::splat(0.5) + r * (xi - Vec3A::splat(0.5));
                let d = (q - centre).length();
                if d < best.d1 {
                    best = CellPoint { d1: d, d2: best.d1, id: h };
                } else if d < best.d2 {
                    best.d2 = d;
                }
            }
        }
    }
    best
}

/// The cell's share w at `at` (see the module doc).
pub fn cell_share(at: CellPoint, density: f32, threshold: f32, creases: bool) -> f32 {
    let radius = 0.5 * density.max(0.0);
    if radius <= 0.0 || !at.d1.is_finite() {
        return 0.0;
    }
    let mut f = at.d1 / radius;
    if creases && at.d1 + at.d2 > 0.0 {
        f = f.max(2.0 * at.d1 / (at.d1 + at.d2));
    }
    let t = if threshold.is_nan() { 0.0 } else { threshold.clamp(0.0, 1.0) };
    let w = if t >= 1.0 {
        if f < 1.0 {
            1.0
        } else {
            0.0
        }
    } else {
        ((1.0 - f) / (1.0 - t)).clamp(0.0, 1.0)
    };
    if w.is_nan() {
        0.0
    } else {
        w
    }
}

/// The intensity of cell `id` for `spottyness`: 1 − spottyness · η, at least 0.
pub fn cell_intensity(id: u32, spottyness: f32) -> f32 {
    (1.0 - spottyness.max(0.0) * unit(id, 4)).max(0.0)
}

/// Which of granite's three colours (0, 1, 2) cell `id` takes for `mixRatio` (see the
/// module doc).
pub fn granite_colour(id: u32, mix_ratio: f32) -> usize {
    let m = if mix_ratio.is_nan() { 0.5 } else { mix_ratio.clamp(0.0, 1.0) };
    (2.0 * m + 1.5 * (unit(id, 5) - 0.5)).round().clamp(0.0, 2.0) as usize
}

maya_shader!(
    /// Maya's leather (see the module doc).
    LEATHER,
    ADSK_LEATHER,
    "maya_leather",
    "adskMayaLeather",
    texture3d_params!(
        "cellColor",
        "creaseColor",
        "cellSize",
        "density",
        "spottyness",
        "randomness",
        "threshold",
        "creases"
    ),
    leather
);

fn leather(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let (cell, crease) = (rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)));
    let s = |ctx: &mut Ctx, i: usize| ctx.scalar(n, EXTRA + i);
    let (size, density, spottyness, randomness, threshold) = (s(ctx, 2), s(ctx, 3), s(ctx, 4), s(ctx, 5), s(ctx, 6));
    let at = nearest_cells(p / size, randomness);
    let w = cell_share(at, density, threshold, ctx.bool(n, EXTRA + 7));
    let c = cell * cell_intensity(at.id, spottyness);
    balance(ctx, n, crease + (c - crease) * w, w, out)
}

maya_shader!(
    /// Maya's granite (see the module doc).
    GRANITE,
    ADSK_GRANITE,
    "maya_granite",
    "adskMayaGranite",
    texture3d_params!(
        "color1",
        "color2",
        "color3",
        "fillerColor",
        "cellSize",
        "density",
        "mixRatio",
        "spottyness",
        "randomness",
        "threshold",
        "creases"
    ),
    granite
);

fn granite(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let colours = [rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)), rgb(ctx.color(n, EXTRA + 2))];
    let filler = rgb(ctx.color(n, EXTRA + 3));
    let s = |ctx: &mut Ctx, i: usize| ctx.scalar(n, EXTRA + i);
    let (size, density, mix) = (s(ctx, 4), s(ctx, 5), s(ctx, 6));
    let (spottyness, randomness, threshold) = (s(ctx, 7), s(ctx, 8), s(ctx, 9));
    let at = nearest_cells(p / size, randomness);
    let w = cell_share(at, density, threshold, ctx.bool(n, EXTRA + 10));
    let c = colours[granite_colour(at.id, mix)] * cell_intensity(at.id, spottyness);
    balance(ctx, n, filler + (c - filler) * w, w, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_regular_lattice_has_its_centres_mid_cell_and_creases_halfway() {
        // Randomness 0: centres at k + ½.
        let at = nearest_cells(Vec3A::new(2.5, -0.5, 7.5), 0.0);
        assert!(at.d1 < 1e-6 && (at.d2 - 1.0).abs() < 1e-6, "{at:?}");
        assert_eq!(cell_share(at, 1.0, 0.83, true), 1.0);
        // Halfway between two centres: equally near both, the crease (no cell).
        let mid = nearest_cells(Vec3A::new(3.0, -0.5, 7.5), 0.0);
        assert!((mid.d1 - 0.5).abs() < 1e-6 && (mid.d2 - 0.5).abs() < 1e-6, "{mid:?}");
        assert_eq!(cell_share(mid, 1.0, 0.5, true), 0.0);
        // Without creases, packed cells (density 1) also end there (d1 = R).
        assert_eq!(cell_share(mid, 1.0, 0.5, false), 0.0);
        // A quarter of the way (d1 = ¼, d2 = ¾): f = max(½, ½) = ½; threshold 0 → ½.
        let q = nearest_cells(Vec3A::new(2.75, -0.5, 7.5), 0.0);
        assert!((cell_share(q, 1.0, 0.0, true) - 0.5).abs() < 1e-5);
        // Threshold 0.5: (1 − ½)/(1 − ½) = 1; threshold 1: a solid dot.
        assert!((cell_share(q, 1.0, 0.5, true) - 1.0).abs() < 1e-5);
        assert_eq!(cell_share(q, 1.0, 1.0, true), 1.0);
        // Density 0: no cells anywhere.
        assert_eq!(cell_share(at, 0.0, 0.5, true), 0.0);
    }

    #[test]
    fn random_cells_are_deterministic_and_their_shares_in_range() {
        let mut solid_values = std::collections::BTreeSet::new();
        for i in 0..3000 {
            let q = Vec3A::new(i as f32 * 0.173, (i % 29) as f32 * 0.31, (i % 13) as f32 * 0.57);
            let at = nearest_cells(q, 1.0);
            assert_eq!(at, nearest_cells(q, 1.0));
            assert!(at.d1 <= at.d2, "{at:?}");
            let w = cell_share(at, 1.0, 0.83, true);
            assert!((0.0..=1.0).contains(&w));
            // Threshold 1: every point is cell or medium, nothing between.
            solid_values.insert((cell_share(at, 1.0, 1.0, true) * 4.0) as i32);
            let k = cell_intensity(at.id, 0.3);
            assert!((0.7..=1.0).contains(&k), "{k}");
            assert_eq!(cell_intensity(at.id, 0.0), 1.0);
        }
        assert_eq!(solid_values.into_iter().collect::<Vec<_>>(), vec![0, 4]);
        // NaN and infinite points (a hostile placement) are medium, not NaN.
        assert_eq!(cell_share(nearest_cells(Vec3A::splat(f32::NAN), 1.0), 1.0, 0.5, true), 0.0);
    }

    #[test]
    fn granite_mix_ratio_picks_the_most_common_colour() {
        let share = |mix: f32| {
            let mut counts = [0usize; 3];
            for i in 0..6000u32 {
                counts[granite_colour(lattice(i as i32, 17, -3), mix)] += 1;
            }
            counts.map(|c| c as f32 / 6000.0)
        };
        let (a, b, c) = (share(0.0), share(0.5), share(1.0));
        assert!((a[0] - 5.0 / 6.0).abs() < 0.03 && a[2] == 0.0, "{a:?}");
        assert!((b[1] - 2.0 / 3.0).abs() < 0.03 && (b[0] - 1.0 / 6.0).abs() < 0.03, "{b:?}");
        assert!((c[2] - 5.0 / 6.0).abs() < 0.03 && c[0] == 0.0, "{c:?}");
    }
}
