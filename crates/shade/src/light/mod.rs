//! Lights as shading sees them: their shapes, their photometric profiles (IES files), and
//! (in [`crate::emission`]) what they emit.

pub mod ies;
pub mod mesh;
pub mod profiles;
pub mod shape;

pub use mesh::MeshShape;
pub use shape::Shape;
