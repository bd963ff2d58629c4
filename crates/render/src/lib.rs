//! Light transport: acceleration structures, the camera, sample generation, lights, the
//! path integrator, the film and its filters, tone mapping.
//!
//! A render goes [`world::World::from_scene`] → [`accel::build`] → [`render::render`] →
//! [`film::Film`]. Everything is in world space unless a name says otherwise; colours are
//! linear Rec.709 RGB.

pub mod accel;
pub mod camera;
pub mod classic;
pub mod environment;
pub mod fgcache;
pub mod film;
pub mod filter;
pub mod hair;
pub mod integrator;
pub mod light;
pub mod mesh;
pub mod photons;
pub mod ray;
pub mod render;
pub mod sampler;
pub mod tonemap;
pub mod tracer;
pub mod world;

pub use accel::{Accel, Backend};
pub use render::{render, EngineKind, Progress, Settings, Stats};
pub use world::World;
