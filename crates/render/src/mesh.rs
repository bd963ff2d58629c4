//! Triangle meshes as the renderer stores them (object space), hair ribbons' extra data
//! included; the world holds them, the acceleration structures and engines read them.

use glam::{Vec3, Vec3A};

pub mod ptex_split;

/// A triangle mesh, object space.
///
/// Positions and normals are stored packed (`Vec3`, 12 bytes a vertex each, as the scene
/// builds them, so the world takes the scene's arrays without copying them); readers widen
/// them to `Vec3A` ([`MeshData::position`], [`MeshData::normal`]) before any arithmetic, so
/// results are the same as with `Vec3A` storage.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Vertex shading normals (empty: use [`MeshData::normals_oct`], or if that is empty
    /// too, the geometric normal).
    pub normals: Vec<Vec3>,
    /// Vertex shading normals of a large mesh ([`LARGE_MESH_TRIANGLES`]), unit vectors as
    /// 32-bit octahedral codes ([`crate::octahedral`]: within 7e-5 radians of the scene's
    /// direction): 4 bytes a vertex instead of 12. Empty where [`MeshData::normals`] holds them.
    pub normals_oct: Vec<u32>,
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
    /// How far the shading normal leans from the interpolated vertex normal towards the
    /// triangle's geometric normal, 0…1 (a displacement approximation's `sharp`, see
    /// [`MeshData::sharpen`]); 0 for every mesh that has none.
    pub sharp: f32,
}

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
        Vec3A::from(self.positions[i as usize])
    }

    /// Object-space shading normal of vertex `i` (the mesh must have normals; those of
    /// [`MeshData::normals_oct`] are unit length, those of [`MeshData::normals`] as given).
    #[inline(always)]
    pub fn normal(&self, i: u32) -> Vec3A {
        match self.normals.get(i as usize) {
            Some(&n) => Vec3A::from(n),
            None => crate::octahedral::decode(self.normals_oct[i as usize]),
        }
    }

    /// Whether the mesh has vertex shading normals (in either form).
    #[inline(always)]
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty() || !self.normals_oct.is_empty()
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
        if self.triangles.len() >= LARGE_MESH_TRIANGLES && !self.normals.is_empty() {
            use rayon::prelude::*;
            self.normals_oct = self.normals.par_iter().map(|&n| crate::octahedral::encode(n.into())).collect();
            self.normals = Vec::new();
        }
    }

    /// Bytes held by the mesh's arrays (their lengths; what a triangle and its vertices
    /// cost, hair data aside).
    pub fn memory_bytes(&self) -> usize {
        let vecs = |v: &[Vec<Vec3A>]| v.iter().map(|a| a.len() * 16).sum::<usize>();
        self.positions.len() * 12
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
            self.positions.iter().map(|&p| Vec3A::from(p)).collect()
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
