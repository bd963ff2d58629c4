//! Every module of an outside corpus of MDL files loads, or fails only on a construct
//! mira names as not supported yet. Ignored by default: it needs the corpus on disk.
//!
//! Run with the NVIDIA MDL SDK's public examples (github:NVIDIA/MDL-SDK, `examples/mdl`):
//! `MIRA_MDL_CORPUS=/path/to/MDL-SDK/examples/mdl cargo test -p mdl_lang --test it corpus:: -- --ignored --nocapture`

use std::path::{Path, PathBuf};

use mdl_lang::{MdlSearchPath, ModuleSet};

fn mdl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            mdl_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "mdl") {
            out.push(path);
        }
    }
}

#[test]
#[ignore = "needs MIRA_MDL_CORPUS, a directory of MDL modules"]
fn corpus_modules_load_or_name_what_is_unsupported() {
    let root = PathBuf::from(std::env::var("MIRA_MDL_CORPUS").expect("MIRA_MDL_CORPUS names a directory"));
    let mut files = Vec::new();
    mdl_files(&root, &mut files);
    files.sort();
    let (mut ok, mut unsupported) = (0, 0);
    let mut wrong = Vec::new();
    for file in &files {
        let rel = file.strip_prefix(&root).unwrap().with_extension("");
        let name: Vec<String> = rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
        let name = format!("::{}", name.join("::"));
        let mut set = ModuleSet::new(MdlSearchPath::for_scene(Some(&root), &[], None));
        let started = std::time::Instant::now();
        match set.load(&name) {
            Ok(m) => {
                ok += 1;
                let (materials, functions) = (m.materials().count(), m.functions().count());
                let elapsed = started.elapsed();
                // The hit-dependence analysis terminates on every definition.
                let mut analysis = mdl_lang::HitDependence::new(&set);
                let m = set.module(&name).unwrap();
                let per_hit = m
                    .decls
                    .iter()
                    .filter(|d| match d {
                        mdl_lang::Decl::Function(f) => match &f.body {
                            mdl_lang::Body::Expr(e) => analysis.varies(e),
                            _ => false,
                        },
                        _ => false,
                    })
                    .count();
                println!(
                    "ok   {name}: {materials} materials, {functions} functions, {per_hit} vary per hit ({elapsed:.1?})"
                );
            }
            Err(e) if e.first().message.contains("not supported yet") => {
                unsupported += 1;
                println!("unsupported {name}: {}", e.first().message);
            }
            Err(e) => {
                println!("FAIL {name}:\n{e}");
                wrong.push(name);
            }
        }
    }
    println!("{ok} loaded, {unsupported} unsupported, {} failed, of {}", wrong.len(), files.len());
    assert!(wrong.is_empty(), "failed: {wrong:?}");
}
