//! Maya's per-vertex data by name, rendered end to end by the classic engine: a triangle
//! with a colour set and two UV sets named by a `"PerVertexNomenclature"` data element,
//! read through mentalrayVertexColors (`maya_vertexcolors`) and uvChooser
//! (`maya_uvchooser`).

use crate::support;

use render::EngineKind;

/// The triangle's corners on the ground plane (world x, z) and their colours.
const CORNERS: [[f32; 2]; 3] = [[-3.0, -3.0], [3.0, -2.0], [0.0, 4.0]];
const COLORS: [[f32; 3]; 3] = [[0.9, 0.1, 0.2], [0.1, 0.8, 0.3], [0.2, 0.3, 0.7]];

/// A camera 3 units above the ground plane looking straight down (8×8 pixels, one
/// sample at each pixel's centre) at the triangle, whose material shows `shader`'s
/// member `member`. Texture space 0 holds a constant decoy, space 1 (UV set "uvB") the
/// corners' ground positions, space 2 (colour set "colorSet1") their colours.
fn scene(shader: &str, member: &str) -> String {
    scene_with(shader, member, NOMENCLATURE)
}

/// Maya 2010+'s names of the texture spaces.
const NOMENCLATURE: &str = r#"data "triShape:PerVertexNomenclature" "PerVertexNomenclature" (
    "magicnumber" 5149248936,
    "tex" [ { "name" "map1", "index" 0 } { "name" "uvB", "index" 1 } ],
    "cpv" [ { "name" "colorSet1", "index" 2 } ]
)"#;

/// The same UV sets in the older exports' `maya_vertexdata` block (its colour sets would
/// be user vectors, which this object has none of).
const VERTEX_DATA: &str = r#"data "triShape:PerVertexNomenclature" "maya_vertexdata" (
    "magic" 1298749048,
    "uvs" [ { "name" "map1", "type" 2, "size" 3, "offset" 0 },
            { "name" "uvB", "type" 2, "size" 3, "offset" 1 } ]
)"#;

/// [`scene`] with the data element `data` naming the texture spaces.
fn scene_with(shader: &str, member: &str, data: &str) -> String {
    let [a, b, c] = CORNERS;
    let [ca, cb, cc] = COLORS;
    format!(
        r#"
$include "mayabase.mi"
options "opt" samples 0 0 filter box 1 1 end options
camera "cam" focal 1 aperture 0.5 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -3 1 end instance
{shader}
shader "surf" "maya_surfaceshader" ("outColor" = "look.{member}")
material "m" opaque "maya_shadingengine" ("surfaceShader" = "surf.outColor") end material
{data}
object "triShape"
    group
        {ax} 0 {az}  {bx} 0 {bz}  {cx} 0 {cz}
        0.25 0.75 0
        {ax} {az} 0  {bx} {bz} 0  {cx} {cz} 0
        {car} {cag} {cab}  {cbr} {cbg} {cbb}  {ccr} {ccg} {ccb}
        v 0 t 3 t 4 t 7  v 1 t 3 t 5 t 8  v 2 t 3 t 6 t 9
        c "m" 0 1 2
    end group
    data "triShape:PerVertexNomenclature"
end object
instance "tri_inst" "triShape" end instance
instgroup "root" "cam_inst" "tri_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        ax = a[0],
        az = a[1],
        bx = b[0],
        bz = b[1],
        cx = c[0],
        cz = c[1],
        car = ca[0],
        cag = ca[1],
        cab = ca[2],
        cbr = cb[0],
        cbg = cb[1],
        cbb = cb[2],
        ccr = cc[0],
        ccg = cc[1],
        ccb = cc[2],
    )
}

/// The ground point (x, z) seen through the centre of pixel (column, row from the top):
/// the pinhole's image plane at focal 1 spans the aperture 0.5, 3 units above the ground.
fn ground_point(column: usize, row: usize) -> [f32; 2] {
    let x_cam = ((column as f32 + 0.5) / 8.0 - 0.5) * 0.5;
    let y_cam = (0.5 - (row as f32 + 0.5) / 8.0) * 0.5;
    [3.0 * x_cam, -3.0 * y_cam]
}

/// Half a pixel's footprint on the ground (the one sample lies somewhere in the pixel).
const HALF_PIXEL: f32 = 0.5 * 3.0 * 0.5 / 8.0;

/// Barycentric coordinates of `p` in the triangle [`CORNERS`].
fn barycentric(p: [f32; 2]) -> [f32; 3] {
    let [a, b, c] = CORNERS;
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    let wb = ((p[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (p[1] - a[1])) / det;
    let wc = ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / det;
    [1.0 - wb - wc, wb, wc]
}

fn render(shader: &str, member: &str) -> Vec<[f32; 4]> {
    let (px, messages) = support::render_text(&scene(shader, member), EngineKind::Classic, Some(1));
    assert!(messages.is_empty(), "{messages:?}");
    assert_eq!(px.len(), 64);
    px
}

/// The hit points of the renders (the same sample in each pixel for every render of the
/// scene): UV set "uvB", which holds the corners' ground positions, interpolated.
fn hit_points() -> Vec<[f32; 2]> {
    let px = render(r#"shader "look" "adskMayaUvChooser" ("uvSets" ["uvB"])"#, "outUv");
    px.iter().map(|p| [p[0], p[1]]).collect()
}

#[test]
fn a_colour_set_named_by_the_nomenclature_is_interpolated_barycentrically() {
    let hits = hit_points();
    let px = render(
        r#"shader "look" "maya_vertexcolors" ("cpvSets" ["notThere", "colorSet1"], "defaultColor" 1 0 1)"#,
        "outColor",
    );
    let mut inside = 0;
    for (i, (p, hit)) in px.iter().zip(&hits).enumerate() {
        let w = barycentric(*hit);
        if w.iter().any(|&w| w < 0.01) {
            continue; // off the triangle, or too close to an edge to tell
        }
        inside += 1;
        for ch in 0..3 {
            let want: f32 = (0..3).map(|k| w[k] * COLORS[k][ch]).sum();
            assert!((p[ch] - want).abs() < 1e-4, "pixel {i} channel {ch}: {} vs {want}", p[ch]);
        }
    }
    assert!(inside >= 20, "only {inside} pixels inside the triangle");
}

#[test]
fn a_colour_set_the_object_lacks_gives_the_default_colour() {
    let px =
        render(r#"shader "look" "maya_vertexcolors" ("cpvSets" ["CPV_DirtMask"], "defaultColor" 1 0 1)"#, "outColor");
    let centre = px[3 * 8 + 4];
    assert!((centre[0] - 1.0).abs() < 1e-6 && centre[1].abs() < 1e-6 && (centre[2] - 1.0).abs() < 1e-6, "{centre:?}");
}

#[test]
fn a_uv_set_named_by_the_nomenclature_is_the_uv_of_the_hit() {
    // Space 1 holds the corners' ground positions: the interpolated UV is the hit point,
    // which lies in the pixel's footprint.
    let mut inside = 0;
    for (i, hit) in hit_points().iter().enumerate() {
        let g = ground_point(i % 8, i / 8);
        if barycentric(g).iter().any(|&w| w < 0.05) {
            continue;
        }
        inside += 1;
        for k in 0..2 {
            assert!((hit[k] - g[k]).abs() <= HALF_PIXEL + 1e-4, "pixel {i}: {hit:?} outside the footprint of {g:?}");
        }
    }
    assert!(inside >= 20, "only {inside} pixels inside the triangle");
    // An unknown name falls back to the first texture space (the decoy 0.25 0.75).
    let px = render(r#"shader "look" "maya_uvchooser" ("uvSets" ["nope"])"#, "outUv");
    let centre = px[3 * 8 + 4];
    assert!((centre[0] - 0.25).abs() < 1e-6 && (centre[1] - 0.75).abs() < 1e-6, "{centre:?}");
}

#[test]
fn a_uv_set_named_by_the_older_vertex_data_block_is_the_uv_of_the_hit() {
    // The same scene with Maya 8.5–2009's `maya_vertexdata` block instead of the
    // nomenclature: "uvB" at offset 1 is texture space 1, so the picture is the same.
    let old = |shader: &str| {
        let (px, messages) =
            support::render_text(&scene_with(shader, "outUv", VERTEX_DATA), EngineKind::Classic, Some(1));
        assert!(messages.is_empty(), "{messages:?}");
        px
    };
    let newer = render(r#"shader "look" "maya_uvchooser" ("uvSets" ["uvB"])"#, "outUv");
    let older = old(r#"shader "look" "maya_uvchooser" ("uvSets" ["uvB"])"#);
    assert_eq!(newer, older, "the block names the same texture space");
    // Not the decoy of space 0: the centre pixel's UV is its ground point.
    let centre = older[3 * 8 + 4];
    let g = ground_point(4, 3);
    assert!((centre[0] - g[0]).abs() <= HALF_PIXEL + 1e-4 && (centre[1] - g[1]).abs() <= HALF_PIXEL + 1e-4);
    // A name the block lacks falls back to space 0 (the decoy 0.25 0.75).
    let px = old(r#"shader "look" "maya_uvchooser" ("uvSets" ["uvC"])"#);
    assert!((px[3 * 8 + 4][0] - 0.25).abs() < 1e-6 && (px[3 * 8 + 4][1] - 0.75).abs() < 1e-6);
}
