//! The shading state: what a shader knows about the point it shades (mental ray's
//! `miState`), with mental ray's names and meanings.
//!
//! mira's internal space is world space: every point, vector and normal here is in world
//! space unless the name says otherwise. Distances are in scene units.

use glam::{Affine3A, Vec2, Vec3A};

pub use crate::media_chain::{MediaChain, Medium};

/// Why a ray was cast (mental ray's `miRay_type`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RayType {
    /// From the camera.
    #[default]
    Eye,
    /// A transparency ray (straight through, no bending).
    Transparent,
    /// A reflection ray.
    Reflect,
    /// A refraction ray.
    Refract,
    /// From a light towards an illuminated point (the light shader's state).
    Light,
    /// A shadow ray (the shadow shader's state).
    Shadow,
    /// An environment lookup (no geometry hit).
    Environment,
    /// A final gather ray (`compute_irradiance`).
    Finalgather,
    /// A probe ray cast by a shader itself (occlusion and similar).
    Probe,
}

impl RayType {
    /// Whether rays of this kind are cast by the eye or by other shading (not light or
    /// shadow work).
    pub fn is_visible(self) -> bool {
        !matches!(self, RayType::Light | RayType::Shadow)
    }
}

/// Most texture spaces a state carries.
pub const MAX_TEXTURES: usize = 8;

/// The hair-specific part of a state (see `mental-ray-material-shaders.md`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HairState {
    /// Interpolated tangent at the hit, root to tip (mental ray puts it in `derivs[0]`).
    pub tangent: Vec3A,
    /// Tangent of the hair's first segment, an approximation of the scalp normal (mental
    /// ray puts it in `normal_geom`; mira keeps `normal_geom` facing the ray for robust
    /// ray offsets).
    pub root: Vec3A,
    /// Position across the hair (0 left edge … 1 right edge, seen from the ray).
    pub across: f32,
    /// Position along the hair (0 at the first vertex … 1 at the last).
    pub along: f32,
}

/// The shading point.
#[derive(Clone, Debug, Default)]
pub struct State {
    /// Why the ray that led here was cast.
    pub ray_type: RayType,
    /// Reflection rays on the path from the eye.
    pub reflection_level: u32,
    /// Refraction and transparency rays on the path from the eye.
    pub refraction_level: u32,
    /// Final gather bounces on the path from the eye.
    pub finalgather_level: u32,
    /// Ray origin (for light shaders: the point on the light).
    pub org: Vec3A,
    /// Ray direction, unit length (for light shaders: from the light to the illuminated
    /// point).
    pub dir: Vec3A,
    /// Distance from `org` to `point` (0 for environment lookups).
    pub dist: f32,
    /// Intersection point (for light shaders: the illuminated point).
    pub point: Vec3A,
    /// Where shadow rays from this point start: the point lifted onto the smooth surface the
    /// vertex normals describe (Hanika, "Hacking the shadow terminator", 2021), so that
    /// coarse tessellations do not shadow themselves near the terminator; the point itself
    /// on flat geometry.
    pub shadow_point: Vec3A,
    /// How far `point` (and `shadow_point`) may lie off the surface as the ray–triangle
    /// test sees it (world units, [`crate::trace::hit_error`]): rays leave from that far
    /// off it ([`crate::trace::leave_point`]); 0 where no triangle was hit.
    pub point_error: f32,
    /// Shading normal, unit length, facing the incoming ray (shaders may change it).
    pub normal: Vec3A,
    /// Geometric normal, unit length, facing the incoming ray.
    pub normal_geom: Vec3A,
    /// The ray hit the back side: `normal` and `normal_geom` were flipped to face it.
    pub inv_normal: bool,
    /// `dot(normal, dir)` (negative when the normal faces the ray).
    pub dot_nd: f32,
    /// Barycentric coordinates of the hit in its triangle.
    pub bary: [f32; 3],
    /// Texture coordinates, one vector per texture space (count in `tex_count`).
    pub tex_list: [Vec3A; MAX_TEXTURES],
    /// How many entries of `tex_list` are meaningful.
    pub tex_count: usize,
    /// Surface derivatives dP/du, dP/dv of the first texture space (zero if unknown).
    pub derivs: [Vec3A; 2],
    /// Pixel differentials of the hit point (mental ray's screen-to-surface projection):
    /// where the point moves on the surface's tangent plane (world space) for a one-pixel
    /// step across the ray's footprint — along the camera's raster x (right) and y (up),
    /// made perpendicular to the ray. Zero when the footprint is unknown. See
    /// [`State::set_pixel_derivs`].
    pub point_derivs: [Vec3A; 2],
    /// dUV/dx and dUV/dy: the change of the first texture space's coordinate (its x and y)
    /// over the steps of `point_derivs`, texture-space units per pixel. Zero when unknown.
    pub tex_derivs: [Vec2; 2],
    /// A texture coordinate handed to a remapping shader in place of its input (mental
    /// ray's fourth argument of `mi_call_shader_x`, set by `mib_texture_filter_lookup`);
    /// shaders that honour it take it (leaving `None`).
    pub tex_arg: Option<Vec3A>,
    /// Bump basis vectors of the first texture space, when the geometry gives them.
    pub bump_basis: Option<[Vec3A; 2]>,
    /// Motion vector of the point (world units per shutter interval).
    pub motion: Vec3A,
    /// The instance's label (written to the tag buffer).
    pub label: u32,
    /// Index of the instance that was hit, in the scene's instance list.
    pub instance: u32,
    /// The renderer's handle of the hit instance (for [`super::Tracer::triangle`]).
    pub geometry: u32,
    /// The triangle that was hit.
    pub prim: u32,
    /// The hit's quad-mesh Ptex face id and face coordinates (u, v) ∈ [0, 1]² (its quad's,
    /// or its n-gon's sub-quad's; [`scene::mesh::ptex_quads`]); `None` where its polygon
    /// has no such face (or the mesh keeps no such table).
    pub ptex_quad: Option<(u32, f32, f32)>,
    /// The current material (scene index), if any.
    pub material: Option<u32>,
    /// Object → world of the hit instance.
    pub object_to_world: Affine3A,
    /// World → object of the hit instance.
    pub world_to_object: Affine3A,
    /// Raster position of the eye sample (pixels, origin at the lower left as in mental
    /// ray).
    pub raster: Vec2,
    /// Index of refraction of the medium the ray travels in (`ior_in`).
    pub ior_in: f32,
    /// Index of refraction of the medium on the other side (`ior`), set by
    /// `mib_refraction_index` and read by refraction.
    pub ior: f32,
    /// The media the ray is inside, outermost first, at any depth.
    pub media: MediaChain,
    /// Shutter time of the sample.
    pub time: f32,
    /// Width of the ray's footprint at the hit (scene units), for texture filtering.
    pub footprint: f32,
    /// Growth of the footprint per unit distance (radians).
    pub spread: f32,
    /// The path engine's width of a pixel's footprint at the hit (scene units), which
    /// tracks no ray footprint of its own (`footprint` stays 0 there, so the shaders that
    /// read it keep their results): pbrt-v4's camera-ray approximation, the camera's
    /// pixel width plus its pixel angle times the camera's distance to the point, at
    /// every bounce. 0 where unknown (the classic engine keeps `footprint`).
    pub camera_footprint: f32,
    /// World-space area of the hit triangle (scene units²), 0 where unknown: the scale of
    /// per-face textures (Ptex) whose face coordinates span the triangle. On a quad-mesh
    /// Ptex face ([`State::ptex_quad`]) half that face's world area instead (a quad's: its
    /// triangle's), whatever the triangle it was cut into.
    pub tri_area: f32,
    /// The hit triangle's world-space edges from its first vertex, p1 − p0 and p2 − p0:
    /// dP/du and dP/dv of its barycentric (u, v) (a triangle-mesh Ptex file's face
    /// coordinates), for footprints that differ along u and v; zero where unknown.
    pub face_edges: [Vec3A; 2],
    /// On a quad-mesh Ptex face ([`State::ptex_quad`]): d(u, v)/d(b1, b2), how the face's
    /// (u, v) change with the hit's barycentrics b1 and b2 (column-major: du/db1, dv/db1,
    /// du/db2, dv/db2), so that the face's dP/du, dP/dv follow from `face_edges`; zero
    /// where unknown.
    pub ptex_quad_jacobian: [f32; 4],
    /// The light a light or shadow shader works for (index into the shading lights).
    pub light: Option<u32>,
    /// Distance travelled by the last ray traced from this state (mental ray's
    /// `child->dist`), infinite if it hit nothing.
    pub child_dist: f32,
    /// At a shadow ray's hit that leaves the receiving point's own instance (from inside):
    /// the world-space length of the stretch the ray went inside it, from where it entered
    /// (or from the receiving point) to this hit; `None` at any other hit and ray.
    pub inside_own: Option<f32>,
    /// Hair data when the hit is on a hair.
    pub hair: Option<HairState>,
    /// Position in the pixel's sample sequence (for shaders that sample).
    pub sample_index: u32,
    /// Pixel the eye sample belongs to (decorrelates shader sampling between pixels).
    pub pixel: [u32; 2],
    /// The last texture coordinate a texture-space shader computed (mental ray's
    /// `state->tex`).
    pub tex: Vec3A,
    /// The next lens shader an eye ray cast from this state runs (index into the camera's
    /// lens shaders; past the end: the ray is cast).
    pub lens_next: u32,
}

impl State {
    /// A state for a ray leaving this one: the new ray's type, origin and direction;
    /// depths and media are carried along.
    ///
    /// Always inlined (as is [`crate::Ctx::new`]): the compiler then builds the new state
    /// in place of the context that takes it, where a call left a copy of the whole state
    /// per light sample (`memcpy`) and a `memset` of its defaults.
    #[inline(always)]
    pub fn child(&self, ray_type: RayType, org: Vec3A, dir: Vec3A) -> State {
        let mut s = State {
            ray_type,
            reflection_level: self.reflection_level,
            refraction_level: self.refraction_level,
            finalgather_level: self.finalgather_level,
            org,
            dir,
            raster: self.raster,
            ior_in: self.ior_in,
            ior: self.ior_in,
            media: self.media.clone(),
            time: self.time,
            footprint: self.footprint,
            spread: self.spread,
            child_dist: f32::INFINITY,
            sample_index: self.sample_index,
            pixel: self.pixel,
            lens_next: self.lens_next,
            ..State::default()
        };
        match ray_type {
            RayType::Reflect => s.reflection_level += 1,
            RayType::Refract | RayType::Transparent => s.refraction_level += 1,
            RayType::Finalgather => s.finalgather_level += 1,
            _ => {}
        }
        s
    }

    /// The texture coordinate of space `i` (zero if the geometry has fewer spaces).
    pub fn tex(&self, i: usize) -> Vec3A {
        if i < self.tex_count {
            self.tex_list[i]
        } else {
            Vec3A::ZERO
        }
    }

    /// The medium the ray is in, if it entered one.
    pub fn medium(&self) -> Option<Medium> {
        self.media.innermost()
    }

    /// Whether the ray is inside material `m` (entered it and has not left).
    pub fn inside(&self, m: u32) -> bool {
        self.media.iter().any(|x| x.material == m)
    }

    /// Records entering a medium (at any depth: nothing is forgotten).
    pub fn enter(&mut self, medium: Medium) {
        self.media.enter(medium, None);
    }

    /// Records entering a medium whose participating medium varies over its surface:
    /// `own` is that medium evaluated where the ray entered.
    pub fn enter_evaluated(&mut self, medium: Medium, own: bsdf::Medium) {
        self.media.enter(medium, Some(own));
    }

    /// Records leaving material `m` (its innermost entry is removed).
    pub fn leave(&mut self, m: u32) {
        self.media.leave(m);
    }

    /// Sets [`State::point_derivs`] from the ray footprint: steps of `footprint` (one
    /// pixel's width at the hit) across the ray, the first along `right` (world space, made
    /// perpendicular to the ray; another perpendicular if it is parallel), the second along
    /// first × `dir` (up for a camera looking down −Z with `right` = +X), each carried
    /// along the ray onto the plane through `point` with normal `normal_geom`. Grazing hits
    /// are limited to a 1/1000 cosine.
    pub fn set_pixel_derivs(&mut self, right: Vec3A) {
        self.point_derivs = [Vec3A::ZERO; 2];
        if !(self.footprint.is_finite() && self.footprint > 0.0) {
            return;
        }
        let d = self.dir;
        let x = (right - d * right.dot(d)).try_normalize().unwrap_or_else(|| d.any_orthonormal_vector());
        let y = x.cross(d);
        let n = self.normal_geom;
        let cos = n.dot(d);
        let cos = if cos.abs() < 1e-3 { 1e-3f32.copysign(cos) } else { cos };
        let onto_plane = |v: Vec3A| (v - d * (v.dot(n) / cos)) * self.footprint;
        self.point_derivs = [onto_plane(x), onto_plane(y)];
    }

    /// The differentials of a texture space over the hit triangle for the steps of
    /// `point_derivs`: `corners` are the triangle's world-space vertices, `coords` their
    /// texture coordinates (x and y used). `None` for a degenerate triangle.
    pub fn texture_derivs(&self, corners: [Vec3A; 3], coords: [Vec3A; 3]) -> Option<[Vec2; 2]> {
        let (e1, e2) = (corners[1] - corners[0], corners[2] - corners[0]);
        let (a, b, c) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let det = a * c - b * b;
        if det.is_nan() || det <= 1e-12 * a * c {
            return None;
        }
        let (t1, t2) = (coords[1] - coords[0], coords[2] - coords[0]);
        // Barycentric steps (least squares in the triangle's plane), then texture steps.
        Some(self.point_derivs.map(|dp| {
            let (r1, r2) = (e1.dot(dp), e2.dot(dp));
            let (b1, b2) = ((c * r1 - b * r2) / det, (a * r2 - b * r1) / det);
            Vec2::new(t1.x * b1 + t2.x * b2, t1.y * b1 + t2.y * b2)
        }))
    }

    /// Object space point of the hit.
    pub fn point_object(&self) -> Vec3A {
        self.world_to_object.transform_point3a(self.point)
    }

    /// A world-space vector in object space.
    pub fn vector_to_object(&self, v: Vec3A) -> Vec3A {
        self.world_to_object.transform_vector3a(v)
    }

    /// An object-space vector in world space.
    pub fn vector_from_object(&self, v: Vec3A) -> Vec3A {
        self.object_to_world.transform_vector3a(v)
    }

    /// A world-space normal in object space (inverse transpose of world → object).
    pub fn normal_to_object(&self, n: Vec3A) -> Vec3A {
        self.object_to_world.matrix3.transpose() * n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn children_count_their_kind_of_depth() {
        let eye = State::default();
        let r = eye.child(RayType::Reflect, Vec3A::ZERO, Vec3A::Z);
        let rr = r.child(RayType::Refract, Vec3A::ZERO, Vec3A::Z);
        assert_eq!((rr.reflection_level, rr.refraction_level), (1, 1));
        let t = rr.child(RayType::Transparent, Vec3A::ZERO, Vec3A::Z);
        assert_eq!(t.refraction_level, 2);
    }

    #[test]
    fn pixel_derivs_stretch_by_the_inverse_cosine_along_the_tilt() {
        // A camera looking down −Z at the plane z = 0 tilted by 60° about x: unit uv per
        // unit length, u along x, v up the tilted plane.
        let tilt = 60f32.to_radians();
        let (up, n) = (Vec3A::new(0.0, tilt.cos(), tilt.sin()), Vec3A::new(0.0, -tilt.sin(), tilt.cos()));
        let s = State { dir: -Vec3A::Z, normal_geom: n, footprint: 0.01, ..State::default() };
        let mut s = s;
        s.set_pixel_derivs(Vec3A::X);
        assert!((s.point_derivs[0] - Vec3A::new(0.01, 0.0, 0.0)).length() < 1e-7);
        // Up one pixel on screen: 0.01 / cos 60° = 0.02 along the plane.
        assert!((s.point_derivs[1] - up * 0.02).length() < 1e-6, "{}", s.point_derivs[1]);
        let corners = [Vec3A::ZERO, Vec3A::X, up];
        let coords = [Vec3A::ZERO, Vec3A::X, Vec3A::Y];
        let [dx, dy] = s.texture_derivs(corners, coords).unwrap();
        assert!((dx - Vec2::new(0.01, 0.0)).length() < 1e-6 && (dy - Vec2::new(0.0, 0.02)).length() < 1e-6);
        // A texture scaled 3× in u and mirrored in v scales the differentials.
        let coords = [Vec3A::ZERO, Vec3A::X * 3.0, -Vec3A::Y];
        let [dx, dy] = s.texture_derivs(corners, coords).unwrap();
        assert!((dx - Vec2::new(0.03, 0.0)).length() < 1e-6 && (dy - Vec2::new(0.0, -0.02)).length() < 1e-6);
        assert!(s.texture_derivs([Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0], coords).is_none());
        // No footprint, no differentials.
        s.footprint = 0.0;
        s.set_pixel_derivs(Vec3A::X);
        assert_eq!(s.point_derivs, [Vec3A::ZERO; 2]);
    }

    #[test]
    fn media_chain_enters_and_leaves_in_any_order() {
        let mut s = State::default();
        s.enter(Medium { material: 1, ior: 1.5 });
        s.enter(Medium { material: 2, ior: 1.33 });
        assert!(s.inside(1) && s.inside(2));
        s.leave(1);
        assert_eq!(s.medium(), Some(Medium { material: 2, ior: 1.33 }));
        assert!(!s.inside(1));
        for m in 0..20 {
            s.enter(Medium { material: m + 10, ior: 1.0 });
        }
        // Nothing is forgotten: twenty-one deep, the outermost still there.
        assert_eq!(s.media.len(), 21);
        assert_eq!(s.medium().unwrap().material, 29);
        assert_eq!(s.media.iter().next(), Some(Medium { material: 2, ior: 1.33 }));
    }
}
