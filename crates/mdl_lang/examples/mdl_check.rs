//! Loads MDL modules and reports what is wrong with them.
//!
//! `cargo run -p mdl_lang --example mdl_check -- [-M DIR]... MODULE_OR_FILE...`: each argument
//! is a module name (`::a::b`, found on the search path: the `-M` directories, then
//! `MDL_PATHS`) or an `.mdl` file. Prints `ok` and the number of materials and functions, or
//! the errors with their places; exits with 1 if any failed.

use std::path::{Path, PathBuf};

use mdl_lang::{MdlSearchPath, ModuleSet};

fn main() {
    let mut dirs = Vec::new();
    let mut targets = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "-M" {
            dirs.extend(args.next().map(PathBuf::from));
        } else {
            targets.push(a);
        }
    }
    let mut failed = false;
    for target in targets {
        let search = MdlSearchPath::from_env(None, &dirs);
        let mut set = ModuleSet::new(search);
        let result = if target.ends_with(".mdl") { set.load_file(Path::new(&target)) } else { set.load(&target) };
        match result {
            Ok(m) => println!("{target}: ok, {} materials, {} functions", m.materials().count(), m.functions().count()),
            Err(e) => {
                failed = true;
                println!("{target}:\n{e}");
            }
        }
    }
    std::process::exit(i32::from(failed));
}
