//! The `mi` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 4: CI's disk and time). Run one file's tests with
//! `cargo test -p mi --test it <module>::`.

mod malformed;
mod mapped;
mod roundtrip;
mod syntax;
