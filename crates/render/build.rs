//! Finds Embree 3 — through pkg-config, or in the standard include and library
//! directories (Debian's `libembree-dev` ships no pkg-config file) or `EMBREE_DIR` — and,
//! when it is there, links it and enables the Embree backend (`cfg(embree)`).
//! `MIRA_NO_EMBREE=1` builds without it.

use std::path::{Path, PathBuf};

fn main() {
    println!("cargo::rustc-check-cfg=cfg(embree)");
    println!("cargo::rerun-if-env-changed=MIRA_NO_EMBREE");
    println!("cargo::rerun-if-env-changed=EMBREE_DIR");
    println!("cargo::rerun-if-env-changed=PKG_CONFIG_PATH");
    if std::env::var_os("MIRA_NO_EMBREE").is_some() {
        return;
    }
    if let Some(flags) = pkg_config() {
        for flag in flags.split_whitespace() {
            if let Some(dir) = flag.strip_prefix("-L") {
                println!("cargo::rustc-link-search=native={dir}");
            }
        }
        println!("cargo::rustc-cfg=embree");
        return;
    }
    let mut roots: Vec<PathBuf> = std::env::var_os("EMBREE_DIR").map(PathBuf::from).into_iter().collect();
    roots.extend(["/usr", "/usr/local"].map(PathBuf::from));
    for root in roots {
        if !root.join("include/embree3/rtcore.h").is_file() {
            continue;
        }
        let lib_dirs = [
            root.join("lib/x86_64-linux-gnu"),
            root.join("lib/aarch64-linux-gnu"),
            root.join("lib64"),
            root.join("lib"),
        ];
        if let Some(dir) = lib_dirs.iter().find(|d| has_library(d)) {
            println!("cargo::rustc-link-search=native={}", dir.display());
            println!("cargo::rustc-cfg=embree");
            return;
        }
    }
}

fn has_library(dir: &Path) -> bool {
    dir.join("libembree3.so").exists() || dir.join("libembree3.dylib").exists() || dir.join("embree3.lib").exists()
}

fn pkg_config() -> Option<String> {
    let out = std::process::Command::new("pkg-config").args(["--libs", "embree3"]).output().ok()?;
    out.status.success().then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}
