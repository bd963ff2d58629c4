//! The Embree 3 backend, through a thin binding of the few functions mira needs (Embree's
//! C API: one scene per mesh, instanced by a top-level scene, ray masks for the instance
//! flags). Only built when the build script found Embree 3 (`cfg(embree)`).
//!
//! This module is the one place in mira with `unsafe` code: calls into the C library. Each
//! call's preconditions are stated next to it.
//!
//! Moving geometry (see [`crate::motion`]) uses Embree's motion blur: a moving mesh's
//! triangle geometry has one vertex buffer per key (`rtcSetGeometryTimeStepCount`), a
//! moving instance one transform per key, and `ray.time` is the ray's shutter time.
#![allow(unsafe_code)]

use std::ffi::c_void;
use std::os::raw::c_uint;

use super::{Accel, Backend, Hit};
use crate::accel::bvh::instance_mask;
use crate::mesh::quad_pairs;
use crate::ray::Ray;
use crate::world::World;

mod ffi;
use ffi::*;

/// The memory monitor mira installs on its devices: adds Embree's allocations and frees
/// to the `AtomicI64` at `user` (the device's [`EmbreeAccel::memory`]) and allows them all.
unsafe extern "C" fn count_memory(user: *mut c_void, bytes: isize, _post: bool) -> bool {
    // SAFETY: `user` is the `AtomicI64` boxed in the `EmbreeAccel` that owns the device,
    // which outlives every call (the device is released in its `drop`).
    let counter = unsafe { &*(user as *const std::sync::atomic::AtomicI64) };
    counter.fetch_add(bytes as i64, std::sync::atomic::Ordering::Relaxed);
    true
}

/// Triangles stored (shared meshes once, flattened instances each) from which the scene's
/// BVH is built compact (`RTC_SCENE_FLAG_COMPACT`: indexed triangle leaves instead of
/// copied vertices). Measured on the 4 M-triangle heavy scene: peak memory 604 → 481 MB
/// for about 12 % more traversal time; small scenes keep the faster layout. (The same
/// size makes a mesh keep its normals in 32 bits, [`crate::mesh::LARGE_MESH_TRIANGLES`].)
const COMPACT_FROM_TRIANGLES: usize = crate::mesh::LARGE_MESH_TRIANGLES;

/// The device of a world with a compact scene: every triangle scene in 8-wide nodes over
/// indexed leaves (`bvh8.triangle4i`), where Embree's own choice for compact scenes is 4-wide
/// nodes (`bvh4.triangle4i`, 33.2 B a triangle on the heavy scene). Measured there: 38.3 B
/// a triangle, 0.86 × the render's CPU time (speed15, perf samples) and 0.91 × (speed17,
/// 10 interleaved pairs); it fits the 60-byte budget since large meshes keep their
/// normals in 4 bytes a vertex. Images are the same as with the 4-wide nodes. Quantized 8-wide nodes
/// (`qbvh8.triangle4i`) take 30.5 B but peak at 353 MiB while building, and have no packet
/// kernels. Build quality has no effect on compact leaves (always binned SAH).
///
/// Large meshes reach Embree as quads where their triangles pair up
/// ([`crate::mesh::MeshData::pair_into_quads`]): compact
/// ones in 8-wide nodes over indexed quad leaves (`bvh8.quad4i`; Embree's own choice for
/// compact quads is 4-wide, `bvh4.quad4i`). Measured on the heavy scene (speed45): 21.5 B a
/// triangle for the BVH against `bvh8.triangle4i`'s 40.9 (the quads' own arrays add 12),
/// built in about half the time.
const COMPACT_DEVICE: &std::ffi::CStr = c"threads=0,tri_accel=bvh8.triangle4i,quad_accel=bvh8.quad4i";

/// Whether this CPU runs Embree's 8-wide kernels (AVX; without it Embree has no 8-wide
/// BVH factory to build with, so [`COMPACT_DEVICE`] must not be asked for).
fn wide_nodes_supported() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Embree's build quality: medium (binned SAH). Measured against high (spatial splits):
/// the Cornell box traces with 3.5 % fewer instructions (2.19 G against 2.27 G for
/// 128², 16 spp) and the heavy scene builds in the same CPU time.
const BUILD_QUALITY: c_uint = BUILD_QUALITY_MEDIUM;

/// Scenes built by Embree for a [`World`].
///
/// Meshes placed without a transform are not copied: Embree reads the world's own vertex
/// and index arrays (shared buffers), which the borrow `'w` keeps alive and unchanged.
pub struct EmbreeAccel<'w> {
    device: RtcDevice,
    /// The top-level scenes, in the order every query traces them (the ray's `tfar`
    /// carried from one to the next). A small world: one scene holding every mesh used
    /// once and every shared mesh's instance. A large world (built compact): one scene a
    /// kind of geometry it has ([`TopKind`]: still triangles, moving triangles, quads,
    /// instances). In one scene Embree builds a BVH for each kind in one parallel loop:
    /// the caller takes the first, and where TBB's worker took the large one the caller
    /// waits inside Embree's task isolation and cannot help, so a large build ran on one
    /// thread in most runs (docs/performance.md, speed47 and tops48). Apart, each scene is
    /// one BVH its committing thread builds with the worker's help. Queried in Embree's own
    /// order of the kinds, the hits are those of one scene bit for bit. `top` is the
    /// first, `more_tops` the others, null past the last (all null in a small world,
    /// whose queries then test one pointer: a list on the heap cost the Cornell box's
    /// render 0.8 % more instructions).
    top: RtcScene,
    more_tops: [RtcScene; TopKind::COUNT - 1],
    meshes: Vec<RtcScene>,
    /// Whether [`Accel::intersect_batch`] traces packets (`rtcIntersect8`): only where no
    /// scene is built compact. With indexed leaves Embree's packet kernel moved hits in the
    /// last bit against its one-ray kernel (AVX2: 4,035 of 16,384 first-hit depths of the
    /// 1 M-triangle heavy scene), where the common layout agrees but for exact ties.
    packets: bool,
    /// Bytes Embree holds for this device, as its memory monitor reported them
    /// ([`count_memory`]): boxed, so that its address, which Embree keeps, stays put.
    memory: Box<std::sync::atomic::AtomicI64>,
    /// Each mesh's quads where Embree holds it as quads (its triangles paired,
    /// [`crate::mesh::MeshData::quad_pairs`]; measured in speed45: half the primitives to
    /// build, half the BVH's bytes); empty where it holds triangles.
    quads: Vec<Vec<[u32; 4]>>,
    /// For each instance, its mesh's [`crate::mesh::MeshData::quad_pairs`] where Embree
    /// holds that mesh as quads, or `u32::MAX` where it holds triangles.
    quad_pairs_of: Vec<u32>,
    world: std::marker::PhantomData<&'w World>,
}

// SAFETY: Embree devices and committed scenes may be used from any thread; after
// construction mira only queries them (rtcIntersect1/rtcOccluded1 are thread-safe on a
// committed scene) and releases them in `drop`.
unsafe impl Send for EmbreeAccel<'_> {}
// SAFETY: as above: queries on a committed scene are thread-safe.
unsafe impl Sync for EmbreeAccel<'_> {}

/// The kinds of top-level geometry a large world holds in scenes of their own (see
/// [`EmbreeAccel`]'s `tops`), in the order Embree queries its BVHs for them in one scene
/// (`Scene::commit_task` of Embree 3.13: triangles, moving triangles, quads, moving quads,
/// …, instances, moving instances).
#[derive(Clone, Copy)]
enum TopKind {
    /// Still meshes used once, as triangles in world space.
    Triangles,
    /// Moving meshes used once, as triangles in world space at each key.
    MovingTriangles,
    /// Still meshes used once, paired into quads ([`EmbreeAccel`]'s `quads`).
    Quads,
    /// Moving meshes used once, paired into quads, in world space at each key.
    MovingQuads,
    /// Instances of shared meshes (or large meshes on moving instances), still and moving.
    Instances,
}

impl TopKind {
    /// How many kinds there are.
    const COUNT: usize = 5;
}

impl<'w> EmbreeAccel<'w> {
    /// Builds Embree scenes for a world (falls back to an empty scene on device errors,
    /// which are reported by [`EmbreeAccel::error`]).
    pub fn new(world: &'w World) -> EmbreeAccel<'w> {
        let flat = super::flat_instances(world);
        let mut shared = vec![false; world.meshes.len()];
        for (inst, f) in world.instances.iter().zip(&flat) {
            shared[inst.mesh as usize] |= !f;
        }
        let flat_triangles: usize = world
            .instances
            .iter()
            .zip(&flat)
            .filter(|(_, &f)| f)
            .map(|(i, _)| world.meshes[i.mesh as usize].triangles.len())
            .sum();
        let compact = flat_triangles >= COMPACT_FROM_TRIANGLES
            || world.meshes.iter().zip(&shared).any(|(m, &used)| used && m.triangles.len() >= COMPACT_FROM_TRIANGLES);
        if compact && wide_nodes_supported() {
            let accel = Self::with_device(world, &flat, &shared, flat_triangles, COMPACT_DEVICE, true, true);
            if accel.error() == 0 {
                return accel;
            }
            // An Embree built without 8-wide kernels rejects the layout: build the default.
        }
        Self::with_device(world, &flat, &shared, flat_triangles, c"threads=0", compact, true)
    }

    /// Builds Embree scenes for a world as a large world's are — compact, the still meshes
    /// whose triangles were paired ([`crate::mesh::MeshData::quad_pairs`]) as quads —
    /// whatever its size: for tests and measurements of that layout on small scenes.
    pub fn new_compact(world: &'w World) -> EmbreeAccel<'w> {
        Self::compact_layout(world, true)
    }

    /// [`EmbreeAccel::new_compact`] with every top-level geometry in one scene (no split
    /// by kind): the layout the split is checked against.
    pub fn new_compact_in_one_scene(world: &'w World) -> EmbreeAccel<'w> {
        Self::compact_layout(world, false)
    }

    /// The compact layout, the top-level geometry split by kind if `kinds_apart`.
    fn compact_layout(world: &'w World, kinds_apart: bool) -> EmbreeAccel<'w> {
        let flat = super::flat_instances(world);
        let mut shared = vec![false; world.meshes.len()];
        for (inst, f) in world.instances.iter().zip(&flat) {
            shared[inst.mesh as usize] |= !f;
        }
        let flat_triangles = COMPACT_FROM_TRIANGLES;
        let config = if wide_nodes_supported() { COMPACT_DEVICE } else { c"threads=0" };
        Self::with_device(world, &flat, &shared, flat_triangles, config, true, kinds_apart)
    }

    /// [`EmbreeAccel::new`] on a device of configuration `config`, the instances placed as
    /// `flat` says, the meshes in `shared` built as scenes of their own; with `use_quads`,
    /// the meshes paired into quads as quads (still or moving); with `kinds_apart`, where
    /// `flat_triangles` makes the world large, the top-level geometry in one scene a kind
    /// (`tops`).
    fn with_device(
        world: &'w World,
        flat: &[bool],
        shared: &[bool],
        flat_triangles: usize,
        config: &std::ffi::CStr,
        use_quads: bool,
        kinds_apart: bool,
    ) -> EmbreeAccel<'w> {
        // SAFETY: `config` is a NUL-terminated string; every pointer passed below comes
        // from Embree itself or from live Rust buffers of the stated sizes.
        unsafe {
            let device = rtcNewDevice(config.as_ptr());
            let memory = Box::new(std::sync::atomic::AtomicI64::new(0));
            if !device.is_null() {
                let user = std::ptr::from_ref::<std::sync::atomic::AtomicI64>(&memory).cast_mut().cast::<c_void>();
                rtcSetDeviceMemoryMonitorFunction(device, count_memory, user);
            }
            let mut compact = false;
            // Quads for the placed meshes paired into them, still or moving.
            let mut quads: Vec<Vec<[u32; 4]>> = vec![Vec::new(); world.meshes.len()];
            for inst in &world.instances {
                let mesh = &world.meshes[inst.mesh as usize];
                if use_quads && mesh.quad_pairs > 0 && quads[inst.mesh as usize].is_empty() {
                    quads[inst.mesh as usize] = quad_pairs::quads(&mesh.triangles, mesh.quad_pairs);
                }
            }
            let meshes: Vec<RtcScene> = world
                .meshes
                .iter()
                .zip(shared)
                .zip(&quads)
                .map(|((m, &used), q)| {
                    let scene = rtcNewScene(device);
                    rtcSetSceneBuildQuality(scene, BUILD_QUALITY);
                    if m.triangles.len() >= COMPACT_FROM_TRIANGLES {
                        rtcSetSceneFlags(scene, SCENE_FLAG_COMPACT);
                        compact |= used;
                    }
                    if used && !m.triangles.is_empty() && m.moves() {
                        let geom = moving_geometry(device, m, q, Keys::Shared(&m.position_keys));
                        rtcAttachGeometryByID(scene, geom, 0);
                        rtcReleaseGeometry(geom);
                    } else if used && !m.triangles.is_empty() {
                        let geom = still_geometry(device, m, q, glam::Affine3A::IDENTITY);
                        rtcAttachGeometryByID(scene, geom, 0);
                        rtcReleaseGeometry(geom);
                    }
                    rtcCommitScene(scene);
                    scene
                })
                .collect();
            let top_scene = || {
                let scene = rtcNewScene(device);
                rtcSetSceneBuildQuality(scene, BUILD_QUALITY);
                if flat_triangles >= COMPACT_FROM_TRIANGLES {
                    rtcSetSceneFlags(scene, SCENE_FLAG_COMPACT);
                }
                scene
            };
            compact |= flat_triangles >= COMPACT_FROM_TRIANGLES;
            // A large world's top-level geometry in one scene a kind (see `tops`), in
            // Embree's order of the kinds; a small world's in one scene.
            let apart = kinds_apart && flat_triangles >= COMPACT_FROM_TRIANGLES;
            let mut scenes: [RtcScene; TopKind::COUNT] = [std::ptr::null_mut(); TopKind::COUNT];
            let mut scene_for = |kind: TopKind| {
                let slot = if apart { kind as usize } else { 0 };
                if scenes[slot].is_null() {
                    scenes[slot] = top_scene();
                }
                scenes[slot]
            };
            for (i, inst) in world.instances.iter().enumerate() {
                let mesh = &world.meshes[inst.mesh as usize];
                if flat[i] && (inst.moves() || mesh.moves()) {
                    // A moving mesh used once: in world space at each key (the mesh's own
                    // keys where its placement is the identity).
                    let quads = &quads[inst.mesh as usize];
                    let geom = if !inst.moves() && inst.object_to_world == glam::Affine3A::IDENTITY {
                        moving_geometry(device, mesh, quads, Keys::Shared(&mesh.position_keys))
                    } else {
                        let keys = crate::world::world_key_positions(inst, mesh);
                        moving_geometry(device, mesh, quads, Keys::Copied(&keys))
                    };
                    rtcSetGeometryMask(geom, instance_mask(&inst.flags));
                    rtcCommitGeometry(geom);
                    let kind = if quads.is_empty() { TopKind::MovingTriangles } else { TopKind::MovingQuads };
                    rtcAttachGeometryByID(scene_for(kind), geom, i as c_uint);
                    rtcReleaseGeometry(geom);
                    continue;
                }
                if flat[i] {
                    // A still mesh used once: its triangles (or quads) in world space.
                    let quads = &quads[inst.mesh as usize];
                    let geom = still_geometry(device, mesh, quads, inst.object_to_world);
                    rtcSetGeometryMask(geom, instance_mask(&inst.flags));
                    rtcCommitGeometry(geom);
                    let kind = if quads.is_empty() { TopKind::Triangles } else { TopKind::Quads };
                    rtcAttachGeometryByID(scene_for(kind), geom, i as c_uint);
                    rtcReleaseGeometry(geom);
                    continue;
                }
                let geom = rtcNewGeometry(device, GEOMETRY_TYPE_INSTANCE);
                rtcSetGeometryInstancedScene(geom, meshes[inst.mesh as usize]);
                let keys = if inst.moves() { &inst.keys[..] } else { std::slice::from_ref(&inst.object_to_world) };
                if keys.len() > 1 {
                    rtcSetGeometryTimeStepCount(geom, keys.len() as c_uint);
                }
                for (step, m) in keys.iter().enumerate() {
                    let cols = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis, m.translation];
                    let xfm: Vec<f32> = cols.iter().flat_map(|c| c.to_array()).collect();
                    rtcSetGeometryTransform(geom, step as c_uint, FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.as_ptr());
                }
                rtcSetGeometryMask(geom, instance_mask(&inst.flags));
                rtcCommitGeometry(geom);
                rtcAttachGeometryByID(scene_for(TopKind::Instances), geom, i as c_uint);
                rtcReleaseGeometry(geom);
            }
            // In query order, the kinds with geometry (an empty world: one empty scene).
            let mut tops: Vec<RtcScene> = scenes.into_iter().filter(|s| !s.is_null()).collect();
            if tops.is_empty() {
                tops.push(top_scene());
            }
            for &scene in &tops {
                rtcCommitScene(scene);
            }
            let top = tops[0];
            let mut more_tops = [std::ptr::null_mut(); TopKind::COUNT - 1];
            more_tops[..tops.len() - 1].copy_from_slice(&tops[1..]);
            let quad_pairs_of = world
                .instances
                .iter()
                .map(|inst| {
                    let mesh = inst.mesh as usize;
                    if quads[mesh].is_empty() {
                        u32::MAX
                    } else {
                        world.meshes[mesh].quad_pairs
                    }
                })
                .collect();
            EmbreeAccel {
                device,
                top,
                more_tops,
                meshes,
                packets: !compact,
                memory,
                quads,
                quad_pairs_of,
                world: std::marker::PhantomData,
            }
        }
    }

    /// How many top-level scenes a query traces (1 to 5; see [`EmbreeAccel`]'s `tops`).
    pub fn top_level_scenes(&self) -> usize {
        1 + self.more_tops().count()
    }

    /// The top-level scenes queried after `top`, in order.
    #[inline(always)]
    fn more_tops(&self) -> impl Iterator<Item = RtcScene> + '_ {
        self.more_tops.iter().copied().take_while(|s| !s.is_null())
    }

    /// How many quads Embree holds (0 where it holds triangles).
    pub fn quad_count(&self) -> usize {
        self.quads.iter().map(Vec::len).sum()
    }

    /// Embree's last error code (0: none).
    #[allow(dead_code)]
    pub fn error(&self) -> u32 {
        // SAFETY: the device is alive until drop.
        unsafe { rtcGetDeviceError(self.device) }
    }

    /// The Embree ray of `ray`, written as three 16-byte stores (origin and `tnear`,
    /// direction and time, `tfar`, mask, id and flags): Embree's one-ray kernels load each
    /// of those groups as one 16-byte vector, which a group written piecemeal (the compiler
    /// stored an 8-byte, a 4-byte and a 4-byte piece) could not be forwarded from, and the
    /// ray's own scalars are read one by one, each from the store that wrote it, instead of
    /// as 8-byte pairs spanning two of the caller's stores (`tmax` with `time`). Measured in
    /// speed36 (docs/performance.md): perf put most of the wrapper's cycles on those stalls.
    #[inline(always)]
    fn rtc_ray(ray: &Ray) -> RtcRay {
        // SAFETY: the references are valid and aligned; volatile reads keep each 4-byte
        // field a load of its own (the compiler merged `tmax` and `time` into one).
        let (tmin, tmax, time) = unsafe {
            (std::ptr::read_volatile(&ray.tmin), std::ptr::read_volatile(&ray.tmax), std::ptr::read_volatile(&ray.time))
        };
        let groups = [
            ray.origin.extend(tmin),
            ray.dir.extend(time),
            glam::Vec4::new(tmax, f32::from_bits(ray.mask), f32::from_bits(0), f32::from_bits(0)),
        ];
        // SAFETY: `RtcRay` is 48 bytes of 4-byte plain fields (aligned to 16), laid out as
        // the three groups' lanes in order: org, tnear | dir, time | tfar, mask, id, flags.
        unsafe { std::mem::transmute::<[glam::Vec4; 3], RtcRay>(groups) }
    }

    /// The barycentrics of a hit Embree wrote, read as two 4-byte loads (Embree stores them
    /// one by one; one 8-byte load across both stalled on store forwarding).
    #[inline(always)]
    fn hit_uv(hit: &RtcHit) -> (f32, f32) {
        // SAFETY: the references are valid and aligned.
        unsafe { (std::ptr::read_volatile(&hit.u), std::ptr::read_volatile(&hit.v)) }
    }

    /// The hit at `t` on primitive `prim` of `instance` at Embree's `(u, v)`: a quad's hit
    /// turned into its triangle's ([`quad_pairs::triangle_hit`]).
    #[inline(always)]
    fn hit(&self, t: f32, instance: u32, prim: u32, u: f32, v: f32) -> Hit {
        let pairs = self.quad_pairs_of[instance as usize];
        if pairs != u32::MAX {
            let (prim, u, v) = quad_pairs::triangle_hit(pairs, prim, u, v);
            return Hit { t, instance, prim, u, v };
        }
        Hit { t, instance, prim, u, v }
    }

    /// Eight rays that trace nothing, to be filled by [`EmbreeAccel::fill_packet`].
    fn empty_packet() -> RtcRay8 {
        RtcRay8 {
            org_x: [0.0; 8],
            org_y: [0.0; 8],
            org_z: [0.0; 8],
            tnear: [0.0; 8],
            dir_x: [0.0; 8],
            dir_y: [0.0; 8],
            dir_z: [1.0; 8],
            time: [0.0; 8],
            tfar: [0.0; 8],
            mask: [0; 8],
            id: [0; 8],
            flags: [0; 8],
        }
    }

    /// Puts up to eight rays into the lanes of `r` and marks them valid in `valid` (the lanes
    /// past `rays` stay invalid and hold a harmless ray).
    #[inline(always)]
    fn fill_packet(rays: &[Ray], valid: &mut Valid8, r: &mut RtcRay8) {
        for (k, ray) in rays.iter().take(8).enumerate() {
            valid.0[k] = -1;
            (r.org_x[k], r.org_y[k], r.org_z[k]) = (ray.origin.x, ray.origin.y, ray.origin.z);
            (r.dir_x[k], r.dir_y[k], r.dir_z[k]) = (ray.dir.x, ray.dir.y, ray.dir.z);
            (r.tnear[k], r.tfar[k], r.time[k], r.mask[k]) = (ray.tmin, ray.tmax, ray.time, ray.mask);
        }
    }

    /// The top-level scenes a query traces, in order.
    #[inline(always)]
    fn scenes(&self) -> impl Iterator<Item = RtcScene> + '_ {
        std::iter::once(self.top).chain(self.more_tops())
    }

    fn context() -> IntersectContext {
        IntersectContext { flags: 0, filter: std::ptr::null(), inst_id: [INVALID_ID] }
    }

    /// The closest hits of `rays` into `hits` (as long as `rays`) through Embree's stream
    /// kernel (`rtcIntersect1M`), which packs the rays into packets itself (`coherent`: the
    /// coherent-rays flag). For measurements only (`benches/wavefront.rs`): with compact
    /// leaves its packet kernels may move hits in the last bit against
    /// [`Accel::intersect`].
    pub fn intersect_stream(&self, rays: &[Ray], hits: &mut [Option<Hit>], coherent: bool) {
        let mut rh: Vec<RtcRayHit> = rays
            .iter()
            .map(|r| RtcRayHit {
                ray: Self::rtc_ray(r),
                hit: RtcHit {
                    ng: [0.0; 3],
                    u: 0.0,
                    v: 0.0,
                    prim_id: INVALID_ID,
                    geom_id: INVALID_ID,
                    inst_id: [INVALID_ID],
                },
            })
            .collect();
        for scene in self.scenes() {
            let mut ctx =
                IntersectContext { flags: if coherent { CONTEXT_FLAG_COHERENT } else { 0 }, ..Self::context() };
            // SAFETY: `scene` is a committed scene; `rh` holds `rays.len()` 16-byte aligned
            // `RTCRayHit`s one after another (stride = their size).
            unsafe {
                rtcIntersect1M(scene, &mut ctx, rh.as_mut_ptr(), rh.len() as c_uint, std::mem::size_of::<RtcRayHit>())
            };
        }
        for (h, rh) in hits.iter_mut().zip(&rh) {
            let instance = if rh.hit.inst_id[0] == INVALID_ID { rh.hit.geom_id } else { rh.hit.inst_id[0] };
            *h = (rh.hit.geom_id != INVALID_ID)
                .then(|| self.hit(rh.ray.tfar, instance, rh.hit.prim_id, rh.hit.u, rh.hit.v));
        }
    }
}

impl Accel for EmbreeAccel<'_> {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut rh = RtcRayHit {
            ray: Self::rtc_ray(ray),
            hit: RtcHit {
                ng: [0.0; 3],
                u: 0.0,
                v: 0.0,
                prim_id: INVALID_ID,
                geom_id: INVALID_ID,
                inst_id: [INVALID_ID],
            },
        };
        // Each scene in turn, the ray's `tfar` carried over (Embree's own order in one scene).
        // `top` first, outside the loop over the others (which a small world does not have).
        let mut ctx = Self::context();
        // SAFETY: `top` is a committed scene; `ctx` and `rh` are valid, 16-byte aligned
        // structures laid out as Embree 3.13 declares them.
        unsafe { rtcIntersect1(self.top, &mut ctx, &mut rh) };
        for scene in self.more_tops() {
            let mut ctx = Self::context();
            // SAFETY: as above, for each further committed top-level scene.
            unsafe { rtcIntersect1(scene, &mut ctx, &mut rh) };
        }
        // Flattened meshes are top-level geometries (their id is the instance); the others
        // are hit inside an instance.
        let instance = if rh.hit.inst_id[0] == INVALID_ID { rh.hit.geom_id } else { rh.hit.inst_id[0] };
        (rh.hit.geom_id != INVALID_ID).then(|| {
            let (u, v) = Self::hit_uv(&rh.hit);
            self.hit(rh.ray.tfar, instance, rh.hit.prim_id, u, v)
        })
    }

    fn occluded(&self, ray: &Ray) -> bool {
        let mut r = Self::rtc_ray(ray);
        let blocked = |r: &RtcRay| r.tfar < 0.0 && r.tfar.is_infinite();
        let mut ctx = Self::context();
        // SAFETY: as for `intersect`.
        unsafe { rtcOccluded1(self.top, &mut ctx, &mut r) };
        // Embree sets tfar to −∞ when the ray is blocked.
        if blocked(&r) {
            return true;
        }
        for scene in self.more_tops() {
            let mut ctx = Self::context();
            // SAFETY: as for `intersect`.
            unsafe { rtcOccluded1(scene, &mut ctx, &mut r) };
            if blocked(&r) {
                return true;
            }
        }
        false
    }

    fn intersect_batch(&self, rays: &[Ray], hits: &mut [Option<Hit>]) {
        for (rays, hits) in rays.chunks(8).zip(hits.chunks_mut(8)) {
            if rays.len() == 1 || !self.packets {
                for (ray, h) in rays.iter().zip(hits) {
                    *h = self.intersect(ray);
                }
                continue;
            }
            let mut valid = Valid8([0; 8]);
            let mut rh = RtcRayHit8 {
                ray: Self::empty_packet(),
                hit: RtcHit8 {
                    ng_x: [0.0; 8],
                    ng_y: [0.0; 8],
                    ng_z: [0.0; 8],
                    u: [0.0; 8],
                    v: [0.0; 8],
                    prim_id: [INVALID_ID; 8],
                    geom_id: [INVALID_ID; 8],
                    inst_id: [[INVALID_ID; 8]],
                },
            };
            Self::fill_packet(rays, &mut valid, &mut rh.ray);
            for scene in self.scenes() {
                let mut ctx = IntersectContext { flags: CONTEXT_FLAG_COHERENT, ..Self::context() };
                // SAFETY: `scene` is a committed scene; `valid` and `rh` are 32-byte
                // aligned and laid out as Embree 3.13's `int[8]` mask and `RTCRayHit8`
                // (one instance level); lanes past the batch are marked invalid and left
                // alone.
                unsafe { rtcIntersect8(&valid, scene, &mut ctx, &mut rh) };
            }
            for (k, h) in hits.iter_mut().enumerate() {
                let (geom, inst) = (rh.hit.geom_id[k], rh.hit.inst_id[0][k]);
                // As in `intersect`: flattened meshes are hit as top-level geometries.
                let instance = if inst == INVALID_ID { geom } else { inst };
                *h = (geom != INVALID_ID)
                    .then(|| self.hit(rh.ray.tfar[k], instance, rh.hit.prim_id[k], rh.hit.u[k], rh.hit.v[k]));
            }
        }
    }

    fn occluded_batch(&self, rays: &[Ray], blocked: &mut [bool]) {
        for (rays, blocked) in rays.chunks(8).zip(blocked.chunks_mut(8)) {
            if rays.len() == 1 {
                blocked[0] = self.occluded(&rays[0]);
                continue;
            }
            let (mut valid, mut r) = (Valid8([0; 8]), Self::empty_packet());
            Self::fill_packet(rays, &mut valid, &mut r);
            for scene in self.scenes() {
                let mut ctx = IntersectContext { flags: CONTEXT_FLAG_COHERENT, ..Self::context() };
                // SAFETY: `scene` is a committed scene; `valid` and `r` are 32-byte aligned
                // and laid out as Embree 3.13's `int[8]` mask and `RTCRay8`; lanes past the
                // batch are marked invalid and left alone (a blocked lane's tfar is −∞,
                // which the next scene leaves as it is).
                unsafe { rtcOccluded8(&valid, scene, &mut ctx, &mut r) };
            }
            for (k, b) in blocked.iter_mut().enumerate() {
                // Embree sets tfar to −∞ in the lanes that are blocked.
                *b = r.tfar[k] < 0.0 && r.tfar[k].is_infinite();
            }
        }
    }

    fn backend(&self) -> Backend {
        Backend::Embree
    }

    fn memory(&self) -> Option<super::AccelMemory> {
        let bytes = self.memory.load(std::sync::atomic::Ordering::Relaxed).max(0) as u64;
        let quads: usize = self.quads.iter().map(|q| q.capacity() * std::mem::size_of::<[u32; 4]>()).sum();
        Some(super::AccelMemory { bytes: bytes + quads as u64, counted: false })
    }
}

/// A committed geometry of a mesh that does not move, its vertices carried by
/// `transform`: its `quads` ([`quad_pairs::quads`]) where it has them, else its triangles.
///
/// # Safety
/// `device` must be a live Embree device; `quads` must outlive the geometry.
unsafe fn still_geometry(
    device: RtcDevice,
    m: &crate::mesh::MeshData,
    quads: &[[u32; 4]],
    transform: glam::Affine3A,
) -> RtcGeometry {
    // SAFETY: the buffers Embree returns hold exactly the item counts asked for; the shared
    // buffers are the mesh's own arrays and its quads, which outlive the accel (it borrows
    // the world and owns the quads).
    unsafe {
        let geom = rtcNewGeometry(device, if quads.is_empty() { GEOMETRY_TYPE_TRIANGLE } else { GEOMETRY_TYPE_QUAD });
        if transform == glam::Affine3A::IDENTITY && m.is_interleaved() {
            // The 16-byte records' first 12 bytes are the position: a float3 buffer with a
            // 16-byte stride (Embree ignores the fourth float its loads bring, the normal).
            rtcSetSharedGeometryBuffer(
                geom,
                BUFFER_TYPE_VERTEX,
                0,
                FORMAT_FLOAT3,
                m.vertices.as_ptr().cast(),
                0,
                std::mem::size_of::<crate::mesh::Vertex>(),
                m.vertices.len(),
            );
        } else if transform == glam::Affine3A::IDENTITY && m.positions.capacity() > m.positions.len() {
            // Vec3 is three f32: a float3 buffer with a 12-byte stride; the vector's room
            // for one more vertex lets Embree read the last one with a 16-byte load.
            rtcSetSharedGeometryBuffer(
                geom,
                BUFFER_TYPE_VERTEX,
                0,
                FORMAT_FLOAT3,
                m.positions.as_ptr().cast(),
                0,
                std::mem::size_of::<glam::Vec3>(),
                m.positions.len(),
            );
        } else {
            let count = m.vertex_count();
            let verts = rtcSetNewGeometryBuffer(geom, BUFFER_TYPE_VERTEX, 0, FORMAT_FLOAT3, 12, count) as *mut f32;
            if !verts.is_null() {
                let out = std::slice::from_raw_parts_mut(verts, 3 * count);
                // Identity placements land here when the vector has no room past its end:
                // their vertices are copied as they are.
                let identity = transform == glam::Affine3A::IDENTITY;
                for (o, p) in out.chunks_exact_mut(3).zip(m.vertex_positions()) {
                    let p = if identity { p.into() } else { transform.transform_point3a(p.into()) };
                    o.copy_from_slice(&glam::Vec3A::to_array(&p));
                }
            }
        }
        if quads.is_empty() {
            share_triangles(geom, m);
        } else {
            share_quads(geom, quads);
        }
        // Committed again by the caller after setting the mask.
        rtcCommitGeometry(geom);
        geom
    }
}

/// The vertex positions of a moving geometry at each of its keys (time steps spread
/// evenly over the shutter).
enum Keys<'a> {
    /// Arrays that outlive the accel (the world's): Embree reads them in place, 16 bytes
    /// a vertex (`Vec3A`), without a copy.
    Shared(&'a [Vec<glam::Vec3A>]),
    /// Arrays made for the build (world-space keys of a placed mesh): copied into buffers
    /// Embree owns.
    Copied(&'a [Vec<glam::Vec3A>]),
}

/// A committed geometry of `mesh` whose vertices are at `keys[j]` at the j-th time step:
/// its `quads` ([`quad_pairs::quads`]) where it has them, else its triangles. Measured on
/// the heavy scene's sphere deforming (docs/performance.md, quadsmb49): as quads the
/// motion-blur BVH builds in half the time and takes half the bytes.
///
/// # Safety
/// `device` must be a live Embree device; `quads` and shared keys must outlive the
/// geometry.
unsafe fn moving_geometry(
    device: RtcDevice,
    m: &crate::mesh::MeshData,
    quads: &[[u32; 4]],
    keys: Keys<'_>,
) -> RtcGeometry {
    // SAFETY: the buffers Embree returns hold exactly the item counts asked for; shared
    // buffers (the mesh's triangles, its quads, shared keys) outlive the accel (it borrows
    // the world and owns the quads), and each `Vec3A` is 16 bytes, so Embree's 16-byte
    // loads of a vertex stay inside its array.
    unsafe {
        let geom = rtcNewGeometry(device, if quads.is_empty() { GEOMETRY_TYPE_TRIANGLE } else { GEOMETRY_TYPE_QUAD });
        let (Keys::Shared(arrays) | Keys::Copied(arrays)) = keys;
        rtcSetGeometryTimeStepCount(geom, arrays.len() as c_uint);
        for (step, key) in arrays.iter().enumerate() {
            if let Keys::Shared(_) = keys {
                let stride = std::mem::size_of::<glam::Vec3A>();
                rtcSetSharedGeometryBuffer(
                    geom,
                    BUFFER_TYPE_VERTEX,
                    step as c_uint,
                    FORMAT_FLOAT3,
                    key.as_ptr().cast(),
                    0,
                    stride,
                    key.len(),
                );
                continue;
            }
            let verts = rtcSetNewGeometryBuffer(geom, BUFFER_TYPE_VERTEX, step as c_uint, FORMAT_FLOAT3, 12, key.len())
                as *mut f32;
            if !verts.is_null() {
                let out = std::slice::from_raw_parts_mut(verts, 3 * key.len());
                for (o, p) in out.chunks_exact_mut(3).zip(key) {
                    o.copy_from_slice(&p.to_array());
                }
            }
        }
        if quads.is_empty() {
            share_triangles(geom, m);
        } else {
            share_quads(geom, quads);
        }
        rtcCommitGeometry(geom);
        geom
    }
}

/// Hands Embree the mesh's own triangle array as `geom`'s index buffer (not copied).
///
/// # Safety
/// `geom` must be a live triangle geometry; the mesh must outlive it (the accel borrows
/// the world).
unsafe fn share_triangles(geom: RtcGeometry, m: &crate::mesh::MeshData) {
    // SAFETY: the array holds `m.triangles.len()` 12-byte index triples.
    unsafe {
        rtcSetSharedGeometryBuffer(
            geom,
            BUFFER_TYPE_INDEX,
            0,
            FORMAT_UINT3,
            m.triangles.as_ptr().cast(),
            0,
            12,
            m.triangles.len(),
        )
    }
}

/// Hands Embree `quads` as `geom`'s index buffer (not copied).
///
/// # Safety
/// `geom` must be a live quad geometry; `quads` must outlive it (the accel owns them).
unsafe fn share_quads(geom: RtcGeometry, quads: &[[u32; 4]]) {
    // SAFETY: the array holds `quads.len()` 16-byte index quadruples.
    unsafe {
        rtcSetSharedGeometryBuffer(geom, BUFFER_TYPE_INDEX, 0, FORMAT_UINT4, quads.as_ptr().cast(), 0, 16, quads.len())
    }
}

impl Drop for EmbreeAccel<'_> {
    fn drop(&mut self) {
        // SAFETY: the scenes and device were created by `new` and are released once.
        unsafe {
            for scene in self.scenes() {
                rtcReleaseScene(scene);
            }
            for s in &self.meshes {
                rtcReleaseScene(*s);
            }
            rtcReleaseDevice(self.device);
        }
    }
}
