//! The Architectural library: `mia_material` (Arch & Design) and its helpers, and the
//! physical sun and sky.

pub mod aerial;
pub mod bokeh;
pub mod bsdf;
pub mod comparison;
pub mod envblur;
pub mod exposure;
pub mod interpolate;
pub mod light_surface;
pub mod lobes;
pub mod params;
pub mod photometric;
pub mod photon;
pub mod portal;
pub mod roundcorners;
pub mod shader;
pub mod sky;
pub mod sun;
pub mod weights;
