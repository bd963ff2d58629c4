//! The built-in standard modules load and check without errors.

use mdl_lang::std_modules::STD_MODULES;
use mdl_lang::{MdlSearchPath, ModuleSet};

#[test]
fn every_builtin_module_loads() {
    let mut set = ModuleSet::new(MdlSearchPath::new());
    for m in STD_MODULES {
        if let Err(e) = set.load(m.name) {
            panic!("{}: {e}", m.name);
        }
    }
    assert!(set.functions("::df::diffuse_reflection_bsdf").len() == 1);
    assert!(set.functions("::math::lerp").len() > 5);
    assert!(set.material("::nvidia::core_definitions::flex_material").is_some());
}

#[test]
fn core_definitions_on_the_search_path_replace_the_builtin_declarations() {
    let builtin = mdl_lang::load_module("::nvidia::core_definitions", &MdlSearchPath::new()).unwrap();
    let m = builtin.module("::nvidia::core_definitions").unwrap();
    assert!(m.builtin);
    assert!(matches!(builtin.material("::nvidia::core_definitions::diffuse").unwrap().body, mdl_lang::Body::Native));
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/override");
    let search = MdlSearchPath::for_scene(Some(&dir), &[], None);
    let found = mdl_lang::load_module("::nvidia::core_definitions", &search).unwrap();
    let m = found.module("::nvidia::core_definitions").unwrap();
    assert!(!m.builtin);
    let diffuse = found.material("::nvidia::core_definitions::diffuse").unwrap();
    assert!(matches!(diffuse.body, mdl_lang::Body::Expr(_)));
    assert_eq!(diffuse.params.len(), 1, "the file's signature, not the built-in one");
    assert!(found.material("::nvidia::core_definitions::flex_material").is_none());
    // The standard library modules are always mira's own.
    assert!(found.module("::df").unwrap().builtin);
}
