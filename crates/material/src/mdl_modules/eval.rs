//! Evaluating a material's expression to a constant [`Value`] once per material instance:
//! arguments bound to parameters (defaults where absent), `let` and calls of
//! expression-bodied definitions followed, operators folded, struct constructors and the
//! `::df` distribution functions built. What depends on the shading point (`state::`
//! values, texture lookups and what is computed from them) becomes a [`Value::Hit`]
//! expression evaluated at each hit; what is not evaluated yet stops the evaluation with a
//! [`Problem`] at its place in the module.

use std::collections::HashMap;
use std::sync::Arc;

use bsdf::Rgb;
use mdl_lang::ast::{Arg, BinaryOp, Body, Decl, Scalar, TextureShape, UnaryOp};
use mdl_lang::{Expr, ExprKind, Function, ModuleSet, Resolution, Type};
use mi::Span;

use super::hit::{BinOp as HitBinOp, HitExpr, UnOp as HitUnOp};
use super::natives;
use super::textures::Textures;
use super::value::{HitType, Value};

/// Deepest nesting of calls followed (recursion in a module is an error, not a hang).
pub(super) const MAX_DEPTH: u32 = 64;

/// Most elements of an array built of defaults (`T[n]()`, an uninitialised `T[n]`).
const MAX_DEFAULT_ARRAY: u64 = 1 << 16;

/// Why an expression has no constant value: the place (in the module's sources) and what.
#[derive(Clone, Debug)]
pub struct Problem {
    /// Where, in the module set's sources.
    pub span: Span,
    /// What is not evaluated.
    pub message: String,
}

/// The result of evaluating.
pub type Eval = Result<Value, Problem>;

/// The bound parameters and the locals of the definition being evaluated.
#[derive(Default)]
pub struct Env {
    /// Parameter values by index.
    pub params: Vec<Value>,
    pub(super) locals: HashMap<u32, Value>,
}

impl Env {
    /// An environment with `params` bound.
    pub fn with_params(params: Vec<Value>) -> Env {
        Env { params, locals: HashMap::new() }
    }
}

/// The evaluator over one module set.
pub struct Evaluator<'a> {
    /// The modules the expressions come from.
    pub set: &'a ModuleSet,
    pub(super) depth: u32,
    /// Statements run so far in the statement bodies this evaluator followed (bounded by
    /// [`super::statements::MAX_STEPS`]).
    pub(super) steps: u64,
    /// The first loop slot free for a loop of the hit compiled now ([`super::hit_loop`]).
    pub(super) slot_top: u8,
    /// The most slots and levels the loops of the hit compiled inside the loop being
    /// compiled reach ([`super::hit_loop::HitLoop::top`]).
    pub(super) loop_nest: (u8, u8),
    /// The hit-dependent numbers the distribution functions read ([`super::value::Leaf`]).
    pub leaves: Vec<Arc<HitExpr>>,
    /// The texture files read.
    pub textures: &'a mut Textures,
}

/// A problem at `span`.
pub fn problem(span: Span, message: impl Into<String>) -> Problem {
    Problem { span, message: message.into() }
}

impl<'a> Evaluator<'a> {
    /// An evaluator of `set`'s definitions.
    pub fn new(set: &'a ModuleSet, textures: &'a mut Textures) -> Evaluator<'a> {
        Evaluator { set, depth: 0, steps: 0, slot_top: 0, loop_nest: (0, 0), leaves: Vec::new(), textures }
    }

    /// The value of `e` in `env`.
    pub fn eval(&mut self, e: &Expr, env: &mut Env) -> Eval {
        let span = e.span;
        match &e.kind {
            ExprKind::Bool(b) => Ok(Value::Bool(*b)),
            ExprKind::Int(i) => Ok(Value::Int(*i)),
            ExprKind::Float { value, .. } => Ok(Value::Float(*value)),
            ExprKind::Str(s) => Ok(Value::Str(s.clone())),
            ExprKind::Name(n) => match &n.res {
                Resolution::Param(i) => env
                    .params
                    .get(*i)
                    .cloned()
                    .ok_or_else(|| problem(span, format!("parameter `{}` is not bound", n.name))),
                Resolution::Local(id) => {
                    env.locals.get(id).cloned().ok_or_else(|| problem(span, format!("`{}` has no value yet", n.name)))
                }
                Resolution::EnumValue { enum_type, value } => Ok(Value::Enum(enum_type.clone(), *value)),
                Resolution::Constant { module, name } => self.constant(module, name, span),
                other => Err(problem(span, format!("`{}` ({other:?}) is not evaluated yet", n.name))),
            },
            ExprKind::Call(call) => match &call.res {
                Resolution::Constructor(ty) => self.construct(ty, &call.args, env, span),
                res @ (Resolution::Function { .. } | Resolution::Material { .. }) => {
                    let Some(def) = self.set.definition(res) else {
                        return Err(problem(span, format!("`{}` has no definition", call.callee)));
                    };
                    let args = self.bind(def, &call.args, env, span)?;
                    self.call(def, res, args, span)
                }
                _ => Err(problem(span, format!("call of `{}` is not evaluated yet", call.callee))),
            },
            ExprKind::Unary { op, operand } => {
                let v = self.eval(operand, env)?;
                if let Value::Hit(e, ty) = &v {
                    let op = match op {
                        UnaryOp::Plus => return Ok(v.clone()),
                        UnaryOp::Neg => HitUnOp::Neg,
                        UnaryOp::Not => HitUnOp::Not,
                        _ => return Err(problem(span, format!("operator {op:?} on a value of the hit"))),
                    };
                    return Ok(Value::from_hit(HitExpr::Unary(op, e.clone()), *ty));
                }
                if *op == UnaryOp::Neg {
                    if let Some(m) = super::state_space::negate(&v) {
                        return Ok(m);
                    }
                }
                unary(*op, v).ok_or_else(|| problem(span, format!("operator {op:?} is not evaluated for this operand")))
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let a = self.eval(lhs, env)?;
                if let (BinaryOp::And | BinaryOp::Or, Value::Bool(x)) = (op, &a) {
                    if (*op == BinaryOp::And) != *x {
                        return Ok(Value::Bool(*x));
                    }
                }
                let b = self.eval(rhs, env)?;
                // A matrix of the hit (`state::transform`) with a vector, a matrix, a scalar.
                if let Some(v) = super::state_space::matrix_binary(*op, &a, &b) {
                    return Ok(v);
                }
                if *op == BinaryOp::Mul && matches!(a, Value::Array(_)) {
                    return Err(problem(span, describe_binary(*op, &a, &b)));
                }
                if matches!(a, Value::Hit(..)) || matches!(b, Value::Hit(..)) {
                    return hit_binary(*op, &a, &b).ok_or_else(|| problem(span, describe_binary(*op, &a, &b)));
                }
                binary(*op, &a, &b).ok_or_else(|| problem(span, describe_binary(*op, &a, &b)))
            }
            ExprKind::Conditional { cond, then, otherwise } => match self.eval(cond, env)? {
                Value::Bool(true) => self.eval(then, env),
                Value::Bool(false) => self.eval(otherwise, env),
                Value::Hit(c, _) => {
                    let (a, b) = (self.eval(then, env)?, self.eval(otherwise, env)?);
                    if let Some(m) = super::state_space::select(&c, &a, &b) {
                        return Ok(m);
                    }
                    match (a.to_hit(), b.to_hit(), a.hit_type()) {
                        (Some(x), Some(y), Some(ty)) => Ok(Value::from_hit(HitExpr::Select(c, x, y), ty)),
                        _ => Err(problem(
                            span,
                            format!(
                                "a choice between {} and {} by a condition of the hit is not compiled",
                                kind(&a),
                                kind(&b)
                            ),
                        )),
                    }
                }
                v => Err(problem(cond.span, format!("condition is not a constant boolean ({})", kind(&v)))),
            },
            ExprKind::Member { base, field } => {
                let v = self.eval(base, env)?;
                if let Value::Hit(e, ty) = &v {
                    let lane = "xyzw".find(field.as_str()).filter(|i| field.len() == 1 && (*i as u8) < ty.width());
                    return match lane {
                        Some(i) => Ok(Value::from_hit(HitExpr::Lane(e.clone(), i as u8), HitType::Float)),
                        None => Err(problem(span, format!("`.{field}` of a value of the hit is not evaluated"))),
                    };
                }
                member(&v, field).ok_or_else(|| problem(span, format!("`.{field}` of {} is not evaluated", kind(&v))))
            }
            ExprKind::Index { base, index } => {
                let (v, i) = (self.eval(base, env)?, self.eval(index, env)?);
                // An index of the hit: a choice between the elements, columns or lanes.
                if let Value::Hit(at, HitType::Int) = &i {
                    return super::hit_index::element(&v, at).ok_or_else(|| {
                        problem(span, format!("{} indexed by an integer of the hit is not compiled", kind(&v)))
                    });
                }
                if let (Value::Hit(e, ty), Value::Int(i)) = (&v, &i) {
                    if (0..i64::from(ty.width())).contains(i) {
                        return Ok(Value::from_hit(HitExpr::Lane(e.clone(), *i as u8), HitType::Float));
                    }
                }
                match (&v, i) {
                    (Value::Array(a), Value::Int(i)) if i >= 0 && (i as usize) < a.len() => Ok(a[i as usize].clone()),
                    (Value::Vector(a), Value::Int(i)) if i >= 0 && (i as usize) < a.len() => {
                        Ok(Value::Float(a[i as usize]))
                    }
                    (Value::Matrix { .. }, Value::Int(i)) if i >= 0 => {
                        super::matrix::column(&v, i as usize).ok_or_else(|| problem(span, "column index out of range"))
                    }
                    _ => Err(problem(span, "index out of range or not constant")),
                }
            }
            ExprKind::Let { decls, body } => {
                for d in decls {
                    let v = match &d.init {
                        Some(init) => self.eval(init, env)?,
                        None => return Err(problem(span, format!("`{}` is declared without a value", d.name))),
                    };
                    env.locals.insert(d.id, v);
                }
                self.eval(body, env)
            }
            ExprKind::Sequence(_) | ExprKind::Assign { .. } => {
                Err(problem(span, "statements are not evaluated in material expressions"))
            }
        }
    }

    /// The values of `def`'s parameters for a call with `args` (evaluated in the caller's
    /// `env`): given by name or position, defaults (which may use earlier parameters) else.
    pub fn bind(&mut self, def: &Function, args: &[Arg], env: &mut Env, span: Span) -> Result<Vec<Value>, Problem> {
        let mut given: Vec<Option<Value>> = vec![None; def.params.len()];
        for (i, a) in args.iter().enumerate() {
            let slot = match &a.name {
                Some(n) => def.param(n).map(|(i, _)| i),
                None => Some(i),
            };
            let Some(slot) = slot.filter(|&s| s < given.len()) else {
                return Err(problem(a.span, format!("`{}` has no such parameter", def.name)));
            };
            given[slot] = Some(self.eval(&a.value, env)?);
        }
        self.complete(def, given, span)
    }

    /// Fills the parameters not given with their defaults, in order.
    pub fn complete(&mut self, def: &Function, given: Vec<Option<Value>>, span: Span) -> Result<Vec<Value>, Problem> {
        let mut callee = Env::default();
        for (p, g) in def.params.iter().zip(given) {
            let v = match (g, &p.default) {
                (Some(v), _) => v,
                (None, Some(d)) => self.eval(d, &mut callee)?,
                (None, None) => {
                    return Err(problem(
                        span,
                        format!("parameter `{}` of `{}` has no default and is not given", p.name, def.name),
                    ))
                }
            };
            callee.params.push(v);
        }
        Ok(callee.params)
    }

    /// Calls `def` (resolved as `res`) with bound `args`.
    pub fn call(&mut self, def: &Function, res: &Resolution, args: Vec<Value>, span: Span) -> Eval {
        if self.depth >= MAX_DEPTH {
            return Err(problem(span, format!("calls nested more than {MAX_DEPTH} deep (recursion?)")));
        }
        match &def.body {
            Body::Expr(body) => {
                self.depth += 1;
                let v = self.eval(body, &mut Env::with_params(args));
                self.depth -= 1;
                v
            }
            Body::Native => {
                let module = match res {
                    Resolution::Function { module, .. } | Resolution::Material { module, .. } => module.as_str(),
                    _ => "",
                };
                natives::call(module, def, &args, span, &mut self.leaves)
            }
            Body::Block(stmts) => {
                self.depth += 1;
                let v = self.call_block(def, stmts, args, span);
                self.depth -= 1;
                v
            }
        }
    }

    fn constant(&mut self, module: &str, name: &str, span: Span) -> Eval {
        let decl = self.set.module(module).and_then(|m| {
            m.decls.iter().find_map(|d| match d {
                Decl::Const(c) if c.name == name => Some(c.value.clone()),
                _ => None,
            })
        });
        match decl {
            Some(v) if self.depth < MAX_DEPTH => {
                self.depth += 1;
                let r = self.eval(&v, &mut Env::default());
                self.depth -= 1;
                r
            }
            _ => natives::constant(module, name)
                .ok_or_else(|| problem(span, format!("constant `{module}::{name}` has no value"))),
        }
    }

    /// A value of type `ty` built from `args`.
    pub(super) fn construct(&mut self, ty: &Type, args: &[Arg], env: &mut Env, span: Span) -> Eval {
        let mut values = Vec::with_capacity(args.len());
        if !matches!(ty, Type::Struct(_) | Type::Material) {
            for a in args {
                values.push(self.eval(&a.value, env)?);
            }
        }
        let floats = |vs: &[Value]| -> Option<Vec<f64>> {
            let mut out = Vec::new();
            for v in vs {
                match v {
                    Value::Vector(x) | Value::Matrix { data: x, .. } => out.extend(x),
                    Value::Color(c) => out.extend([c.x as f64, c.y as f64, c.z as f64]),
                    v => out.push(v.float()?),
                }
            }
            Some(out)
        };
        let bad = || problem(span, format!("`{ty}(…)` with these arguments is not evaluated"));
        if values.iter().any(|v| matches!(v, Value::Hit(..))) {
            if let Type::Array(..) = ty {
                // An array of which some elements vary (a measured curve's `curve_values`):
                // its elements as they are, read by what takes the array.
                return Ok(Value::Array(values));
            }
            if let Type::Matrix(_, c, r) = ty {
                return super::state_space::construct(*c, *r, &values).ok_or_else(bad);
            }
            return construct_hit(ty, &values).ok_or_else(bad);
        }
        match ty {
            Type::Texture(TextureShape::Tex2d) => {
                // `texture_2d()`: the invalid texture (lookups give black).
                let Some(Value::Str(name)) = values.first() else {
                    return if values.is_empty() { Ok(Value::Texture(None)) } else { Err(bad()) };
                };
                let dir = self.set.sources().file(span.file).dir().map(std::path::Path::to_path_buf);
                return match self.textures.file(name, dir.as_deref()) {
                    Ok(image) => Ok(Value::Texture(Some(image))),
                    Err(why) => Err(problem(span, why)),
                };
            }
            Type::Texture(shape @ (TextureShape::Tex3d | TextureShape::Cube)) => {
                // `texture_3d()`, `texture_cube()`: the invalid texture; a file: read once.
                let cube = *shape == TextureShape::Cube;
                let Some(Value::Str(name)) = values.first() else {
                    return match (values.is_empty(), cube) {
                        (true, false) => Ok(Value::Texture3d(None)),
                        (true, true) => Ok(Value::TextureCube(None)),
                        _ => Err(bad()),
                    };
                };
                let dir = self.set.sources().file(span.file).dir().map(std::path::Path::to_path_buf);
                let read = if cube {
                    self.textures.cube(name, dir.as_deref()).map(|c| Value::TextureCube(Some(c)))
                } else {
                    self.textures.volume(name, dir.as_deref()).map(|v| Value::Texture3d(Some(v)))
                };
                return read.map_err(|why| problem(span, why));
            }
            Type::Texture(TextureShape::Ptex) => {
                // `texture_ptex()`: the invalid texture; a file: a Ptex file, read once.
                let Some(Value::Str(name)) = values.first() else {
                    return if values.is_empty() { Ok(Value::TexturePtex(None)) } else { Err(bad()) };
                };
                let dir = self.set.sources().file(span.file).dir().map(std::path::Path::to_path_buf);
                return match self.textures.ptex(name, dir.as_deref()) {
                    Ok(ptex) => Ok(Value::TexturePtex(Some(ptex))),
                    Err(why) => Err(problem(span, why)),
                };
            }
            Type::LightProfile => {
                // `light_profile()`: the invalid profile; a file: an IES profile, read once.
                let Some(Value::Str(name)) = values.first() else {
                    return if values.is_empty() { Ok(Value::LightProfile(None)) } else { Err(bad()) };
                };
                let dir = self.set.sources().file(span.file).dir().map(std::path::Path::to_path_buf);
                return match self.textures.light_profile(name, dir.as_deref()) {
                    Ok(profile) => Ok(Value::LightProfile(Some(profile))),
                    Err(why) => Err(problem(span, why)),
                };
            }
            Type::BsdfMeasurement => {
                // `bsdf_measurement()`: the invalid measurement; a file: an MBSDF file, read once.
                let Some(Value::Str(name)) = values.first() else {
                    return if values.is_empty() { Ok(Value::BsdfMeasurement(None)) } else { Err(bad()) };
                };
                let dir = self.set.sources().file(span.file).dir().map(std::path::Path::to_path_buf);
                return match self.textures.bsdf_measurement(name, dir.as_deref()) {
                    Ok(m) => Ok(Value::BsdfMeasurement(Some(m))),
                    Err(why) => Err(problem(span, why)),
                };
            }
            Type::Matrix(_, c, r) => {
                let n = usize::from(*c) * usize::from(*r);
                return match floats(&values) {
                    Some(v) if v.is_empty() => Ok(super::matrix::diagonal(*c, *r, 0.0)),
                    Some(v) if v.len() == 1 => Ok(super::matrix::diagonal(*c, *r, v[0])),
                    Some(data) if data.len() == n => Ok(Value::Matrix { columns: *c, rows: *r, data }),
                    _ => Err(bad()),
                };
            }
            _ => {}
        }
        // An enum value converts to its integer.
        for v in values.iter_mut() {
            if let Value::Enum(_, i) = v {
                *v = Value::Int(*i);
            }
        }
        match ty {
            Type::Scalar(Scalar::Bool) => {
                values.first().and_then(Value::float).map(|f| Value::Bool(f != 0.0)).ok_or_else(bad)
            }
            Type::Scalar(Scalar::Int) => {
                values.first().and_then(Value::float).map(|f| Value::Int(f as i64)).ok_or_else(bad)
            }
            Type::Scalar(_) => match values.as_slice() {
                [] => Ok(Value::Float(0.0)),
                [v] => v.float().map(Value::Float).ok_or_else(bad),
                _ => Err(bad()),
            },
            Type::Color => match floats(&values).as_deref() {
                Some([]) => Ok(Value::Color(Rgb::ZERO)),
                Some([g]) => Ok(Value::Color(Rgb::splat(*g as f32))),
                Some([r, g, b]) => Ok(Value::Color(Rgb::new(*r as f32, *g as f32, *b as f32))),
                _ => Err(bad()),
            },
            Type::Vector(_, n) => match floats(&values) {
                Some(v) if v.is_empty() => Ok(Value::Vector(vec![0.0; *n as usize])),
                Some(v) if v.len() == 1 => Ok(Value::Vector(vec![v[0]; *n as usize])),
                Some(v) if v.len() == *n as usize => Ok(Value::Vector(v)),
                _ => Err(bad()),
            },
            Type::String => match values.as_slice() {
                [] => Ok(Value::Str(String::new())),
                [v @ Value::Str(_)] => Ok(v.clone()),
                _ => Err(bad()),
            },
            Type::Bsdf if values.is_empty() => Ok(Value::Bsdf(super::value::Df::Black)),
            Type::Edf if values.is_empty() => Ok(Value::Edf(super::value::Edf::Black)),
            Type::Vdf if values.is_empty() => {
                Ok(Value::Vdf(super::value::Vdf::HenyeyGreenstein(super::value::VdfNumber::Const(Rgb::ZERO))))
            }
            Type::HairBsdf if values.is_empty() => Ok(Value::HairBsdf),
            // `T[n]()`: n elements of T's default (an uninitialised `T[n] a;` likewise).
            Type::Array(elem, mdl_lang::ast::ArrayLen::Fixed(n)) if values.is_empty() && *n > 0 => {
                if *n > MAX_DEFAULT_ARRAY {
                    return Err(problem(span, format!("`{ty}()`: more than {MAX_DEFAULT_ARRAY} elements")));
                }
                let one = self.construct(elem, &[], env, span)?;
                Ok(Value::Array(vec![one; *n as usize]))
            }
            Type::Array(..) => Ok(Value::Array(values)),
            Type::Material => self.construct_struct("material", args, env, span),
            Type::Struct(name) => self.construct_struct(name, args, env, span),
            _ => Err(bad()),
        }
    }

    fn construct_struct(&mut self, name: &str, args: &[Arg], env: &mut Env, span: Span) -> Eval {
        let Some(decl) = self.set.struct_decl(name) else {
            return Err(problem(span, format!("struct `{name}` is not known")));
        };
        let mut fields: Vec<(String, Option<Value>)> = decl.fields.iter().map(|f| (f.name.clone(), None)).collect();
        for (i, a) in args.iter().enumerate() {
            let slot = match &a.name {
                Some(n) => fields.iter().position(|(f, _)| f == n),
                None => (i < fields.len()).then_some(i),
            };
            let Some(slot) = slot else {
                return Err(problem(a.span, format!("struct `{name}` has no such field")));
            };
            fields[slot].1 = Some(self.eval(&a.value, env)?);
        }
        let defaults: Vec<Option<Expr>> = decl.fields.iter().map(|f| f.default.clone()).collect();
        let mut out = Vec::with_capacity(fields.len());
        for ((field, v), default) in fields.into_iter().zip(defaults) {
            let v = match (v, default) {
                (Some(v), _) => v,
                (None, Some(d)) => self.eval(&d, &mut Env::default())?,
                (None, None) => return Err(problem(span, format!("field `{field}` of `{name}` has no default"))),
            };
            out.push((field, v));
        }
        let ty = if name == "material" {
            "material".to_string()
        } else {
            name.rsplit("::").next().unwrap_or(name).to_string()
        };
        Ok(Value::Struct(ty, out))
    }
}

/// A short description of a value's kind, for messages.
pub fn kind(v: &Value) -> &'static str {
    match v {
        Value::Bool(_) => "a bool",
        Value::Int(_) => "an int",
        Value::Float(_) => "a float",
        Value::Vector(_) => "a vector",
        Value::Matrix { .. } => "a matrix",
        Value::Color(_) => "a color",
        Value::Str(_) => "a string",
        Value::Enum(..) => "an enum value",
        Value::Struct(..) => "a struct",
        Value::Array(_) => "an array",
        Value::Bsdf(_) => "a bsdf",
        Value::Edf(_) => "an edf",
        Value::Vdf(_) => "a vdf",
        Value::HairBsdf => "a hair_bsdf",
        Value::Hit(..) => "a value of the shading point",
        Value::Texture(_) => "a texture",
        Value::Texture3d(_) => "a 3D texture",
        Value::TextureCube(_) => "a cube texture",
        Value::TexturePtex(_) => "a Ptex texture",
        Value::LightProfile(_) => "a light profile",
        Value::BsdfMeasurement(_) => "a bsdf measurement",
    }
}

fn describe_binary(op: BinaryOp, a: &Value, b: &Value) -> String {
    format!("operator {op:?} on {} and {} is not evaluated", kind(a), kind(b))
}

/// A binary operator on values one of which depends on the hit.
pub(super) fn hit_binary(op: BinaryOp, a: &Value, b: &Value) -> Option<Value> {
    use BinaryOp::*;
    let (x, y) = (a.to_hit()?, b.to_hit()?);
    let (ta, tb) = (a.hit_type()?, b.hit_type()?);
    let wider = if ta.width() >= tb.width() { ta } else { tb };
    let (hop, ty) = match op {
        Add => (HitBinOp::Add, wider),
        Sub => (HitBinOp::Sub, wider),
        Mul => (HitBinOp::Mul, wider),
        Div => (HitBinOp::Div, wider),
        Rem => (HitBinOp::Rem, wider),
        Lt => (HitBinOp::Lt, HitType::Bool),
        Le => (HitBinOp::Le, HitType::Bool),
        Gt => (HitBinOp::Gt, HitType::Bool),
        Ge => (HitBinOp::Ge, HitType::Bool),
        Eq => (HitBinOp::Eq, HitType::Bool),
        Ne => (HitBinOp::Ne, HitType::Bool),
        And => (HitBinOp::And, HitType::Bool),
        Or => (HitBinOp::Or, HitType::Bool),
        _ => return None,
    };
    // Integer division truncates.
    if op == Div && ta == HitType::Int && tb == HitType::Int {
        let q = super::hit::fold(HitExpr::Binary(hop, x, y));
        return Some(Value::from_hit(HitExpr::Math(super::hit::MathFn::Trunc, [q].into()), ty));
    }
    Some(Value::from_hit(HitExpr::Binary(hop, x, y), ty))
}

/// A number, vector or colour of type `ty` built from `values`, some of which depend on
/// the hit: one value fills every lane (a scalar) or converts; several fill the lanes in
/// order.
fn construct_hit(ty: &Type, values: &[Value]) -> Option<Value> {
    let target = super::value::HitType::of(ty)?;
    match values {
        [v] => {
            let t = v.hit_type()?;
            if t.width() == 1 || t.width() >= target.width() || matches!(target, HitType::Color) {
                let e = v.to_hit()?;
                let e = if target.width() == 1 && t.width() > 1 { HitExpr::Lane(e, 0) } else { (*e).clone() };
                // A number to `int` truncates towards zero, to `bool` is whether it is not 0.
                let e = match (target, t) {
                    (HitType::Int, HitType::Float) => {
                        HitExpr::Math(super::hit::MathFn::Trunc, [super::hit::fold(e)].into())
                    }
                    (HitType::Bool, HitType::Float | HitType::Int) => {
                        HitExpr::Binary(HitBinOp::Ne, super::hit::fold(e), Arc::new(HitExpr::Const(glam::Vec4::ZERO)))
                    }
                    _ => e,
                };
                return Some(Value::from_hit(e, target));
            }
            None
        }
        _ => {
            let mut parts = Vec::with_capacity(values.len());
            let mut lanes = 0;
            for v in values {
                let w = v.hit_type()?.width();
                lanes += w;
                parts.push((v.to_hit()?, w));
            }
            // The lanes of one vector in order (`color(r.x, r.y, r.z)`): that vector, read once.
            if let Some(whole) = in_order(&parts) {
                parts = vec![(whole, lanes)];
            }
            (lanes == target.width()).then(|| Value::from_hit(HitExpr::Compose(parts.into()), target))
        }
    }
}

/// The vector whose lanes 0, 1, … `parts` are, one lane each, if they are.
fn in_order(parts: &[(Arc<HitExpr>, u8)]) -> Option<Arc<HitExpr>> {
    let mut whole: Option<&Arc<HitExpr>> = None;
    for (k, (p, w)) in parts.iter().enumerate() {
        let HitExpr::Lane(x, i) = &**p else { return None };
        if *w != 1 || usize::from(*i) != k || whole.is_some_and(|y| !Arc::ptr_eq(x, y)) {
            return None;
        }
        whole = Some(x);
    }
    whole.cloned()
}

fn unary(op: UnaryOp, v: Value) -> Option<Value> {
    match (op, v) {
        (UnaryOp::Plus, v) => Some(v),
        (UnaryOp::Neg, Value::Int(i)) => Some(Value::Int(-i)),
        (UnaryOp::Neg, Value::Float(f)) => Some(Value::Float(-f)),
        (UnaryOp::Neg, Value::Color(c)) => Some(Value::Color(-c)),
        (UnaryOp::Neg, Value::Vector(v)) => Some(Value::Vector(v.iter().map(|x| -x).collect())),
        (UnaryOp::Neg, m @ Value::Matrix { .. }) => super::matrix::negate(&m),
        (UnaryOp::Not, Value::Bool(b)) => Some(Value::Bool(!b)),
        (UnaryOp::BitNot, Value::Int(i)) => Some(Value::Int(!i)),
        _ => None,
    }
}

/// Folds a binary operator on constants.
pub fn binary(op: BinaryOp, a: &Value, b: &Value) -> Option<Value> {
    use BinaryOp::*;
    let cmp = |x: f64, y: f64| -> Option<bool> {
        Some(match op {
            Lt => x < y,
            Le => x <= y,
            Gt => x > y,
            Ge => x >= y,
            Eq => x == y,
            Ne => x != y,
            _ => return None,
        })
    };
    match (a, b) {
        (Value::Matrix { .. }, _) | (_, Value::Matrix { .. }) => super::matrix::binary(op, a, b),
        (Value::Bool(x), Value::Bool(y)) => match op {
            And => Some(Value::Bool(*x && *y)),
            Or => Some(Value::Bool(*x || *y)),
            Eq => Some(Value::Bool(x == y)),
            Ne => Some(Value::Bool(x != y)),
            _ => None,
        },
        (Value::Enum(t, x), Value::Enum(u, y)) if t == u => match op {
            Eq => Some(Value::Bool(x == y)),
            Ne => Some(Value::Bool(x != y)),
            _ => None,
        },
        (Value::Int(x), Value::Int(y)) => {
            if let Some(c) = cmp(*x as f64, *y as f64) {
                return Some(Value::Bool(c));
            }
            Some(Value::Int(match op {
                Add => x.wrapping_add(*y),
                Sub => x.wrapping_sub(*y),
                Mul => x.wrapping_mul(*y),
                Div => x.checked_div(*y)?,
                Rem => x.checked_rem(*y)?,
                BitAnd => x & y,
                BitOr => x | y,
                BitXor => x ^ y,
                _ => return None,
            }))
        }
        (Value::Int(_) | Value::Float(_), Value::Int(_) | Value::Float(_)) => {
            let (x, y) = (a.float()?, b.float()?);
            if let Some(c) = cmp(x, y) {
                return Some(Value::Bool(c));
            }
            Some(Value::Float(arith(op, x, y)?))
        }
        (Value::Color(_), _) | (_, Value::Color(_)) => {
            let (x, y) = (a.color()?, b.color()?);
            match op {
                Eq => return Some(Value::Bool(x == y)),
                Ne => return Some(Value::Bool(x != y)),
                _ => {}
            }
            let f = |p: f32, q: f32| arith(op, p as f64, q as f64).map(|r| r as f32);
            Some(Value::Color(Rgb::new(f(x.x, y.x)?, f(x.y, y.y)?, f(x.z, y.z)?)))
        }
        (Value::Vector(_), _) | (_, Value::Vector(_)) => {
            let n = match (a, b) {
                (Value::Vector(v), _) | (_, Value::Vector(v)) => v.len(),
                _ => return None,
            };
            let comp = |v: &Value, i: usize| match v {
                Value::Vector(x) if x.len() == n => Some(x[i]),
                Value::Vector(_) => None,
                other => other.float(),
            };
            let mut out = Vec::with_capacity(n);
            for i in 0..n {
                out.push(arith(op, comp(a, i)?, comp(b, i)?)?);
            }
            Some(Value::Vector(out))
        }
        _ => None,
    }
}

fn arith(op: BinaryOp, x: f64, y: f64) -> Option<f64> {
    Some(match op {
        BinaryOp::Add => x + y,
        BinaryOp::Sub => x - y,
        BinaryOp::Mul => x * y,
        BinaryOp::Div => x / y,
        BinaryOp::Rem => x % y,
        _ => return None,
    })
}

fn member(v: &Value, field: &str) -> Option<Value> {
    match v {
        Value::Struct(..) => v.field(field).cloned(),
        Value::Vector(x) => {
            let i = "xyzw".find(field).filter(|_| field.len() == 1)?;
            x.get(i).map(|f| Value::Float(*f))
        }
        _ => None,
    }
}
