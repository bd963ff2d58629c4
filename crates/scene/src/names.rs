//! The element table: every named element defined before the chosen `render` statement,
//! with `namespace` prefixes, `incremental` re-opening and `delete` applied.

use std::collections::HashMap;

use mi::ast::*;
use mi::{Diagnostic, Span};

/// A named element's definitions: the first one, then incremental changes in order.
#[derive(Clone, Debug)]
pub enum Def<'a> {
    /// `options`
    Options(Vec<&'a Block>),
    /// `camera`
    Camera(Vec<&'a Block>),
    /// `light`
    Light(Vec<&'a Block>),
    /// `material`
    Material(Vec<&'a Material>),
    /// `texture`
    Texture(&'a Texture),
    /// `object`
    Object(Vec<&'a Object>),
    /// `instance`
    Instance(Vec<&'a Instance>),
    /// `instgroup`
    Instgroup(Vec<&'a Instgroup>),
    /// `shader`
    Shader(Vec<&'a ShaderDef>),
    /// `data`
    Data(&'a Data),
    /// `lightprofile`
    Lightprofile(Vec<&'a Block>),
    /// `assembly`
    Assembly(&'a Block),
    /// `colorprofile`
    Colorprofile(&'a Block),
    /// `spectrum`
    Spectrum(&'a Spectrum),
}

impl Def<'_> {
    /// The element keyword, for messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Def::Options(_) => "options",
            Def::Camera(_) => "camera",
            Def::Light(_) => "light",
            Def::Material(_) => "material",
            Def::Texture(_) => "texture",
            Def::Object(_) => "object",
            Def::Instance(_) => "instance",
            Def::Instgroup(_) => "instgroup",
            Def::Shader(_) => "shader",
            Def::Data(_) => "data",
            Def::Lightprofile(_) => "lightprofile",
            Def::Assembly(_) => "assembly",
            Def::Colorprofile(_) => "colorprofile",
            Def::Spectrum(_) => "spectrum",
        }
    }
}

/// One entry of the table.
#[derive(Clone, Debug)]
pub struct Element<'a> {
    /// Its definitions.
    pub def: Def<'a>,
    /// The namespace it was defined in (`"a::b::"`, empty at the top).
    pub scope: String,
    /// Where its (first) definition is.
    pub span: Span,
}

/// All elements and declarations in scope at a `render` statement.
#[derive(Debug, Default)]
pub struct Table<'a> {
    /// Elements by full name (`namespace::name`).
    pub elements: HashMap<String, Element<'a>>,
    /// Shader, phenomenon and data declarations by name.
    pub declarations: HashMap<String, &'a Declaration>,
    /// MDL modules included.
    pub mdl_modules: Vec<String>,
    /// Where each of `mdl_modules` was included (same order).
    pub mdl_module_spans: Vec<Span>,
    /// Order in which elements were first defined (full names).
    pub order: Vec<String>,
}

/// The `render` statement chosen and the namespace it was written in.
pub struct RenderAt<'a> {
    /// The statement.
    pub render: &'a Render,
    /// Its namespace.
    pub scope: String,
}

impl<'a> Table<'a> {
    /// Builds the table from `items` up to the `frame`-th `render` statement (0-based),
    /// returning that statement, or `None` if there are not that many.
    pub fn collect(items: &'a [Item], frame: usize, diags: &mut Vec<Diagnostic>) -> (Table<'a>, Option<RenderAt<'a>>) {
        let mut table = Table::default();
        let mut renders = 0;
        let mut found = None;
        table.walk(items, "", frame, &mut renders, &mut found, diags);
        (table, found)
    }

    fn walk(
        &mut self,
        items: &'a [Item],
        scope: &str,
        frame: usize,
        renders: &mut usize,
        found: &mut Option<RenderAt<'a>>,
        diags: &mut Vec<Diagnostic>,
    ) {
        for item in items {
            if found.is_some() {
                return;
            }
            match item {
                Item::Include(inc) => {
                    if inc.target == mi::IncludeTarget::Mdl {
                        self.mdl_modules.push(inc.path.text.clone());
                        self.mdl_module_spans.push(inc.path.span);
                    }
                    self.walk(&inc.items, scope, frame, renders, found, diags);
                }
                Item::Namespace(ns) => {
                    let inner = format!("{scope}{}::", ns.name.text);
                    self.walk(&ns.items, &inner, frame, renders, found, diags);
                }
                Item::Modified { prefixes, item } => {
                    let incremental = prefixes.iter().any(|p| p.key == "incremental");
                    self.define(item, scope, incremental, diags);
                }
                Item::Delete(name) => match self.resolve_name(&name.text, scope) {
                    Some(full) => {
                        self.elements.remove(&full);
                    }
                    None => diags
                        .push(Diagnostic::warning(name.span, format!("'delete' of unknown element '{}'", name.text))),
                },
                Item::Render(r) => {
                    if *renders == frame {
                        *found = Some(RenderAt { render: r, scope: scope.to_string() });
                    }
                    *renders += 1;
                }
                Item::Declare(d) => {
                    self.declarations.insert(d.name.text.clone(), d);
                }
                other => self.define(other, scope, false, diags),
            }
        }
    }

    /// Adds an element definition (or an incremental change of one).
    fn define(&mut self, item: &'a Item, scope: &str, incremental: bool, diags: &mut Vec<Diagnostic>) {
        let (name, def, span) = match item {
            Item::Options(b) => (&b.name, Def::Options(vec![b]), b.span),
            Item::Camera(b) => (&b.name, Def::Camera(vec![b]), b.span),
            Item::Light(b) => (&b.name, Def::Light(vec![b]), b.span),
            Item::Material(m) => (&m.name, Def::Material(vec![m]), m.span),
            Item::Texture(t) => (&t.name, Def::Texture(t), t.span),
            Item::Object(o) => (&o.name, Def::Object(vec![o]), o.span),
            Item::Instance(i) => (&i.name, Def::Instance(vec![i]), i.span),
            Item::Instgroup(g) => (&g.name, Def::Instgroup(vec![g]), g.span),
            Item::Shader(s) => (&s.name, Def::Shader(vec![s]), s.span),
            Item::Data(d) => (&d.name, Def::Data(d), d.span),
            Item::Lightprofile(b) => (&b.name, Def::Lightprofile(vec![b]), b.span),
            Item::Assembly(b) => (&b.name, Def::Assembly(b), b.span),
            Item::Colorprofile(b) => (&b.name, Def::Colorprofile(b), b.span),
            Item::Spectrum(s) => (&s.name, Def::Spectrum(s), s.span),
            Item::Declare(d) => {
                self.declarations.insert(d.name.text.clone(), d);
                return;
            }
            _ => return,
        };
        let full = format!("{scope}{}", name.text.trim_start_matches("::"));
        if incremental {
            if let Some(existing) = self.elements.get_mut(&full) {
                let ok = match (&mut existing.def, def) {
                    (Def::Options(a), Def::Options(b))
                    | (Def::Camera(a), Def::Camera(b))
                    | (Def::Light(a), Def::Light(b))
                    | (Def::Lightprofile(a), Def::Lightprofile(b)) => {
                        a.extend(b);
                        true
                    }
                    (Def::Material(a), Def::Material(b)) => {
                        a.extend(b);
                        true
                    }
                    (Def::Object(a), Def::Object(b)) => {
                        a.extend(b);
                        true
                    }
                    (Def::Instance(a), Def::Instance(b)) => {
                        a.extend(b);
                        true
                    }
                    (Def::Instgroup(a), Def::Instgroup(b)) => {
                        a.extend(b);
                        true
                    }
                    (Def::Shader(a), Def::Shader(b)) => {
                        a.extend(b);
                        true
                    }
                    (
                        slot @ (Def::Texture(_)
                        | Def::Data(_)
                        | Def::Assembly(_)
                        | Def::Colorprofile(_)
                        | Def::Spectrum(_)),
                        new,
                    ) if slot.kind() == new.kind() => {
                        *slot = new;
                        true
                    }
                    _ => false,
                };
                if !ok {
                    diags.push(Diagnostic::error(
                        name.span,
                        format!("'incremental' changes '{}' into another kind of element", name.text),
                    ));
                }
                return;
            }
        }
        if !self.elements.contains_key(&full) {
            self.order.push(full.clone());
        }
        self.elements.insert(full, Element { def, scope: scope.to_string(), span });
    }

    /// The full name `name` refers to from namespace `scope`: innermost namespace first,
    /// `::name` meaning the top level.
    pub fn resolve_name(&self, name: &str, scope: &str) -> Option<String> {
        if let Some(global) = name.strip_prefix("::") {
            return self.elements.contains_key(global).then(|| global.to_string());
        }
        let mut prefix = scope;
        loop {
            let full = format!("{prefix}{name}");
            if self.elements.contains_key(&full) {
                return Some(full);
            }
            if prefix.is_empty() {
                return None;
            }
            // Drop the innermost namespace: "a::b::" -> "a::".
            let trimmed = &prefix[..prefix.len() - 2];
            prefix = match trimmed.rfind("::") {
                Some(i) => &prefix[..i + 2],
                None => "",
            };
        }
    }

    /// The element `name` refers to from `scope`, with its full name.
    pub fn get(&self, name: &str, scope: &str) -> Option<(String, &Element<'a>)> {
        let full = self.resolve_name(name, scope)?;
        let e = self.elements.get(&full)?;
        Some((full, e))
    }

    /// The element `name` refers to, or an error "unknown {what} 'name'" at the reference.
    pub fn lookup(&self, name: &Name, scope: &str, what: &str) -> Result<(String, &Element<'a>), Diagnostic> {
        self.get(&name.text, scope)
            .ok_or_else(|| Diagnostic::error(name.span, format!("unknown {what} '{}'", name.text)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str, _frame: usize) -> (Vec<Item>, Vec<Diagnostic>) {
        let parsed = mi::parse_str("t.mi", text);
        assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
        (parsed.items, Vec::new())
    }

    #[test]
    fn namespaces_resolve_innermost_first() {
        let (items, mut diags) = table(
            "shader \"s\" \"x\" ()\nnamespace \"a\"\n shader \"s\" \"y\" ()\n namespace \"b\"\n  shader \"t\" \"z\" ()\n end namespace\nend namespace\nrender \"r\" \"c\" \"o\"\n",
            0,
        );
        let (t, render) = Table::collect(&items, 0, &mut diags);
        assert!(render.is_some());
        assert_eq!(t.resolve_name("s", "a::b::").as_deref(), Some("a::s"));
        assert_eq!(t.resolve_name("s", "").as_deref(), Some("s"));
        assert_eq!(t.resolve_name("::s", "a::").as_deref(), Some("s"));
        assert_eq!(t.resolve_name("t", "a::").as_deref(), None);
        assert_eq!(t.resolve_name("b::t", "a::").as_deref(), Some("a::b::t"));
    }

    #[test]
    fn incremental_delete_and_frames() {
        let text = "options \"o\" samples 0 1 end options\nrender \"r\" \"c\" \"o\"\n\
                    incremental options \"o\" samples 1 2 end options\nshader \"gone\" \"x\" ()\ndelete \"gone\"\nrender \"r\" \"c\" \"o\"\n";
        let (items, mut diags) = table(text, 0);
        let (t0, _) = Table::collect(&items, 0, &mut diags);
        let (t1, r1) = Table::collect(&items, 1, &mut diags);
        assert!(r1.is_some());
        assert!(matches!(&t0.elements["o"].def, Def::Options(v) if v.len() == 1));
        assert!(matches!(&t1.elements["o"].def, Def::Options(v) if v.len() == 2));
        assert!(!t1.elements.contains_key("gone"));
        let (_, r2) = Table::collect(&items, 2, &mut diags);
        assert!(r2.is_none());
    }
}
