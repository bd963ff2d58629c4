//! Ray–scene intersection behind one small trait, with a two-level structure (a BVH per
//! mesh, one over the instances) so that instanced geometry is stored once.
//!
//! Backends: [`bvh`] (pure Rust, always built: compressed 8-wide BVHs from the `obvhs`
//! crate) and, when Embree 3 was found at build time, `embree`.

pub mod bvh;
#[cfg(embree)]
pub mod embree;

use crate::ray::Ray;
use crate::world::World;

/// The closest hit of a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray (in units of the ray's `dir`).
    pub t: f32,
    /// Index of the instance in [`World::instances`].
    pub instance: u32,
    /// Index of the triangle in the instance's mesh.
    pub prim: u32,
    /// Barycentric coordinate of the triangle's second vertex.
    pub u: f32,
    /// Barycentric coordinate of the third vertex.
    pub v: f32,
}

/// Which acceleration structure to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// mira's pure-Rust BVHs.
    Rust,
    /// Intel Embree 3.
    Embree,
}

impl Backend {
    /// The best backend compiled in.
    pub fn default_available() -> Backend {
        if cfg!(embree) {
            Backend::Embree
        } else {
            Backend::Rust
        }
    }

    /// Whether this backend is compiled in.
    pub fn available(self) -> bool {
        match self {
            Backend::Rust => true,
            Backend::Embree => cfg!(embree),
        }
    }
}

/// Ray queries against a built scene.
pub trait Accel: Send + Sync {
    /// The closest hit along `ray` within its `[tmin, tmax]`.
    fn intersect(&self, ray: &Ray) -> Option<Hit>;
    /// Whether anything blocks `ray` within its `[tmin, tmax]`.
    fn occluded(&self, ray: &Ray) -> bool;
    /// [`Accel::occluded`] for each of `rays` into `blocked` (as long as `rays`): for rays
    /// that start at one point, as a light's samples do, a backend may trace them together.
    fn occluded_batch(&self, rays: &[Ray], blocked: &mut [bool]) {
        for (ray, b) in rays.iter().zip(blocked) {
            *b = self.occluded(ray);
        }
    }
    /// [`Accel::intersect`] for each of `rays` into `hits` (as long as `rays`), each hit the
    /// one the one-ray query finds: for coherent rays (a tile's camera rays) a backend may
    /// trace them together.
    fn intersect_batch(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        for (ray, h) in rays.iter().zip(hits) {
            *h = self.intersect(ray);
        }
    }
    /// Which backend this is.
    fn backend(&self) -> Backend;
    /// Bytes the built structure holds (nodes, leaves and any copied triangles), as far as
    /// the backend knows them ([`AccelMemory`]); `None` where it cannot tell.
    fn memory(&self) -> Option<AccelMemory> {
        None
    }
}

/// The memory of a built acceleration structure, for `--stats`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccelMemory {
    /// Bytes held (nodes, leaves, copied triangles and vertices).
    pub bytes: u64,
    /// How the figure was obtained: `true` when the backend counted its own arrays,
    /// `false` when it is what the library reported allocating through its memory monitor
    /// (Embree: its node and leaf blocks and build arrays still held, which includes
    /// allocated block space its build did not fill), with the quad arrays mira hands it.
    pub counted: bool,
}

/// Which instances are placed flat in world space (their mesh is used by no other
/// instance, so a world-space copy costs no extra memory over instancing and saves the
/// top-level traversal and ray transforms), and which keep a shared mesh BVH.
///
/// An instance that moves and whose mesh's vertices move too is never flat: where it is
/// at time `t` is the product of the instance's transform and the vertices at `t`, not
/// linear between keys, and both backends form that product exactly only by carrying the
/// ray into the moving mesh with the instance's transform at the ray's time (as shading
/// places the hit, [`crate::world::InstanceData::placement`] × [`crate::mesh::MeshData::triangle_at`]).
///
/// Nor is a moving instance of a large still mesh (≥ [`crate::mesh::LARGE_MESH_TRIANGLES`]):
/// flat, its vertices would be copied into world space at every key of the motion and
/// built into a motion-blur BVH; instanced, its one still BVH (compact, quads) moves with
/// the instance's keys. Measured on the heavy scene's sphere sliding 20 mm (docs/performance.md,
/// moving48): Embree's build 4.3 → 0.5 s, peak memory 609 → 214 MiB.
pub fn flat_instances(world: &World) -> Vec<bool> {
    let mut uses = vec![0u32; world.meshes.len()];
    for i in &world.instances {
        uses[i.mesh as usize] += 1;
    }
    world
        .instances
        .iter()
        .map(|i| {
            let mesh = &world.meshes[i.mesh as usize];
            let large = mesh.triangles.len() >= crate::mesh::LARGE_MESH_TRIANGLES;
            uses[i.mesh as usize] == 1 && !(i.moves() && (mesh.moves() || large))
        })
        .collect()
}

/// Builds the acceleration structure of `world` with `backend` (falling back to the Rust
/// backend if the requested one is not compiled in). It may read the world's mesh arrays in
/// place, so it borrows the world.
pub fn build(world: &World, backend: Backend) -> Box<dyn Accel + '_> {
    match backend {
        #[cfg(embree)]
        Backend::Embree => Box::new(embree::EmbreeAccel::new(world)),
        _ => Box::new(bvh::BvhAccel::new(world)),
    }
}

/// Möller–Trumbore ray–triangle intersection: (t, u, v) of a hit within `[tmin, tmax]`.
#[inline(always)]
pub fn intersect_triangle(ray: &Ray, p0: glam::Vec3A, p1: glam::Vec3A, p2: glam::Vec3A) -> Option<(f32, f32, f32)> {
    let e1 = p1 - p0;
    let e2 = p2 - p0;
    let pv = ray.dir.cross(e2);
    let det = e1.dot(pv);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let tv = ray.origin - p0;
    let u = tv.dot(pv) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qv = tv.cross(e1);
    let v = ray.dir.dot(qv) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(qv) * inv;
    (t >= ray.tmin && t <= ray.tmax).then_some((t, u, v))
}
