//! The pure-Rust backend: a compressed 8-wide BVH (Ylitie et al. 2017, built by PLOC with
//! reinsertion, from the `obvhs` crate) per mesh, and one over the instances' world
//! bounds. Rays enter an instance's BVH transformed to its object space (the parameter t
//! is the same in both spaces, since the direction is not renormalised).

use glam::Vec3A;
use obvhs::aabb::Aabb;
use obvhs::cwbvh::builder::{build_cwbvh, build_cwbvh_from_tris};
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as BvhRay, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;

use super::{intersect_triangle, Accel, Backend, Hit};
use crate::integrator::mask;
use crate::ray::Ray;
use crate::world::World;

/// A triangle in BVH order: its vertices and its index in the mesh.
#[derive(Clone, Copy)]
struct Tri {
    p0: Vec3A,
    p1: Vec3A,
    p2: Vec3A,
    index: u32,
}

struct MeshBvh {
    bvh: CwBvh,
    tris: Vec<Tri>,
}

struct InstanceRef {
    mesh: u32,
    world_to_object: glam::Affine3A,
    mask: u32,
}

/// Two-level BVH over a [`World`].
pub struct BvhAccel {
    meshes: Vec<MeshBvh>,
    instances: Vec<InstanceRef>,
    tlas: Option<CwBvh>,
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
    m
}

impl BvhAccel {
    /// Builds the BVHs of a world.
    pub fn new(world: &World) -> BvhAccel {
        let params = BvhBuildParams::medium_build();
        let meshes = world
            .meshes
            .iter()
            .map(|m| {
                let source: Vec<Triangle> = m
                    .triangles
                    .iter()
                    .map(|t| Triangle {
                        v0: m.positions[t[0] as usize],
                        v1: m.positions[t[1] as usize],
                        v2: m.positions[t[2] as usize],
                    })
                    .collect();
                if source.is_empty() {
                    return MeshBvh { bvh: CwBvh::default(), tris: Vec::new() };
                }
                let bvh = build_cwbvh_from_tris(&source, params, &mut Default::default());
                let tris = bvh
                    .primitive_indices
                    .iter()
                    .map(|&i| {
                        let t = &source[i as usize];
                        Tri { p0: t.v0, p1: t.v1, p2: t.v2, index: i }
                    })
                    .collect();
                MeshBvh { bvh, tris }
            })
            .collect();
        let instances: Vec<InstanceRef> = world
            .instances
            .iter()
            .map(|i| InstanceRef { mesh: i.mesh, world_to_object: i.world_to_object, mask: instance_mask(&i.flags) })
            .collect();
        let bounds: Vec<Aabb> = world
            .instances
            .iter()
            .map(|i| {
                let mut b = Aabb::empty();
                for p in &world.meshes[i.mesh as usize].positions {
                    b.extend(i.object_to_world.transform_point3a(*p));
                }
                b
            })
            .collect();
        let tlas = (!bounds.is_empty()).then(|| build_cwbvh(&bounds, params, &mut Default::default()));
        BvhAccel { meshes, instances, tlas }
    }

    /// Closest hit in one instance, updating `best`; returns the new closest distance.
    fn intersect_instance(&self, ray: &Ray, tmax: f32, instance: u32, best: &mut Option<Hit>) -> f32 {
        let inst = &self.instances[instance as usize];
        if inst.mask & ray.mask == 0 {
            return f32::INFINITY;
        }
        let mesh = &self.meshes[inst.mesh as usize];
        let local = Ray {
            origin: inst.world_to_object.transform_point3a(ray.origin),
            dir: inst.world_to_object.transform_vector3a(ray.dir),
            tmin: ray.tmin,
            tmax,
            mask: ray.mask,
        };
        let mut found = f32::INFINITY;
        let mut hit = RayHit::none();
        let bvh_ray = BvhRay::new(local.origin, local.dir, local.tmin, local.tmax);
        mesh.bvh.ray_traverse(bvh_ray, &mut hit, |r, id| {
            let t = &mesh.tris[id];
            match intersect_triangle(&Ray { tmax: r.tmax, ..local }, t.p0, t.p1, t.p2) {
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

impl Accel for BvhAccel {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let tlas = self.tlas.as_ref()?;
        let mut best = None;
        let mut hit = RayHit::none();
        let bvh_ray = BvhRay::new(ray.origin, ray.dir, ray.tmin, ray.tmax);
        tlas.ray_traverse(bvh_ray, &mut hit, |r, id| {
            let instance = tlas.primitive_indices[id];
            self.intersect_instance(ray, r.tmax, instance, &mut best)
        });
        best
    }

    fn occluded(&self, ray: &Ray) -> bool {
        let Some(tlas) = self.tlas.as_ref() else { return false };
        let bvh_ray = BvhRay::new(ray.origin, ray.dir, ray.tmin, ray.tmax);
        !tlas.ray_traverse_miss(bvh_ray, |_, id| {
            let inst = &self.instances[tlas.primitive_indices[id] as usize];
            if inst.mask & ray.mask == 0 {
                return f32::INFINITY;
            }
            let mesh = &self.meshes[inst.mesh as usize];
            let local = Ray {
                origin: inst.world_to_object.transform_point3a(ray.origin),
                dir: inst.world_to_object.transform_vector3a(ray.dir),
                ..*ray
            };
            let bvh_ray = BvhRay::new(local.origin, local.dir, local.tmin, local.tmax);
            let missed = mesh.bvh.ray_traverse_miss(bvh_ray, |_, id| {
                let t = &mesh.tris[id];
                intersect_triangle(&local, t.p0, t.p1, t.p2).map_or(f32::INFINITY, |h| h.0)
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
}
