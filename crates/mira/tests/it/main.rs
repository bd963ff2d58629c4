//! The `mira` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 7: CI's disk and time). Run one file's tests with
//! `cargo test -p mira --test it <module>::`.

mod cli;
mod farm;
mod farm_prepass;
mod hostile;
mod image_formats;
mod motion_output;
mod strips;
