//! Triangle meshes as the renderer stores them (object space), hair ribbons' extra data
//! included; the world holds them, the acceleration structures and engines read them.

use glam::Vec3A;

/// A triangle mesh, object space.
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<Vec3A>,
    /// Vertex shading normals (empty: use the geometric normal).
    pub normals: Vec<Vec3A>,
    /// Vertex coordinates of each texture space (mental ray's `tex_list`).
    pub textures: Vec<Vec<Vec3A>>,
    /// Vertex bump basis vectors (u, v) of the first texture space, object space (empty if
    /// the geometry gives none).
    pub bump_basis: Vec<[Vec3A; 2]>,
    /// Triangles (counter-clockwise is the front).
    pub triangles: Vec<[u32; 3]>,
    /// Material slot of each triangle.
    pub slots: Vec<u32>,
    /// For hair ribbons: where each vertex lies on its hair, and the hairs' tangents.
    pub hair: Option<HairData>,
    /// Vertex motion vectors, object space per shutter interval (empty: none).
    pub motion: Vec<Vec3A>,
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
