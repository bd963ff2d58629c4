//! The camera's output shaders, run on the finished film in the order the `output`
//! statements give them (mental ray runs output shaders after rendering, before the files
//! are written). Those mira knows: Maya's shader glow (`maya::glow`), a post pass that
//! changes the colour buffer; the exposure and colour-management shaders
//! (`mia_exposure_*`, `maya_colormgt`), which the display images' tone mapping applies
//! (`tonemap`). Any other output shader is not run, with a warning naming it.

use scene::camera::{Camera, Output};

use crate::film::Film;

/// Output shaders the tone mapping applies when display images are written.
const TONE_MAPPING: &[&str] =
    &["mia_exposure_simple", "mia_exposure_photographic", "maya_colormgt", "adskMayaColorMgt"];

/// Runs the output shaders of `camera` on `film`; returns a warning for each shader it
/// cannot run.
pub fn run(film: &mut Film, camera: &Camera, lib: &scene::Library) -> Vec<String> {
    let mut warnings = Vec::new();
    for out in &camera.outputs {
        let Output::Shader { types, shaders } = out else { continue };
        for item in &shaders.0 {
            let Some((name, params)) = material::first_call(std::slice::from_ref(item), lib) else {
                warnings.push("an output shader that names no shader is not run".to_string());
                continue;
            };
            if maya::glow::is_glow(name) {
                glow(film, types, &maya::glow::Glow::from_params(params));
            } else if !TONE_MAPPING.contains(&name) {
                warnings.push(format!("output shader '{name}' is not run (mira has no implementation of it)"));
            }
        }
    }
    warnings
}

/// Whether `camera` runs a shader glow among its output shaders (then the world holds
/// the materials' glow buffer, [`maya::glow::BUFFER`]).
pub fn has_glow(camera: &Camera, lib: &scene::Library) -> bool {
    camera.outputs.iter().any(|out| match out {
        Output::Shader { shaders, .. } => shaders.0.iter().any(|item| {
            material::first_call(std::slice::from_ref(item), lib).is_some_and(|(n, _)| maya::glow::is_glow(n))
        }),
        _ => false,
    })
}

/// The user frame buffer Maya materials' glow goes to when `scene`'s camera runs a shader
/// glow (`None` without one), as an index into `user_buffers` ((name, data type) of the
/// world's user frame buffers): `fb<n>` when the options' state shader (`maya_state`,
/// `adskFrameBufferState`) names `frame buffer n` in its `glowColorBuffer` and the options
/// declare it, else [`maya::glow::BUFFER`], added to `user_buffers` when not there.
pub fn glow_buffer(scene: &scene::Scene, user_buffers: &mut Vec<(String, String)>) -> Option<u32> {
    if !has_glow(&scene.camera, &scene.library) {
        return None;
    }
    let named = scene
        .options
        .state
        .iter()
        .find_map(|item| {
            let (name, params) = material::first_call(std::slice::from_ref(item), &scene.library)?;
            maya::glow::is_state(name).then(|| maya::glow::color_buffer(params)).flatten()
        })
        .map(|n| format!("fb{n}"))
        .filter(|name| user_buffers.iter().any(|(b, _)| b == name));
    let name = named.unwrap_or_else(|| maya::glow::BUFFER.to_string());
    let index = match user_buffers.iter().position(|(b, _)| *b == name) {
        Some(i) => i,
        None => {
            user_buffers.push((name, "rgba_fp".to_string()));
            user_buffers.len() - 1
        }
    };
    Some(index as u32)
}

/// Applies a shader glow: its source is the first user frame buffer among the output's
/// `types` that shaders wrote, else the materials' glow buffer ([`maya::glow::BUFFER`])
/// where a material glows, else the image's pixels brighter than white.
fn glow(film: &mut Film, types: &[String], glow: &maya::glow::Glow) {
    let named = types.iter().find_map(|t| {
        let name = t.trim().trim_start_matches(['+', '-']);
        film.user.iter().find(|b| b.name == name && b.writes.iter().any(|&n| n > 0))
    });
    // The materials' buffer holds zeros wherever nothing glows: a source only if some glow.
    let materials = || {
        film.user
            .iter()
            .find(|b| b.name == maya::glow::BUFFER && b.data.iter().any(|v| v[..3].iter().any(|&c| c > 0.0)))
    };
    let buffer: Option<Vec<[f32; 3]>> =
        named.or_else(materials).map(|b| b.data.iter().map(|v| [v[0], v[1], v[2]]).collect());
    let mut image = film.rgba();
    glow.apply(&mut image, buffer.as_deref(), film.width as usize, film.height as usize);
    film.set_rgba(&image);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scene of a 21×21 camera with `outputs`.
    fn scene(outputs: &str) -> scene::Scene {
        let text = format!(
            r#"
$include "mayabase.mi"
options "opt" end options
camera "cam" {outputs} focal 1 aperture 1 aspect 1 resolution 21 21 end camera
instance "cam_inst" "cam" end instance
instgroup "root" "cam_inst" end instgroup
render "root" "cam_inst" "opt"
"#
        );
        let parsed = mi::parse_str("t.mi", &text);
        assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
        scene::Scene::build(&parsed, 0, &mut Vec::new()).expect("a scene")
    }

    /// A grey 21×21 film with one pixel at 3 in red.
    fn film() -> Film {
        let mut film = Film::new(21, 21);
        let mut image = vec![[0.5f32, 0.5, 0.5, 1.0]; 21 * 21];
        image[10 * 21 + 10][0] = 3.0;
        film.set_rgba(&image);
        film
    }

    #[test]
    fn a_glow_output_shader_spreads_the_bright_pixel_and_nothing_else() {
        let sc =
            scene(r#"output "+rgba" "maya_shaderglow" ("glowIntensity" 0.5, "glowSpread" 0.2, "autoExposure" off)"#);
        let mut f = film();
        let before = f.rgba();
        assert!(run(&mut f, &sc.camera, &sc.library).is_empty());
        let after = f.rgba();
        // The excess over white (2) spread with intensity 0.5 adds 1 to the red channel.
        let added: f32 = after.iter().zip(&before).map(|(a, b)| a[0] - b[0]).sum();
        assert!((added - 1.0).abs() < 1e-4, "{added}");
        assert!(after.iter().zip(&before).all(|(a, b)| a[1] == b[1] && a[3] == b[3]));
        // Linear falloff over R = 0.2 × 21 = 4.2 pixels: zero at 5 pixels.
        assert!(after[10 * 21 + 11][0] > before[10 * 21 + 11][0]);
        assert_eq!(after[10 * 21 + 15][0], before[10 * 21 + 15][0]);
    }

    #[test]
    fn a_written_glow_buffer_is_the_source() {
        let sc = scene(r#"output "+rgba,fb0" "adskMayaShaderGlow" ("glowSpread" 0.2, "autoExposure" off)"#);
        let mut f = film();
        f.add_user_buffer("fb0", "rgba");
        f.user[0].put(10 * 21 + 10, [0.0, 0.0, 2.0, 1.0]);
        let before = f.rgba();
        run(&mut f, &sc.camera, &sc.library);
        let after = f.rgba();
        let blue: f32 = after.iter().zip(&before).map(|(a, b)| a[2] - b[2]).sum();
        let red: f32 = after.iter().zip(&before).map(|(a, b)| a[0] - b[0]).sum();
        assert!((blue - 2.0).abs() < 1e-4 && red == 0.0, "blue {blue}, red {red}: the buffer, not the image");
    }

    #[test]
    fn without_output_shaders_the_film_is_unchanged_and_unknown_ones_are_named() {
        let sc = scene(r#"output "+rgba" "png" "x.png""#);
        let mut f = film();
        let before = f.rgba();
        assert!(run(&mut f, &sc.camera, &sc.library).is_empty());
        assert_eq!(f.rgba(), before);
        let sc = scene(r#"output "+rgba" "my_denoiser" ("strength" 1)"#);
        let warnings = run(&mut f, &sc.camera, &sc.library);
        assert_eq!(f.rgba(), before);
        assert!(warnings.len() == 1 && warnings[0].contains("'my_denoiser'"), "{warnings:?}");
    }
}
