//! Quad-mesh Ptex face ids of polygon meshes (`scene::mesh::ptex_quads`): each triangle cut
//! from a quad keeps its polygon's Ptex face id and which quad corner each of its vertices
//! is; a polygon of other than 4 vertices takes one face id per vertex (Ptex's sub-quads):
//! a triangle of its own (3-vertex polygons, each triangle of a strip, a fan or a trilist)
//! its first id and its polygon's vertex order, an n-gon's triangles its first id and its
//! outline kept (`scene::mesh::ptex_ngons`); groups of one object number their faces on.
//!
//! Asserted exactly: face ids, corner of every triangle vertex (the vertex's position is
//! that quad vertex's), the n-gons' first ids and outlines, nothing unmapped, no table (no
//! bytes per triangle) for an object of lone triangles.

use crate::support::build;
use glam::Vec3;
use scene::mesh::ptex_quads;

const SCENE: &str = r#"
options "opt" end options
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
object "quads" group
    0 0 0  1 0 0  1 1 0  0 1 0  2 0 0  2 1 0  3 0.5 0  3 2 0  2 2 0  1 2 0
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 v 8 v 9
    c 0 1 2 3
    p 1 4 6 5 2
    p 2 5 8 9
    p 5 6 7
    p 3 2 9
end group
group
    0 0 1  1 0 1  1 1 1  0 1 1
    v 0 v 1 v 2 v 3
    p 1 2 3 0
end group end object
object "tris" group
    0 0 0  1 0 0  1 1 0
    v 0 v 1 v 2
    p 0 1 2
end group end object
instance "q" "quads" end instance
instance "t" "tris" end instance
instgroup "root" "cam_inst" "q" "t" end instgroup
render "root" "cam_inst" "opt"
"#;

#[test]
fn triangles_of_quads_keep_their_polygons_face_and_corners() {
    let (scene, ..) = build(SCENE);
    let mesh = &scene.objects.iter().find(|o| o.name == "quads").expect("quads").geometry.mesh;
    assert_eq!(mesh.ptex_quads.len(), mesh.triangles.len());
    // Faces: quad 0, pentagon 1–5, quad 6, triangle 7–9, triangle 10–12; the second group's
    // quad 13.
    assert_eq!(mesh.ptex_faces, 14);
    // The quads (face, vertex positions in polygon order).
    let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let quads = [
        (0, [p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 0.), p(0., 1., 0.)]),
        (6, [p(1., 1., 0.), p(2., 1., 0.), p(2., 2., 0.), p(1., 2., 0.)]),
        (13, [p(1., 0., 1.), p(1., 1., 1.), p(0., 1., 1.), p(0., 0., 1.)]),
    ];
    let mut halves = [0; 3];
    let mut ngons: Vec<u32> = Vec::new();
    let mut lone: Vec<(u32, Vec3)> = Vec::new();
    for (t, code) in mesh.triangles.iter().zip(&mesh.ptex_quads) {
        if let Some(first) = ptex_quads::triangle_first(*code) {
            lone.push((first, mesh.positions[t[0] as usize]));
            continue;
        }
        let Some((face, corners)) = ptex_quads::decode(*code) else {
            ngons.push(ptex_quads::ngon_first(*code).expect("an n-gon's triangle"));
            continue;
        };
        let q = quads.iter().position(|(f, _)| *f == face).unwrap_or_else(|| panic!("face {face}"));
        halves[q] += 1;
        for (v, k) in t.iter().zip(corners) {
            assert_eq!(mesh.positions[*v as usize], quads[q].1[k as usize], "face {face}, triangle {t:?}");
        }
    }
    assert_eq!(halves, [2, 2, 2], "two triangles per quad");
    // The pentagon (`p 1 4 6 5 2`): three triangles of first face 1, its outline kept.
    assert_eq!(ngons, [1, 1, 1]);
    let outline: Vec<Vec3> = mesh.ptex_ngons.outline.iter().map(|&v| mesh.positions[v as usize]).collect();
    assert_eq!(outline, [p(1., 0., 0.), p(2., 0., 0.), p(3., 0.5, 0.), p(2., 1., 0.), p(1., 1., 0.)]);
    assert_eq!(mesh.ptex_ngons.polygons.iter().map(|n| n.first).collect::<Vec<_>>(), [1]);
    // The two triangles (`p 5 6 7`, `p 3 2 9`): their first face ids, their vertex 0 first.
    assert_eq!(lone, [(7, p(2., 1., 0.)), (10, p(0., 1., 0.))]);
    assert!(mesh.ptex_unmapped.is_none() && mesh.ptex_holed.is_none() && mesh.ptex_surface.is_none());
    // Triangles only: no table, face ids by index.
    let tris = &scene.objects.iter().find(|o| o.name == "tris").expect("tris").geometry.mesh;
    assert!(tris.ptex_quads.is_empty() && tris.ptex_triangles && tris.ptex_unmapped.is_none());
    assert_eq!(tris.ptex_faces, 3);
}

const FORMS: &str = r#"
options "opt" end options
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
object "forms" group
    0 1 0  0 0 0  1 1 0  1 0 0
    2 0 0  3 0 0  3 1 0  2 1 0
    4 0 0  6 0 0  6 2 0  5 3 0  4 2 0  4.5 0.5 0  5.5 0.5 0  5.5 1.5 0  4.5 1.5 0
    7 0 0  8 0 0  8 1 0  7 1 0
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 v 8 v 9 v 10 v 11 v 12 v 13 v 14 v 15 v 16 v 17 v 18 v 19 v 20
    strip 0 1 2 3
    fan 4 5 6 7
    p 8 9 10 11 12 hole 13 16 15 14
    c 17 18 19 20
end group
trilist vertex 4 p triangle 2
    [ 9 0 0  10 0 0  10 1 0  9 1 0 ]
    [ 0 1 2  0 2 3 ]
end trilist
end object
object "lone" group
    0 1 0  0 0 0  1 1 0  1 0 0  2 1 0
    v 0 v 1 v 2 v 3 v 4
    strip 0 1 2 3 4
    fan 2 3 4
end group
trilist vertex 3 p triangle 1
    [ 9 0 0  10 0 0  10 1 0 ]
    [ 0 1 2 ]
end trilist
end object
instance "f" "forms" end instance
instance "l" "lone" end instance
instgroup "root" "cam_inst" "f" "l" end instgroup
render "root" "cam_inst" "opt"
"#;

/// Strips, fans and trilists give each triangle 3 sub-quad faces in the object's face
/// order (each triangle's vertex 0 its own, odd strip triangles turned as the strip makes
/// them); a polygon with holes its outer boundary's sub-quads (its outline kept, the hole
/// noted); an object of lone triangles keeps no table. Exact.
#[test]
fn strips_fans_holes_and_trilists_number_their_faces() {
    let (scene, ..) = build(FORMS);
    let mesh = &scene.objects.iter().find(|o| o.name == "forms").expect("forms").geometry.mesh;
    assert_eq!(mesh.ptex_quads.len(), mesh.triangles.len());
    // Strip 0–5, fan 6–11, holed pentagon 12–16, quad 17, trilist 18–23.
    assert_eq!(mesh.ptex_faces, 24);
    let lone: Vec<(u32, [u32; 3])> = mesh
        .triangles
        .iter()
        .zip(&mesh.ptex_quads)
        .filter_map(|(t, c)| ptex_quads::triangle_first(*c).map(|f| (f, *t)))
        .collect();
    let trilist = 21;
    assert_eq!(
        lone,
        [
            (0, [0, 1, 2]),
            (3, [2, 1, 3]),
            (6, [4, 5, 6]),
            (9, [4, 6, 7]),
            (18, [trilist, 22, 23]),
            (21, [trilist, 23, 24])
        ]
    );
    let holed = mesh.ptex_quads.iter().filter(|c| ptex_quads::ngon_first(**c) == Some(12)).count();
    assert_eq!(holed, 5 + 4 + 2 - 2, "the holed pentagon's triangles (n + 2h − 2)");
    assert_eq!(mesh.ptex_ngons.outline, [8, 9, 10, 11, 12]);
    assert!(mesh.ptex_holed.is_some() && mesh.ptex_unmapped.is_none());
    assert_eq!(mesh.ptex_quads.iter().filter(|c| ptex_quads::decode(**c).is_some_and(|d| d.0 == 17)).count(), 2);
    // Lone triangles only (strip, fan, trilist): no table, 3 faces a triangle.
    let lone = &scene.objects.iter().find(|o| o.name == "lone").expect("lone").geometry.mesh;
    assert!(lone.ptex_quads.is_empty() && lone.ptex_triangles);
    assert_eq!((lone.triangles.len(), lone.ptex_faces), (5, 15));
}

/// An n-gon of more than `MAX_NGON_VERTICES` vertices (a hostile bound) gets no sub-quad
/// faces (its triangles none, the object's unmapped polygon it, its n face ids still
/// counted) while one of exactly that many keeps them. Exact counts.
#[test]
fn a_huge_ngon_gets_no_sub_quads() {
    let cap = ptex_quads::MAX_NGON_VERTICES;
    for n in [cap, cap + 1] {
        let ring = |k: usize| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            format!("{} {} 0", a.cos(), a.sin())
        };
        let points: Vec<String> = (0..n).map(ring).collect();
        let verts: Vec<String> = (0..n).map(|k| format!("v {k}")).collect();
        let poly: Vec<String> = (0..n).map(|k| k.to_string()).collect();
        let text = SCENE.replace(
            "object \"tris\" group\n    0 0 0  1 0 0  1 1 0\n    v 0 v 1 v 2\n    p 0 1 2\n",
            &format!(
                "object \"tris\" group\n    {}\n    {}\n    c {}\n",
                points.join("  "),
                verts.join(" "),
                poly.join(" ")
            ),
        );
        let (scene, ..) = build(&text);
        let mesh = &scene.objects.iter().find(|o| o.name == "tris").expect("tris").geometry.mesh;
        assert_eq!(mesh.triangles.len(), n - 2);
        assert_eq!(mesh.ptex_faces as usize, n);
        let ngon = mesh.ptex_quads.iter().filter(|c| ptex_quads::ngon_first(**c).is_some()).count();
        if n <= cap {
            assert_eq!(ngon, n - 2);
            assert_eq!(mesh.ptex_ngons.outline.len(), n);
            assert!(mesh.ptex_unmapped.is_none());
        } else {
            assert_eq!(ngon, 0);
            assert!(mesh.ptex_quads.iter().all(|&c| c == ptex_quads::NONE));
            assert!(mesh.ptex_ngons.is_empty());
            assert_eq!(mesh.ptex_unmapped.map(|u| u.1), Some(n));
        }
    }
}
