//! The pure-Rust backend: compressed 8-wide BVHs (Ylitie et al. 2017, built by PLOC with
//! reinsertion, from the `obvhs` crate). Instances of meshes used once are merged into one
//! world-space BVH; meshes used by several instances get one BVH each, shared, under a
//! BVH over those instances' world bounds. Rays enter an instance's BVH transformed to its
//! object space (the parameter t is the same in both spaces, since the direction is not
//! renormalised).
//!
//! Moving geometry (see [`crate::motion`]) lives apart from the static: its triangles keep
//! their vertices at each key over the shutter, are bounded by the union of their boxes
//! at the keys (which holds the triangle at every time in between, since the vertices move
//! linearly from key to key) and are intersected where they are at the ray's time; moving
//! instances of shared meshes are bounded the same way and enter at the ray's time. A
//! static scene has none of them and traces exactly as before.

mod parts;

use glam::Vec3A;
use obvhs::aabb::Aabb;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as BvhRay, RayHit};
use obvhs::BvhBuildParams;
use rayon::prelude::*;

use super::{intersect_triangle, Accel, Backend, Hit};
use crate::ray::mask;
use crate::ray::Ray;
use crate::world::World;

/// A triangle in BVH order: its vertices, its index in the mesh and (for the world-space
/// BVH) its instance; 44 bytes, where 16-byte-aligned vertices took 64.
#[derive(Clone, Copy)]
struct Tri {
    p0: glam::Vec3,
    p1: glam::Vec3,
    p2: glam::Vec3,
    index: u32,
    instance: u32,
}

const _: () = assert!(std::mem::size_of::<Tri>() == 44);

impl Tri {
    /// A triangle of vertices `p0`, `p1`, `p2`.
    fn new(p0: Vec3A, p1: Vec3A, p2: Vec3A, index: u32, instance: u32) -> Tri {
        Tri { p0: p0.into(), p1: p1.into(), p2: p2.into(), index, instance }
    }

    /// Its three vertices.
    #[inline(always)]
    fn corners(&self) -> [Vec3A; 3] {
        [self.p0.into(), self.p1.into(), self.p2.into()]
    }

    /// Where `ray` hits it, as [`intersect_triangle`] finds it.
    #[inline(always)]
    fn hit(&self, ray: &Ray) -> Option<(f32, f32, f32)> {
        let [p0, p1, p2] = self.corners();
        intersect_triangle(ray, p0, p1, p2)
    }
}

impl obvhs::Boundable for Tri {
    /// The box of its vertices (the box obvhs's own triangles give the same vertices).
    fn aabb(&self) -> Aabb {
        Aabb::from_points(&self.corners())
    }
}

struct MeshBvh {
    bvh: CwBvh,
    tris: Vec<Tri>,
    /// The mesh's triangles when its vertices move (then `tris` is empty).
    moving: Option<MovingBvh>,
}

/// A moving triangle in BVH order: where its keys start in [`MovingBvh::verts`], how many
/// there are, its index in the mesh and its instance.
#[derive(Clone, Copy)]
struct MovingTri {
    first: u32,
    keys: u32,
    index: u32,
    instance: u32,
}

/// A moving triangle to build from: its index in the mesh, its instance, its vertex
/// indices and its mesh's vertex positions at each key.
type MovingSource<'k> = (u32, u32, [u32; 3], &'k [Vec<Vec3A>]);

/// A BVH over moving triangles, bounded over the whole shutter.
struct MovingBvh {
    bvh: CwBvh,
    tris: Vec<MovingTri>,
    /// Each triangle's vertices at each of its keys.
    verts: Vec<[Vec3A; 3]>,
}

impl MovingBvh {
    /// A BVH over the triangles `tris` (index in the mesh, instance) of meshes whose vertex
    /// keys are `keys` (one list of positions per key, evenly over the shutter).
    fn build(source: Vec<MovingSource>, params: BvhBuildParams) -> Option<MovingBvh> {
        if source.is_empty() {
            return None;
        }
        let mut tris = Vec::with_capacity(source.len());
        let mut verts = Vec::new();
        let mut boxes = Vec::with_capacity(source.len());
        for (index, instance, tri, keys) in source {
            let mut b = Aabb::empty();
            tris.push(MovingTri { first: verts.len() as u32, keys: keys.len() as u32, index, instance });
            for key in keys {
                let v = tri.map(|i| key[i as usize]);
                for p in v {
                    b.extend(p);
                }
                verts.push(v);
            }
            boxes.push(b);
        }
        let bvh = build_cwbvh(&boxes, params, &mut Default::default());
        let tris = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
        Some(MovingBvh { bvh, tris, verts })
    }

    /// The vertices of `t` at shutter time `time`.
    #[inline]
    fn at(&self, t: &MovingTri, time: f32) -> [Vec3A; 3] {
        let first = t.first as usize;
        if t.keys < 2 {
            return self.verts[first];
        }
        let (j, f) = crate::motion::key_segment(t.keys as usize, time);
        let (a, b) = (self.verts[first + j], self.verts[first + j + 1]);
        [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f]
    }

    /// The closest hit of `ray` among triangles that `accept` lets through, updating
    /// `best` (the hit's instance is `instance` if given, else the triangle's); returns the
    /// closest distance found (`ray.tmax` if none).
    fn closest(
        &self,
        ray: &Ray,
        instance: Option<u32>,
        accept: impl Fn(&MovingTri) -> bool,
        best: &mut Option<Hit>,
    ) -> f32 {
        let mut found = ray.tmax;
        let mut hit = RayHit::none();
        let bvh_ray = traversal_ray(ray.origin, ray.dir, ray.tmin, ray.tmax);
        self.bvh.ray_traverse(bvh_ray, &mut hit, |r, id| {
            let t = &self.tris[id];
            if !accept(t) {
                return f32::INFINITY;
            }
            let [p0, p1, p2] = self.at(t, ray.time);
            match intersect_triangle(&Ray { tmax: r.tmax, ..*ray }, p0, p1, p2) {
                Some((d, u, v)) => {
                    if d < found {
                        found = d;
                        *best = Some(Hit { t: d, instance: instance.unwrap_or(t.instance), prim: t.index, u, v });
                    }
                    d
                }
                None => f32::INFINITY,
            }
        });
        found
    }

    /// Whether `ray` hits a triangle that `accept` lets through.
    fn any(&self, ray: &Ray, accept: impl Fn(&MovingTri) -> bool) -> bool {
        let bvh_ray = traversal_ray(ray.origin, ray.dir, ray.tmin, ray.tmax);
        !self.bvh.ray_traverse_miss(bvh_ray, |_, id| {
            let t = &self.tris[id];
            if !accept(t) {
                return f32::INFINITY;
            }
            let [p0, p1, p2] = self.at(t, ray.time);
            intersect_triangle(ray, p0, p1, p2).map_or(f32::INFINITY, |h| h.0)
        })
    }
}

struct InstanceRef {
    mesh: u32,
    world_to_object: glam::Affine3A,
    mask: u32,
    /// Object → world at keys over the shutter when the instance moves (else empty).
    keys: Vec<glam::Affine3A>,
}

impl InstanceRef {
    /// World → object at shutter time `time`.
    #[inline]
    fn world_to_object_at(&self, time: f32) -> glam::Affine3A {
        if self.keys.is_empty() {
            self.world_to_object
        } else {
            crate::motion::lerp_keys(&self.keys, time).inverse()
        }
    }
}

/// Two-level BVH over a [`World`], with singly-used meshes flattened into world space.
pub struct BvhAccel {
    meshes: Vec<MeshBvh>,
    instances: Vec<InstanceRef>,
    /// Instances of the top-level BVH (its primitive i is instance `tlas_instances[i]`).
    tlas_instances: Vec<u32>,
    tlas: Option<CwBvh>,
    /// The world-space BVH of the flattened instances.
    flat: Option<MeshBvh>,
    /// The world-space BVH of the flattened instances that move.
    flat_moving: Option<MovingBvh>,
}

/// A BVH over triangles (each carrying its mesh index and instance), which it keeps in
/// its leaf order ([`sort_into_bvh`]).
fn triangle_bvh(mut tris: Vec<Tri>, params: BvhBuildParams) -> MeshBvh {
    if tris.is_empty() {
        return MeshBvh { bvh: CwBvh::default(), tris, moving: None };
    }
    let bvh = sort_into_bvh(&mut tris, params);
    MeshBvh { bvh, tris, moving: None }
}

/// The 8-wide BVH of the triangles of `piece`, which it puts in the BVH's leaf order
/// (traversal names a triangle by its place in that order): the caller's array becomes
/// the one traversal reads, and no array of boxes or second array of the triangles is kept
/// beside it (a copy of the piece while it is put in order). `params` must not split
/// primitives (`pre_split`): each triangle is in one leaf.
fn sort_into_bvh(piece: &mut [Tri], params: BvhBuildParams) -> CwBvh {
    debug_assert!(!params.pre_split);
    let bvh = build_cwbvh(piece, params, &mut Default::default());
    let ordered: Vec<Tri> = bvh.primitive_indices.iter().map(|&i| piece[i as usize]).collect();
    piece.copy_from_slice(&ordered);
    bvh
}

/// The traversal ray for `origin + t·dir`, t in [tmin, tmax]. Negative zeros in the
/// direction become positive: obvhs picks the traversal octant from the comparison
/// `d < 0` but inverts −0 to −1/ε, and the two disagreeing made rays straight down an
/// axis (shadow rays towards a sun at (0, 0, −1) ⇒ direction (−0, −0, 1)) miss.
fn traversal_ray(origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> BvhRay {
    BvhRay::new(origin, dir + Vec3A::ZERO, tmin, tmax)
}

/// The ray kinds an instance accepts, from its flags.
pub fn instance_mask(flags: &scene::Flags) -> u32 {
    let mut m = 0;
    if flags.visible {
        m |= mask::CAMERA;
    }
    if flags.shadow.cast {
        m |= mask::SHADOW;
    }
    if flags.reflection.cast || flags.refraction.cast || flags.finalgather.cast {
        m |= mask::SECONDARY;
    }
    if flags.reflection.cast {
        m |= mask::REFLECT;
    }
    if flags.refraction.cast {
        m |= mask::REFRACT;
    }
    if flags.transparency.cast {
        m |= mask::TRANSPARENT;
    }
    if flags.finalgather.cast {
        m |= mask::FINALGATHER;
    }
    m
}

impl BvhAccel {
    /// Builds the BVHs of a world.
    pub fn new(world: &World) -> BvhAccel {
        let params = BvhBuildParams::medium_build();
        let flat = super::flat_instances(world);
        let mut shared = vec![false; world.meshes.len()];
        for (inst, f) in world.instances.iter().zip(&flat) {
            shared[inst.mesh as usize] |= !f;
        }
        let meshes = world
            .meshes
            .iter()
            .zip(&shared)
            .map(|(m, &used)| {
                if used && m.moves() {
                    let source =
                        m.triangles.iter().enumerate().map(|(i, t)| (i as u32, 0, *t, &m.position_keys[..])).collect();
                    let mut empty = triangle_bvh(Vec::new(), params);
                    empty.moving = MovingBvh::build(source, params);
                    return empty;
                }
                let source: Vec<Tri> = if used {
                    m.triangles
                        .iter()
                        .enumerate()
                        .map(|(i, t)| Tri::new(m.position(t[0]), m.position(t[1]), m.position(t[2]), i as u32, 0))
                        .collect()
                } else {
                    Vec::new()
                };
                parts::bvh_in_parts(source, params, parts::PART_TRIANGLES)
                    .unwrap_or_else(|| triangle_bvh(Vec::new(), params))
            })
            .collect();
        let instances: Vec<InstanceRef> = world
            .instances
            .iter()
            .map(|i| InstanceRef {
                mesh: i.mesh,
                world_to_object: i.world_to_object,
                mask: instance_mask(&i.flags),
                keys: i.keys.clone(),
            })
            .collect();
        let mut world_tris = Vec::new();
        let mut moving_keys = Vec::new();
        for (k, inst) in world.instances.iter().enumerate().filter(|(k, _)| flat[*k]) {
            let m = &world.meshes[inst.mesh as usize];
            if inst.moves() || m.moves() {
                moving_keys.push((k as u32, crate::world::world_key_positions(inst, m)));
                continue;
            }
            let w = |i: u32| inst.object_to_world.transform_point3a(m.position(i));
            world_tris.par_extend(
                m.triangles
                    .par_iter()
                    .enumerate()
                    .map(|(i, t)| Tri::new(w(t[0]), w(t[1]), w(t[2]), i as u32, k as u32)),
            );
        }
        let flat_bvh = parts::bvh_in_parts(world_tris, params, parts::PART_TRIANGLES);
        let moving_source = moving_keys
            .iter()
            .flat_map(|(k, keys)| {
                let m = &world.meshes[world.instances[*k as usize].mesh as usize];
                m.triangles.iter().enumerate().map(move |(i, t)| (i as u32, *k, *t, &keys[..]))
            })
            .collect();
        let flat_moving = MovingBvh::build(moving_source, params);
        let tlas_instances: Vec<u32> = (0..world.instances.len() as u32).filter(|k| !flat[*k as usize]).collect();
        let bounds: Vec<Aabb> = tlas_instances
            .iter()
            .map(|&k| {
                let i = &world.instances[k as usize];
                let mesh = &world.meshes[i.mesh as usize];
                let mut b = Aabb::empty();
                if i.moves() || mesh.moves() {
                    let (lo, hi) = crate::world::world_motion_bounds(i, mesh);
                    b.extend(lo);
                    b.extend(hi);
                    return b;
                }
                for p in mesh.vertex_positions() {
                    b.extend(i.object_to_world.transform_point3a(p.into()));
                }
                b
            })
            .collect();
        let tlas = (!bounds.is_empty()).then(|| build_cwbvh(&bounds, params, &mut Default::default()));
        BvhAccel { meshes, instances, tlas_instances, tlas, flat: flat_bvh, flat_moving }
    }

    /// Closest hit among the flattened instances, updating `best`.
    fn intersect_flat(&self, ray: &Ray, best: &mut Option<Hit>) -> f32 {
        let Some(flat) = &self.flat else { return ray.tmax };
        let mut found = ray.tmax;
        let mut hit = RayHit::none();
        let bvh_ray = traversal_ray(ray.origin, ray.dir, ray.tmin, ray.tmax);
        flat.bvh.ray_traverse(bvh_ray, &mut hit, |r, id| {
            let t = &flat.tris[id];
            if self.instances[t.instance as usize].mask & ray.mask == 0 {
                return f32::INFINITY;
            }
            match t.hit(&Ray { tmax: r.tmax, ..*ray }) {
                Some((d, u, v)) => {
                    found = d;
                    *best = Some(Hit { t: d, instance: t.instance, prim: t.index, u, v });
                    d
                }
                None => f32::INFINITY,
            }
        });
        found
    }

    /// Closest hit in one instance, updating `best`; returns the new closest distance.
    fn intersect_instance(&self, ray: &Ray, tmax: f32, instance: u32, best: &mut Option<Hit>) -> f32 {
        let inst = &self.instances[instance as usize];
        if inst.mask & ray.mask == 0 {
            return f32::INFINITY;
        }
        let mesh = &self.meshes[inst.mesh as usize];
        let world_to_object = inst.world_to_object_at(ray.time);
        let local = Ray {
            origin: world_to_object.transform_point3a(ray.origin),
            dir: world_to_object.transform_vector3a(ray.dir),
            tmin: ray.tmin,
            tmax,
            mask: ray.mask,
            time: ray.time,
        };
        if let Some(moving) = &mesh.moving {
            let found = moving.closest(&local, Some(instance), |_| true, best);
            return if found < tmax { found } else { f32::INFINITY };
        }
        let mut found = f32::INFINITY;
        let mut hit = RayHit::none();
        let bvh_ray = traversal_ray(local.origin, local.dir, local.tmin, local.tmax);
        mesh.bvh.ray_traverse(bvh_ray, &mut hit, |r, id| {
            let t = &mesh.tris[id];
            match t.hit(&Ray { tmax: r.tmax, ..local }) {
                Some((d, u, v)) => {
                    if d < found {
                        found = d;
                        *best = Some(Hit { t: d, instance, prim: t.index, u, v });
                    }
                    d
                }
                None => f32::INFINITY,
            }
        });
        found
    }
}

impl BvhAccel {
    /// Bytes of the BVHs' nodes, primitive indices and triangle copies.
    fn heap_bytes(&self) -> u64 {
        fn bvh_bytes(b: &CwBvh) -> usize {
            std::mem::size_of_val(&b.nodes[..])
                + std::mem::size_of_val(&b.primitive_indices[..])
                + b.exact_node_aabbs.as_ref().map_or(0, |a| std::mem::size_of_val(&a[..]))
        }
        fn moving_bytes(m: &MovingBvh) -> usize {
            bvh_bytes(&m.bvh) + std::mem::size_of_val(&m.tris[..]) + std::mem::size_of_val(&m.verts[..])
        }
        fn mesh_bytes(m: &MeshBvh) -> usize {
            bvh_bytes(&m.bvh) + std::mem::size_of_val(&m.tris[..]) + m.moving.as_ref().map_or(0, moving_bytes)
        }
        let bytes = self.meshes.iter().map(mesh_bytes).sum::<usize>()
            + self.tlas.as_ref().map_or(0, bvh_bytes)
            + self.flat.as_ref().map_or(0, mesh_bytes)
            + self.flat_moving.as_ref().map_or(0, moving_bytes)
            + std::mem::size_of_val(&self.instances[..])
            + std::mem::size_of_val(&self.tlas_instances[..]);
        bytes as u64
    }
}

impl Accel for BvhAccel {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut best = None;
        let mut tmax = self.intersect_flat(ray, &mut best);
        if let Some(moving) = &self.flat_moving {
            let accept = |t: &MovingTri| self.instances[t.instance as usize].mask & ray.mask != 0;
            tmax = moving.closest(&Ray { tmax, ..*ray }, None, accept, &mut best);
        }
        let Some(tlas) = self.tlas.as_ref() else { return best };
        let mut hit = RayHit::none();
        let bvh_ray = traversal_ray(ray.origin, ray.dir, ray.tmin, tmax);
        tlas.ray_traverse(bvh_ray, &mut hit, |r, id| {
            let instance = self.tlas_instances[tlas.primitive_indices[id] as usize];
            self.intersect_instance(ray, r.tmax, instance, &mut best)
        });
        best
    }

    fn occluded(&self, ray: &Ray) -> bool {
        if let Some(flat) = &self.flat {
            let bvh_ray = traversal_ray(ray.origin, ray.dir, ray.tmin, ray.tmax);
            let missed = flat.bvh.ray_traverse_miss(bvh_ray, |_, id| {
                let t = &flat.tris[id];
                if self.instances[t.instance as usize].mask & ray.mask == 0 {
                    return f32::INFINITY;
                }
                t.hit(ray).map_or(f32::INFINITY, |h| h.0)
            });
            if !missed {
                return true;
            }
        }
        if let Some(moving) = &self.flat_moving {
            if moving.any(ray, |t| self.instances[t.instance as usize].mask & ray.mask != 0) {
                return true;
            }
        }
        let Some(tlas) = self.tlas.as_ref() else { return false };
        let bvh_ray = traversal_ray(ray.origin, ray.dir, ray.tmin, ray.tmax);
        !tlas.ray_traverse_miss(bvh_ray, |_, id| {
            let inst = &self.instances[self.tlas_instances[tlas.primitive_indices[id] as usize] as usize];
            if inst.mask & ray.mask == 0 {
                return f32::INFINITY;
            }
            let mesh = &self.meshes[inst.mesh as usize];
            let world_to_object = inst.world_to_object_at(ray.time);
            let local = Ray {
                origin: world_to_object.transform_point3a(ray.origin),
                dir: world_to_object.transform_vector3a(ray.dir),
                ..*ray
            };
            if let Some(moving) = &mesh.moving {
                return if moving.any(&local, |_| true) { ray.tmin } else { f32::INFINITY };
            }
            let bvh_ray = traversal_ray(local.origin, local.dir, local.tmin, local.tmax);
            let missed = mesh.bvh.ray_traverse_miss(bvh_ray, |_, id| {
                let t = &mesh.tris[id];
                t.hit(&local).map_or(f32::INFINITY, |h| h.0)
            });
            if missed {
                f32::INFINITY
            } else {
                ray.tmin
            }
        })
    }

    fn backend(&self) -> Backend {
        Backend::Rust
    }

    fn memory(&self) -> Option<super::AccelMemory> {
        Some(super::AccelMemory { bytes: self.heap_bytes(), counted: true })
    }
}
