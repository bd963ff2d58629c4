//! The printer: syntax tree to `.mi` text.
//!
//! The output parses back to an equal tree (`parse(print(t)) == t`, spans aside). Names are
//! always quoted, floats always carry a point or exponent (so `4.` stays a float), binary
//! blocks are written as text, and `$include`s are written as `$include`s (their items are
//! not inlined).

use crate::ast::*;

mod geometry;

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
}
