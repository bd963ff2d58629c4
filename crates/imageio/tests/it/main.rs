//! The `imageio` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 2: CI's disk and time). Run one file's tests with
//! `cargo test -p imageio --test it <module>::`.

mod common;

mod hand_written;
mod standard;
