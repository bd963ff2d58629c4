//! Maya's bulge and cloth 2D textures: regular patterns over each UV tile, read through
//! the shared 2D texture parameters and colour balance (`crate::texture`).
//!
//! Maya's node reference describes what they show, not their formulas; the formulas here
//! are mira's readings of those descriptions, stated on each function.
//!
//! UV space: the texture's coordinate modulo 1 (u right, v up), as for every 2D texture.

use glam::{Vec2, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::noise::gradient_noise;
use crate::texture::{balance, outside, texture_uv};
use crate::values::rgb;

/// The shared 2D texture parameters (`crate::texture`), then the texture's own.
macro_rules! params2d {
    ($($extra:literal),*) => {
        &["uvCoord", "invert", "alphaIsLuminance", "colorGain", "colorOffset", "alphaGain",
          "alphaOffset", "defaultColor", $($extra),*]
    };
}
pub(crate) use params2d;

/// The index of a 2D texture's first own parameter.
pub(crate) const EXTRA: usize = 8;

/// Bulge's profile across one direction of the tile: 0 on the frame — within `width`/2
/// of the tile's edges (Maya: "U Width and V Width … control the width of the window
/// frame") — and rising as sin(π·(d − w/2)/(1 − w)) to 1 at the tile's middle, d the
/// distance from the nearer edge. A width of 1 or more is all frame.
pub fn bulge_profile(x: f32, width: f32) -> f32 {
    let w = width.clamp(0.0, 1.0);
    let d = x.min(1.0 - x);
    if w >= 1.0 || d <= 0.5 * w {
        return 0.0;
    }
    (std::f32::consts::PI * (d - 0.5 * w) / (1.0 - w)).sin().clamp(0.0, 1.0)
}

/// Bulge's value at `uv` (in the unit tile): the product of the u and v profiles, so
/// "flat along the outer edges, and bulging in the middle" (Maya's node reference).
pub fn bulge_value(uv: Vec2, u_width: f32, v_width: f32) -> f32 {
    bulge_profile(uv.x, u_width) * bulge_profile(uv.y, v_width)
}

maya_shader!(
    /// Maya's bulge: grey [`bulge_value`] with the same alpha, through the colour
    /// balance. Parameters: `uWidth`, `vWidth` (0.1 each).
    BULGE,
    ADSK_BULGE,
    "maya_bulge",
    "adskMayaBulge",
    params2d!("uWidth", "vWidth"),
    bulge
);

fn bulge(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let v = bulge_value(uv, ctx.scalar(n, EXTRA), ctx.scalar(n, EXTRA + 1));
    balance(ctx, n, Vec3A::splat(v), v, out)
}

/// The settings of a cloth texture (Maya's cloth attributes; defaults in brackets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cloth {
    /// `gapColor` (black): between the threads.
    pub gap: Vec3A,
    /// `uColor` (white): the threads that run along u (the warp).
    pub u_color: Vec3A,
    /// `vColor` (0.5 grey): the threads that run along v (the weft).
    pub v_color: Vec3A,
    /// `uWidth`, `vWidth` (0.75): thread widths as a share of the spacing between
    /// neighbouring threads (1: they touch; 0: they vanish).
    pub width: [f32; 2],
    /// `uWave`, `vWave` (0): how far each thread's centre line swings to either side, as
    /// a share of the spacing, over one period per tile.
    pub wave: [f32; 2],
    /// `randomness` (0): how far the lookup is smeared in u and v.
    pub randomness: f32,
    /// `widthSpread` (0): a random amount in [0, spread] taken off each thread's width
    /// along its length.
    pub width_spread: f32,
    /// `brightSpread` (0): a random share in [0, spread] taken off each thread's colour
    /// along its length.
    pub bright_spread: f32,
}

/// A random number in [0, 1] that varies smoothly along a thread: gradient noise over
/// the position `along` it (8 features per tile), a different stream per thread `index`
/// and `salt`.
fn along_thread(along: f32, index: i32, salt: f32) -> f32 {
    (0.5 + 0.5 * gradient_noise(Vec3A::new(8.0 * along, index as f32 + 0.5, salt))).clamp(0.0, 1.0)
}

/// One family of threads at the coordinate across them (`across`) and along them
/// (`along`): the index of the nearest thread and how much of it covers the point (a
/// round thread's height, √(1 − (d/w)²), d the distance from its centre line in half
/// spacings, w its width; 0 off it), and its colour.
fn thread(c: &Cloth, axis: usize, across: f32, along: f32) -> (i32, f32, Vec3A) {
    // Two threads per tile, centre lines at 1/4 and 3/4, swinging by the wave.
    let offset = 0.5 * c.wave[axis] * (std::f32::consts::TAU * along).sin();
    let s = 2.0 * (across - offset) - 0.5;
    let k = s.round();
    let d = 2.0 * (s - k).abs();
    let index = (k as i32).rem_euclid(2);
    let salt = axis as f32 * 7.31;
    let width = (c.width[axis] - c.width_spread * along_thread(along, index, salt + 1.7)).max(0.0);
    let cover = if width > 0.0 && d < width { (1.0 - (d / width).powi(2)).max(0.0).sqrt() } else { 0.0 };
    let base = if axis == 0 { c.u_color } else { c.v_color };
    let colour = base * (1.0 - c.bright_spread * along_thread(along, index, salt + 3.9));
    (index, cover, colour)
}

impl Cloth {
    /// The colour and alpha at `uv` in the unit tile. Two threads run each way per tile
    /// (centre lines at ¼ and ¾), woven plainly: at the crossing of u-thread i and
    /// v-thread j the u thread lies on top when i + j is even. A thread blends into what
    /// lies under it — the gap colour, or the thread below — by its cover (Maya: "the
    /// colors blend into the Gap Color at their edges"); alpha is the larger cover.
    /// `randomness` smears the lookup by up to 0.1 × randomness of a tile in u and v.
    pub fn at(&self, uv: Vec2) -> (Vec3A, f32) {
        let uv = if self.randomness > 0.0 {
            let q = Vec3A::new(16.0 * uv.x, 16.0 * uv.y, 0.37);
            let smear = Vec2::new(gradient_noise(q), gradient_noise(q + Vec3A::new(5.2, 1.3, 2.9)));
            uv + 0.1 * self.randomness * smear
        } else {
            uv
        };
        // u threads run along u: across them is v.
        let (iu, cu, colour_u) = thread(self, 0, uv.y, uv.x);
        let (iv, cv, colour_v) = thread(self, 1, uv.x, uv.y);
        let over = |under: Vec3A, colour: Vec3A, cover: f32| under + (colour - under) * cover;
        let colour = if (iu + iv) % 2 == 0 {
            over(over(self.gap, colour_v, cv), colour_u, cu)
        } else {
            over(over(self.gap, colour_u, cu), colour_v, cv)
        };
        (colour, cu.max(cv))
    }
}

maya_shader!(
    /// Maya's cloth ([`Cloth::at`]) through the colour balance. Parameters: `gapColor`,
    /// `uColor`, `vColor`, `uWidth`, `vWidth`, `uWave`, `vWave`, `randomness`,
    /// `widthSpread`, `brightSpread`.
    CLOTH,
    ADSK_CLOTH,
    "maya_cloth",
    "adskMayaCloth",
    params2d!(
        "gapColor",
        "uColor",
        "vColor",
        "uWidth",
        "vWidth",
        "uWave",
        "vWave",
        "randomness",
        "widthSpread",
        "brightSpread"
    ),
    cloth
);

fn cloth(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let e = EXTRA;
    let c = Cloth {
        gap: rgb(ctx.color(n, e)),
        u_color: rgb(ctx.color(n, e + 1)),
        v_color: rgb(ctx.color(n, e + 2)),
        width: [ctx.scalar(n, e + 3), ctx.scalar(n, e + 4)],
        wave: [ctx.scalar(n, e + 5), ctx.scalar(n, e + 6)],
        randomness: ctx.scalar(n, e + 7).max(0.0),
        width_spread: ctx.scalar(n, e + 8).max(0.0),
        bright_spread: ctx.scalar(n, e + 9).max(0.0),
    };
    let (colour, alpha) = c.at(uv);
    balance(ctx, n, colour, alpha, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3A, b: Vec3A) {
        assert!((a - b).abs().max_element() < 1e-5, "{a} vs {b}");
    }

    #[test]
    fn bulge_is_flat_on_the_frame_and_peaks_mid_tile() {
        assert_eq!(bulge_value(Vec2::new(0.5, 0.5), 0.1, 0.1), 1.0);
        for uv in [Vec2::new(0.02, 0.5), Vec2::new(0.5, 0.97), Vec2::new(0.04, 0.04), Vec2::new(0.0, 0.3)] {
            assert_eq!(bulge_value(uv, 0.1, 0.1), 0.0, "{uv}");
        }
        // (0.3, 0.5) with a frame of 0.1: sin(π·0.25/0.9).
        let want = (std::f32::consts::PI * 0.25 / 0.9).sin();
        assert!((bulge_value(Vec2::new(0.3, 0.5), 0.1, 0.1) - want).abs() < 1e-6);
        // Symmetric about the middle, and all frame at width 1.
        assert!((bulge_value(Vec2::new(0.3, 0.2), 0.1, 0.2) - bulge_value(Vec2::new(0.7, 0.8), 0.1, 0.2)).abs() < 1e-6);
        assert_eq!(bulge_value(Vec2::new(0.5, 0.5), 1.0, 0.1), 0.0);
    }

    fn plain() -> Cloth {
        Cloth {
            gap: Vec3A::new(0.1, 0.0, 0.0),
            u_color: Vec3A::new(0.9, 0.8, 0.7),
            v_color: Vec3A::new(0.2, 0.3, 0.9),
            width: [0.75, 0.75],
            wave: [0.0, 0.0],
            randomness: 0.0,
            width_spread: 0.0,
            bright_spread: 0.0,
        }
    }

    #[test]
    fn cloth_threads_cross_over_and_under_with_the_gap_between() {
        let c = plain();
        // Crossings: u thread 0 over v thread 0, under v thread 1.
        let (col, a) = c.at(Vec2::new(0.25, 0.25));
        close(col, c.u_color);
        assert_eq!(a, 1.0);
        close(c.at(Vec2::new(0.75, 0.25)).0, c.v_color);
        close(c.at(Vec2::new(0.75, 0.75)).0, c.u_color);
        // Between the threads both ways: the gap, alpha 0.
        let (col, a) = c.at(Vec2::new(0.5, 0.5));
        close(col, c.gap);
        assert_eq!(a, 0.0);
        // On a v thread's centre line, between u threads.
        close(c.at(Vec2::new(0.25, 0.5)).0, c.v_color);
        // At 0.6 of a thread's half width from its centre: cover 0.8 over the gap.
        let d = 0.6 * 0.75 / 4.0; // half spacings → tile units (a half spacing is ¼).
        close(c.at(Vec2::new(0.5, 0.25 + d)).0, c.gap + (c.u_color - c.gap) * 0.8);
        // Width 0: no threads; width spread ≥ width: none either.
        close(Cloth { width: [0.0, 0.0], ..plain() }.at(Vec2::new(0.25, 0.25)).0, c.gap);
        close(Cloth { width_spread: 1.0, width: [0.0, 0.0], ..plain() }.at(Vec2::new(0.25, 0.75)).0, c.gap);
    }

    #[test]
    fn cloth_waves_move_the_threads_and_spreads_only_take_away() {
        // A u wave of 0.5 swings the u threads' centre by ¼ tile at u = ¼.
        let c = Cloth { wave: [0.5, 0.0], width: [0.75, 0.0], ..plain() };
        close(c.at(Vec2::new(0.25, 0.5)).0, c.u_color);
        close(plain().at(Vec2::new(0.5, 0.5)).0, plain().gap);
        // Spreads take colour and width away, never add.
        let s = Cloth { width_spread: 0.5, bright_spread: 0.5, ..plain() };
        for i in 0..50 {
            let uv = Vec2::new(i as f32 * 0.0197, 0.25);
            let (col, _) = s.at(uv);
            assert!(col.cmple(s.u_color.max(s.v_color) + 1e-6).all(), "{uv}: {col}");
            assert!(s.at(uv).1 <= plain().at(uv).1 + 1e-6);
        }
        // Randomness moves the pattern but keeps it between its colours.
        let r = Cloth { randomness: 1.0, ..plain() };
        let moved = (0..50).any(|i| {
            let uv = Vec2::new(0.013 * i as f32, 0.3);
            (r.at(uv).0 - plain().at(uv).0).length() > 1e-3
        });
        assert!(moved);
    }
}
