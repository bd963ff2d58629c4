//! Objects: `object … end object` with its statements and bases, dispatching to the
//! geometry it holds (groups in [`super::group`], trilists in [`super::trilist`], hair in
//! [`super::hair`]), and the helpers those share.
//!
//! Vectors, vertex lines, polygons and trilist data are read straight from the lexer
//! (no token objects), which is what lets million-polygon files parse at hundreds of MB/s.

use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::grammar;
use crate::lexer::{Lexer, Tok};
use crate::source::Span;

/// Reserves room for `count` items of which each needs at least `min_bytes` of text, never
/// more than the rest of the file could hold: a hostile count cannot allocate unboundedly.
pub(super) fn reserve_for<T>(v: &mut Vec<T>, count: usize, remaining_bytes: usize, min_bytes: usize) {
    v.reserve(count.min(remaining_bytes / min_bytes.max(1) + 1));
}

impl Parser {
    /// The lexer for a fast path, or an error if buffered tokens straddle an include.
    pub(super) fn lexer(&mut self) -> PResult<&mut Lexer> {
        let span = self.peek()?.span;
        self.ts
            .fast_lexer()
            .ok_or_else(|| Diagnostic::error(span, "geometry data may not straddle an '$include' boundary"))
    }

    /// `object "name" … end object`.
    pub fn object(&mut self) -> PResult<Object> {
        let start = self.expect("object")?;
        self.ends.push("object");
        // The name is optional in the grammar: an object may start with its flags.
        let next = self.peek()?;
        let unnamed = next.tok == Tok::Name
            && (["group", "trilist", "hair", "basis", "end", "attribute"].iter().any(|w| self.is(&next, w))
                || self.match_rule(&[grammar::OBJECT])?.is_some());
        let name = if unnamed { Name { text: String::new(), span: next.span.start() } } else { self.name()? };
        let mut object = Object { name, stmts: Vec::new(), bases: Vec::new(), geometry: Vec::new(), span: start };
        loop {
            self.not_eof("object", start)?;
            if self.at_end("object")? {
                let end = self.expect_end("object")?;
                self.ends.pop();
                object.span = start.to(end);
                return Ok(object);
            }
            let t = self.peek()?;
            if self.is(&t, "group") {
                let tagged = object.is_tagged();
                object.geometry.push(Geometry::Group(self.group(tagged)?));
            } else if self.is(&t, "trilist") {
                let tagged = object.is_tagged();
                object.geometry.push(Geometry::Trilist(self.trilist(tagged)?));
            } else if self.is(&t, "hair") {
                object.geometry.push(Geometry::Hair(self.hair()?));
            } else if self.is(&t, "basis") {
                object.bases.push(self.basis()?);
            } else if self.is(&t, "attribute") {
                object.stmts.push(Stmt::Attribute(self.attribute()?));
            } else if self.at_approximate()? {
                let a = self.approximate_stmt()?;
                let span = a.span;
                object.stmts.push(Stmt::Kw(KwStmt { key: "approximate", args: vec![Arg::Approx(Box::new(a))], span }));
            } else if let Some(s) = self.kw_stmt(&[grammar::OBJECT])? {
                object.stmts.push(Stmt::Kw(s));
            } else {
                return Err(Diagnostic::error(t.span, format!("unknown object statement {}", self.describe(&t))));
            }
        }
    }

    /// `basis "name" [rational] bezier N | taylor N | bspline N | cardinal | matrix D S values…`
    fn basis(&mut self) -> PResult<Basis> {
        let start = self.expect("basis")?;
        let name = self.name()?;
        let rational = self.eat("rational")?;
        let t = self.peek()?;
        let kind = match self.bytes(&t) {
            b"bezier" => {
                self.bump()?;
                BasisKind::Bezier(self.int()?)
            }
            b"taylor" => {
                self.bump()?;
                BasisKind::Taylor(self.int()?)
            }
            b"bspline" => {
                self.bump()?;
                BasisKind::Bspline(self.int()?)
            }
            b"cardinal" => {
                self.bump()?;
                BasisKind::Cardinal
            }
            b"matrix" => {
                self.bump()?;
                let degree = self.int()?;
                let step = self.int()?;
                let mut values = Vec::new();
                while self.at_number()? {
                    values.push(self.float()?);
                }
                BasisKind::Matrix { degree, step, values }
            }
            _ => return self.expected("'bezier', 'bspline', 'taylor', 'cardinal' or 'matrix'"),
        };
        let end = self.peek()?.span;
        Ok(Basis { name, rational, kind, span: start.to(end.start()) })
    }
}

/// Reads a non-negative integer through the fast path or fails with `what`.
pub(super) fn need_u32(lx: &mut Lexer, what: &str) -> PResult<u32> {
    match lx.try_u32()? {
        Some(v) => Ok(v),
        None => Err(at_lexer(lx, &format!("expected {what}"))),
    }
}

/// An error at the lexer's current position.
pub(super) fn at_lexer(lx: &mut Lexer, msg: &str) -> Diagnostic {
    lx.skip_trivia();
    let p = lx.pos as u32;
    Diagnostic::error(Span::new(lx.file, p, p + 1), msg)
}

pub(super) fn be_f32s(bytes: &[u8]) -> Vec<f32> {
    bytes.chunks_exact(4).map(|c| f32::from_be_bytes([c[0], c[1], c[2], c[3]])).collect()
}

pub(super) fn be_u32s(bytes: &[u8]) -> Vec<u32> {
    bytes.chunks_exact(4).map(|c| u32::from_be_bytes([c[0], c[1], c[2], c[3]])).collect()
}
