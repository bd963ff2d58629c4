//! Building the world: the `render` statement's options, camera and root group resolved,
//! the instance DAG walked, objects tessellated once, materials bound.

mod geometry;

use std::collections::HashMap;

use glam::DMat4;
use mi::ast::{self, Arg, InstanceTarget, Name, Stmt};
use mi::Diagnostic;

use crate::camera::Camera;
use crate::instance::{FlagOwner, FlagSet, Instance, LightLink};
use crate::light::Light;
use crate::mesh::MaterialSlot;
use crate::names::{Def, Table};
use crate::options::{Dialect, Options};
use crate::tessellate::taken::TakenTrilists;
use crate::tessellate::{self, ObjectGeometry};
use crate::transform;
use crate::{Library, Material, MaterialKind, Object, Scene};

/// How deeply instgroups may nest.
pub const MAX_DAG_DEPTH: usize = 256;

pub use crate::sanity::WORLD_LIMIT;

/// Whether every vertex of `geometry` (its object-space bounding box) stays within
/// ±[`WORLD_LIMIT`] once placed by `object_to_world`.
fn fits_single_precision(geometry: &ObjectGeometry, object_to_world: DMat4) -> bool {
    let points = geometry.mesh.positions.iter().chain(geometry.hair.iter().flat_map(|h| h.points.iter()));
    let mut lo = glam::DVec3::splat(f64::INFINITY);
    let mut hi = glam::DVec3::splat(f64::NEG_INFINITY);
    for p in points {
        lo = lo.min(p.as_dvec3());
        hi = hi.max(p.as_dvec3());
    }
    if lo.x > hi.x {
        return true;
    }
    (0..8).all(|i| {
        let corner = glam::DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let w = object_to_world.transform_point3(corner);
        w.is_finite() && w.abs().max_element() <= WORLD_LIMIT
    })
}

/// A material inherited down the DAG: one name or an array (for labels), where it was
/// written, and whether it overrides materials below.
#[derive(Clone, Debug)]
struct Binding {
    names: Vec<Name>,
    array: bool,
    scope: String,
    overrides: bool,
}

/// A light list as written: exclusive, the light instance names, their namespace.
type LinkSpec = (bool, Vec<Name>, String);

/// What flows down the DAG to the instances below.
#[derive(Clone, Debug)]
struct Inherited {
    world_to_local: DMat4,
    motion_world_to_local: Option<DMat4>,
    flags: FlagSet,
    material: Option<Binding>,
    lights: Option<LinkSpec>,
    shadow_lights: Option<LinkSpec>,
}

struct Builder<'a, 'd> {
    table: &'a Table<'a>,
    /// Trilist arrays moved out of the syntax tree, moved on into the meshes.
    taken: &'a TakenTrilists,
    diags: &'d mut Vec<Diagnostic>,
    options: Options,
    objects: Vec<Object>,
    object_index: HashMap<String, u32>,
    instances: Vec<Instance>,
    /// Light links by instance index, resolved after the walk.
    pending_links: Vec<(usize, Option<LinkSpec>, Option<LinkSpec>)>,
    lights: Vec<Light>,
    materials: Vec<Material>,
    material_index: HashMap<String, u32>,
    camera_instance: String,
    camera: Option<(DMat4, Option<DMat4>)>,
    path: Vec<String>,
}

/// The dialect a scene is written in: Iray when it uses MDL.
fn dialect(table: &Table) -> Dialect {
    let mdl_shader = table.elements.values().any(|e| match &e.def {
        Def::Shader(defs) => defs.iter().any(|d| {
            d.list.0.iter().any(|i| matches!(i, ast::ShaderItem::Call { decl, .. } if decl.text.starts_with("mdl::")))
        }),
        _ => false,
    });
    if !table.mdl_modules.is_empty() || mdl_shader {
        Dialect::Iray
    } else {
        Dialect::MentalRay
    }
}

/// Builds the world at the `frame`-th `render` statement (0 for the first).
pub fn build(items: &[ast::Item], frame: usize, diags: &mut Vec<Diagnostic>) -> Option<Scene> {
    build_with(items, &TakenTrilists::default(), frame, diags)
}

/// [`build`], moving the trilists' vertex and index arrays out of `items` into the meshes
/// instead of copying them ([`TakenTrilists::take_from`]; `items` keeps empty arrays).
pub fn build_taking(items: &mut [ast::Item], frame: usize, diags: &mut Vec<Diagnostic>) -> Option<Scene> {
    let taken = TakenTrilists::take_from(items);
    build_with(items, &taken, frame, diags)
}

/// [`build`] with the trilist arrays already moved into `taken`.
fn build_with(items: &[ast::Item], taken: &TakenTrilists, frame: usize, diags: &mut Vec<Diagnostic>) -> Option<Scene> {
    let (table, render) = Table::collect(items, frame, diags);
    let Some(render) = render else {
        let span = items.last().map_or(mi::Span::default(), item_span);
        diags.push(Diagnostic::error(
            span,
            if frame == 0 {
                "the file has no 'render' statement".to_string()
            } else {
                format!("the file has no render statement number {}", frame + 1)
            },
        ));
        return None;
    };
    crate::references::check(&table, diags);
    crate::shader_graph::check(&table, diags);
    crate::sanity::check_numbers(&table, diags);
    let r = render.render;
    let scope = &render.scope;
    let dialect = dialect(&table);
    let options = match table.lookup(&r.options, scope, "options") {
        Ok((_, e)) => match &e.def {
            Def::Options(blocks) => {
                let mut o = Options::from_blocks(blocks, dialect);
                crate::sanity::options(&mut o, blocks, diags);
                o
            }
            other => {
                diags.push(Diagnostic::error(
                    r.options.span,
                    format!("'{}' is a {}, not options", r.options.text, other.kind()),
                ));
                return None;
            }
        },
        Err(d) => {
            diags.push(d);
            return None;
        }
    };
    let camera_instance = match table.lookup(&r.camera, scope, "camera instance") {
        Ok((full, _)) => full,
        Err(d) => {
            diags.push(d);
            return None;
        }
    };
    let mut b = Builder {
        table: &table,
        taken,
        diags,
        options,
        objects: Vec::new(),
        object_index: HashMap::new(),
        instances: Vec::new(),
        pending_links: Vec::new(),
        lights: Vec::new(),
        materials: Vec::new(),
        material_index: HashMap::new(),
        camera_instance,
        camera: None,
        path: Vec::new(),
    };
    let root = Inherited {
        world_to_local: DMat4::IDENTITY,
        motion_world_to_local: None,
        flags: FlagSet::default(),
        material: None,
        lights: None,
        shadow_lights: None,
    };
    b.group(&r.root, scope, &root);
    let camera = b.camera_element()?;
    b.resolve_links();
    let library = Library::from_table(&table);
    Some(Scene {
        options: b.options,
        camera,
        lights: b.lights,
        objects: b.objects,
        instances: b.instances,
        materials: b.materials,
        library,
    })
}

/// An instgroup path for a message: all of it when short, else its two ends.
/// The data element names of an object's `data` statements, in order (`data null`
/// clears those before it).
fn data_names(stmts: &[&Stmt]) -> Vec<String> {
    let mut names = Vec::new();
    for s in stmts {
        if let Stmt::Kw(k) = s {
            if k.key == "data" {
                match k.args.first() {
                    Some(Arg::Name(n)) => names.push(n.text.clone()),
                    _ => names.clear(),
                }
            }
        }
    }
    names
}

fn path_text(path: &[String]) -> String {
    if path.len() <= 8 {
        return path.join(" -> ");
    }
    format!("{} -> … {} more … -> {}", path[..3].join(" -> "), path.len() - 6, path[path.len() - 3..].join(" -> "))
}

fn item_span(item: &ast::Item) -> mi::Span {
    match item {
        ast::Item::Render(r) => r.span,
        ast::Item::Options(b) | ast::Item::Camera(b) | ast::Item::Light(b) => b.span,
        ast::Item::Object(o) => o.span,
        ast::Item::Instance(i) => i.span,
        ast::Item::Include(inc) => inc.path.span,
        _ => mi::Span::default(),
    }
}

impl<'a> Builder<'a, '_> {
    fn error(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    /// Walks an instgroup.
    fn group(&mut self, name: &Name, scope: &str, inherited: &Inherited) {
        let (full, element) = match self.table.lookup(name, scope, "instgroup") {
            Ok(x) => x,
            Err(d) => return self.error(d),
        };
        let Def::Instgroup(defs) = &element.def else {
            return self.error(Diagnostic::error(
                name.span,
                format!("'{}' is a {}, not an instgroup", name.text, element.def.kind()),
            ));
        };
        if self.path.contains(&full) {
            return self.error(Diagnostic::error(
                name.span,
                format!("instgroup '{}' contains itself (through {})", name.text, path_text(&self.path)),
            ));
        }
        if self.path.len() >= MAX_DAG_DEPTH {
            return self.error(Diagnostic::error(
                name.span,
                format!(
                    "instgroup '{}' is nested {} levels deep; mira follows at most {MAX_DAG_DEPTH} levels of \
                     instgroups (through {})",
                    name.text,
                    self.path.len() + 1,
                    path_text(&self.path)
                ),
            ));
        }
        self.path.push(full);
        // An incremental instgroup replaces the member list.
        let group = defs.last().expect("at least one definition");
        let group_scope = element.scope.clone();
        for member in &group.members {
            match self.table.get(&member.text, &group_scope) {
                Some((_, e)) if matches!(e.def, Def::Instgroup(_)) => self.group(member, &group_scope, inherited),
                Some((full, e)) => match &e.def {
                    Def::Instance(defs) => {
                        let defs = defs.clone();
                        let scope = e.scope.clone();
                        self.instance(&full, &defs, &scope, inherited);
                    }
                    other => self.error(Diagnostic::error(
                        member.span,
                        format!("instgroup member '{}' is a {}, not an instance", member.text, other.kind()),
                    )),
                },
                None => self.error(Diagnostic::error(member.span, format!("unknown instance '{}'", member.text))),
            }
        }
        self.path.pop();
    }

    /// Walks an instance: composes its transform and flags, then places what it instances.
    fn instance(&mut self, full: &str, defs: &[&'a ast::Instance], scope: &str, inherited: &Inherited) {
        let stmts: Vec<&Stmt> = defs.iter().flat_map(|d| d.stmts.iter()).collect();
        let own = FlagSet::read(stmts.iter().copied(), FlagOwner::Instance);
        if own.hide == Some(true) {
            return;
        }
        let span = defs[0].span;
        let mut world_to_local = inherited.world_to_local;
        let mut motion = inherited.motion_world_to_local;
        let mut own_motion: Option<Option<DMat4>> = None;
        let mut overrides = false;
        let mut material = inherited.material.clone();
        let mut lights = inherited.lights.clone();
        let mut shadow_lights = inherited.shadow_lights.clone();
        let mut local = DMat4::IDENTITY;
        for s in &stmts {
            let Stmt::Kw(k) = s else { continue };
            match k.key {
                "transform" => match k.args.first() {
                    Some(Arg::Floats(m)) => match transform::from_mi(m) {
                        Some(t) if transform::inverse(t).is_some() => local = t,
                        _ => {
                            self.diags
                                .push(Diagnostic::warning(k.span, "singular or invalid transform: identity used"));
                            local = DMat4::IDENTITY;
                        }
                    },
                    _ => local = DMat4::IDENTITY,
                },
                "motion transform" => {
                    let motion = match k.args.first() {
                        Some(Arg::Floats(m)) => transform::from_mi(m).filter(|t| transform::inverse(*t).is_some()),
                        _ => None,
                    };
                    if motion.is_none() && matches!(k.args.first(), Some(Arg::Floats(_))) {
                        self.diags.push(Diagnostic::warning(
                            k.span,
                            "singular or invalid motion transform: the instance does not move",
                        ));
                    }
                    own_motion = Some(motion);
                }
                "motion" => {
                    if matches!(k.args.first(), Some(Arg::Bool(false))) {
                        own_motion = Some(None);
                    }
                }
                "override" => overrides = true,
                "material" => {
                    // A material written below an overriding one is ignored.
                    if inherited.material.as_ref().is_some_and(|m| m.overrides) {
                        continue;
                    }
                    material = match k.args.first() {
                        Some(Arg::Name(n)) => {
                            Some(Binding { names: vec![n.clone()], array: false, scope: scope.to_string(), overrides })
                        }
                        Some(Arg::Names(ns)) => {
                            Some(Binding { names: ns.clone(), array: true, scope: scope.to_string(), overrides })
                        }
                        _ => None,
                    };
                    overrides = false;
                }
                "light" | "light shadow" => {
                    let exclusive = matches!(k.args.first(), Some(Arg::Name(n)) if n.text == "exclusive");
                    let names = k
                        .args
                        .iter()
                        .find_map(|a| if let Arg::Names(n) = a { Some(n.clone()) } else { None })
                        .unwrap_or_default();
                    let link = Some((exclusive, names, scope.to_string()));
                    if k.key == "light" {
                        lights = link;
                    } else {
                        shadow_lights = link;
                    }
                }
                _ => {}
            }
        }
        world_to_local = local * world_to_local;
        // Motion: this level's motion matrix (or its static one) composed with the parent's
        // motion path (or its static path).
        let this_motion = match own_motion {
            Some(Some(m)) => Some(m),
            Some(None) => None,
            None => None,
        };
        if this_motion.is_some() || motion.is_some() {
            let parent = motion.unwrap_or(inherited.world_to_local);
            motion = Some(this_motion.unwrap_or(local) * parent);
        }
        if own_motion == Some(None) {
            motion = None;
        }
        let next = Inherited {
            world_to_local,
            motion_world_to_local: motion,
            flags: own.or(inherited.flags),
            material,
            lights,
            shadow_lights,
        };
        let target: Option<&'a InstanceTarget> = defs.iter().rev().find_map(|d| match &d.target {
            InstanceTarget::None => None,
            t => Some(t),
        });
        match target {
            Some(InstanceTarget::Element(name)) => {
                let Some((target_full, element)) = self.table.get(&name.text, scope) else {
                    return self
                        .error(Diagnostic::error(name.span, format!("unknown element '{}' in instance", name.text)));
                };
                match &element.def {
                    Def::Object(objs) => {
                        let objs = objs.clone();
                        self.place_object(full, &target_full, &objs, &next, span);
                    }
                    Def::Light(blocks) => {
                        let Some(light_to_world) = transform::inverse(next.world_to_local) else {
                            return self.diags.push(Diagnostic::warning(
                                span,
                                format!("light instance '{full}': its transform is singular; the light is left out"),
                            ));
                        };
                        let mut light = Light::from_blocks(blocks, full, light_to_world, own.visible);
                        light.motion_light_to_world = next
                            .motion_world_to_local
                            .filter(|m| *m != next.world_to_local)
                            .and_then(transform::inverse);
                        crate::sanity::light(&mut light, blocks, self.diags);
                        self.lights.push(light);
                    }
                    Def::Camera(_) => {
                        if full == self.camera_instance {
                            self.camera = Some((next.world_to_local, next.motion_world_to_local));
                        }
                    }
                    Def::Instgroup(_) => {
                        let scope = scope.to_string();
                        self.group(name, &scope, &next);
                    }
                    other => self.error(Diagnostic::error(
                        name.span,
                        format!("an instance cannot place a {} ('{}')", other.kind(), name.text),
                    )),
                }
            }
            Some(InstanceTarget::Geometry(list)) => self.geometry(full, list, scope, &next, span),
            _ => self.error(Diagnostic::error(span, format!("instance '{full}' names nothing to instance"))),
        }
    }

    /// Places an object: tessellated on first use, then shared.
    fn place_object(
        &mut self,
        instance: &str,
        full: &str,
        defs: &[&'a ast::Object],
        inherited: &Inherited,
        span: mi::Span,
    ) {
        self.place_object_as(instance, full, defs, inherited, span, false);
    }

    /// [`Builder::place_object`] under the name `full`; with `uv_texsurf`, the object's
    /// free-form surfaces first get `mib_geo_add_uv_texsurf`'s (u, v) texture surface.
    fn place_object_as(
        &mut self,
        instance: &str,
        full: &str,
        defs: &[&'a ast::Object],
        inherited: &Inherited,
        span: mi::Span,
        uv_texsurf: bool,
    ) {
        let object = match self.object_index.get(full) {
            Some(&i) => i,
            None => {
                // Incremental objects: flags accumulate, the last geometry wins.
                let mut geometry = match defs.iter().rev().find(|o| !o.geometry.is_empty()) {
                    Some(o) if uv_texsurf => {
                        let mut o = (*o).clone();
                        if tessellate::freeform::add_uv_texture_surfaces(&mut o) == 0 {
                            self.diags.push(Diagnostic::warning(
                                span,
                                format!(
                                    "instance '{instance}': mib_geo_add_uv_texsurf: object '{}' has no free-form \
                                     surfaces; it is placed unchanged",
                                    o.name.text
                                ),
                            ));
                        }
                        tessellate::tessellate_with(&o, self.taken, self.diags)
                    }
                    Some(o) => tessellate::tessellate_with(o, self.taken, self.diags),
                    None => ObjectGeometry::default(),
                };
                crate::sanity::mesh(&mut geometry, full, defs[0].span, self.diags);
                let stmts: Vec<&Stmt> = defs.iter().flat_map(|d| d.stmts.iter()).collect();
                let tagged = defs.iter().rev().find_map(|o| {
                    o.stmts.iter().rev().find_map(|s| match s {
                        Stmt::Kw(k) if k.key == "tagged" => Some(!matches!(k.args.first(), Some(Arg::Bool(false)))),
                        _ => None,
                    })
                });
                let tag = crate::values::last(&stmts, "tag").and_then(|k| crate::values::int_arg(k, 0));
                self.objects.push(Object {
                    name: full.to_string(),
                    flags: FlagSet::read(stmts.iter().copied(), FlagOwner::Object),
                    tagged: tagged.unwrap_or(false),
                    tag,
                    data: data_names(&stmts),
                    displace: crate::displace::DisplaceSettings::of_object(
                        &stmts,
                        defs.iter().rev().find(|o| !o.geometry.is_empty()).map_or(&[], |o| &o.geometry),
                    ),
                    geometry,
                    span: defs[0].span,
                });
                let i = (self.objects.len() - 1) as u32;
                self.object_index.insert(full.to_string(), i);
                i
            }
        };
        self.place(instance, object, inherited, span);
    }

    /// Places object number `object` under `instance`: its flags resolved and its
    /// material slots bound.
    fn place(&mut self, instance: &str, object: u32, inherited: &Inherited, span: mi::Span) {
        let Some(object_to_world) = transform::inverse(inherited.world_to_local) else {
            return self.diags.push(Diagnostic::warning(
                span,
                format!("instance '{instance}': its transform is singular; the object is left out"),
            ));
        };
        let obj = &self.objects[object as usize];
        if !fits_single_precision(&obj.geometry, object_to_world) {
            return self.diags.push(Diagnostic::warning(
                span,
                format!(
                    "instance '{instance}': object '{}' placed in world space reaches beyond single precision \
                     (±{WORLD_LIMIT:e}); the object is left out",
                    obj.name
                ),
            ));
        }
        let flags = inherited.flags.or(obj.flags).resolve(self.options.face);
        let slots = obj.geometry.mesh.slots.clone();
        let hair_slots: Vec<MaterialSlot> = obj.geometry.hair.iter().map(|h| h.slot.clone()).collect();
        let object_name = obj.name.clone();
        let tag = obj.tag;
        let mut missing = false;
        let mut materials = Vec::with_capacity(slots.len());
        for slot in slots.iter().chain(hair_slots.iter()) {
            let m = self.bind(slot, inherited.material.as_ref(), instance, span);
            missing |= m.is_none();
            materials.push(m);
        }
        let hair_materials = materials.split_off(slots.len());
        if missing && !slots.is_empty() {
            self.diags.push(Diagnostic::warning(
                span,
                format!("instance '{instance}': faces of object '{object_name}' have no material"),
            ));
        }
        self.pending_links.push((self.instances.len(), inherited.lights.clone(), inherited.shadow_lights.clone()));
        self.instances.push(Instance {
            name: instance.to_string(),
            object,
            object_to_world,
            world_to_object: inherited.world_to_local,
            motion_world_to_object: inherited.motion_world_to_local,
            flags,
            materials,
            hair_materials,
            lights: None,
            shadow_lights: None,
            tag,
        });
    }

    /// The material of a face slot under an inherited binding.
    fn bind(&mut self, slot: &MaterialSlot, binding: Option<&Binding>, instance: &str, span: mi::Span) -> Option<u32> {
        let name = match (slot, binding) {
            (MaterialSlot::Named(n), b) if !b.is_some_and(|b| b.overrides) => {
                let scope = b.map_or(String::new(), |b| b.scope.clone());
                return self.material(&Name { text: n.clone(), span }, &scope);
            }
            (MaterialSlot::Label(l), Some(b)) if b.array => match b.names.get(*l as usize) {
                Some(n) => n.clone(),
                None => {
                    let first = b.names.first().cloned()?;
                    self.diags.push(Diagnostic::warning(
                        span,
                        format!(
                            "instance '{instance}': label {l} is beyond its {} materials; the first is used",
                            b.names.len()
                        ),
                    ));
                    first
                }
            },
            (_, Some(b)) => b.names.first().cloned()?,
            (_, None) => return None,
        };
        let scope = binding.map_or(String::new(), |b| b.scope.clone());
        self.material(&name, &scope)
    }

    /// The index of material `name` (a `material`, or in Iray a `shader`), added on first use.
    fn material(&mut self, name: &Name, scope: &str) -> Option<u32> {
        let (full, element) = match self.table.lookup(name, scope, "material") {
            Ok(x) => x,
            Err(d) => {
                // Report each unknown name once.
                if !self.diags.iter().any(|e| e.message == d.message) {
                    self.error(d);
                }
                return None;
            }
        };
        if let Some(&i) = self.material_index.get(&full) {
            return Some(i);
        }
        let kind = match &element.def {
            Def::Material(defs) => MaterialKind::Material(defs.iter().map(|d| (*d).clone()).collect()),
            Def::Shader(defs) => MaterialKind::Shader(defs.last().map(|d| (*d).clone())?),
            other => {
                self.error(Diagnostic::error(
                    name.span,
                    format!("'{}' is a {}, not a material", name.text, other.kind()),
                ));
                return None;
            }
        };
        self.materials.push(Material { name: full.clone(), kind });
        let i = (self.materials.len() - 1) as u32;
        self.material_index.insert(full, i);
        Some(i)
    }

    /// The camera of the render statement.
    fn camera_element(&mut self) -> Option<Camera> {
        let full = self.camera_instance.clone();
        let element = &self.table.elements[&full];
        let Def::Instance(defs) = &element.def else {
            self.error(Diagnostic::error(
                element.span,
                format!("'{full}' is a {}, not a camera instance", element.def.kind()),
            ));
            return None;
        };
        let target =
            defs.iter().rev().find_map(|d| if let InstanceTarget::Element(n) = &d.target { Some(n) } else { None });
        let Some(target) = target else {
            self.error(Diagnostic::error(element.span, format!("camera instance '{full}' names no camera")));
            return None;
        };
        let blocks = match self.table.get(&target.text, &element.scope) {
            Some((_, e)) => match &e.def {
                Def::Camera(blocks) => blocks.clone(),
                other => {
                    self.error(Diagnostic::error(
                        target.span,
                        format!("'{}' is a {}, not a camera", target.text, other.kind()),
                    ));
                    return None;
                }
            },
            None => {
                self.error(Diagnostic::error(target.span, format!("unknown camera '{}'", target.text)));
                return None;
            }
        };
        let world_to_camera = match self.camera {
            Some((m, _)) => m,
            None => {
                self.diags.push(Diagnostic::warning(
                    element.span,
                    format!("camera instance '{full}' is not in the rendered instgroup; its own transform is used"),
                ));
                let stmts: Vec<&Stmt> = defs.iter().flat_map(|d| d.stmts.iter()).collect();
                crate::values::last(&stmts, "transform")
                    .and_then(|k| crate::values::floats_arg(k, 0))
                    .and_then(transform::from_mi)
                    .unwrap_or(DMat4::IDENTITY)
            }
        };
        let Some(camera_to_world) = transform::inverse(world_to_camera) else {
            self.error(Diagnostic::error(element.span, "the camera's transform is singular"));
            return None;
        };
        let eye = camera_to_world.transform_point3(glam::DVec3::ZERO);
        if !(eye.is_finite() && eye.abs().max_element() <= WORLD_LIMIT) {
            self.error(Diagnostic::error(
                element.span,
                format!("the camera's position is beyond single precision (±{WORLD_LIMIT:e})"),
            ));
            return None;
        }
        let mut camera = Camera::from_blocks(&blocks, &full, world_to_camera, camera_to_world, self.diags);
        camera.motion_world_to_camera = match self.camera {
            Some((_, Some(m))) if m != world_to_camera && transform::inverse(m).is_some() => Some(m),
            _ => None,
        };
        Some(camera)
    }

    /// Resolves instance light lists to light indices.
    fn resolve_links(&mut self) {
        let by_name: HashMap<String, u32> =
            self.lights.iter().enumerate().map(|(i, l)| (l.instance.clone(), i as u32)).collect();
        let pending = std::mem::take(&mut self.pending_links);
        for (inst, lights, shadow) in pending {
            let mut resolve = |link: Option<LinkSpec>| -> Option<LightLink> {
                let (exclusive, names, scope) = link?;
                let mut out = LightLink { exclusive, lights: Vec::new() };
                for n in names {
                    match self.table.resolve_name(&n.text, &scope).and_then(|full| by_name.get(&full)) {
                        Some(&i) => out.lights.push(i),
                        None => {
                            let msg = format!("unknown light instance '{}' in a light list", n.text);
                            if !self.diags.iter().any(|d| d.message == msg) {
                                self.diags.push(Diagnostic::warning(n.span, msg));
                            }
                        }
                    }
                }
                Some(out)
            };
            let l = resolve(lights);
            let s = resolve(shadow);
            self.instances[inst].lights = l;
            self.instances[inst].shadow_lights = s;
        }
    }
}
