//! Maya test support: small Maya scenes (no key light) compiled with the Maya library's
//! implementations counted, tracers with one occluder or a half-space of them, and the
//! shading point the Maya tests use. Rays that miss use [`super::Empty`].

use glam::Vec3A;
use shader::{Color, Ctx, NodeId, RayType, Shading, State, Tracer, Value, VertexData};

use super::{build_shading, scene_text, CAMERA};

/// A compiled test scene.
pub struct Compiled {
    /// The shading.
    pub shading: Shading,
    /// Every diagnostic of parsing, building and compiling, rendered.
    pub messages: Vec<String>,
    /// Nodes the Maya library implements.
    pub attached: usize,
}

impl Compiled {
    /// The surface shader of material `name`.
    pub fn material(&self, name: &str) -> NodeId {
        let m = self.shading.materials.iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no material {name}"));
        m.surface.expect("a surface shader")
    }

    /// The index of material `name`.
    pub fn material_index(&self, name: &str) -> u32 {
        self.shading.materials.iter().position(|m| m.name == name).expect("material") as u32
    }

    /// The index of the (first) instance with its own light list.
    pub fn linked_instance(&self) -> u32 {
        self.shading.instance_lights.iter().position(Option::is_some).expect("an instance with a light list") as u32
    }

    /// The index of the first instance without a light list of its own (all lights).
    pub fn unlinked_instance(&self) -> u32 {
        self.shading.instance_lights.iter().position(Option::is_none).expect("an instance without a light list") as u32
    }
}

/// Compiles `body` (lights with their instances, shaders, materials) after the header;
/// each material of `materials` goes on one triangle (instance `obj{i}_inst`; the first
/// one has `instance_extra` in its instance block) so that the scene uses it. Every `instance`
/// of `body` joins the root group.
pub fn compile(options: &str, body: &str, materials: &[&str], instance_extra: &str) -> Compiled {
    compile_with_camera("", options, body, materials, instance_extra)
}

/// [`compile`] with extra statements in the camera (an environment shader).
pub fn compile_with_camera(
    camera: &str,
    options: &str,
    body: &str,
    materials: &[&str],
    instance_extra: &str,
) -> Compiled {
    let header = CAMERA.replace("{OPTIONS}", options).replace("{CAMERA}", camera);
    let (shading, messages) = build_shading(&scene_text(&header, &[], body, materials, instance_extra));
    // Nodes implemented by the Maya library (found through the registry).
    let attached = shading
        .graph
        .nodes
        .iter()
        .filter(|n| n.imp.is_some_and(|i| maya::REGISTRY.iter().any(|m| std::ptr::eq(*m, i))))
        .count();
    Compiled { shading, messages, attached }
}

/// A tracer whose every shadow ray passes one occluder of material `material` (at the
/// middle of the ray); other rays miss.
pub struct Occluder {
    /// The occluder's material index.
    pub material: u32,
}

impl Tracer for Occluder {
    fn intersect(&self, _ray: &mut State, _max_dist: f32) -> bool {
        false
    }

    fn shadow_hits(&self, ray: &State, max_dist: f32, visit: &mut dyn FnMut(&State) -> bool) {
        let d = if max_dist.is_finite() { 0.5 * max_dist } else { 1.0 };
        let mut hit = ray.clone();
        hit.ray_type = RayType::Shadow;
        hit.point = ray.org + ray.dir * d;
        hit.dist = d;
        hit.normal = -ray.dir;
        hit.normal_geom = -ray.dir;
        hit.material = Some(self.material);
        visit(&hit);
    }

    fn triangle(&self, _hit: &State, _data: VertexData) -> Option<[Vec3A; 3]> {
        None
    }

    fn fb_put(&self, _buffer: u32, _value: Color) -> bool {
        false
    }
}

/// A tracer whose shadow rays are blocked (by an occluder of material `material`) when
/// they travel towards +x, and pass otherwise: half of a light spread symmetrically about
/// the y axis is hidden.
pub struct HalfSpace {
    /// The occluder's material index.
    pub material: u32,
}

impl Tracer for HalfSpace {
    fn intersect(&self, _ray: &mut State, _max_dist: f32) -> bool {
        false
    }

    fn shadow_hits(&self, ray: &State, max_dist: f32, visit: &mut dyn FnMut(&State) -> bool) {
        if ray.dir.x > 0.0 {
            Occluder { material: self.material }.shadow_hits(ray, max_dist, visit);
        }
    }

    fn triangle(&self, _hit: &State, _data: VertexData) -> Option<[Vec3A; 3]> {
        None
    }

    fn fb_put(&self, _buffer: u32, _value: Color) -> bool {
        false
    }
}

/// A shading point at the origin on a surface of normal +y, seen from straight above,
/// with texture coordinate `uv` and dP/du = +x, dP/dv = −z.
pub fn point(uv: [f32; 2]) -> State {
    let dir = -Vec3A::Y;
    let mut s = State {
        ray_type: RayType::Eye,
        org: -dir,
        dir,
        dist: 1.0,
        point: Vec3A::ZERO,
        shadow_point: Vec3A::ZERO,
        normal: Vec3A::Y,
        normal_geom: Vec3A::Y,
        dot_nd: -1.0,
        ior_in: 1.0,
        ior: 1.0,
        child_dist: f32::INFINITY,
        ..State::default()
    };
    s.tex_list[0] = Vec3A::new(uv[0], uv[1], 0.0);
    s.tex_count = 1;
    s.derivs = [Vec3A::X, -Vec3A::Z];
    s
}

/// Runs the shader list at `node` on `state` and returns its result.
pub fn run(c: &Compiled, tracer: &dyn Tracer, node: NodeId, state: State) -> Value {
    run_in(&c.shading, tracer, node, state)
}

/// [`run`] in any compiled shading.
pub fn run_in(shading: &Shading, tracer: &dyn Tracer, node: NodeId, state: State) -> Value {
    let mut ctx = Ctx::new(shading, tracer, state);
    let mut out = Value::Color(Color::ZERO);
    ctx.run_list(node, &mut out);
    out
}

/// Asserts two colours agree within `tol` per RGB component.
pub fn assert_rgb(got: Color, want: [f32; 3], tol: f32) {
    let g = [got.x, got.y, got.z];
    assert!(g.iter().zip(want).all(|(a, b)| (a - b).abs() <= tol), "got {got}, want {want:?} (tol {tol})");
}
