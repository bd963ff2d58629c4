//! The path engine's data at a surface hit: its point, normals, material and how far off
//! the surface its rays leave from ([`Surface`]), found from a hit ([`surface_into`]).

use glam::Vec3A;

use crate::accel::Hit;
use crate::ray::Ray;
use crate::world::World;

/// Surface data at a hit.
pub(super) struct Surface {
    /// The hit point (world space).
    pub(super) p: Vec3A,
    /// The unit geometric normal (world space, the triangle's counter-clockwise front).
    pub(super) ng: Vec3A,
    /// The unit shading normal (world space, on `ng`'s side).
    pub(super) ns: Vec3A,
    /// The material (an index into [`World::materials`]).
    pub(super) material: u32,
    /// The instance's label for the tag buffer.
    pub(super) tag: u32,
    /// How far `p` may lie off the surface as the intersector sees it (world units; see
    /// [`super::leave::hit_error`]): rays leave from that far off it ([`Surface::leave`]).
    pub(super) err: f32,
}

/// The unit geometric and shading normals (world space, the shading normal on the
/// geometric normal's side) the path engine shades the hit `hit` of `ray` with.
pub fn hit_normals(world: &World, ray: &Ray, hit: &Hit) -> (Vec3A, Vec3A) {
    let s = surface(world, ray, hit);
    (s.ng, s.ns)
}

impl Surface {
    /// A placeholder, overwritten by [`surface_into`] before it is read.
    pub(super) const UNSET: Surface =
        Surface { p: Vec3A::ZERO, ng: Vec3A::Z, ns: Vec3A::Z, material: 0, tag: 0, err: 0.0 };
}

/// The surface data of hit `hit` of `ray`.
#[inline]
pub(super) fn surface(world: &World, ray: &Ray, hit: &Hit) -> Surface {
    let mut s = Surface::UNSET;
    surface_into(world, ray, hit, &mut s);
    s
}

/// [`surface`] written to `out` (where the path loop keeps it: returned by value, it was
/// copied there and copied again out of the cutout loop).
#[inline(never)]
pub(super) fn surface_into(world: &World, ray: &Ray, hit: &Hit, out: &mut Surface) {
    let inst = &world.instances[hit.instance as usize];
    let mesh = &world.meshes[inst.mesh as usize];
    let tri = mesh.triangles[hit.prim as usize];
    let [i0, i1, i2] = tri;
    // Where the instance and its vertices are at the ray's time (see `crate::motion`).
    let placed = inst.placement(ray.time);
    let [p0, p1, p2] = mesh.triangle_at(tri, ray.time);
    let w = 1.0 - hit.u - hit.v;
    let p_obj = p0 * w + p1 * hit.u + p2 * hit.v;
    let p = placed.object_to_world.transform_point3a(p_obj);
    // The face's unit normal and hit-error bound: kept for instances that hold still
    // (the same numbers as computed here), else computed.
    let (ng, err) = match world.faces.get(hit.instance, hit.prim) {
        Some(face) => face,
        None => (
            crate::world::face_normal(&placed.normal_to_world, p0, p1, p2),
            super::leave::hit_error(p0, p1, p2, &placed.object_to_world),
        ),
    };
    let ns = if !mesh.has_normals() {
        ng
    } else {
        let n = mesh.normal(i0) * w + mesh.normal(i1) * hit.u + mesh.normal(i2) * hit.v;
        let n = (placed.normal_to_world * n).normalize_or(ng);
        mesh.sharpen(if n.dot(ng) < 0.0 { -n } else { n }, ng)
    };
    let slot = mesh.slots.get(hit.prim as usize).copied().unwrap_or(0) as usize;
    let material = inst.materials.get(slot).copied().unwrap_or(0);
    *out = Surface { p, ng, ns, material, tag: inst.tag, err };
}
