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
