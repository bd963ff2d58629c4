//! Test support: compiling small scenes' shading and running material shaders at a
//! hand-made shading point with a tracer that has no geometry; [`maya`] adds what the
//! Maya tests use (a scene without the key light, occluding tracers, Maya's shading
//! point).

#![allow(dead_code)]

pub mod maya;

use std::cell::RefCell;

use glam::Vec3A;
use shader::{Color, Ctx, NodeId, RayType, Shading, ShadingOptions, State, Tracer, Value, VertexData};

/// The options, camera and camera instance of every test scene (a macro so that
/// [`HEADER`] can extend the literal).
macro_rules! camera_header {
    () => {
        r#"
options "opt" {OPTIONS} end options
camera "cam" focal 1 aperture 1 aspect 1 resolution 8 8 {CAMERA} end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
"#
    };
}

/// The options, camera and camera instance alone; `{OPTIONS}` and `{CAMERA}` take extra
/// statements.
pub const CAMERA: &str = camera_header!();

/// [`CAMERA`] and a light: `key`, a `mib_light_point` of colour (0.8, 0.6, 0.4) ten units
/// above the origin (instance `key_inst`).
pub const HEADER: &str = concat!(
    camera_header!(),
    r#"light "key" "mib_light_point" ("color" 0.8 0.6 0.4) origin 0 0 0 end light
instance "key_inst" "key" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -10 0 1 end instance
"#
);

/// A compiled test scene.
pub struct Compiled {
    /// The shading.
    pub shading: Shading,
    /// Every diagnostic of parsing, building and compiling, rendered.
    pub messages: Vec<String>,
}

impl Compiled {
    /// The surface shader of material `name`.
    pub fn material(&self, name: &str) -> NodeId {
        let m = self.shading.materials.iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no material {name}"));
        m.surface.expect("a surface shader")
    }

    /// The names of the nodes in a call log.
    pub fn names(&self, log: &[NodeId]) -> Vec<String> {
        log.iter().map(|&n| self.shading.graph.nodes[n as usize].name.to_string()).collect()
    }
}

/// Compiles `body` (shaders and materials) after [`HEADER`]; each material named in
/// `materials` is put on one triangle so that the scene uses it.
pub fn compile(body: &str, materials: &[&str]) -> Compiled {
    compile_with("", "", body, materials)
}

/// [`compile`] with extra statements in the options and the camera.
pub fn compile_with(options: &str, camera: &str, body: &str, materials: &[&str]) -> Compiled {
    let header = HEADER.replace("{OPTIONS}", options).replace("{CAMERA}", camera);
    let text = scene_text(&header, &["key_inst"], body, materials, "");
    let (shading, messages) = build_shading(&text);
    Compiled { shading, messages }
}

/// The text of a test scene: `header`, then `body`, then one triangle object per
/// material of `materials` (instance `obj{i}_inst`, the first with `instance_extra` in
/// its instance block), a root group of the camera, the `header_instances`, every
/// `instance` of `body` and the objects, and the render statement.
pub fn scene_text(
    header: &str,
    header_instances: &[&str],
    body: &str,
    materials: &[&str],
    instance_extra: &str,
) -> String {
    let mut text = format!("{header}{body}\n");
    let mut members: String = header_instances.iter().map(|n| format!(" \"{n}\"")).collect();
    members.extend(
        body.lines()
            .filter_map(|l| l.trim().strip_prefix("instance \"").and_then(|r| r.split('"').next()))
            .map(|n| format!(" \"{n}\"")),
    );
    for (i, m) in materials.iter().enumerate() {
        let instance_extra = if i == 0 { instance_extra } else { "" };
        text.push_str(&format!(
            "object \"obj{i}\" group 0 0 0 1 0 0 0 0 1 v 0 v 1 v 2 c \"{m}\" 0 1 2 end group end object\n\
             instance \"obj{i}_inst\" \"obj{i}\" {instance_extra} end instance\n"
        ));
        members.push_str(&format!(" \"obj{i}_inst\""));
    }
    text.push_str(&format!("instgroup \"root\" \"cam_inst\"{members} end instgroup\n"));
    text.push_str("render \"root\" \"cam_inst\" \"opt\"\n");
    text
}

/// Parses `text`, builds its scene and compiles its shading with every library mira has:
/// the shading and every diagnostic, rendered. Panics (with the text) if no scene results.
pub fn build_shading(text: &str) -> (Shading, Vec<String>) {
    let parsed = mi::parse_str("test.mi", text);
    let mut messages: Vec<String> = parsed.diagnostics.list.iter().map(|d| d.render(&parsed.sources)).collect();
    let mut diags = Vec::new();
    let Some(scene) = scene::Scene::build(&parsed, 0, &mut diags) else {
        let all: Vec<String> = diags.iter().map(|d| d.render(&parsed.sources)).collect();
        panic!("no scene:\n{}\n{}\n{text}", messages.join("\n"), all.join("\n"));
    };
    let (shading, shade_diags) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    diags.extend(shade_diags);
    messages.extend(diags.iter().map(|d| d.render(&parsed.sources)));
    (shading, messages)
}

/// A tracer without geometry: every ray misses (and is recorded), no shadows.
#[derive(Default)]
pub struct Empty {
    /// (ray type, direction) of every ray cast.
    pub rays: RefCell<Vec<(RayType, Vec3A)>>,
    /// Their origins.
    pub origins: RefCell<Vec<Vec3A>>,
}

impl Tracer for Empty {
    fn intersect(&self, ray: &mut State, _max_dist: f32) -> bool {
        self.rays.borrow_mut().push((ray.ray_type, ray.dir));
        self.origins.borrow_mut().push(ray.org);
        false
    }

    fn shadow_hits(&self, _ray: &State, _max_dist: f32, _visit: &mut dyn FnMut(&State) -> bool) {}

    fn triangle(&self, _hit: &State, _data: VertexData) -> Option<[Vec3A; 3]> {
        None
    }

    fn fb_put(&self, _buffer: u32, _value: Color) -> bool {
        false
    }
}

/// A shading point at the origin on a surface with normal `normal`, seen along `dir`.
pub fn point(normal: Vec3A, dir: Vec3A) -> State {
    let dir = dir.normalize();
    State {
        ray_type: RayType::Eye,
        org: -dir,
        dir,
        dist: 1.0,
        point: Vec3A::ZERO,
        shadow_point: Vec3A::ZERO,
        normal,
        normal_geom: normal,
        dot_nd: normal.dot(dir),
        ior_in: 1.0,
        ior: 1.0,
        child_dist: f32::INFINITY,
        ..State::default()
    }
}

/// Runs the shader list at `node` on `state`: the result and the shaders that ran.
pub fn run(c: &Compiled, tracer: &dyn Tracer, node: NodeId, state: State) -> (Value, Vec<NodeId>, State) {
    let mut ctx = Ctx::new(&c.shading, tracer, state);
    ctx.call_log = Some(Vec::new());
    let mut out = Value::Color(Color::ZERO);
    ctx.run_list(node, &mut out);
    (out, ctx.call_log.take().unwrap_or_default(), ctx.state)
}

/// Asserts two colours agree within `tol` per component.
pub fn assert_color(got: Color, want: [f32; 4], tol: f32) {
    let want = Color::from_array(want);
    assert!((got - want).abs().max_element() <= tol, "got {got}, want {want}");
}
