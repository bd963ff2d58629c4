//! Maya's projection and envSphere: 2D textures laid over space.
//!
//! projection (parameters after the 3D textures' shared ones, see [`crate::texture3d`]):
//! `projType` (1), `image` (the colour of the 2D texture it projects, usually connected to
//! its `outColor`), `transparency` (not read), `uAngle` (180) and `vAngle` (90), in
//! degrees. The shading point p in the placement space of `placementMatrix` gives the
//! coordinate (u, v) at which `image` is evaluated (the connected texture reads it as its
//! surface coordinate, through its place2dTexture if it has one):
//!
//! | projType | (u, v) |
//! |---|---|
//! | 1 planar | ((x + 1)/2, (y + 1)/2): the placement's XY square [−1, 1]² |
//! | 2 spherical | (½ + φ/uAngle, ½ + λ/vAngle), φ = atan2(x, z) the longitude about Y from +Z, λ = asin(y/‖p‖) the latitude |
//! | 3 cylindrical | (½ + φ/uAngle, (y + 1)/2) |
//! | 4 ball | ½ + ½ (θ/π) (x, y)/‖(x, y)‖, θ the angle of p from +Z |
//! | 5 cubic | planar along the axis on which p is largest: (z, y), (x, z) or (x, y) |
//! | 6 triplanar | the cubic layout, the plane chosen by the largest component of the surface normal n (placement space) instead of p |
//! | 7 concentric | (fract ‖p‖, fract ‖p‖): the image's diagonal repeated over shells one placement unit apart about the origin |
//! | 8 perspective (camera) | the point's place in the linked camera's image, fitted by `fitType`/`fitFill` (below); behind the camera: `defaultColor` |
//!
//! **The perspective projection's camera.** Maya links the projection to a camera node
//! (`linkedCamera`, a message connection) and fits the image to that camera's frame by
//! `fitType` (0 None, 1 Match Camera Film Gate, 2 Match Camera Resolution) and `fitFill`
//! (0 Fill, 1 Horizontal, 2 Vertical). No page documents how mental ray for Maya passes
//! the camera (a `.mi` shader parameter cannot name a camera) nor the fit's formulas, so
//! mira's declaration carries the linked camera as Maya's own attributes, after the
//! others: `linkedCamera` (a transform: world → the camera's space, as a camera
//! instance's `transform`; the camera looks down its −Z), `cameraFocalLength` (mm),
//! `cameraHorizontalFilmAperture` and `cameraVerticalFilmAperture` (inches; Maya's 35 mm
//! defaults 1.417 × 0.945), `fitType` (1), `fitFill` (0) and `imageAspect` (the projected
//! image's width / height, 1; mira cannot see the resolution of the texture behind
//! `image`), `cameraOrthographic` (off) and `cameraOrthographicWidth` (1, Maya's
//! camera's `orthographic` and `orthographicWidth`: the width of the orthographic view in
//! scene units). With `cameraFocalLength` 0 (the default) and `cameraOrthographic` off the
//! render camera is the linked one, its film gate the image's own aspect. The fit is read as 3Delight for Maya's
//! projection shader reads it: the point's screen position s = (x_c, y_c)/(−z_c)/h, h
//! the image plane's half width at distance 1 (horizontal aperture·25.4/(2·focal)), is
//! scaled for the frame of aspect a (the film gate's H/V for fitType 1, the render
//! resolution's for 2) and the image's aspect i: None leaves it (the image square, as
//! wide as the frame), Fill scales s_y by a (the image stretched over the frame),
//! Horizontal s_y by i (the image's width across the frame, its proportions kept),
//! Vertical s_x by a/i and s_y by a (its height over the frame); (u, v) = ½ + ½ s. An
//! orthographic camera — the render camera or a linked one with `cameraOrthographic` on,
//! whose h is half its `cameraOrthographicWidth` and whose film gate still gives the
//! frame's aspect for fitType 1 — gives s = (x_c, y_c)/h with h half the view's width.
//! The placement is ignored.
//!
//! `projType` 0 (off) returns `defaultColor`. envSphere: `image` wrapped over the sphere of
//! directions, the ray direction d (world) giving u = ½ + atan2(d_x, −d_z)/2π (the −Z
//! axis at the centre of the image), v = ½ + asin(d_y)/π, sheared by `shearU`,
//! `shearV` (u += shearU·v, v += shearV·u) and mirrored in u by `flip`. The layouts are
//! Maya's descriptions of the projections (a plane, a sphere, a cylinder, a ball)
//! written out by mira; Maya's exact seams are not published.

use glam::{Vec2, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::texture::{at_uv, balance, outside};
use crate::texture3d::{placement_matrix, placement_point, texture3d_params, EXTRA};
use crate::values::{rgb, rgba, write_struct};

/// The surface coordinate of placement-space point `p` under `proj_type` (Maya's
/// enumeration) with `u_angle` and `v_angle` in degrees; `None` for the projections mira
/// does not lay out (and 0, off).
pub fn project(proj_type: i32, p: Vec3A, u_angle: f32, v_angle: f32) -> Option<Vec2> {
    let span = |deg: f32| deg.to_radians().abs().max(1e-4);
    match proj_type {
        1 => Some(cube_face(p, Vec3A::Z)),
        2 => {
            let r = p.length();
            if r <= 0.0 {
                return Some(Vec2::splat(0.5));
            }
            let phi = p.x.atan2(p.z);
            let lat = (p.y / r).clamp(-1.0, 1.0).asin();
            Some(Vec2::new(0.5 + phi / span(u_angle), 0.5 + lat / span(v_angle)))
        }
        3 => Some(Vec2::new(0.5 + p.x.atan2(p.z) / span(u_angle), 0.5 * (p.y + 1.0))),
        4 => {
            let d = p.try_normalize()?;
            let theta = d.z.clamp(-1.0, 1.0).acos();
            let xy = Vec2::new(d.x, d.y);
            let dir = xy.try_normalize().unwrap_or(Vec2::ZERO);
            Some(Vec2::splat(0.5) + 0.5 * (theta / std::f32::consts::PI) * dir)
        }
        5 => Some(cube_face(p, p)),
        7 => {
            let r = p.length().fract();
            Some(Vec2::splat(r))
        }
        _ => None,
    }
}

/// The triplanar layout of placement-space point `p` on a surface of placement-space
/// normal `n`: the cubic layout of the plane `n` is most nearly perpendicular to.
pub fn triplanar(p: Vec3A, n: Vec3A) -> Vec2 {
    cube_face(p, n)
}

/// The planar layout of `p` on the cube face `axis` points at most nearly: (z, y) for
/// ±X, (x, z) for ±Y, (x, y) for ±Z, each mapped from [−1, 1] to [0, 1].
fn cube_face(p: Vec3A, axis: Vec3A) -> Vec2 {
    let planar = |a: f32, b: f32| Vec2::new(0.5 * (a + 1.0), 0.5 * (b + 1.0));
    let a = axis.abs();
    if a.x >= a.y && a.x >= a.z {
        planar(p.z, p.y)
    } else if a.y >= a.z {
        planar(p.x, p.z)
    } else {
        planar(p.x, p.y)
    }
}

/// How a perspective projection fits its image to the linked camera's frame (Maya's
/// `fitType` and `fitFill`, see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fit {
    /// `fitType` 0: the image square, as wide as the frame.
    None,
    /// `fitFill` 0: stretched over the frame.
    Fill,
    /// `fitFill` 1: its width across the frame, its proportions kept.
    Horizontal,
    /// `fitFill` 2: its height over the frame, its proportions kept.
    Vertical,
}

impl Fit {
    /// Maya's `fitType` and `fitFill` values (an unknown `fitFill` is Fill).
    pub fn from_maya(fit_type: i32, fit_fill: i32) -> Fit {
        match (fit_type, fit_fill) {
            (0, _) => Fit::None,
            (_, 1) => Fit::Horizontal,
            (_, 2) => Fit::Vertical,
            _ => Fit::Fill,
        }
    }
}

/// The position of camera-space point `p_camera` in a camera's image as (u, v) (v up):
/// `half_width` is the image plane's half width at distance 1 (orthographic: half the
/// view's width), `frame_aspect` the frame's width / height, `image_aspect` the image's,
/// `fit` how the image is laid over the frame (see the module doc); `None` behind a
/// perspective camera.
pub fn camera_uv(
    p_camera: Vec3A,
    half_width: f32,
    orthographic: bool,
    fit: Fit,
    frame_aspect: f32,
    image_aspect: f32,
) -> Option<Vec2> {
    let mut s = if orthographic {
        Vec2::new(p_camera.x, p_camera.y)
    } else {
        if p_camera.z >= 0.0 {
            return None;
        }
        Vec2::new(p_camera.x, p_camera.y) / -p_camera.z
    } / half_width.max(1e-6);
    let (frame, image) = (frame_aspect.max(1e-6), image_aspect.max(1e-6));
    match fit {
        Fit::None => {}
        Fit::Fill => s.y *= frame,
        Fit::Horizontal => s.y *= image,
        Fit::Vertical => s *= Vec2::new(frame / image, frame),
    }
    Some(Vec2::splat(0.5) + 0.5 * s)
}

/// The perspective projection's coordinate of the shading point (world `point`) through
/// the linked camera of node `n`, or the render camera's (see the module doc).
fn perspective(ctx: &mut Ctx, n: NodeId, point: Vec3A) -> Option<Vec2> {
    let fit = Fit::from_maya(ctx.int(n, FIT_TYPE), ctx.int(n, FIT_TYPE + 1));
    let image_aspect = ctx.scalar(n, FIT_TYPE + 6);
    let focal_mm = ctx.scalar(n, FIT_TYPE + 3);
    let shading = ctx.shading();
    let (w, h) = shading.resolution;
    let resolution_aspect = if h > 0 { w as f32 / h as f32 } else { 1.0 };
    let render_aspect = shading.image_plane.x / shading.image_plane.y.max(1e-12);
    let orthographic = ctx.bool(n, FIT_TYPE + 7);
    if orthographic || focal_mm > 0.0 {
        let world_to_camera = ctx.eval(n, FIT_TYPE + 2).transform();
        let (h_aperture, v_aperture) = (ctx.scalar(n, FIT_TYPE + 4), ctx.scalar(n, FIT_TYPE + 5));
        let half_width =
            if orthographic { 0.5 * ctx.scalar(n, FIT_TYPE + 8) } else { h_aperture * 25.4 / (2.0 * focal_mm) };
        let film_aspect = h_aperture / v_aperture.max(1e-6);
        let frame = if ctx.int(n, FIT_TYPE) == 2 { resolution_aspect } else { film_aspect };
        let p_camera = Vec3A::from(world_to_camera.transform_point3(point.into()));
        camera_uv(p_camera, half_width, orthographic, fit, frame, image_aspect)
    } else {
        let frame = if ctx.int(n, FIT_TYPE) == 2 { resolution_aspect } else { render_aspect };
        let p_camera = shading.world_to_camera.transform_point3a(point);
        camera_uv(p_camera, shading.image_plane.x, shading.orthographic, fit, frame, image_aspect)
    }
}

/// Evaluates colour parameter `i` of `n` (a connected 2D texture) at surface coordinate
/// `uv` (the first texture space replaced while it runs).
fn image_at(ctx: &mut Ctx, n: NodeId, i: usize, uv: Vec2) -> shader::Color {
    at_uv(ctx, Vec3A::new(uv.x, uv.y, 0.0), |c| c.color(n, i))
}

maya_shader!(
    /// Maya's projection (see the module doc).
    PROJECTION,
    ADSK_PROJECTION,
    "maya_projection",
    "adskMayaProjection",
    texture3d_params!(
        "projType",
        "image",
        "uAngle",
        "vAngle",
        "fitType",
        "fitFill",
        "linkedCamera",
        "cameraFocalLength",
        "cameraHorizontalFilmAperture",
        "cameraVerticalFilmAperture",
        "imageAspect",
        "cameraOrthographic",
        "cameraOrthographicWidth"
    ),
    projection
);

/// The index of `fitType`; the linked camera's parameters follow it.
const FIT_TYPE: usize = EXTRA + 4;

fn projection(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let kind = ctx.int(n, EXTRA);
    let (ua, va) = (ctx.scalar(n, EXTRA + 2), ctx.scalar(n, EXTRA + 3));
    let uv = match kind {
        6 => {
            // Normals go to placement space by the inverse transpose of the placement.
            let m = placement_matrix(&ctx.eval(n, 0));
            let normal = Vec3A::from(m.inverse().transpose().transform_vector3(ctx.state.normal.into()));
            Some(triplanar(p, normal))
        }
        8 => {
            let point = ctx.state.point;
            perspective(ctx, n, point)
        }
        _ => project(kind, p, ua, va),
    };
    let Some(uv) = uv else { return outside(ctx, n, out) };
    let c = image_at(ctx, n, EXTRA + 1, uv);
    balance(ctx, n, rgb(c), c.w, out)
}

/// envSphere's coordinate of world direction `d` (see the module doc).
pub fn env_sphere_uv(d: Vec3A, shear: Vec2, flip: bool) -> Vec2 {
    let d = d.try_normalize().unwrap_or(Vec3A::NEG_Z);
    let u = 0.5 + d.x.atan2(-d.z) / std::f32::consts::TAU;
    let v = 0.5 + d.y.clamp(-1.0, 1.0).asin() / std::f32::consts::PI;
    let (u, v) = (u + shear.x * v, v + shear.y * u);
    Vec2::new(if flip { 1.0 - u } else { u }, v)
}

maya_shader!(
    /// Maya's envSphere (see the module doc); usable as a texture or a camera's
    /// environment shader.
    ENVSPHERE,
    ADSK_ENVSPHERE,
    "maya_envsphere",
    "adskMayaEnvSphere",
    &["image", "shearU", "shearV", "flip"],
    env_sphere
);

fn env_sphere(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let shear = Vec2::new(ctx.scalar(n, 1), ctx.scalar(n, 2));
    let uv = env_sphere_uv(ctx.state.dir, shear, ctx.bool(n, 3));
    let c = image_at(ctx, n, 0, uv);
    match out {
        Value::Struct(_) => {
            write_struct(out, &[("outColor", Value::Color(rgba(rgb(c), 1.0))), ("outAlpha", Value::Scalar(c.w))])
        }
        _ => *out = Value::Color(rgba(rgb(c), 1.0)),
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2) {
        assert!((a - b).length() < 1e-5, "{a} vs {b}");
    }

    #[test]
    fn planar_spherical_cylindrical_ball_and_cubic_layouts() {
        close(project(1, Vec3A::new(-1.0, 1.0, 7.0), 180.0, 90.0).unwrap(), Vec2::new(0.0, 1.0));
        close(project(1, Vec3A::new(0.5, 0.0, 0.0), 180.0, 90.0).unwrap(), Vec2::new(0.75, 0.5));
        // Spherical, 360° × 180°: +Z is the centre, +X a quarter turn right, +Y the top.
        close(project(2, Vec3A::Z, 360.0, 180.0).unwrap(), Vec2::new(0.5, 0.5));
        close(project(2, Vec3A::X * 3.0, 360.0, 180.0).unwrap(), Vec2::new(0.75, 0.5));
        close(project(2, Vec3A::Y, 360.0, 180.0).unwrap(), Vec2::new(0.5, 1.0));
        // Halving uAngle doubles the spread in u.
        close(project(2, Vec3A::new(1.0, 0.0, 1.0), 180.0, 90.0).unwrap(), Vec2::new(0.75, 0.5));
        // Cylindrical: longitude in u, height in v.
        close(project(3, Vec3A::new(-1.0, 0.5, 0.0), 360.0, 90.0).unwrap(), Vec2::new(0.25, 0.75));
        // Ball: +Z at the centre, −Z on the rim.
        close(project(4, Vec3A::Z, 0.0, 0.0).unwrap(), Vec2::new(0.5, 0.5));
        close(project(4, Vec3A::X, 0.0, 0.0).unwrap(), Vec2::new(0.75, 0.5));
        // Cubic: the largest axis picks the plane.
        close(project(5, Vec3A::new(0.9, 0.2, -0.4), 0.0, 0.0).unwrap(), Vec2::new(0.3, 0.6));
        assert_eq!(project(6, Vec3A::X, 180.0, 90.0), None, "triplanar needs the normal");
        assert_eq!(project(0, Vec3A::X, 180.0, 90.0), None);
    }

    /// Triplanar, concentric and perspective layouts of points worked out by hand.
    #[test]
    fn triplanar_concentric_and_perspective_layouts() {
        // Triplanar: a point far out in x on a surface facing +Y lies on the XZ plane
        // (cubic would pick the YZ plane by the point).
        let p = Vec3A::new(0.9, 0.2, -0.4);
        close(triplanar(p, Vec3A::Y), Vec2::new(0.95, 0.3));
        close(triplanar(p, Vec3A::new(-0.8, 0.1, 0.3)), project(5, p, 0.0, 0.0).unwrap());
        close(triplanar(p, Vec3A::new(0.1, 0.2, -0.9)), Vec2::new(0.95, 0.6));
        // Concentric: ‖(0.6, 0.8, 0)‖ = 1 starts the next shell; ‖(0, 1.5, 2)‖ = 2.5.
        close(project(7, Vec3A::new(0.3, 0.4, 0.0), 0.0, 0.0).unwrap(), Vec2::splat(0.5));
        close(project(7, Vec3A::new(0.0, 1.5, 2.0), 0.0, 0.0).unwrap(), Vec2::splat(0.5));
        close(project(7, Vec3A::new(0.0, 0.0, -1.25), 0.0, 0.0).unwrap(), Vec2::splat(0.25));
        // Perspective, filled: a 90° × 60° view (half size 1 × tan 30°, aspect 1/tan 30°).
        // On the axis: the centre; at 45° right: the right edge; x_c = 0.5, y_c = −tan 30°
        // / 2 at z_c = −1: (¾, ¼).
        let (half, aspect) = (1.0, 1.0 / 30f32.to_radians().tan());
        let fill = |p: Vec3A| camera_uv(p, half, false, Fit::Fill, aspect, 1.0).unwrap();
        close(fill(Vec3A::new(0.0, 0.0, -5.0)), Vec2::splat(0.5));
        close(fill(Vec3A::new(3.0, 0.0, -3.0)), Vec2::new(1.0, 0.5));
        close(fill(Vec3A::new(1.0, -1.0 / aspect, -2.0)), Vec2::new(0.75, 0.25));
        assert_eq!(camera_uv(Vec3A::new(0.0, 0.0, 1.0), half, false, Fit::Fill, aspect, 1.0), None, "behind");
        // Orthographic: the view's half size 2 × 1; depth does not matter.
        close(camera_uv(Vec3A::new(1.0, 0.5, 7.0), 2.0, true, Fit::Fill, 2.0, 1.0).unwrap(), Vec2::new(0.75, 0.75));
    }

    /// The four fits of a frame of aspect 2 (half width 0.5 at distance 1: the frame's
    /// top-right corner at (0.5, 0.25, −1)) and an image of aspect 4/3, by hand.
    #[test]
    fn fit_types_lay_the_image_over_the_frame() {
        let uv = |fit, p: Vec3A| camera_uv(p, 0.5, false, fit, 2.0, 4.0 / 3.0).unwrap();
        let corner = Vec3A::new(0.5, 0.25, -1.0);
        // None: s = (1, 0.5): the square image as wide as the frame, reaching v = ¾.
        close(uv(Fit::None, corner), Vec2::new(1.0, 0.75));
        // Fill: s_y × 2: the corner is the image's corner.
        close(uv(Fit::Fill, corner), Vec2::new(1.0, 1.0));
        // Horizontal: s_y × 4/3: v = ½ + ½ · ⅔ (the image's top lies above the frame's).
        close(uv(Fit::Horizontal, corner), Vec2::new(1.0, 0.5 + 1.0 / 3.0));
        // Vertical: s_x × 2 / (4/3) = 1.5, s_y × 2 = 1: the frame's top edge is the image's,
        // its right edge beyond the image's (u = 1.25).
        close(uv(Fit::Vertical, corner), Vec2::new(1.25, 1.0));
        // The same direction twice as far: the same place; twice as deep: half as far out.
        close(uv(Fit::Fill, corner * 2.0), Vec2::new(1.0, 1.0));
        close(uv(Fit::Fill, Vec3A::new(0.5, 0.25, -2.0)), Vec2::new(0.75, 0.75));
        assert_eq!(Fit::from_maya(0, 2), Fit::None);
        assert_eq!(Fit::from_maya(1, 0), Fit::Fill);
        assert_eq!(Fit::from_maya(2, 1), Fit::Horizontal);
        assert_eq!(Fit::from_maya(1, 2), Fit::Vertical);
    }

    #[test]
    fn env_sphere_centres_minus_z_and_flips() {
        close(env_sphere_uv(Vec3A::NEG_Z, Vec2::ZERO, false), Vec2::new(0.5, 0.5));
        close(env_sphere_uv(Vec3A::X, Vec2::ZERO, false), Vec2::new(0.75, 0.5));
        close(env_sphere_uv(Vec3A::new(0.0, 1.0, -1.0), Vec2::ZERO, false), Vec2::new(0.5, 0.75));
        close(env_sphere_uv(Vec3A::X, Vec2::ZERO, true), Vec2::new(0.25, 0.5));
        close(env_sphere_uv(Vec3A::NEG_Z, Vec2::new(0.2, 0.0), false), Vec2::new(0.6, 0.5));
    }
}
