//! Quad-mesh Ptex face ids of polygon meshes (`scene::mesh::ptex_quads`): each triangle cut
//! from a quad keeps its polygon's Ptex face id and which quad corner each of its vertices
//! is; a polygon of other than 4 vertices takes one face id per vertex (Ptex's sub-quads)
//! and its triangles that first id (n-gon packed), the first starting at the polygon's
//! vertex 0; groups of one object number their faces on.
//!
//! Asserted exactly: face ids, corner of every triangle vertex (the vertex's position is
//! that quad vertex's), the n-gons' first ids and first vertices, nothing unmapped, no
//! table (no bytes per triangle) for an object of triangles only.

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
    let mut ngons: Vec<(u32, u32)> = Vec::new();
    for (t, code) in mesh.triangles.iter().zip(&mesh.ptex_quads) {
        let Some((face, corners)) = ptex_quads::decode(*code) else {
            let first = ptex_quads::ngon_first(*code).expect("an n-gon's triangle");
            if ngons.last().is_none_or(|n| n.0 != first) {
                ngons.push((first, t[0]));
            }
            continue;
        };
        let q = quads.iter().position(|(f, _)| *f == face).unwrap_or_else(|| panic!("face {face}"));
        halves[q] += 1;
        for (v, k) in t.iter().zip(corners) {
            assert_eq!(mesh.positions[*v as usize], quads[q].1[k as usize], "face {face}, triangle {t:?}");
        }
    }
    assert_eq!(halves, [2, 2, 2], "two triangles per quad");
    // The pentagon (`p 1 4 6 5 2`) and the two triangles (`p 5 6 7`, `p 3 2 9`): their
    // first face ids, their first triangles starting at their vertex 0.
    let first = ngons.iter().map(|n| (n.0, mesh.positions[n.1 as usize])).collect::<Vec<_>>();
    assert_eq!(first, [(1, p(1., 0., 0.)), (7, p(2., 1., 0.)), (10, p(0., 1., 0.))]);
    assert_eq!(mesh.ptex_quads.iter().filter(|c| ptex_quads::ngon_first(**c).is_some()).count(), 3 + 2);
    assert!(mesh.ptex_unmapped.is_none());
    // Triangles only: no table.
    let tris = &scene.objects.iter().find(|o| o.name == "tris").expect("tris").geometry.mesh;
    assert!(tris.ptex_quads.is_empty() && tris.ptex_unmapped.is_none());
    assert_eq!(tris.ptex_faces, 3);
}

/// An n-gon of more than `MAX_NGON_VERTICES` vertices gets no sub-quad faces (its
/// triangles none, the object's unmapped polygon it, its n face ids still counted) while
/// one of exactly that many keeps them: the hit-time outline rebuild is O(n²), so a
/// hostile 10⁶-gon must not reach it. Exact counts.
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
                "object \"tris\" group\n    {}\n    {}\n    p {}\n",
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
            assert!(mesh.ptex_unmapped.is_none());
        } else {
            assert_eq!(ngon, 0);
            assert!(mesh.ptex_quads.iter().all(|&c| c == ptex_quads::NONE));
            assert_eq!(mesh.ptex_unmapped.map(|u| u.1), Some(n));
        }
    }
}
