//! Tessellated geometry in object space: triangle meshes and hair curves.
//!
//! One [`Mesh`] per `object` (all its groups, trilists and subdivision surfaces merged),
//! shared by every instance of the object. Materials are not bound here: each triangle
//! names a [`MaterialSlot`] (a label of a tagged object, a material written on the face, or
//! nothing), and each instance maps the slots to materials.

use glam::Vec3;

pub mod ptex_ngons;
pub mod ptex_quads;
pub mod ptex_refined;

/// What a face says about its material; the instance decides what it becomes.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum MaterialSlot {
    /// No material on the face: the instance's material applies.
    #[default]
    Inherit,
    /// A material named on the face (untagged objects).
    Named(String),
    /// An integer label (tagged objects): index into the instance's material array.
    Label(u32),
}

/// One texture (or user) space: a coordinate per vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TexSpace {
    /// How many components are meaningful (1 to 3).
    pub dim: u8,
    /// One coordinate per vertex, unused components zero.
    pub coords: Vec<Vec3>,
}

/// A triangle mesh in object space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The object's name.
    pub name: String,
    /// Vertex positions, object space.
    pub positions: Vec<Vec3>,
    /// Per-vertex shading normals, object space; empty when the geometry gives none (the
    /// geometric normal is used).
    pub normals: Vec<Vec3>,
    /// Texture spaces, in order (`t` references of group vertices, `t` layouts of trilists).
    pub textures: Vec<TexSpace>,
    /// User vector spaces (`u`), in order.
    pub user: Vec<TexSpace>,
    /// Per-vertex motion vectors (the first `m`), object space per shutter interval; empty
    /// when there are none.
    pub motion: Vec<Vec3>,
    /// The further motion vectors of `motion steps` 2…n (each vertex's second, third, …
    /// `m`): `motion_more[k]` holds every vertex's vector of step k + 2, aligned with
    /// `positions` (vertices without it get zero); empty with one step or none.
    pub motion_more: Vec<Vec<Vec3>>,
    /// Per-vertex surface derivatives (dP/du, dP/dv) when the geometry gives them (`d`);
    /// empty otherwise.
    pub derivatives: Vec<[Vec3; 2]>,
    /// Per-vertex bump basis vectors (u, v) of the first texture space (`t i bu bv`, `b`).
    pub bump_basis: Vec<[Vec3; 2]>,
    /// Triangles as vertex indices, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle: index into `slots`.
    pub triangle_slots: Vec<u32>,
    /// The distinct material slots of the faces.
    pub slots: Vec<MaterialSlot>,
    /// Per triangle: its quad-mesh Ptex face id and which corners of that quad its vertices
    /// are, its n-gon's first sub-quad face id, or, for a triangle that is a polygon of its
    /// own, its first sub-quad face id, packed ([`ptex_quads`]); empty, nothing per
    /// triangle, when the mesh is of lone triangles only ([`Mesh::ptex_triangles`]) or has
    /// no polygons (4 bytes per triangle otherwise).
    pub ptex_quads: Vec<u32>,
    /// With no [`Mesh::ptex_quads`] table: every triangle is a polygon of its own (3-vertex
    /// `c`/`p` polygons, strips, fans, trilists), triangle t's sub-quad faces 3t … 3t + 2
    /// ([`Mesh::materialize_ptex_triangles`] writes the table out).
    pub ptex_triangles: bool,
    /// The mesh's n-gons' outlines ([`ptex_ngons`]), where its n-gon triangles find their
    /// sub-quads.
    pub ptex_ngons: ptex_ngons::Ngons,
    /// The mesh's refined subdivision surfaces and ccmeshes ([`ptex_refined`]), where their
    /// triangles find their cage's Ptex faces.
    pub ptex_refined: ptex_refined::Refined,
    /// How many quad-mesh Ptex face ids the mesh's polygons and surfaces number
    /// ([`ptex_quads`]: a quad one, any other polygon one per outline vertex, a strip's or
    /// a fan's triangles 3 each; a subdivision surface's or ccmesh's control faces
    /// likewise).
    pub ptex_faces: u32,
    /// The first polygon that has no quad-mesh Ptex face (an n-gon of over
    /// [`ptex_quads::MAX_NGON_VERTICES`] vertices, or one past the face ids the packing
    /// holds) and its outline's vertex count.
    pub ptex_unmapped: Option<(mi::Span, usize)>,
    /// The first polygon with holes (given its outer boundary's sub-quads: mira's reading).
    pub ptex_holed: Option<mi::Span>,
    /// The first surface whose triangles have no quad-mesh Ptex faces (a free-form
    /// surface, which Ptex does not define): its place and what it is.
    pub ptex_surface: Option<(mi::Span, &'static str)>,
}

impl Mesh {
    /// An empty mesh named `name`.
    pub fn new(name: &str) -> Mesh {
        Mesh { name: name.to_string(), ..Mesh::default() }
    }

    /// Index of `slot`, added if new.
    pub fn slot(&mut self, slot: MaterialSlot) -> u32 {
        match self.slots.iter().position(|s| *s == slot) {
            Some(i) => i as u32,
            None => {
                self.slots.push(slot);
                (self.slots.len() - 1) as u32
            }
        }
    }

    /// Surface area of the triangles, object space.
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize].as_dvec3());
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// Axis-aligned bounds, object space (`None` when empty).
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))))
    }

    /// Bytes held by the arrays.
    pub fn memory_bytes(&self) -> usize {
        let spaces = |s: &[TexSpace]| s.iter().map(|t| t.coords.len() * 12).sum::<usize>();
        self.positions.len() * 12
            + self.normals.len() * 12
            + spaces(&self.textures)
            + spaces(&self.user)
            + self.motion.len() * 12
            + self.motion_more.iter().map(|m| m.len() * 12).sum::<usize>()
            + self.derivatives.len() * 24
            + self.bump_basis.len() * 24
            + self.triangles.len() * 12
            + self.triangle_slots.len() * 4
            + self.ptex_quads.len() * 4
            + self.ptex_ngons.memory_bytes()
            + self.ptex_refined.memory_bytes()
    }

    /// Writes out the table of a mesh of lone triangles ([`Mesh::ptex_triangles`]): before
    /// its triangles are removed or reordered (their face ids would follow their index).
    pub fn materialize_ptex_triangles(&mut self) {
        if self.ptex_triangles {
            self.ptex_triangles = false;
            self.ptex_quads = (0..self.triangles.len() as u32)
                .map(|t| t.checked_mul(3).map_or(ptex_quads::NONE, ptex_quads::encode_triangle))
                .collect();
        }
    }

    /// Appends `other`, offsetting its indices and merging its slots. Appended to an empty
    /// mesh (an object's only geometry, the common case), `other` moves in whole: its
    /// arrays are not copied (for a 4 M-triangle trilist, 112 MB less to copy and to hold
    /// twice while the scene is built).
    pub fn append(&mut self, other: Mesh) {
        if self.is_blank() && other.is_merged_form() {
            let name = std::mem::take(&mut self.name);
            *self = Mesh { name, ..other };
            return;
        }
        let base = self.positions.len() as u32;
        let had = self.positions.len();
        let slot_map: Vec<u32> = other.slots.iter().map(|s| self.slot(s.clone())).collect();
        self.append_ptex_quads(&other, base);
        self.triangles.extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
        self.triangle_slots.extend(other.triangle_slots.iter().map(|&s| slot_map[s as usize]));
        // Per-vertex arrays: keep them aligned with positions, padding what one side lacks.
        let n_other = other.positions.len();
        pad_merge(&mut self.normals, other.normals, had, n_other, Vec3::ZERO);
        pad_merge(&mut self.motion, other.motion, had, n_other, Vec3::ZERO);
        let steps = self.motion_more.len().max(other.motion_more.len());
        self.motion_more.resize(steps, Vec::new());
        let mut other_more = other.motion_more;
        other_more.resize(steps, Vec::new());
        for (mine, theirs) in self.motion_more.iter_mut().zip(other_more) {
            pad_merge(mine, theirs, had, n_other, Vec3::ZERO);
        }
        pad_merge(&mut self.derivatives, other.derivatives, had, n_other, [Vec3::ZERO; 2]);
        pad_merge(&mut self.bump_basis, other.bump_basis, had, n_other, [Vec3::ZERO; 2]);
        merge_spaces(&mut self.textures, other.textures, had, n_other);
        merge_spaces(&mut self.user, other.user, had, n_other);
        self.positions.extend(other.positions);
    }
}

impl Mesh {
    /// Whether the mesh holds nothing at all (its name aside).
    fn is_blank(&self) -> bool {
        self.positions.is_empty()
            && self.normals.is_empty()
            && self.textures.is_empty()
            && self.user.is_empty()
            && self.motion.is_empty()
            && self.motion_more.is_empty()
            && self.derivatives.is_empty()
            && self.bump_basis.is_empty()
            && self.triangles.is_empty()
            && self.triangle_slots.is_empty()
            && self.slots.is_empty()
            && self.ptex_quads.is_empty()
            && !self.ptex_triangles
            && self.ptex_ngons.is_empty()
            && self.ptex_refined.is_empty()
            && self.ptex_faces == 0
            && self.ptex_unmapped.is_none()
            && self.ptex_holed.is_none()
            && self.ptex_surface.is_none()
    }

    /// Appends the quad-mesh Ptex faces of `other` (before its triangles are appended; its
    /// vertices will start at `base`): its face ids follow this mesh's, a side without
    /// them pads with none; two meshes of lone triangles stay without a table.
    fn append_ptex_quads(&mut self, other: &Mesh, base: u32) {
        let (mine, theirs) = (self.triangles.len(), other.triangles.len());
        let offset = self.ptex_faces;
        let empty = |m: &Mesh| m.triangles.is_empty() && m.ptex_faces == 0;
        let lone = |m: &Mesh| m.ptex_triangles || empty(m);
        if lone(self) && lone(other) {
            self.ptex_triangles = self.ptex_triangles || other.ptex_triangles;
        } else if !self.ptex_quads.is_empty()
            || !other.ptex_quads.is_empty()
            || self.ptex_triangles
            || other.ptex_triangles
        {
            self.materialize_ptex_triangles();
            self.ptex_quads.resize(mine, ptex_quads::NONE);
            if other.ptex_triangles {
                let first = |t: u32| t.checked_mul(3).and_then(|f| f.checked_add(offset));
                self.ptex_quads
                    .extend((0..theirs as u32).map(|t| first(t).map_or(ptex_quads::NONE, ptex_quads::encode_triangle)));
            } else if other.ptex_quads.is_empty() {
                self.ptex_quads.resize(mine + theirs, ptex_quads::NONE);
            } else {
                let refined = self.ptex_refined.triangles;
                self.ptex_quads.extend(other.ptex_quads.iter().map(|&c| ptex_quads::offset(c, offset, refined)));
            }
        }
        self.ptex_ngons.append(&other.ptex_ngons, offset, base);
        self.ptex_refined.append(&other.ptex_refined, offset);
        self.ptex_faces = self.ptex_faces.saturating_add(other.ptex_faces);
        self.ptex_unmapped = self.ptex_unmapped.or(other.ptex_unmapped);
        self.ptex_holed = self.ptex_holed.or(other.ptex_holed);
        self.ptex_surface = self.ptex_surface.or(other.ptex_surface);
    }

    /// Whether appending the mesh to a blank one would give it back unchanged: its texture
    /// and user spaces hold a coordinate per vertex and its slots are distinct (what
    /// [`Mesh::append`]'s merge would otherwise pad or fold together).
    fn is_merged_form(&self) -> bool {
        let n = self.positions.len();
        self.textures.iter().chain(&self.user).all(|t| t.coords.len() == n)
            && self.slots.iter().enumerate().all(|(i, s)| !self.slots[..i].contains(s))
    }
}

/// Appends per-vertex `b` (for `n_b` vertices) to `a` (for `n_a`), padding with `zero`
/// where one side has no data; leaves both empty if neither has any.
fn pad_merge<T: Clone>(a: &mut Vec<T>, b: Vec<T>, n_a: usize, n_b: usize, zero: T) {
    if a.is_empty() && b.is_empty() {
        return;
    }
    a.resize(n_a, zero.clone());
    if b.is_empty() {
        a.resize(n_a + n_b, zero);
    } else {
        a.extend(b);
    }
}

fn merge_spaces(a: &mut Vec<TexSpace>, b: Vec<TexSpace>, n_a: usize, n_b: usize) {
    let count = a.len().max(b.len());
    a.resize(count, TexSpace::default());
    let mut b = b.into_iter();
    for space in a.iter_mut() {
        let other = b.next().unwrap_or_default();
        space.dim = space.dim.max(other.dim);
        space.coords.resize(n_a, Vec3::ZERO);
        if other.coords.is_empty() {
            space.coords.resize(n_a + n_b, Vec3::ZERO);
        } else {
            space.coords.extend(other.coords);
        }
    }
}

/// Hair curves of one object, object space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HairGeometry {
    /// The object's name.
    pub name: String,
    /// 1 (polylines) or 3 (cubic Bézier segments).
    pub degree: u8,
    /// Control point positions of all hairs.
    pub points: Vec<Vec3>,
    /// Radius per control point.
    pub radii: Vec<f32>,
    /// Hair `h` owns points `starts[h] .. starts[h + 1]`.
    pub starts: Vec<u32>,
    /// Per-hair texture scalars (`hair t k`): `k` per hair.
    pub hair_scalars: Vec<f32>,
    /// Per-vertex texture scalars (`vertex t k`): `k` per point.
    pub vertex_scalars: Vec<f32>,
    /// The material slot of all hairs.
    pub slot: MaterialSlot,
}

impl HairGeometry {
    /// Number of hairs.
    pub fn len(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn append_offsets_indices_and_merges_slots() {
        let mut a = Mesh::new("a");
        a.positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        a.triangles = vec![[0, 1, 2]];
        let s = a.slot(MaterialSlot::Label(1));
        a.triangle_slots = vec![s];
        let mut b = a.clone();
        b.normals = vec![Vec3::Z; 3];
        b.slots = vec![MaterialSlot::Named("m".into()), MaterialSlot::Label(1)];
        b.triangle_slots = vec![1];
        a.append(b);
        assert_eq!(a.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(a.triangle_slots, vec![0, 0]);
        assert_eq!(a.normals, vec![Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, Vec3::Z, Vec3::Z, Vec3::Z]);
        assert_eq!(a.area(), 1.0);
    }

    /// Appended to a blank mesh, a mesh comes back as it was (moved, not merged), and one
    /// the merge would change (a texture space without coordinates) is still merged.
    #[test]
    fn append_to_a_blank_mesh_keeps_the_mesh() {
        let mut m = Mesh::new("object");
        m.positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::ONE];
        m.normals = vec![Vec3::Z; 4];
        m.motion = vec![Vec3::X; 4];
        m.textures = vec![TexSpace { dim: 2, coords: vec![Vec3::ONE; 4] }];
        m.triangles = vec![[0, 1, 2], [1, 3, 2]];
        m.slots = vec![MaterialSlot::Label(7), MaterialSlot::Inherit];
        m.triangle_slots = vec![1, 0];
        let mut blank = Mesh::new("kept name");
        blank.append(m.clone());
        assert_eq!(blank, Mesh { name: "kept name".into(), ..m.clone() });

        let mut partial = m.clone();
        partial.user = vec![TexSpace { dim: 3, coords: Vec::new() }];
        let mut blank = Mesh::new("");
        blank.append(partial);
        assert_eq!(blank.user, vec![TexSpace { dim: 3, coords: vec![Vec3::ZERO; 4] }]);
        assert_eq!((blank.triangles, blank.triangle_slots), (m.triangles, m.triangle_slots));
    }
}
