//! The shading context: lazy, cached evaluation of shader parameters (mental ray's
//! `mi_eval`) at one shading point.
//!
//! A [`Ctx`] lives for one shading point: the hit of one ray. Reading a parameter that is a
//! constant returns it; reading one connected to another shader runs that shader the first
//! time and returns its cached result afterwards, so a texture read by two parameters runs
//! once. Shaders that evaluate at offset positions (bump mapping) call [`Ctx::flush_cache`]
//! between evaluations. A shader that never reads a parameter never runs what is connected
//! to it. Rays traced from a shader get their own context (their own cache).

use glam::{Vec2, Vec3A};

use super::graph::{Node, NodeId, Slot};
use super::shading::Shading;
pub use super::site::hash;
use super::site::SitePairs;
use super::state::State;
use super::tracer::Tracer;
use super::value::{Color, Tag, Value};

/// Deepest chain of connections evaluated inside each other; deeper ones give zero. Graphs
/// with deeper chains are errors when they are built ([`super::graph::Builder::finish`]), so
/// this guard is never reached by a scene that rendered without errors.
const MAX_EVAL_DEPTH: u32 = super::graph::MAX_NESTING;

/// Counts kept per rendering thread.
#[derive(Clone, Copy, Debug, Default)]
pub struct ShadeCounts {
    /// Shader calls (cache misses).
    pub calls: u64,
    /// Parameter reads answered from the cache.
    pub cache_hits: u64,
}

/// The context of one shading point.
pub struct Ctx<'a> {
    shading: &'a Shading,
    /// The renderer's ray casting.
    pub tracer: &'a dyn Tracer,
    /// The shading point (shaders may change it, as mental ray shaders change `state`).
    pub state: State,
    cache: Vec<(NodeId, Value)>,
    eval_depth: u32,
    /// Sampling sites handed out so far at this point (each gets its own dimensions).
    site: u32,
    /// Calls and cache hits at this point.
    pub counts: ShadeCounts,
    /// When set, every shader run at this point (not in contexts of rays it traces) is
    /// appended: for tests and debugging.
    pub call_log: Option<Vec<NodeId>>,
    /// A light state's shadow query answered ahead by the light loop (see
    /// [`Ctx::trace_shadow`]).
    pub(crate) shadow_hint: Option<super::tracer::ShadowHint>,
    /// A shadow ray was asked for here without shadow shaders to run (any-hit query).
    pub(crate) shadow_queried: bool,
    /// A shadow ray walked the surfaces and media between the point and the light here
    /// (its light is attenuated by the media on the way; see [`super::volume`]).
    pub(crate) media_walked: bool,
}

impl<'a> Ctx<'a> {
    /// A context for shading `state` (always inlined: see [`crate::State::child`]).
    #[inline(always)]
    pub fn new(shading: &'a Shading, tracer: &'a dyn Tracer, state: State) -> Ctx<'a> {
        Ctx {
            shading,
            tracer,
            state,
            cache: Vec::new(),
            eval_depth: 0,
            site: 0,
            counts: ShadeCounts::default(),
            call_log: None,
            shadow_hint: None,
            shadow_queried: false,
            media_walked: false,
        }
    }

    /// The scene's shading data.
    pub fn shading(&self) -> &'a Shading {
        self.shading
    }

    /// The user data elements the hit instance's object carries (its `data` statements),
    /// in the order written.
    pub fn object_data(&self) -> impl Iterator<Item = &'a super::user_data::UserData> + 'a {
        let shading = self.shading;
        let indices = shading.instance_data.get(self.state.instance as usize).map_or(&[][..], Vec::as_slice);
        indices.iter().filter_map(move |&i| shading.data.get(i as usize))
    }

    /// The node `node`.
    pub fn node(&self, node: NodeId) -> &'a Node {
        &self.shading.graph.nodes[node as usize]
    }

    /// Forgets every cached shader result (mental ray's `mi_flush_cache`).
    pub fn flush_cache(&mut self) {
        self.cache.clear();
    }

    #[inline(always)]
    fn slot(&self, node: NodeId, i: usize) -> Option<&'a Slot> {
        self.shading.graph.nodes[node as usize].slots.get(i)
    }

    /// Evaluates parameter `i` of `node` (in its implementation's parameter order).
    pub fn eval(&mut self, node: NodeId, i: usize) -> Value {
        match self.slot(node, i) {
            Some(slot) => self.eval_slot(slot),
            None => Value::Null,
        }
    }

    fn eval_slot(&mut self, slot: &'a Slot) -> Value {
        match slot {
            Slot::Value(v) => v.clone(),
            Slot::Connect { node, member } => {
                let v = self.result(*node);
                match member {
                    Some(m) => v.member(m).cloned().unwrap_or(Value::Null),
                    None => v,
                }
            }
            Slot::Array(items) => Value::Array(items.iter().map(|s| self.eval_slot(s)).collect::<Vec<_>>().into()),
            Slot::Struct(members) => {
                Value::Struct(members.iter().map(|(n, s)| (n.clone(), self.eval_slot(s))).collect::<Vec<_>>().into())
            }
        }
    }

    /// The result of running `node` at this shading point (cached until flushed).
    pub fn result(&mut self, node: NodeId) -> Value {
        if let Some((_, v)) = self.cache.iter().find(|(n, _)| *n == node) {
            self.counts.cache_hits += 1;
            return v.clone();
        }
        let mut out = self.zero_result(node);
        self.call(node, &mut out);
        self.cache.push((node, out.clone()));
        out
    }

    /// The zero value of `node`'s result type.
    fn zero_result(&self, node: NodeId) -> Value {
        match &self.node(node).decl.ret {
            Some(ty) => super::graph::zero(ty),
            None => Value::Color(Color::ZERO),
        }
    }

    /// Runs one shader (not its list successors) on `result`; uncached.
    pub fn call(&mut self, node: NodeId, result: &mut Value) -> bool {
        let Some(imp) = self.node(node).imp else { return false };
        if self.eval_depth >= MAX_EVAL_DEPTH {
            return false;
        }
        self.counts.calls += 1;
        if let Some(log) = &mut self.call_log {
            log.push(node);
        }
        self.eval_depth += 1;
        let ok = (imp.run)(self, node, result);
        self.eval_depth -= 1;
        ok
    }

    /// Runs the shader list starting at `head`: every shader in order on the same result.
    /// Returns whether the last one succeeded.
    pub fn run_list(&mut self, head: NodeId, result: &mut Value) -> bool {
        let mut node = Some(head);
        let mut ok = false;
        let mut guard = 0;
        while let Some(n) = node {
            ok = self.call(n, result);
            node = self.node(n).next;
            guard += 1;
            if guard > 1024 {
                break;
            }
        }
        ok
    }

    /// Parameter `i` as a colour (always inlined, as are the other constant reads: a light
    /// shader reads its parameters once per light sample).
    #[inline(always)]
    pub fn color(&mut self, node: NodeId, i: usize) -> Color {
        match self.slot(node, i) {
            Some(Slot::Value(Value::Color(c))) => *c,
            Some(Slot::Value(v)) => v.color(),
            Some(s) => self.eval_slot(s).color(),
            None => Color::ZERO,
        }
    }

    /// Parameter `i` as a scalar.
    #[inline(always)]
    pub fn scalar(&mut self, node: NodeId, i: usize) -> f32 {
        match self.slot(node, i) {
            Some(Slot::Value(Value::Scalar(s))) => *s,
            Some(Slot::Value(v)) => v.scalar(),
            Some(s) => self.eval_slot(s).scalar(),
            None => 0.0,
        }
    }

    /// Parameter `i` as an integer.
    #[inline(always)]
    pub fn int(&mut self, node: NodeId, i: usize) -> i32 {
        match self.slot(node, i) {
            Some(Slot::Value(Value::Int(n))) => *n,
            Some(Slot::Value(v)) => v.int(),
            Some(s) => self.eval_slot(s).int(),
            None => 0,
        }
    }

    /// Parameter `i` as a boolean.
    #[inline(always)]
    pub fn bool(&mut self, node: NodeId, i: usize) -> bool {
        match self.slot(node, i) {
            Some(Slot::Value(Value::Bool(b))) => *b,
            Some(Slot::Value(v)) => v.bool(),
            Some(s) => self.eval_slot(s).bool(),
            None => false,
        }
    }

    /// Parameter `i` as a vector.
    #[inline]
    pub fn vector(&mut self, node: NodeId, i: usize) -> Vec3A {
        match self.slot(node, i) {
            Some(Slot::Value(v)) => v.vector(),
            Some(s) => self.eval_slot(s).vector(),
            None => Vec3A::ZERO,
        }
    }

    /// Parameter `i` as a tag (a texture, light, material, shader or data element).
    pub fn tag(&mut self, node: NodeId, i: usize) -> Option<Tag> {
        match self.slot(node, i) {
            Some(Slot::Value(v)) => v.tag(),
            // A texture parameter connected to a shader: the shader is the texture.
            Some(Slot::Connect { node: n, member: None }) => Some(Tag::Shader(*n)),
            Some(s) => self.eval_slot(s).tag(),
            None => None,
        }
    }

    /// Whether parameter `i` is connected to a shader (rather than a constant).
    pub fn is_connected(&self, node: NodeId, i: usize) -> bool {
        matches!(self.slot(node, i), Some(Slot::Connect { .. }))
    }

    /// Parameter `i` as an array of values.
    pub fn array(&mut self, node: NodeId, i: usize) -> Value {
        self.eval(node, i)
    }

    /// Looks up a colour texture (an image or a texture shader) at `coord` (mental ray's
    /// `mi_lookup_color_texture`); `None` if the tag is not a texture or the coordinate is
    /// outside it.
    pub fn lookup_color_texture(&mut self, tag: Tag, coord: Vec3A) -> Option<Color> {
        match tag {
            Tag::Texture(i) => {
                let tex = self.shading.textures.get(i as usize)?;
                let width = self.texture_footprint();
                tex.lookup(coord, width)
            }
            Tag::Shader(n) => {
                // A texture shader finds the coordinate in `state.tex` (mental ray's
                // `state->tex`). Its result is cached like any other: a shader looking a
                // texture up at several coordinates flushes the cache in between.
                let saved = self.state.tex;
                self.state.tex = coord;
                let out = self.result(n);
                self.state.tex = saved;
                Some(out.color())
            }
            _ => None,
        }
    }

    /// Looks up a scalar texture.
    pub fn lookup_scalar_texture(&mut self, tag: Tag, coord: Vec3A) -> Option<f32> {
        self.lookup_color_texture(tag, coord).map(|c| c.x)
    }

    /// The ray footprint at the point in texture-space units of the first texture space,
    /// for choosing a mip-map level (0: sharpest).
    fn texture_footprint(&self) -> f32 {
        let du = self.state.derivs[0].length();
        let dv = self.state.derivs[1].length();
        let scale = du.max(dv);
        if scale > 0.0 && self.state.footprint > 0.0 {
            self.state.footprint / scale
        } else {
            0.0
        }
    }

    /// Two sample numbers in [0,1)² for the `i`-th of `n` samples a shader takes at this
    /// point through `site` (its place among this point's sampling loops). Successive
    /// pixel samples continue the same low-discrepancy sequence. A loop taking many samples
    /// at one site gets the same numbers cheaper from [`Ctx::site_pairs`].
    pub fn sample2(&mut self, site: u32, i: u32, n: u32) -> Vec2 {
        self.site_pairs(site, n).pair(i)
    }

    /// The numbers of a loop of `n` samples at `site` from this point: its
    /// [`SitePairs::pair`]`(i)` is `sample2(site, i, n)`, bit for bit, with the hashes the
    /// loop shares computed once.
    pub fn site_pairs(&self, site: u32, n: u32) -> SitePairs {
        let s = &self.state;
        let depth = s.reflection_level + s.refraction_level * 7 + s.finalgather_level * 31;
        SitePairs::new(s.pixel, self.shading.seed, depth, s.sample_index, site, n)
    }

    /// A new sampling site for a shader's sampling loop at this point.
    pub fn next_site(&mut self) -> u32 {
        self.site += 1;
        self.site
    }

    /// Stores into a user frame buffer for the current eye sample.
    pub fn fb_put(&self, buffer: u32, value: Color) -> bool {
        self.tracer.fb_put(buffer, value)
    }

    /// The index of the user frame buffer named `name`, if the render has one.
    pub fn fb_named(&self, name: &str) -> Option<u32> {
        self.tracer.fb_named(name)
    }
}
