//! Keyword statements read by the tables of [`crate::grammar`], attributes and
//! approximations.

use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::grammar::{Rule, APPROX_FLAGS, APPROX_TARGETS, APPROX_WORDS, P};
use crate::lexer::Tok;

impl Parser {
    /// The rule of `tables` whose keywords are next (the longest such), if any.
    pub fn match_rule(&mut self, tables: &[&'static [Rule]]) -> PResult<Option<&'static Rule>> {
        let t = self.peek()?;
        if t.tok != Tok::Name {
            return Ok(None);
        }
        let first = self.bytes(&t).to_vec();
        let mut best: Option<(&'static Rule, usize)> = None;
        for table in tables {
            for rule in table.iter() {
                let words = rule.key.split(' ').count();
                if !rule.key.as_bytes().starts_with(&first)
                    || !(rule.key.len() == first.len() || rule.key.as_bytes()[first.len()] == b' ')
                {
                    continue;
                }
                if best.is_some_and(|(_, n)| n >= words) {
                    continue;
                }
                if self.at_words(rule.key)? {
                    best = Some((rule, words));
                }
            }
        }
        Ok(best.map(|(r, _)| r))
    }

    /// A keyword statement of one of `tables`, if one starts here.
    pub fn kw_stmt(&mut self, tables: &[&'static [Rule]]) -> PResult<Option<KwStmt>> {
        let Some(rule) = self.match_rule(tables)? else { return Ok(None) };
        Ok(Some(self.kw_stmt_by(rule)?))
    }

    /// Reads the statement of `rule` (its keywords are next).
    pub fn kw_stmt_by(&mut self, rule: &'static Rule) -> PResult<KwStmt> {
        let start = self.peek()?.span;
        for _ in rule.key.split(' ') {
            self.bump()?;
        }
        let mut args = Vec::new();
        for p in rule.args {
            self.pattern(p, &mut args).map_err(|d| {
                if d.message.starts_with("expected") {
                    Diagnostic { message: format!("{} (in '{}')", d.message, rule.key), ..d }
                } else {
                    d
                }
            })?;
        }
        let end = self.peek()?.span;
        Ok(KwStmt { key: rule.key, args, span: start.to(end.start()) })
    }

    /// Whether the next token can start pattern `p`.
    pub fn can_start(&mut self, p: &P) -> PResult<bool> {
        let t = self.peek()?;
        Ok(match p {
            P::Bool => t.tok == Tok::Name && matches!(self.bytes(&t), b"on" | b"off" | b"true" | b"false"),
            P::Int | P::Ints(..) => matches!(t.tok, Tok::Int(_)),
            P::Float | P::Num | P::Color | P::Matrix | P::Floats(..) => matches!(t.tok, Tok::Int(_) | Tok::Float(_)),
            P::Vec3 => matches!(t.tok, Tok::Int(_) | Tok::Float(_) | Tok::Binary),
            P::Name => matches!(t.tok, Tok::Str { .. }),
            P::NameNotCall => matches!(t.tok, Tok::Str { .. }) && self.peek_at(1)?.tok != Tok::LParen,
            P::CommaNames => matches!(t.tok, Tok::Str { .. } | Tok::Name),
            P::Words(ws) => t.tok == Tok::Name && ws.iter().any(|w| self.is(&t, w)),
            P::Shaders => self.at_shader_item()?,
            P::ShaderArray | P::Names => t.tok == Tok::LBracket,
            P::Tree => matches!(t.tok, Tok::LParen | Tok::LBracket | Tok::LBrace),
            P::Approx => true,
            P::Comma => t.tok == Tok::Comma,
            P::Bytes => t.tok == Tok::ByteStr,
            P::Opt(ps) => self.can_start(&ps[0])?,
            P::Alt(alts) => {
                for alt in alts.iter() {
                    if self.can_start_seq(alt)? {
                        return Ok(true);
                    }
                }
                false
            }
        })
    }

    /// Whether the next token can start the sequence `ps` (leading optional parts may be
    /// absent).
    fn can_start_seq(&mut self, ps: &[P]) -> PResult<bool> {
        for p in ps {
            if self.can_start(p)? {
                return Ok(true);
            }
            if !matches!(p, P::Opt(_) | P::Ints(0, _) | P::Floats(0, _)) {
                return Ok(false);
            }
        }
        Ok(false)
    }

    /// What a pattern expects, for messages.
    fn describe_pattern(p: &P) -> String {
        match p {
            P::Bool => "on or off".into(),
            P::Int | P::Ints(..) => "an integer".into(),
            P::Float | P::Num | P::Floats(..) => "a number".into(),
            P::Color => "a colour (3 or 4 numbers)".into(),
            P::Vec3 => "a vector (3 numbers)".into(),
            P::Matrix => "a matrix (16 numbers)".into(),
            P::Name | P::NameNotCall | P::CommaNames => "a name in \"quotes\"".into(),
            P::Words(ws) => ws.iter().map(|w| format!("'{w}'")).collect::<Vec<_>>().join(" or "),
            P::Shaders => "a shader".into(),
            P::ShaderArray | P::Names => "'['".into(),
            P::Tree => "'(' or '['".into(),
            P::Approx => "an approximation".into(),
            P::Comma => "','".into(),
            P::Bytes => "a byte string in 'single quotes'".into(),
            P::Opt(ps) => Self::describe_pattern(&ps[0]),
            P::Alt(alts) => alts.iter().map(|a| Self::describe_pattern(&a[0])).collect::<Vec<_>>().join(" or "),
        }
    }

    /// Reads pattern `p`, appending its arguments.
    fn pattern(&mut self, p: &P, out: &mut Vec<Arg>) -> PResult<()> {
        match p {
            P::Bool => match self.try_bool()? {
                Some(b) => out.push(Arg::Bool(b)),
                None => return self.expected("on or off"),
            },
            P::Int => out.push(Arg::Int(self.int()?)),
            P::Float => out.push(Arg::Float(self.float()?)),
            P::Num => out.push(Arg::Num(self.num()?)),
            P::Name | P::NameNotCall => out.push(Arg::Name(self.name()?)),
            P::Color => {
                let mut v = Vec::with_capacity(4);
                for _ in 0..3 {
                    v.push(self.float()?);
                }
                if self.at_number()? {
                    v.push(self.float()?);
                }
                out.push(Arg::Floats(v));
            }
            P::Vec3 => {
                if self.peek()?.tok == Tok::Binary {
                    let v = self.binary_vector()?;
                    out.push(Arg::Floats(v.iter().map(|&x| f64::from(x)).collect()));
                } else {
                    let v = vec![self.float()?, self.float()?, self.float()?];
                    out.push(Arg::Floats(v));
                }
            }
            P::Matrix => {
                let mut v = Vec::with_capacity(16);
                for _ in 0..16 {
                    v.push(self.float()?);
                }
                out.push(Arg::Floats(v));
            }
            P::Ints(min, max) => {
                let mut n = 0;
                while n < *max && matches!(self.peek()?.tok, Tok::Int(_)) {
                    out.push(Arg::Int(self.int()?));
                    n += 1;
                }
                if n < *min {
                    return self.expected(&if *min == 1 {
                        "an integer".to_string()
                    } else {
                        format!("{min} integers")
                    });
                }
            }
            P::Floats(min, max) => {
                let mut n = 0;
                while n < *max && self.at_number()? {
                    out.push(Arg::Float(self.float()?));
                    n += 1;
                }
                if n < *min {
                    return self.expected(&if *min == 1 { "a number".to_string() } else { format!("{min} numbers") });
                }
            }
            P::Words(ws) => {
                let t = self.peek()?;
                match ws.iter().find(|w| self.is(&t, w)) {
                    Some(w) => {
                        self.bump()?;
                        out.push(Arg::Word(w));
                    }
                    None => return self.expected(&Self::describe_pattern(p)),
                }
            }
            P::Shaders => out.push(Arg::Shaders(self.shader_list()?)),
            P::ShaderArray => {
                let open = self.expect_tok(Tok::LBracket, "'['")?;
                let mut items = Vec::new();
                while !self.eat_tok(Tok::RBracket)? {
                    if self.peek()?.tok == Tok::Eof {
                        return Err(Diagnostic::error(open, "shader array is not closed by ']'"));
                    }
                    items.push(self.shader_item()?);
                    if !self.eat_tok(Tok::Comma)? && self.peek()?.tok != Tok::RBracket {
                        return self.expected("',' or ']'");
                    }
                }
                out.push(Arg::ShaderArray(ShaderList(items)));
            }
            P::Names => out.push(Arg::Names(self.name_list()?)),
            P::CommaNames => {
                let mut names = vec![self.name()?];
                while self.eat_tok(Tok::Comma)? {
                    names.push(self.name()?);
                }
                out.push(Arg::List(names));
            }
            P::Tree => out.push(Arg::Tree(self.token_tree()?)),
            P::Approx => {
                let start = self.peek()?.span;
                out.push(Arg::Approx(Box::new(self.approximation(Vec::new(), start)?)));
            }
            P::Comma => {
                self.expect_tok(Tok::Comma, "','")?;
                out.push(Arg::Comma);
            }
            P::Bytes => {
                let mut pieces = Vec::new();
                while self.peek()?.tok == Tok::ByteStr {
                    pieces.push(self.byte_string()?);
                }
                if pieces.is_empty() {
                    return self.expected("a byte string in 'single quotes'");
                }
                out.push(Arg::Bytes(pieces));
            }
            P::Opt(ps) => {
                if self.can_start(&ps[0])? {
                    for p in ps.iter() {
                        self.pattern(p, out)?;
                    }
                }
            }
            P::Alt(alts) => {
                for alt in alts.iter() {
                    if self.can_start_seq(alt)? {
                        for p in alt.iter() {
                            self.pattern(p, out)?;
                        }
                        return Ok(());
                    }
                }
                return self.expected(&Self::describe_pattern(p));
            }
        }
        Ok(())
    }

    /// `[ "a", "b" ]` (commas optional).
    pub fn name_list(&mut self) -> PResult<Vec<Name>> {
        let open = self.expect_tok(Tok::LBracket, "'['")?;
        let mut names = Vec::new();
        loop {
            let t = self.peek()?;
            match t.tok {
                Tok::RBracket => {
                    self.bump()?;
                    return Ok(names);
                }
                Tok::Comma => {
                    self.bump()?;
                }
                Tok::Str { .. } | Tok::Name => names.push(self.name()?),
                Tok::Eof => return Err(Diagnostic::error(open, "list is not closed by ']'")),
                _ => return self.expected("a name or ']'"),
            }
        }
    }

    /// `attribute [override] {const|global} type "name" value`, or a flag form.
    pub fn attribute(&mut self) -> PResult<Attribute> {
        let start = self.expect("attribute")?;
        let mut modifiers = Vec::new();
        while self.at("override")? || self.at("const")? || self.at("global")? {
            modifiers.push(self.name()?);
        }
        if self.peek()?.tok != Tok::Name {
            return self.expected("an attribute type such as 'scalar' or 'boolean'");
        }
        let ty = self.name()?;
        let (name, value) = if self.at_str()? {
            let name = self.name()?;
            (Some(name), Some(self.stmt_value()?))
        } else if let Some(b) = self.try_bool()? {
            (None, Some(Value::Bool(b)))
        } else if self.at_number()? {
            (None, Some(Value::Num(self.num()?)))
        } else if ty.text == "face" {
            (None, Some(Value::Str(self.name()?)))
        } else {
            (None, None)
        };
        let end = self.peek()?.span;
        Ok(Attribute { modifiers, ty, name, value, span: start.to(end.start()) })
    }

    /// Whether `[flags] approximate` starts here.
    pub fn at_approximate(&mut self) -> PResult<bool> {
        let mut i = 0;
        loop {
            let t = self.peek_at(i)?;
            if self.is(&t, "approximate") {
                return Ok(true);
            }
            if !APPROX_FLAGS.iter().any(|f| self.is(&t, f)) {
                return Ok(false);
            }
            i += 1;
        }
    }

    /// `[flags] approximate [target] technique… names… [all]`.
    pub fn approximate_stmt(&mut self) -> PResult<Approximation> {
        let start = self.peek()?.span;
        let mut flags = Vec::new();
        while !self.at("approximate")? {
            let t = self.bump()?;
            flags.extend(APPROX_FLAGS.iter().find(|f| self.is(&t, f)));
        }
        self.expect("approximate")?;
        self.approximation(flags, start)
    }

    /// The part of an approximation after `approximate`.
    pub fn approximation(&mut self, flags: Vec<&'static str>, start: crate::source::Span) -> PResult<Approximation> {
        let mut target = None;
        for t in APPROX_TARGETS {
            if self.at_words(t)? {
                for _ in t.split(' ') {
                    self.bump()?;
                }
                target = Some(*t);
                break;
            }
        }
        let mut technique = Vec::new();
        loop {
            let t = self.peek()?;
            match t.tok {
                Tok::Int(_) | Tok::Float(_) => technique.push(ApproxTerm::Num(self.num()?)),
                Tok::Percent => {
                    self.bump()?;
                    technique.push(ApproxTerm::Percent);
                }
                Tok::Name => {
                    let Some(w) = APPROX_WORDS.iter().find(|w| self.is(&t, w)) else { break };
                    // `max`, `min` and `samples` take a number; otherwise they start
                    // another statement (`max displace`).
                    if matches!(*w, "max" | "min" | "samples")
                        && !matches!(self.peek_at(1)?.tok, Tok::Int(_) | Tok::Float(_))
                    {
                        break;
                    }
                    self.bump()?;
                    technique.push(ApproxTerm::Word(w));
                }
                _ => break,
            }
        }
        if technique.is_empty() && target.is_none() {
            return self.expected("an approximation technique such as 'parametric 2'");
        }
        let mut names = Vec::new();
        while self.at_str()? {
            names.push(self.name()?);
        }
        let all = self.eat("all")?;
        let end = self.peek()?.span;
        Ok(Approximation { flags, target, technique, names, all, span: start.to(end.start()) })
    }
}
