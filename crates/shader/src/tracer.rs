//! The contract between shading and the renderer's ray casting.
//!
//! Shading owns what mental ray's shader interface does with a ray (which shader runs at a
//! hit, depth limits, shadow shaders, light loops, final gathering; see [`super::Ctx`]);
//! the renderer owns the geometry. It implements this trait: cast a ray and describe what
//! it hit as a [`State`], walk the surfaces between two points for a shadow ray, and take
//! frame-buffer writes for the current eye sample.

use glam::Vec3A;

use super::state::State;
use super::value::Color;

/// Per-vertex data of a hit triangle that shaders may ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexData {
    /// Vertex positions, world space.
    Point,
    /// Vertex normals, world space (the geometric normal where there are none).
    Normal,
    /// Vertex motion vectors, world space.
    Motion,
    /// Vertex coordinates of texture space `k`.
    Texture(usize),
    /// Vertex user vector `k` (the `k`-th `u` of each vertex, as written: mental ray
    /// gives shaders user vectors untransformed).
    User(usize),
}

/// What a ray hit, for shading.
pub type Hit = State;

/// One shadow-ray query of [`Tracer::shadow_blocked`]: from `org` along unit `dir`
/// (world space) up to `max_dist`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowQuery {
    /// Where the ray starts (already offset from the surface).
    pub org: Vec3A,
    /// Unit direction towards the light.
    pub dir: Vec3A,
    /// How far the ray looks (scene units; infinite for directional lights).
    pub max_dist: f32,
}

/// A shadow query of a light sample, traced ahead by the light loop, with its answer: the
/// light shader's [`crate::Ctx::trace_shadow`] takes the answer when its ray is made from
/// the same inputs at this shutter time.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShadowHint {
    pub(crate) time: f32,
    pub(crate) blocked: bool,
    /// What the query traced ahead was made from: the light state's `shadow_point`, `normal_geom`,
    /// `-dir` (lanes x, y, z; `point_error` and `dist` in the `w` lanes of the first two).
    /// The same inputs give the same ray, so `trace_shadow` compares these instead of
    /// computing the ray's origin again.
    pub(crate) from: [glam::Vec4; 3],
}

/// Ray casting for shaders (implemented by the renderer, one per rendering thread).
pub trait Tracer {
    /// Casts the ray of `ray` (its `ray_type`, `org`, unit `dir`, levels and media set up
    /// by the caller) up to distance `max_dist`. On a hit, fills in the surface fields of
    /// `ray` (point, normals facing the ray, `inv_normal`, `dist`, texture spaces,
    /// derivatives, instance, label, material, transforms) and returns true. The instance
    /// flags decide what each ray type can see (`visible`, `reflection`, `refraction`,
    /// `transparency`, `finalgather`).
    fn intersect(&self, ray: &mut State, max_dist: f32) -> bool;

    /// Visits the surfaces a shadow ray from `ray.org` along `ray.dir` crosses before
    /// `max_dist`, nearest first, each described as a shadow-ray hit (as [`intersect`]
    /// fills it in, with `ray_type` [`super::RayType::Shadow`]); only instances that cast
    /// shadows are visited. `visit` returns false to stop.
    ///
    /// [`intersect`]: Tracer::intersect
    fn shadow_hits(&self, ray: &State, max_dist: f32, visit: &mut dyn FnMut(&State) -> bool);

    /// The surfaces [`shadow_hits`] visits, each as its distance from the one before (from
    /// `ray.org` for the first) and its material (scene index; `None` for none, and for a
    /// walk cut short, which counts as blocked), without the rest of a hit's state: what a
    /// shadow ray's walk through participating media needs. `visit` returns false to stop.
    /// A renderer answers it without describing each hit in full.
    ///
    /// [`shadow_hits`]: Tracer::shadow_hits
    fn boundary_hits(&self, ray: &State, max_dist: f32, visit: &mut dyn FnMut(f32, Option<u32>) -> bool) {
        self.shadow_hits(ray, max_dist, &mut |hit| visit(hit.dist, hit.material));
    }

    /// Whether a shadow ray from `org` along unit `dir` (world space) at shutter time
    /// `time` meets any surface that casts shadows before `max_dist`: whether
    /// [`shadow_hits`] would visit one. A renderer answers it with an any-hit query that
    /// stops at the first surface found, without finding the nearest or describing it.
    ///
    /// [`shadow_hits`]: Tracer::shadow_hits
    fn shadow_blocked(&self, org: Vec3A, dir: Vec3A, max_dist: f32, time: f32) -> bool {
        let ray = State { ray_type: super::RayType::Shadow, org, dir, time, ..State::default() };
        let mut any = false;
        self.shadow_hits(&ray, max_dist, &mut |_| {
            any = true;
            false
        });
        any
    }

    /// [`Tracer::shadow_blocked`] for each of `queries` at shutter time `time`, into
    /// `blocked` (as long as `queries`). The light loop asks for a light's samples from one
    /// point together, which a renderer may trace as a packet.
    fn shadow_blocked_batch(&self, queries: &[ShadowQuery], time: f32, blocked: &mut [bool]) {
        for (q, b) in queries.iter().zip(blocked) {
            *b = self.shadow_blocked(q.org, q.dir, q.max_dist, time);
        }
    }

    /// The three vertices' `data` of the triangle `hit` (a state [`intersect`] filled in)
    /// lies on; `None` if the geometry has no such data.
    ///
    /// [`intersect`]: Tracer::intersect
    fn triangle(&self, hit: &State, data: VertexData) -> Option<[Vec3A; 3]>;

    /// Stores `value` into user frame buffer `buffer` for the current eye sample
    /// (mental ray's `mi_fb_put`). Returns false if there is no such buffer.
    fn fb_put(&self, buffer: u32, value: Color) -> bool;

    /// The index of the user frame buffer named `name` for [`Tracer::fb_put`] (mental
    /// ray's named frame buffers); `None` if the render has none of that name.
    fn fb_named(&self, _name: &str) -> Option<u32> {
        None
    }

    /// The final gather interpolation cache of this render, if the renderer built one
    /// ([`super::fgcache`]); `compute_irradiance` then interpolates where it can.
    fn fg_cache(&self) -> Option<&super::fgcache::FgCache> {
        None
    }

    /// Where light `light` (its index in `Shading::lights`) has moved to at shutter time
    /// `time` (see `State::time`): the world → world displacement from where the light is
    /// at the shutter's opening, or `None` when the light does not move (motion blur off,
    /// or its instance has no motion). Shading places the light with it
    /// ([`super::light::ShadingLight::moved`]).
    fn light_motion(&self, light: u32, time: f32) -> Option<glam::Affine3A> {
        let _ = (light, time);
        None
    }

    /// The triangles of object light `light` (its index in `Shading::lights`) at shutter
    /// time `time` when they change shape while the shutter is open (their vertices'
    /// motion vectors, or instances of the emitting object moving differently; see
    /// [`super::light::DeformingMesh`]), before the light's own displacement
    /// ([`Tracer::light_motion`]) is applied; `None` when its shape stays as it is.
    fn light_mesh(&self, light: u32, time: f32) -> Option<super::light::MeshShape> {
        let _ = (light, time);
        None
    }

    /// The path engine's scattering of the surface `hit` (a state [`intersect`] filled
    /// in), for material shaders that shade a material through its compiled BSDF (mira's
    /// classic form of MDL module materials): the material's BSDF at the point, its shading
    /// frame and emission, evaluated from the state alone (a material that evaluates
    /// itself per hit; no shader graph). `None` where the renderer has no such material
    /// (the shader then falls back on its own parameters).
    ///
    /// [`intersect`]: Tracer::intersect
    fn surface_scatter(&self, hit: &State) -> Option<SurfaceScatter> {
        let _ = hit;
        None
    }
}

/// A material's scattering at one shading point, as [`Tracer::surface_scatter`] gives it.
#[derive(Clone, Debug)]
pub struct SurfaceScatter {
    /// The BSDF in the local frame of `frame` (its `eval` without the cosine).
    pub bsdf: bsdf::Bsdf,
    /// The shading frame (world space; +Z the shading normal, facing the ray).
    pub frame: bsdf::Frame,
    /// The reflectance of the BSDF's diffuse part (what final gathering's irradiance lights).
    pub diffuse: bsdf::Rgb,
    /// Emitted radiance (W·m⁻²·sr⁻¹ in scene units, the path engine's).
    pub emission: bsdf::Rgb,
}

/// A tracer over an empty scene: every ray misses and nothing is stored. Shaders run
/// outside rendering (a shutter shape function, a displacement shader at tessellation)
/// get it as their tracer.
pub struct NoScene;

impl Tracer for NoScene {
    fn intersect(&self, _: &mut State, _: f32) -> bool {
        false
    }
    fn shadow_hits(&self, _: &State, _: f32, _: &mut dyn FnMut(&State) -> bool) {}
    fn triangle(&self, _: &State, _: VertexData) -> Option<[Vec3A; 3]> {
        None
    }
    fn fb_put(&self, _: u32, _: Color) -> bool {
        false
    }
}
