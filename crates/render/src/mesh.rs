//! Triangle meshes as the renderer stores them (object space), hair ribbons' extra data
//! included; the world holds them, the acceleration structures and engines read them.

use glam::{Vec3, Vec3A};

pub mod incidence;
pub mod ptex_split;
pub mod quad_pairs;

/// A triangle mesh, object space.
///
/// Positions and normals are stored packed (`Vec3`, 12 bytes a vertex each, as the scene
/// builds them, so the world takes the scene's arrays without copying them); readers widen
/// them to `Vec3A` ([`MeshData::position`], [`MeshData::normal`]) before any arithmetic, so
/// results are the same as with `Vec3A` storage. A large mesh keeps each vertex's position
/// and packed normal together instead ([`MeshData::vertices`]); the accessors read either.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Vertex shading normals (empty: use [`MeshData::normals_oct`] or
    /// [`MeshData::vertices`], or if both are empty too, the geometric normal).
    pub normals: Vec<Vec3>,
    /// Vertex shading normals of a large mesh ([`LARGE_MESH_TRIANGLES`]), unit vectors as
    /// 32-bit octahedral codes ([`crate::octahedral`]: within 7e-5 radians of the scene's
    /// direction): 4 bytes a vertex instead of 12. Empty where [`MeshData::normals`] holds them.
    pub normals_oct: Vec<u32>,
    /// A large mesh's vertices with their normals ([`MeshData::interleave`]): position and
    /// 32-bit octahedral normal in one 16-byte record, so that the hit's normals come in
    /// the cache lines Embree's leaf test loaded its positions from. When not empty,
    /// [`MeshData::positions`] and [`MeshData::normals_oct`] are empty; read positions
    /// through [`MeshData::position`] or [`MeshData::vertex_positions`].
    pub vertices: Vec<Vertex>,
    /// Vertex coordinates of each texture space (mental ray's `tex_list`).
    pub textures: Vec<Vec<Vec3A>>,
    /// Vertex user vectors (`u`), one array per user space, each one vector per vertex as
    /// written (packed `Vec3`, moved from the scene); empty for the meshes that have none,
    /// which then pay nothing per vertex or triangle. Shaders read them through
    /// [`shader::VertexData::User`].
    pub user: Vec<Vec<Vec3>>,
    /// Vertex bump basis vectors (u, v) of the first texture space, object space (empty if
    /// the geometry gives none).
    pub bump_basis: Vec<[Vec3A; 2]>,
    /// Triangles (counter-clockwise is the front).
    pub triangles: Vec<[u32; 3]>,
    /// Material slot of each triangle; empty when every triangle has slot 0 (readers take
    /// a missing entry as slot 0), which saves 4 bytes per triangle of one-material meshes.
    pub slots: Vec<u32>,
    /// Per triangle: its quad-mesh Ptex face and corners, its n-gon's first sub-quad face,
    /// or a lone triangle's first sub-quad face, packed ([`scene::mesh::ptex_quads`]; 4
    /// bytes a triangle); empty for meshes without polygons and in scenes that read no
    /// quad-mesh Ptex file.
    pub ptex_quads: Vec<u32>,
    /// The n-gons' outlines, prepared for the per-hit search
    /// ([`scene::mesh::ptex_ngons`]); empty where `ptex_quads` is.
    pub ptex_ngons: scene::mesh::ptex_ngons::Ngons,
    /// The refined subdivision surfaces' and ccmeshes' Ptex faces
    /// ([`scene::mesh::ptex_refined`]); empty where `ptex_quads` is.
    pub ptex_refined: scene::mesh::ptex_refined::Refined,
    /// For a mesh whose triangles were split from another's (uniform or adaptive
    /// displacement) where the scene reads a quad-mesh Ptex file: that one's Ptex faces,
    /// which each fine triangle keeps ([`ptex_split`]); `ptex_quads` is then empty.
    pub ptex_split: Option<std::sync::Arc<ptex_split::PtexSplit>>,
    /// For hair ribbons: where each vertex lies on its hair, and the hairs' tangents.
    pub hair: Option<HairData>,
    /// Vertex motion vectors, object space per shutter interval (empty: none).
    pub motion: Vec<Vec3A>,
    /// The motion vectors of motion steps 2…n (object space, offsets from the position at
    /// motion time 0): `motion_more[k][i]` is vertex i's of step k + 2 (empty: one step).
    pub motion_more: Vec<Vec<Vec3A>>,
    /// Vertex positions at shutter times spread evenly over the shutter (see
    /// [`crate::motion`]), when the vertices move while it is open; empty: they stay at
    /// `positions`.
    pub position_keys: Vec<Vec<Vec3A>>,
    /// The number of triangle pairs at the start of [`MeshData::triangles`] that make quads
    /// ([`quad_pairs`]: triangles 2k and 2k + 1 share an edge, the diagonal of quad k), for
    /// the acceleration structure; 0 for meshes not so ordered ([`MeshData::pair_into_quads`]).
    pub quad_pairs: u32,
    /// How far the shading normal leans from the interpolated vertex normal towards the
    /// triangle's geometric normal, 0…1 (a displacement approximation's `sharp`, see
    /// [`MeshData::sharpen`]); 0 for every mesh that has none.
    pub sharp: f32,
}

/// A vertex of an interleaved mesh ([`MeshData::vertices`]): its object-space position
/// and the 32-bit octahedral code of its unit shading normal ([`crate::octahedral`]),
/// 16 bytes, the position first (Embree reads it as a float3 with a 16-byte stride).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct Vertex {
    /// Object-space position.
    pub p: Vec3,
    /// The unit shading normal's octahedral code.
    pub n: u32,
}

/// The positions' allocation while [`MeshData::interleave`] writes its records on all
/// threads (each wave's threads touch disjoint floats).
#[derive(Clone, Copy)]
struct Records(*mut f32);

impl Records {
    /// The allocation's first float.
    fn ptr(&self) -> *mut f32 {
        self.0
    }
}

// SAFETY: shared only within `interleave`, whose waves give each thread its own floats.
#[allow(unsafe_code)]
unsafe impl Sync for Records {}

const _: () = assert!(std::mem::size_of::<Vertex>() == 16 && std::mem::align_of::<Vertex>() == 4);

/// Triangles from which a mesh counts as large: its vertex normals are kept in 32 bits
/// ([`MeshData::pack_normals_if_large`]) and Embree builds it compact. Measured on the
/// 4 M-triangle heavy scene (speed17): 4 bytes a triangle less, the image within the
/// Monte Carlo noise of the full normals'.
pub const LARGE_MESH_TRIANGLES: usize = 500_000;

/// Most motion steps (motion vectors per vertex) mental ray takes.
pub const MAX_MOTION_STEPS: usize = 15;

impl MeshData {
    /// Object-space position of vertex `i`.
    #[inline(always)]
    pub fn position(&self, i: u32) -> Vec3A {
        match self.positions.get(i as usize) {
            Some(&p) => Vec3A::from(p),
            None => Vec3A::from(self.vertices[i as usize].p),
        }
    }

    /// Number of vertices (in either form).
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.positions.len().max(self.vertices.len())
    }

    /// The object-space vertex positions in vertex order (in either form).
    pub fn vertex_positions(&self) -> impl Iterator<Item = Vec3> + '_ {
        self.positions.iter().copied().chain(self.vertices.iter().map(|v| v.p))
    }

    /// Object-space shading normal of vertex `i` (the mesh must have normals; those of
    /// [`MeshData::normals_oct`] are unit length, those of [`MeshData::normals`] as given).
    #[inline(always)]
    pub fn normal(&self, i: u32) -> Vec3A {
        match self.normals.get(i as usize) {
            Some(&n) => Vec3A::from(n),
            None => crate::octahedral::decode(match self.vertices.get(i as usize) {
                Some(v) => v.n,
                None => self.normals_oct[i as usize],
            }),
        }
    }

    /// Whether the mesh has vertex shading normals (in either form).
    #[inline(always)]
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty() || !self.normals_oct.is_empty() || !self.vertices.is_empty()
    }

    /// The shading normal of a hit given the interpolated vertex normal `ns` and the
    /// geometric normal `ng` (unit, world space, on one side): `ns` itself where
    /// [`MeshData::sharp`] is 0, else normalize((1 − s)·ns + s·ng), so that 1 gives the
    /// faceted normal of the triangle (mental ray's `sharp` of fine displacement).
    #[inline(always)]
    pub fn sharpen(&self, ns: Vec3A, ng: Vec3A) -> Vec3A {
        if self.sharp > 0.0 {
            (ns * (1.0 - self.sharp) + ng * self.sharp).normalize_or(ng)
        } else {
            ns
        }
    }

    /// Moves the vertex normals into their 32-bit form ([`MeshData::normals_oct`]) if the
    /// mesh is large ([`LARGE_MESH_TRIANGLES`]); small meshes keep them exactly as given.
    pub fn pack_normals_if_large(&mut self) {
        if self.triangles.len() >= LARGE_MESH_TRIANGLES {
            self.pack_normals();
        }
    }

    /// Moves the vertex normals into their 32-bit form ([`MeshData::normals_oct`]) whatever
    /// the mesh's size (nothing to do without normals or once packed).
    pub fn pack_normals(&mut self) {
        if !self.normals.is_empty() {
            use rayon::prelude::*;
            self.normals_oct = self.normals.par_iter().map(|&n| crate::octahedral::encode(n.into())).collect();
            self.normals = Vec::new();
        }
    }

    /// Reorders the triangles of a large mesh as pairs that share an edge
    /// ([`quad_pairs::pair_in_place`]), its material slots with them, and records the
    /// pairs in [`MeshData::quad_pairs`]: the acceleration structure then holds the mesh as
    /// quads (moving ones too: the pairing only reads the indices). Each triangle keeps its
    /// corners and winding (rotated at most). Nothing changes for other meshes, nor for a
    /// mesh whose data names triangles by index and corner (quad-mesh Ptex faces, the faces
    /// of the mesh it was split from) or per triangle beside the slots (hair tangents).
    pub fn pair_into_quads(&mut self) {
        if self.triangles.len() < LARGE_MESH_TRIANGLES
            || self.quad_pairs > 0
            || !self.ptex_quads.is_empty()
            || self.ptex_split.is_some()
            || self.hair.is_some()
        {
            return;
        }
        let vertex_count = self.vertex_count();
        let Some(pairing) = quad_pairs::pair_in_place(&mut self.triangles, vertex_count) else {
            return;
        };
        if !self.slots.is_empty() {
            self.slots = pairing.reorder(&self.slots);
        }
        self.quad_pairs = pairing.pairs;
    }

    /// Whether the mesh keeps its vertices interleaved ([`MeshData::vertices`]).
    #[inline]
    pub fn is_interleaved(&self) -> bool {
        !self.vertices.is_empty()
    }

    /// Moves the positions and normals (one a vertex: [`MeshData::normals`], encoded to
    /// 32 bits, or [`MeshData::normals_oct`]) into 16-byte records
    /// ([`MeshData::vertices`]) in the positions' own allocation, grown by a third (a large
    /// block is remapped, not copied), so that no second copy of the positions is made; the
    /// codes are encoded as the records are written (on all threads), so no array of them
    /// is allocated either. Nothing changes unless every vertex has a normal, the mesh's vertices hold
    /// still (no motion vectors or keys) and it keeps no quad-mesh Ptex faces or hair data
    /// (whose readers take the positions as a slice).
    #[allow(unsafe_code)] // the in-place move from 12- to 16-byte records; see the SAFETY notes
    pub fn interleave(&mut self) {
        let n = self.positions.len();
        if n == 0
            || (self.normals.len() != n && self.normals_oct.len() != n)
            || !self.motion.is_empty()
            || self.moves()
            || !self.ptex_quads.is_empty()
            || self.ptex_split.is_some()
            || self.hair.is_some()
        {
            return;
        }
        let normals = std::mem::take(&mut self.normals);
        let packed = std::mem::take(&mut self.normals_oct);
        // [`MeshData::pack_normals`]' codes, encoded as the records are written.
        let code = |i: usize| match normals.get(i) {
            Some(&v) => crate::octahedral::encode(v.into()),
            None => packed[i],
        };
        let mut positions = std::mem::take(&mut self.positions);
        // Room for n records (4 floats each) in whole records: a multiple of 4 `Vec3`s.
        let cap = (4 * n).div_ceil(3).next_multiple_of(4);
        positions.reserve_exact(cap - n);
        if positions.capacity() % 4 != 0 {
            // The allocator gave a capacity of a size that is not whole records: copied.
            self.vertices = positions.iter().enumerate().map(|(i, &p)| Vertex { p, n: code(i) }).collect();
            return;
        }
        let floats = positions.capacity() * 3;
        let base = Records(positions.as_mut_ptr().cast::<f32>());
        std::mem::forget(positions);
        // Record i (floats 4i..4i+4) replaces position i (floats 3i..3i+3), in waves from
        // the back: the vertices a ≤ i < b with 4a ≥ 3b read floats 3a..3b and write floats
        // 4a..4b, which are disjoint, and leave the positions below a (floats ..3a) alone,
        // so a wave's records are written on all threads in any order.
        let write = |i: usize| {
            // SAFETY: 4i + 4 ≤ 4n ≤ the allocation's `floats`; no other thread reads or
            // writes these floats in this wave (above); plain f32/u32 data, alignment 4.
            unsafe {
                let p = base.ptr().add(3 * i).cast::<[f32; 3]>().read();
                base.ptr().add(4 * i).cast::<Vertex>().write(Vertex { p: Vec3::from_array(p), n: code(i) });
            }
        };
        let mut b = n;
        while b > 4096 {
            use rayon::prelude::*;
            let a = (3 * b).div_ceil(4);
            (a..b).into_par_iter().with_min_len(4096).for_each(write);
            b = a;
        }
        // The first few back to front: record i overwrites only positions i and above,
        // read already.
        (0..b).rev().for_each(write);
        // SAFETY: the allocation is `floats` f32s, alignment 4: exactly `floats / 4`
        // records of 16 bytes, alignment 4 (the capacity is a multiple of 4 `Vec3`s); the
        // first n are written.
        self.vertices = unsafe { Vec::from_raw_parts(base.0.cast::<Vertex>(), n, floats / 4) };
    }

    /// The mesh with its vertices in separate arrays again (positions, packed normals):
    /// a copy for the code that reads [`MeshData::positions`] as a slice (displacement).
    pub fn to_plain(&self) -> MeshData {
        if !self.is_interleaved() {
            return self.clone();
        }
        // Every field named, so that a new one is not forgotten; the records themselves
        // are not cloned (a large mesh's would briefly cost 16 bytes a vertex more).
        let MeshData {
            positions: _,
            normals,
            normals_oct: _,
            vertices,
            textures,
            user,
            bump_basis,
            triangles,
            slots,
            ptex_quads,
            ptex_ngons,
            ptex_refined,
            ptex_split,
            hair,
            motion,
            motion_more,
            position_keys,
            quad_pairs,
            sharp,
        } = self;
        MeshData {
            positions: vertices.iter().map(|v| v.p).collect(),
            normals: normals.clone(),
            normals_oct: vertices.iter().map(|v| v.n).collect(),
            vertices: Vec::new(),
            textures: textures.clone(),
            user: user.clone(),
            bump_basis: bump_basis.clone(),
            triangles: triangles.clone(),
            slots: slots.clone(),
            ptex_quads: ptex_quads.clone(),
            ptex_ngons: ptex_ngons.clone(),
            ptex_refined: ptex_refined.clone(),
            ptex_split: ptex_split.clone(),
            hair: hair.clone(),
            motion: motion.clone(),
            motion_more: motion_more.clone(),
            position_keys: position_keys.clone(),
            quad_pairs: *quad_pairs,
            sharp: *sharp,
        }
    }

    /// Bytes held by the mesh's arrays (their lengths; what a triangle and its vertices
    /// cost, hair data aside).
    pub fn memory_bytes(&self) -> usize {
        let vecs = |v: &[Vec<Vec3A>]| v.iter().map(|a| a.len() * 16).sum::<usize>();
        self.positions.len() * 12
            + self.vertices.len() * 16
            + self.normals.len() * 12
            + self.normals_oct.len() * 4
            + vecs(&self.textures)
            + self.user.iter().map(|u| u.len() * 12).sum::<usize>()
            + self.bump_basis.len() * 32
            + self.triangles.len() * 12
            + self.slots.len() * 4
            + self.ptex_quads.len() * 4
            + self.ptex_ngons.memory_bytes()
            + self.ptex_refined.memory_bytes()
            + self.ptex_split.as_ref().map_or(0, |s| s.memory_bytes())
            + self.motion.len() * 16
            + vecs(&self.motion_more)
            + vecs(&self.position_keys)
    }

    /// Whether the vertices move while the shutter is open.
    #[inline]
    pub fn moves(&self) -> bool {
        !self.position_keys.is_empty()
    }

    /// Motion vectors per vertex (0: none).
    pub fn motion_steps(&self) -> usize {
        if self.motion.is_empty() {
            0
        } else {
            1 + self.motion_more.len()
        }
    }

    /// The first `n` motion vectors of vertex `i` (the offsets from its position at motion
    /// time 0 at motion times `1/n, 2/n, … 1`).
    pub fn motion_vectors(&self, i: usize, n: usize) -> Vec<Vec3A> {
        let mut v = vec![self.motion.get(i).copied().unwrap_or_default()];
        v.extend(self.motion_more.iter().take(n.saturating_sub(1)).map(|m| m.get(i).copied().unwrap_or_default()));
        v
    }

    /// The object-space vertices of triangle `tri` at shutter time `time`.
    #[inline]
    pub fn triangle_at(&self, tri: [u32; 3], time: f32) -> [Vec3A; 3] {
        if self.position_keys.is_empty() {
            tri.map(|i| self.position(i))
        } else {
            let (j, f) = crate::motion::key_segment(self.position_keys.len(), time);
            let (a, b) = (&self.position_keys[j], &self.position_keys[j + 1]);
            tri.map(|i| a[i as usize] + (b[i as usize] - a[i as usize]) * f)
        }
    }

    /// All object-space vertex positions at shutter time `time`.
    pub fn positions_at(&self, time: f32) -> Vec<Vec3A> {
        if self.position_keys.is_empty() {
            self.vertex_positions().map(Vec3A::from).collect()
        } else {
            let (j, f) = crate::motion::key_segment(self.position_keys.len(), time);
            let (a, b) = (&self.position_keys[j], &self.position_keys[j + 1]);
            a.iter().zip(b).map(|(a, b)| *a + (*b - *a) * f).collect()
        }
    }
}

/// Per-vertex and per-triangle hair data of a ribbon mesh.
#[derive(Clone, Debug, Default)]
pub struct HairData {
    /// Position along the hair of each vertex (0 at the root, 1 at the tip).
    pub along: Vec<f32>,
    /// Position across the ribbon of each vertex (0 one edge, 1 the other).
    pub across: Vec<f32>,
    /// Per triangle: the segment's unit tangent (root to tip) and the first segment's
    /// (the "scalp normal" mental ray gives hair shaders), object space.
    pub tangents: Vec<[Vec3A; 2]>,
}
