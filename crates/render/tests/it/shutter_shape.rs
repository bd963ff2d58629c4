//! mental ray 3.7's `"shutter shape function"`: a shader named by the string option gives
//! the shutter's opening as a function of time, and sample times follow it. The shaders
//! here are registered by the test (no library shader depends on time): `test_shutter_ramp`
//! returns `State::time` itself, `test_shutter_fails` returns false.

use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use render::{Backend, EngineKind, Settings};
use shader::{Ctx, Library, NodeId, Registry, ShaderImpl, Shading, ShadingOptions, Value};

fn ramp(ctx: &mut Ctx, _: NodeId, out: &mut Value) -> bool {
    *out = Value::Scalar(ctx.state.time);
    true
}

static RAMP: ShaderImpl = ShaderImpl { name: "test_shutter_ramp", params: &[], run: ramp, ..ShaderImpl::PLAIN };
static FAILS: ShaderImpl =
    ShaderImpl { name: "test_shutter_fails", params: &[], run: |_, _, _| false, ..ShaderImpl::PLAIN };
static TEST_LIBRARY: Library = Library {
    name: "test",
    shaders: &[&RAMP, &FAILS],
    declarations: &[(
        "test.mi",
        "declare shader scalar \"test_shutter_ramp\" () end declare\n\
         declare shader scalar \"test_shutter_fails\" () end declare\n",
    )],
};

/// Image width (pixels) over x ∈ [−2, 2], and height.
const W: usize = 16;
const H: usize = 4;

/// A 16×4 orthographic view of x ∈ [−2, 2] and a white quad over x ∈ [−10, 0] that moves
/// +2 in x over the shutter; `options` go into the options block (line 4 of the text).
fn scene(options: &str) -> String {
    format!(
        r#"
shader "ramp" "test_shutter_ramp" ()
shader "fails" "test_shutter_fails" ()
options "opt" filter box 1 1 motion on shutter 0 1
    {options}
end options
camera "cam" focal infinity aperture 4 aspect 4 resolution {W} {H} end camera
instance "cam_inst" "cam" end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 1 1 1, "diffuse" 0 0 0) end material
object "quad" group
    -10 -10 -5  0 -10 -5  0 10 -5  -10 10 -5
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "quad_inst" "quad" material "m" motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1 end instance
instgroup "root" "cam_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The scene `text` compiled with the libraries mira has and the test's, its shutter
/// shape shader tabulated as `render::pipeline::build_world` does: the scene, its shading
/// and the messages rendered with file:line:col.
fn compile(text: &str) -> (scene::Scene, Shading, Vec<String>) {
    let parsed = mi::parse_str("t.mi", text);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let mut libraries = material::LIBRARIES.to_vec();
    libraries.push(&TEST_LIBRARY);
    let registry = Arc::new(Registry::new(&libraries));
    let (mut shading, shade_diags) = Shading::build(&scene, &ShadingOptions::default(), &registry);
    diags.extend(shade_diags);
    shader::shutter::tabulate_into(&mut shading, &scene.options, &mut diags);
    let messages = diags.iter().map(|d| d.render(&parsed.sources)).collect();
    (scene, shading, messages)
}

/// Each pixel column's alpha averaged over the rows, classic and path engines, 64 spp.
fn column_alphas(scene: &scene::Scene, shading: &Shading, engine: EngineKind) -> Vec<f32> {
    let world = render::World::from_scene_shaded(scene, Some(shading));
    let accel = render::accel::build(&world, Backend::default_available());
    let settings = Settings { engine, spp: Some(64), ..Settings::default() };
    let (film, _) = render::render(&world, accel.as_ref(), Some(shading), &settings, &AtomicBool::new(false), &|_| {});
    let a: Vec<f32> = film.rgba().iter().map(|p| p[3]).collect();
    (0..W).map(|i| (0..H).map(|y| a[y * W + i]).sum::<f32>() / H as f32).collect()
}

/// The centre of pixel column `i` (scene units).
fn column_x(i: usize) -> f32 {
    -2.0 + (i as f32 + 0.5) * 4.0 / W as f32
}

/// A shutter whose opening grows linearly with time (weight s, density 2s): sample times
/// have the CDF s², so the quad's edge (at x = 2s) covers x ∈ [0, 2] with probability
/// 1 − (x/2)². Each column within 0.03 at 64 spp, both engines; without the shape shader
/// (the box shutter) the profile would be 1 − x/2, 0.19 off at x = 1.
#[test]
fn a_shape_shader_weights_the_sample_times() {
    let (scene, shading, messages) = scene_and_shading(r#""shutter shape function" "ramp""#);
    assert!(messages.is_empty(), "{messages:?}");
    let weights = shading.shutter_weights.as_ref().expect("the shape is tabulated");
    assert_eq!(weights.len(), shader::shutter::TABLE_SIZE);
    assert!((weights[0] - 0.5 / 256.0).abs() < 1e-6 && (weights[255] - 255.5 / 256.0).abs() < 1e-6);
    for engine in [EngineKind::Classic, EngineKind::Path] {
        let alphas = column_alphas(&scene, &shading, engine);
        for (i, a) in alphas.iter().enumerate() {
            let x = column_x(i);
            let want = if x <= 0.0 { 1.0 } else { 1.0 - (x / 2.0).min(1.0).powi(2) };
            assert!((a - want).abs() < 0.03, "{engine:?} column {i} (x = {x}): {a} vs {want}");
        }
    }
}

fn scene_and_shading(options: &str) -> (scene::Scene, Shading, Vec<String>) {
    compile(&scene(options))
}

/// A name that is no shader, a shader that fails, and a value that is no name: a warning
/// at the string option's line (t.mi:5) says so, and the full open/close shape (here the
/// box: the linear ramp 1 − x/2) is used.
#[test]
fn an_unusable_shape_shader_warns_at_its_line_and_keeps_the_box() {
    for (option, why) in [
        (r#""shutter shape function" "nothing""#, "names 'nothing', which is no shader"),
        (r#""shutter shape function" "fails""#, "its shader failed"),
        (r#""shutter shape function" 3"#, "is not a shader's name"),
    ] {
        let (scene, shading, messages) = scene_and_shading(option);
        assert!(
            messages.iter().any(|m| m.contains("t.mi:5:") && m.contains("shutter shape function") && m.contains(why)),
            "{option}: {messages:?}"
        );
        assert!(shading.shutter_weights.is_none());
        let alphas = column_alphas(&scene, &shading, EngineKind::Classic);
        for (i, a) in alphas.iter().enumerate() {
            let x = column_x(i);
            let want = if x <= 0.0 { 1.0 } else { (1.0 - x / 2.0).max(0.0) };
            assert!((a - want).abs() < 0.03, "{option}: column {i}: {a} vs {want}");
        }
    }
}
