//! Geometry shaders: an instance's `geometry` shader list followed to its shader call
//! (through `= "name"` references to named shaders), then
//! - the shapes (`mib_geo_sphere`, `_cone`, `_cylinder`, `_cube`, `_square`, `_torus`) made
//!   once per call into an object named `<instance or named shader>#<shader>` and placed
//!   under the instance, with the flags mental ray's shaders give their objects;
//! - `mib_geo_instance` and `mib_geo_instance_mlist` placing the object (or instgroup)
//!   their `object` parameter names below the instance, with their `matrix` as one more
//!   instance transform and their `material` (array) as that level's instance material.
//!
//! - `mib_geo_add_uv_texsurf` placing a copy of the object its `object` parameter names
//!   whose free-form surfaces get a last texture space holding their (u, v) parameters
//!   (made once per object, named `<object>#mib_geo_add_uv_texsurf`).
//!
//! Other geometry shaders (custom ones) are skipped with a warning naming them.

use glam::DMat4;
use mi::ast::{Name, Param, ShaderItem, ShaderList, Value};
use mi::{Diagnostic, Span};

use super::{Binding, Builder, Inherited};
use crate::instance::{FlagSet, ModeSet};
use crate::names::Def;
use crate::tessellate::procedural::{Shape, MAX_TRIANGLES};
use crate::tessellate::ObjectGeometry;
use crate::{transform, Object};

/// Most `= "name"` references followed to find a geometry shader's call.
const MAX_REFERENCES: usize = 64;

/// A geometry shader call found through a shader list.
struct Call<'a> {
    /// The shader's declaration name.
    decl: &'a str,
    /// Its parameters.
    params: &'a [Param],
    /// The namespace names in its parameters are resolved from.
    scope: String,
    /// The named shader holding the call (full name), if any: its geometry is made once
    /// and shared by every instance using it.
    named: Option<String>,
    /// The call.
    span: Span,
}

/// The flags mental ray's shape shaders set on their objects: visible, casting and
/// receiving shadows, reflection, refraction and final gathering.
fn shape_flags() -> FlagSet {
    let both = ModeSet { cast: Some(true), receive: Some(true) };
    FlagSet {
        visible: Some(true),
        shadow: both,
        reflection: both,
        refraction: both,
        finalgather: both,
        ..FlagSet::default()
    }
}

/// The last parameter called `name`.
fn param<'p>(params: &'p [Param], name: &str) -> Option<&'p Param> {
    params.iter().rev().find(|p| p.name.text == name)
}

impl<'a> Builder<'a, '_> {
    /// Places what instance `full`'s geometry shader list makes.
    pub(super) fn geometry(
        &mut self,
        full: &str,
        list: &'a ShaderList,
        scope: &str,
        inherited: &Inherited,
        span: Span,
    ) {
        let Some(call) = self.geometry_call(list, scope, span) else { return };
        if let Some(shape) = Shape::from_call(call.decl, call.params) {
            let name = format!("{}#{}", call.named.as_deref().unwrap_or(full), call.decl);
            let object = match self.object_index.get(&name) {
                Some(&i) => i,
                None => {
                    let limited = shape.limited(MAX_TRIANGLES);
                    if limited != shape {
                        self.diags.push(Diagnostic::warning(
                            call.span,
                            format!(
                                "instance '{full}': {} would make {} triangles; its subdivisions are reduced to \
                                 make {}",
                                call.decl,
                                shape.triangle_count(),
                                limited.triangle_count()
                            ),
                        ));
                    }
                    let mesh = limited.mesh(&name);
                    self.objects.push(Object {
                        name: name.clone(),
                        flags: shape_flags(),
                        tagged: false,
                        tag: None,
                        data: Vec::new(),
                        geometry: ObjectGeometry { mesh, hair: Vec::new() },
                        displace: Default::default(),
                        span: call.span,
                    });
                    let i = (self.objects.len() - 1) as u32;
                    self.object_index.insert(name, i);
                    i
                }
            };
            return self.place(full, object, inherited, span);
        }
        match call.decl {
            "mib_geo_instance" | "mib_geo_instance_mlist" => self.geo_instance(full, &call, inherited, span),
            "mib_geo_add_uv_texsurf" => self.add_uv_texsurf(full, &call, inherited, span),
            decl => self.diags.push(Diagnostic::warning(
                span,
                format!("instance '{full}' uses the geometry shader '{decl}', which mira does not support yet; it is skipped"),
            )),
        }
    }

    /// The call a geometry shader list runs: its first item, `= "name"` references
    /// followed to the named shader's definition.
    fn geometry_call(&mut self, list: &'a ShaderList, scope: &str, span: Span) -> Option<Call<'a>> {
        let table = self.table;
        if list.0.len() > 1 {
            self.diags.push(Diagnostic::warning(
                span,
                "only the first shader of a geometry shader list is used; the others are ignored",
            ));
        }
        let mut item = list.0.first()?;
        let mut scope = scope.to_string();
        let mut named = None;
        for _ in 0..MAX_REFERENCES {
            match item {
                ShaderItem::Call { decl, params, span } => {
                    return Some(Call { decl: &decl.text, params, scope, named, span: *span });
                }
                ShaderItem::Ref(name) => {
                    let (full, element) = match table.lookup(name, &scope, "shader") {
                        Ok(x) => x,
                        Err(d) => {
                            self.error(d);
                            return None;
                        }
                    };
                    let Def::Shader(defs) = &element.def else {
                        self.error(Diagnostic::error(
                            name.span,
                            format!("'{}' is a {}, not a shader", name.text, element.def.kind()),
                        ));
                        return None;
                    };
                    item = defs.last()?.list.0.first()?;
                    scope = element.scope.clone();
                    named = Some(full);
                }
                ShaderItem::Define { name, list, .. } => {
                    named = Some(format!("{scope}{}", name.text.trim_start_matches("::")));
                    item = list.0.first()?;
                }
            }
        }
        self.error(Diagnostic::error(span, "the geometry shader's references to named shaders go round in a loop"));
        None
    }

    /// `mib_geo_add_uv_texsurf`: the object named by `object`, its free-form surfaces with
    /// one more texture surface giving their (u, v) parameters, placed below instance `full`.
    fn add_uv_texsurf(&mut self, full: &str, call: &Call<'a>, inherited: &Inherited, span: Span) {
        let table = self.table;
        let decl = call.decl;
        let name: &'a Name = match param(call.params, "object").map(|p| &p.value) {
            Some(Value::Str(n)) => n,
            _ => {
                return self.diags.push(Diagnostic::warning(
                    call.span,
                    format!("instance '{full}': {decl} names no object; nothing is placed"),
                ));
            }
        };
        let Some((target_full, element)) = table.get(&name.text, &call.scope) else {
            return self.error(Diagnostic::error(name.span, format!("unknown element '{}' in {decl}", name.text)));
        };
        match &element.def {
            Def::Object(objs) => {
                let objs = objs.clone();
                let key = format!("{target_full}#{decl}");
                self.place_object_as(full, &key, &objs, inherited, span, true);
            }
            other => self.error(Diagnostic::error(
                name.span,
                format!("{decl} needs an object; '{}' is a {}", name.text, other.kind()),
            )),
        }
    }

    /// `mib_geo_instance` and `mib_geo_instance_mlist`: the element named by `object`
    /// placed below instance `full` with `matrix` (world → object, as an instance
    /// transform; absent or all zero: identity) and `material`.
    fn geo_instance(&mut self, full: &str, call: &Call<'a>, inherited: &Inherited, span: Span) {
        let table = self.table;
        let decl = call.decl;
        let name: &'a Name = match param(call.params, "object").map(|p| &p.value) {
            Some(Value::Str(n)) => n,
            Some(Value::Null) | None => {
                return self.diags.push(Diagnostic::warning(
                    call.span,
                    format!("instance '{full}': {decl} names no object; nothing is placed"),
                ));
            }
            Some(_) => {
                return self.diags.push(Diagnostic::warning(
                    call.span,
                    format!("instance '{full}': {decl}'s 'object' is not an element name; nothing is placed"),
                ));
            }
        };
        let Some((target_full, element)) = table.get(&name.text, &call.scope) else {
            return self.error(Diagnostic::error(name.span, format!("unknown element '{}' in {decl}", name.text)));
        };
        let matrix = match param(call.params, "matrix") {
            None => DMat4::IDENTITY,
            Some(p) => match &p.value {
                Value::Null => DMat4::IDENTITY,
                Value::Tuple(nums) if nums.iter().all(|n| n.as_f64() == 0.0) => DMat4::IDENTITY,
                Value::Tuple(nums) => {
                    let m: Vec<f64> = nums.iter().map(|n| n.as_f64()).collect();
                    match transform::from_mi(&m).filter(|t| transform::inverse(*t).is_some()) {
                        Some(t) if m.len() == 16 => t,
                        _ => {
                            self.diags
                                .push(Diagnostic::warning(p.span, "singular or invalid transform: identity used"));
                            DMat4::IDENTITY
                        }
                    }
                }
                _ => {
                    self.diags.push(Diagnostic::warning(p.span, "singular or invalid transform: identity used"));
                    DMat4::IDENTITY
                }
            },
        };
        let names: Vec<Name> = match param(call.params, "material").map(|p| &p.value) {
            Some(Value::Str(n)) => vec![n.clone()],
            Some(Value::Array(values)) => {
                values.iter().filter_map(|v| if let Value::Str(n) = v { Some(n.clone()) } else { None }).collect()
            }
            _ => Vec::new(),
        };
        let mut material = inherited.material.clone();
        // As for an instance's own `material`: ignored below an overriding one.
        if !names.is_empty() && !inherited.material.as_ref().is_some_and(|m| m.overrides) {
            material = Some(Binding { array: names.len() > 1, names, scope: call.scope.clone(), overrides: false });
        }
        let next = Inherited {
            world_to_local: matrix * inherited.world_to_local,
            motion_world_to_local: inherited.motion_world_to_local.map(|m| matrix * m),
            flags: inherited.flags,
            material,
            lights: inherited.lights.clone(),
            shadow_lights: inherited.shadow_lights.clone(),
        };
        match &element.def {
            Def::Object(objs) => {
                let objs = objs.clone();
                self.place_object(full, &target_full, &objs, &next, span);
            }
            Def::Instgroup(_) => self.group(name, &call.scope, &next),
            other => self.error(Diagnostic::error(
                name.span,
                format!("{decl} cannot place a {} ('{}')", other.kind(), name.text),
            )),
        }
    }
}
