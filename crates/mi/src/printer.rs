//! The printer: syntax tree to `.mi` text.
//!
//! The output parses back to an equal tree (`parse(print(t)) == t`, spans aside). Names are
//! always quoted, floats always carry a point or exponent (so `4.` stays a float), binary
//! blocks are written as text, and `$include`s are written as `$include`s (their items are
//! not inlined).

use std::io::Write;

use crate::ast::*;

/// Prints items as `.mi` text.
pub fn print(items: &[Item]) -> Vec<u8> {
    let mut p = Printer { out: Vec::new(), indent: 0 };
    for item in items {
        p.item(item);
    }
    p.out
}

struct Printer {
    out: Vec<u8>,
    indent: usize,
}

/// The key of `$lookup` as written. The preprocessor reads the rest of the line as it is
/// (no escapes), drops a `#` comment outside quotes and trims spaces and quotes: the key
/// between bare quotes reads back the same in all but contrived cases (a quote, a `#` and
/// leading spaces together), where the bare key is tried too.
fn lookup_key(key: &str) -> String {
    let reads_back = |written: &str| {
        let line = format!("$lookup {written}");
        String::from_utf8_lossy(crate::lexer::directive_args(line.as_bytes())).trim_matches('"') == key
    };
    let quoted = format!("\"{key}\"");
    if reads_back(&quoted) || !reads_back(key) {
        quoted
    } else {
        key.to_string()
    }
}

/// A number as text. Infinities become ±1e999 (which read back as infinities); NaN, which
/// only binary data can hold and text cannot express, is written as -1e999.
fn float(v: f64) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else if v > 0.0 {
        "1e999".into()
    } else {
        "-1e999".into()
    }
}

fn float32(v: f32) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else {
        float(f64::from(v))
    }
}

fn num(n: Num) -> String {
    match n {
        Num::Int(i) => i.to_string(),
        Num::Float(f) => float(f),
    }
}

fn quote(s: &str) -> String {
    let mut q = String::with_capacity(s.len() + 2);
    q.push('"');
    for c in s.chars() {
        if c == '"' || c == '\\' {
            q.push('\\');
        }
        q.push(c);
    }
    q.push('"');
    q
}

fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 2 + 2);
    s.push('\'');
    for b in bytes {
        s.push_str(&format!("{b:02x}"));
    }
    s.push('\'');
    s
}

impl Printer {
    fn w(&mut self, s: &str) {
        self.out.extend_from_slice(s.as_bytes());
    }

    /// Starts a new line at the current indentation.
    fn line(&mut self) {
        if !self.out.is_empty() && self.out.last() != Some(&b'\n') {
            self.out.push(b'\n');
        }
        for _ in 0..self.indent {
            self.out.extend_from_slice(b"    ");
        }
    }

    fn sp(&mut self, s: &str) {
        if !matches!(self.out.last(), None | Some(b' ' | b'\n' | b'(' | b'[')) {
            self.out.push(b' ');
        }
        self.w(s);
    }

    fn name(&mut self, n: &Name) {
        let q = quote(&n.text);
        self.sp(&q);
    }

    fn block_open(&mut self, keyword: &str, name: &Name) {
        self.line();
        self.w(keyword);
        self.name(name);
        self.indent += 1;
    }

    fn block_close(&mut self, keyword: &str) {
        self.indent -= 1;
        self.line();
        self.w("end ");
        self.w(keyword);
        self.w("\n");
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Options(b) => self.block("options", b),
            Item::Camera(b) => self.block("camera", b),
            Item::Light(b) => self.block("light", b),
            Item::Lightprofile(b) => self.block("lightprofile", b),
            Item::Assembly(b) => self.block("assembly", b),
            Item::Colorprofile(b) => self.block("colorprofile", b),
            Item::Spectrum(s) => {
                self.block_open("spectrum", &s.name);
                for pair in s.values.chunks(2) {
                    self.line();
                    for v in pair {
                        self.sp(&float(*v));
                    }
                }
                self.block_close("spectrum");
            }
            Item::Material(m) => {
                self.block_open("material", &m.name);
                if let Some(list) = &m.shaders {
                    self.line();
                    self.shader_list(list);
                }
                for s in &m.stmts {
                    self.stmt(s);
                }
                self.block_close("material");
            }
            Item::Texture(t) => self.texture(t),
            Item::Object(o) => self.object(o),
            Item::Instance(i) => {
                self.block_open("instance", &i.name);
                match &i.target {
                    InstanceTarget::Element(n) => self.name(n),
                    InstanceTarget::Geometry(list) => {
                        self.sp("geometry");
                        self.shader_list(list);
                    }
                    InstanceTarget::None => {}
                }
                for s in &i.stmts {
                    self.stmt(s);
                }
                if let Some(params) = &i.params {
                    self.line();
                    self.params(params);
                }
                self.block_close("instance");
            }
            Item::Instgroup(g) => {
                self.block_open("instgroup", &g.name);
                // Members first: a flag attribute without a value (`attribute hide`) would
                // take a quoted member written after it as its value.
                for m in &g.members {
                    self.line();
                    self.name(m);
                }
                for s in &g.stmts {
                    self.stmt(s);
                }
                self.block_close("instgroup");
            }
            Item::Shader(s) => {
                self.line();
                self.w("shader");
                self.name(&s.name);
                self.shader_list(&s.list);
                self.w("\n");
            }
            Item::Declare(d) => self.declaration(d),
            Item::Data(d) => {
                self.line();
                self.w("data");
                self.name(&d.name);
                if let Some(tag) = d.tag {
                    self.sp(&format!("tag {tag}"));
                }
                match &d.body {
                    DataBody::Params { decl, params } => {
                        self.name(decl);
                        self.params(params);
                    }
                    DataBody::Bytes { size, pieces } => {
                        self.sp(&size.to_string());
                        self.sp("[");
                        self.indent += 1;
                        for p in pieces {
                            self.line();
                            self.w(&hex(p));
                        }
                        self.indent -= 1;
                        self.line();
                        self.w("]");
                    }
                    DataBody::File(f) => self.name(f),
                }
                self.w("\n");
            }
            Item::Gui(g) => {
                self.line();
                self.gui(g);
                self.w("\n");
            }
            Item::Namespace(ns) => {
                self.block_open("namespace", &ns.name);
                for i in &ns.items {
                    self.item(i);
                }
                self.block_close("namespace");
            }
            Item::Modified { prefixes, item } => {
                self.line();
                for p in prefixes {
                    self.kw(p);
                    self.w(" ");
                }
                // The element follows on the same line.
                let mut inner = Printer { out: Vec::new(), indent: self.indent };
                inner.item(item);
                let text = inner.out;
                let start = text.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(text.len());
                self.out.extend_from_slice(&text[start..]);
            }
            Item::Delete(n) => {
                self.line();
                self.w("delete");
                self.name(n);
                self.w("\n");
            }
            Item::Render(r) => {
                self.line();
                self.w("render");
                self.name(&r.root);
                self.name(&r.camera);
                self.name(&r.options);
                self.w("\n");
            }
            Item::Include(inc) => {
                self.line();
                self.w("$include ");
                if inc.angle {
                    self.w(&format!("<{}>", inc.path.text));
                } else {
                    self.w(&format!("\"{}\"", inc.path.text));
                }
                self.w("\n");
            }
            Item::Registry(r) => {
                self.block_open("registry", &r.key);
                for (field, value) in &r.entries {
                    self.line();
                    let f = quote(&field.text);
                    self.w(&f);
                    self.name(value);
                }
                self.block_close("registry");
            }
            Item::Command(Command::CodeBlock { text, .. }) => {
                self.line();
                self.w("$code\n");
                self.w(text);
                if !text.is_empty() && !text.ends_with('\n') {
                    self.w("\n");
                }
                self.w("$end code\n");
            }
            Item::Command(Command::Kw(k)) if k.key == "$lookup" => {
                self.line();
                self.w("$lookup ");
                if let Some(Arg::Name(n)) = k.args.first() {
                    self.w(&lookup_key(&n.text));
                }
                self.w("\n");
            }
            Item::Command(Command::Kw(k)) => {
                self.line();
                self.kw(k);
                self.w("\n");
            }
        }
    }

    fn block(&mut self, keyword: &str, b: &Block) {
        self.block_open(keyword, &b.name);
        for s in &b.stmts {
            self.stmt(s);
        }
        self.block_close(keyword);
    }

    fn stmt(&mut self, s: &Stmt) {
        self.line();
        match s {
            Stmt::Kw(k) => self.kw(k),
            Stmt::StringOption { name, value } => {
                self.name(name);
                self.value(value);
            }
            Stmt::Attribute(a) => {
                self.w("attribute");
                for m in &a.modifiers {
                    self.sp(&m.text);
                }
                self.sp(&a.ty.text);
                if let Some(n) = &a.name {
                    self.name(n);
                }
                match &a.value {
                    Some(Value::Str(v)) if a.name.is_none() => self.sp(&v.text),
                    Some(v) => self.value(v),
                    None => {}
                }
            }
            Stmt::Shaders(list) => self.shader_list(list),
            Stmt::Output(o) => {
                self.w("output");
                if let Some(cp) = &o.colorprofile {
                    self.sp("colorprofile");
                    self.name(cp);
                }
                if let Some(t) = &o.types {
                    self.name(t);
                }
                match &o.kind {
                    OutputKind::File { format, options, file } => {
                        self.name(format);
                        for opt in options {
                            self.sp("");
                            self.kw(opt);
                        }
                        self.name(file);
                    }
                    OutputKind::Shader(list) => self.shader_list(list),
                    OutputKind::Clear => {}
                }
            }
            Stmt::Framebuffer(fb) => {
                self.w("framebuffer");
                self.name(&fb.name);
                self.indent += 1;
                for f in &fb.fields {
                    self.stmt(f);
                }
                self.indent -= 1;
            }
        }
    }

    fn kw(&mut self, k: &KwStmt) {
        // `visible trace approximate …`: the flags come before the keyword.
        if let (true, [Arg::Approx(a)]) = (k.key == "approximate", k.args.as_slice()) {
            self.approximation(a, true);
            return;
        }
        self.sp(k.key);
        for a in &k.args {
            self.arg(a);
        }
    }

    fn arg(&mut self, a: &Arg) {
        match a {
            Arg::Bool(b) => self.sp(if *b { "on" } else { "off" }),
            Arg::Int(i) => self.sp(&i.to_string()),
            Arg::Float(f) => self.sp(&float(*f)),
            Arg::Num(n) => self.sp(&num(*n)),
            Arg::Name(n) => self.name(n),
            Arg::Word(w) => self.sp(w),
            Arg::Floats(v) => {
                for f in v {
                    self.sp(&float(*f));
                }
            }
            Arg::Shaders(list) => self.shader_list(list),
            Arg::ShaderArray(list) => {
                self.sp("[");
                for (i, item) in list.0.iter().enumerate() {
                    if i > 0 {
                        self.w(",");
                    }
                    self.shader_item(item);
                }
                self.sp("]");
            }
            Arg::Names(names) => {
                self.sp("[");
                for (i, n) in names.iter().enumerate() {
                    if i > 0 {
                        self.w(",");
                    }
                    self.name(n);
                }
                self.sp("]");
            }
            Arg::List(names) => {
                for (i, n) in names.iter().enumerate() {
                    if i > 0 {
                        self.w(",");
                    }
                    self.sp(&n.text);
                }
            }
            Arg::Tree(t) => self.tree(t),
            Arg::Approx(a) => self.approximation(a, false),
            Arg::Comma => self.w(","),
            Arg::Bytes(pieces) => {
                for p in pieces {
                    self.sp(&hex(p));
                }
            }
        }
    }

    fn shader_list(&mut self, list: &ShaderList) {
        for item in &list.0 {
            self.shader_item(item);
        }
    }

    fn shader_item(&mut self, item: &ShaderItem) {
        match item {
            ShaderItem::Call { decl, params, .. } => {
                self.name(decl);
                self.params(params);
            }
            ShaderItem::Ref(n) => {
                self.sp("=");
                self.name(n);
            }
            ShaderItem::Define { incremental, name, list } => {
                self.sp("=");
                if *incremental {
                    self.sp("incremental");
                }
                self.sp("shader");
                self.name(name);
                self.shader_list(list);
            }
        }
    }

    fn params(&mut self, params: &[Param]) {
        self.sp("(");
        self.indent += 1;
        for (i, p) in params.iter().enumerate() {
            if i > 0 {
                self.w(",");
            }
            if params.len() > 3 {
                self.line();
            }
            self.param(p);
        }
        self.indent -= 1;
        if params.len() > 3 {
            self.line();
        }
        self.w(")");
    }

    fn param(&mut self, p: &Param) {
        self.name(&p.name);
        if let Some(cp) = &p.colorprofile {
            self.sp("colorprofile");
            self.name(cp);
        }
        self.value(&p.value);
    }

    fn value(&mut self, v: &Value) {
        match v {
            Value::Null => self.sp("null"),
            Value::Bool(b) => self.sp(if *b { "on" } else { "off" }),
            Value::Num(n) => self.sp(&num(*n)),
            Value::Tuple(ns) => {
                for n in ns {
                    self.sp(&num(*n));
                }
            }
            Value::Str(n) => self.name(n),
            Value::Connect(n) => {
                self.sp("=");
                self.name(n);
            }
            Value::Interface(n) => {
                self.sp("= interface");
                self.name(n);
            }
            Value::Define(item) => self.shader_item(item),
            Value::Struct(fields) => {
                self.sp("{");
                for (i, f) in fields.iter().enumerate() {
                    if i > 0 {
                        self.w(",");
                    }
                    self.param(f);
                }
                self.sp("}");
            }
            Value::Array(elems) => {
                self.sp("[");
                for (i, e) in elems.iter().enumerate() {
                    if i > 0 {
                        self.w(",");
                    }
                    self.value(e);
                }
                self.sp("]");
            }
            Value::Seq(vs) => {
                for v in vs {
                    self.value(v);
                }
            }
        }
    }

    fn tree(&mut self, t: &TokenTree) {
        let (open, close, items) = match t {
            TokenTree::Atom(a) => {
                match a {
                    Atom::Word(w) => self.sp(w),
                    Atom::Str(s) => {
                        let q = quote(s);
                        self.sp(&q);
                    }
                    Atom::Num(n) => self.sp(&num(*n)),
                    Atom::Comma => self.w(","),
                    Atom::Equals => self.sp("="),
                    Atom::Percent => self.w("%"),
                }
                return;
            }
            TokenTree::Paren(items) => ("(", ")", items),
            TokenTree::Bracket(items) => ("[", "]", items),
            TokenTree::Brace(items) => ("{", "}", items),
        };
        self.sp(open);
        for i in items {
            self.tree(i);
        }
        self.sp(close);
    }

    fn gui(&mut self, g: &Gui) {
        self.w("gui");
        if let Some(n) = &g.name {
            self.name(n);
        }
        for t in &g.body {
            self.tree(t);
        }
    }

    fn texture(&mut self, t: &Texture) {
        self.line();
        for f in &t.flags {
            self.kw(f);
        }
        self.sp(match t.kind {
            TextureKind::Color => "color",
            TextureKind::Scalar => "scalar",
            TextureKind::Vector => "vector",
        });
        self.sp("texture");
        self.name(&t.name);
        if let Some(cp) = &t.colorprofile {
            self.sp("colorprofile");
            self.name(cp);
        }
        match &t.source {
            TextureSource::File { file, filetype, size } => {
                self.name(file);
                for f in filetype {
                    self.name(f);
                }
                if let Some(size) = size {
                    self.ints_bracket(size);
                }
            }
            TextureSource::Pixels { dims, pieces } => {
                self.ints_bracket(dims);
                for p in pieces {
                    self.line();
                    self.w(&hex(p));
                }
            }
            TextureSource::Shader(list) => self.shader_list(list),
        }
        self.w("\n");
    }

    fn ints_bracket(&mut self, v: &[i64]) {
        self.sp("[");
        for i in v {
            self.sp(&i.to_string());
        }
        self.sp("]");
    }

    fn declaration(&mut self, d: &Declaration) {
        self.line();
        self.w("declare");
        if !d.legacy {
            self.sp(match d.kind {
                DeclKind::Shader => "shader",
                DeclKind::Phenomenon => "phenomenon",
                DeclKind::Data => "data",
            });
        }
        self.indent += 1;
        if let Some(ret) = &d.ret {
            self.line();
            self.param_type(ret, true);
        }
        self.name(&d.name);
        self.sp("(");
        self.param_decls(&d.params);
        self.w(")");
        for item in &d.body {
            match item {
                DeclItem::Kw(k) => {
                    self.line();
                    self.kw(k);
                }
                DeclItem::Gui(g) => {
                    self.line();
                    self.gui(g);
                }
                DeclItem::Item(i) => self.item(i),
            }
        }
        self.indent -= 1;
        if d.legacy {
            self.w("\n");
        } else {
            self.line();
            self.w("end declare\n");
        }
    }

    fn param_decls(&mut self, decls: &[ParamDecl]) {
        self.indent += 1;
        for (i, p) in decls.iter().enumerate() {
            if i > 0 {
                self.w(",");
            }
            self.line();
            self.param_decl(p);
        }
        self.indent -= 1;
        if !decls.is_empty() {
            self.line();
        }
    }

    fn param_decl(&mut self, p: &ParamDecl) {
        let mut ty = &p.ty;
        while let ParamType::Array(inner) = ty {
            self.sp("array");
            ty = inner;
        }
        match ty {
            ParamType::Struct(fields) => {
                self.sp("struct");
                self.name(&p.name);
                self.sp("{");
                self.param_decls(fields);
                self.w("}");
            }
            _ => {
                self.param_type(ty, false);
                self.name(&p.name);
            }
        }
        if let Some(d) = &p.default {
            self.sp("default");
            self.value(d);
        }
    }

    fn param_type(&mut self, ty: &ParamType, ret: bool) {
        let word = match ty {
            ParamType::Boolean => "boolean",
            ParamType::Integer => "integer",
            ParamType::Scalar => "scalar",
            ParamType::String => "string",
            ParamType::Color => "color",
            ParamType::Vector => "vector",
            ParamType::Transform => "transform",
            ParamType::Shader => "shader",
            ParamType::Data => "data",
            ParamType::Light => "light",
            ParamType::Material => "material",
            ParamType::Geometry => "geometry",
            ParamType::Lightprofile => "lightprofile",
            ParamType::Spectrum => "spectrum",
            ParamType::ColorTexture => "color texture",
            ParamType::ScalarTexture => "scalar texture",
            ParamType::VectorTexture => "vector texture",
            ParamType::Struct(fields) if ret => {
                self.sp("struct {");
                self.param_decls(fields);
                self.w("}");
                return;
            }
            ParamType::Struct(_) | ParamType::Array(_) => unreachable!("handled by param_decl"),
        };
        self.sp(word);
    }

    // ----- geometry -----

    fn object(&mut self, o: &Object) {
        self.block_open("object", &o.name);
        for s in &o.stmts {
            self.stmt(s);
        }
        for b in &o.bases {
            self.line();
            self.w("basis");
            self.name(&b.name);
            if b.rational {
                self.sp("rational");
            }
            match &b.kind {
                BasisKind::Bezier(d) => self.sp(&format!("bezier {d}")),
                BasisKind::Taylor(d) => self.sp(&format!("taylor {d}")),
                BasisKind::Bspline(d) => self.sp(&format!("bspline {d}")),
                BasisKind::Cardinal => self.sp("cardinal"),
                BasisKind::Matrix { degree, step, values } => {
                    self.sp(&format!("matrix {degree} {step}"));
                    for v in values {
                        self.sp(&float(*v));
                    }
                }
            }
        }
        for g in &o.geometry {
            match g {
                Geometry::Group(g) => self.group(g, o.is_tagged()),
                Geometry::Trilist(t) => self.trilist(t),
                Geometry::Hair(h) => self.hair(h),
            }
        }
        self.block_close("object");
    }

    fn group(&mut self, g: &Group, tagged: bool) {
        self.line();
        self.w("group");
        if let Some(n) = &g.name {
            self.name(n);
        }
        if let Some(m) = g.merge {
            self.sp(&format!("merge {}", float(m)));
        }
        self.indent += 1;
        for v in &g.vectors {
            self.line();
            let _ = write!(self.out, "{} {} {}", float32(v[0]), float32(v[1]), float32(v[2]));
        }
        for (i, v) in g.vertices.iter().enumerate() {
            self.line();
            let _ = write!(self.out, "v {}", v.pos);
            if let Some(n) = v.normal {
                let _ = write!(self.out, " n {n}");
            }
            for a in g.vertex_attrs(i) {
                match a {
                    VertexAttr::Deriv { count, idx } => {
                        self.w(" d");
                        for i in &idx[..*count as usize] {
                            let _ = write!(self.out, " {i}");
                        }
                    }
                    VertexAttr::Tex { index, basis } => {
                        let _ = write!(self.out, " t {index}");
                        if let Some([u, v]) = basis {
                            let _ = write!(self.out, " {u} {v}");
                        }
                    }
                    VertexAttr::Motion(m) => {
                        let _ = write!(self.out, " m {m}");
                    }
                    VertexAttr::User(u) => {
                        let _ = write!(self.out, " u {u}");
                    }
                    VertexAttr::Feature { kind, arg } => {
                        self.w(match kind {
                            FeatureKind::Cusp => " cusp",
                            FeatureKind::Conic => " conic",
                            FeatureKind::Corner => " corner",
                            FeatureKind::Dart => " dart",
                        });
                        match arg {
                            Some(FeatureArg::Level(l)) => {
                                let _ = write!(self.out, " level {l}");
                            }
                            Some(FeatureArg::Value(v)) => {
                                let _ = write!(self.out, " {}", num(*v));
                            }
                            None => {}
                        }
                    }
                }
            }
        }
        let polys = &g.polygons;
        for (i, p) in polys.list.iter().enumerate() {
            self.line();
            self.w(match p.kind {
                PolygonKind::Convex => "c",
                PolygonKind::ConvexLegacy => "cp",
                PolygonKind::General => "p",
                PolygonKind::Strip => "strip",
                PolygonKind::Fan => "fan",
            });
            match p.material {
                PolygonMaterial::Inherit => {}
                PolygonMaterial::Named(m) => {
                    let q = quote(&polys.material_names[m as usize].text);
                    self.sp(&q);
                }
                PolygonMaterial::Label(l) => {
                    let _ = write!(self.out, " {l}");
                }
            }
            for (j, lp) in polys.loops(i).enumerate() {
                if j > 0 {
                    self.w(" hole");
                }
                for idx in lp {
                    let _ = write!(self.out, " {idx}");
                }
            }
        }
        for item in &g.items {
            match item {
                GroupItem::Subdivision(s) => self.subdivision(s, tagged),
                GroupItem::Ccmesh(c) => self.ccmesh(c),
                GroupItem::Curve(c) => {
                    self.line();
                    self.w("curve");
                    self.name(&c.name);
                    if c.rational {
                        self.sp("rational");
                    }
                    self.name(&c.basis);
                    self.knots(&c.params);
                    self.vertex_refs(&c.refs);
                    if let Some(sp) = &c.special {
                        self.sp("special");
                        self.special(sp);
                    }
                }
                GroupItem::SpaceCurve(s) => {
                    self.line();
                    self.w("space curve");
                    self.name(&s.name);
                    self.segments(&s.segments);
                }
                GroupItem::Surface(s) => self.surface(s),
                GroupItem::Connect(c) => {
                    self.line();
                    self.w("connect");
                    self.name(&c.first.0);
                    self.segments(std::slice::from_ref(&c.first.1));
                    self.name(&c.second.0);
                    self.segments(std::slice::from_ref(&c.second.1));
                }
                GroupItem::Approximate(a) => {
                    self.line();
                    self.approximation(a, true);
                }
            }
        }
        self.indent -= 1;
        self.line();
        self.w("end group");
    }

    fn face_material(&mut self, m: &FaceMaterial) {
        match m {
            FaceMaterial::Inherit => {}
            FaceMaterial::Named(n) => self.name(n),
            FaceMaterial::Label(l) => self.sp(&l.to_string()),
        }
    }

    fn derivatives(&mut self, ds: &[Derivative]) {
        for d in ds {
            self.line();
            self.w(&format!("derivative {}", d.order));
            if let Some(s) = d.space {
                self.w(&format!(" space {s}"));
            }
        }
    }

    fn subdivision(&mut self, s: &SubdivSurface, _tagged: bool) {
        self.line();
        self.w("subdivision surface");
        self.name(&s.name);
        self.indent += 1;
        if let Some(c) = &s.counts {
            self.line();
            self.w("polygon");
            for n in c {
                self.sp(&n.to_string());
            }
        }
        if let Some(ts) = &s.texture_space {
            self.line();
            self.w("texture space");
            self.arg(&Arg::Names(ts.clone()));
        }
        for f in &s.faces {
            self.line();
            self.w(if f.quad_keyword { "q" } else { "p" });
            self.face_material(&f.material);
            for i in &f.indices {
                self.sp(&i.to_string());
            }
            for e in &f.extras {
                match e {
                    FaceExtra::Crease { mask, values } => {
                        self.sp(&format!("crease {mask}"));
                        for v in values {
                            self.sp(&float(*v));
                        }
                    }
                    FaceExtra::Trim(m) => self.sp(&format!("trim {m}")),
                    FaceExtra::Hierarchy(h) => self.hira(h),
                }
            }
        }
        self.derivatives(&s.derivatives);
        self.indent -= 1;
        self.line();
        self.w("end subdivision surface");
    }

    fn hira(&mut self, body: &[Hira]) {
        self.sp("{");
        self.indent += 1;
        for h in body {
            self.line();
            match h {
                Hira::Material { child, material } => {
                    self.w(&format!("material {child}"));
                    self.face_material(material);
                }
                Hira::Detail { mask, indices } => {
                    self.w(&format!("detail {mask}"));
                    for i in indices {
                        self.sp(&i.to_string());
                    }
                }
                Hira::Crease { child, mask, values } => {
                    self.w(&format!("crease {child} {mask}"));
                    for v in values {
                        self.sp(&float(*v));
                    }
                }
                Hira::Trim { child, mask } => self.w(&format!("trim {child} {mask}")),
                Hira::Child { child, body } => {
                    self.w(&format!("child {child}"));
                    self.hira(body);
                }
            }
        }
        self.indent -= 1;
        self.line();
        self.w("}");
    }

    fn ccmesh(&mut self, c: &Ccmesh) {
        self.line();
        self.w("ccmesh");
        self.name(&c.name);
        self.sp(&format!("polygon {} vertex {}", c.polygon_count, c.vertex_count));
        self.indent += 1;
        let (mut start, mut cstart) = (0usize, 0usize);
        for f in &c.faces {
            self.line();
            self.w("p");
            match f.material {
                PolygonMaterial::Inherit => {}
                PolygonMaterial::Named(m) => {
                    let q = quote(&c.material_names[m as usize].text);
                    self.sp(&q);
                }
                PolygonMaterial::Label(l) => self.sp(&l.to_string()),
            }
            for i in &c.indices[start..f.end as usize] {
                self.sp(&i.to_string());
            }
            if f.has_crease {
                self.sp("crease");
                for v in &c.creases[cstart..f.crease_end as usize] {
                    self.sp(&float32(*v));
                }
            }
            start = f.end as usize;
            cstart = f.crease_end as usize;
        }
        self.derivatives(&c.derivatives);
        self.indent -= 1;
        self.line();
        self.w("end ccmesh");
    }

    fn knots(&mut self, params: &[f64]) {
        for p in params {
            // Knots must be written as floats: an integer would start the vertex list.
            self.sp(&float(*p));
        }
    }

    fn vertex_refs(&mut self, refs: &[VertexRef]) {
        for r in refs {
            self.sp(&r.index.to_string());
            match r.weight {
                Some((true, w)) => self.sp(&format!("w {}", float(w))),
                Some((false, w)) => self.sp(&float(w)),
                None => {}
            }
        }
    }

    fn segments(&mut self, segs: &[CurveSegment]) {
        for s in segs {
            self.name(&s.curve);
            self.sp(&float(s.t0));
            self.sp(&float(s.t1));
        }
    }

    fn special(&mut self, points: &[SpecialPoint]) {
        for p in points {
            match p {
                SpecialPoint::Vertex(i) => self.sp(&i.to_string()),
                SpecialPoint::MapsTo(a, b) => self.sp(&format!("{a} mapsto {b}")),
                SpecialPoint::Curve(s) => self.segments(std::slice::from_ref(s)),
            }
        }
    }

    fn surface_dir(&mut self, d: &SurfaceDir) {
        if d.rational {
            self.sp("rational");
        }
        self.name(&d.basis);
        if let Some((a, b)) = d.range {
            self.sp(&float(a));
            self.sp(&float(b));
        }
        self.knots(&d.params);
    }

    fn surface(&mut self, s: &Surface) {
        self.line();
        self.w("surface");
        self.name(&s.name);
        self.face_material(&s.material);
        self.indent += 1;
        self.line();
        self.surface_dir(&s.u);
        self.line();
        self.surface_dir(&s.v);
        self.line();
        self.vertex_refs(&s.refs);
        for e in &s.extras {
            self.line();
            match e {
                SurfaceExtra::Texture { volume, vector, u, v, refs } => {
                    if *volume {
                        self.sp("volume");
                    }
                    if *vector {
                        self.sp("vector");
                    }
                    self.sp("texture");
                    self.surface_dir(u);
                    self.surface_dir(v);
                    self.vertex_refs(refs);
                }
                SurfaceExtra::Derivative(n) => {
                    self.w("derivative");
                    for i in n {
                        self.sp(&i.to_string());
                    }
                }
                SurfaceExtra::Trim(segs) => {
                    self.w("trim");
                    self.segments(segs);
                }
                SurfaceExtra::Hole(segs) => {
                    self.w("hole");
                    self.segments(segs);
                }
                SurfaceExtra::Special(points) => {
                    self.w("special");
                    self.special(points);
                }
            }
        }
        self.indent -= 1;
    }

    fn approximation(&mut self, a: &Approximation, with_keyword: bool) {
        for f in &a.flags {
            self.sp(f);
        }
        if with_keyword {
            self.sp("approximate");
        }
        if let Some(t) = a.target {
            self.sp(t);
        }
        for term in &a.technique {
            match term {
                ApproxTerm::Word(w) => self.sp(w),
                ApproxTerm::Num(n) => self.sp(&num(*n)),
                ApproxTerm::Percent => self.w("%"),
            }
        }
        for n in &a.names {
            self.name(n);
        }
        if a.all {
            self.sp("all");
        }
    }

    fn trilist(&mut self, t: &Trilist) {
        self.line();
        self.w(&format!("trilist vertex {}", t.vertex_count));
        for l in &t.layout {
            match l {
                LayoutItem::P => self.w(" p"),
                LayoutItem::N => self.w(" n"),
                LayoutItem::D => self.w(" d"),
                LayoutItem::D2 => self.w(" d2"),
                LayoutItem::M(k) | LayoutItem::B(k) => {
                    self.w(if matches!(l, LayoutItem::M(_)) { " m" } else { " b" });
                    if let Some(k) = k {
                        self.w(&format!(" {k}"));
                    }
                }
                LayoutItem::T(d) | LayoutItem::U(d) => {
                    self.w(if matches!(l, LayoutItem::T(_)) { " t" } else { " u" });
                    for x in d {
                        self.w(&format!(" {x}"));
                    }
                }
            }
        }
        self.indent += 1;
        self.line();
        self.w(&format!("triangle {}", t.triangle_count));
        if let Some(b) = t.border_count {
            self.w(&format!(" border {b}"));
        }
        if let Some((a, b)) = t.data_sizes {
            self.w(&format!(" data {a} {b}"));
        }
        self.line();
        self.w("[");
        let per_line = t.floats_per_line().max(1);
        self.indent += 1;
        for line in t.floats.chunks(per_line) {
            self.line();
            for (i, f) in line.iter().enumerate() {
                if i > 0 {
                    self.w(" ");
                }
                self.w(&float32(*f));
            }
        }
        self.indent -= 1;
        self.line();
        self.w("]");
        self.triangles(&t.triangles);
        if let Some(b) = &t.border {
            self.triangles(b);
        }
        if let Some((a, b)) = &t.triangle_data {
            self.line();
            self.w("triangle data");
            self.word_block(a);
            self.word_block(b);
        }
        if let Some(top) = &t.topology {
            self.line();
            self.w("topology");
            self.word_block(top);
        }
        self.indent -= 1;
        self.line();
        self.w("end trilist");
    }

    fn word_block(&mut self, words: &[u32]) {
        self.sp("[");
        for w in words {
            self.sp(&w.to_string());
        }
        self.sp("]");
    }

    fn triangles(&mut self, tris: &Triangles) {
        self.line();
        self.w("[");
        self.indent += 1;
        let mut materials = tris.materials.iter().flatten().peekable();
        for (i, tri) in tris.indices.chunks(3).enumerate() {
            self.line();
            while let Some((at, name)) = materials.next_if(|(at, _)| *at as usize <= i) {
                let _ = at;
                let q = quote(&name.text);
                self.w(&q);
                self.w(" ");
            }
            if let Some(labels) = &tris.labels {
                let _ = write!(self.out, "{} ", labels[i]);
            }
            let _ = write!(self.out, "{}", tri.iter().map(u32::to_string).collect::<Vec<_>>().join(" "));
        }
        self.indent -= 1;
        self.line();
        self.w("]");
    }

    fn hair(&mut self, h: &Hair) {
        self.line();
        self.w("hair");
        self.indent += 1;
        for s in &h.header {
            self.line();
            self.kw(s);
        }
        self.line();
        self.w(&format!("scalar [ {} ]", h.scalars.len()));
        for chunk in h.scalars.chunks(8) {
            self.line();
            self.w(&chunk.iter().map(|f| float32(*f)).collect::<Vec<_>>().join(" "));
        }
        self.line();
        self.w(&format!("hair [ {} ]", h.offsets.len()));
        for chunk in h.offsets.chunks(16) {
            self.line();
            self.w(&chunk.iter().map(u32::to_string).collect::<Vec<_>>().join(" "));
        }
        self.indent -= 1;
        self.line();
        self.w("end hair");
    }
}
