//! Hair objects: `hair … scalar [N] values… hair [K] offsets… end hair`.

use super::geometry::{be_f32s, be_u32s, reserve_for};
use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::grammar;
use crate::lexer::Tok;

impl Parser {
    /// `hair … scalar [N] values… hair [K] offsets… end hair`.
    pub(super) fn hair(&mut self) -> PResult<Hair> {
        let start = self.expect("hair")?;
        let mut header = Vec::new();
        while !self.at("scalar")? {
            self.not_eof("hair", start)?;
            match self.kw_stmt(&[grammar::HAIR])? {
                Some(s) => header.push(s),
                None => return self.expected("a hair statement or 'scalar'"),
            }
        }
        self.expect("scalar")?;
        let scalar_count = self.bracketed_count()?;
        let remaining = self.lexer()?.remaining();
        let mut scalars = Vec::new();
        if self.eat("binary")? {
            let t = self.bump()?;
            let span = self.exact_binary(t, scalar_count * 4)?;
            scalars = be_f32s(self.ts.bytes(span));
        } else {
            if scalar_count > remaining / 2 + 1 {
                return Err(Diagnostic::error(
                    start,
                    format!("hair declares {scalar_count} scalars but the file is shorter"),
                ));
            }
            scalars.reserve(scalar_count);
            for _ in 0..scalar_count {
                let lx = self.lexer()?;
                match lx.try_f32()? {
                    Some(x) => scalars.push(x),
                    None => scalars.push(self.float()? as f32),
                }
            }
        }
        self.expect("hair")?;
        let offset_count = self.bracketed_count()?;
        let mut offsets = Vec::new();
        if self.eat("binary")? {
            let t = self.bump()?;
            let span = self.exact_binary(t, offset_count * 4)?;
            offsets = be_u32s(self.ts.bytes(span));
        } else {
            reserve_for(&mut offsets, offset_count, remaining, 2);
            for _ in 0..offset_count {
                offsets.push(self.uint("a hair offset")?);
            }
        }
        let end = self.expect_end("hair")?;
        Ok(Hair { header, scalars, offsets, span: start.to(end) })
    }

    /// `[ N ]`
    fn bracketed_count(&mut self) -> PResult<usize> {
        self.expect_tok(Tok::LBracket, "'['")?;
        let n = self.uint("a count")? as usize;
        self.expect_tok(Tok::RBracket, "']'")?;
        Ok(n)
    }
}
