//! The physical sun and sky of mental ray's Architectural library (`mia_physicalsky`,
//! `mia_physicalsun`) and of Iray's `base::sun_and_sky`, as plain functions of directions
//! (world space, unit vectors, +Z up unless a model's `y_is_up` says otherwise) returning
//! linear Rec.709 RGB in the units the shaders document.
//!
//! - [`sky`]: the Perez/Preetham daylight sky, ground and sun disk ([`sky::PhysicalSky`]).
//! - [`perez`]: Perez's all-weather sky from measured irradiances (MDL's
//!   `base::perez_sun_and_sky`, [`perez::PerezSky`]).
//! - [`light_table`]: the sky's costly light terms interpolated between turbidities and
//!   sun heights, for skies whose haze varies per lookup.
//! - [`settings`]: what both share (turbidity, frame, units, colour tweaks).
//! - [`sun`]: the sun's spectrum through the atmosphere, its colour and illuminance
//!   ([`sun::PhysicalSun`]).
//!
//! The shaders that read these from their parameters live in the libraries (`mia`, `mdl`);
//! this crate knows nothing of shaders.

pub mod light_table;
pub mod perez;
pub mod settings;
pub mod sky;
pub mod sun;
