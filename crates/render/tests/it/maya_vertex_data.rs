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

/// Custom data that sits before the colour set among the user vectors (a scalar per
/// corner): a colour set read from the wrong user vector would show these.
const WEIGHTS: [f32; 3] = [5.0, 6.0, 7.0];

/// The older exports' block for geometry whose user vectors are the custom data
/// "weight" (user vector 0) and the colour set "colorSet1" (user vector 1: its offset 0
/// after the one custom data entry), with the UV sets of [`VERTEX_DATA`].
const VERTEX_DATA_USER: &str = r#"data "triShape:vxdata" "maya_vertexdata" (
    "magic" 1298749048,
    "data" [ { "name" "weight", "type" 0, "size" 1, "offset" 0 } ],
    "uvs" [ { "name" "map1", "type" 2, "size" 3, "offset" 0 },
            { "name" "uvB", "type" 2, "size" 3, "offset" 1 } ],
    "cpv" [ { "name" "colorSet1", "type" 3, "size" 3, "offset" 0 } ]
)"#;

/// How the older export's triangle is written.
#[derive(Clone, Copy, Debug)]
enum Form {
    /// A `group` whose vertices name their user vectors (`u i`).
    Group,
    /// A `trilist` with user spaces in its layout (`u 1 3`).
    Trilist,
}

/// A ground point (x, z) as a UV in [0, 1]² (the path engine emits no negative light).
fn ground_to_uv([x, z]: [f32; 2]) -> [f32; 2] {
    [(x + 4.0) / 8.0, (z + 4.0) / 8.0]
}

/// The ground point of a UV of [`ground_to_uv`].
fn uv_to_ground([u, v]: [f32; 2]) -> [f32; 2] {
    [u * 8.0 - 4.0, v * 8.0 - 4.0]
}

/// The triangle of [`scene`] written as Maya 8.5–2009 export it: a `maya_vertexdata`
/// block, texture spaces 0 (decoy 0.25 0.75) and 1 ("uvB", the corners' ground
/// positions through [`ground_to_uv`]), user vectors 0 ([`WEIGHTS`]) and 1 ([`COLORS`]).
fn older_scene(shader: &str, member: &str, form: Form) -> String {
    let corner = |k: usize| {
        let [r, g, b] = COLORS[k];
        (CORNERS[k], ground_to_uv(CORNERS[k]), WEIGHTS[k], r, g, b)
    };
    let geometry = match form {
        Form::Group => {
            let mut vectors = String::new();
            for [x, z] in CORNERS {
                vectors += &format!("{x} 0 {z}\n");
            }
            vectors += "0.25 0.75 0\n";
            for k in 0..3 {
                let (_, [u, v], w, r, g, b) = corner(k);
                vectors += &format!("{u} {v} 0\n{w} 0 0\n{r} {g} {b}\n");
            }
            // Vectors: 0–2 positions, 3 the decoy, then per corner k: 4 + 3k its ground
            // position, 5 + 3k its weight, 6 + 3k its colour.
            let vertices: String =
                (0..3).map(|k| format!("v {k} t 3 t {} u {} u {}\n", 4 + 3 * k, 5 + 3 * k, 6 + 3 * k)).collect();
            format!("group\n{vectors}{vertices}c \"m\" 0 1 2\nend group")
        }
        Form::Trilist => {
            let lines: String = (0..3)
                .map(|k| {
                    let ([x, z], [u, v], w, r, g, b) = corner(k);
                    format!("{x} 0 {z}  0.25 0.75 0  {u} {v} 0  {w}  {r} {g} {b}\n")
                })
                .collect();
            format!("trilist vertex 3 p t 3 3 u 1 3 triangle 1\n[\n{lines}]\n[ 0 1 2 ]\nend trilist")
        }
    };
    format!(
        r#"
$include "mayabase.mi"
options "opt" samples 0 0 filter box 1 1 end options
camera "cam" focal 1 aperture 0.5 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -3 1 end instance
{shader}
shader "surf" "maya_surfaceshader" ("outColor" = "look.{member}")
material "m" opaque "maya_shadingengine" ("surfaceShader" = "surf.outColor") end material
{VERTEX_DATA_USER}
object "triShape"
    {geometry}
    data "triShape:vxdata"
end object
instance "tri_inst" "triShape" material "m" end instance
instgroup "root" "cam_inst" "tri_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

fn render_older(shader: &str, member: &str, form: Form, engine: EngineKind) -> Vec<[f32; 4]> {
    let (px, messages) = support::render_text(&older_scene(shader, member, form), engine, Some(1));
    assert!(messages.is_empty(), "{form:?} {engine:?}: {messages:?}");
    assert_eq!(px.len(), 64);
    px
}

/// mentalrayVertexColors reading the older block's colour set (after a name it lacks).
const COLOR_SET: &str =
    r#"shader "look" "adskMayaVertexColors" ("cpvSets" ["notThere", "colorSet1"], "defaultColor" 1 0 1)"#;

#[test]
fn a_colour_set_of_the_older_vertex_data_block_is_its_user_vector_interpolated_in_both_engines() {
    for engine in [EngineKind::Classic, EngineKind::Path] {
        for form in [Form::Group, Form::Trilist] {
            // Where each pixel's one sample hits (the same sample in every render of the
            // scene): UV set "uvB" holds the corners' ground positions.
            let hits = render_older(r#"shader "look" "maya_uvchooser" ("uvSets" ["uvB"])"#, "outUv", form, engine);
            let px = render_older(COLOR_SET, "outColor", form, engine);
            let mut inside = 0;
            for (i, (p, hit)) in px.iter().zip(&hits).enumerate() {
                let w = barycentric(uv_to_ground([hit[0], hit[1]]));
                if w.iter().any(|&w| w < 0.01) {
                    continue; // off the triangle, or too close to an edge to tell
                }
                inside += 1;
                let g = ground_point(i % 8, i / 8);
                let hit = uv_to_ground([hit[0], hit[1]]);
                assert!(
                    (0..2).all(|k| (hit[k] - g[k]).abs() <= HALF_PIXEL + 1e-4),
                    "{engine:?} {form:?} pixel {i}: hit {hit:?} outside the footprint of {g:?}"
                );
                for ch in 0..3 {
                    let want: f32 = (0..3).map(|k| w[k] * COLORS[k][ch]).sum();
                    assert!(
                        (p[ch] - want).abs() < 1e-3,
                        "{engine:?} {form:?} pixel {i} channel {ch}: {} vs {want} at barycentric {w:?}",
                        p[ch]
                    );
                }
            }
            assert!(inside >= 20, "{engine:?} {form:?}: only {inside} pixels inside the triangle");
        }
    }
}

#[test]
fn a_colour_set_of_the_older_block_without_user_vectors_gives_the_default_colour() {
    // The block names "colorSet1" but the object of `scene_with` has no user vectors.
    let block = VERTEX_DATA_USER.replace("triShape:vxdata", "triShape:PerVertexNomenclature");
    let shader = r#"shader "look" "maya_vertexcolors" ("cpvSets" ["colorSet1"], "defaultColor" 1 0 1)"#;
    let (px, messages) = support::render_text(&scene_with(shader, "outColor", &block), EngineKind::Classic, Some(1));
    assert!(messages.is_empty(), "{messages:?}");
    let centre = px[3 * 8 + 4];
    assert!((centre[0] - 1.0).abs() < 1e-6 && centre[1].abs() < 1e-6 && (centre[2] - 1.0).abs() < 1e-6, "{centre:?}");
}

/// The bytes per triangle of `world`'s meshes (their arrays).
fn bytes_per_triangle(world: &render::World) -> f64 {
    let bytes: usize = world.meshes.iter().map(|m| m.memory_bytes()).sum();
    let triangles: usize = world.meshes.iter().map(|m| m.triangles.len()).sum();
    bytes as f64 / triangles as f64
}

#[test]
fn only_meshes_with_user_vectors_pay_for_them() {
    // The seed Cornell box has none: no user array, no byte more per triangle.
    let (scene, shading) = support::build_clean(include_str!("../../../../scenes/iray_cornell_box.mi"));
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.meshes.iter().all(|m| m.user.is_empty() && m.user.capacity() == 0));
    eprintln!("Cornell box: {:.1} bytes per triangle", bytes_per_triangle(&world));
    // The older export's triangle: two user spaces of 3 vertices, 12 bytes a vector.
    for form in [Form::Group, Form::Trilist] {
        let (scene, shading) = support::build_clean(&older_scene(COLOR_SET, "outColor", form));
        let world = render::World::from_scene_shaded(&scene, Some(&shading));
        let [mesh] = world.meshes.as_slice() else { panic!("one mesh") };
        assert_eq!(mesh.user.len(), 2, "{form:?}");
        let user_bytes: usize = mesh.user.iter().map(|u| u.len() * 12).sum();
        assert_eq!(user_bytes, 2 * 3 * 12, "{form:?}");
        let mut bare = mesh.clone();
        bare.user.clear();
        assert_eq!(mesh.memory_bytes() - bare.memory_bytes(), user_bytes, "{form:?}");
    }
}

#[test]
fn the_older_block_locates_uv_sets_colour_sets_and_custom_data() {
    use maya::vertex_data::{locate, value_at, SetSource, VertexSet};
    for form in [Form::Group, Form::Trilist] {
        let (scene, shading) = support::build_clean(&older_scene(COLOR_SET, "outColor", form));
        let world = render::World::from_scene_shaded(&scene, Some(&shading));
        let accel = render::accel::build(&world, render::Backend::Rust);
        let tracer = render::tracer::SceneTracer::new(&world, &*accel);
        // A hit on the triangle (world instance 0, its only primitive) at barycentric w.
        let w = [0.2, 0.3, 0.5];
        let state = shader::State {
            instance: world.instances[0].scene_index,
            geometry: 0,
            prim: 0,
            bary: w,
            ..shader::State::default()
        };
        let ctx = shader::Ctx::new(&shading, &tracer, state);
        assert_eq!(locate(&ctx, VertexSet::Uv, "uvB"), Some(SetSource::TextureSpace(1)), "{form:?}");
        assert_eq!(locate(&ctx, VertexSet::Custom, "weight"), Some(SetSource::UserVector(0)), "{form:?}");
        assert_eq!(locate(&ctx, VertexSet::Color, "colorSet1"), Some(SetSource::UserVector(1)), "{form:?}");
        assert_eq!(locate(&ctx, VertexSet::Color, "weight"), None, "{form:?}: custom data is no colour set");
        assert_eq!(locate(&ctx, VertexSet::Custom, "colorSet1"), None, "{form:?}");
        // Custom data interpolated at w: Σ w_k weight_k in x.
        let weight = value_at(&ctx, SetSource::UserVector(0)).expect("user vector 0");
        let want: f32 = (0..3).map(|k| w[k] * WEIGHTS[k]).sum();
        assert!((weight.x - want).abs() < 1e-5 && weight.y == 0.0 && weight.z == 0.0, "{form:?}: {weight} vs {want}");
        assert_eq!(value_at(&ctx, SetSource::UserVector(2)), None, "{form:?}: the mesh has two user vectors");
    }
}
