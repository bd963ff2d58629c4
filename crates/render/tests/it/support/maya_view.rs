//! The view the Maya path-engine tests share: a square image looking straight down at the
//! ground from 4 above, and what their checks against a formula share.

use glam::Vec3A;
use render::{EngineKind, Settings};

use super::scene_text::SceneText;

/// The `.mi` options, camera and camera instance of a `side` × `side` pixel image looking
/// down −y at the plane y = 0 from (0, 4, 0) (focal 1, aperture 1.2: x and z in ±2.4 on
/// the ground), 2 samples per pixel at most (`samples 0 2`) through a 1-pixel box filter:
/// options "opt", camera instance "cam_inst".
pub fn top_down(side: usize) -> String {
    top_down_scene(side, "").head()
}

/// [`top_down`] as a scene under construction, after `$include "mayabase.mi"`, with the
/// option statements `options` added (e.g. `trace depth 8 8 16`; may be empty).
pub fn top_down_scene(side: usize, options: &str) -> SceneText {
    let options = format!("samples 0 2 filter box 1 1 {options}");
    SceneText::maya_down(options.trim_end(), 1.2, side as u32, 4.0)
}

/// The `reflectionLimit` tests' two facing reflectors: [`top_down_scene`] (its options
/// `options`) over a ground of material `ground_material` (its shaders and material,
/// `ground`, as `.mi` text) at y = 0, under a Maya mirror ceiling of material "m" at y = 5
/// (`maya_phongE` "mat" without a highlight: reflectivity `r`, incandescence `e`,
/// `reflectionLimit` `limit`); both squares span ±`half` in x and z.
#[allow(clippy::too_many_arguments)]
pub fn under_a_mirror(
    side: usize,
    options: &str,
    ground: &str,
    ground_material: &str,
    half: u32,
    limit: u32,
    e: f32,
    r: f32,
) -> String {
    let h = half;
    top_down_scene(side, options)
        .text(ground)
        .text(&format!(
            r#"shader "mat" "maya_phongE" ("color" 0 0 0, "diffuse" 0, "whiteness" 0 0 0, "specularColor" 1 1 1,
    "reflectivity" {r}, "reflectionLimit" {limit}, "incandescence" {e} {e} {e})
material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -{h} 0 {h}  {h} 0 {h}  {h} 0 -{h}  -{h} 0 -{h}  v 0 v 1 v 2 v 3 c "{ground_material}" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
object "ceiling" group -{h} 5 {h}  {h} 5 {h}  {h} 5 -{h}  -{h} 5 -{h}  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ceiling_inst" "ceiling" end instance"#
        ))
        .instance("ground_inst")
        .instance("ceiling_inst")
        .build()
}

/// Half the side of the ground [`top_down`] shows: x and z in ±`HALF` at y = 0 (scene units).
pub const HALF: f32 = 2.4;

/// The camera's position in [`top_down`] (world space).
pub const EYE: Vec3A = Vec3A::new(0.0, 4.0, 0.0);

/// The `sub` × `sub` points of the ground (y = 0, world space) spread evenly over pixel
/// column `col` and row `row` of a `side` × `side` [`top_down`] image, at the centres of
/// their cells: where a formula is averaged to compare with a pixel.
pub fn ground_points(side: usize, col: usize, row: usize, sub: usize) -> impl Iterator<Item = Vec3A> {
    let pixel = 2.0 * HALF / side as f32;
    (0..sub).flat_map(move |a| {
        (0..sub).map(move |b| {
            let x = -HALF + (col as f32 + (a as f32 + 0.5) / sub as f32) * pixel;
            let z = -HALF + (row as f32 + (b as f32 + 0.5) / sub as f32) * pixel;
            Vec3A::new(x, 0.0, z)
        })
    })
}

/// The RGB pixels of `text` rendered by `engine` with `spp` samples per pixel, asserting
/// the world was built without a warning.
pub fn pixels(text: &str, engine: EngineKind, spp: u32) -> Vec<Vec3A> {
    let (scene, shading) = super::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    super::render_world(&world, &shading, &settings).0.rgba().iter().map(|p| Vec3A::new(p[0], p[1], p[2])).collect()
}

/// The path engine's RGB pixels of `text` with `spp` samples per pixel and paths cut
/// after `max_depth` bounces, asserting the world was built without a warning.
pub fn path_pixels_to_depth(text: &str, spp: u32, max_depth: u32) -> Vec<Vec3A> {
    let (scene, shading) = super::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let mut settings = Settings { engine: EngineKind::Path, spp: Some(spp), ..Settings::default() };
    settings.path.max_depth = max_depth;
    super::render_world(&world, &shading, &settings).0.rgba().iter().map(|p| Vec3A::new(p[0], p[1], p[2])).collect()
}

/// [`pixels`] of a scene whose world warns only about what the test expects: every
/// warning contains `expected`.
pub fn pixels_warned(text: &str, engine: EngineKind, spp: u32, expected: &str) -> Vec<Vec3A> {
    let (scene, shading) = super::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.iter().all(|w| w.contains(expected)), "{:?}", world.warnings);
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    super::render_world(&world, &shading, &settings).0.rgba().iter().map(|p| Vec3A::new(p[0], p[1], p[2])).collect()
}

/// The mean of `px`.
pub fn mean(px: &[Vec3A]) -> Vec3A {
    px.iter().fold(Vec3A::ZERO, |m, p| m + *p) / px.len() as f32
}

/// The mean of `px` and its standard error (per channel, from the pixels' spread).
pub fn mean_and_error(px: &[Vec3A]) -> (Vec3A, Vec3A) {
    let n = px.len() as f32;
    let mean = mean(px);
    let var = px.iter().fold(Vec3A::ZERO, |v, p| v + (*p - mean) * (*p - mean)) / (n - 1.0);
    (mean, (var / n).powf(0.5))
}

/// The 5 × 5 pixels about the peak of a `side` × `side` image `want` (its brightest red
/// pixel, moved two pixels in from the border): the peak's (column, row), and the means
/// of those pixels in `got` and in `want`.
pub fn around_peak(side: usize, got: &[Vec3A], want: &[Vec3A]) -> ((usize, usize), Vec3A, Vec3A) {
    let peak = (0..want.len()).max_by(|&a, &b| want[a].x.total_cmp(&want[b].x)).expect("pixels");
    let (row, col) = ((peak / side).clamp(2, side - 3), (peak % side).clamp(2, side - 3));
    let block = |img: &[Vec3A]| {
        let mut sum = Vec3A::ZERO;
        for r in row - 2..=row + 2 {
            for k in col - 2..=col + 2 {
                sum += img[r * side + k];
            }
        }
        sum / 25.0
    };
    ((col, row), block(got), block(want))
}
