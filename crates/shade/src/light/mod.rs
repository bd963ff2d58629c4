//! Lights as shading sees them: their shapes, and (in [`crate::emission`]) what they emit.

pub mod shape;

pub use shape::Shape;
