//! The pure-Rust backend: 8-wide BVHs (binary BVHs built by PLOC with reinsertion, by the
//! `obvhs` crate, collapsed into 8-wide nodes by [`collapse`] and traversed as [`wide`]
//! lays them out). Instances of meshes used once are merged into one
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

mod collapse;
mod moving;
mod parts;
mod wide;

use moving::{KeySet, MovingBvh, MovingTri};
use wide::WideBvh;

use glam::Vec3A;
use obvhs::aabb::Aabb;
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
    bvh: WideBvh,
    /// The triangles in the BVH's leaf order.
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
    /// Instances of the top-level BVH (its primitive i, in leaf order, is instance
    /// `tlas_instances[i]`).
    tlas_instances: Vec<u32>,
    tlas: Option<WideBvh>,
    /// The world-space BVH of the flattened instances.
    flat: Option<MeshBvh<'w>>,
    /// The world-space BVH of the flattened instances that move.
    flat_moving: Option<MovingBvh<'w>>,
}

/// A BVH over triangles (each carrying its mesh index and instance), which it keeps in
/// its leaf order ([`sort_into_bvh`]).
fn triangle_bvh(mut tris: Vec<Tri>, params: BvhBuildParams) -> MeshBvh<'static> {
    if tris.is_empty() {
        return MeshBvh { bvh: WideBvh::default(), tris, moving: None };
    }
    // The triangles are in leaf order: the map to the order they came in is not kept.
    let bvh = sort_into_bvh(&mut tris, params);
    MeshBvh { bvh, tris, moving: None }
}

/// The 8-wide BVH of the triangles of `piece` ([`collapse::build_wide`]), which it puts
/// in the BVH's leaf order (traversal names a triangle by its place in that order): the
/// caller's array becomes the one traversal reads, and no array of boxes or second array of
/// the triangles is kept beside it (a copy of the piece while it is put in order). `params`
/// must not split primitives (`pre_split`): each triangle is in one leaf.
fn sort_into_bvh(piece: &mut [Tri], params: BvhBuildParams) -> WideBvh {
    debug_assert!(!params.pre_split);
    let (bvh, order) = collapse::build_wide(piece, params);
    let ordered: Vec<Tri> = order.iter().map(|&i| piece[i as usize]).collect();
    piece.copy_from_slice(&ordered);
    bvh
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
        let tlas_members: Vec<u32> = (0..world.instances.len() as u32).filter(|k| !flat[*k as usize]).collect();
        let bounds: Vec<Aabb> = tlas_members
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
        let (tlas, tlas_order) = collapse::build_wide(&bounds, params);
        let tlas_instances = tlas_order.iter().map(|&i| tlas_members[i as usize]).collect();
        let tlas = (!bounds.is_empty()).then_some(tlas);
        BvhAccel { meshes, instances, tlas_instances, tlas, flat: flat_bvh, flat_moving }
    }

    /// Closest hit among the flattened instances, updating `best`; returns the new
    /// closest distance (`ray.tmax` if none).
    fn intersect_flat(&self, ray: &Ray, best: &mut Option<Hit>) -> f32 {
        let Some(flat) = &self.flat else { return ray.tmax };
        flat.bvh.closest(ray.origin, ray.dir, ray.tmin, ray.tmax, |id, reach| {
            let t = &flat.tris[id];
            if self.instances[t.instance as usize].mask & ray.mask == 0 {
                return reach;
            }
            match t.hit(&Ray { tmax: reach, ..*ray }) {
                Some((d, u, v)) => {
                    *best = Some(Hit { t: d, instance: t.instance, prim: t.index, u, v });
                    d
                }
                None => reach,
            }
        })
    }

    /// Closest hit in one instance within `tmax`, updating `best`; returns the new closest
    /// distance (`tmax` if none).
    fn intersect_instance(&self, ray: &Ray, tmax: f32, instance: u32, best: &mut Option<Hit>) -> f32 {
        let inst = &self.instances[instance as usize];
        if inst.mask & ray.mask == 0 {
            return tmax;
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
            return moving.closest(&local, Some(instance), |_| true, best).min(tmax);
        }
        mesh.bvh.closest(local.origin, local.dir, local.tmin, tmax, |id, reach| {
            let t = &mesh.tris[id];
            match t.hit(&Ray { tmax: reach, ..local }) {
                Some((d, u, v)) => {
                    *best = Some(Hit { t: d, instance, prim: t.index, u, v });
                    d
                }
                None => reach,
            }
        })
    }
}

impl BvhAccel<'_> {
    /// Bytes of the BVHs' nodes, primitive indices and triangle copies.
    fn heap_bytes(&self) -> u64 {
        fn bvh_bytes(b: &WideBvh) -> usize {
            b.heap_bytes()
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
        tlas.closest(ray.origin, ray.dir, ray.tmin, tmax, |id, reach| {
            self.intersect_instance(ray, reach, self.tlas_instances[id], &mut best)
        });
        best
    }

    fn occluded(&self, ray: &Ray) -> bool {
        if let Some(flat) = &self.flat {
            let blocked = flat.bvh.any(ray.origin, ray.dir, ray.tmin, ray.tmax, |id| {
                let t = &flat.tris[id];
                self.instances[t.instance as usize].mask & ray.mask != 0 && t.hit(ray).is_some()
            });
            if blocked {
                return true;
            }
        }
        if let Some(moving) = &self.flat_moving {
            if moving.any(ray, |t| self.instances[t.instance as usize].mask & ray.mask != 0) {
                return true;
            }
        }
        let Some(tlas) = self.tlas.as_ref() else { return false };
        tlas.any(ray.origin, ray.dir, ray.tmin, ray.tmax, |id| {
            let inst = &self.instances[self.tlas_instances[id] as usize];
            if inst.mask & ray.mask == 0 {
                return false;
            }
            let mesh = &self.meshes[inst.mesh as usize];
            let world_to_object = inst.world_to_object_at(ray.time);
            let local = Ray {
                origin: world_to_object.transform_point3a(ray.origin),
                dir: world_to_object.transform_vector3a(ray.dir),
                ..*ray
            };
            if let Some(moving) = &mesh.moving {
                return moving.any(&local, |_| true);
            }
            mesh.bvh.any(local.origin, local.dir, local.tmin, local.tmax, |id| mesh.tris[id].hit(&local).is_some())
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

/// `count` small triangles for the BVH tests, each with its corners within `spread` of a
/// point of the 100-unit cube (from the stream of `seed`), indexed 0… in `instance`.
#[cfg(test)]
fn test_scattered_triangles(seed: u64, count: u32, spread: f32, instance: u32) -> Vec<Tri> {
    let mut rnd = test_numbers(seed);
    (0..count)
        .map(|index| {
            let c = Vec3A::new(rnd(), rnd(), rnd()) * 100.0;
            let mut corner = || c + (Vec3A::new(rnd(), rnd(), rnd()) - 0.5) * (2.0 * spread);
            Tri::new(corner(), corner(), corner(), index, instance)
        })
        .collect()
}
