//! Trilists: `trilist vertex N layout… triangle M … end trilist`, the vertex data and
//! triangle sections in text or binary form, triangle data and topology blocks.
//!
//! Vertex data and indices are read straight from the lexer into their final arrays.

use super::geometry::{be_f32s, be_u32s, reserve_for};
use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::lexer::Tok;
use crate::source::Span;

impl Parser {
    /// `trilist vertex N layout… triangle M … end trilist`.
    pub(super) fn trilist(&mut self, tagged: bool) -> PResult<Trilist> {
        let start = self.expect("trilist")?;
        if self.at("vector")? {
            return Err(Diagnostic::error(
                start,
                "the mental ray 3.3 'trilist vector …' form is not read; use the 3.4 'trilist vertex …' form",
            ));
        }
        self.expect("vertex")?;
        let vertex_count = self.uint("the vertex line count")?;
        let mut layout = Vec::new();
        loop {
            let t = self.peek()?;
            let word = self.bytes(&t).to_vec();
            let item = match (t.tok, word.as_slice()) {
                (Tok::Name, b"p") => LayoutItem::P,
                (Tok::Name, b"n") => LayoutItem::N,
                (Tok::Name, b"d") => LayoutItem::D,
                (Tok::Name, b"d2") => LayoutItem::D2,
                (Tok::Name, b"m" | b"b") => {
                    self.bump()?;
                    let k = if matches!(self.peek()?.tok, Tok::Int(_)) { Some(self.uint("a count")?) } else { None };
                    layout.push(if word == b"m" { LayoutItem::M(k) } else { LayoutItem::B(k) });
                    continue;
                }
                (Tok::Name, b"t" | b"u") => {
                    self.bump()?;
                    let mut dims = Vec::new();
                    while matches!(self.peek()?.tok, Tok::Int(_)) {
                        dims.push(self.uint("a dimension")?);
                    }
                    layout.push(if word == b"t" { LayoutItem::T(dims) } else { LayoutItem::U(dims) });
                    continue;
                }
                _ => break,
            };
            self.bump()?;
            layout.push(item);
        }
        if layout.first() != Some(&LayoutItem::P) {
            return Err(Diagnostic::error(start, "a trilist vertex layout must start with 'p'"));
        }
        self.expect("triangle")?;
        let triangle_count = self.uint("the triangle count")?;
        let border_count = if self.eat("border")? { Some(self.uint("the border triangle count")?) } else { None };
        let data_sizes = if self.eat("data")? { Some((self.uint("a size")?, self.uint("a size")?)) } else { None };
        let mut list = Trilist {
            layout,
            vertex_count,
            triangle_count,
            border_count,
            data_sizes,
            floats: Vec::new(),
            triangles: Triangles::default(),
            border: None,
            triangle_data: None,
            topology: None,
            span: start,
        };
        let per_line = list.floats_per_line();
        let count =
            (vertex_count as usize).checked_mul(per_line).filter(|&n| n < u32::MAX as usize).ok_or_else(|| {
                Diagnostic::error(
                    start,
                    format!("trilist of {vertex_count} vertex lines of {per_line} numbers is too large"),
                )
            })?;
        // Vertex data.
        if self.eat("scalar")? {
            let t = self.bump()?;
            let span = self.binary_words(t, count, "vertex data")?;
            list.floats = be_f32s(self.ts.bytes(span));
        } else {
            let open = self.expect_tok(Tok::LBracket, "'[' or 'scalar' to start the vertex data")?;
            let remaining = self.lexer()?.remaining();
            if count > remaining / 2 + 1 {
                return Err(Diagnostic::error(
                    start,
                    format!("trilist declares {count} vertex numbers but only {remaining} bytes of the file are left"),
                ));
            }
            list.floats.reserve(count);
            self.float_block(&mut list.floats)?;
            if list.floats.len() != count {
                return Err(Diagnostic::error(
                    open,
                    format!(
                        "trilist vertex data holds {} numbers; {} lines of {} ({}) were declared",
                        list.floats.len(),
                        vertex_count,
                        per_line,
                        count
                    ),
                ));
            }
        }
        let at = self.peek()?.span;
        list.triangles = self.triangles(triangle_count, tagged, at)?;
        if let Some(n) = border_count {
            let at = self.peek()?.span;
            list.border = Some(self.triangles(n, tagged, at)?);
        }
        if self.at_words("triangle data")? {
            self.bump()?;
            self.bump()?;
            let (info, data) = data_sizes
                .map_or((None, None), |(i, d)| (Some(i as usize), (d as usize).checked_mul(triangle_count as usize)));
            let a = self.word_block(info)?;
            let b = self.word_block(data)?;
            list.triangle_data = Some((a, b));
        }
        if self.eat("topology")? {
            list.topology = Some(self.word_block((triangle_count as usize).checked_mul(3))?);
        }
        let end = self.expect_end("trilist")?;
        list.span = start.to(end);
        Ok(list)
    }

    /// `[ numbers… ]` read fast into `out` (the `[` already consumed).
    fn float_block(&mut self, out: &mut Vec<f32>) -> PResult<()> {
        if self.lexer()?.f32_list_parallel(out) {
            return Ok(());
        }
        loop {
            let lx = self.lexer()?;
            while let Some(x) = lx.try_f32()? {
                out.push(x);
            }
            let t = self.peek()?;
            match t.tok {
                Tok::RBracket => {
                    self.bump()?;
                    return Ok(());
                }
                Tok::Int(_) | Tok::Float(_) => out.push(self.float()? as f32),
                _ => return self.expected("a number or ']'"),
            }
        }
    }

    /// `[ integers… ]` read fast (the `[` not yet consumed); strings (per-triangle
    /// material names) are returned with the number of integers before them.
    fn int_block(&mut self, out: &mut Vec<u32>) -> PResult<Vec<(u32, Name)>> {
        self.expect_tok(Tok::LBracket, "'['")?;
        let mut names = Vec::new();
        if self.lexer()?.u32_list_parallel(out) {
            return Ok(names);
        }
        loop {
            let lx = self.lexer()?;
            while let Some(x) = lx.try_u32()? {
                out.push(x);
            }
            let t = self.peek()?;
            match t.tok {
                Tok::RBracket => {
                    self.bump()?;
                    return Ok(names);
                }
                Tok::Int(_) => out.push(self.uint("a vertex index")?),
                Tok::Str { .. } => {
                    let n = self.name()?;
                    names.push((out.len() as u32, n));
                }
                _ => return self.expected("an integer or ']'"),
            }
        }
    }

    /// `[ ints ]` or `integer `…`` (of `words` words when known: the payload may then hold
    /// backquotes).
    fn word_block(&mut self, words: Option<usize>) -> PResult<Vec<u32>> {
        if self.eat("integer")? {
            let t = self.bump()?;
            if t.tok != Tok::Binary {
                return Err(Diagnostic::error(t.span, "expected a backquoted binary block"));
            }
            let payload = match words.and_then(|w| w.checked_mul(4)) {
                Some(len) => self.exact_binary(t, len)?,
                None => Span::new(t.span.file, t.span.lo + 1, t.span.hi - 1),
            };
            let bytes = self.ts.bytes(payload);
            if bytes.len() % 4 != 0 {
                return Err(Diagnostic::error(t.span, "binary block length is not a multiple of 4"));
            }
            return Ok(bytes.chunks_exact(4).map(|c| u32::from_be_bytes([c[0], c[1], c[2], c[3]])).collect());
        }
        let mut v = Vec::new();
        self.int_block(&mut v)?;
        Ok(v)
    }

    /// Reads a binary token as exactly `words` big-endian 32-bit words.
    fn binary_words(&mut self, t: crate::lexer::Token, words: usize, what: &str) -> PResult<Span> {
        self.exact_binary(t, words * 4)
            .map_err(|d| Diagnostic { message: format!("{} (trilist {what}: {words} words)", d.message), ..d })
    }

    /// The triangle section: `[ ints ]` (3 per triangle, or 4 with the label first, or
    /// with material names) or `integer `…` [integer `…`]`.
    fn triangles(&mut self, count: u32, tagged: bool, start: Span) -> PResult<Triangles> {
        let n = count as usize;
        if self.eat("integer")? {
            let t = self.bump()?;
            let span = self.binary_words(t, n * 3, "triangle indices")?;
            let indices = be_u32s(self.ts.bytes(span));
            let labels = if self.eat("integer")? {
                let t = self.bump()?;
                let span = self.binary_words(t, n, "triangle labels")?;
                Some(be_u32s(self.ts.bytes(span)))
            } else {
                None
            };
            return Ok(Triangles { indices, labels, materials: None });
        }
        let mut ints = Vec::new();
        let remaining = self.lexer()?.remaining();
        reserve_for(&mut ints, n.saturating_mul(if tagged { 4 } else { 3 }), remaining, 2);
        let names = self.int_block(&mut ints)?;
        if !names.is_empty() {
            if ints.len() != 3 * n {
                return Err(Diagnostic::error(
                    start,
                    format!("trilist declares {n} triangles but its index list holds {} indices", ints.len()),
                ));
            }
            let materials = names.into_iter().map(|(at, name)| (at / 3, name)).collect();
            return Ok(Triangles { indices: ints, labels: None, materials: Some(materials) });
        }
        if ints.len() == 3 * n && !(tagged && n == 0) {
            return Ok(Triangles { indices: ints, labels: None, materials: None });
        }
        if ints.len() == 4 * n {
            let mut labels = Vec::with_capacity(n);
            let mut indices = Vec::with_capacity(3 * n);
            for quad in ints.chunks_exact(4) {
                labels.push(quad[0]);
                indices.extend_from_slice(&quad[1..]);
            }
            return Ok(Triangles { indices, labels: Some(labels), materials: None });
        }
        Err(Diagnostic::error(
            start,
            format!(
                "trilist declares {n} triangles but its index list holds {} integers (expected {} or, with labels, {})",
                ints.len(),
                3 * n,
                4 * n
            ),
        ))
    }
}
