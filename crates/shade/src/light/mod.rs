//! Lights as shading sees them: their shapes, and (in [`crate::emission`]) what they emit.

pub mod mesh;
pub mod shape;

pub use mesh::MeshShape;
pub use shape::Shape;
