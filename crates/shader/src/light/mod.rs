//! Lights as shading sees them ([`ShadingLight`]): their shapes, their photometric profiles
//! (IES files), light shaders the light loop evaluates in place ([`SimpleLight`]), and
//! (in the `material` crate's `emission`) what they emit.

pub mod deforming;
pub mod ies;
pub mod mesh;
pub mod profiles;
pub mod shape;
pub mod simple;

pub use deforming::DeformingMesh;
pub use mesh::MeshShape;
pub use shape::Shape;
pub use simple::SimpleLight;

/// A light instance as the shader model sees it, world space.
#[derive(Clone, Debug)]
pub struct ShadingLight {
    /// The light instance's name.
    pub name: String,
    /// The head of its light shader list.
    pub shader: Option<crate::graph::NodeId>,
    /// Point, spot or directional.
    pub kind: scene::LightKind,
    /// Position (centre of an area light).
    pub origin: glam::Vec3A,
    /// Direction the light shines (spot, directional), unit.
    pub direction: glam::Vec3A,
    /// Cosine of the spot's outer half-angle.
    pub spread: f32,
    /// The area shape, for area lights.
    pub shape: Option<Shape>,
    /// A `user` area light: its shader picks each sample's point on the light itself
    /// (see `Ctx::sample_light`).
    pub user: bool,
    /// Area samples in u and v.
    pub samples: (u32, u32),
    /// From this reflection/refraction level on, use these sample counts instead.
    pub low: Option<(u32, u32, u32)>,
    /// Seen by eye and secondary rays (area lights).
    pub visible: bool,
    /// Distance falloff exponent of physical lights.
    pub exponent: f32,
    /// World → light-local rotation of directions (light profile lookups; see
    /// [`crate::light::ies`] for the axes).
    pub to_local: glam::Mat3A,
    /// The light's own `lightprofile` statement (index into `Shading::lightprofiles`).
    pub profile: Option<u32>,
    /// Photon emission, if the light has `energy`.
    pub photons: Option<crate::photonmap::LightPhotons>,
}

impl ShadingLight {
    /// This light with `mesh` as its area shape (an object light's triangles where they
    /// are at some shutter time; see [`DeformingMesh`]).
    pub fn reshaped(&self, mesh: MeshShape) -> ShadingLight {
        ShadingLight { shape: Some(Shape::Mesh(std::sync::Arc::new(mesh))), ..self.clone() }
    }

    /// This light displaced by `by` (world → world, the light instance's motion at some
    /// time; see [`crate::Tracer::light_motion`]): its position, its direction, its frame
    /// for light profiles and its area shape move with it. `by` is a rigid motion (as
    /// mental ray moves an instance: rotation, translation, and a scale that moves with
    /// them): directions turn with its rotation and area shapes' edges scale with it; an
    /// object light's triangles ([`Shape::Mesh`]) are carried by `by` itself
    /// ([`MeshShape::displaced`]).
    pub fn moved(&self, by: glam::Affine3A) -> ShadingLight {
        let (_, rotation, _) = by.to_scale_rotation_translation();
        let turn = glam::Mat3A::from_quat(rotation);
        let edge = |v: glam::Vec3A| by.transform_vector3a(v);
        let shape = self.shape.as_ref().map(|shape| match shape {
            Shape::Point | Shape::Sphere { .. } => shape.clone(),
            Shape::Mesh(mesh) => Shape::Mesh(std::sync::Arc::new(mesh.displaced(by))),
            &Shape::Rect { u, v, normal, .. } => Shape::rect(edge(u), edge(v), turn * normal),
            &Shape::Disc { normal, radius } => Shape::Disc { normal: turn * normal, radius },
            &Shape::Cylinder { axis, radius } => Shape::Cylinder { axis: edge(axis), radius },
        });
        ShadingLight {
            origin: by.transform_point3a(self.origin),
            direction: (turn * self.direction).normalize_or(self.direction),
            to_local: self.to_local * turn.transpose(),
            shape,
            ..self.clone()
        }
    }
}
