//! The shader model's ray casting over the world: [`SceneTracer`] implements
//! [`shader::Tracer`] on the acceleration structure for both engines (the classic engine's
//! shaders, and the path engine's connected material parameters and environment), and fills
//! the shading state of a hit ([`fill_state`]).

use std::cell::{Cell, RefCell};

use glam::{Vec2, Vec3A};
use shader::{Color, RayType, ShadowQuery, State, Tracer, VertexData};

use crate::accel::{Accel, Hit};
use crate::ray::{mask, FirstHit, Ray, RayCounts};
use crate::world::World;

/// The ray casting of one rendering thread for one eye sample.
pub struct SceneTracer<'a> {
    world: &'a World,
    accel: &'a dyn Accel,
    /// Counts of rays cast.
    pub counts: Cell<RayCounts>,
    /// The first surface the eye ray hit.
    pub first: Cell<Option<FirstHit>>,
    /// World-space motion of that hit over the shutter interval (`state.motion`).
    pub first_motion: Cell<Vec3A>,
    /// `fb_put` writes of this sample: (buffer, value).
    pub fb: RefCell<Vec<(u32, Color)>>,
    /// The render's final gather interpolation cache, if it has one.
    pub fg_cache: Option<&'a shader::fgcache::FgCache>,
}

impl<'a> SceneTracer<'a> {
    /// A tracer over a built world.
    pub fn new(world: &'a World, accel: &'a dyn Accel) -> SceneTracer<'a> {
        SceneTracer {
            world,
            accel,
            counts: Cell::new(RayCounts::default()),
            first: Cell::new(None),
            first_motion: Cell::new(Vec3A::ZERO),
            fb: RefCell::new(Vec::new()),
            fg_cache: None,
        }
    }

    fn count(&self, shadow: bool) {
        let mut c = self.counts.get();
        if shadow {
            c.shadow_rays += 1;
        } else {
            c.rays += 1;
        }
        self.counts.set(c);
    }
}

/// The instances a ray of `kind` may see.
fn ray_mask(kind: RayType) -> u32 {
    match kind {
        RayType::Eye => mask::CAMERA,
        RayType::Reflect => mask::REFLECT,
        RayType::Refract => mask::REFRACT,
        RayType::Transparent => mask::TRANSPARENT,
        RayType::Finalgather => mask::FINALGATHER,
        RayType::Shadow | RayType::Light => mask::SHADOW,
        RayType::Environment | RayType::Probe => u32::MAX,
    }
}

/// Fills in the surface part of `s` for `hit` on the ray `s.org + t s.dir`.
pub fn fill_state(world: &World, hit: &Hit, s: &mut State) {
    let inst = &world.instances[hit.instance as usize];
    let mesh = &world.meshes[inst.mesh as usize];
    let tri = mesh.triangles[hit.prim as usize];
    let [i0, i1, i2] = tri.map(|i| i as usize);
    // Where the instance and its vertices are at the ray's time (see `crate::motion`).
    let placed = inst.placement(s.time);
    let [p0, p1, p2] = mesh.triangle_at(tri, s.time);
    let (b1, b2) = (hit.u, hit.v);
    let b0 = 1.0 - b1 - b2;
    s.dist = hit.t;
    s.point = s.org + s.dir * hit.t;
    s.bary = [b0, b1, b2];
    let ng = (placed.normal_to_world * (p1 - p0).cross(p2 - p0)).normalize_or(Vec3A::Z);
    s.shadow_point = s.point;
    s.point_error = shader::trace::hit_error(p0, p1, p2, &placed.object_to_world);
    let mut ns = if !mesh.has_normals() {
        ng
    } else {
        let (n0, n1, n2) = (mesh.normal(tri[0]), mesh.normal(tri[1]), mesh.normal(tri[2]));
        // Lift the point onto the vertices' tangent planes (object space), where it lies
        // below them.
        let p_obj = p0 * b0 + p1 * b1 + p2 * b2;
        let lift = |p_i: Vec3A, n_i: Vec3A| {
            let n_i = n_i.normalize_or_zero();
            let d = (p_obj - p_i).dot(n_i);
            if d < 0.0 {
                p_obj - n_i * d
            } else {
                p_obj
            }
        };
        let lifted = lift(p0, n0) * b0 + lift(p1, n1) * b1 + lift(p2, n2) * b2;
        s.shadow_point = placed.object_to_world.transform_point3a(lifted);
        let n = n0 * b0 + n1 * b1 + n2 * b2;
        (placed.normal_to_world * n).normalize_or(ng)
    };
    if ns.dot(ng) < 0.0 {
        ns = -ns;
    }
    let ns = mesh.sharpen(ns, ng);
    // Face the ray: a back-side hit flips both normals and says so.
    s.inv_normal = ng.dot(s.dir) > 0.0;
    let (ng, ns) = if s.inv_normal { (-ng, -ns) } else { (ng, ns) };
    s.normal_geom = ng;
    s.normal = ns;
    s.dot_nd = ns.dot(s.dir);
    s.tex_count = mesh.textures.len().min(shader::state::MAX_TEXTURES);
    for (k, space) in mesh.textures.iter().take(s.tex_count).enumerate() {
        s.tex_list[k] = space[i0] * b0 + space[i1] * b1 + space[i2] * b2;
    }
    // Surface derivatives from the first texture space: dP/du, dP/dv of the triangle.
    s.derivs = [Vec3A::ZERO; 2];
    if let Some(space) = mesh.textures.first() {
        let (t0, t1, t2) = (space[i0], space[i1], space[i2]);
        let (du1, dv1, du2, dv2) = (t1.x - t0.x, t1.y - t0.y, t2.x - t0.x, t2.y - t0.y);
        let det = du1 * dv2 - du2 * dv1;
        if det.abs() > 1e-20 {
            let (e1, e2) = (p1 - p0, p2 - p0);
            let dpdu = (e1 * dv2 - e2 * dv1) / det;
            let dpdv = (e2 * du1 - e1 * du2) / det;
            s.derivs =
                [placed.object_to_world.transform_vector3a(dpdu), placed.object_to_world.transform_vector3a(dpdv)];
        }
    }
    s.bump_basis = (!mesh.bump_basis.is_empty()).then(|| {
        let [a, b, c] = [mesh.bump_basis[i0], mesh.bump_basis[i1], mesh.bump_basis[i2]];
        let u = a[0] * b0 + b[0] * b1 + c[0] * b2;
        let v = a[1] * b0 + b[1] * b1 + c[1] * b2;
        [placed.object_to_world.transform_vector3a(u), placed.object_to_world.transform_vector3a(v)]
    });
    s.hair = None;
    if let Some(hair) = &mesh.hair {
        // mental ray's hair state: the normal faces the ray, perpendicular to the hair.
        let [t, root] = hair.tangents[hit.prim as usize];
        let t = placed.object_to_world.transform_vector3a(t).normalize_or(Vec3A::Y);
        let root = placed.object_to_world.transform_vector3a(root).normalize_or(t);
        let back = -s.dir;
        let n = (back - t * t.dot(back)).normalize_or(back);
        let along = hair.along[i0] * b0 + hair.along[i1] * b1 + hair.along[i2] * b2;
        let across = hair.across[i0] * b0 + hair.across[i1] * b1 + hair.across[i2] * b2;
        s.normal = n;
        s.normal_geom = n;
        s.inv_normal = false;
        s.dot_nd = n.dot(s.dir);
        s.shadow_point = s.point;
        s.derivs = [t, Vec3A::ZERO];
        s.bary = [across, along, 0.0];
        s.hair = Some(shader::state::HairState { tangent: t, root, across, along });
    }
    s.label = inst.tag;
    s.instance = inst.scene_index;
    s.geometry = hit.instance;
    s.prim = hit.prim;
    s.ptex_quad = ptex_quad_face(mesh, hit.prim as usize, s.bary);
    let slot = mesh.slots.get(hit.prim as usize).copied().unwrap_or(0) as usize;
    s.material = inst.materials.get(slot).copied().and_then(|m| m.checked_sub(1));
    s.object_to_world = placed.object_to_world;
    s.world_to_object = placed.world_to_object;
    s.footprint += s.spread * hit.t;
    let to_world = |e: Vec3A| placed.object_to_world.transform_vector3a(e);
    s.face_edges = [to_world(p1 - p0), to_world(p2 - p0)];
    s.tri_area = 0.5 * s.face_edges[0].cross(s.face_edges[1]).length();
    s.ptex_quad_jacobian = [0.0; 4];
    if let Some(at) = s.ptex_quad {
        // A quad-mesh Ptex lookup's width in face units needs its face's size: `tri_area`
        // becomes half the face's world area (a quad of two triangles keeps its triangle's).
        s.tri_area *= 0.5 * ptex_face_ratio(mesh, hit.prim as usize, s.bary);
        s.ptex_quad_jacobian = ptex_quad_jacobian(mesh, hit.prim as usize, s.bary, at);
    }
    s.motion = motion(inst, mesh, [i0, i1, i2], s);
    // Pixel differentials across the footprint (raster x along the camera's right), and
    // the first texture space's dUV/dx, dUV/dy over the triangle.
    s.set_pixel_derivs(world.camera.camera_to_world.transform_vector3a(Vec3A::X));
    s.tex_derivs = [glam::Vec2::ZERO; 2];
    if let (Some(space), None) = (mesh.textures.first(), &s.hair) {
        let corners = [p0, p1, p2].map(|p| placed.object_to_world.transform_point3a(p));
        s.tex_derivs = s.texture_derivs(corners, [space[i0], space[i1], space[i2]]).unwrap_or_default();
    }
}

/// World-space motion of the hit point over the shutter interval: where the instance's
/// `motion transform` carries it by the end of the interval, plus the interpolated vertex
/// motion vectors (object space, carried to world space by the instance transform).
fn motion(inst: &crate::world::InstanceData, mesh: &crate::mesh::MeshData, v: [usize; 3], s: &State) -> Vec3A {
    let mut m = Vec3A::ZERO;
    if let Some(to_world) = inst.motion_to_world {
        if inst.moves() {
            // The hit is where the instance is at the sample's time: the motion is that
            // material point's, from the interval's start to its end.
            let p_obj = inst.placement(s.time).world_to_object.transform_point3a(s.point);
            m += to_world.transform_point3a(p_obj) - inst.object_to_world.transform_point3a(p_obj);
        } else {
            m += to_world.transform_point3a(inst.world_to_object.transform_point3a(s.point)) - s.point;
        }
    }
    if let (Some(a), Some(b), Some(c)) = (mesh.motion.get(v[0]), mesh.motion.get(v[1]), mesh.motion.get(v[2])) {
        if s.hair.is_none() {
            let [b0, b1, b2] = s.bary;
            m += inst.object_to_world.transform_vector3a(*a * b0 + *b * b1 + *c * b2);
        }
    }
    m
}

/// World-space motion over the shutter interval of `point` on `hit` (as [`fill_state`]
/// finds it at shutter time `time`; for the path engine's first hit). (The test whether
/// anything moves is inlined: most hits are on still objects.)
#[inline]
pub fn hit_motion(world: &World, hit: &Hit, point: Vec3A, time: f32) -> Vec3A {
    let inst = &world.instances[hit.instance as usize];
    let mesh = &world.meshes[inst.mesh as usize];
    if inst.motion_to_world.is_none() && mesh.motion.is_empty() {
        // Nothing of it moves (`motion` would add nothing): skip building a state.
        return Vec3A::ZERO;
    }
    moving_hit_motion(inst, mesh, hit, point, time)
}

/// [`hit_motion`] on an instance or mesh that moves.
#[inline(never)]
fn moving_hit_motion(
    inst: &crate::world::InstanceData,
    mesh: &crate::mesh::MeshData,
    hit: &Hit,
    point: Vec3A,
    time: f32,
) -> Vec3A {
    let tri = mesh.triangles[hit.prim as usize].map(|i| i as usize);
    let s = State {
        point,
        bary: [1.0 - hit.u - hit.v, hit.u, hit.v],
        hair: mesh.hair.as_ref().map(|_| shader::state::HairState::default()),
        time,
        ..State::default()
    };
    motion(inst, mesh, tri, &s)
}

/// The raster position (pixels, origin at the lower left as mental ray's raster space) of
/// world point `p`, or `None` behind a perspective camera.
pub fn raster_position(cam: &crate::camera::CameraModel, p: Vec3A) -> Option<Vec2> {
    let c = cam.world_to_camera.transform_point3a(p);
    let (w, h) = (cam.width as f32, cam.height as f32);
    let sx = cam.aperture / (cam.focal * w);
    let sy = cam.aperture / (cam.focal * cam.aspect * h);
    let (x, y) = if cam.orthographic {
        (c.x, c.y)
    } else {
        if c.z >= 0.0 {
            return None;
        }
        (c.x / -c.z, c.y / -c.z)
    };
    Some(Vec2::new(x / sx + w * 0.5 - cam.offset.0, y / sy + h * 0.5 - cam.offset.1))
}

/// The raster-space motion (pixels, y up) of world point `p` moving by `m`.
pub fn raster_motion(cam: &crate::camera::CameraModel, p: Vec3A, m: Vec3A) -> Vec2 {
    if m == Vec3A::ZERO {
        return Vec2::ZERO;
    }
    match (raster_position(cam, p), raster_position(cam, p + m)) {
        (Some(a), Some(b)) => b - a,
        _ => Vec2::ZERO,
    }
}

impl Tracer for SceneTracer<'_> {
    fn intersect(&self, s: &mut State, max_dist: f32) -> bool {
        self.count(false);
        let mut ray =
            Ray { mask: ray_mask(s.ray_type), origin: s.org, dir: s.dir, tmin: 0.0, tmax: max_dist, time: s.time };
        if s.ray_type == RayType::Eye {
            let cam = &self.world.camera;
            let r = cam.clip_ray(s.org, s.dir);
            ray.tmin = r.tmin;
            ray.tmax = ray.tmax.min(r.tmax);
        }
        let Some(hit) = self.accel.intersect(&ray) else { return false };
        fill_state(self.world, &hit, s);
        if s.ray_type == RayType::Eye && s.reflection_level == 0 && s.refraction_level == 0 {
            let first = self.first.get();
            if first.is_none() {
                self.first.set(Some(FirstHit { point: s.point, normal: s.normal, tag: s.label, motion: s.motion }));
                self.first_motion.set(s.motion);
            }
        }
        true
    }

    fn shadow_hits(&self, s: &State, max_dist: f32, visit: &mut dyn FnMut(&State) -> bool) {
        let mut origin = s.org;
        let mut remaining = max_dist;
        // A shadow ray crosses at most this many surfaces before it counts as blocked.
        for _ in 0..64 {
            self.count(true);
            let ray = Ray { mask: mask::SHADOW, origin, dir: s.dir, tmin: 0.0, tmax: remaining, time: s.time };
            let Some(hit) = self.accel.intersect(&ray) else { return };
            let mut h = s.child(RayType::Shadow, origin, s.dir);
            h.light = s.light;
            fill_state(self.world, &hit, &mut h);
            if !visit(&h) {
                return;
            }
            origin = shader::trace::leave_point(h.point, h.point_error, h.normal_geom, s.dir);
            remaining -= hit.t;
            if remaining <= 0.0 {
                return;
            }
        }
        // Too many layers: treat the light as blocked.
        let mut h = s.child(RayType::Shadow, origin, s.dir);
        h.material = None;
        visit(&h);
    }

    fn boundary_hits(&self, s: &State, max_dist: f32, visit: &mut dyn FnMut(f32, Option<u32>) -> bool) {
        let mut origin = s.org;
        let mut remaining = max_dist;
        // As `shadow_hits`, each hit described by its distance and material only (and its
        // geometric normal, to leave it), as `fill_state` finds them.
        for _ in 0..64 {
            self.count(true);
            let ray = Ray { mask: mask::SHADOW, origin, dir: s.dir, tmin: 0.0, tmax: remaining, time: s.time };
            let Some(hit) = self.accel.intersect(&ray) else { return };
            let inst = &self.world.instances[hit.instance as usize];
            let mesh = &self.world.meshes[inst.mesh as usize];
            let slot = mesh.slots.get(hit.prim as usize).copied().unwrap_or(0) as usize;
            let material = inst.materials.get(slot).copied().and_then(|m| m.checked_sub(1));
            let (point, ng, err) = if mesh.hair.is_some() {
                let mut h = s.child(RayType::Shadow, origin, s.dir);
                fill_state(self.world, &hit, &mut h);
                (h.point, h.normal_geom, h.point_error)
            } else {
                let tri = mesh.triangles[hit.prim as usize];
                let [p0, p1, p2] = mesh.triangle_at(tri, s.time);
                let placed = inst.placement(s.time);
                let ng = (placed.normal_to_world * (p1 - p0).cross(p2 - p0)).normalize_or(Vec3A::Z);
                (origin + s.dir * hit.t, ng, shader::trace::hit_error(p0, p1, p2, &placed.object_to_world))
            };
            if !visit(hit.t, material) {
                return;
            }
            origin = shader::trace::leave_point(point, err, ng, s.dir);
            remaining -= hit.t;
            if remaining <= 0.0 {
                return;
            }
        }
        // Too many layers: treat the light as blocked.
        visit(0.0, None);
    }

    fn shadow_blocked(&self, org: Vec3A, dir: Vec3A, max_dist: f32, time: f32) -> bool {
        // The ray of `shadow_hits`' first query, as an any-hit query that stops at the
        // first surface it finds.
        self.count(true);
        self.accel.occluded(&Ray { mask: mask::SHADOW, origin: org, dir, tmin: 0.0, tmax: max_dist, time })
    }

    fn shadow_blocked_batch(&self, queries: &[ShadowQuery], time: f32, blocked: &mut [bool]) {
        // In packets of at most eight (a light's samples from one point), on the stack.
        for (queries, blocked) in queries.chunks(8).zip(blocked.chunks_mut(8)) {
            let mut rays =
                [Ray { mask: mask::SHADOW, origin: Vec3A::ZERO, dir: Vec3A::Z, tmin: 0.0, tmax: 0.0, time }; 8];
            for (ray, q) in rays.iter_mut().zip(queries) {
                (ray.origin, ray.dir, ray.tmax) = (q.org, q.dir, q.max_dist);
            }
            let mut c = self.counts.get();
            c.shadow_rays += queries.len() as u64;
            self.counts.set(c);
            self.accel.occluded_batch(&rays[..queries.len()], blocked);
        }
    }

    fn triangle(&self, hit: &State, data: VertexData) -> Option<[Vec3A; 3]> {
        let inst = self.world.instances.get(hit.geometry as usize)?;
        let mesh = &self.world.meshes[inst.mesh as usize];
        let tri = mesh.triangles.get(hit.prim as usize)?.map(|i| i as usize);
        let placed = inst.placement(hit.time);
        match data {
            VertexData::Point => {
                let p = mesh.triangle_at(tri.map(|i| i as u32), hit.time);
                Some(p.map(|p| placed.object_to_world.transform_point3a(p)))
            }
            VertexData::Normal if !mesh.has_normals() => Some([hit.normal_geom; 3]),
            VertexData::Normal => {
                Some(tri.map(|i| (placed.normal_to_world * mesh.normal(i as u32)).normalize_or_zero()))
            }
            VertexData::Motion if mesh.motion.is_empty() => Some([Vec3A::ZERO; 3]),
            VertexData::Motion => {
                Some(tri.map(|i| {
                    placed.object_to_world.transform_vector3a(mesh.motion.get(i).copied().unwrap_or_default())
                }))
            }
            VertexData::Texture(k) => mesh.textures.get(k).map(|t| tri.map(|i| t[i])),
            VertexData::User(k) => {
                let u = mesh.user.get(k)?;
                let [a, b, c] = tri.map(|i| u.get(i).copied());
                Some([Vec3A::from(a?), Vec3A::from(b?), Vec3A::from(c?)])
            }
        }
    }

    fn fb_put(&self, buffer: u32, value: Color) -> bool {
        if (buffer as usize) < self.world.user_buffers.len() {
            self.fb.borrow_mut().push((buffer, value));
            true
        } else {
            false
        }
    }

    fn fb_named(&self, name: &str) -> Option<u32> {
        if name == maya::glow::BUFFER {
            // Maya materials' glow: the buffer the state shader names, or the world's own.
            return self.world.glow_buffer;
        }
        self.world.user_buffers.iter().position(|(n, _)| n == name).map(|i| i as u32)
    }

    fn fg_cache(&self) -> Option<&shader::fgcache::FgCache> {
        self.fg_cache
    }

    #[inline]
    fn light_motion(&self, light: u32, time: f32) -> Option<glam::Affine3A> {
        let keys = self.world.light_motion.get(light as usize)?;
        (!keys.is_empty()).then(|| crate::motion::lerp_keys(keys, time))
    }

    fn light_mesh(&self, light: u32, time: f32) -> Option<shader::light::MeshShape> {
        self.world.light_meshes.get(light as usize)?.as_ref()?.at(time)
    }

    fn surface_scatter(&self, hit: &State) -> Option<shader::SurfaceScatter> {
        // The shading state's material is the scene's; the world's list starts with the
        // default material.
        let m = self.world.materials.get(hit.material? as usize + 1)?;
        let mut h = m.constant();
        if let material::Varying::Evaluated(e) = &m.varying {
            e.0.apply(hit, &mut h);
        }
        let facing = h.normal.unwrap_or(hit.normal);
        // Materials light enters keep their geometric orientation (as the path engine
        // does): from inside, the frame's normal points away from the ray.
        let normal = if m.has_inside() && hit.inv_normal { -facing } else { facing };
        let frame = bsdf::Frame::from_normal(normal);
        let wo = frame.to_local(-hit.dir);
        // A spot or measured EDF's radiance follows its shape about the surface's own
        // normal (as the path engine's hits see it: nothing behind the surface);
        // Lambertian otherwise.
        let surface_normal = if hit.inv_normal { -hit.normal } else { hit.normal };
        let spread =
            h.emission_shape.as_deref().map_or(bsdf::Rgb::ONE, |e| e.factor(surface_normal, h.tangent, -hit.dir));
        Some(shader::SurfaceScatter {
            bsdf: h.model.bsdf_in(h.diffuse, wo, &frame),
            frame,
            diffuse: h.diffuse,
            emission: h.emission * spread,
        })
    }
}

/// The area of the quad-mesh Ptex face a hit at barycentrics `bary` on triangle `prim` of
/// `mesh` lies on, over the triangle's (a displaced mesh's faces are its original
/// triangles': the finer triangle's share of its original divides); 2, a quad's, where
/// unknown.
fn ptex_face_ratio(mesh: &crate::mesh::MeshData, prim: usize, bary: [f32; 3]) -> f32 {
    use scene::mesh::ptex_ngons::face_area_ratio;
    let ratio = if let Some(split) = &mesh.ptex_split {
        let share = f64::from(split.area_share(prim));
        split
            .original(prim, bary)
            .and_then(|(t, _)| {
                face_area_ratio(&split.codes, &split.ngons, &split.refined, &split.triangles, &split.positions, t)
            })
            .filter(|_| share > 0.0)
            .map(|r| r / share)
    } else {
        face_area_ratio(&mesh.ptex_quads, &mesh.ptex_ngons, &mesh.ptex_refined, &mesh.triangles, &mesh.positions, prim)
    };
    ratio.filter(|r| r.is_finite() && *r > 0.0).map_or(2.0, |r| r as f32)
}

/// How the quad-mesh Ptex face coordinates `at` (face, u, v) of a hit at barycentrics
/// `bary` on triangle `prim` of `mesh` change with the barycentrics b1 and b2
/// ([`State::ptex_quad_jacobian`]): differences over a step of 2⁻⁸ along each (exact where
/// the face's (u, v) are affine on the triangle, as on a quad's; a sub-quad's bilinear map
/// to within the step), backward where the forward step leaves the face; zero where both
/// do.
fn ptex_quad_jacobian(mesh: &crate::mesh::MeshData, prim: usize, bary: [f32; 3], at: (u32, f32, f32)) -> [f32; 4] {
    const STEP: f32 = 1.0 / 256.0;
    let column = |k: usize| {
        [STEP, -STEP].into_iter().find_map(|h| {
            let mut b = bary;
            b[0] -= h;
            b[k] += h;
            let (face, u, v) = ptex_quad_face(mesh, prim, b)?;
            (face == at.0).then(|| [(u - at.1) / h, (v - at.2) / h])
        })
    };
    match (column(1), column(2)) {
        (Some([a, b]), Some([c, d])) => [a, b, c, d],
        _ => [0.0; 4],
    }
}

/// The quad-mesh Ptex face and (u, v) of a hit at barycentrics `bary` on triangle `prim`
/// of `mesh` (`None` where the mesh keeps no such table or the triangle has no face).
fn ptex_quad_face(mesh: &crate::mesh::MeshData, prim: usize, bary: [f32; 3]) -> Option<(u32, f32, f32)> {
    if let Some(split) = &mesh.ptex_split {
        return split.face_uv(prim, bary);
    }
    if mesh.ptex_quads.is_empty() {
        return None;
    }
    scene::mesh::ptex_ngons::hit_face_uv(
        &mesh.ptex_quads,
        &mesh.ptex_ngons,
        &mesh.ptex_refined,
        &mesh.triangles,
        &mesh.positions,
        prim,
        bary,
    )
}
