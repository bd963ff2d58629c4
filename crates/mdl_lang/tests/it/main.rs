//! The `mdl_lang` crate's integration tests, one module per file, built as one test binary
//! (one link instead of 6: CI's disk and time). Run one file's tests with
//! `cargo test -p mdl_lang --test it <module>::`.

mod constructs;
mod corpus;
mod errors;
mod precedence;
mod robustness;
mod std_modules;
