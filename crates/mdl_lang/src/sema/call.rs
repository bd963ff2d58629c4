//! Calls: overload resolution of functions and materials, struct constructors, constructors
//! of the built-in types and array constructors.

use mi::Span;

use super::Checker;
use crate::ast::*;
use crate::symbols::{type_name, SymbolKind};

/// A signature to bind arguments to: (name, type, has a default).
type Signature = Vec<(String, Type, bool)>;

impl Checker<'_> {
    /// Checks a call and returns its type.
    pub(super) fn call(&mut self, call: &mut Call, span: Span) -> Option<Type> {
        let arg_types: Vec<Option<Type>> = call.args.iter_mut().map(|a| self.expr(&mut a.value)).collect();
        if let Some(len) = call.array.clone() {
            return self.array_ctor(call, len, &arg_types, span);
        }
        let shadowed = self.own.contains_key(call.callee.last());
        if !call.callee.is_qualified() && !shadowed {
            if let Some(t) = Type::builtin(call.callee.last()) {
                if t != Type::Material {
                    return self.builtin_ctor(call, t, &arg_types, span);
                }
            }
        }
        let syms = match self.lookup(&call.callee) {
            Ok(s) => s,
            Err(e) => {
                self.error(span, e);
                return None;
            }
        };
        let callee = call.callee.clone();
        match syms[0].kind {
            SymbolKind::Function | SymbolKind::Material => {
                let mut rejections = Vec::new();
                let mut best: Option<(u32, usize)> = None;
                for (k, sym) in syms.iter().enumerate() {
                    let Some(Decl::Function(f)) = self.decl_of(sym) else { continue };
                    let sig: Signature =
                        f.params.iter().map(|p| (p.name.clone(), p.ty.ty.clone(), p.default.is_some())).collect();
                    match bind(&sig, &call.args, &arg_types) {
                        Ok(cost) if best.is_none_or(|(c, _)| cost < c) => best = Some((cost, k)),
                        Ok(_) => {}
                        Err(why) => rejections.push(why),
                    }
                }
                if let Some((_, k)) = best {
                    let sym = &syms[k];
                    let Some(Decl::Function(f)) = self.decl_of(sym) else { return None };
                    // A uniform parameter takes no value that varies over the surface.
                    let mut varying_args = Vec::new();
                    for (i, a) in call.args.iter().enumerate() {
                        let p = match &a.name {
                            Some(n) => f.param(n).map(|(_, p)| p),
                            None => f.params.get(i),
                        };
                        if let Some(p) = p.filter(|p| p.ty.frequency == Frequency::Uniform) {
                            if self.varies(&a.value) {
                                varying_args.push((a.span, p.name.clone()));
                            }
                        }
                    }
                    for (span, name) in varying_args {
                        let message = format!(
                            "parameter `{name}` of `{callee}` is uniform, but this value varies over the surface"
                        );
                        self.error(span, message);
                    }
                    let Some(Decl::Function(f)) = self.decl_of(sym) else { return None };
                    let (ret, name, material) = (f.ret.ty.clone(), f.name.clone(), f.is_material());
                    let (module, decl) = (sym.module.clone(), sym.decl);
                    call.res = if material {
                        Resolution::Material { module, name, decl }
                    } else {
                        Resolution::Function { module, name, decl }
                    };
                    return Some(ret);
                }
                if rejections.len() == 1 {
                    self.error(span, format!("in the call of `{callee}`: {}", rejections[0]));
                } else {
                    let list: Vec<String> =
                        arg_types.iter().map(|t| t.as_ref().map_or("?".to_string(), Type::to_string)).collect();
                    self.error(span, format!("no overload of `{callee}` accepts the arguments ({})", list.join(", ")));
                }
                None
            }
            SymbolKind::Struct => {
                let sym = &syms[0];
                let decl_name = self.decl_of(sym).map(|d| d.name().to_string()).unwrap_or_default();
                let ty = if sym.module == crate::std_modules::PRELUDE && decl_name == "material" {
                    Type::Material
                } else {
                    Type::Struct(type_name(&sym.module, &decl_name))
                };
                let fields = match &ty {
                    Type::Material => self.struct_fields("material"),
                    Type::Struct(n) => self.struct_fields(n),
                    _ => None,
                }?;
                let sig: Signature = fields.into_iter().map(|(n, t)| (n, t, true)).collect();
                if let Err(why) = bind(&sig, &call.args, &arg_types).map(|_| ()) {
                    self.error(span, format!("in the constructor `{callee}`: {why}"));
                }
                call.res = Resolution::Constructor(ty.clone());
                Some(ty)
            }
            SymbolKind::Enum => {
                let sym = &syms[0];
                let decl_name = self.decl_of(sym).map(|d| d.name().to_string()).unwrap_or_default();
                let ty = Type::Enum(type_name(&sym.module, &decl_name));
                if call.args.len() > 1 {
                    self.error(span, format!("`{callee}(…)` takes at most one argument"));
                }
                call.res = Resolution::Constructor(ty.clone());
                Some(ty)
            }
            SymbolKind::Typedef => {
                let mut ty = Type::Named(callee);
                self.resolve_type(&mut ty, span);
                call.res = Resolution::Constructor(ty.clone());
                Some(ty)
            }
            _ => {
                self.error(span, format!("`{callee}` cannot be called"));
                None
            }
        }
    }

    fn array_ctor(&mut self, call: &mut Call, len: ArrayLen, arg_types: &[Option<Type>], span: Span) -> Option<Type> {
        if call.args.iter().any(|a| a.name.is_some()) {
            self.error(span, "an array constructor takes positional arguments only");
        }
        let mut elem = Type::builtin(call.callee.last())
            .filter(|_| !call.callee.is_qualified())
            .unwrap_or_else(|| Type::Named(call.callee.clone()));
        self.resolve_type(&mut elem, span);
        let mut array = Type::Array(Box::new(elem.clone()), len);
        self.resolve_type(&mut array, span);
        let Type::Array(_, len) = &array else { return None };
        let n = call.args.len() as u64;
        let len = match len {
            ArrayLen::Unsized => ArrayLen::Fixed(n),
            ArrayLen::Fixed(m) if *m == n || n == 0 => ArrayLen::Fixed(*m),
            ArrayLen::Fixed(m) => {
                self.error(span, format!("array of {m} elements constructed from {n} values"));
                ArrayLen::Fixed(*m)
            }
            other => other.clone(),
        };
        for (arg, t) in call.args.iter().zip(arg_types) {
            if let Some(t) = t {
                if !t.converts_to(&elem) {
                    self.error(arg.span, format!("an element of type `{t}` in an array of `{elem}`"));
                }
            }
        }
        let ty = Type::Array(Box::new(elem), len);
        call.res = Resolution::Constructor(ty.clone());
        Some(ty)
    }

    fn builtin_ctor(&mut self, call: &mut Call, t: Type, arg_types: &[Option<Type>], span: Span) -> Option<Type> {
        let n = call.args.len();
        let max = match &t {
            Type::Scalar(_) | Type::String => 1,
            Type::Vector(_, k) => *k as usize,
            Type::Matrix(_, c, r) => (*c * *r) as usize,
            Type::Color => 3,
            Type::Texture(_) => 3,
            Type::LightProfile | Type::BsdfMeasurement => 1,
            _ => 0,
        };
        if n > max {
            let what = if max == 0 { "no arguments".to_string() } else { format!("at most {max} argument(s)") };
            self.error(span, format!("the constructor `{t}(…)` takes {what}, {n} given"));
        }
        let resource = matches!(t, Type::Texture(_) | Type::LightProfile | Type::BsdfMeasurement);
        if !resource && call.args.iter().any(|a| a.name.is_some()) {
            self.error(span, format!("the constructor `{t}(…)` takes positional arguments only"));
        }
        for (i, (arg, at)) in call.args.iter().zip(arg_types).enumerate() {
            let Some(at) = at else { continue };
            let ok = match &t {
                _ if resource && i == 0 => *at == Type::String,
                Type::String => *at == Type::String,
                Type::Scalar(_) | Type::Vector(..) | Type::Matrix(..) | Type::Color => {
                    matches!(at, Type::Scalar(_) | Type::Vector(..) | Type::Matrix(..) | Type::Color | Type::Enum(_))
                        || matches!(at, Type::Array(e, _) if e.is_numeric_scalar())
                }
                _ => true,
            };
            if !ok {
                self.error(arg.span, format!("`{t}` cannot be constructed from a value of type `{at}`"));
            }
        }
        call.res = Resolution::Constructor(t.clone());
        Some(t)
    }
}

/// Whether arguments fit a signature: positional ones in order, named ones by name, every
/// parameter without a default given, every known argument type convertible. The total
/// conversion cost if they do; the error says why not.
fn bind(sig: &Signature, args: &[Arg], types: &[Option<Type>]) -> Result<u32, String> {
    let mut given = vec![false; sig.len()];
    let mut cost = 0;
    for (i, (arg, t)) in args.iter().zip(types).enumerate() {
        let idx = match &arg.name {
            Some(n) => match sig.iter().position(|(p, _, _)| p == n) {
                Some(idx) => idx,
                None => return Err(format!("there is no parameter `{n}`")),
            },
            None if i < sig.len() => i,
            None => return Err(format!("too many arguments ({} given, {} expected at most)", args.len(), sig.len())),
        };
        if given[idx] {
            return Err(format!("parameter `{}` is given twice", sig[idx].0));
        }
        given[idx] = true;
        if let Some(t) = t {
            match t.conversion_cost(&sig[idx].1) {
                Some(c) => cost += c,
                None => return Err(format!("argument `{}` is of type `{t}`, expected `{}`", sig[idx].0, sig[idx].1)),
            }
        }
    }
    if let Some(((name, _, _), _)) = sig.iter().zip(&given).find(|((_, _, default), g)| !**g && !default) {
        return Err(format!("parameter `{name}` has no default and is not given"));
    }
    Ok(cost)
}
