//! The pure-Rust backend: compressed 8-wide BVHs (Ylitie et al. 2017, built by PLOC with
//! reinsertion, from the `obvhs` crate). Instances of meshes used once are merged into one
//! world-space BVH; meshes used by several instances get one BVH each, shared, under a
//! BVH over those instances' world bounds. Rays enter an instance's BVH transformed to its
//! object space (the parameter t is the same in both spaces, since the direction is not
//! renormalised).
//!
//! Moving geometry (see [`crate::motion`]) lives apart from the static: its triangles keep
//! their vertices at each key over the shutter, in BVHs whose boxes move with them
//! ([`moving`]: each node's box at both ends of an interval between keys, interpolated to
//! the ray's time), and are intersected where they are at the ray's time; moving instances
//! of shared meshes are bounded by the union of their boxes over the shutter and enter at
//! the ray's time. A static scene has none of them and traces exactly as before.

mod moving;
mod parts;

use moving::{KeySet, MovingBvh, MovingTri};

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

struct MeshBvh<'w> {
    bvh: CwBvh,
    tris: Vec<Tri>,
    /// The mesh's triangles when its vertices move (then `tris` is empty).
    moving: Option<MovingBvh<'w>>,
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

/// The triangles of mesh `m` as moving triangles of key set `set` and instance `instance`.
fn moving_triangles(m: &crate::mesh::MeshData, set: usize, instance: u32) -> impl Iterator<Item = MovingTri> + '_ {
    m.triangles.iter().enumerate().map(move |(i, &v)| MovingTri { v, set: set as u32, index: i as u32, instance })
}

/// Two-level BVH over a [`World`], with singly-used meshes flattened into world space.
pub struct BvhAccel<'w> {
    meshes: Vec<MeshBvh<'w>>,
    instances: Vec<InstanceRef>,
    /// Instances of the top-level BVH (its primitive i is instance `tlas_instances[i]`).
    tlas_instances: Vec<u32>,
    tlas: Option<CwBvh>,
    /// The world-space BVH of the flattened instances.
    flat: Option<MeshBvh<'w>>,
    /// The world-space BVH of the flattened instances that move.
    flat_moving: Option<MovingBvh<'w>>,
}

/// A BVH over triangles (each carrying its mesh index and instance), which it keeps in
/// its leaf order ([`sort_into_bvh`]).
fn triangle_bvh(mut tris: Vec<Tri>, params: BvhBuildParams) -> MeshBvh<'static> {
    if tris.is_empty() {
        return MeshBvh { bvh: CwBvh::default(), tris, moving: None };
    }
    let mut bvh = sort_into_bvh(&mut tris, params);
    // The triangles are in leaf order: the map to the order they came in is not needed.
    bvh.primitive_indices = Vec::new();
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

/// The ray obvhs traverses in `bvh` for `origin + t·dir`, t in [tmin, tmax], and how far
/// back along it that one starts (`shift`, in units of t: obvhs's distance t′ is
/// t + `shift`; a leaf's triangles are still tested with the ray itself, and what the
/// callback returns to obvhs is t′).
///
/// The start is moved back because obvhs 0.4's node test raises every box's entry
/// distance to at least an absolute 1e-4 (where the ray's tmin was meant), which drops
/// boxes the ray leaves within 1e-4 of its origin — and its box distances are differences
/// of terms as large as the node's extent over the direction's component, so a flat box
/// (one face) at the origin came out anywhere within that rounding of it: such boxes were
/// not entered, and a probe ray starting 5e-5 before a box's side found its far side
/// (`mia_roundcorners` on the Rust backend; docs/performance.md, movingbvh49). Moved back
/// by 2e-4 plus eight times that rounding, only boxes wholly behind the origin are dropped.
/// (Directions within 1e-3 of parallel to an axis plane are not counted in the rounding: a
/// flat box along that axis is one the ray runs along, and counting them would start an
/// axis-aligned ray — a sun's shadow ray — far behind.)
///
/// Negative zeros in the direction become positive: obvhs picks the traversal octant from
/// the comparison `d < 0` but inverts −0 to −1/ε, and the two disagreeing made rays
/// straight down an axis (shadow rays towards a sun at (0, 0, −1) ⇒ direction (−0, −0, 1))
/// miss.
fn traversal_ray(bvh: &CwBvh, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> (BvhRay, f32) {
    let dir = dir + Vec3A::ZERO;
    let longest = dir.abs().max_element().max(f32::MIN_POSITIVE);
    let shortest = dir.abs().min_element().max(longest * 1e-3);
    let extent = bvh.total_aabb.min.abs().max(bvh.total_aabb.max.abs()).max_element() + origin.abs().max_element();
    // At most 1e30: a zero direction (a ray from a point to itself) leaves the origin.
    let shift = (2e-4 + 8.0 * f32::EPSILON * extent / shortest).min(1e30);
    (BvhRay::new(origin - dir * shift, dir, tmin + shift, tmax + shift), shift)
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

impl<'w> BvhAccel<'w> {
    /// Builds the BVHs of a world (reading moving meshes' keys in place: it borrows the
    /// world).
    pub fn new(world: &'w World) -> BvhAccel<'w> {
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
                    let tris = moving_triangles(m, 0, 0).collect();
                    let mut empty = triangle_bvh(Vec::new(), params);
                    empty.moving = MovingBvh::build(vec![KeySet::Borrowed(&m.position_keys)], tris);
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
                // The mesh's own keys where it is placed at the identity (as Embree reads
                // them), world-space copies where it is placed elsewhere or its instance moves.
                let keys = if m.moves() && !inst.moves() && inst.object_to_world == glam::Affine3A::IDENTITY {
                    KeySet::Borrowed(&m.position_keys)
                } else {
                    KeySet::Owned(crate::world::world_key_positions(inst, m))
                };
                moving_keys.push((k as u32, keys));
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
        let moving_tris = moving_keys
            .iter()
            .enumerate()
            .flat_map(|(set, (k, _))| {
                moving_triangles(&world.meshes[world.instances[*k as usize].mesh as usize], set, *k)
            })
            .collect();
        let sets: Vec<KeySet> = moving_keys.into_iter().map(|(_, keys)| keys).collect();
        let flat_moving = MovingBvh::build(sets, moving_tris);
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
        let (bvh_ray, shift) = traversal_ray(&flat.bvh, ray.origin, ray.dir, ray.tmin, ray.tmax);
        flat.bvh.ray_traverse(bvh_ray, &mut hit, |_, id| {
            let t = &flat.tris[id];
            if self.instances[t.instance as usize].mask & ray.mask == 0 {
                return f32::INFINITY;
            }
            match t.hit(&Ray { tmax: found, ..*ray }) {
                Some((d, u, v)) => {
                    found = d;
                    *best = Some(Hit { t: d, instance: t.instance, prim: t.index, u, v });
                    d + shift
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
        let mut reach = local.tmax;
        let mut hit = RayHit::none();
        let (bvh_ray, shift) = traversal_ray(&mesh.bvh, local.origin, local.dir, local.tmin, local.tmax);
        mesh.bvh.ray_traverse(bvh_ray, &mut hit, |_, id| {
            let t = &mesh.tris[id];
            match t.hit(&Ray { tmax: reach, ..local }) {
                Some((d, u, v)) => {
                    if d < found {
                        found = d;
                        *best = Some(Hit { t: d, instance, prim: t.index, u, v });
                    }
                    reach = reach.min(d);
                    d + shift
                }
                None => f32::INFINITY,
            }
        });
        found
    }
}

impl BvhAccel<'_> {
    /// Bytes of the BVHs' nodes, primitive indices and triangle copies.
    fn heap_bytes(&self) -> u64 {
        fn bvh_bytes(b: &CwBvh) -> usize {
            std::mem::size_of_val(&b.nodes[..])
                + std::mem::size_of_val(&b.primitive_indices[..])
                + b.exact_node_aabbs.as_ref().map_or(0, |a| std::mem::size_of_val(&a[..]))
        }
        fn moving_bytes(m: &MovingBvh) -> usize {
            m.heap_bytes()
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

impl Accel for BvhAccel<'_> {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut best = None;
        let mut tmax = self.intersect_flat(ray, &mut best);
        if let Some(moving) = &self.flat_moving {
            let accept = |t: &MovingTri| self.instances[t.instance as usize].mask & ray.mask != 0;
            tmax = moving.closest(&Ray { tmax, ..*ray }, None, accept, &mut best);
        }
        let Some(tlas) = self.tlas.as_ref() else { return best };
        let mut hit = RayHit::none();
        let (bvh_ray, shift) = traversal_ray(tlas, ray.origin, ray.dir, ray.tmin, tmax);
        let mut reach = tmax;
        tlas.ray_traverse(bvh_ray, &mut hit, |_, id| {
            let instance = self.tlas_instances[tlas.primitive_indices[id] as usize];
            let found = self.intersect_instance(ray, reach, instance, &mut best);
            reach = reach.min(found);
            found + shift
        });
        best
    }

    fn occluded(&self, ray: &Ray) -> bool {
        if let Some(flat) = &self.flat {
            let (bvh_ray, _) = traversal_ray(&flat.bvh, ray.origin, ray.dir, ray.tmin, ray.tmax);
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
        let (bvh_ray, _) = traversal_ray(tlas, ray.origin, ray.dir, ray.tmin, ray.tmax);
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
            let (bvh_ray, _) = traversal_ray(&mesh.bvh, local.origin, local.dir, local.tmin, local.tmax);
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

/// A deterministic stream of numbers in [0, 1) for the BVH tests (a 64-bit LCG's top 24
/// bits).
#[cfg(test)]
fn test_numbers(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 40) as f32) / (1u64 << 24) as f32
    }
}
