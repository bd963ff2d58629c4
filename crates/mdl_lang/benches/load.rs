//! Time to load MDL modules: lexing, parsing, loading imports and the semantic pass.
//!
//! `cargo bench -p mdl_lang --bench load`

use std::path::PathBuf;

use criterion::{criterion_group, criterion_main, Criterion};
use mdl_lang::std_modules::STD_MODULES;
use mdl_lang::{load_module, MdlSearchPath, ModuleSet};

fn load(c: &mut Criterion) {
    c.bench_function("every built-in module", |b| {
        b.iter(|| {
            let mut set = ModuleSet::new(MdlSearchPath::new());
            for m in STD_MODULES {
                set.load(m.name).unwrap();
            }
            set
        })
    });
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/modules");
    let search = MdlSearchPath::for_scene(Some(&dir), &[], None);
    c.bench_function("export_multi with its imports", |b| b.iter(|| load_module("::export_multi", &search).unwrap()));
    c.bench_function("three-module chain with its imports", |b| {
        b.iter(|| load_module("::chain::top", &search).unwrap())
    });
}

criterion_group!(benches, load);
criterion_main!(benches);
