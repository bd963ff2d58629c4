//! The `scene` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 4: CI's disk and time). Run one file's tests with
//! `cargo test -p scene --test it <module>::`.

mod geometry_shaders;
mod hostile;
mod ptex_quads;
mod support;
mod taken;
mod world;
