//! Quad-mesh Ptex files on geometry without `c`/`p` quads: the triangles of a strip, a fan
//! and a trilist (each a face of its own: 3 sub-quads, numbered per triangle in the
//! object's face order) and a polygon with holes (its outer boundary's 5 sub-quads), each
//! sub-quad a constant colour, rendered in both engines; a hostile n-gon's warning at its
//! line; a free-form surface's warning at its line (subdivision surfaces are in
//! `mdl_ptex_subdiv`).

use crate::mdl_ptex::{assert_constant_regions, ptex_bytes, ptex_scene, FaceSpec, MODULE};
use crate::support;
use crate::support::scene_text::SceneText;
use render::{EngineKind, Settings};

/// One polygon as Ptex sees it: its object (0: lone triangles, 1: the holed pentagon), its
/// first face id, its vertices (x, y) in its own order, and a hole (x0, y0, x1, y1) on
/// pixel borders.
struct Poly {
    object: usize,
    first: usize,
    points: &'static [[f32; 2]],
    hole: Option<[f32; 4]>,
}

/// The strip's two triangles (the second turned as a strip makes it: vertices 2, 1, 3),
/// the fan's two, the trilist's two; the pentagon with a square hole around its centroid.
const POLYS: [Poly; 7] = [
    Poly { object: 0, first: 0, points: &[[-0.9, 0.9], [-0.9, 0.1], [-0.1, 0.9]], hole: None },
    Poly { object: 0, first: 3, points: &[[-0.1, 0.9], [-0.9, 0.1], [-0.1, 0.1]], hole: None },
    Poly { object: 0, first: 6, points: &[[0.1, 0.1], [0.9, 0.1], [0.9, 0.9]], hole: None },
    Poly { object: 0, first: 9, points: &[[0.1, 0.1], [0.9, 0.9], [0.1, 0.9]], hole: None },
    Poly { object: 0, first: 12, points: &[[0.1, -0.9], [0.9, -0.9], [0.9, -0.1]], hole: None },
    Poly { object: 0, first: 15, points: &[[0.1, -0.9], [0.9, -0.1], [0.1, -0.1]], hole: None },
    Poly {
        object: 1,
        first: 0,
        points: &[[-0.9, -0.9], [-0.1, -0.9], [-0.1, -0.3], [-0.5, -0.1], [-0.9, -0.3]],
        hole: Some([-0.625, -0.625, -0.375, -0.375]),
    },
];

/// The two objects (sharing one quad-mesh Ptex file, each numbering its faces from 0):
/// lone triangles only (a strip, a fan, a trilist) and a pentagon with a hole.
fn forms_scene() -> String {
    ptex_scene(
        SceneText::head_on(32),
        "faces",
        r#"object "lone" group
    -0.9 0.9 -1  -0.9 0.1 -1  -0.1 0.9 -1  -0.1 0.1 -1  0.1 0.1 -1  0.9 0.1 -1  0.9 0.9 -1  0.1 0.9 -1
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    strip 0 1 2 3
    fan 4 5 6 7
end group
trilist vertex 4 p triangle 2
    [ 0.1 -0.9 -1  0.9 -0.9 -1  0.9 -0.1 -1  0.1 -0.1 -1 ]
    [ 0 1 2  0 2 3 ]
end trilist
end object
object "holed" group
    -0.9 -0.9 -1  -0.1 -0.9 -1  -0.1 -0.3 -1  -0.5 -0.1 -1  -0.9 -0.3 -1
    -0.625 -0.625 -1  -0.375 -0.625 -1  -0.375 -0.375 -1  -0.625 -0.375 -1
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 v 8
    p 0 1 2 3 4 hole 5 8 7 6
end group end object"#,
        &["lone", "holed"],
    )
}

/// The constant colour of face `f` (each channel in (0, 1)).
fn form_colour(f: usize) -> [f32; 3] {
    let t = (f + 1) as f32 / 20.0;
    [t, 1.0 - 0.5 * t, 0.2 + 0.05 * (f % 3) as f32]
}

/// The (object, face) whose sub-quad region holds point (x, y), by Ptex's split (sub-quad
/// i: vertex i, the midpoint of edge i → i+1, the vertex mean, the midpoint of edge
/// i−1 → i; a convex counter-clockwise quadrilateral here); `None` in a hole or outside.
fn form_at(x: f32, y: f32) -> Option<(usize, usize)> {
    for poly in &POLYS {
        if poly.hole.is_some_and(|[x0, y0, x1, y1]| x > x0 && x < x1 && y > y0 && y < y1) {
            continue;
        }
        let pts = poly.points;
        let n = pts.len();
        let mean = pts.iter().fold([0.0; 2], |a, p| [a[0] + p[0] / n as f32, a[1] + p[1] / n as f32]);
        let mid = |a: [f32; 2], b: [f32; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        for i in 0..n {
            let (prev, here, next) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
            let quad = [here, mid(here, next), mean, mid(prev, here)];
            let inside = (0..4).all(|k| {
                let (a, b) = (quad[k], quad[(k + 1) % 4]);
                (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]) >= 0.0
            });
            if inside {
                return Some((poly.object, poly.first + i));
            }
        }
    }
    None
}

/// A strip's, a fan's and a trilist's triangles (an object of lone triangles, which keeps
/// no table until the renderer writes one) and a pentagon with a hole, in a quad-mesh file
/// whose faces are distinct constant colours: every pixel wholly inside one sub-quad's
/// region is that face's colour within 1e-4 in both engines (the classic engine's π
/// times), all 18 + 5 sub-quads are seen, and the only message is the warning that the
/// holed polygon's numbering is a guess, at its line.
#[test]
fn each_geometry_form_renders_its_sub_quads_ptex_faces() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_forms_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    let faces: Vec<FaceSpec> = (0..18).map(|f| FaceSpec { log2: (0, 0), texels: vec![form_colour(f)] }).collect();
    std::fs::write(dir.join("faces.ptx"), ptex_bytes(1, &faces)).unwrap();
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let parsed = mi::parse_str("t.mi", &forms_scene());
        let built = support::build_parsed(&parsed, 32, std::slice::from_ref(&dir));
        assert_eq!(built.messages.len(), 1, "{:#?}", built.messages);
        assert!(built.messages[0].contains("t.mi:23:") && built.messages[0].contains("holes"), "{:?}", built.messages);
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        let seen = assert_constant_regions(engine, &film.rgba(), form_at, |(_, face)| form_colour(face));
        assert_eq!(seen.len(), 18 + 5, "{engine:?}: pixels of every sub-quad");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A hostile n-gon (over `MAX_NGON_VERTICES` vertices) in a scene that reads a quad-mesh
/// file: a warning at its line naming its vertex count (its sub-quads are not made).
#[test]
fn a_hostile_ngon_is_warned_of_at_its_line() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_hostile_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    std::fs::write(dir.join("faces.ptx"), ptex_bytes(1, &[FaceSpec { log2: (0, 0), texels: vec![[0.5; 3]] }])).unwrap();
    let n = scene::mesh::ptex_quads::MAX_NGON_VERTICES + 1;
    let ring: Vec<String> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            format!("{} {} -1", a.cos(), a.sin())
        })
        .collect();
    let verts: Vec<String> = (0..n).map(|k| format!("v {k}")).collect();
    let poly: Vec<String> = (0..n).map(|k| k.to_string()).collect();
    let forms = forms_scene();
    let at = forms.find("object \"holed\"").unwrap();
    let end = forms.find("end group end object").unwrap();
    let text = format!(
        "{}object \"holed\" group\n    {}\n    {}\n    c {}\n{}",
        &forms[..at],
        ring.join("  "),
        verts.join(" "),
        poly.join(" "),
        &forms[end..]
    );
    let parsed = mi::parse_str("t.mi", &text);
    let built = support::build_parsed(&parsed, 8, std::slice::from_ref(&dir));
    let want = format!("a polygon of {n} vertices has no quad-mesh Ptex faces");
    assert!(built.messages.iter().any(|m| m.starts_with("t.mi:22:") && m.contains(&want)), "{:#?}", built.messages);
    std::fs::remove_dir_all(&dir).ok();
}

/// A free-form surface, a subdivision surface and an adaptively displaced quad in a scene
/// that reads a quad-mesh file: the free-form surface has no faces (Ptex defines none for
/// it: black) and is warned of at its group's line; the subdivision surface and the
/// displaced quad carry theirs and are not warned of.
#[test]
fn free_form_surfaces_are_warned_of_at_their_lines_subdivision_and_displacement_are_not() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_surfaces_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    std::fs::write(dir.join("faces.ptx"), ptex_bytes(1, &[FaceSpec { log2: (0, 0), texels: vec![[0.5; 3]] }])).unwrap();
    let text = SceneText::new()
        .options("")
        .text(
            r#"shader "tinted" "mdl::ptexmod::faces" ()
shader "disp" "maya_material_displace" ("displacement" 0)
material "m" = "tinted" displace = "disp" end material
object "cube" group
    -1 -1 -11  1 -1 -11  -1 1 -11  1 1 -11  -1 -1 -9  1 -1 -9  -1 1 -9  1 1 -9
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    subdivision surface "s"
    p 0 2 3 1
    p 4 5 7 6
    p 0 1 5 4
    p 2 6 7 3
    p 0 4 6 2
    p 1 3 7 5
    end subdivision surface
end group end object
object "patch"
    basis "lin" bezier 1
    group
    -1 -1 -7  1 -1 -7  -1 1 -7  1 1 -7
    v 0 v 1 v 2 v 3
    surface "f" "" "lin" 0 1 0. 1. "lin" 0 1 0. 1. 0 1 2 3
    approximate surface regular parametric 4 3 "f"
end group end object
object "plane"
    approximate displace length 0.05 0 10
    group
    -1 -1 -5  1 -1 -5  1 1 -5  -1 1 -5
    v 0 v 1 v 2 v 3
    c 0 1 2 3
end group end object
instance "cube_inst" "cube" material "tinted" end instance
instance "plane_inst" "plane" material "m" end instance
instance "patch_inst" "patch" material "tinted" end instance"#,
        )
        .instance("cube_inst")
        .instance("patch_inst")
        .instance("plane_inst")
        .build();
    let line = |what: &str| text.lines().position(|l| l.contains(what)).unwrap() + 1;
    let parsed = mi::parse_str("t.mi", &text);
    let built = support::build_parsed(&parsed, 8, std::slice::from_ref(&dir));
    let at = line("object \"patch\"") + 2;
    let what = "free-form surface has no quad-mesh Ptex faces (Ptex defines faces for polygon meshes";
    assert!(
        built.messages.iter().any(|m| m.starts_with(&format!("t.mi:{at}:")) && m.contains(what)),
        "{what} at line {at}: {:#?}",
        built.messages
    );
    assert_eq!(built.messages.len(), 1, "{:#?}", built.messages);
    std::fs::remove_dir_all(&dir).ok();
}
