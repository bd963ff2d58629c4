//! Each MDL construct, read from a module in `tests/modules/` and checked in the tree.

use std::path::PathBuf;

use mdl_lang::ast::*;
use mdl_lang::{load_module, MdlSearchPath, ModuleSet};

fn modules_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/modules")
}

fn load(name: &str) -> ModuleSet {
    let search = MdlSearchPath::for_scene(Some(&modules_dir()), &[], None);
    match load_module(name, &search) {
        Ok(set) => set,
        Err(e) => panic!("{name} failed to load:\n{e}"),
    }
}

/// The body expression of a definition.
fn body(f: &Function) -> &Expr {
    match &f.body {
        Body::Expr(e) => e,
        other => panic!("{} has no expression body: {other:?}", f.name),
    }
}

/// The call an expression is, with its callee's resolution.
fn call(e: &Expr) -> &Call {
    match &e.kind {
        ExprKind::Call(c) => c,
        other => panic!("not a call: {other:?}"),
    }
}

/// The argument named `name` of a call.
fn arg<'a>(c: &'a Call, name: &str) -> &'a Expr {
    &c.args.iter().find(|a| a.name.as_deref() == Some(name)).unwrap_or_else(|| panic!("no argument {name}")).value
}

fn float(e: &Expr) -> f64 {
    match &e.kind {
        ExprKind::Float { value, .. } => *value,
        ExprKind::Int(i) => *i as f64,
        other => panic!("not a number: {other:?}"),
    }
}

#[test]
fn exporter_module_matte_has_typed_parameters_and_a_diffuse_body() {
    let set = load("::export_multi");
    let matte = set.material("::export_multi::matte").expect("matte is exported");
    assert_eq!(matte.params.len(), 2);
    assert_eq!((matte.params[0].name.as_str(), &matte.params[0].ty.ty), ("tint", &Type::Color));
    assert_eq!((matte.params[1].name.as_str(), &matte.params[1].ty.ty), ("roughness", &Type::FLOAT));
    // The default `color(0.8)` is a constructor of a colour from one float.
    let default = matte.params[0].default.as_ref().unwrap();
    assert_eq!(call(default).res, Resolution::Constructor(Type::Color));
    assert_eq!(float(&call(default).args[0].value), 0.8);
    // material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(tint: tint, …)))
    let m = call(body(matte));
    assert_eq!(m.res, Resolution::Constructor(Type::Material));
    let surface = call(arg(m, "surface"));
    assert_eq!(surface.res, Resolution::Constructor(Type::Struct("material_surface".into())));
    let bsdf = call(arg(surface, "scattering"));
    assert!(matches!(&bsdf.res, Resolution::Function { module, name, .. }
        if module == "::df" && name == "diffuse_reflection_bsdf"));
    let def = set.definition(&bsdf.res).unwrap();
    assert_eq!(def.params.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(), ["tint", "roughness", "handle"]);
    match &arg(bsdf, "tint").kind {
        ExprKind::Name(n) => assert_eq!(n.res, Resolution::Param(0)),
        other => panic!("{other:?}"),
    }
    assert_eq!(body(matte).ty, Some(Type::Material));
    assert_eq!(matte.display_name(), Some("Matte"));
    // Every exported material of the module is there.
    let names: Vec<&str> = set.module("::export_multi").unwrap().materials().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["matte", "glossy", "emitter", "glass"]);
}

#[test]
fn instance_arguments_replace_parameters_and_defaults_fill_the_rest() {
    let set = load("::export_multi");
    let matte = set.material("::export_multi::matte").unwrap();
    let red = Expr::new(ExprKind::Float { value: 0.5, double: false }, Default::default());
    let values = matte.bind_args(&[("tint", red)]).unwrap();
    assert_eq!(float(&values[0]), 0.5);
    assert_eq!(float(&values[1]), 0.0, "roughness keeps its default 0.0");
    let inst = matte.instantiate(&[]).unwrap().unwrap();
    let bsdf = call(arg(call(arg(call(&inst), "surface")), "scattering"));
    assert_eq!(float(&call(arg(bsdf, "tint")).args[0].value), 0.8, "tint default color(0.8) substituted");
    assert!(matte.bind_args(&[("tnt", Expr::new(ExprKind::Int(1), Default::default()))]).is_err());
}

#[test]
fn let_material_binds_locals_and_overrides_reach_them() {
    let set = load("::let_material");
    let plaster = set.material("::let_material::plaster").unwrap();
    let ExprKind::Let { decls, body: inner } = &body(plaster).kind else { panic!("not a let") };
    let names: Vec<(&str, &Type)> = decls.iter().map(|d| (d.name.as_str(), &d.ty.ty)).collect();
    assert_eq!(names, [("dirty", &Type::Color), ("rough", &Type::FLOAT), ("diffuse", &Type::Bsdf)]);
    // `dirty` = base * (1.0 - dirt): colour times float is a colour.
    assert_eq!(decls[0].init.as_ref().unwrap().ty, Some(Type::Color));
    assert_eq!(inner.ty, Some(Type::Material));
    // The layer's `base: diffuse` names the third local.
    let layer = call(arg(call(arg(call(inner), "surface")), "scattering"));
    match &arg(layer, "base").kind {
        ExprKind::Name(n) => assert_eq!(n.res, Resolution::Local(decls[2].id)),
        other => panic!("{other:?}"),
    }
    assert_eq!(arg(layer, "weight").ty, Some(Type::FLOAT), "?: of two floats is a float");
    // Overriding `base` replaces the parameter inside the let's first declaration.
    let grey = Expr::new(ExprKind::Float { value: 0.25, double: false }, Default::default());
    let inst = plaster.instantiate(&[("base", grey)]).unwrap().unwrap();
    let ExprKind::Let { decls, .. } = &inst.kind else { panic!() };
    let ExprKind::Binary { lhs, .. } = &decls[0].init.as_ref().unwrap().kind else { panic!() };
    assert_eq!(float(lhs), 0.25);
    assert!(set.material("::let_material::shade").is_some());
}

#[test]
fn import_chain_of_three_modules_with_using_and_alias() {
    let set = load("::chain::top");
    for m in ["::chain::top", "::chain::middle", "::chain::bottom"] {
        assert!(set.module(m).is_some(), "{m} loaded");
    }
    // `rough_diffuse(tint)` in the middle module, imported by `using`, resolves to the bottom.
    let coated = set.material("::chain::middle::coated").unwrap();
    let layer = call(arg(call(arg(call(body(coated)), "surface")), "scattering"));
    let res = &call(arg(layer, "base")).res;
    assert!(
        matches!(res, Resolution::Function { module, name, .. } if module == "::chain::bottom" && name == "rough_diffuse")
    );
    assert_eq!(set.definition(res).unwrap().ret.ty, Type::Bsdf);
    // The enum default through `using`, with its explicit value 4.
    let f = coated.param("f").unwrap().1;
    assert_eq!(f.ty.ty, Type::Enum("::chain::bottom::finish".into()));
    match &f.default.as_ref().unwrap().kind {
        ExprKind::Name(n) => {
            assert_eq!(n.res, Resolution::EnumValue { enum_type: "::chain::bottom::finish".into(), value: 4 })
        }
        other => panic!("{other:?}"),
    }
    // The alias `b::` reaches the bottom module's constant; the re-export is seen as middle's.
    let plain = set.material("::chain::top::plain").unwrap();
    match &plain.params[0].default.as_ref().unwrap().kind {
        ExprKind::Name(n) => assert_eq!(
            n.res,
            Resolution::Constant { module: "::chain::bottom".into(), name: "DEFAULT_ROUGHNESS".into() }
        ),
        other => panic!("{other:?}"),
    }
    assert_eq!(set.functions("::chain::middle::rough_diffuse").len(), 1);
    // The variant takes the middle material's parameters with its own defaults.
    let red = set.material("::chain::top::red_coat").unwrap();
    assert_eq!(red.params.len(), 2);
    let gloss = red.param("f").unwrap().1.default.as_ref().unwrap();
    match &gloss.kind {
        ExprKind::Name(n) => {
            assert_eq!(n.res, Resolution::EnumValue { enum_type: "::chain::bottom::finish".into(), value: 5 })
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn enums_number_their_values_and_convert_to_int() {
    let set = load("::enums");
    let e = set.enum_decl("::enums::surface_kind").unwrap();
    let values: Vec<(&str, i64)> = e.values.iter().map(|v| (v.name.as_str(), v.value)).collect();
    assert_eq!(
        values,
        [("kind_paint", 0), ("kind_metal", 10), ("kind_glass", 11), ("kind_skin", -3), ("kind_cloth", -2)]
    );
    let flags = set.enum_decl("::enums::flags").unwrap();
    let values: Vec<i64> = flags.values.iter().map(|v| v.value).collect();
    assert_eq!(values, [0, 1, 2, 3, 4]);
    let code = &set.functions("::enums::code")[0];
    assert_eq!(body(code).ty, Some(Type::INT));
    let by_kind = set.material("::enums::by_kind").unwrap();
    assert_eq!(by_kind.params[1].ty.ty, Type::Enum("::df::scatter_mode".into()));
    let cond = arg(call(arg(call(body(by_kind)), "surface")), "scattering");
    assert!(matches!(cond.kind, ExprKind::Conditional { .. }));
    assert_eq!(cond.ty, Some(Type::Bsdf));
}

#[test]
fn arrays_sized_deferred_and_constructed() {
    let set = load("::arrays");
    let sum3 = &set.functions("::arrays::sum3")[0];
    assert_eq!(sum3.params[0].ty.ty, Type::Array(Box::new(Type::FLOAT), ArrayLen::Fixed(3)));
    assert_eq!(body(sum3).ty, Some(Type::FLOAT));
    let average = &set.functions("::arrays::average")[0];
    assert_eq!(average.params[0].ty.ty, Type::Array(Box::new(Type::FLOAT), ArrayLen::Deferred("N".into())));
    let ramp = &set.functions("::arrays::ramp")[0];
    assert_eq!(ramp.ret.ty, Type::Array(Box::new(Type::FLOAT), ArrayLen::Fixed(4)), "COUNT resolved to 4");
    let mixed = set.material("::arrays::mixed").unwrap();
    let mix = call(arg(call(arg(call(body(mixed)), "surface")), "scattering"));
    let components = &mix.args[0].value;
    assert_eq!(
        components.ty,
        Some(Type::Array(Box::new(Type::Struct("::df::bsdf_component".into())), ArrayLen::Fixed(2)))
    );
    let mean = &set.functions("::arrays::mean_of_four")[0];
    assert_eq!(body(mean).ty, Some(Type::FLOAT));
}

#[test]
fn annotations_are_resolved_and_kept() {
    let set = load("::annotations");
    let module = set.module("::annotations").unwrap();
    assert_eq!(module.annotations.len(), 2);
    assert_eq!(module.annotations[0].string_arg(), Some("mira tests"));
    let painted = set.material("::annotations::painted").unwrap();
    assert_eq!(painted.display_name(), Some("Painted surface"));
    assert_eq!(painted.annotations.len(), 3);
    assert_eq!(
        painted.annotations[0].res,
        Resolution::Annotation { module: "::anno".into(), name: "display_name".into() }
    );
    let tint = &painted.params[0];
    let names: Vec<String> = tint.annotations.iter().map(|a| a.name.to_string()).collect();
    assert_eq!(names, ["anno::display_name", "anno::in_group"]);
    assert_eq!(tint.annotations[0].string_arg(), Some("Paint colour"));
    assert_eq!(painted.params[1].ty.frequency, Frequency::Uniform);
    let tone = set.enum_decl("::annotations::tone").unwrap();
    assert_eq!(tone.values[1].annotations[0].string_arg(), Some("Cold"));
}

#[test]
fn variants_take_the_base_parameters_with_new_defaults() {
    let set = load("::variants");
    let red = set.material("::variants::red_matte").unwrap();
    let v = red.variant.as_ref().unwrap();
    assert_eq!(v.resolved, Some(("::export_multi".to_string(), "matte".to_string())));
    let names: Vec<&str> = red.params.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["tint", "roughness"]);
    let tint = call(red.params[0].default.as_ref().unwrap());
    let rgb: Vec<f64> = tint.args.iter().map(|a| float(&a.value)).collect();
    assert_eq!(rgb, [0.8, 0.05, 0.05]);
    assert_eq!(float(red.params[1].default.as_ref().unwrap()), 0.0, "roughness keeps matte's default");
    assert!(matches!(&call(body(red)).res, Resolution::Material { module, name, .. }
        if module == "::export_multi" && name == "matte"));
    assert_eq!(set.definition(&call(body(red)).res).unwrap().name, "matte");
    // A variant of a variant keeps the first variant's defaults and adds its own.
    let dg = set.material("::variants::dim_green").unwrap();
    assert_eq!(float(dg.param("amount").unwrap().1.default.as_ref().unwrap()), 0.25);
    assert_eq!(call(dg.param("tint").unwrap().1.default.as_ref().unwrap()).args.len(), 3);
    assert_eq!(set.material("::variants::dim").unwrap().display_name(), Some("Dim"));
}

#[test]
fn functions_with_expression_and_statement_bodies() {
    let set = load("::functions");
    let square = &set.functions("::functions::square")[0];
    assert_eq!(body(square).ty, Some(Type::FLOAT));
    let ramp = &set.functions("::functions::smooth_ramp")[0];
    let Body::Block(stmts) = &ramp.body else { panic!() };
    assert!(matches!(stmts[0].kind, StmtKind::If { otherwise: Some(_), .. }));
    let StmtKind::Var(decls) = &stmts[1].kind else { panic!("{:?}", stmts[1].kind) };
    assert_eq!(decls.iter().map(|d| d.name.as_str()).collect::<Vec<_>>(), ["t", "u"]);
    assert!(
        matches!(stmts[3].kind, StmtKind::Expr(ref e) if matches!(e.kind, ExprKind::Assign { op: AssignOp::Compound(BinaryOp::Mul), .. }))
    );
    let count = &set.functions("::functions::count_down")[0];
    let Body::Block(stmts) = &count.body else { panic!() };
    assert!(matches!(stmts[1].kind, StmtKind::While { .. }));
    assert!(matches!(stmts[2].kind, StmtKind::DoWhile { .. }));
    let checker = &set.functions("::functions::checker")[0];
    assert_eq!(checker.frequency, Frequency::Varying);
    let checkered = set.material("::functions::checkered").unwrap();
    let geometry = call(arg(call(body(checkered)), "geometry"));
    assert_eq!(arg(geometry, "normal").ty, Some(Type::Vector(Scalar::Float, 3)));
}

#[test]
fn std_declarations_are_reachable_by_qualified_name() {
    let set = load("::export_multi");
    let specular = &set.functions("::df::specular_bsdf")[0];
    assert_eq!(specular.params[1].ty.ty, Type::Enum("::df::scatter_mode".into()));
    assert!(set.struct_decl("material_surface").is_some());
    assert!(set.struct_decl("::df::bsdf_component").is_some());
    assert!(set.material("::export_multi::nothing").is_none());
}

#[test]
fn scene_copies_of_the_modules_load() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mdl");
    let search = MdlSearchPath::for_scene(Some(&dir), &[], None);
    let mut set = ModuleSet::new(search);
    let mut loaded = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "mdl") {
            if let Err(e) = set.load_file(&path) {
                panic!("{}: {e}", path.display());
            }
            loaded += 1;
        }
    }
    assert_eq!(loaded, 10);
    assert!(set.module("::chain::top").is_none(), "only what is asked for and imported is loaded");
    set.load("::chain::top").unwrap();
    assert!(set.material("::export_multi::matte").is_some());
}

#[test]
fn switch_comma_step_constructor_constants_joined_strings_and_overload_choice() {
    let set = load("::functions");
    let classify = &set.functions("::functions::classify")[0];
    let Body::Block(stmts) = &classify.body else { panic!() };
    let StmtKind::Switch { cases, .. } = &stmts[1].kind else { panic!("{:?}", stmts[1].kind) };
    let labels: Vec<Option<i64>> = cases
        .iter()
        .map(|c| {
            c.label.as_ref().map(|l| match l.kind {
                ExprKind::Int(i) => i,
                _ => panic!(),
            })
        })
        .collect();
    assert_eq!(labels, [Some(0), Some(1), Some(2), None]);
    assert_eq!(cases[1].body.len(), 2, "case 1: the assignment and the break");
    let StmtKind::For { step: Some(step), .. } = &stmts[2].kind else { panic!() };
    assert!(matches!(&step.kind, ExprKind::Sequence(list) if list.len() == 2));
    let joined = &set.functions("::functions::joined")[0];
    assert!(matches!(&body(joined).kind, ExprKind::Str(s) if s == "first part, second part"));
    let Some(Decl::Const(axis)) = set.module("::functions").unwrap().decls.iter().find(|d| d.name() == "AXIS") else {
        panic!()
    };
    assert_eq!(call(&axis.value).res, Resolution::Constructor(Type::Vector(Scalar::Float, 3)));
    // math::pow(float3, float) picks the (float3, float) overload, not (color, color).
    let power = &set.functions("::functions::scaled_power")[0];
    let ExprKind::Binary { lhs, .. } = &body(power).kind else { panic!() };
    let chosen = set.definition(&call(lhs).res).unwrap();
    assert_eq!(chosen.name, "pow");
    let types: Vec<&Type> = chosen.params.iter().map(|p| &p.ty.ty).collect();
    assert_eq!(types, [&Type::Vector(Scalar::Float, 3), &Type::FLOAT]);
    assert_eq!(body(power).ty, Some(Type::Vector(Scalar::Float, 3)));
}

#[test]
fn std_reexports_every_standard_module_and_enum_imports_bring_values() {
    let mut set = ModuleSet::new(MdlSearchPath::new());
    set.load_source(
        "::uses_std",
        "mdl 1.7;\nimport ::std::*;\nusing ::df import scatter_mode;\n\
         export bsdf b(scatter_mode m = scatter_transmit) = std::specular_bsdf(mode: m);\n\
         export float big() = std::FLOAT_MAX * std::PI;\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let b = &set.functions("::uses_std::b")[0];
    match &b.params[0].default.as_ref().unwrap().kind {
        ExprKind::Name(n) => {
            assert_eq!(n.res, Resolution::EnumValue { enum_type: "::df::scatter_mode".into(), value: 1 })
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(&call(body(b)).res, Resolution::Function { module, name, .. }
        if module == "::df" && name == "specular_bsdf"));
}

#[test]
fn user_structs_construct_typedef_and_field_access() {
    let set = load("::structs");
    let s = set.struct_decl("::structs::layer_info").unwrap();
    let fields: Vec<(&str, &Type)> = s.fields.iter().map(|f| (f.name.as_str(), &f.ty.ty)).collect();
    assert_eq!(fields, [("tint", &Type::Color), ("weight", &Type::FLOAT), ("enabled", &Type::BOOL)]);
    assert_eq!(s.fields[2].ty.frequency, Frequency::Uniform);
    let make = &set.functions("::structs::make_info")[0];
    let info = Type::Struct("::structs::layer_info".into());
    assert_eq!(make.ret.ty, info, "the typedef names the struct");
    assert_eq!(call(body(make)).res, Resolution::Constructor(info.clone()));
    let m = set.material("::structs::from_info").unwrap();
    assert_eq!(m.params[0].ty.ty, info);
    let cond = arg(call(arg(call(body(m)), "surface")), "scattering");
    let ExprKind::Conditional { cond: test, then, .. } = &cond.kind else { panic!() };
    assert_eq!(test.ty, Some(Type::BOOL), "info.enabled is a bool");
    assert_eq!(arg(call(then), "tint").ty, Some(Type::Color), "info.tint * info.weight is a colour");
}

#[test]
fn unexported_names_are_invisible_to_importers_and_several_errors_are_reported() {
    let mut set = ModuleSet::new(MdlSearchPath::new());
    set.load_source("::lib", "mdl 1.7;\nfloat hidden() = 1.0;\nexport float shown() = 2.0;\n").unwrap();
    let err = set
        .load_source(
            "::user",
            "mdl 1.7;\nimport ::lib::*;\nexport float a() = lib::hidden();\nexport float b() = lib::shown() + nope;\n",
        )
        .unwrap_err();
    let found: Vec<(u32, u32, &str)> = err.problems.iter().map(|p| (p.line, p.col, p.message.as_str())).collect();
    assert_eq!(found.len(), 2, "{err}");
    assert_eq!((found[0].0, found[0].1), (3, 20));
    assert!(found[0].2.contains("no exported `hidden`"), "{err}");
    assert_eq!((found[1].0, found[1].1), (4, 35));
    assert!(found[1].2.contains("unknown name `nope`"), "{err}");
    assert!(set.module("::user").is_none(), "a module with errors is not kept");
    assert!(set.functions("::lib::hidden").is_empty() && set.functions("::lib::shown").len() == 1);
}

#[test]
fn uniform_values_pass_to_uniform_parameters() {
    // Literals, uniform parameters and parameters without a modifier are accepted.
    let mut set = ModuleSet::new(MdlSearchPath::new());
    set.load_source(
        "::uniform_ok",
        "mdl 1.7;\nimport ::df::*;\nimport ::math::*;\n\
         export edf a(uniform float e = 2.0) = df::spot_edf(exponent: e * math::PI);\n\
         export edf b(float e) = df::spot_edf(exponent: e, spread: 1.0);\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn hit_dependence_follows_state_calls_through_functions_defaults_and_lets() {
    let mut set = ModuleSet::new(MdlSearchPath::for_scene(Some(&modules_dir()), &[], None));
    set.load("::functions").unwrap();
    set.load("::export_multi").unwrap();
    set.load_source(
        "::hits",
        "mdl 1.7;\nimport ::df::*;\nimport ::base::*;\nimport ::math::*;\nimport ::state::*;\nimport ::functions::*;\n\
             export color fixed() = math::lerp(color(0.0), color(1.0), 0.5) * functions::square(0.5);\n\
             export float3 per_hit() = functions::bent_normal(0.2);\n\
             export color checked() = functions::checker(8.0);\n\
             export color textured() = base::file_texture(texture: texture_2d(\"wood.png\")).tint;\n\
             export color textured_at_a_point() = base::file_texture(texture: texture_2d(\"wood.png\"),\n\
                 uvw: base::texture_coordinate_info(float3(0.5), float3(1.0, 0.0, 0.0), float3(0.0, 1.0, 0.0))).tint;\n\
             export bsdf rough() = df::diffuse_reflection_bsdf(tint: color(0.5), roughness: 0.2);\n\
             export float let_fixed() = let float k = 2.0; in k * 3.0;\n\
             export float let_hit() = let float k = state::position().x; in k * 3.0;\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let m = set.module("::hits").unwrap();
    let expected = [
        ("fixed", false),
        ("per_hit", true),
        ("checked", true),
        ("textured", true),
        ("textured_at_a_point", false),
        ("rough", false),
        ("let_fixed", false),
        ("let_hit", true),
    ];
    let found: Vec<(&str, bool)> = expected
        .iter()
        .map(|(name, _)| {
            let f = m.functions().find(|f| f.name == *name).unwrap();
            (*name, set.varies_per_hit(body(f)))
        })
        .collect();
    assert_eq!(found, expected);
    // A material instance: constant arguments keep the BSDF fixed; a varying one does not.
    let matte = set.material("::export_multi::matte").unwrap();
    let inst = matte.instantiate(&[]).unwrap().unwrap();
    let scattering = arg(call(arg(call(&inst), "surface")), "scattering");
    assert!(!set.varies_per_hit(scattering));
    let per_hit_tint = body(m.functions().find(|f| f.name == "checked").unwrap()).clone();
    let inst = matte.instantiate(&[("tint", per_hit_tint)]).unwrap().unwrap();
    let scattering = arg(call(arg(call(&inst), "surface")), "scattering");
    assert!(set.varies_per_hit(scattering));
}
