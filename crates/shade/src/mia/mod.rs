//! The Architectural library: `mia_material` (Arch & Design) and its helpers.

pub mod bsdf;
pub mod comparison;
pub mod exposure;
pub mod lobes;
pub mod params;
pub mod shader;
pub mod weights;
