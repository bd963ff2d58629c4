//! Shading: BSDFs in a local frame, materials translated from the scene's mental ray
//! materials and MDL shaders, and the emission of lights.
//!
//! Colours are linear RGB with Rec.709 primaries ([`Rgb`]). BSDFs work in a local shading
//! frame whose +Z is the shading normal; directions point away from the surface.

pub mod base;
pub mod bsdf;
pub mod color;
pub mod emission;
pub mod frame;
pub mod light;
pub mod material;
pub mod mdl;
pub mod mia;
pub mod model;
pub mod texture;

pub use bsdf::{Bsdf, BsdfSample};
pub use color::{luminance, Rgb};
pub use frame::Frame;
pub use material::SurfaceMaterial;
