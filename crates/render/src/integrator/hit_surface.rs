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
    let w = 1.0 - hit.u - hit.v;
    // A kept face: the instance and its mesh hold still, and what the general path below
    // reads from them (vertices, normal, error bound, material) was read once, the same
    // numbers, when the world was built.
    if let Some(face) = world.faces.face(hit.instance, hit.prim) {
        let [p0, p1, p2] = face.vertices.map(Vec3A::from);
        let p_obj = p0 * w + p1 * hit.u + p2 * hit.v;
        let p = inst.object_to_world.transform_point3a(p_obj);
        let ng = Vec3A::from(face.ng);
        let ns = if face.smooth {
            let mesh = &world.meshes[inst.mesh as usize];
            shading_normal(mesh, mesh.triangles[hit.prim as usize], &inst.normal_to_world, hit, w, ng)
        } else {
            ng
        };
        *out = Surface { p, ng, ns, material: face.material, tag: inst.tag, err: face.err };
        return;
    }
    let mesh = &world.meshes[inst.mesh as usize];
    let tri = mesh.triangles[hit.prim as usize];
    // Where the instance and its vertices are at the ray's time (see `crate::motion`).
    let placed = inst.placement(ray.time);
    let [p0, p1, p2] = mesh.triangle_at(tri, ray.time);
    let p_obj = p0 * w + p1 * hit.u + p2 * hit.v;
    let p = placed.object_to_world.transform_point3a(p_obj);
    let ng = crate::world::face_normal(&placed.normal_to_world, p0, p1, p2);
    let err = super::leave::hit_error(p0, p1, p2, &placed.object_to_world);
    let ns = if !mesh.has_normals() { ng } else { shading_normal(mesh, tri, &placed.normal_to_world, hit, w, ng) };
    let slot = mesh.slots.get(hit.prim as usize).copied().unwrap_or(0) as usize;
    let material = inst.materials.get(slot).copied().unwrap_or(0);
    *out = Surface { p, ng, ns, material, tag: inst.tag, err };
}

/// The unit shading normal (world space, on `ng`'s side) at barycentrics (`w`, `hit.u`,
/// `hit.v`) of triangle `tri` of `mesh` (which has vertex normals), whose normals go to
/// world space by `normal_to_world`.
#[inline(always)]
fn shading_normal(
    mesh: &crate::mesh::MeshData,
    tri: [u32; 3],
    normal_to_world: &glam::Mat3A,
    hit: &Hit,
    w: f32,
    ng: Vec3A,
) -> Vec3A {
    let [i0, i1, i2] = tri;
    let n = mesh.normal(i0) * w + mesh.normal(i1) * hit.u + mesh.normal(i2) * hit.v;
    let n = (*normal_to_world * n).normalize_or(ng);
    mesh.sharpen(if n.dot(ng) < 0.0 { -n } else { n }, ng)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshData;
    use glam::Vec3;

    /// Vertices of the random test mesh.
    const VERTICES: usize = 20_000;

    /// A small xorshift generator: numbers in [0, 1).
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    /// The seed Cornell box's world with its first instance's mesh replaced by `mesh`.
    fn world_with(mesh: MeshData, keep_faces: bool) -> World {
        let text = include_str!("../../../../scenes/iray_cornell_box.mi");
        let parsed = mi::parse_str("cbox.mi", text);
        let mut diags = Vec::new();
        let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("the scene builds");
        let mut world = World::from_scene(&scene);
        let k = world.instances[0].mesh as usize;
        world.meshes[k] = mesh;
        world.faces = if keep_faces {
            crate::world::FaceCache::build(&world.meshes, &world.instances)
        } else {
            crate::world::FaceCache::default()
        };
        world
    }

    /// A mesh of 20,000 vertices at random places with random unit normals (enough for
    /// several of [`MeshData::interleave`]'s parallel waves) and 1,000 random triangles
    /// over them.
    fn random_mesh(rng: &mut Rng) -> MeshData {
        let mut v = || Vec3::new(rng.next(), rng.next(), rng.next()) * 2.0 - 1.0;
        let positions: Vec<Vec3> = (0..VERTICES).map(|_| v() * 300.0).collect();
        let normals: Vec<Vec3> = (0..VERTICES).map(|_| v().normalize_or(Vec3::Z)).collect();
        let mut index = || (rng.next() * VERTICES as f32) as u32 % VERTICES as u32;
        let triangles = (0..1000).map(|_| [index(), index(), index()]).collect();
        MeshData { positions, normals, triangles, ..MeshData::default() }
    }

    /// The mesh with its normals packed to 32 bits (a large mesh's plain layout) and the
    /// mesh interleaved from its given normals.
    fn both_layouts(given: &MeshData) -> (MeshData, MeshData) {
        let mut plain = given.clone();
        plain.pack_normals();
        let mut interleaved = given.clone();
        interleaved.interleave();
        (plain, interleaved)
    }

    /// The interleaved layout ([`MeshData::interleave`]) gives every hit the surface data
    /// of the plain layout (positions, packed normals) bit for bit: point, both normals,
    /// hit-error bound and material, on 20,000 random hits (random triangles and
    /// barycentrics), with the faces kept and computed per hit. Tolerance: none (exact).
    #[test]
    fn interleaved_vertices_give_the_plain_layouts_surface_bit_for_bit() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mesh, interleaved) = both_layouts(&random_mesh(&mut rng));
        assert!(interleaved.is_interleaved() && interleaved.positions.is_empty() && interleaved.normals_oct.is_empty());
        assert_eq!(interleaved.vertex_count(), VERTICES);
        for keep_faces in [true, false] {
            let plain = world_with(mesh.clone(), keep_faces);
            let packed = world_with(interleaved.clone(), keep_faces);
            let ray = Ray::new(Vec3A::ZERO, Vec3A::Z);
            for _ in 0..20_000 {
                let (u, v) = (rng.next(), rng.next());
                let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
                let hit = Hit { t: 1.0, instance: 0, prim: (rng.next() * 1000.0) as u32 % 1000, u, v };
                let (a, b) = (surface(&plain, &ray, &hit), surface(&packed, &ray, &hit));
                for (x, y) in [(a.p, b.p), (a.ng, b.ng), (a.ns, b.ns)] {
                    assert_eq!(x.to_array().map(f32::to_bits), y.to_array().map(f32::to_bits), "hit {hit:?}");
                }
                assert_eq!((a.err.to_bits(), a.material, a.tag), (b.err.to_bits(), b.material, b.tag));
            }
        }
    }

    /// A kept face ([`crate::world::Face`]) gives every hit the surface data the mesh and
    /// instance give it when no face is kept, bit for bit: point, both normals (with and
    /// without vertex normals), hit-error bound, material (three slots, the instance's
    /// materials for two of them: the third falls back to 0) and tag, on 20,000 random
    /// hits. Tolerance: none (exact).
    #[test]
    fn kept_faces_give_the_computed_surface_bit_for_bit() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut smooth = random_mesh(&mut rng);
        smooth.slots = (0..1000).map(|_| (rng.next() * 3.0) as u32 % 3).collect();
        let flat = MeshData { normals: Vec::new(), ..smooth.clone() };
        for mesh in [smooth, flat] {
            let (mut kept, mut computed) = (world_with(mesh.clone(), true), world_with(mesh, false));
            for world in [&mut kept, &mut computed] {
                world.instances[0].materials = vec![1, 2];
            }
            kept.faces = crate::world::FaceCache::build(&kept.meshes, &kept.instances);
            assert!(kept.faces.face(0, 999).is_some() && computed.faces.face(0, 0).is_none());
            let ray = Ray::new(Vec3A::ZERO, Vec3A::Z);
            let mut materials = [0usize; 3];
            for _ in 0..20_000 {
                let (u, v) = (rng.next(), rng.next());
                let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
                let hit = Hit { t: 1.0, instance: 0, prim: (rng.next() * 1000.0) as u32 % 1000, u, v };
                let (a, b) = (surface(&kept, &ray, &hit), surface(&computed, &ray, &hit));
                for (x, y) in [(a.p, b.p), (a.ng, b.ng), (a.ns, b.ns)] {
                    assert_eq!(x.to_array().map(f32::to_bits), y.to_array().map(f32::to_bits), "hit {hit:?}");
                }
                assert_eq!((a.err.to_bits(), a.material, a.tag), (b.err.to_bits(), b.material, b.tag));
                materials[a.material as usize] += 1;
            }
            assert!(materials.iter().all(|&n| n > 1000), "every material is met: {materials:?}");
        }
    }

    /// Interleaving keeps each vertex's position and normal code (the codes
    /// [`MeshData::pack_normals`] gives, whether interleaved from the given normals or
    /// the packed ones), and a mesh with motion vectors stays plain (its readers take the
    /// positions as a slice). Exact.
    #[test]
    fn interleaving_keeps_every_vertex_and_leaves_moving_meshes_plain() {
        let mut rng = Rng(7);
        let (mesh, interleaved) = both_layouts(&random_mesh(&mut rng));
        let mut from_packed = mesh.clone();
        from_packed.interleave();
        assert_eq!(from_packed.vertices, interleaved.vertices);
        assert!(interleaved.normals.is_empty() && interleaved.normals_oct.is_empty());
        for (i, (&p, &n)) in mesh.positions.iter().zip(&mesh.normals_oct).enumerate() {
            assert_eq!(interleaved.vertices[i], crate::mesh::Vertex { p, n });
        }
        let back = interleaved.to_plain();
        assert_eq!((back.positions, back.normals_oct), (mesh.positions.clone(), mesh.normals_oct.clone()));
        let mut moving = MeshData { motion: vec![Vec3A::X; VERTICES], ..mesh };
        moving.interleave();
        assert!(!moving.is_interleaved() && moving.positions.len() == VERTICES);
    }
}
