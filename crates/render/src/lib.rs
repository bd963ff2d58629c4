//! Light transport: acceleration structures, the camera, sample generation, lights, the
//! path and classic engines, the film and its filters, tone mapping.
//!
//! A render is a pipeline of named stages, each a function or type of this crate:
//!
//! 1. **load** — [`pipeline::load`]: parse the `.mi` file and build the scene at one
//!    `render` statement ([`pipeline::Loaded`]); settings that change the scene apply here
//!    ([`pipeline::set_resolution`], [`pipeline::choose_engine`]).
//! 2. **build the world** — [`pipeline::build_world`]: compile the shading and translate
//!    the scene into the [`World`] the engines trace (meshes, materials, lights), displaced
//!    surfaces included ([`displace`]).
//! 3. **prepare** — [`accel::build`] (the acceleration structure), then
//!    [`prepare::prepare`]: the environment's importance table, the photon maps, the final
//!    gather points ([`prepare::Prepared`]); a farm's parts may read the classic pre-passes
//!    from a file instead ([`prepass_file`], [`prepare::prepare_saved`]).
//! 4. **render** — [`render::render_prepared`]: the progressive sample passes, of the whole
//!    image, of one [`part`] of it, or of one of the [`strips`] of rows an image too large
//!    for one film is rendered in ([`Settings`]); [`render::render`] runs stages 3 and 4.
//! 5. **film** — [`film::Film`]: the per-pixel accumulators and the frame buffers made from
//!    them (colour, depth, normals, labels, motion, user buffers); [`output_shaders`] runs
//!    the camera's output shaders on it (Maya's glow); [`tonemap`] maps colour for 8-bit
//!    files.
//! 6. **write** — the `mira` command's `output` module writes the film's buffers to image
//!    files (and a part's to a partial EXR that `mira merge` reassembles).
//!
//! Everything is in world space unless a name says otherwise; colours are linear Rec.709
//! RGB.

pub mod accel;
pub mod camera;
pub mod classic;
pub mod displace;
pub mod engine;
pub mod environment;
pub mod fgcache;
pub mod film;
pub mod filter;
pub mod hair;
pub mod integrator;
pub mod light;
pub mod mesh;
pub mod motion;
pub mod octahedral;
pub mod output_shaders;
pub mod part;
mod path_band;
pub mod photons;
pub mod pipeline;
pub mod prepare;
pub mod prepass_file;
pub mod ray;
pub mod render;
pub mod sampler;
pub mod strips;
pub mod tonemap;
pub mod tracer;
pub mod world;

pub use accel::{Accel, Backend};
pub use render::{render, render_prepared, EngineKind, Progress, Settings, Stats};
pub use world::World;
