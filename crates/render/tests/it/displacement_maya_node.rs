//! Maya's displacementShader node (`maya_displace`, `adskMayaDisplacementShader`) through a
//! shading group's displacement connection: its `displacement` × `scale` along the normal
//! and its `vectorDisplacement` in object, world and tangent space, absolute and signed.

use glam::{Vec3, Vec3A};

use crate::support;

/// A unit square (corners (0,0,0)…(1,1,0), normal +z, texture coordinates = positions)
/// placed rotated a quarter turn about z and translated, whose material displaces through
/// `shader "dn" "<node>" (<params>)` connected as `"displacement" = "dn.displacement"`.
fn scene(node: &str, params: &str) -> String {
    scene_uv(node, params, "0 0 0  1 0 0  1 1 0  0 1 0")
}

/// [`scene`] with the texture coordinates `uv` of the corners (0,0), (1,0), (1,1), (0,1).
fn scene_uv(node: &str, params: &str, uv: &str) -> String {
    format!(
        r#"$include "mayabase.mi"
$include "AdskShaderSDK.mi"
options "opt" end options
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0 0 1 0 0 0 0 1 0 -0.5 -0.5 -3 1 end instance
shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1)
shader "dn" "{node}" ({params})
shader "sg_disp" "maya_material_displace" ("displacement" = "dn.displacement")
material "m" = "lam" displace = "sg_disp" end material
object "square"
    group
    0 0 0  1 0 0  1 1 0  0 1 0
    {uv}
    v 0 t 4 v 1 t 5 v 2 t 6 v 3 t 7
    p 0 1 2 3
end group end object
instance "square_inst" "square" material "m" transform 0 1 0 0 -1 0 0 0 0 0 1 0 0.5 0 0 1 end instance
instgroup "root" "cam_inst" "square_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The displaced square's object-space vertices and its instance's world → object.
fn displaced(text: &str) -> (Vec<Vec3>, glam::Affine3A) {
    let b = support::build_parsed(&mi::parse_str("t.mi", text), 8, &[]);
    assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("warning")), "{:?}", b.messages);
    let inst = &b.built.world.instances[0];
    (b.built.world.meshes[inst.mesh as usize].positions.clone(), inst.world_to_object)
}

/// Every corner c of the square moved to c + `offset` (object space, 1e-4), whatever the
/// vertex order.
fn assert_moved(positions: &[Vec3], offset: Vec3A, what: &str) {
    assert_eq!(positions.len(), 4, "{what}");
    for corner in [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y] {
        let want = corner + Vec3::from(offset);
        assert!(
            positions.iter().any(|p| (*p - want).length() < 1e-4),
            "{what}: no vertex at {want} (offset {offset}): {positions:?}"
        );
    }
}

/// `displacement` 0.2 × `scale` 2 moves every vertex 0.4 along its normal (+z, object
/// space; 1e-4), under both names.
#[test]
fn scalar_displacement_times_scale_moves_along_the_normal() {
    for node in ["maya_displace", "adskMayaDisplacementShader"] {
        let (positions, _) = displaced(&scene(node, r#""displacement" 0.2, "scale" 2"#));
        assert_moved(&positions, Vec3A::new(0.0, 0.0, 0.4), node);
    }
}

/// `vectorDisplacement` v = (0.1, 0.2, 0.3) with `scale` 2 (1e-4): in object space
/// (`vectorSpace` 1, the default) each vertex moves 2v in object space; in world space (0)
/// by the world vector 2v, which is world → object of it in object space (the quarter turn
/// makes the two differ); in tangent space (2, `tangent` 1 0 0) by 2·(x T + y N + z B) with
/// T = +x, N = +z, B = N × T = +y (object space: the instance turns all three alike);
/// with `yIsUp` off y and z swap. Signed encoding (`vectorEncoding` 1) decodes
/// (0.75, 0.5, 0.25) to (0.5, 0, −0.5).
#[test]
fn vector_displacement_moves_by_the_vector_in_its_space() {
    let v = r#""vectorDisplacement" 0.1 0.2 0.3, "scale" 2"#;
    let (positions, _) = displaced(&scene("maya_displace", v));
    assert_moved(&positions, Vec3A::new(0.2, 0.4, 0.6), "object (default)");

    let (positions, world_to_object) = displaced(&scene("maya_displace", &format!("{v}, \"vectorSpace\" 0")));
    let expect = world_to_object.transform_vector3a(Vec3A::new(0.2, 0.4, 0.6));
    assert!((expect - Vec3A::new(0.2, 0.4, 0.6)).length() > 0.1, "the turn makes world and object differ");
    assert_moved(&positions, expect, "world");

    let tangent = format!("{v}, \"vectorSpace\" 2, \"tangent\" 1 0 0");
    let (positions, _) = displaced(&scene("maya_displace", &tangent));
    assert_moved(&positions, Vec3A::new(0.2, 0.6, 0.4), "tangent");
    let (positions, _) = displaced(&scene("adskMayaDisplacementShader", &format!("{tangent}, \"yIsUp\" off")));
    assert_moved(&positions, Vec3A::new(0.2, 0.4, 0.6), "tangent, z up");

    let signed = r#""vectorDisplacement" 0.75 0.5 0.25, "vectorEncoding" 1"#;
    let (positions, _) = displaced(&scene("maya_displace", signed));
    assert_moved(&positions, Vec3A::new(0.5, 0.0, -0.5), "signed");
}

/// Tangent space without a `tangent` parameter or a bump basis takes Maya's UV tangent,
/// dP/du of the texture coordinates (1e-4): with u = x (coordinates = positions) T = +x,
/// so v = (0.1, 0.2, 0.3) × 2 moves 2·(x T + y N + z B) = (0.2, 0.6, 0.4) as with
/// `tangent` 1 0 0 — the instance's quarter turn makes the world x axis (the fallback
/// without coordinates) differ; with the coordinates turned a quarter turn (u = y,
/// v = 1 − x) T = +y, B = N × T = −x, and the move is (−0.6, 0.2, 0.4).
#[test]
fn tangent_space_without_a_tangent_follows_the_texture_u_direction() {
    let v = r#""vectorDisplacement" 0.1 0.2 0.3, "scale" 2, "vectorSpace" 2"#;
    let (positions, _) = displaced(&scene("maya_displace", v));
    assert_moved(&positions, Vec3A::new(0.2, 0.6, 0.4), "u along x");
    let turned = "0 1 0  0 0 0  1 0 0  1 1 0";
    let (positions, _) = displaced(&scene_uv("adskMayaDisplacementShader", v, turned));
    assert_moved(&positions, Vec3A::new(-0.6, 0.2, 0.4), "u along y");
}
