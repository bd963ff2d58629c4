//! The shader graph: every shader instance of a scene as a node whose parameters are
//! constants or connections to other nodes, compiled once from the syntax tree.
//!
//! - A node's parameters are stored in its declaration's order, each given value converted
//!   to the declared type; omitted parameters take the declaration's default, else zero
//!   (mental ray's rule). Unknown parameter names and values of the wrong type are warned
//!   about at the parameter.
//! - `= "s"` and `= "s.member"` become connections, evaluated lazily by
//!   [`crate::Ctx`]. Shader lists chain nodes through `next`.
//! - A phenomenon instance is expanded: its internal shaders become nodes whose
//!   `= interface "p"` parameters take the instance's value (or connection) for `p`, and the
//!   instance's node returns its `root`.
//! - Connection cycles are errors (reported once, the offending connection dropped).

use std::collections::HashMap;
use std::sync::Arc;

use glam::{Mat4, Vec3A, Vec4};
use mi::ast::{self, DeclItem, DeclKind, Item, Num, ParamType, ShaderItem, ShaderList};
use mi::{Diagnostic, Span};

use super::decl::{Decl, Decls};
use super::value::{Tag, Value};
use super::Implementation;

/// Index of a node.
pub type NodeId = u32;

/// One parameter of a node.
#[derive(Clone, Debug, PartialEq)]
pub enum Slot {
    /// A constant.
    Value(Value),
    /// The result (or one member of the result) of another node, evaluated on demand.
    Connect {
        /// The node.
        node: NodeId,
        /// The struct member selected with `"shader.member"`.
        member: Option<Arc<str>>,
    },
    /// An array whose elements may be connections.
    Array(Vec<Slot>),
    /// A struct whose members may be connections.
    Struct(Vec<(Arc<str>, Slot)>),
}

/// A shader instance.
#[derive(Clone, Debug)]
pub struct Node {
    /// Its name (the named shader's, or a generated one).
    pub name: Arc<str>,
    /// Its declaration.
    pub decl: Arc<Decl>,
    /// The code that runs it (`None`: not implemented; it returns nothing).
    pub imp: Option<Implementation>,
    /// Parameters in declaration order.
    pub slots: Vec<Slot>,
    /// The next shader of its shader list.
    pub next: Option<NodeId>,
    /// Where it was written.
    pub span: Span,
}

/// Names the graph resolves parameters against.
#[derive(Clone, Debug, Default)]
pub struct Names {
    /// Texture names.
    pub textures: HashMap<String, u32>,
    /// Light instance names (in the renderer's light order).
    pub lights: HashMap<String, u32>,
    /// Material names (in the scene's material order).
    pub materials: HashMap<String, u32>,
    /// Data element names.
    pub data: HashMap<String, u32>,
    /// Light profile names (in the library's order: `Shading::lightprofiles`).
    pub lightprofiles: HashMap<String, u32>,
}

/// The compiled shader network of a scene.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    /// All nodes.
    pub nodes: Vec<Node>,
    /// Named shaders: the head of each one's list.
    pub named: HashMap<String, NodeId>,
    /// The names parameters were resolved against.
    pub names: Names,
}

/// Most shader lists built inside one another (each connection to a named shader and each
/// phenomenon body is one level). Real shader networks nest a few dozen deep; the limit keeps
/// a hostile chain from exhausting the stack, here or when the shaders run.
pub const MAX_NESTING: u32 = 256;

/// Most nodes phenomenon expansion grows a graph to (a scene's own shaders are bounded by
/// its size; expansions inside expansions multiply).
pub const MAX_NODES: usize = 1 << 22;

/// Builds the graph.
pub struct Builder<'a> {
    decls: &'a Decls,
    shaders: &'a std::collections::BTreeMap<String, ast::ShaderDef>,
    graph: Graph,
    /// Named shaders being built (cycle detection).
    building: Vec<String>,
    /// Shader lists being built inside one another (connections, phenomenon bodies).
    depth: u32,
    /// The nesting limit was reported.
    too_deep: bool,
    /// The node limit was reported.
    too_many: bool,
    /// Phenomenon scopes: local shader names and interface values.
    scopes: Vec<Scope>,
    /// Problems found.
    pub diags: Vec<Diagnostic>,
    counter: u32,
}

#[derive(Default)]
struct Scope {
    local: HashMap<String, NodeId>,
    interface: HashMap<String, Slot>,
}

/// The nodes `slots` connect to (inside arrays and structs too).
fn connections(slots: &[Slot]) -> impl Iterator<Item = NodeId> + '_ {
    let mut stack: Vec<&Slot> = slots.iter().rev().collect();
    std::iter::from_fn(move || {
        while let Some(s) = stack.pop() {
            match s {
                Slot::Connect { node, .. } => return Some(*node),
                Slot::Array(items) => stack.extend(items.iter().rev()),
                Slot::Struct(members) => stack.extend(members.iter().rev().map(|(_, s)| s)),
                Slot::Value(_) => {}
            }
        }
        None
    })
}

/// For every node, the longest chain of connections evaluation follows from it: 1 for a
/// node connected to nothing, 1 + the deepest node it connects to otherwise (a phenomenon's
/// node connects to its root). Walked with an explicit stack, so that no graph can
/// overflow the call stack here; a connection back into the chain being walked (a cycle,
/// reported where the graph was built) is not followed.
pub fn chain_depths(graph: &Graph) -> Vec<usize> {
    const NEW: usize = 0;
    const OPEN: usize = usize::MAX;
    let n = graph.nodes.len();
    let mut depth = vec![NEW; n];
    for root in 0..n {
        if depth[root] != NEW {
            continue;
        }
        depth[root] = OPEN;
        let mut stack: Vec<(usize, Vec<NodeId>)> = vec![(root, connections(&graph.nodes[root].slots).collect())];
        while let Some((node, pending)) = stack.last_mut() {
            let node = *node;
            match pending.pop() {
                Some(next) => {
                    let next = next as usize;
                    if next < n && depth[next] == NEW {
                        depth[next] = OPEN;
                        let below = connections(&graph.nodes[next].slots).collect();
                        stack.push((next, below));
                    }
                }
                None => {
                    stack.pop();
                    let below = connections(&graph.nodes[node].slots)
                        .map(|c| c as usize)
                        .filter(|&c| c < n && depth[c] != OPEN)
                        .map(|c| depth[c])
                        .max()
                        .unwrap_or(0);
                    depth[node] = below + 1;
                }
            }
        }
    }
    depth
}

/// The zero value of a type (mental ray's omitted-parameter value).
pub fn zero(ty: &ParamType) -> Value {
    match ty {
        ParamType::Boolean => Value::Bool(false),
        ParamType::Integer => Value::Int(0),
        ParamType::Scalar => Value::Scalar(0.0),
        ParamType::Color => Value::Color(Vec4::ZERO),
        ParamType::Vector => Value::Vector(Vec3A::ZERO),
        ParamType::Transform => Value::Transform(Mat4::ZERO),
        ParamType::String => Value::Str(Arc::from("")),
        ParamType::Struct(fields) => Value::Struct(
            fields.iter().map(|f| (Arc::from(f.name.text.as_str()), zero(&f.ty))).collect::<Vec<_>>().into(),
        ),
        ParamType::Array(_) => Value::Array(Arc::from(Vec::new())),
        _ => Value::Null,
    }
}

fn nums(n: &[Num]) -> Vec<f32> {
    n.iter().map(|x| x.as_f64() as f32).collect()
}

impl<'a> Builder<'a> {
    /// A builder over a scene's declarations and named shaders.
    pub fn new(
        decls: &'a Decls,
        shaders: &'a std::collections::BTreeMap<String, ast::ShaderDef>,
        names: Names,
    ) -> Builder<'a> {
        Builder {
            decls,
            shaders,
            graph: Graph { names, ..Graph::default() },
            building: Vec::new(),
            depth: 0,
            too_deep: false,
            too_many: false,
            scopes: Vec::new(),
            diags: Vec::new(),
            counter: 0,
        }
    }

    /// A node for an internal shader (declared in mira's internal declarations) with the
    /// given constant parameters.
    pub fn internal(&mut self, decl_name: &str, params: &[(&str, Value)], span: Span) -> Option<NodeId> {
        let decl = self.decls.get(decl_name)?;
        let imp = self.decls.implementation(decl_name)?;
        let slots = imp
            .params
            .iter()
            .map(|name| Slot::Value(params.iter().find(|(n, _)| n == name).map_or(Value::Null, |(_, v)| v.clone())))
            .collect();
        let name = format!("{decl_name}#{}", self.graph.nodes.len());
        Some(self.push(Node { name: Arc::from(name.as_str()), decl, imp: Some(imp), slots, next: None, span }))
    }

    /// The finished graph, with an error at every shader that starts a chain of connections
    /// deeper than [`MAX_NESTING`] (see [`chain_depths`]): evaluating one recurses once per
    /// connection, and [`crate::Ctx`] stops at that depth.
    pub fn finish(mut self) -> (Graph, Vec<Diagnostic>) {
        let depths = chain_depths(&self.graph);
        let limit = MAX_NESTING as usize;
        // Report the over-deep chains at their first shaders: those no over-deep chain reaches.
        let mut reached = vec![false; depths.len()];
        for (j, n) in self.graph.nodes.iter().enumerate() {
            if depths[j] > limit {
                for c in connections(&n.slots) {
                    if let Some(r) = reached.get_mut(c as usize) {
                        *r = true;
                    }
                }
            }
        }
        let starts = depths.iter().enumerate().filter(|&(i, &d)| d > limit && !reached[i]);
        for (i, &d) in starts.take(8) {
            // The chain's next shaders: each the deepest connection of the one before.
            let mut names = Vec::new();
            let mut at = i;
            while names.len() < 3 {
                let next = connections(&self.graph.nodes[at].slots).max_by_key(|&c| depths.get(c as usize));
                match next {
                    Some(c) if (c as usize) < depths.len() && depths[c as usize] < depths[at] => {
                        at = c as usize;
                        names.push(format!("'{}'", self.graph.nodes[at].name));
                    }
                    _ => break,
                }
            }
            let node = &self.graph.nodes[i];
            self.diags.push(Diagnostic::error(
                node.span,
                format!(
                    "shader '{}' starts a chain of {d} connected shaders ({} -> …, counting those inside \
                     phenomena); mira evaluates chains of at most {MAX_NESTING}",
                    node.name,
                    names.join(" -> ")
                ),
            ));
        }
        (self.graph, self.diags)
    }

    /// Read access to the graph being built.
    pub fn graph(&self) -> &Graph {
        &self.graph
    }

    /// The head node of a named shader (built on first use).
    pub fn named(&mut self, name: &str, span: Span) -> Option<NodeId> {
        for scope in self.scopes.iter().rev() {
            if let Some(&n) = scope.local.get(name) {
                return Some(n);
            }
        }
        if let Some(&n) = self.graph.named.get(name) {
            return Some(n);
        }
        let def = self.shaders.get(name).or_else(|| self.shaders.get(name.trim_start_matches("::")))?;
        if self.building.iter().any(|b| b == name) {
            self.diags.push(Diagnostic::error(
                span,
                format!("shader connections form a cycle: {} -> {name}", self.building.join(" -> ")),
            ));
            return None;
        }
        self.building.push(name.to_string());
        // Phenomenon scopes do not reach into top-level named shaders.
        let saved = std::mem::take(&mut self.scopes);
        let head = self.list(&def.list, Some(name));
        self.scopes = saved;
        self.building.pop();
        if let Some(h) = head {
            self.graph.named.insert(name.to_string(), h);
        }
        head
    }

    /// Builds a shader list; returns its first node. `name` names the first node. Lists
    /// nested deeper than [`MAX_NESTING`] (a connection chain or phenomena inside phenomena)
    /// are an error and not built.
    pub fn list(&mut self, list: &ShaderList, name: Option<&str>) -> Option<NodeId> {
        if self.depth >= MAX_NESTING {
            if !self.too_deep {
                self.too_deep = true;
                let span = list.0.first().map_or(Span::default(), item_span);
                self.diags.push(Diagnostic::error(
                    span,
                    format!(
                        "shader connections nest more than {MAX_NESTING} deep here (through {}): the shaders below are not built",
                        self.building.last().map_or("a phenomenon", String::as_str)
                    ),
                ));
            }
            return None;
        }
        self.depth += 1;
        let head = self.list_items(list, name);
        self.depth -= 1;
        head
    }

    fn list_items(&mut self, list: &ShaderList, name: Option<&str>) -> Option<NodeId> {
        let mut head: Option<NodeId> = None;
        let mut prev: Option<NodeId> = None;
        for (k, item) in list.0.iter().enumerate() {
            let node = match item {
                ShaderItem::Call { decl, params, span } => {
                    let n = if k == 0 { name.map(str::to_string) } else { None };
                    self.call(&decl.text, params, *span, n)
                }
                ShaderItem::Ref(r) => {
                    let n = self.named(&r.text, r.span);
                    // A defined shader that is no node (an MDL material, an undeclared
                    // shader, already warned about) is not an unknown one.
                    let defined = self.shaders.contains_key(&r.text);
                    if n.is_none()
                        && !defined
                        && !self.diags.iter().any(|d| d.span.lo == r.span.lo && d.span.file == r.span.file)
                    {
                        self.diags.push(Diagnostic::error(r.span, format!("unknown shader '{}'", r.text)));
                    }
                    n
                }
                ShaderItem::Define { name: n, list, .. } => self.define(&n.text, list),
            };
            let Some(node) = node else { continue };
            match prev {
                // A named shader put in a list chains permanently (mental ray's rule); a
                // shader that already has a successor is copied instead so that both lists
                // stay as written.
                Some(p) => {
                    let node = if self.graph.nodes[node as usize].next.is_some() && item_is_ref(item) {
                        let mut copy = self.graph.nodes[node as usize].clone();
                        copy.next = None;
                        self.push(copy)
                    } else {
                        node
                    };
                    self.graph.nodes[p as usize].next = Some(node);
                    prev = Some(last_of(&self.graph, node));
                }
                None => {
                    head = Some(node);
                    prev = Some(last_of(&self.graph, node));
                }
            }
        }
        head
    }

    /// `= shader "name" list`: defines a named shader in place.
    fn define(&mut self, name: &str, list: &ShaderList) -> Option<NodeId> {
        let head = self.list(list, Some(name))?;
        match self.scopes.last_mut() {
            Some(scope) => {
                scope.local.insert(name.to_string(), head);
            }
            None => {
                self.graph.named.insert(name.to_string(), head);
            }
        }
        Some(head)
    }

    fn push(&mut self, node: Node) -> NodeId {
        self.graph.nodes.push(node);
        (self.graph.nodes.len() - 1) as NodeId
    }

    /// One shader call.
    fn call(&mut self, decl_name: &str, params: &[ast::Param], span: Span, name: Option<String>) -> Option<NodeId> {
        let name = name.unwrap_or_else(|| {
            self.counter += 1;
            format!("{decl_name}#{}", self.counter)
        });
        let Some(decl) = self.decls.get(decl_name) else {
            if decl_name.starts_with("mdl::") || decl_name == "unified_material" {
                // An MDL material or mira's unified material: translated to a BSDF by the
                // path engine, but the functions its parameters connect to are nodes,
                // evaluated per hit.
                self.connect_all(params);
            } else {
                self.diags
                    .push(Diagnostic::warning(span, format!("shader '{decl_name}' is not declared; it is ignored")));
            }
            return None;
        };
        let mut slots: Vec<Slot> = decl.params.iter().map(|p| Slot::Value(zero(&p.ty))).collect();
        for (i, p) in decl.params.iter().enumerate() {
            if let Some(d) = &p.default {
                slots[i] = self.typed(d, &p.ty, span);
            }
        }
        for p in params {
            match decl.param(&p.name.text) {
                Some(i) => {
                    let ty = decl.params[i].ty.clone();
                    slots[i] = self.typed(&p.value, &ty, p.span);
                }
                None => self.diags.push(Diagnostic::warning(
                    p.name.span,
                    format!("shader '{decl_name}' has no parameter '{}'; it is ignored", p.name.text),
                )),
            }
        }
        if decl.kind == DeclKind::Phenomenon {
            return self.phenomenon(&decl, slots, name, span);
        }
        let imp = self.decls.implementation(decl_name);
        if imp.is_none() {
            self.diags.push(Diagnostic::warning(
                span,
                format!("shader '{decl_name}' is not implemented by mira; it returns nothing"),
            ));
        }
        // The implementation reads its parameters by position in its own list: reorder.
        let slots = match imp {
            Some(imp) => imp
                .params
                .iter()
                .map(|p| match decl.param(p) {
                    Some(i) => slots[i].clone(),
                    None => Slot::Value(Value::Null),
                })
                .collect(),
            None => slots,
        };
        Some(self.push(Node { name: Arc::from(name.as_str()), decl, imp, slots, next: None, span }))
    }

    /// Expands a phenomenon instance.
    fn phenomenon(&mut self, decl: &Arc<Decl>, slots: Vec<Slot>, name: String, span: Span) -> Option<NodeId> {
        if self.scopes.len() > 16 {
            self.diags.push(Diagnostic::error(span, format!("phenomenon '{}' nests too deeply", decl.name)));
            return None;
        }
        // Phenomena that use phenomena several times each multiply: 16 levels of ten uses
        // would be 10^16 nodes. The graph stops growing at MAX_NODES, with one error.
        if self.graph.nodes.len() >= MAX_NODES {
            if !self.too_many {
                self.too_many = true;
                self.diags.push(Diagnostic::error(
                    span,
                    format!(
                        "phenomenon '{}' is not expanded: the scene's shaders and phenomenon expansions already \
                         make {} nodes, the most mira builds",
                        decl.name, MAX_NODES
                    ),
                ));
            }
            return None;
        }
        let interface = decl.params.iter().zip(slots.iter()).map(|(p, s)| (p.name.to_string(), s.clone())).collect();
        self.scopes.push(Scope { local: HashMap::new(), interface });
        let source = decl.source.clone();
        let mut root = None;
        for item in &source.body {
            match item {
                DeclItem::Item(Item::Shader(def)) => {
                    if let Some(head) = self.list(&def.list, Some(&def.name.text)) {
                        self.scopes.last_mut().expect("scope").local.insert(def.name.text.clone(), head);
                    }
                }
                DeclItem::Kw(k) if k.key == "root" => {
                    if let Some(ast::Arg::Shaders(list)) = k.args.first() {
                        root = self.list(list, None);
                    }
                }
                DeclItem::Kw(k) if k.key == "root material" || k.key == "root light" => {
                    self.diags.push(Diagnostic::warning(
                        k.span,
                        format!("phenomenon '{}': '{}' is not supported yet", decl.name, k.key),
                    ));
                }
                _ => {}
            }
        }
        self.scopes.pop();
        let root = root?;
        let slots = vec![Slot::Connect { node: root, member: None }];
        Some(self.push(Node {
            name: Arc::from(name.as_str()),
            decl: decl.clone(),
            imp: Some(&super::PHENOMENON),
            slots,
            next: None,
            span,
        }))
    }

    /// A connection `= "s"` or `= "s.member"`.
    /// Builds the shaders that `params` connect to (also inside arrays and structs).
    fn connect_all(&mut self, params: &[ast::Param]) {
        fn walk(b: &mut Builder, v: &ast::Value) {
            match v {
                ast::Value::Connect(name) => {
                    b.connect(name);
                }
                ast::Value::Array(items) => items.iter().for_each(|i| walk(b, i)),
                ast::Value::Struct(members) => members.iter().for_each(|m| walk(b, &m.value)),
                _ => {}
            }
        }
        for p in params {
            walk(self, &p.value);
        }
    }

    fn connect(&mut self, name: &ast::Name) -> Slot {
        if let Some(n) = self.named(&name.text, name.span) {
            return Slot::Connect { node: n, member: None };
        }
        if let Some((base, member)) = name.text.rsplit_once('.') {
            if let Some(n) = self.named(base, name.span) {
                return Slot::Connect { node: n, member: Some(Arc::from(member)) };
            }
        }
        // A defined shader that could not be built (a cycle, the nesting limit) was
        // reported where it failed; it is no unknown one.
        if !self.defined(&name.text) {
            self.diags.push(Diagnostic::error(name.span, format!("unknown shader '{}'", name.text)));
        }
        Slot::Value(Value::Null)
    }

    /// Whether `name` (or `name` without its `.member`) is a shader the scene defines.
    fn defined(&self, name: &str) -> bool {
        let known = |n: &str| self.shaders.contains_key(n) || self.shaders.contains_key(n.trim_start_matches("::"));
        known(name) || name.rsplit_once('.').is_some_and(|(base, _)| known(base))
    }

    /// Converts a written value to the declared type.
    fn typed(&mut self, v: &ast::Value, ty: &ParamType, span: Span) -> Slot {
        use ast::Value as V;
        match v {
            V::Connect(n) => return self.connect(n),
            V::Interface(p) => {
                let found = self.scopes.last().and_then(|s| s.interface.get(&p.text)).cloned();
                return found.unwrap_or_else(|| {
                    self.diags.push(Diagnostic::warning(p.span, format!("no interface parameter '{}'", p.text)));
                    Slot::Value(zero(ty))
                });
            }
            V::Define(item) => {
                if let ShaderItem::Define { name, list, .. } = &**item {
                    if let Some(n) = self.define(&name.text, list) {
                        return Slot::Connect { node: n, member: None };
                    }
                }
                return Slot::Value(zero(ty));
            }
            V::Null => return Slot::Value(Value::Null),
            _ => {}
        }
        let mismatch = |b: &mut Builder, what: &str| {
            b.diags.push(Diagnostic::warning(span, format!("expected {what} here; the value is ignored")));
            Slot::Value(zero(ty))
        };
        let value = match (ty, v) {
            (ParamType::Boolean, V::Bool(b)) => Value::Bool(*b),
            (ParamType::Boolean, V::Num(n)) => Value::Bool(n.as_f64() != 0.0),
            (ParamType::Integer, V::Num(n)) => Value::Int(n.as_f64() as i32),
            (ParamType::Integer, V::Bool(b)) => Value::Int(i32::from(*b)),
            (ParamType::Scalar, V::Num(n)) => Value::Scalar(n.as_f64() as f32),
            (ParamType::Scalar, V::Bool(b)) => Value::Scalar(f32::from(u8::from(*b))),
            (ParamType::Scalar, V::Tuple(t)) => Value::Scalar(t[0].as_f64() as f32),
            (ParamType::Color, V::Tuple(t)) if t.len() >= 3 => {
                let f = nums(t);
                Value::Color(Vec4::new(f[0], f[1], f[2], f.get(3).copied().unwrap_or(1.0)))
            }
            (ParamType::Color, V::Num(n)) => {
                let f = n.as_f64() as f32;
                Value::Color(Vec4::new(f, f, f, 1.0))
            }
            (ParamType::Vector, V::Tuple(t)) if t.len() >= 3 => {
                let f = nums(t);
                Value::Vector(Vec3A::new(f[0], f[1], f[2]))
            }
            (ParamType::Transform, V::Tuple(t)) if t.len() >= 16 => {
                let f = nums(t);
                Value::Transform(Mat4::from_cols_array(&f[..16].try_into().expect("16 numbers")))
            }
            (ParamType::String, V::Str(s)) => Value::Str(Arc::from(s.text.as_str())),
            (ParamType::ColorTexture | ParamType::ScalarTexture | ParamType::VectorTexture, V::Str(s)) => {
                match self.graph.names.textures.get(&s.text) {
                    Some(&i) => Value::Tag(Tag::Texture(i)),
                    // A texture may be given as a (procedural) shader's name.
                    None => match self.named(&s.text, s.span) {
                        Some(n) => return Slot::Connect { node: n, member: None },
                        None => {
                            self.diags.push(Diagnostic::warning(s.span, format!("unknown texture '{}'", s.text)));
                            Value::Null
                        }
                    },
                }
            }
            (ParamType::Light, V::Str(s)) => match self.graph.names.lights.get(&s.text) {
                Some(&i) => Value::Tag(Tag::Light(i)),
                None => {
                    self.diags
                        .push(Diagnostic::warning(s.span, format!("light '{}' is not in the rendered scene", s.text)));
                    Value::Null
                }
            },
            (ParamType::Material, V::Str(s)) => match self.graph.names.materials.get(&s.text) {
                Some(&i) => Value::Tag(Tag::Material(i)),
                None => Value::Str(Arc::from(s.text.as_str())),
            },
            (ParamType::Shader, V::Str(s)) => match self.named(&s.text, s.span) {
                Some(n) => Value::Tag(Tag::Shader(n)),
                None => {
                    if !self.defined(&s.text) {
                        self.diags.push(Diagnostic::warning(s.span, format!("unknown shader '{}'", s.text)));
                    }
                    Value::Null
                }
            },
            (ParamType::Data, V::Str(s)) => match self.graph.names.data.get(&s.text) {
                Some(&i) => Value::Tag(Tag::Data(i)),
                None => Value::Str(Arc::from(s.text.as_str())),
            },
            (ParamType::Lightprofile, V::Str(s)) => match self.graph.names.lightprofiles.get(&s.text) {
                Some(&i) => Value::Tag(Tag::Lightprofile(i)),
                None => {
                    self.diags.push(Diagnostic::warning(s.span, format!("unknown lightprofile '{}'", s.text)));
                    Value::Null
                }
            },
            (ParamType::Geometry | ParamType::Spectrum, V::Str(s)) => Value::Str(Arc::from(s.text.as_str())),
            (ParamType::Struct(fields), V::Struct(given)) => {
                let mut members: Vec<(Arc<str>, Slot)> =
                    fields.iter().map(|f| (Arc::from(f.name.text.as_str()), Slot::Value(zero(&f.ty)))).collect();
                for f in fields.iter().enumerate() {
                    if let Some(d) = &f.1.default {
                        members[f.0].1 = self.typed(d, &f.1.ty, span);
                    }
                }
                for g in given {
                    match fields.iter().position(|f| f.name.text == g.name.text) {
                        Some(i) => members[i].1 = self.typed(&g.value, &fields[i].ty, g.span),
                        None => self
                            .diags
                            .push(Diagnostic::warning(g.name.span, format!("no struct member '{}'", g.name.text))),
                    }
                }
                return Slot::Struct(members);
            }
            (ParamType::Array(inner), V::Array(elems)) => {
                return constant_array(elems.iter().map(|e| self.typed(e, inner, span)).collect());
            }
            (ParamType::Array(inner), single) => {
                // A single value where an array is declared: a one-element array.
                return constant_array(vec![self.typed(single, inner, span)]);
            }
            (ParamType::Color, _) => return mismatch(self, "a colour"),
            (ParamType::Vector, _) => return mismatch(self, "a vector"),
            (ParamType::Scalar, _) => return mismatch(self, "a number"),
            (ParamType::Integer, _) => return mismatch(self, "an integer"),
            (ParamType::Transform, _) => return mismatch(self, "a transform (16 numbers)"),
            (ParamType::Struct(_), _) => return mismatch(self, "a struct { … }"),
            _ => return mismatch(self, "another kind of value"),
        };
        Slot::Value(value)
    }
}

/// An array slot, as one constant value when no element is connected.
fn constant_array(items: Vec<Slot>) -> Slot {
    if items.iter().all(|s| matches!(s, Slot::Value(_))) {
        let values: Vec<Value> = items
            .into_iter()
            .map(|s| match s {
                Slot::Value(v) => v,
                _ => unreachable!("checked above"),
            })
            .collect();
        Slot::Value(Value::Array(values.into()))
    } else {
        Slot::Array(items)
    }
}

/// Where a list item is written.
fn item_span(item: &ShaderItem) -> Span {
    match item {
        ShaderItem::Call { span, .. } => *span,
        ShaderItem::Ref(r) => r.span,
        ShaderItem::Define { name, .. } => name.span,
    }
}

fn item_is_ref(item: &ShaderItem) -> bool {
    matches!(item, ShaderItem::Ref(_))
}

/// The last node of the list starting at `node`.
fn last_of(graph: &Graph, mut node: NodeId) -> NodeId {
    let mut guard = 0;
    while let Some(n) = graph.nodes[node as usize].next {
        node = n;
        guard += 1;
        if guard > 10_000 {
            break;
        }
    }
    node
}
