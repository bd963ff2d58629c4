//! What the parser makes of each construct: the seed scene's element counts, and the
//! statement families of `tests/data/all_constructs.mi`, checked node by node.

use mi::ast::*;
use mi::stats::Stats;

fn parse(text: &str) -> mi::Parsed {
    let parsed = mi::parse_str("test.mi", text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    parsed
}

fn all_constructs() -> mi::Parsed {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/all_constructs.mi");
    let parsed = mi::parse_file(&path, &mi::ReadOptions::default()).unwrap();
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    assert_eq!(parsed.diagnostics.warning_count(), 0, "{}", parsed.diagnostics.render(&parsed.sources));
    parsed
}

/// Every item, included files and namespaces flattened, prefixes removed.
fn flat(items: &[Item]) -> Vec<&Item> {
    let mut out = Vec::new();
    for item in items {
        match item {
            Item::Include(inc) => out.extend(flat(&inc.items)),
            Item::Namespace(ns) => out.extend(flat(&ns.items)),
            Item::Modified { item, .. } => out.push(&**item),
            other => out.push(other),
        }
    }
    out
}

fn kw<'a>(stmts: &'a [Stmt], key: &str) -> &'a KwStmt {
    stmts
        .iter()
        .find_map(|s| match s {
            Stmt::Kw(k) if k.key == key => Some(k),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no '{key}' statement"))
}

fn block<'a>(items: &'a [&'a Item], f: impl Fn(&'a Item) -> Option<&'a Block>, name: &str) -> &'a Block {
    items.iter().find_map(|i| f(i).filter(|b| b.name.text == name)).unwrap_or_else(|| panic!("no block '{name}'"))
}

fn object<'a>(items: &'a [&'a Item], name: &str) -> &'a Object {
    items
        .iter()
        .find_map(|i| match i {
            Item::Object(o) if o.name.text == name => Some(o),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no object '{name}'"))
}

#[test]
fn seed_scene_has_the_expected_elements() {
    let text = include_str!("../../../../scenes/iray_cornell_box.mi");
    let parsed = mi::parse_str("iray_cornell_box.mi", text);
    assert!(!parsed.diagnostics.has_errors());
    let stats = Stats::of(&parsed.items);
    let count = |k: &str| stats.elements.get(k).copied().unwrap_or(0);
    assert_eq!(count("shader"), 4);
    assert_eq!(count("light"), 1);
    assert_eq!(count("camera"), 1);
    assert_eq!(count("object"), 5);
    assert_eq!(count("instance"), 7);
    assert_eq!(count("instgroup"), 1);
    assert_eq!(count("options"), 1);
    assert_eq!(count("render"), 1);
    assert_eq!(stats.includes, 2);
    assert_eq!(stats.polygons, 5);
    // Floor: 12 vertices, 2 holes -> 14 triangles; ceiling: 8, 1 hole -> 8; 3 walls -> 6.
    assert_eq!(stats.polygon_triangles, 28);
    assert_eq!(stats.trilist_triangles, 20);
    assert_eq!(stats.subdivision_faces, 6 + 8);
    // The two MDL modules are recorded, not read.
    assert!(parsed.includes.iter().all(|i| i.target == mi::IncludeTarget::Mdl));
    // The ccmesh caps hold 4 indices but 6 creases (the sample lost two indices): warned.
    assert_eq!(parsed.diagnostics.warning_count(), 3);
}

#[test]
fn seed_scene_values() {
    let parsed = parse(include_str!("../../../../scenes/iray_cornell_box.mi"));
    let items = flat(&parsed.items);
    let light = block(&items, |i| if let Item::Light(b) = i { Some(b) } else { None }, "Light_lgt");
    assert!(
        matches!(&light.stmts[0], Stmt::Shaders(ShaderList(l)) if matches!(&l[0], ShaderItem::Ref(n) if n.text == "Light_def"))
    );
    let rect = kw(&light.stmts, "rectangle");
    assert_eq!(rect.args, vec![Arg::Floats(vec![130.0, 0.0, 0.0]), Arg::Floats(vec![0.0, 105.0, 0.0]), Arg::Int(1)]);
    let camera = block(&items, |i| if let Item::Camera(b) = i { Some(b) } else { None }, "Camera");
    assert_eq!(kw(&camera.stmts, "focal").args, vec![Arg::Float(0.035)]);
    assert_eq!(kw(&camera.stmts, "resolution").args, vec![Arg::Int(1024), Arg::Int(1024)]);
    let tm = camera.stmts.iter().find_map(|s| match s {
        Stmt::Attribute(a) if a.name.as_ref().is_some_and(|n| n.text == "tm_tonemapper") => a.value.clone(),
        _ => None,
    });
    assert!(matches!(tm, Some(Value::Str(n)) if n.text == "mia_exposure_photographic"));
    let room = object(&items, "Room_obj");
    assert!(room.is_tagged());
    let Geometry::Group(g) = &room.geometry[0] else { panic!() };
    assert_eq!(g.vectors.len(), 32);
    assert_eq!(g.vertices.len(), 32);
    let floor: Vec<&[u32]> = g.polygons.loops(0).collect();
    assert_eq!(floor, vec![&[0, 1, 2, 3][..], &[4, 5, 6, 7][..], &[8, 9, 10, 11][..]]);
    assert_eq!(g.polygons.list[3].material, PolygonMaterial::Label(1));
    let sub = object(&items, "Subdiv_obj");
    let Geometry::Group(g) = &sub.geometry[0] else { panic!() };
    let GroupItem::Subdivision(s) = &g.items[0] else { panic!() };
    assert_eq!(s.faces.len(), 6);
    assert_eq!(s.faces[4].extras, vec![FaceExtra::Hierarchy(vec![Hira::Detail { mask: 256, indices: vec![8] }])]);
    assert_eq!(s.faces[5].extras, vec![FaceExtra::Crease { mask: 15, values: vec![1.0; 4] }]);
    let GroupItem::Approximate(a) = &g.items[1] else { panic!() };
    assert_eq!(a.target, Some("subdivision surface"));
    assert_eq!(a.technique, vec![ApproxTerm::Word("parametric"), ApproxTerm::Num(Num::Int(3))]);
}

#[test]
fn commands_and_preprocessor() {
    let parsed = all_constructs();
    let items = flat(&parsed.items);
    let commands: Vec<&KwStmt> =
        items.iter().filter_map(|i| if let Item::Command(Command::Kw(k)) = i { Some(k) } else { None }).collect();
    let keys: Vec<&str> = commands.iter().map(|k| k.key).collect();
    for expected in [
        "verbose",
        "link",
        "min version",
        "max version",
        "version",
        "memory",
        "echo",
        "set",
        "$lookup",
        "code",
        "system",
        "debug",
        "touch",
    ] {
        assert!(keys.contains(&expected), "{expected} missing from {keys:?}");
    }
    // The `$ifdef` took its first branch, `$ifeq` its first, the skipped line was not read.
    let sets: Vec<String> = commands
        .iter()
        .filter(|k| k.key == "set")
        .map(|k| if let Arg::Name(n) = &k.args[0] { n.text.clone() } else { String::new() })
        .collect();
    assert_eq!(sets, vec!["quality", "seen_quality", "high"]);
    assert!(items
        .iter()
        .any(|i| matches!(i, Item::Command(Command::CodeBlock { text, .. }) if text.contains("not_compiled"))));
    assert!(items
        .iter()
        .any(|i| matches!(i, Item::Registry(r) if r.key.text == "{MIRA_TEST}" && r.entries.len() == 2)));
    // base.mi and architectural.mi come from mira's built-in declarations; base.mdl is MDL.
    let targets: Vec<&mi::IncludeTarget> = parsed.includes.iter().map(|i| &i.target).collect();
    assert_eq!(
        targets,
        vec![
            &mi::IncludeTarget::Builtin("base.mi"),
            &mi::IncludeTarget::Builtin("architectural.mi"),
            &mi::IncludeTarget::Mdl
        ]
    );
    assert!(parsed.includes[1].angle);
}

#[test]
fn declarations() {
    let parsed = all_constructs();
    let items = flat(&parsed.items);
    let decl = |name: &str| {
        items
            .iter()
            .find_map(|i| match i {
                Item::Declare(d) if d.name.text == name => Some(d),
                _ => None,
            })
            .unwrap_or_else(|| panic!("no declaration {name}"))
    };
    let d = decl("my_lambert");
    assert_eq!(d.kind, DeclKind::Shader);
    assert_eq!(d.ret, Some(ParamType::Color));
    assert_eq!(d.params.len(), 9);
    assert_eq!(d.params[1].default, Some(Value::Tuple(vec![Num::Float(0.5); 3])));
    assert_eq!(d.params[3].ty, ParamType::Array(Box::new(ParamType::Light)));
    let ParamType::Array(layers) = &d.params[5].ty else { panic!() };
    let ParamType::Struct(fields) = &**layers else { panic!() };
    assert_eq!(fields[0].ty, ParamType::ColorTexture);
    assert_eq!(fields[1].default, Some(Value::Num(Num::Float(1.0))));
    assert_eq!(d.params[6].ty, ParamType::ScalarTexture);
    assert_eq!(d.params[7].default, Some(Value::Bool(true)));
    let body_keys: Vec<&str> =
        d.body.iter().filter_map(|b| if let DeclItem::Kw(k) = b { Some(k.key) } else { None }).collect();
    assert_eq!(
        body_keys,
        vec!["version", "apply", "scanline", "trace", "shadow", "face", "derivative", "object space", "volume level"]
    );
    assert!(d.body.iter().any(|b| matches!(b, DeclItem::Gui(g) if g.name.as_ref().unwrap().text == "gui_my_lambert")));
    let s = decl("my_struct_shader");
    assert!(matches!(&s.ret, Some(ParamType::Struct(f)) if f.len() == 2));
    assert!(s.params.is_empty());
    let legacy = decl("legacy_shader");
    assert!(legacy.legacy);
    assert_eq!(legacy.params.len(), 2);
    assert_eq!(decl("my_data").kind, DeclKind::Data);
    let phen = decl("my_phen");
    assert_eq!(phen.kind, DeclKind::Phenomenon);
    let inner = phen.body.iter().find_map(|b| match b {
        DeclItem::Item(Item::Shader(s)) => Some(s),
        _ => None,
    });
    let ShaderItem::Call { params, .. } = &inner.unwrap().list.0[0] else { panic!() };
    assert_eq!(params[1].value, Value::Interface(Name { text: "tint".into(), span: Default::default() }));
    assert!(phen.body.iter().any(|b| matches!(b, DeclItem::Kw(k) if k.key == "root")));
    assert!(phen.body.iter().any(|b| matches!(b, DeclItem::Item(Item::Material(_)))));
}

#[test]
fn shader_parameter_forms() {
    let parsed = all_constructs();
    let items = flat(&parsed.items);
    let mixer = items
        .iter()
        .find_map(|i| match i {
            Item::Shader(s) if s.name.text == "mixer" => Some(s),
            _ => None,
        })
        .unwrap();
    let ShaderItem::Call { decl, params, .. } = &mixer.list.0[0] else { panic!() };
    assert_eq!(decl.text, "mib_color_mix");
    let p = |name: &str| &params.iter().find(|p| p.name.text == name).unwrap().value;
    assert_eq!(p("num"), &Value::Num(Num::Int(2)));
    assert_eq!(p("weight_0"), &Value::Num(Num::Float(1.0)));
    assert!(matches!(p("color_0"), Value::Connect(n) if n.text == "tex.out"));
    assert_eq!(p("color_base"), &Value::Tuple(vec![Num::Int(0); 4]));
    let Value::Struct(fields) = p("nested") else { panic!() };
    let Value::Array(elems) = &fields[1].value else { panic!() };
    let Value::Struct(inner) = &elems[0] else { panic!() };
    assert_eq!(inner[1].value, Value::Null);
    assert!(
        matches!(p("inline"), Value::Define(item) if matches!(&**item, ShaderItem::Define { name, .. } if name.text == "inline_shader"))
    );
    let profiled = params.iter().find(|p| p.name.text == "profiled").unwrap();
    assert_eq!(profiled.colorprofile.as_ref().unwrap().text, "linear");
    assert!(matches!(p("matrix"), Value::Tuple(v) if v.len() == 16));
    assert!(matches!(p("names"), Value::Array(v) if v.len() == 2));
    assert_eq!(p("empty"), &Value::Array(Vec::new()));
    // A shader list of two items.
    let chain = items.iter().find_map(|i| match i {
        Item::Shader(s) if s.name.text == "chain" => Some(s),
        _ => None,
    });
    assert_eq!(chain.unwrap().list.0.len(), 2);
}

#[test]
fn options_camera_lights() {
    let parsed = all_constructs();
    let items = flat(&parsed.items);
    let opt = block(&items, |i| if let Item::Options(b) = i { Some(b) } else { None }, "opt");
    assert_eq!(kw(&opt.stmts, "samples").args, vec![Arg::Int(-1), Arg::Int(2)]);
    assert_eq!(
        kw(&opt.stmts, "filter").args,
        vec![Arg::Word("clip"), Arg::Word("mitchell"), Arg::Float(4.0), Arg::Float(4.0)]
    );
    assert_eq!(kw(&opt.stmts, "trace depth").args, vec![Arg::Int(4), Arg::Int(4), Arg::Int(8)]);
    assert_eq!(kw(&opt.stmts, "finalgather trace depth").args.len(), 4);
    assert_eq!(kw(&opt.stmts, "finalgather accuracy").args[0], Arg::Word("view"));
    assert_eq!(kw(&opt.stmts, "grid size").args, vec![Arg::Num(Num::Float(4.0))]);
    assert_eq!(kw(&opt.stmts, "frame buffer").args.len(), 2);
    assert!(matches!(&kw(&opt.stmts, "state").args[0], Arg::ShaderArray(l) if l.0.len() == 2));
    let Arg::Approx(a) = &kw(&opt.stmts, "approximate").args[0] else { panic!() };
    assert!(a.all && a.target == Some("displace"));
    let string_options: Vec<&str> = opt
        .stmts
        .iter()
        .filter_map(|s| if let Stmt::StringOption { name, .. } = s { Some(name.as_str()) } else { None })
        .collect();
    assert_eq!(
        string_options,
        vec!["unified sampling", "samples quality", "samples min", "progressive", "finalgather mode"]
    );
    let attrs: Vec<&Attribute> =
        opt.stmts.iter().filter_map(|s| if let Stmt::Attribute(a) = s { Some(a) } else { None }).collect();
    assert_eq!(attrs.len(), 6);
    assert_eq!(attrs[0].value, Some(Value::Num(Num::Int(100))));
    assert_eq!(attrs[4].value, Some(Value::Tuple(vec![Num::Int(1); 4])));
    assert_eq!(attrs[5].ty.text, "visible");
    assert_eq!(attrs[5].modifiers[0].text, "override");

    let cam = block(&items, |i| if let Item::Camera(b) = i { Some(b) } else { None }, "cam");
    let outputs: Vec<&Output> =
        cam.stmts.iter().filter_map(|s| if let Stmt::Output(o) = s { Some(o) } else { None }).collect();
    assert_eq!(outputs.len(), 7);
    assert!(
        matches!(&outputs[0].kind, OutputKind::File { format, file, .. } if format.text == "exr" && file.text == "beauty.exr")
    );
    assert!(outputs[1].types.is_none());
    assert!(matches!(&outputs[2].kind, OutputKind::File { options, .. } if options[0].key == "quality"));
    assert!(matches!(&outputs[3].kind, OutputKind::Shader(_)) && outputs[3].types.is_some());
    assert!(matches!(&outputs[5].kind, OutputKind::Shader(l) if matches!(&l.0[0], ShaderItem::Call { .. })));
    assert!(outputs[6].colorprofile.is_some());
    let fbs: Vec<&Framebuffer> =
        cam.stmts.iter().filter_map(|s| if let Stmt::Framebuffer(f) = s { Some(f) } else { None }).collect();
    assert_eq!(fbs.len(), 2);
    assert_eq!(fbs[0].fields.len(), 5);
    assert!(matches!(&kw(&cam.stmts, "lens").args[0], Arg::Shaders(l) if l.0.len() == 2));
    assert!(kw(&cam.stmts, "volume").args.is_empty());
    assert_eq!(kw(&cam.stmts, "field").args, vec![Arg::Int(0)]);

    let area = block(&items, |i| if let Item::Light(b) = i { Some(b) } else { None }, "area");
    assert_eq!(kw(&area.stmts, "rectangle").args.len(), 2 + 5);
    let off = block(&items, |i| if let Item::Light(b) = i { Some(b) } else { None }, "off_area");
    assert!(kw(&off.stmts, "rectangle").args.is_empty());
    let point = block(&items, |i| if let Item::Light(b) = i { Some(b) } else { None }, "point");
    assert_eq!(kw(&point.stmts, "globillum photons").args, vec![Arg::Int(10000), Arg::Int(20000)]);
    assert_eq!(kw(&point.stmts, "shadowmap filter").args, vec![Arg::Word("gauss"), Arg::Float(2.0)]);
    assert_eq!(kw(&point.stmts, "energy").args, vec![Arg::Floats(vec![700.0; 3])]);
}

#[test]
fn materials_textures_instances() {
    let parsed = all_constructs();
    let items = flat(&parsed.items);
    let mtl = items.iter().find_map(|i| if let Item::Material(m) = i { Some(m) } else { None }).unwrap();
    assert_eq!(mtl.shaders.as_ref().unwrap().0.len(), 2);
    let slots: Vec<&str> =
        mtl.stmts.iter().filter_map(|s| if let Stmt::Kw(k) = s { Some(k.key) } else { None }).collect();
    assert_eq!(slots, vec!["opaque", "shadow", "photon", "displace", "volume", "environment", "contour"]);
    let textures: Vec<&Texture> =
        items.iter().filter_map(|i| if let Item::Texture(t) = i { Some(t) } else { None }).collect();
    assert_eq!(textures.len(), 6);
    assert_eq!(textures[0].flags.iter().map(|f| f.key).collect::<Vec<_>>(), vec!["local", "filter"]);
    assert!(matches!(&textures[1].source, TextureSource::File { size: Some(s), .. } if s == &vec![512, 512]));
    assert!(matches!(&textures[2].source, TextureSource::File { filetype, .. } if filetype.len() == 1));
    assert_eq!(
        textures[3].source,
        TextureSource::Pixels {
            dims: vec![2, 1],
            pieces: vec![vec![0x00, 0x11, 0x22, 0x33], vec![0x44, 0x55, 0x66, 0x77]]
        }
    );
    assert!(matches!(&textures[4].source, TextureSource::Shader(_)));
    assert_eq!(textures[5].colorprofile.as_ref().unwrap().text, "linear");

    let inst = items
        .iter()
        .find_map(|i| match i {
            Item::Instance(x) if x.name.text == "poly_inst" => Some(x),
            _ => None,
        })
        .unwrap();
    assert!(matches!(&inst.target, InstanceTarget::Element(n) if n.text == "poly"));
    let Arg::Floats(m) = &kw(&inst.stmts, "transform").args[0] else { panic!() };
    assert_eq!(&m[12..], &[-1.0, 2.0, -3.0, 1.0]);
    assert!(matches!(&kw(&inst.stmts, "material").args[0], Arg::Names(n) if n.len() == 2));
    let light = kw(&inst.stmts, "light");
    assert!(matches!(&light.args[..], [Arg::Name(e), Arg::Names(l)] if e.text == "exclusive" && l.len() == 2));
    assert!(matches!(&kw(&inst.stmts, "approximate").args[0], Arg::Tree(TokenTree::Bracket(_))));
    assert_eq!(inst.params.as_ref().unwrap().len(), 2);
    let geo = items
        .iter()
        .find_map(|i| match i {
            Item::Instance(x) if x.name.text == "geo_inst" => Some(x),
            _ => None,
        })
        .unwrap();
    assert!(matches!(&geo.target, InstanceTarget::Geometry(_)));
    let group = items.iter().find_map(|i| if let Item::Instgroup(g) = i { Some(g) } else { None }).unwrap();
    assert_eq!(group.members.len(), 5);
    assert_eq!(group.stmts.len(), 2);
    let datas: Vec<&Data> = items.iter().filter_map(|i| if let Item::Data(d) = i { Some(d) } else { None }).collect();
    assert_eq!(datas[0].tag, Some(7));
    assert_eq!(datas[0].body, DataBody::Bytes { size: 4, pieces: vec![vec![10, 11], vec![12, 13]] });
    assert!(matches!(&datas[1].body, DataBody::Params { params, .. } if params.len() == 2));
    assert!(matches!(&datas[2].body, DataBody::File(f) if f.text == "payload.bin"));
}

#[test]
fn group_geometry() {
    let parsed = all_constructs();
    let items = flat(&parsed.items);
    let o = object(&items, "poly");
    assert!(o.is_tagged());
    assert_eq!(o.stmts.len(), 16);
    let Geometry::Group(g) = &o.geometry[0] else { panic!() };
    assert_eq!(g.name.as_ref().unwrap().text, "poly_group");
    assert_eq!(g.merge, Some(0.001));
    assert_eq!(g.vectors.len(), 11);
    assert_eq!(g.vertices.len(), 7);
    assert_eq!(g.vertices[0], Vertex { pos: 0, normal: Some(7), attrs_end: 1 });
    assert_eq!(
        g.vertex_attrs(3),
        &[
            VertexAttr::Tex { index: 8, basis: Some([9, 10]) },
            VertexAttr::Motion(7),
            VertexAttr::User(7),
            VertexAttr::Deriv { count: 2, idx: [8, 9, 0, 0, 0] }
        ]
    );
    let kinds: Vec<PolygonKind> = g.polygons.list.iter().map(|p| p.kind).collect();
    use PolygonKind::*;
    assert_eq!(kinds, vec![Convex, ConvexLegacy, General, Strip, Fan]);
    let loops: Vec<&[u32]> = g.polygons.loops(2).collect();
    assert_eq!(loops, vec![&[0, 1, 2, 3][..], &[4, 5, 6][..], &[6, 5, 4][..]]);
    assert_eq!(g.polygons.list[2].material, PolygonMaterial::Label(2));

    let named = object(&items, "named_polys");
    let Geometry::Group(g) = &named.geometry[0] else { panic!() };
    assert_eq!(g.polygons.list[0].material, PolygonMaterial::Named(0));
    assert_eq!(g.polygons.list[1].material, PolygonMaterial::Inherit);
    assert_eq!(g.polygons.material_names.iter().map(|n| n.as_str()).collect::<Vec<_>>(), vec!["mtl", ""]);

    let subd = object(&items, "subd");
    assert!(subd.is_tagged());
    let Geometry::Group(g) = &subd.geometry[0] else { panic!() };
    assert_eq!(
        g.vertex_attrs(3),
        &[VertexAttr::Feature { kind: FeatureKind::Corner, arg: Some(FeatureArg::Level(2)) }]
    );
    let GroupItem::Subdivision(s) = &g.items[0] else { panic!() };
    assert_eq!(s.counts, Some(vec![0, 0, 1, 0]));
    assert_eq!(s.faces[0].material, FaceMaterial::Label(0));
    let FaceExtra::Hierarchy(h) = &s.faces[0].extras[1] else { panic!() };
    assert_eq!(h.len(), 5);
    assert!(matches!(&h[4], Hira::Child { child: 3, body } if body.len() == 1));
    assert!(s.faces[1].quad_keyword);
    assert_eq!(s.derivatives, vec![Derivative { order: 1, space: Some(0) }]);
    let GroupItem::Ccmesh(c) = &g.items[2] else { panic!() };
    assert_eq!((c.faces.len(), c.indices.len(), c.creases.len()), (2, 7, 4));
    let GroupItem::Approximate(a) = &g.items[3] else { panic!() };
    assert_eq!(a.flags, vec!["visible"]);
    assert_eq!(a.technique.iter().filter(|t| **t == ApproxTerm::Percent).count(), 2);

    let nurbs = object(&items, "nurbs");
    assert_eq!(nurbs.bases.len(), 4);
    assert!(matches!(&nurbs.bases[1].kind, BasisKind::Bspline(3)) && nurbs.bases[1].rational);
    let Geometry::Group(g) = &nurbs.geometry[0] else { panic!() };
    let GroupItem::Curve(c1) = &g.items[0] else { panic!() };
    assert_eq!(c1.params, vec![0.0, 1.0]);
    assert_eq!(c1.refs.len(), 4);
    assert_eq!(c1.special.as_ref().unwrap().len(), 2);
    let GroupItem::Curve(c2) = &g.items[1] else { panic!() };
    assert_eq!(c2.refs[1].weight, Some((true, 0.5)));
    assert_eq!(c2.refs[2].weight, Some((false, 2.0)));
    let GroupItem::Surface(s) = &g.items[3] else { panic!() };
    assert_eq!(s.u.range, Some((0.0, 1.0)));
    assert_eq!(s.extras.len(), 5);
    assert!(matches!(&s.extras[0], SurfaceExtra::Texture { volume: true, vector: true, .. }));
    assert!(matches!(&g.items[5], GroupItem::Connect(_)));
    let GroupItem::Approximate(a) = &g.items[6] else { panic!() };
    assert_eq!(a.names.len(), 2);
}

#[test]
fn trilists_and_hair() {
    let parsed = all_constructs();
    let items = flat(&parsed.items);
    let t = object(&items, "tri");
    let Geometry::Trilist(list) = &t.geometry[0] else { panic!() };
    assert_eq!(list.floats_per_line(), 3 + 3 + 2 + 6 + 3);
    assert_eq!(list.floats.len(), 4 * 17);
    assert_eq!(list.triangles.indices, vec![0, 1, 2, 0, 2, 3]);
    assert_eq!(list.border.as_ref().unwrap().indices, vec![0, 1, 3]);
    assert_eq!(list.topology, Some(vec![1, 2, 3]));
    assert!(matches!(&t.stmts[1], Stmt::Kw(k) if k.key == "approximate"));
    let tm = object(&items, "tri_materials");
    let Geometry::Trilist(list) = &tm.geometry[0] else { panic!() };
    let mats: Vec<(u32, &str)> =
        list.triangles.materials.as_ref().unwrap().iter().map(|(i, n)| (*i, n.as_str())).collect();
    assert_eq!(mats, vec![(0, "mtl"), (1, "other")]);
    let h = object(&items, "furry");
    let Geometry::Hair(hair) = &h.geometry[0] else { panic!() };
    assert_eq!(hair.header.len(), 8);
    assert_eq!(hair.scalars.len(), 18);
    assert_eq!(hair.offsets, vec![0, 18]);
}

#[test]
fn binary_vectors_and_binary_trilists() {
    // Big-endian floats, one containing the byte 0x60 (a backquote) to check count-driven reads.
    let be = |v: f32| v.to_be_bytes();
    let tricky = f32::from_be_bytes([0x60, 0x60, 0x60, 0x60]);
    let mut text = b"object \"o\"\n tagged on\n group\n".to_vec();
    for v in [[1.0f32, 2.0, 3.0], [tricky, -0.5, 1e-5]] {
        text.push(b'`');
        for c in v {
            text.extend_from_slice(&be(c));
        }
        text.extend_from_slice(b"`\n");
    }
    text.extend_from_slice(b" v 0 v 1\n end group\n trilist vertex 2 p\n triangle 1\n scalar `");
    for c in [0.0f32, 1.0, 2.0, tricky, 4.0, 5.0] {
        text.extend_from_slice(&be(c));
    }
    text.extend_from_slice(b"`\n integer `");
    for i in [0u32, 1, 0x6060_6060] {
        text.extend_from_slice(&i.to_be_bytes());
    }
    text.extend_from_slice(b"`\n integer `");
    text.extend_from_slice(&7u32.to_be_bytes());
    text.extend_from_slice(b"`\n end trilist\nend object\n");
    let parsed = mi::parse_source(mi::Origin::Memory("bin.mi".into()), text, &mi::ReadOptions::default());
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let Item::Object(o) = &parsed.items[0] else { panic!() };
    let Geometry::Group(g) = &o.geometry[0] else { panic!() };
    assert_eq!(g.vectors[0], [1.0, 2.0, 3.0]);
    assert_eq!(g.vectors[1][0].to_bits(), tricky.to_bits());
    assert_eq!(g.vectors[1][2], 1e-5);
    let Geometry::Trilist(t) = &o.geometry[1] else { panic!() };
    assert_eq!(t.floats[3].to_bits(), tricky.to_bits());
    assert_eq!(t.triangles.indices, vec![0, 1, 0x6060_6060]);
    assert_eq!(t.triangles.labels, Some(vec![7]));
    // The printed text is ASCII and says the same.
    let printed = mi::print(&parsed.items);
    assert!(printed.iter().all(|b| b.is_ascii()));
    let again = mi::parse_source(mi::Origin::Memory("p.mi".into()), printed, &mi::ReadOptions::default());
    assert!(again.items == parsed.items);
}

#[test]
fn real_file_tolerance() {
    // Unquoted parameter names, trailing commas, empty lists, `declare` and the name on
    // separate lines, #: pragmas, CRLF line ends, no newline at the end of the file, and a
    // multi-kilobyte escaped string in data.
    let long = "x\\\"y\\\\z ".repeat(2000);
    let text = format!(
        "declare\r\nshader\r\n  color #: shortname \"c\"\r\n  \"s\" ( color brickColor, #: default 1 1 1\r\n scalar mortar , )\r\n  version 1\r\nend declare\r\n\
         shader \"x\" \"s\" ( brickColor 1 0 0, \"mortar\" .5, )\r\nshader \"e\" \"s\" ()\r\n\
         data \"d\" \"s\" ( \"text\" \"{long}\" )\r\nrender \"a\" \"b\" \"c\""
    );
    let parsed = parse(&text);
    let Item::Data(d) = &parsed.items[3] else { panic!() };
    let DataBody::Params { params, .. } = &d.body else { panic!() };
    let Value::Str(s) = &params[0].value else { panic!() };
    assert_eq!(s.text.len(), 2000 * 6);
    assert!(s.text.starts_with("x\"y\\z "));
}

#[test]
fn real_world_forms_read_without_complaint() {
    // tests/data/forms: one file per construct family, in the styles real exporters write.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/forms");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "mi") {
            let parsed = mi::parse_file(&path, &mi::ReadOptions::default()).unwrap();
            assert!(parsed.diagnostics.list.is_empty(), "{}", parsed.diagnostics.render(&parsed.sources));
            count += 1;
        }
    }
    assert!(count >= 40);
}

#[test]
fn chained_conditionals_take_the_right_branch() {
    let text = "set \"exporter\" \"mayatomr\"\n$ifdef \"nothing\"\ngarbage 1\n$elseifeq \"exporter\" \"mayatomr\"\n\
                options \"a\" end options\n$else\ngarbage 2\n$endif\nset \"gi\"\n$ifdef \"nothing\"\ngarbage 3\n\
                $elseifdef gi\noptions \"b\" end options\n$endif\n$ifndef \"gi\"\ngarbage\n$elseifdef \"nothing\"\ngarbage\n\
                $else\noptions \"c\" end options\n$endif\n";
    let parsed = parse(text);
    let names: Vec<&str> = parsed
        .items
        .iter()
        .filter_map(|i| if let Item::Options(b) = i { Some(b.name.as_str()) } else { None })
        .collect();
    assert_eq!(names, vec!["a", "b", "c"]);
}

#[test]
fn windows_paths_latin1_names_and_byte_order_marks() {
    let mut text = vec![0xef, 0xbb, 0xbf];
    text.extend_from_slice(b"color texture \"t\" \"C:\\textures\\new\\wood.jpg\"\nmaterial \"Mat\xe9riau\" end material\nmaterial \"Mat\xe8riau\" end material\n");
    let parsed = mi::parse_source(mi::Origin::Memory("w.mi".into()), text, &mi::ReadOptions::default());
    assert!(parsed.diagnostics.list.is_empty(), "{}", parsed.diagnostics.render(&parsed.sources));
    let Item::Texture(t) = &parsed.items[0] else { panic!() };
    assert!(matches!(&t.source, TextureSource::File { file, .. } if file.text == r"C:\textures\new\wood.jpg"));
    let names: Vec<&str> = parsed.items[1..]
        .iter()
        .filter_map(|i| if let Item::Material(m) = i { Some(m.name.as_str()) } else { None })
        .collect();
    assert_eq!(names, vec!["Mat\u{e9}riau", "Mat\u{e8}riau"]);
}

#[test]
fn a_bad_character_costs_one_error_and_not_the_next_element() {
    let parsed = mi::parse_str("b.mi", "options \"o\" end options\n~\ncamera \"c\" end camera\n");
    assert_eq!(parsed.diagnostics.error_count(), 1, "{}", parsed.diagnostics.render(&parsed.sources));
    assert!(matches!(parsed.items.last(), Some(Item::Camera(_))));
}

#[test]
fn binary_topology_and_triangle_data_are_read_by_count() {
    let mut text = b"object \"o\" tagged\n trilist vertex 3 p\n triangle 1 data 1 1\n [ 0 0 0 1 0 0 0 1 0 ]\n [ 0 0 1 2 ]\n triangle data integer `".to_vec();
    text.extend_from_slice(&0x60u32.to_be_bytes());
    text.extend_from_slice(b"` integer `");
    text.extend_from_slice(&0x6060u32.to_be_bytes());
    text.extend_from_slice(b"`\n topology integer `");
    for w in [96u32, 0x60_00_00_60, 2] {
        text.extend_from_slice(&w.to_be_bytes());
    }
    text.extend_from_slice(b"`\n end trilist\nend object\n");
    let parsed = mi::parse_source(mi::Origin::Memory("t.mi".into()), text, &mi::ReadOptions::default());
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let Item::Object(o) = &parsed.items[0] else { panic!() };
    let Geometry::Trilist(t) = &o.geometry[0] else { panic!() };
    assert_eq!(t.triangle_data, Some((vec![0x60], vec![0x6060])));
    assert_eq!(t.topology, Some(vec![96, 0x60_00_00_60, 2]));
}

#[test]
fn registry_keys_expand_recursively_in_include_paths() {
    let dir = std::env::temp_dir().join(format!("mira-registry-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(dir.join("sub/e.mi"), "options \"from_include\" end options\n").unwrap();
    let main = dir.join("main.mi");
    std::fs::write(
        &main,
        format!(
            "registry \"{{ROOT}}\" value \"{}\" end registry\nregistry \"{{SUB}}\" value \"{{ROOT}}/sub\" end registry\n$include \"{{SUB}}/e.mi\"\n",
            dir.display()
        ),
    )
    .unwrap();
    let parsed = mi::parse_file(&main, &mi::ReadOptions::default()).unwrap();
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    assert_eq!(Stats::of(&parsed.items).elements.get("options"), Some(&1));
}

#[test]
fn unquoted_and_missing_names_where_the_grammar_allows_them() {
    let parsed = parse(
        "object group g1 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 c 0 1 2 end group end object\ninstance \"i\" pCubeShape1 visible on end instance\n\
         call \"mib_color_alpha\" (), \"a\" \"b\"\ncode 'c0de'\n",
    );
    let Item::Object(o) = &parsed.items[0] else { panic!() };
    assert_eq!(o.name.text, "");
    let Geometry::Group(g) = &o.geometry[0] else { panic!() };
    assert_eq!(g.name.as_ref().unwrap().text, "g1");
    let Item::Instance(i) = &parsed.items[1] else { panic!() };
    assert!(matches!(&i.target, InstanceTarget::Element(n) if n.text == "pCubeShape1"));
}

/// Every declaration option of the mental ray 3.x manual ("Declaration Options"), in the
/// forms real files write, after the parameters of `declare shader` and `declare
/// phenomenon`: each is read as its own statement with its arguments.
#[test]
fn declaration_options() {
    let text = "declare shader color \"s\" (color \"c\")\n\
        version 3\n apply material, shadow, photon\n apply material,shadow\n scanline off\n trace on\n\
        shadow sort\n shadow segments\n shadow on\n face both\n derivative 1 2\n derivative 1\n derivative\n\
        object space\n camera space\n mixed space\n world space\n volume level 2\n parallel\n\
        texture 2\n bump 1\n hardware\n end declare\n\
        declare phenomenon color \"p\" (color \"c\")\n shader \"x\" \"s\" (\"c\" = interface \"c\")\n root = \"x\"\n\
        version 2\n apply material\n scanline on\n trace off\n shadow off\n face front\n derivative 2\n\
        volume level 1\n parallel\n output priority 3\n end declare\n";
    let parsed = parse(text);
    let decls: Vec<&Declaration> =
        parsed.items.iter().filter_map(|i| if let Item::Declare(d) = i { Some(d) } else { None }).collect();
    let keys = |d: &Declaration| -> Vec<(&'static str, usize)> {
        d.body.iter().filter_map(|b| if let DeclItem::Kw(k) = b { Some((k.key, k.args.len())) } else { None }).collect()
    };
    assert_eq!(
        keys(decls[0]),
        [
            ("version", 1),
            ("apply", 1),
            ("apply", 1),
            ("scanline", 1),
            ("trace", 1),
            ("shadow", 1),
            ("shadow", 1),
            ("shadow", 1),
            ("face", 1),
            ("derivative", 2),
            ("derivative", 1),
            ("derivative", 0),
            ("object space", 0),
            ("camera space", 0),
            ("mixed space", 0),
            ("world space", 0),
            ("volume level", 1),
            ("parallel", 0),
            ("texture", 1),
            ("bump", 1),
            ("hardware", 0),
        ]
    );
    let DeclItem::Kw(apply) = &decls[0].body[1] else { panic!() };
    let Arg::List(names) = &apply.args[0] else { panic!("{apply:?}") };
    assert_eq!(names.iter().map(|n| n.text.as_str()).collect::<Vec<_>>(), ["material", "shadow", "photon"]);
    assert_eq!(
        keys(decls[1]),
        [
            ("root", 1),
            ("version", 1),
            ("apply", 1),
            ("scanline", 1),
            ("trace", 1),
            ("shadow", 1),
            ("face", 1),
            ("derivative", 1),
            ("volume level", 1),
            ("parallel", 0),
            ("output priority", 1),
        ]
    );
    // Printed and read again, the declarations are the same.
    let again = parse(std::str::from_utf8(&mi::print(&parsed.items)).unwrap());
    assert_eq!(again.items, parsed.items);
}

/// The libraries Maya exports include resolve to mira's built-in declarations and their
/// `link` lines pass without a message, while a real file of the same name on the
/// include path wins over the built-in one (issue 17).
#[test]
fn maya_libraries_resolve_built_in_unless_a_real_file_is_on_the_include_path() {
    let dir = std::env::temp_dir().join(format!("mira_maya_includes_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("mayabase.mi"), "declare shader color \"maya_local\" () end declare\n").expect("write");
    let libs = [
        "mayabase",
        "AdskShaderSDK",
        "MayaShaders",
        "coreutil",
        "object_light_phen",
        "lookdevKitMR",
        "syncolor_shaders",
    ];
    let scene: String = libs.iter().map(|l| format!("link \"{l}.so\"\n$include \"{l}.mi\"\n")).collect();
    let file = dir.join("scene.mi");
    std::fs::write(&file, scene).expect("write");
    let options = mi::ReadOptions { include_paths: vec![dir.clone()], ..mi::ReadOptions::default() };
    let parsed = mi::parse_file(&file, &options).expect("readable");
    std::fs::remove_dir_all(&dir).ok();
    assert!(parsed.diagnostics.list.is_empty(), "{}", parsed.diagnostics.render(&parsed.sources));
    let targets: Vec<&mi::IncludeTarget> = parsed.includes.iter().map(|i| &i.target).collect();
    assert!(matches!(targets[0], mi::IncludeTarget::File(p) if p.ends_with("mayabase.mi")), "{targets:?}");
    for (lib, target) in libs.iter().zip(&targets).skip(1) {
        assert_eq!(*target, &mi::IncludeTarget::Builtin(Box::leak(format!("{lib}.mi").into_boxed_str())), "{lib}");
    }
    // The real mayabase.mi was read: its one declaration, not the built-in maya_lambert.
    let items = flat(&parsed.items);
    let declared: Vec<&str> =
        items.iter().filter_map(|i| if let Item::Declare(d) = i { Some(d.name.text.as_str()) } else { None }).collect();
    assert!(declared.contains(&"maya_local") && !declared.contains(&"maya_lambert"), "{declared:?}");
    assert!(declared.contains(&"adskMayaLambert"));
}
