//! Trilist arrays moved from the syntax tree into the meshes (`Scene::build_taking`): the
//! same scene as the copying build, bit for bit, with the tree's arrays left empty, and
//! nothing moved where a geometry shader could tessellate an object twice.

use mi::ast::{Geometry, Item, Trilist};
use scene::tessellate::taken::TrilistArrays;
use scene::tessellate::trilist::{trilist_mesh, trilist_mesh_with};
use scene::Scene;

/// A scene of `body` under the root group holding `members`.
fn scene_text(body: &str, members: &str) -> String {
    format!(
        "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
         material \"m\" \"x\" () end material\nmaterial \"m2\" \"x\" () end material\n{body}\n\
         instgroup \"root\" \"ci\" {members} end instgroup\nrender \"root\" \"ci\" \"o\"\n"
    )
}

/// Trilists of several layouts: normals, texture spaces, a border, labels, per-triangle
/// materials, an incomplete last triangle, one inside a namespace and one behind
/// `incremental`, and an object with a group before its trilist.
const BODY: &str = "\
object \"pn\" trilist vertex 4 p n triangle 2 [\n\
 0 0 0 0 0 2   1 0 0 0 0 1   1 1 0 0 0 1   0 1 0 0 0 1 ]\n\
 [ 0 1 2 0 2 3 ] end trilist end object\n\
object \"pt\" trilist vertex 4 p t 2 triangle 2 border 1 [\n\
 0 0 1 0.5 0.25  1 0 1 0.75 0.25  1 1 1 0.75 0.5  0 1 1 0.5 0.5 ]\n\
 [ 0 1 2 0 2 3 ] [ 0 1 3 ] end trilist end object\n\
object \"tagged\" tagged trilist vertex 3 p triangle 1 [ 0 0 2 1 0 2 0 1 2 ] [ 1 0 1 2 ] end trilist end object\n\
object \"mats\" trilist vertex 4 p triangle 2 [ 0 0 3 1 0 3 1 1 3 0 1 3 ]\n\
 [ \"m\" 0 1 2 \"m2\" 0 2 3 ] end trilist end object\n\
object \"mixed\" group 0 0 4 1 0 4 0 1 4 v 0 v 1 v 2 p 0 1 2 end group\n\
 trilist vertex 3 p triangle 1 [ 5 0 4 6 0 4 5 1 4 ] [ 0 1 2 ] end trilist end object\n\
namespace \"ns\" object \"inner\" trilist vertex 3 p n triangle 1 [ 0 0 5 0 0 1 1 0 5 0 0 1 0 1 5 0 0 1 ]\n\
 [ 0 1 2 ] end trilist end object end namespace\n\
object \"inc\" visible on end object\n\
incremental object \"inc\" trilist vertex 3 p triangle 1 [ 0 0 6 1 0 6 0 1 6 ] [ 0 1 2 ] end trilist end object\n\
instance \"i1\" \"pn\" material \"m\" end instance\n\
instance \"i1b\" \"pn\" material \"m\" transform 1 0 0 0 0 1 0 0 0 0 1 0 2 0 0 1 end instance\n\
instance \"i2\" \"pt\" material \"m\" end instance\n\
instance \"i3\" \"tagged\" material [ \"m\" \"m2\" ] end instance\n\
instance \"i4\" \"mats\" end instance\n\
instance \"i5\" \"mixed\" material \"m\" end instance\n\
instance \"i6\" \"ns::inner\" material \"m\" end instance\n\
instance \"i7\" \"inc\" material \"m\" end instance";

const MEMBERS: &str = "\"i1\" \"i1b\" \"i2\" \"i3\" \"i4\" \"i5\" \"i6\" \"i7\"";

/// Every trilist of `items`, at any depth.
fn trilists(items: &[Item]) -> Vec<&Trilist> {
    let mut out = Vec::new();
    for item in items {
        match item {
            Item::Object(o) => out.extend(o.geometry.iter().filter_map(|g| match g {
                Geometry::Trilist(t) => Some(t),
                _ => None,
            })),
            Item::Namespace(n) => out.extend(trilists(&n.items)),
            Item::Modified { item, .. } => out.extend(trilists(std::slice::from_ref(&**item))),
            _ => {}
        }
    }
    out
}

/// The scene of `text` built by copying and by taking: (copied, taken, the tree after taking).
fn both(text: &str) -> (Scene, Scene, mi::Parsed) {
    let parsed = mi::parse_str("t.mi", text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let copied = Scene::build(&parsed, 0, &mut diags).expect("a scene");
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
    let mut taken_from = mi::parse_str("t.mi", text);
    let mut taken_diags = Vec::new();
    let taken = Scene::build_taking(&mut taken_from, 0, &mut taken_diags).expect("a scene");
    let messages = |d: &[mi::Diagnostic]| d.iter().map(|d| d.message.clone()).collect::<Vec<_>>();
    assert_eq!(messages(&taken_diags), messages(&diags));
    (copied, taken, taken_from)
}

/// Every object's mesh (positions, normals, texture spaces, triangles, slots) and every
/// instance is the same, exactly, whether the arrays were copied or moved; the tree's
/// trilists hold no numbers or indices afterwards (border triangles stay in the tree).
#[test]
fn taking_builds_the_same_scene_and_empties_the_tree() {
    let (copied, taken, tree) = both(&scene_text(BODY, MEMBERS));
    assert_eq!(copied.objects.len(), 7);
    assert_eq!(taken.objects.len(), copied.objects.len());
    for (a, b) in copied.objects.iter().zip(&taken.objects) {
        assert_eq!(a.name, b.name);
        assert!(!a.geometry.mesh.triangles.is_empty(), "object {}", a.name);
        assert_eq!(a.geometry.mesh, b.geometry.mesh, "object {}", a.name);
    }
    assert_eq!(format!("{:?}", copied.instances), format!("{:?}", taken.instances));
    let lists = trilists(&tree.items);
    assert_eq!(lists.len(), 7);
    for t in lists {
        assert!(t.floats.is_empty() && t.triangles.indices.is_empty(), "{:?}", t.span);
    }
    // The copying build read the same text: its tree still has its arrays.
    let pt = copied.objects.iter().find(|o| o.name == "pt").unwrap();
    assert_eq!(pt.geometry.mesh.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 3]]);
    assert_eq!(pt.geometry.mesh.textures[0].coords[1], glam::Vec3::new(0.75, 0.25, 0.0));
    let pn = taken.objects.iter().find(|o| o.name == "pn").unwrap();
    assert_eq!(pn.geometry.mesh.normals[0], glam::Vec3::Z, "normalised from (0, 0, 2)");
}

/// With a geometry shader instance in the file (`mib_geo_add_uv_texsurf` tessellates a
/// copy of its object beside the object itself) nothing is moved: the tree keeps its
/// arrays and the scene is the copying build's.
#[test]
fn nothing_is_taken_beside_a_geometry_shader() {
    let body = format!(
        "{BODY}\ninstance \"uv\" geometry \"mib_geo_add_uv_texsurf\" (\"object\" \"pn\") material \"m\" end instance"
    );
    let (copied, taken, tree) = both(&scene_text(&body, &format!("{MEMBERS} \"uv\"")));
    assert_eq!(copied.objects.len(), 8, "the shader's copy of pn is an object of its own");
    for (a, b) in copied.objects.iter().zip(&taken.objects) {
        assert_eq!(a.geometry.mesh, b.geometry.mesh, "object {}", a.name);
        assert!(!b.geometry.mesh.triangles.is_empty(), "object {}", b.name);
    }
    assert!(trilists(&tree.items).iter().all(|t| !t.floats.is_empty() && !t.triangles.indices.is_empty()));
}

/// The trilist `p n` of three vertices and one triangle, parsed.
fn one_triangle() -> Trilist {
    let parsed = mi::parse_str(
        "t.mi",
        "object \"o\" trilist vertex 3 p n triangle 1 [ 0 0 0 0 0 1 1 0 0 0 0 1 0 1 0 0 0 1 ] [ 0 1 2 ] end trilist end object",
    );
    let Some(Item::Object(o)) = parsed.items.into_iter().next() else { panic!("an object") };
    let Some(Geometry::Trilist(t)) = o.geometry.into_iter().next() else { panic!("a trilist") };
    t
}

/// Moved arrays become the mesh's: the index list is the triangles' buffer itself (no
/// copy) when its capacity holds whole triangles, and is copied when it does not; the
/// positions are the first three numbers of each line either way.
#[test]
fn moved_arrays_become_the_meshs_own() {
    let list = one_triangle();
    let reference = trilist_mesh(&list, "o", &mut Vec::new()).expect("a mesh");
    let mut indices = Vec::with_capacity(3);
    indices.extend_from_slice(&list.triangles.indices);
    let buffer = indices.as_ptr() as usize;
    let arrays = TrilistArrays { floats: list.floats.clone(), indices };
    let mesh = trilist_mesh_with(&list, Some(arrays), "o", &mut Vec::new()).expect("a mesh");
    assert_eq!(mesh, reference);
    assert_eq!(mesh.triangles.as_ptr() as usize, buffer, "the index list's own buffer");
    assert_eq!(mesh.positions[1], glam::Vec3::X);
    // A capacity of 4 indices is no whole number of triangles: copied, the same mesh.
    let mut indices = Vec::with_capacity(4);
    indices.extend_from_slice(&list.triangles.indices);
    let arrays = TrilistArrays { floats: list.floats.clone(), indices };
    assert_eq!(trilist_mesh_with(&list, Some(arrays), "o", &mut Vec::new()).expect("a mesh"), reference);
    // Bad moved indices are reported as the tree's are.
    let arrays = TrilistArrays { floats: list.floats.clone(), indices: vec![0, 1, 3] };
    let mut diags = Vec::new();
    assert!(trilist_mesh_with(&list, Some(arrays), "o", &mut diags).is_none());
    assert!(diags[0].message.contains("vertex line 3 but there are 3"), "{diags:?}");
}
