//! The `bsdf` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 2: CI's disk and time). Run one file's tests with
//! `cargo test -p bsdf --test it <module>::`.

mod layered_lobes;
mod measured_bsdf;
mod multiscatter;
mod own_frames;
