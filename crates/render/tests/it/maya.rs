//! Maya scenes rendered end to end by the classic engine (the renderer's ray casting,
//! state set-up and image) with the Maya library's shaders, and by the path engine.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use shader::{Shading, ShadingOptions};

use crate::support::scene_text::{translate, SceneText};

/// A `maya_directionallight` of `parameters` shining at 60° from straight down, along
/// (−cos 30°, −sin 30°, 0) in world space.
fn sun_60(parameters: &str) -> String {
    format!(r#""maya_directionallight" ({parameters}) direction -0.8660254 -0.5 0"#)
}

/// A warm `maya_pointlight` of intensity 6 with quadratic decay at its instance's origin.
const DECAYING_POINT: &str = r#""maya_pointlight" ("color" 1 0.8 0.6, "intensity" 6, "decayRate" 2) origin 0 0 0"#;

/// Material "m" of the shading engine whose surface shader is "top" (defined by the test).
const TOP_MATERIAL: &str =
    r#"material "m" opaque "maya_shadingengine" ("surfaceShader" = "top.outColor") end material"#;

/// Object "plane" of material "m" (x and z in ±3 at y = 0, texture coordinates 0…1) and its
/// instance "plane_inst".
const UV_PLANE: &str = r#"object "plane" group -3 0 3  3 0 3  3 0 -3  -3 0 -3  0 0 0  1 0 0  1 1 0  0 1 0
    v 0 t 4 v 1 t 5 v 2 t 6 v 3 t 7 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance"#;

/// A `maya_lambert` "lam" of colour (0.6, 0.5, 0.4) and `diffuse`, its material "m"
/// (shadow shader too) and object "plane" of it (x and z in ±`half` at y = 0) with
/// instance "plane_inst".
fn lambert_plane(diffuse: f32, half: u32) -> String {
    format!(
        r#"shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" {diffuse})
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "plane" group -{half} 0 {half}  {half} 0 {half}  {half} 0 -{half}  -{half} 0 -{half}  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance"#
    )
}

/// A parsed, built and compiled scene.
struct Loaded {
    scene: scene::Scene,
    shading: Shading,
}

fn load(parsed: &mi::Parsed, dirs: Vec<PathBuf>, resolution: Option<(u32, u32)>) -> Loaded {
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let mut scene = scene::Scene::build(parsed, 0, &mut diags).expect("a scene");
    if let Some((w, h)) = resolution {
        // Keep the image plane (square pixels).
        scene.camera.aspect = f64::from(w) / f64::from(h);
        scene.camera.resolution = (w, h);
    }
    let options = ShadingOptions { search: shader::texture::SearchPath { dirs }, ..ShadingOptions::default() };
    let (shading, _) = Shading::build(&scene, &options, &material::registry());
    Loaded { scene, shading }
}

/// Renders with the classic engine at `spp` samples per pixel: RGBA per pixel, top row
/// first.
fn render_classic(l: &Loaded, spp: u32) -> (u32, u32, Vec<[f32; 4]>) {
    let world = render::World::from_scene_shaded(&l.scene, Some(&l.shading));
    let accel = render::accel::build(&world, render::Backend::Rust);
    let settings =
        render::Settings { engine: render::EngineKind::Classic, spp: Some(spp), ..render::Settings::default() };
    let (film, _) =
        render::render(&world, accel.as_ref(), Some(&l.shading), &settings, &AtomicBool::new(false), &|_| {});
    (film.width, film.height, film.rgba())
}

fn export(name: &str, resolution: (u32, u32)) -> Loaded {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/maya");
    let parsed = mi::parse_file(&dir.join(name), &mi::ReadOptions::default()).expect("readable");
    load(&parsed, vec![dir], Some(resolution))
}

#[test]
fn a_lambert_plane_renders_c_d_i_cos_theta_in_every_pixel() {
    // A camera 3 units above a large lambert plane, looking straight down; a directional
    // light of intensity 2 at 60° from the normal: every pixel is c·d·I·cos 60°.
    let text = SceneText::maya_down("samples 0 0 filter box 1 1", 0.5, 8, 3.0)
        .light("sun", &sun_60(r#""intensity" 2, "useRayTraceShadows" on"#), None)
        .text(&lambert_plane(0.7, 20))
        .instance("plane_inst")
        .build();
    let l = load(&mi::parse_str("plane.mi", &text), Vec::new(), None);
    let (w, h, px) = render_classic(&l, 1);
    assert_eq!((w, h), (8, 8));
    let k = 0.7 * 2.0 * 0.5;
    for p in &px {
        for (got, want) in p.iter().zip([0.6 * k, 0.5 * k, 0.4 * k, 1.0]) {
            assert!((got - want).abs() < 1e-4, "pixel {p:?}, want {want}");
        }
    }
}

/// Mean RGB and the share of pixels whose alpha is 1.
fn summary(px: &[[f32; 4]]) -> ([f32; 3], f32) {
    let mut mean = [0.0f32; 3];
    let mut opaque = 0;
    for p in px {
        assert!(p.iter().all(|v| v.is_finite()), "non-finite pixel {p:?}");
        for i in 0..3 {
            mean[i] += p[i] / px.len() as f32;
        }
        opaque += usize::from((p[3] - 1.0).abs() < 1e-3);
    }
    (mean, opaque as f32 / px.len() as f32)
}

#[test]
fn the_maya_exports_render_with_the_classic_engine() {
    for name in ["maya2017_export.mi", "maya2012_export.mi", "maya_materials.mi"] {
        let l = export(name, (24, 16));
        let (_, _, px) = render_classic(&l, 1);
        let (mean, opaque) = summary(&px);
        // The ground fills the lower part of the frame, lit: never black.
        assert!(mean.iter().all(|&m| m > 0.02), "{name}: mean {mean:?}");
        assert!(opaque > 0.3, "{name}: {opaque} of the pixels opaque");
    }
}

/// Writes the README picture of the Maya 2012 export:
/// `cargo test -p render --test it -- --ignored --nocapture maya::write_picture`
/// (`MAYA_PICTURE` names the output, `docs/images/maya_export.png` by default;
/// `MAYA_SCENE` another scene of `scenes/maya`).
#[test]
#[ignore]
fn write_picture() {
    let scene = std::env::var("MAYA_SCENE").unwrap_or_else(|_| "maya2012_export.mi".into());
    let l = export(&scene, (480, 320));
    let t = std::time::Instant::now();
    let (w, h, px) = render_classic(&l, 16);
    let tone = render::tonemap::ToneMapper::for_camera(&l.scene.camera, &l.scene.library, true);
    let mut img = image::RgbImage::new(w, h);
    for (i, p) in px.iter().enumerate() {
        let c = tone.map_at(bsdf::Rgb::new(p[0], p[1], p[2]), i as u32 % w, i as u32 / w, w, h);
        let rgb = [c.x, c.y, c.z].map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
        img.put_pixel(i as u32 % w, i as u32 / w, image::Rgb(rgb));
    }
    let out = std::env::var("MAYA_PICTURE").map_or_else(
        |_| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/images/maya_export.png"),
        PathBuf::from,
    );
    img.save(&out).expect("written");
    println!("{} ({w}x{h}, 16 spp, {:.1} s)", out.display(), t.elapsed().as_secs_f32());
}

/// The world of a loaded scene for the path engine, its Maya materials and lights
/// translated by this crate (as the renderer will once it asks this crate).
fn path_world(l: &Loaded) -> render::World {
    let mut world = render::World::from_scene_shaded(&l.scene, Some(&l.shading));
    for m in world.materials.iter_mut().skip(1) {
        let Some(ms) = l.shading.materials.iter().find(|s| s.name == m.name) else { continue };
        if let Some((translated, _)) =
            ms.surface.and_then(|s| material::maya::surface_material(&m.name, &l.shading.graph, s))
        {
            *m = translated;
        }
    }
    world.lights = l
        .scene
        .lights
        .iter()
        .filter_map(|light| {
            let e = material::emission::maya::light_emission(light, &l.scene.library)?.ok()?;
            let output = match e.power {
                material::emission::Power::Constant { color, falloff } => {
                    render::light::Output::Constant { color, falloff }
                }
                material::emission::Power::Photometric { color, exponent, range } => {
                    render::light::Output::Photometric { color, exponent, range, distribution: None }
                }
                _ => return None,
            };
            Some(render::light::LightSource {
                name: light.instance.clone(),
                kind: light.kind,
                position: light.position.as_vec3a(),
                direction: light.direction.as_vec3a(),
                shape: render::light::Shape::Point,
                rect_frame: None,
                output,
                spread: light.spread as f32,
                cone: e.cone,
                spot_exponent: None,
                maya_spot: None,
                visible: false,
                shadow: light.shadow,
                shadow_color: glam::Vec3A::ZERO,
                soft_shadow: None,
                motion: Vec::new(),
                lobes: Default::default(),
            })
        })
        .collect();
    world
}

#[test]
fn the_path_engine_agrees_with_the_classic_engine_on_a_diffuse_maya_scene() {
    // A checker-textured lambert plane under a directional light at 60°, a point light
    // with quadratic decay and a spot: nothing else in the scene, so no indirect light;
    // the image means of the two engines agree within 2 %.
    let text = SceneText::maya_down("samples 0 2 filter box 1 1", 1.2, 32, 4.0)
        .light("sun", &sun_60(r#""intensity" 0.8"#), None)
        .light("pt", DECAYING_POINT, Some(&translate(-1.0, -2.0, 0.0)))
        .light(
            "sp",
            r#""maya_spotlight" ("color" 0.5 0.6 1, "intensity" 0.5, "coneAngle" 1.2)
    origin 0 0 0 direction 0 -1 0 spread 0.8253356"#,
            Some(&translate(1.0, -2.5, 0.5)),
        )
        .text(
            r#"shader "place" "maya_place2dtexture" ("repeatU" 3, "repeatV" 3)
shader "chk" "maya_checker" ("uvCoord" = "place.outUV", "color1" 0.9 0.8 0.7, "color2" 0.2 0.3 0.4)
shader "lam" "maya_lambert" ("color" = "chk.outColor", "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
        )
        .text(UV_PLANE)
        .instance("plane_inst")
        .build();
    let l = load(&mi::parse_str("plane.mi", &text), Vec::new(), None);
    let (_, _, classic) = render_classic(&l, 4);
    let world = path_world(&l);
    assert_eq!(world.lights.len(), 3);
    let accel = render::accel::build(&world, render::Backend::Rust);
    let settings = render::Settings { engine: render::EngineKind::Path, spp: Some(64), ..render::Settings::default() };
    let (film, _) =
        render::render(&world, accel.as_ref(), Some(&l.shading), &settings, &AtomicBool::new(false), &|_| {});
    let path = film.rgba();
    let (cm, _) = summary(&classic);
    let (pm, _) = summary(&path);
    println!("image means: classic {cm:?}, path {pm:?}");
    for i in 0..3 {
        assert!(cm[i] > 0.05, "classic mean {cm:?}");
        assert!((pm[i] / cm[i] - 1.0).abs() < 0.02, "path {pm:?} vs classic {cm:?}");
    }
}

/// Renders `text` with both engines (classic 4 spp, path 64 spp): the image means.
fn both_engines(text: &str) -> ([f32; 3], [f32; 3]) {
    let l = load(&mi::parse_str("scene.mi", text), Vec::new(), None);
    let (_, _, classic) = render_classic(&l, 4);
    let world = path_world(&l);
    let accel = render::accel::build(&world, render::Backend::Rust);
    let settings = render::Settings { engine: render::EngineKind::Path, spp: Some(64), ..render::Settings::default() };
    let (film, _) =
        render::render(&world, accel.as_ref(), Some(&l.shading), &settings, &AtomicBool::new(false), &|_| {});
    (summary(&classic).0, summary(&film.rgba()).0)
}

#[test]
fn both_engines_agree_on_ramp_layered_and_3d_textured_maya_materials() {
    // A plane lit by a directional light at 60° and a point light, seen from above;
    // only diffuse reflection, so the two engines' image means agree within 2 %: the
    // rampShader in Maya's documented lambert recipe (path: Lambert of the colour at 1),
    // a layeredShader of two lamberts (path: the albedos mixed by their visible shares)
    // and a lambert coloured by a marble 3D texture (evaluated per hit in both engines).
    let scene = |materials: &str| {
        SceneText::maya_down("samples 0 2 filter box 1 1", 1.2, 32, 4.0)
            .include("AdskShaderSDK.mi")
            .light("sun", &sun_60(r#""intensity" 0.8"#), None)
            .light("pt", DECAYING_POINT, Some(&translate(-1.0, -2.0, 0.0)))
            .text(materials)
            .text(TOP_MATERIAL)
            .text(UV_PLANE)
            .instance("plane_inst")
            .build()
    };
    let cases = [
        (
            "rampShader",
            r#"shader "top" "maya_rampshader" ("colorInput" 0, "diffuse" 0, "translucence" 1,
    "color" [ { "color_Position" 0.5, "color_Color" 0 0 0, "color_Interp" 1 },
              { "color_Position" 1, "color_Color" 0.8 0.6 0.4, "color_Interp" 1 } ])"#,
        ),
        (
            "layeredShader",
            r#"shader "a" "maya_lambert" ("color" 0.9 0.2 0.1, "diffuse" 0.8, "transparency" 0.6 0.6 0.6)
shader "b" "adskMayaLambert" ("color" 0.1 0.5 0.9, "diffuse" 0.7)
shader "top" "maya_layeredshader" ("inputs" [
    { "color" = "a.outColor", "transparency" = "a.outTransparency" },
    { "color" = "b.outColor", "transparency" = "b.outTransparency" } ])"#,
        ),
        (
            "marble",
            r#"shader "mb" "maya_marble" ("fillerColor" 0.9 0.85 0.8, "veinColor" 0.2 0.25 0.3,
    "placementMatrix" 2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1)
shader "top" "maya_lambert" ("color" = "mb.outColor", "diffuse" 0.8)"#,
        ),
    ];
    for (what, materials) in cases {
        let (cm, pm) = both_engines(&scene(materials));
        println!("{what}: classic {cm:?}, path {pm:?}");
        for i in 0..3 {
            assert!(cm[i] > 0.02, "{what}: classic mean {cm:?}");
            assert!((pm[i] / cm[i] - 1.0).abs() < 0.02, "{what}: path {pm:?} vs classic {cm:?}");
        }
    }
}

#[test]
fn a_sphere_volume_light_lights_the_plane_by_its_falloff_in_both_engines() {
    // A sphere volume light of radius 3 (its instance scales the unit sphere) centred 1
    // above a lambert plane, colorRange black on the boundary to white at the centre: a
    // point at distance r from the centre receives I·(1 − r/3), at an angle whose cosine
    // is 1/r, so a pixel shows c·d·I·(1 − r/3)/r. Seen from 4 above; both engines are
    // checked against the formula at the pixel centres (within 2 % of the peak: a
    // pixel averages the smooth falloff over its footprint).
    let text = SceneText::maya_down("samples 0 2 filter box 1 1", 1.2, 24, 4.0)
        .light(
            "vol",
            r#""maya_volumelight" ("color" 1 0.9 0.8, "intensity" 2, "lightShape" 1, "colorRange" [
    { "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 },
    { "colorRange_Position" 1, "colorRange_Color" 1 1 1, "colorRange_Interp" 1 } ]) origin 0 0 0"#,
            Some("0.33333333 0 0 0  0 0.33333333 0 0  0 0 0.33333333 0  0 -0.33333333 0 1"),
        )
        .text(&lambert_plane(0.8, 5))
        .instance("plane_inst")
        .build();
    let l = load(&mi::parse_str("volume.mi", &text), Vec::new(), None);
    let world = path_world(&l);
    assert_eq!(world.lights.len(), 1, "the volume light is translated for the path engine");
    let accel = render::accel::build(&world, render::Backend::Rust);
    let settings = render::Settings { engine: render::EngineKind::Path, spp: Some(16), ..render::Settings::default() };
    let (film, _) =
        render::render(&world, accel.as_ref(), Some(&l.shading), &settings, &AtomicBool::new(false), &|_| {});
    let path = film.rgba();
    let (_, _, classic) = render_classic(&l, 4);
    let albedo = [0.6 * 0.8, 0.5 * 0.8, 0.4 * 0.8];
    let tint = [1.0, 0.9, 0.8];
    let peak = albedo[0] * 2.0; // c·d·I bounds every pixel
    for (i, (c, p)) in classic.iter().zip(&path).enumerate() {
        let (col, row) = ((i % 24) as f32, (i / 24) as f32);
        let x = ((col + 0.5) / 24.0 - 0.5) * 1.2 * 4.0;
        let z = ((row + 0.5) / 24.0 - 0.5) * 1.2 * 4.0;
        let r = (x * x + z * z + 1.0).sqrt();
        let falloff = (1.0 - r / 3.0).max(0.0) / r;
        for ch in 0..3 {
            let want = albedo[ch] * tint[ch] * 2.0 * falloff;
            assert!((c[ch] - want).abs() < 0.02 * peak, "classic pixel {i} channel {ch}: {} vs {want}", c[ch]);
            assert!((p[ch] - want).abs() < 0.02 * peak, "path pixel {i} channel {ch}: {} vs {want}", p[ch]);
        }
    }
}

/// A plane 4 below the camera lit straight down by a directional light of intensity 1,
/// seen through an aperture of 1.2 at `resolution`² pixels, with the shader lines
/// `materials` defining "top" (the plane's material) and the camera's extra `outputs`.
fn lit_plane(materials: &str, outputs: &str, resolution: u32) -> String {
    SceneText::maya_down("samples 0 0 filter box 1 1", 1.2, resolution, 4.0)
        .camera(&format!("{outputs} focal 1 aperture 1.2 aspect 1"))
        .light("sun", r#""maya_directionallight" ("intensity" 1) direction 0 -1 0"#, None)
        .text(materials)
        .text(TOP_MATERIAL)
        .text(UV_PLANE)
        .instance("plane_inst")
        .build()
}

/// The second moments (Σ I·dx², Σ I·dy²) of the image's red channel about its
/// brightness-weighted centre, in pixels²: the spread of a highlight across and down.
fn second_moments(px: &[[f32; 4]], width: usize) -> (f32, f32) {
    let total: f32 = px.iter().map(|p| p[0]).sum();
    let (mut cx, mut cy) = (0.0, 0.0);
    for (i, p) in px.iter().enumerate() {
        cx += p[0] * (i % width) as f32 / total;
        cy += p[0] * (i / width) as f32 / total;
    }
    let (mut mxx, mut myy) = (0.0, 0.0);
    for (i, p) in px.iter().enumerate() {
        mxx += p[0] * ((i % width) as f32 - cx).powi(2) / total;
        myy += p[0] * ((i / width) as f32 - cy).powi(2) / total;
    }
    (mxx, myy)
}

#[test]
fn the_anisotropic_highlight_is_stretched_across_the_grooves_in_both_engines() {
    // A black anisotropic plane (only its highlight shows) with grooves along U (world x,
    // image columns) at angle 0 and along V (image rows) at angle π/2; spreadX 13 >
    // spreadY 3 makes the highlight narrow along the grooves and long across them. Seen
    // from above with the light straight down, the highlight is where the half vector
    // meets the normal: its second moments across and down the image follow the grooves
    // in both engines (the long axis at least 1.5× the short one), and the two engines'
    // image means agree within 10 % (the path engine's lobe is GGX, the classic one
    // Maya's Gaussian of the same widths; both are lit by the same light).
    let material = |angle: f32| {
        format!(
            r#"shader "top" "maya_anisotropic" ("color" 0 0 0, "diffuse" 0, "angle" {angle},
    "roughness" 0.5, "spreadX" 13, "spreadY" 3, "fresnelRefractiveIndex" 6, "specularColor" 0.5 0.5 0.5)"#
        )
    };
    let n = 32;
    let mut means = Vec::new();
    for (angle, grooves_across) in [(0.0, true), (std::f32::consts::FRAC_PI_2, false)] {
        let l = load(&mi::parse_str("aniso.mi", &lit_plane(&material(angle), "", n)), Vec::new(), None);
        let (_, _, classic) = render_classic(&l, 1);
        let world = path_world(&l);
        let accel = render::accel::build(&world, render::Backend::Rust);
        let settings =
            render::Settings { engine: render::EngineKind::Path, spp: Some(64), ..render::Settings::default() };
        let (film, _) =
            render::render(&world, accel.as_ref(), Some(&l.shading), &settings, &AtomicBool::new(false), &|_| {});
        let path = film.rgba();
        for (engine, px) in [("classic", &classic), ("path", &path)] {
            let (across, down) = second_moments(px, n as usize);
            println!("angle {angle}: {engine} moments across {across:.2}, down {down:.2}, mean {:?}", summary(px).0);
            // Grooves along the columns (x): narrow across, long down the image.
            let (long, short) = if grooves_across { (down, across) } else { (across, down) };
            assert!(long > 1.5 * short, "{engine}, angle {angle}: long {long} vs short {short}");
        }
        means.push((summary(&classic).0[0], summary(&path).0[0]));
    }
    for (c, p) in means {
        assert!(c > 1e-3, "classic mean {c}");
        assert!((p / c - 1.0).abs() < 0.1, "path mean {p} vs classic {c}");
    }
}

/// Renders `text` with the classic engine at 1 sample per pixel and runs the camera's
/// output shaders: the film before and after them.
fn classic_with_outputs(text: &str) -> (render::film::Film, render::film::Film) {
    let l = load(&mi::parse_str("glow.mi", text), Vec::new(), None);
    let world = render::World::from_scene_shaded(&l.scene, Some(&l.shading));
    let accel = render::accel::build(&world, render::Backend::Rust);
    let settings =
        render::Settings { engine: render::EngineKind::Classic, spp: Some(1), ..render::Settings::default() };
    let (film, _) =
        render::render(&world, accel.as_ref(), Some(&l.shading), &settings, &AtomicBool::new(false), &|_| {});
    let mut after = film.clone();
    let warnings = render::output_shaders::run(&mut after, &l.scene.camera, &l.scene.library);
    assert!(warnings.is_empty(), "{warnings:?}");
    (film, after)
}

#[test]
fn a_glowing_material_brightens_its_neighbourhood_and_a_plain_one_does_not() {
    // Two lambert squares (colour 0.6, 8 pixels wide) on a dark plane under a light
    // straight down; the left one has glowIntensity 0.5. The camera's shader glow spreads
    // the materials' glow buffer: it holds 0.6 × 0.5 = 0.3 on the glowing square and 0
    // elsewhere; the glow adds exactly the buffer's sum (intensity 1, white, no auto
    // exposure) around the left square, and nothing around the right one.
    let materials = r#"shader "dark" "maya_lambert" ("color" 0.1 0.1 0.1, "diffuse" 1)
shader "glowing" "maya_lambert" ("color" 0.6 0.6 0.6, "diffuse" 1, "glowIntensity" 0.5)
shader "plain" "maya_lambert" ("color" 0.6 0.6 0.6, "diffuse" 1)
material "mg" opaque "maya_shadingengine" ("surfaceShader" = "glowing.outColor") end material
material "mp" opaque "maya_shadingengine" ("surfaceShader" = "plain.outColor") end material
object "squares" group -1.4 0.01 0.4  -0.6 0.01 0.4  -0.6 0.01 -0.4  -1.4 0.01 -0.4
    0.6 0.01 0.4  1.4 0.01 0.4  1.4 0.01 -0.4  0.6 0.01 -0.4
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 c "mg" 0 1 2 3 c "mp" 4 5 6 7 end group end object
instance "squares_inst" "squares" end instance"#;
    let text = lit_plane(
        &format!("{materials}\nshader \"top\" \"maya_lambert\" (\"color\" 0.1 0.1 0.1, \"diffuse\" 1)"),
        r#"output "+rgba" "maya_shaderglow" ("glowSpread" 0.1, "autoExposure" off)"#,
        48,
    )
    .replace(r#""sun_inst" "plane_inst""#, r#""sun_inst" "plane_inst" "squares_inst""#);
    let (before, after) = classic_with_outputs(&text);
    let buffer = before.user.iter().find(|b| b.name == maya::glow::BUFFER).expect("the materials' glow buffer");
    let (w, h) = (before.width as usize, before.height as usize);
    let (b, a) = (before.rgba(), after.rgba());
    // The buffer: 0.3 where the left square is seen, 0 elsewhere; at least 7×7 pixels.
    let glowing: Vec<usize> = (0..w * h).filter(|&i| buffer.data[i][0] > 0.0).collect();
    assert!(glowing.len() >= 49, "{} glowing pixels", glowing.len());
    for &i in &glowing {
        assert!((buffer.data[i][0] - 0.3).abs() < 1e-5, "pixel {i}: {:?}", buffer.data[i]);
        assert!((i % w) < w / 2, "pixel {i} glows but is not on the left square");
    }
    let source: f32 = glowing.iter().map(|&i| buffer.data[i][0]).sum();
    let added: f32 = a.iter().zip(&b).map(|(x, y)| x[0] - y[0]).sum();
    assert!((added - source).abs() < 1e-3 * source, "added {added} vs the buffer's {source}");
    // Neighbourhoods: the plane pixels within 3 pixels of each square (R = 4.8 pixels).
    let near = |left: bool| -> Vec<usize> {
        let square: Vec<(usize, usize)> = (0..w * h)
            .filter(|&i| (b[i][0] - 0.6).abs() < 1e-3 && ((i % w) < w / 2) == left)
            .map(|i| (i % w, i / w))
            .collect();
        (0..w * h)
            .filter(|&i| (b[i][0] - 0.1).abs() < 1e-3)
            .filter(|&i| {
                square.iter().any(|&(x, y)| {
                    (x as isize - (i % w) as isize).abs().max((y as isize - (i / w) as isize).abs()) <= 3
                })
            })
            .collect()
    };
    let (left, right) = (near(true), near(false));
    assert!(left.len() > 20 && right.len() > 20, "{} / {} neighbours", left.len(), right.len());
    let brightened = left.iter().filter(|&&i| a[i][0] > b[i][0] + 1e-4).count();
    assert_eq!(brightened, left.len(), "every pixel beside the glowing square brightens");
    for &i in &right {
        assert_eq!(a[i], b[i], "pixel {i} beside the plain square is unchanged");
    }
}

/// An orthographic camera looking down −Z at a plane of constant colour (0.8 0.5 0.3,
/// ambient only) 5 away, with the camera's volume `volume` and the shader lines `body`.
fn fogged_plane(body: &str) -> Vec<[f32; 4]> {
    let text = format!(
        r#"
$include "mayabase.mi"
$include "AdskShaderSDK.mi"
options "opt" filter box 1 1 samples 0 0 end options
{body}
camera "cam" focal infinity aperture 2 aspect 1 resolution 4 4 volume = "sampler" end camera
instance "cam_inst" "cam" end instance
material "plane_mtl" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 0.8 0.5 0.3 1, "diffuse" 0 0 0) end material
object "plane" group -4 -4 -5  4 -4 -5  4 4 -5  -4 4 -5  v 0 v 1 v 2 v 3 c "plane_mtl" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    );
    let l = load(&mi::parse_str("fog.mi", &text), Vec::new(), None);
    render_classic(&l, 1).2
}

#[test]
fn the_volume_sampler_composites_a_maya_volume_output_and_runs_a_mental_ray_volume() {
    // A node with Maya's output struct covers the segment: plane ⊙ T + outColor. Here a
    // surfaceShader of colour 0.1 0.2 0.9 and transparency 0.25 0.5 0.75, whose outColor
    // is its colour ⊙ (1 − T) (nothing lies behind the plane for its own transparency ray).
    let px = fogged_plane(
        r#"shader "vol" "maya_surfaceshader" ("outColor" 0.1 0.2 0.9, "outTransparency" 0.25 0.5 0.75)
shader "sampler" "adskMayaVolumeSampler" ("volumeShader" = "vol.outColor")"#,
    );
    let want = [0.8 * 0.25 + 0.1 * 0.75, 0.5 * 0.5 + 0.2 * 0.5, 0.3 * 0.75 + 0.9 * 0.25];
    for p in &px {
        for k in 0..3 {
            assert!((p[k] - want[k]).abs() < 1e-5, "{p:?} vs {want:?}");
        }
    }
    // mib_volume connected directly: the sampler is that fog (share 5/20 of its colour).
    let px = fogged_plane(
        r#"shader "fog" "mib_volume" ("color" 0.2 0.4 0.6 1, "max" 20)
shader "sampler" "maya_volumesampler" ("volumeShader" = "fog")"#,
    );
    let f = 0.25;
    let want = [0.8 * (1.0 - f) + 0.2 * f, 0.5 * (1.0 - f) + 0.4 * f, 0.3 * (1.0 - f) + 0.6 * f];
    for p in &px {
        for k in 0..3 {
            assert!((p[k] - want[k]).abs() < 1e-5, "{p:?} vs {want:?}");
        }
    }
}

/// A camera 4 above a plane showing the unlit colour 0.8 (a surfaceShader), looking
/// straight down through the camera volume `volume` with a field of view of 0.01 (every
/// ray crosses 4 units within 2e-5 of it), at 4×4 pixels, optionally a point light of
/// intensity 2 (no decay, no shadows) 1 beside the middle of the rays: the pixels.
fn through_fog(volume: &str, light: bool) -> Vec<[f32; 4]> {
    let mut scene = SceneText::maya_down("samples 0 0 filter box 1 1", 0.01, 4, 4.0)
        .camera(&format!("volume {volume} focal 1 aperture 0.01 aspect 1"))
        .text(
            r#"shader "flat" "maya_surfaceshader" ("outColor" 0.8 0.8 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material
object "plane" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance"#,
        )
        .instance("plane_inst");
    if light {
        let lamp = r#""maya_pointlight" ("intensity" 2, "decayRate" 0) origin 0 0 0"#;
        scene = scene.light("lamp", lamp, Some(&translate(-1.0, -2.0, 0.0)));
    }
    let text = scene.build();
    let l = load(&mi::parse_str("fog.mi", &text), Vec::new(), None);
    render_classic(&l, 1).2
}

/// Maya's fogs as the camera's volume, against their formulas (1e-3; see `maya::fog`):
/// a black light fog without colour-based transparency leaves the plane's 0.8 times the
/// transmittance exp(−density · 4) with fast drop-off, exp(−density) without; a coloured
/// one covers each channel by α·c; lit by a point light 1 from the rays' middle it adds
/// α·c·I; environment fog covers α = 4 / saturationDistance, with useHeight only the 2
/// units between heights 1 and 3.
#[test]
fn maya_fogs_cover_and_light_what_lies_behind_by_their_formulas() {
    let d = 0.2f32;
    let light_fog = |params: &str| format!(r#""maya_lightfog" ("density" {d}, {params})"#);
    let alpha = |through: f32| 1.0 - (-through).exp();
    let cases: Vec<(String, bool, [f32; 3])> = vec![
        (
            light_fog(r#""color" 0 0 0, "colorBasedTransparency" off, "fastDropOff" on"#),
            false,
            [0.8 * (-d * 4.0).exp(); 3],
        ),
        (light_fog(r#""color" 0 0 0, "colorBasedTransparency" off"#), false, [0.8 * (-d).exp(); 3]),
        (
            light_fog(r#""color" 1 0.5 0, "fastDropOff" on"#),
            false,
            [0.8 * (1.0 - alpha(d * 4.0)), 0.8 * (1.0 - 0.5 * alpha(d * 4.0)), 0.8],
        ),
        (
            light_fog(r#""color" 1 0.5 0, "fastDropOff" on"#),
            true,
            [
                0.8 * (1.0 - alpha(d * 4.0)) + alpha(d * 4.0) * 2.0,
                0.8 * (1.0 - 0.5 * alpha(d * 4.0)) + alpha(d * 4.0) * 0.5 * 2.0,
                0.8,
            ],
        ),
        (
            r#""maya_envfog" ("color" 0.2 0.4 0.6, "saturationDistance" 10)"#.to_string(),
            false,
            [0.8 * (1.0 - 0.4 * 0.2) + 0.4 * 0.2, 0.8 * (1.0 - 0.4 * 0.4) + 0.4 * 0.4, 0.8 * (1.0 - 0.4 * 0.6) + 0.4 * 0.6],
        ),
        (
            r#""maya_envfog" ("color" 0 0 0, "colorBasedTransparency" off, "saturationDistance" 10, "useHeight" on, "minHeight" 1, "maxHeight" 3)"#.to_string(),
            false,
            [0.8 * (1.0 - 0.2); 3],
        ),
    ];
    for (volume, lit, want) in &cases {
        for p in through_fog(volume, *lit) {
            for c in 0..3 {
                assert!((p[c] - want[c]).abs() < 1e-3, "{volume} (lit {lit}): pixel {p:?}, want {want:?}");
            }
        }
    }
}
