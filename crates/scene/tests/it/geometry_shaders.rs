//! mental ray's geometry shaders (`mib_geo_*`) through the whole scene layer: shapes with
//! the counts, sizes and winding of the base shader sources, and `mib_geo_instance(_mlist)`
//! placing other objects.

use std::f64::consts::PI;

use glam::DVec3;
use scene::{Instance, Mesh, Scene};

/// [`crate::support::build`] without the parse.
fn build(text: &str) -> (Scene, Vec<mi::Diagnostic>) {
    let (scene, diags, _) = crate::support::build(text);
    (scene, diags)
}

/// A scene with `body` (elements) whose root group holds the camera and `members`.
fn scene_text(body: &str, members: &str) -> String {
    format!(
        "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
         material \"m\" \"x\" () end material\n{body}\n\
         instgroup \"root\" \"ci\" {members} end instgroup\nrender \"root\" \"ci\" \"o\"\n"
    )
}

/// The object mesh of the one instance of a geometry shader call `call`, placed with
/// material "m".
fn shape(call: &str) -> Mesh {
    let (s, _) = build(&scene_text(&format!("instance \"g\" geometry {call} material \"m\" end instance"), "\"g\""));
    assert_eq!(s.instances.len(), 1);
    let inst = &s.instances[0];
    assert!(inst.materials.iter().all(|m| *m == Some(0)), "faces take the instance's material");
    s.objects[inst.object as usize].geometry.mesh.clone()
}

fn instance<'s>(s: &'s Scene, name: &str) -> &'s Instance {
    s.instances.iter().find(|i| i.name == name).unwrap_or_else(|| panic!("no instance '{name}'"))
}

/// World-space bounds of an instance.
fn world_bounds(s: &Scene, inst: &Instance) -> (DVec3, DVec3) {
    let mesh = &s.objects[inst.object as usize].geometry.mesh;
    mesh.positions
        .iter()
        .map(|p| inst.object_to_world.transform_point3(p.as_dvec3()))
        .fold((DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)), |(lo, hi), p| (lo.min(p), hi.max(p)))
}

fn bounds(mesh: &Mesh) -> (DVec3, DVec3) {
    let (lo, hi) = mesh.bounds().expect("vertices");
    (lo.as_dvec3(), hi.as_dvec3())
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element() < 1e-6
}

/// Triangles as (unnormalised geometric normal, centroid).
fn faces(mesh: &Mesh) -> impl Iterator<Item = (DVec3, DVec3)> + '_ {
    mesh.triangles.iter().map(|t| {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
        ((b - a).cross(c - a), (a + b + c) / 3.0)
    })
}

#[test]
fn sphere_counts_radius_winding_and_normals() {
    let mesh = shape("\"mib_geo_sphere\" (\"u_subdiv\" 8, \"v_subdiv\" 8)");
    // mental ray's 8·8 + 2 vertices, plus the seam column (8) and one pole vertex per
    // segment (2·8 − 2) for the texture space.
    assert_eq!(mesh.positions.len(), 9 * 8 + 2 * 8);
    assert_eq!(mesh.triangles.len(), 2 * 8 + 2 * 8 * 7);
    let distinct: std::collections::BTreeSet<[u32; 3]> =
        mesh.positions.iter().map(|p| p.to_array().map(f32::to_bits)).collect();
    assert_eq!(distinct.len(), 8 * 8 + 2, "seam and pole copies share their positions exactly");
    assert!(mesh.positions.iter().all(|p| (p.length() - 1.0).abs() < 1e-6));
    assert!(faces(&mesh).all(|(n, c)| n.dot(c) > 0.0), "every triangle faces outward");
    assert_eq!(mesh.normals.len(), mesh.positions.len());
    assert!(mesh.normals.iter().zip(&mesh.positions).all(|(n, p)| (*n - *p).length() < 1e-6), "normals = positions");
    let (lo, hi) = bounds(&mesh);
    assert!((hi.z - 1.0).abs() < 1e-6 && (lo.z + 1.0).abs() < 1e-6, "poles on ±z: {lo} {hi}");
    // Texture space 0: u around, v from the south pole (0) to the north pole (1).
    assert_eq!(mesh.textures.len(), 1);
    let uv = &mesh.textures[0];
    assert_eq!((uv.dim, uv.coords.len()), (2, mesh.positions.len()));
    for (t, p) in uv.coords.iter().zip(&mesh.positions) {
        assert!((0.0..=1.0).contains(&t.x) && (0.0..=1.0).contains(&t.y));
        assert!((t.y - (-p.z).acos() / std::f32::consts::PI).abs() < 1e-5, "{t} at {p}");
    }
}

#[test]
fn sphere_area_approaches_four_pi() {
    let coarse = shape("\"mib_geo_sphere\" (\"u_subdiv\" 8, \"v_subdiv\" 4)").area();
    let fine = shape("\"mib_geo_sphere\" (\"u_subdiv\" 64, \"v_subdiv\" 32)").area();
    let sphere = 4.0 * PI;
    assert!(coarse < fine && fine < sphere, "inscribed: {coarse} < {fine} < {sphere}");
    assert!((fine - sphere).abs() / sphere < 0.02, "{fine}");
}

#[test]
fn zero_or_missing_parameters_take_mental_rays_defaults() {
    // u_subdiv < 3 → 8, v_subdiv < 1 → 8.
    for call in ["\"mib_geo_sphere\" ()", "\"mib_geo_sphere\" (\"u_subdiv\" 2, \"v_subdiv\" 0)"] {
        assert_eq!(shape(call).triangles.len(), 2 * 8 * 8, "{call}");
    }
    // Cone and cylinder: v_subdiv 0 is kept (one band), only negative ones become 8.
    assert_eq!(shape("\"mib_geo_cylinder\" (\"v_subdiv\" 0)").triangles.len(), 2 * 8);
    assert_eq!(shape("\"mib_geo_cylinder\" (\"v_subdiv\" -1)").triangles.len(), 2 * 8 * 9);
    assert_eq!(shape("\"mib_geo_cone\" (\"u_subdiv\" 0, \"v_subdiv\" 0)").triangles.len(), 8);
    // Torus: radius ≤ 0 → 2, thickness ≤ 0 → 1, spans 0 → 32.
    let torus = shape("\"mib_geo_torus\" (\"radius\" 0, \"thickness\" -1, \"uSpans\" 0, \"vSpans\" 0)");
    assert_eq!(torus.triangles.len(), 2 * 32 * 32);
    let (lo, hi) = bounds(&torus);
    assert!(close(lo, DVec3::new(-3.0, -3.0, -1.0)) && close(hi, DVec3::new(3.0, 3.0, 1.0)), "{lo} {hi}");
}

#[test]
fn cube_and_square_have_unit_sides() {
    let cube = shape("\"mib_geo_cube\" ()");
    assert_eq!((cube.positions.len(), cube.triangles.len()), (8, 12));
    let (lo, hi) = bounds(&cube);
    assert!(close(lo, DVec3::splat(-0.5)) && close(hi, DVec3::splat(0.5)), "{lo} {hi}");
    assert!((cube.area() - 6.0).abs() < 1e-9);
    assert!(faces(&cube).all(|(n, c)| n.dot(c) > 0.0), "every face outward");
    // Six axis-aligned faces, two triangles each.
    for axis in 0..3 {
        for side in [-1.0, 1.0] {
            let count = faces(&cube).filter(|(n, _)| n.normalize()[axis] == side).count();
            assert_eq!(count, 2, "axis {axis} side {side}");
        }
    }
    let square = shape("\"mib_geo_square\" ()");
    assert_eq!(square.triangles.len(), 2);
    let (lo, hi) = bounds(&square);
    assert!(close(lo, DVec3::new(-0.5, -0.5, 0.0)) && close(hi, DVec3::new(0.5, 0.5, 0.0)));
    assert!((square.area() - 1.0).abs() < 1e-9);
    assert!(faces(&square).all(|(n, _)| n.normalize() == DVec3::Z), "faces +z");
}

#[test]
fn cylinder_spans_z_minus_one_to_zero_with_caps() {
    let open = shape("\"mib_geo_cylinder\" (\"u_subdiv\" 16, \"v_subdiv\" 3)");
    assert_eq!(open.triangles.len(), 2 * 16 * 4);
    let (lo, hi) = bounds(&open);
    assert!(close(lo, DVec3::new(-1.0, -1.0, -1.0)) && close(hi, DVec3::new(1.0, 1.0, 0.0)), "{lo} {hi}");
    assert!(faces(&open).all(|(n, c)| n.dot(DVec3::new(c.x, c.y, 0.0)) > 0.0), "sides face away from the axis");
    assert!(open.normals.iter().all(|n| n.z == 0.0 && (n.length() - 1.0).abs() < 1e-6));
    let capped =
        shape("\"mib_geo_cylinder\" (\"u_subdiv\" 64, \"v_subdiv\" 0, \"bottom_capped\" on, \"top_capped\" true)");
    assert_eq!(capped.triangles.len(), 2 * 64 + 2 * 64);
    // Side 2π·1·1 and two discs of π, inscribed.
    let area = capped.area();
    assert!(area < 4.0 * PI && (area - 4.0 * PI).abs() / (4.0 * PI) < 0.01, "{area}");
    for (n, c) in faces(&capped).filter(|(n, _)| n.x == 0.0 && n.y == 0.0) {
        assert_eq!(n.z > 0.0, c.z > -0.5, "the top disc faces +z, the bottom one −z");
    }
}

#[test]
fn cone_has_its_apex_at_the_origin_and_base_at_minus_one() {
    let cone = shape("\"mib_geo_cone\" (\"u_subdiv\" 64, \"v_subdiv\" 2, \"capped\" on)");
    assert_eq!(cone.triangles.len(), 64 * (2 * 2 + 1) + 64);
    let (lo, hi) = bounds(&cone);
    assert!(close(lo, DVec3::new(-1.0, -1.0, -1.0)) && close(hi, DVec3::new(1.0, 1.0, 0.0)), "{lo} {hi}");
    // Radius 1 − (z + 1) = −z on the side.
    for p in &cone.positions {
        let r = (p.x * p.x + p.y * p.y).sqrt();
        assert!(r <= -p.z + 1e-6, "{p}");
    }
    // Side π·r·slant = π√2, base π.
    let area = cone.area();
    let expected = PI * 2f64.sqrt() + PI;
    assert!(area < expected && (area - expected).abs() / expected < 0.01, "{area} vs {expected}");
    // The source's side normals: (2 cos p, 2 sin p, 1) normalised; the base faces −z.
    let side = cone.normals.iter().filter(|n| n.z > 0.0);
    assert!(side.clone().count() > 0);
    assert!(side.clone().all(|n| (n.z - 1.0 / 5f32.sqrt()).abs() < 1e-6));
    for (n, c) in faces(&cone) {
        if c.z == -1.0 && n.x == 0.0 && n.y == 0.0 {
            assert!(n.z < 0.0);
        } else {
            assert!(n.dot(DVec3::new(c.x, c.y, 0.0)) > 0.0 && n.z > 0.0, "side faces out and up");
        }
    }
}

#[test]
fn torus_size_area_and_outward_normals() {
    let (r, t) = (3.0, 0.5);
    let torus = shape("\"mib_geo_torus\" (\"radius\" 3, \"thickness\" 0.5, \"uSpans\" 32, \"vSpans\" 32)");
    assert_eq!(torus.triangles.len(), 2 * 32 * 32);
    let (lo, hi) = bounds(&torus);
    assert!(close(lo, DVec3::new(-r - t, -r - t, -t)) && close(hi, DVec3::new(r + t, r + t, t)), "{lo} {hi}");
    let area = torus.area();
    let expected = 4.0 * PI * PI * r * t;
    assert!((area - expected).abs() / expected < 0.02, "{area} vs {expected}");
    // Outward from the tube's centre circle, both the faces and the vertex normals.
    let tube_centre = |p: DVec3| DVec3::new(p.x, p.y, 0.0).normalize() * r;
    assert!(faces(&torus).all(|(n, c)| n.dot(c - tube_centre(c)) > 0.0));
    for (n, p) in torus.normals.iter().zip(&torus.positions) {
        let p = p.as_dvec3();
        let expected = (p - tube_centre(p)) / t;
        assert!((n.as_dvec3() - expected).length() < 1e-5, "{n} at {p}");
    }
    assert_eq!(torus.textures[0].coords.len(), 33 * 33);
}

#[test]
fn named_geometry_shaders_are_made_once_and_placed_by_each_instance() {
    let body = "shader \"ball\" \"mib_geo_sphere\" (\"u_subdiv\" 16, \"v_subdiv\" 8)\n\
        instance \"a\" geometry = \"ball\" material \"m\" end instance\n\
        instance \"b\" geometry = \"ball\" material \"m\" visible off\n\
          transform 1 0 0 0  0 1 0 0  0 0 1 0  -10 0 0 1 end instance\n\
        instance \"cu\" geometry = shader \"inline\" \"mib_geo_cube\" () material \"m\" end instance";
    let (s, diags) = build(&scene_text(body, "\"a\" \"b\" \"cu\""));
    assert!(diags.is_empty(), "{diags:?}");
    let (a, b, c) = (instance(&s, "a"), instance(&s, "b"), instance(&s, "cu"));
    assert_eq!(a.object, b.object, "one sphere shared");
    let sphere = &s.objects[a.object as usize];
    assert_eq!(sphere.name, "ball#mib_geo_sphere");
    assert_eq!(sphere.geometry.mesh.triangles.len(), 2 * 16 * 8);
    assert_eq!(s.objects[c.object as usize].name, "inline#mib_geo_cube");
    // Moved to x = 10 (rings at 8 v_subdiv miss the equator: x and y stay inside ±1).
    let (lo, hi) = world_bounds(&s, b);
    assert!(close((lo + hi) * 0.5, DVec3::new(10.0, 0.0, 0.0)), "{lo} {hi}");
    assert!((lo.z + 1.0).abs() < 1e-6 && (hi.z - 1.0).abs() < 1e-6 && hi.x < 11.0 && hi.x > 10.98, "{lo} {hi}");
    // The shaders' object flags, and the instance's own on top.
    assert!(a.flags.visible && a.flags.shadow.cast && a.flags.shadow.receive);
    assert!(a.flags.reflection.cast && a.flags.refraction.cast && a.flags.finalgather.cast);
    assert!(!b.flags.visible);
}

#[test]
fn inline_calls_make_one_object_per_instance() {
    let body = "instance \"a\" geometry \"mib_geo_sphere\" (\"u_subdiv\" 4) material \"m\" end instance\n\
        instance \"b\" geometry \"mib_geo_sphere\" (\"u_subdiv\" 5) material \"m\" end instance";
    let (s, _) = build(&scene_text(body, "\"a\" \"b\""));
    let names: Vec<&str> = s.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["a#mib_geo_sphere", "b#mib_geo_sphere"]);
    assert_eq!(s.unique_triangles(), 2 * 4 * 8 + 2 * 5 * 8);
}

#[test]
fn geo_instance_places_an_object_with_its_matrix_and_material() {
    // The matrix is world → object: a translation by −5 in x puts the object at +5.
    let body = "material \"red\" \"x\" () end material\n\
        object \"tri\" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 p 0 1 2 end group end object\n\
        instance \"gi\" geometry \"mib_geo_instance\" (\"object\" \"tri\",\n\
          \"matrix\" 1 0 0 0  0 1 0 0  0 0 1 0  -5 0 0 1, \"material\" \"red\")\n\
          transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -2 0 1 end instance\n\
        instance \"zero\" geometry \"mib_geo_instance\" (\"object\" \"tri\",\n\
          \"matrix\" 0 0 0 0  0 0 0 0  0 0 0 0  0 0 0 0) material \"m\" end instance";
    let (s, diags) = build(&scene_text(body, "\"gi\" \"zero\""));
    assert!(diags.is_empty(), "{diags:?}");
    let gi = instance(&s, "gi");
    assert_eq!(s.objects[gi.object as usize].name, "tri");
    let (lo, hi) = world_bounds(&s, gi);
    // The shader's matrix below the instance's own transform (which moves it by +2 in y).
    assert!(close(lo, DVec3::new(5.0, 2.0, 0.0)) && close(hi, DVec3::new(6.0, 3.0, 0.0)), "{lo} {hi}");
    assert_eq!(gi.materials.len(), 1);
    assert_eq!(s.materials[gi.materials[0].unwrap() as usize].name, "red");
    // An all-zero matrix is the identity; the instance's material applies when the shader names none.
    let zero = instance(&s, "zero");
    assert_eq!(zero.object, gi.object, "the object is tessellated once");
    let (lo, hi) = world_bounds(&s, zero);
    assert!(close(lo, DVec3::ZERO) && close(hi, DVec3::new(1.0, 1.0, 0.0)), "{lo} {hi}");
    assert_eq!(s.materials[zero.materials[0].unwrap() as usize].name, "m");
}

#[test]
fn geo_instance_mlist_binds_a_material_list_to_labels() {
    let body = "material \"a\" \"x\" () end material\nmaterial \"b\" \"x\" () end material\n\
        object \"t\" tagged on group 0 0 0 1 0 0 0 1 0 1 1 0 v 0 v 1 v 2 v 3 c 0 0 1 2 c 1 1 3 2 end group end object\n\
        shader \"two\" \"mib_geo_instance_mlist\" (\"object\" \"t\", \"material\" [\"a\", \"b\"])\n\
        instance \"ml\" geometry = \"two\" end instance\n\
        instance \"one\" geometry \"mib_geo_instance_mlist\" (\"object\" \"t\", \"material\" [\"b\"]) end instance";
    let (s, diags) = build(&scene_text(body, "\"ml\" \"one\""));
    assert!(diags.is_empty(), "{diags:?}");
    let mat = |inst: &str, tri: usize| {
        let i = instance(&s, inst);
        let mesh = &s.objects[i.object as usize].geometry.mesh;
        s.materials[i.materials[mesh.triangle_slots[tri] as usize].unwrap() as usize].name.clone()
    };
    assert_eq!([mat("ml", 0), mat("ml", 1)], ["a", "b"]);
    // One entry: the material of every face.
    assert_eq!([mat("one", 0), mat("one", 1)], ["b", "b"]);
}

#[test]
fn geo_instance_under_an_overriding_material_keeps_it() {
    let body = "material \"red\" \"x\" () end material\n\
        object \"tri\" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 p 0 1 2 end group end object\n\
        instance \"gi\" geometry \"mib_geo_instance\" (\"object\" \"tri\", \"material\" \"red\") end instance\n\
        instgroup \"g\" \"gi\" end instgroup\n\
        instance \"top\" \"g\" override material \"m\" end instance";
    let (s, _) = build(&scene_text(body, "\"top\""));
    let gi = instance(&s, "gi");
    assert_eq!(s.materials[gi.materials[0].unwrap() as usize].name, "m");
}

#[test]
fn unsupported_and_unknown_geometry_shaders_warn_and_place_nothing() {
    let body = "object \"tri\" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 p 0 1 2 end group end object\n\
        instance \"u\" geometry \"my_own_geometry\" (\"size\" 2) end instance\n\
        instance \"t\" geometry \"mib_geo_add_uv_texsurf\" (\"object\" \"tri\") material \"m\" end instance";
    let text = scene_text(body, "\"u\" \"t\"");
    let (s, diags) = build(&text);
    // mib_geo_add_uv_texsurf on an object without free-form surfaces places it unchanged.
    assert_eq!(s.instances.len(), 1);
    assert_eq!(s.objects[s.instances[0].object as usize].geometry.mesh.triangles.len(), 1);
    let parsed = mi::parse_str("t.mi", &text);
    let warnings: Vec<(u32, String)> = diags
        .iter()
        .filter(|d| !d.is_error())
        .map(|d| (parsed.sources.file(d.span.file).line_col(d.span.lo).0, d.message.clone()))
        .collect();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert_eq!(warnings[0].0, 6, "at the instance");
    assert!(warnings[0].1.contains("'my_own_geometry'") && warnings[0].1.contains("instance 'u'"), "{warnings:?}");
    assert!(warnings[1].1.contains("mib_geo_add_uv_texsurf") && warnings[1].1.contains("no free-form"), "{warnings:?}");
}

#[test]
fn add_uv_texsurf_gives_free_form_surfaces_their_parameters() {
    // A flat Bézier patch over u ∈ [0, 2], v ∈ [0, 1] with a texture surface of its own.
    let body = "object \"patch\" basis \"lin\" bezier 1 group\n\
        0 0 0  1 0 0  0 1 0  1 1 0  5 5 0  6 5 0  5 6 0  6 6 0\n\
        v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7\n\
        surface \"s\" \"\" \"lin\" 0 2 0. 2. \"lin\" 0 1 0. 1. 0 1 2 3 texture \"lin\" 0. 2. \"lin\" 0. 1. 4 5 6 7\n\
        approximate surface regular parametric 4 4 \"s\"\n\
        end group end object\n\
        instance \"plain\" \"patch\" material \"m\" end instance\n\
        instance \"uv\" geometry \"mib_geo_add_uv_texsurf\" (\"object\" \"patch\") material \"m\" end instance";
    let (s, diags) = build(&scene_text(body, "\"plain\" \"uv\""));
    assert!(diags.is_empty(), "{diags:?}");
    let plain = &s.objects[instance(&s, "plain").object as usize].geometry.mesh;
    let uv = &s.objects[instance(&s, "uv").object as usize].geometry.mesh;
    assert_eq!(plain.textures.len(), 1);
    assert_eq!(uv.textures.len(), 2, "the (u, v) space comes last");
    assert_eq!(plain.triangles.len(), 32);
    for (p, t) in uv.positions.iter().zip(&uv.textures[1].coords) {
        assert!((t.x - 2.0 * p.x).abs() < 1e-6 && (t.y - p.y).abs() < 1e-6, "{t} at {p}");
    }
}

#[test]
fn unknown_references_in_geometry_shaders_are_errors() {
    let text = scene_text(
        "instance \"a\" geometry = \"nowhere\" end instance\n\
         instance \"b\" geometry \"mib_geo_instance\" (\"object\" \"ghost\") end instance",
        "\"a\" \"b\"",
    );
    let parsed = mi::parse_str("t.mi", &text);
    let mut diags = Vec::new();
    let s = Scene::build(&parsed, 0, &mut diags).expect("a scene");
    assert!(s.instances.is_empty());
    let mut errors: Vec<String> = diags.iter().filter(|d| d.is_error()).map(|d| d.message.clone()).collect();
    errors.sort();
    assert_eq!(errors, ["unknown element 'ghost' in mib_geo_instance", "unknown shader 'nowhere'"]);
}

#[test]
fn huge_subdivisions_are_reduced_with_a_warning() {
    let text = scene_text(
        "instance \"g\" geometry \"mib_geo_sphere\" (\"u_subdiv\" 100000, \"v_subdiv\" 100000) material \"m\" end instance",
        "\"g\"",
    );
    let (s, diags) = build(&text);
    let triangles = s.objects[0].geometry.mesh.triangles.len() as u64;
    assert!(triangles <= scene::tessellate::procedural::MAX_TRIANGLES && triangles > 1 << 20, "{triangles}");
    assert!(diags.iter().any(|d| d.message.contains("reduced")), "{diags:?}");
}
