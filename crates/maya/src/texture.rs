//! Maya's 2D textures and their placement: place2dTexture, file, checker, grid and
//! bump2d (the ramp is in [`crate::ramp_texture`]).
//!
//! Every 2D texture reads its coordinate from `uvCoord` — connected to a place2dTexture's
//! `outUV` — or, unconnected, from the first texture space of the surface (the `data`
//! UV set an export writes). The coordinate is taken modulo 1 (the texture tiles). A
//! place2dTexture that finds the point outside its frame (coverage without wrap) marks
//! `outUV` with z = −1 and the texture returns its `defaultColor` (0.5 grey).
//!
//! Colour balance, shared by all (Maya's texture2d attributes): the texture's colour is
//! inverted by `invert` (1 − c, 1 − α), its alpha replaced by its luminance by
//! `alphaIsLuminance`, then `outColor = c ⊙ colorGain + colorOffset` and
//! `outAlpha = α · alphaGain + alphaOffset`.
//!
//! UV space: u to the right, v up, as in Maya and in mental ray's image lookups.
//! `uvFilterSize` is not read; the file texture's `filterType`, `filter` and
//! `filterOffset` choose its image filter ([`crate::file_filter`]); procedural textures
//! are point-sampled.

use glam::{Vec2, Vec3A};
use shader::texture::Texture;
use shader::{Color, Ctx, NodeId, Tag, Value};

use crate::file_filter::{ray_footprint, FilterType};
use crate::maya_shader;
use crate::values::{luma, rgb, rgba, write_struct};

/// Parameters every 2D texture reads first, in this order.
macro_rules! texture_params {
    ($($extra:literal),*) => {
        &["uvCoord", "invert", "alphaIsLuminance", "colorGain", "colorOffset", "alphaGain",
          "alphaOffset", "defaultColor", $($extra),*]
    };
}
pub(crate) use texture_params;

/// The first parameter a texture adds to the shared ones.
pub(crate) const EXTRA: usize = 8;

/// The coordinate a 2D texture looks up, modulo 1; `None` outside its placement frame.
pub(crate) fn texture_uv(ctx: &mut Ctx, n: NodeId) -> Option<Vec2> {
    let uv = if ctx.is_connected(n, 0) {
        let v = ctx.vector(n, 0);
        if v.z < 0.0 {
            return None;
        }
        Vec2::new(v.x, v.y)
    } else {
        let t = ctx.state.tex(0);
        Vec2::new(t.x, t.y)
    };
    Some(uv - uv.floor())
}

/// Applies the colour balance to a texture colour `c` of alpha `a` and writes the
/// result (`outColor`, `outAlpha`, `outTransparency`).
pub(crate) fn balance(ctx: &mut Ctx, n: NodeId, c: Vec3A, a: f32, out: &mut Value) -> bool {
    let (mut c, mut a) = (c, a);
    if ctx.bool(n, 1) {
        c = Vec3A::ONE - c;
        a = 1.0 - a;
    }
    if ctx.bool(n, 2) {
        a = luma(c);
    }
    let c = c * rgb(ctx.color(n, 3)) + rgb(ctx.color(n, 4));
    let a = a * ctx.scalar(n, 5) + ctx.scalar(n, 6);
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(c, a))),
            ("outAlpha", Value::Scalar(a)),
            ("outTransparency", Value::Color(rgba(Vec3A::splat(1.0 - a), 1.0))),
        ],
    );
    true
}

/// The default colour, for points outside the placement frame.
pub(crate) fn outside(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let d = ctx.color(n, 7);
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(rgb(d), 1.0))),
            ("outAlpha", Value::Scalar(0.0)),
            ("outTransparency", Value::Color(Color::new(1.0, 1.0, 1.0, 1.0))),
        ],
    );
    true
}

/// The settings of a place2dTexture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// `coverageU`, `coverageV`: the part of the surface's UV square the frame covers.
    pub coverage: Vec2,
    /// `translateFrameU`, `translateFrameV`.
    pub translate_frame: Vec2,
    /// `rotateFrame`, radians, about the centre (0.5, 0.5).
    pub rotate_frame: f32,
    /// `mirrorU`, `mirrorV`: every other repeat mirrored.
    pub mirror: [bool; 2],
    /// `stagger`: every other row of repeats shifted by half a tile in u.
    pub stagger: bool,
    /// `wrapU`, `wrapV`: the frame repeats outside itself.
    pub wrap: [bool; 2],
    /// `repeatU`, `repeatV`.
    pub repeat: Vec2,
    /// `offsetU`, `offsetV`.
    pub offset: Vec2,
    /// `rotateUV`, radians: the texture turns counter-clockwise about the centre of the
    /// repeated space, i.e. the coordinate turns by −rotateUV.
    pub rotate_uv: f32,
}

impl Default for Placement {
    fn default() -> Self {
        Placement {
            coverage: Vec2::ONE,
            translate_frame: Vec2::ZERO,
            rotate_frame: 0.0,
            mirror: [false; 2],
            stagger: false,
            wrap: [true; 2],
            repeat: Vec2::ONE,
            offset: Vec2::ZERO,
            rotate_uv: 0.0,
        }
    }
}

/// Turns `p` by `angle` (radians, counter-clockwise) about (0.5, 0.5).
fn rotate_about_centre(p: Vec2, angle: f32) -> Vec2 {
    let (s, c) = angle.sin_cos();
    let d = p - Vec2::splat(0.5);
    Vec2::new(c * d.x - s * d.y, s * d.x + c * d.y) + Vec2::splat(0.5)
}

impl Placement {
    /// The texture coordinate of surface coordinate `uv`, or `None` outside the frame.
    /// In order: the frame is moved by `translateFrame` and turned by `rotateFrame`; the
    /// frame's coordinate is uv / coverage (outside [0,1) and not wrapping: `None`); then
    /// `× repeat + offset`, stagger, mirror, and the turn by `rotateUV`.
    pub fn apply(&self, uv: Vec2) -> Option<Vec2> {
        let p = rotate_about_centre(uv - self.translate_frame, -self.rotate_frame);
        let cov = self.coverage.max(Vec2::splat(1e-6));
        let f = p / cov;
        for i in 0..2 {
            if !self.wrap[i] && !(0.0..1.0).contains(&f[i]) {
                return None;
            }
        }
        let mut t = f * self.repeat + self.offset;
        if self.stagger && (t.y.floor() as i64).rem_euclid(2) == 1 {
            t.x += 0.5;
        }
        for i in 0..2 {
            if self.mirror[i] && (t[i].floor() as i64).rem_euclid(2) == 1 {
                t[i] = 2.0 * t[i].floor() + 1.0 - t[i];
            }
        }
        Some(rotate_about_centre(t, -self.rotate_uv))
    }
}

maya_shader!(
    /// Maya's place2dTexture ([`Placement`]): `outUV` is the placed coordinate (x, y;
    /// z = −1 outside the frame), `outUvFilterSize` zero. `uvCoord` unconnected reads the
    /// first texture space.
    PLACE2D,
    ADSK_PLACE2D,
    "maya_place2dtexture",
    "adskMayaPlace2dTexture",
    &[
        "uvCoord",
        "coverageU",
        "coverageV",
        "translateFrameU",
        "translateFrameV",
        "rotateFrame",
        "mirrorU",
        "mirrorV",
        "stagger",
        "wrapU",
        "wrapV",
        "repeatU",
        "repeatV",
        "offsetU",
        "offsetV",
        "rotateUV"
    ],
    place2d
);

fn place2d(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let uv = if ctx.is_connected(n, 0) { ctx.vector(n, 0) } else { ctx.state.tex(0) };
    let p = Placement {
        coverage: Vec2::new(ctx.scalar(n, 1), ctx.scalar(n, 2)),
        translate_frame: Vec2::new(ctx.scalar(n, 3), ctx.scalar(n, 4)),
        rotate_frame: ctx.scalar(n, 5),
        mirror: [ctx.bool(n, 6), ctx.bool(n, 7)],
        stagger: ctx.bool(n, 8),
        wrap: [ctx.bool(n, 9), ctx.bool(n, 10)],
        repeat: Vec2::new(ctx.scalar(n, 11), ctx.scalar(n, 12)),
        offset: Vec2::new(ctx.scalar(n, 13), ctx.scalar(n, 14)),
        rotate_uv: ctx.scalar(n, 15),
    };
    let placed = match p.apply(Vec2::new(uv.x, uv.y)) {
        Some(t) => Vec3A::new(t.x, t.y, 0.0),
        None => Vec3A::new(0.0, 0.0, -1.0),
    };
    write_struct(out, &[("outUV", Value::Vector(placed)), ("outUvFilterSize", Value::Vector(Vec3A::ZERO))]);
    true
}

maya_shader!(
    /// Maya's file texture: the image of `fileTextureName` at the coordinate, filtered as
    /// `filterType`, `filter` and `filterOffset` say ([`crate::file_filter`]), through the
    /// colour balance. `exposure` is not read.
    FILE,
    ADSK_FILE,
    "maya_file",
    "adskMayaFile",
    texture_params!("fileTextureName", "filterType", "filter", "filterOffset"),
    file
);

fn file(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let looked = match ctx.tag(n, EXTRA) {
        Some(Tag::Texture(i)) => match ctx.shading().textures.get(i as usize) {
            Some(Texture::Image { image, filter, .. }) => {
                let kind = FilterType::from_maya(ctx.int(n, EXTRA + 1));
                let eye = filter.map_or(0.0, |s| s.max(0.0) * ray_footprint(&ctx.state));
                let width = ctx.scalar(n, EXTRA + 2) * eye + ctx.scalar(n, EXTRA + 3);
                let mut c = kind.lookup(image, uv, width);
                if image.channels < 3 {
                    // Grey (and alpha) images: the grey value in all three colour channels.
                    let a = if image.channels == 2 { c.y } else { 1.0 };
                    c = Color::new(c.x, c.x, c.x, a);
                }
                Some(c)
            }
            _ => None,
        },
        _ => None,
    };
    match looked {
        Some(c) => balance(ctx, n, rgb(c), c.w, out),
        None => outside(ctx, n, out),
    }
}

/// `c1` and `c2` pulled towards their mean by `contrast` (1: unchanged, 0: both the mean).
fn with_contrast(c1: Vec3A, c2: Vec3A, contrast: f32) -> (Vec3A, Vec3A) {
    let mean = 0.5 * (c1 + c2);
    (mean + (c1 - mean) * contrast, mean + (c2 - mean) * contrast)
}

maya_shader!(
    /// Maya's checker: a 2×2 board per UV tile, `color1` in the lower-left and
    /// upper-right squares, `color2` in the others, pulled together by `contrast`; alpha
    /// 1 on color1's squares and 0 on color2's, pulled to 0.5 likewise.
    CHECKER,
    ADSK_CHECKER,
    "maya_checker",
    "adskMayaChecker",
    texture_params!("color1", "color2", "contrast"),
    checker
);

fn checker(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let contrast = ctx.scalar(n, EXTRA + 2);
    let (c1, c2) = with_contrast(rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)), contrast);
    let first = ((uv.x >= 0.5) as u8 + (uv.y >= 0.5) as u8) % 2 == 0;
    let (c, a) = if first { (c1, 0.5 + 0.5 * contrast) } else { (c2, 0.5 - 0.5 * contrast) };
    balance(ctx, n, c, a, out)
}

maya_shader!(
    /// Maya's grid: `lineColor` on lines of widths `uWidth`, `vWidth` (fractions of the
    /// tile, centred on its edges), `fillerColor` between, pulled together by
    /// `contrast`; alpha 1 on the lines.
    GRID,
    ADSK_GRID,
    "maya_grid",
    "adskMayaGrid",
    texture_params!("lineColor", "fillerColor", "uWidth", "vWidth", "contrast"),
    grid
);

fn grid(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let (uw, vw) = (0.5 * ctx.scalar(n, EXTRA + 2), 0.5 * ctx.scalar(n, EXTRA + 3));
    let contrast = ctx.scalar(n, EXTRA + 4);
    let (line, fill) = with_contrast(rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)), contrast);
    let on_line = uv.x < uw || uv.x > 1.0 - uw || uv.y < vw || uv.y > 1.0 - vw;
    let (c, a) = if on_line { (line, 0.5 + 0.5 * contrast) } else { (fill, 0.5 - 0.5 * contrast) };
    balance(ctx, n, c, a, out)
}

/// The step in texture space bump2d differentiates over.
const BUMP_STEP: f32 = 1e-3;

maya_shader!(
    /// Maya's bump2d: `outNormal` is the normal (world space) of the surface displaced by
    /// `bumpValue · bumpDepth` along it, `bumpValue` differentiated over the first
    /// texture space by finite differences; `normalCamera`, when connected, is the normal
    /// it starts from.
    BUMP2D,
    ADSK_BUMP2D,
    "maya_bump2d",
    "adskMayaBump2d",
    &["bumpValue", "bumpDepth", "normalCamera"],
    bump2d
);

/// The normal (world space) a bump node starts from: its connected `normalCamera`
/// (parameter `i`), else the shading normal.
pub(crate) fn bump_base_normal(ctx: &mut Ctx, n: NodeId, i: usize) -> Vec3A {
    if ctx.is_connected(n, i) {
        ctx.vector(n, i).try_normalize().unwrap_or(ctx.state.normal)
    } else {
        ctx.state.normal
    }
}

/// Runs `f` with the first texture space's coordinate replaced by `uv` (the shader cache
/// flushed before and after, so that nothing computed at the true coordinate is reused),
/// then restores the coordinate.
pub(crate) fn at_uv<T>(ctx: &mut Ctx, uv: Vec3A, f: impl FnOnce(&mut Ctx) -> T) -> T {
    let (saved, saved_count) = (ctx.state.tex_list[0], ctx.state.tex_count);
    ctx.flush_cache();
    ctx.state.tex_list[0] = uv;
    ctx.state.tex_count = saved_count.max(1);
    let result = f(ctx);
    ctx.flush_cache();
    ctx.state.tex_list[0] = saved;
    ctx.state.tex_count = saved_count;
    result
}

fn bump2d(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let base = bump_base_normal(ctx, n, 2);
    let depth = ctx.scalar(n, 1);
    let [pu, pv] = ctx.state.derivs;
    let area = pu.cross(pv).length();
    let normal = if depth != 0.0 && area > 0.0 && ctx.is_connected(n, 0) && ctx.state.tex_count > 0 {
        let uv = ctx.state.tex_list[0];
        let h = ctx.scalar(n, 0);
        let hu = (at_uv(ctx, uv + Vec3A::new(BUMP_STEP, 0.0, 0.0), |c| c.scalar(n, 0)) - h) / BUMP_STEP;
        let hv = (at_uv(ctx, uv + Vec3A::new(0.0, BUMP_STEP, 0.0), |c| c.scalar(n, 0)) - h) / BUMP_STEP;
        let tilt = depth * (hv * pu.cross(base) + hu * base.cross(pv)) / area;
        (base + tilt).try_normalize().unwrap_or(base)
    } else {
        base
    };
    write_struct(out, &[("outNormal", Value::Vector(normal))]);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2) {
        assert!((a - b).length() < 1e-5, "{a} vs {b}");
    }

    #[test]
    fn placement_repeat_offset_and_rotate() {
        let p = Placement { repeat: Vec2::new(2.0, 3.0), offset: Vec2::new(0.25, 0.5), ..Placement::default() };
        close(p.apply(Vec2::new(0.1, 0.2)).unwrap(), Vec2::new(0.45, 1.1));
        // rotateUV 90°: the coordinate turns by −90° about the centre: (0.75, 0.5) → (0.5, 0.25).
        let r = Placement { rotate_uv: std::f32::consts::FRAC_PI_2, ..Placement::default() };
        close(r.apply(Vec2::new(0.75, 0.5)).unwrap(), Vec2::new(0.5, 0.25));
        // Coverage 0.5 without wrap: (0.6, 0.2) lies outside; with wrap it maps to (1.2, 0.4).
        let c = Placement { coverage: Vec2::splat(0.5), wrap: [false, false], ..Placement::default() };
        assert_eq!(c.apply(Vec2::new(0.6, 0.2)), None);
        let w = Placement { coverage: Vec2::splat(0.5), ..Placement::default() };
        close(w.apply(Vec2::new(0.6, 0.2)).unwrap(), Vec2::new(1.2, 0.4));
        // Translate frame moves the frame's origin.
        let t = Placement { translate_frame: Vec2::new(0.25, 0.0), ..Placement::default() };
        close(t.apply(Vec2::new(0.5, 0.5)).unwrap(), Vec2::new(0.25, 0.5));
        // Rotate frame 90° turns the frame about its centre: the coordinate turns by −90°,
        // (0.75, 0.5) → (0.5, 0.25), as rotateUV does before the repeat.
        let f = Placement { rotate_frame: std::f32::consts::FRAC_PI_2, ..Placement::default() };
        close(f.apply(Vec2::new(0.75, 0.5)).unwrap(), Vec2::new(0.5, 0.25));
        // Mirror: the second repeat runs backwards (1.2 → 1.8, i.e. 0.8 in its tile).
        let m = Placement { repeat: Vec2::new(2.0, 1.0), mirror: [true, false], ..Placement::default() };
        close(m.apply(Vec2::new(0.6, 0.5)).unwrap(), Vec2::new(1.8, 0.5));
        // Stagger: odd rows shift half a tile.
        let s = Placement { repeat: Vec2::new(1.0, 2.0), stagger: true, ..Placement::default() };
        close(s.apply(Vec2::new(0.1, 0.6)).unwrap(), Vec2::new(0.6, 1.2));
    }
}
