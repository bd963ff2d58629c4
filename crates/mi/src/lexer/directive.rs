//! Preprocessor directives as the lexer sees them: `$` lines, `$include` paths, `$code`
//! blocks, and skipping the lines of a conditional branch not taken.

use super::{Directive, Lexer, SkipEnd, Tok, Token};
use crate::diag::Diagnostic;

/// The arguments of a directive whose span runs from its `$`: the text after the word.
pub fn directive_args(directive_text: &[u8]) -> &[u8] {
    let word_end =
        directive_text.iter().skip(1).position(|b| !b.is_ascii_alphabetic()).map_or(directive_text.len(), |i| i + 1);
    let rest = &directive_text[word_end..];
    // Drop a trailing comment.
    let mut in_string = false;
    for (i, &b) in rest.iter().enumerate() {
        match b {
            b'"' => in_string = !in_string,
            b'#' if !in_string => return rest[..i].trim_ascii(),
            _ => {}
        }
    }
    rest.trim_ascii()
}

impl Lexer {
    pub(super) fn lex_directive(&mut self, start: usize) -> Result<Token, Diagnostic> {
        let mut end = start + 1;
        while end < self.src.len() && self.src[end].is_ascii_alphabetic() {
            end += 1;
        }
        let word = &self.src[start + 1..end];
        self.pos = end;
        let directive = match word {
            b"include" => return self.lex_include_path(start),
            b"code" => return self.lex_code_block(start),
            b"ifdef" => Directive::IfDef,
            b"ifndef" => Directive::IfNDef,
            b"ifeq" => Directive::IfEq,
            b"ifneq" => Directive::IfNEq,
            b"elseifdef" => Directive::ElseIfDef,
            b"elseifeq" => Directive::ElseIfEq,
            b"else" => Directive::Else,
            b"endif" => Directive::EndIf,
            b"lookup" => Directive::Lookup,
            _ => {
                let w = String::from_utf8_lossy(word);
                return Err(self.err(start, end, format!("unknown directive '${w}'")));
            }
        };
        // The arguments: the rest of the line up to a comment, trimmed.
        let line_end = memchr::memchr(b'\n', &self.src[end..]).map_or(self.src.len(), |i| end + i);
        let mut arg_end = line_end;
        let mut in_string = false;
        for (i, &b) in self.src[end..line_end].iter().enumerate() {
            match b {
                b'"' => in_string = !in_string,
                b'#' if !in_string => {
                    arg_end = end + i;
                    break;
                }
                _ => {}
            }
        }
        let args = &self.src[end..arg_end];
        let lo = end + (args.len() - args.trim_ascii_start().len());
        let hi = (arg_end - (args.len() - args.trim_ascii_end().len())).max(lo);
        self.pos = line_end;
        let needs_args = !matches!(directive, Directive::Else | Directive::EndIf);
        if needs_args && lo == hi {
            return Err(self.err(start, end, format!("'${}' needs a name", String::from_utf8_lossy(word))));
        }
        // The span runs from `$` to the end of the arguments; see [`directive_args`].
        Ok(Token { tok: Tok::Directive(directive), span: self.span(start, hi.max(end)) })
    }

    /// Skips spaces and tabs (not line breaks).
    fn skip_blanks(&mut self) {
        while matches!(self.src.get(self.pos), Some(b' ' | b'\t')) {
            self.pos += 1;
        }
    }

    fn lex_include_path(&mut self, start: usize) -> Result<Token, Diagnostic> {
        self.skip_blanks();
        let p = self.pos;
        let (close, angle) = match self.src.get(p) {
            Some(b'"') => (b'"', false),
            Some(b'<') => (b'>', true),
            _ => return Err(self.err(start, p, "'$include' needs a file name in \"quotes\" or <angle brackets>")),
        };
        let line_end = memchr::memchr(b'\n', &self.src[p + 1..]).map_or(self.src.len(), |i| p + 1 + i);
        let Some(len) = memchr::memchr(close, &self.src[p + 1..line_end]) else {
            return Err(self.err(p, p + 1, "include file name is not closed on its line"));
        };
        self.pos = p + 1 + len + 1;
        Ok(Token { tok: Tok::Directive(Directive::Include { angle }), span: self.span(p + 1, p + 1 + len) })
    }

    /// `$code ["name"]` then raw lines up to a line starting with `$end code`.
    fn lex_code_block(&mut self, start: usize) -> Result<Token, Diagnostic> {
        let body_start = memchr::memchr(b'\n', &self.src[self.pos..]).map_or(self.src.len(), |i| self.pos + i + 1);
        let mut line = body_start;
        while line < self.src.len() {
            let next = memchr::memchr(b'\n', &self.src[line..]).map_or(self.src.len(), |i| line + i + 1);
            let text = self.src[line..next].trim_ascii_start();
            if let Some(rest) = text.strip_prefix(b"$end") {
                if rest.trim_ascii_start().starts_with(b"code") {
                    self.pos = next;
                    return Ok(Token { tok: Tok::CodeBlock, span: self.span(body_start, line) });
                }
            }
            line = next;
        }
        Err(self.err(start, start + 5, "'$code' block has no '$end code'"))
    }

    /// Skips the lines of a conditional branch that is not taken, up to the `$else`,
    /// `$elseifdef`, `$elseifeq` or `$endif` that belongs to it (nested conditionals are
    /// skipped whole). With `stop_at_else` false, the other branches are skipped too, up to
    /// the `$endif`. Returns `None` when the file ends first.
    pub fn skip_conditional(&mut self, stop_at_else: bool) -> Option<SkipEnd> {
        let mut depth = 0u32;
        let mut line = self.pos;
        while line < self.src.len() {
            let next = memchr::memchr(b'\n', &self.src[line..]).map_or(self.src.len(), |i| line + i + 1);
            let raw = &self.src[line..next];
            let text = raw.trim_ascii_start();
            if text.first() == Some(&b'$') {
                let word_len = text[1..].iter().position(|b| !b.is_ascii_alphabetic()).map_or(text.len() - 1, |i| i);
                let word = &text[1..1 + word_len];
                // The span runs from `$` to the end of the line, like a directive token's.
                let dollar = line + (raw.len() - text.len());
                let args_span = self.span(dollar, dollar + text.trim_ascii_end().len());
                match word {
                    b"ifdef" | b"ifndef" | b"ifeq" | b"ifneq" => depth += 1,
                    b"endif" if depth == 0 => {
                        self.pos = next;
                        return Some(SkipEnd::EndIf);
                    }
                    b"endif" => depth -= 1,
                    b"else" | b"elseifdef" | b"elseifeq" if depth == 0 && stop_at_else => {
                        self.pos = next;
                        let d = match word {
                            b"else" => Directive::Else,
                            b"elseifdef" => Directive::ElseIfDef,
                            _ => Directive::ElseIfEq,
                        };
                        return Some(SkipEnd::Else(d, args_span));
                    }
                    _ => {}
                }
            }
            line = next;
        }
        self.pos = self.src.len();
        None
    }
}
