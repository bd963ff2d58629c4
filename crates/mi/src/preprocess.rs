//! The preprocessor: a token stream over the main file and everything it `$include`s, with
//! `$ifdef`/`$ifndef`/`$else`/`$endif` conditionals on `set` variables and registry keys.
//!
//! `$include "f"` looks in the including file's directory, then on the include path;
//! `$include <f>` looks on the include path only. The standard declaration files that mira
//! carries (`base.mi`, `physics.mi`, `contour.mi`, `architectural.mi`, `production.mi`)
//! are used when no file of that name is found. MDL modules (`x.mdl`, `::pkg::x.mdl`) are
//! recorded, not read. Include loops and depths past [`MAX_INCLUDE_DEPTH`] are errors.
//! The tokens of an included file are bracketed by [`Tok::IncludeBegin`] and
//! [`Tok::IncludeEnd`] so that the parser can keep the file structure.

use std::collections::{HashMap, VecDeque};
use std::path::{Path, PathBuf};

use crate::diag::Diagnostic;
use crate::lexer::{Directive, Lexer, SkipEnd, Tok, Token};
use crate::source::{read_source, FileId, Origin, SourceMap, Span};
use crate::stdlib;

/// How deeply `$include`s may nest.
pub const MAX_INCLUDE_DEPTH: usize = 64;

/// Longest text a registry expansion may produce (bytes).
pub const MAX_EXPANSION: usize = 64 * 1024;

/// Where an `$include` led.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum IncludeTarget {
    /// A file on disk, read and parsed.
    File(PathBuf),
    /// One of mira's built-in standard declaration files (by its file name).
    Builtin(&'static str),
    /// An MDL module: recorded for the material layer, not parsed as `.mi`.
    Mdl,
    /// Not found, unreadable or a loop: an error was reported.
    Missing,
}

/// One `$include` as written and what it resolved to.
#[derive(Clone, Debug)]
pub struct IncludeRecord {
    /// The file name as written (registry keys not yet expanded).
    pub path: String,
    /// Written as `<path>`.
    pub angle: bool,
    /// What it resolved to.
    pub target: IncludeTarget,
    /// Where the name was written.
    pub span: Span,
}

/// Settings for reading a scene.
#[derive(Clone, Debug)]
pub struct ReadOptions {
    /// Directories searched for `$include`d files, in order (after the including file's own
    /// directory for the `"quoted"` form).
    pub include_paths: Vec<PathBuf>,
    /// Whether mira's built-in standard declaration files stand in for missing ones.
    pub builtin_declarations: bool,
    /// Parsing stops after this many errors.
    pub max_errors: usize,
}

impl Default for ReadOptions {
    fn default() -> ReadOptions {
        ReadOptions { include_paths: Vec::new(), builtin_declarations: true, max_errors: 50 }
    }
}

impl ReadOptions {
    /// Adds the directories of the `MI_INCLUDE_PATH` environment variable (separated like
    /// `PATH`) after those already given.
    pub fn with_env_include_path(mut self) -> ReadOptions {
        if let Some(var) = std::env::var_os("MI_INCLUDE_PATH") {
            self.include_paths.extend(std::env::split_paths(&var).filter(|p| !p.as_os_str().is_empty()));
        }
        self
    }
}

struct Frame {
    lexer: Lexer,
    /// Open conditionals whose taken branch is being read: the span of their `$if…`.
    conds: Vec<Span>,
    /// Canonical path, for loop detection.
    canonical: Option<PathBuf>,
}

/// The preprocessed token stream.
pub(crate) struct TokenStream {
    /// Every file and text read so far, for messages' file:line:col.
    pub sources: SourceMap,
    frames: Vec<Frame>,
    lookahead: VecDeque<Token>,
    /// A token to produce before reading on (the end marker of an include not opened).
    pending: Option<Token>,
    /// The `$include`s met, in order.
    pub includes: Vec<IncludeRecord>,
    /// Built-in declaration files already read.
    builtins_read: Vec<&'static str>,
    vars: HashMap<String, String>,
    registry: HashMap<String, String>,
    options: ReadOptions,
    /// Diagnostics found by the preprocessor itself.
    pub diags: Vec<Diagnostic>,
}

impl TokenStream {
    /// A stream over `root`, a file already in `sources`.
    pub fn new(sources: SourceMap, root: FileId, options: ReadOptions) -> TokenStream {
        let file = sources.file(root);
        let canonical = match &file.origin {
            Origin::Disk(p) => p.canonicalize().ok(),
            _ => None,
        };
        let lexer = Lexer::new(root, file.bytes.clone());
        TokenStream {
            sources,
            frames: vec![Frame { lexer, conds: Vec::new(), canonical }],
            lookahead: VecDeque::new(),
            pending: None,
            includes: Vec::new(),
            builtins_read: Vec::new(),
            vars: HashMap::new(),
            registry: HashMap::new(),
            options,
            diags: Vec::new(),
        }
    }

    /// The bytes of a span.
    pub fn bytes(&self, span: Span) -> &[u8] {
        self.sources.slice(span)
    }

    /// Records `set "var" "value"` for later conditionals.
    pub fn set_var(&mut self, name: &str, value: &str) {
        self.vars.insert(name.to_string(), value.to_string());
    }

    /// Records a registry key's `value` (used for `{key}` in include paths and conditionals).
    pub fn set_registry(&mut self, key: &str, value: &str) {
        self.registry.insert(key.to_string(), value.to_string());
    }

    /// The top file's lexer, for the bulk-data fast paths. A single buffered token is given
    /// back to the lexer first (include markers before it are dropped: an include inside
    /// geometry reads as if its text stood there). `None` when more is buffered, since a
    /// directive may have been acted on between the buffered tokens.
    #[inline]
    pub fn fast_lexer(&mut self) -> Option<&mut Lexer> {
        if matches!(self.pending.map(|t| t.tok), Some(Tok::IncludeEnd)) && self.lookahead.is_empty() {
            self.pending = None;
        }
        while matches!(self.lookahead.front().map(|t| t.tok), Some(Tok::IncludeBegin(_) | Tok::IncludeEnd)) {
            self.lookahead.pop_front();
        }
        let frame = self.frames.last_mut()?;
        match self.lookahead.len() {
            0 => {}
            1 => {
                let t = self.lookahead[0];
                if t.span.file != frame.lexer.file || matches!(t.tok, Tok::Directive(_) | Tok::CodeBlock) {
                    return None;
                }
                frame.lexer.pos = t.span.lo as usize;
                self.lookahead.clear();
            }
            _ => return None,
        }
        Some(&mut frame.lexer)
    }

    /// The `n`-th token ahead (0 = next), markers included.
    pub fn peek_raw(&mut self, n: usize) -> Result<Token, Diagnostic> {
        while self.lookahead.len() <= n {
            let t = self.produce()?;
            self.lookahead.push_back(t);
        }
        Ok(self.lookahead[n])
    }

    /// Takes the next token, markers included.
    pub fn next_raw(&mut self) -> Result<Token, Diagnostic> {
        match self.lookahead.pop_front() {
            Some(t) => Ok(t),
            None => self.produce(),
        }
    }

    /// Drops buffered tokens and restarts the top lexer at `pos` (used after a count-driven
    /// binary read that the generic lexer had split at an embedded backquote).
    pub fn reposition(&mut self, file: FileId, pos: usize) {
        self.lookahead.clear();
        if let Some(frame) = self.frames.last_mut() {
            if frame.lexer.file == file {
                frame.lexer.pos = pos;
            }
        }
    }

    /// Produces the next token from the files, acting on directives.
    fn produce(&mut self) -> Result<Token, Diagnostic> {
        if let Some(t) = self.pending.take() {
            return Ok(t);
        }
        loop {
            let depth = self.frames.len();
            let frame = self.frames.last_mut().expect("the root frame is never popped");
            let tok = match frame.lexer.next_token() {
                Ok(t) => t,
                Err(e) => {
                    // Step past the offending bytes so that recovery makes progress.
                    let lx = &mut frame.lexer;
                    lx.pos = lx.pos.max(e.span.hi as usize).max(e.span.lo as usize + 1).min(lx.src().len());
                    return Err(e);
                }
            };
            match tok.tok {
                Tok::Eof => {
                    for span in std::mem::take(&mut frame.conds) {
                        self.diags.push(Diagnostic::error(span, "conditional is not closed by '$endif'"));
                    }
                    if depth > 1 {
                        self.frames.pop();
                        return Ok(Token { tok: Tok::IncludeEnd, span: tok.span });
                    }
                    return Ok(tok);
                }
                Tok::Directive(Directive::Include { angle }) => return Ok(self.include(tok.span, angle)),
                Tok::Directive(d @ (Directive::IfDef | Directive::IfNDef | Directive::IfEq | Directive::IfNEq)) => {
                    if self.condition(d, tok.span) {
                        self.frames.last_mut().expect("frame").conds.push(tok.span);
                    } else {
                        self.skip_branches(tok.span);
                    }
                }
                Tok::Directive(Directive::Else | Directive::ElseIfDef | Directive::ElseIfEq) => {
                    // Met while in a taken branch: the rest of the chain is skipped.
                    match frame.conds.pop() {
                        Some(span) => {
                            if frame.lexer.skip_conditional(false).is_none() {
                                self.diags.push(Diagnostic::error(span, "conditional is not closed by '$endif'"));
                            }
                        }
                        None => self.diags.push(Diagnostic::error(tok.span, "'$else' without '$ifdef' or '$ifndef'")),
                    }
                }
                Tok::Directive(Directive::EndIf) => {
                    if frame.conds.pop().is_none() {
                        self.diags.push(Diagnostic::error(tok.span, "'$endif' without '$ifdef' or '$ifndef'"));
                    }
                }
                _ => return Ok(tok),
            }
        }
    }

    /// Skips the branches of a conditional whose condition failed, until one is taken or
    /// the `$endif` is reached.
    fn skip_branches(&mut self, span: Span) {
        loop {
            let frame = self.frames.last_mut().expect("frame");
            match frame.lexer.skip_conditional(true) {
                Some(SkipEnd::Else(Directive::Else, _)) => {
                    frame.conds.push(span);
                    return;
                }
                Some(SkipEnd::Else(d, args)) => {
                    if self.condition(d, args) {
                        self.frames.last_mut().expect("frame").conds.push(span);
                        return;
                    }
                }
                Some(SkipEnd::EndIf) => return,
                None => {
                    self.diags.push(Diagnostic::error(span, "conditional is not closed by '$endif'"));
                    return;
                }
            }
        }
    }

    /// Evaluates a conditional directive whose arguments are at `args`.
    fn condition(&self, d: Directive, args: Span) -> bool {
        let text = String::from_utf8_lossy(crate::lexer::directive_args(self.sources.slice(args))).into_owned();
        let words = split_args(&text);
        let key = words.first().map_or("", String::as_str);
        let constant = words.get(1).map_or("", String::as_str);
        match d {
            Directive::IfDef | Directive::ElseIfDef => self.is_defined(key),
            Directive::IfNDef => !self.is_defined(key),
            Directive::IfEq | Directive::ElseIfEq => self.value_of(key).unwrap_or_default() == constant,
            Directive::IfNEq => self.value_of(key).unwrap_or_default() != constant,
            _ => false,
        }
    }

    /// The value of a conditional's key: a `set` variable, `{registry}` key, `${ENV}`
    /// variable or `${?ENV}` ("1" when the variable exists).
    fn value_of(&self, key: &str) -> Option<String> {
        if let Some(env) = key.strip_prefix("${").and_then(|k| k.strip_suffix('}')) {
            return match env.strip_prefix('?') {
                Some(name) => Some(if std::env::var_os(name).is_some() { "1".into() } else { String::new() }),
                None => std::env::var(env).ok(),
            };
        }
        if let Some(v) = self.vars.get(key) {
            return Some(v.clone());
        }
        let bare = key.strip_prefix('{').and_then(|k| k.strip_suffix('}')).unwrap_or(key);
        self.registry.get(bare).cloned()
    }

    /// Whether a conditional's key is defined: a `set` variable (even without a value), or a
    /// registry key or environment variable with a non-empty value.
    fn is_defined(&self, key: &str) -> bool {
        self.vars.contains_key(key) || self.value_of(key).is_some_and(|v| !v.is_empty())
    }

    /// Replaces `{key}` by registry values and `{$NAME}` by environment variables,
    /// recursively (registry values may name other keys); unknown keys are left as written.
    /// Expansion stops (leaving the rest as written) once the text would pass
    /// [`MAX_EXPANSION`] bytes, so that self-multiplying registry values cannot exhaust
    /// memory.
    fn expand(&self, text: &str) -> String {
        let mut current = text.to_string();
        for _ in 0..16 {
            let Some(next) = self.expand_once(&current) else { break };
            if next == current {
                break;
            }
            current = next;
        }
        current
    }

    fn expand_once(&self, text: &str) -> Option<String> {
        let mut out = String::new();
        let mut rest = text;
        while let Some(open) = rest.find('{') {
            if out.len() > MAX_EXPANSION {
                return None;
            }
            let Some(close) = rest[open..].find('}') else { break };
            let key = &rest[open + 1..open + close];
            out.push_str(&rest[..open]);
            let value = match key.strip_prefix('$') {
                Some(env) => std::env::var(env).ok(),
                None => self.registry.get(key).cloned(),
            };
            match value {
                Some(v) => out.push_str(&v),
                None => out.push_str(&rest[open..=open + close]),
            }
            rest = &rest[open + close + 1..];
        }
        out.push_str(rest);
        (out.len() <= MAX_EXPANSION).then_some(out)
    }

    /// Resolves an `$include`, opens the file if there is one and returns its begin marker.
    fn include(&mut self, span: Span, angle: bool) -> Token {
        let written = String::from_utf8_lossy(self.sources.slice(span)).into_owned();
        let target = self.resolve(&written, angle, span);
        let index = self.includes.len() as u32;
        let opened = match &target {
            IncludeTarget::File(path) => self.open_file(path, span),
            // mira's built-in declaration files hold declarations only: reading one again
            // changes nothing, so it is read once per parse.
            IncludeTarget::Builtin(name) if self.builtins_read.contains(name) => false,
            IncludeTarget::Builtin(name) => {
                self.builtins_read.push(name);
                let text = stdlib::text(name).expect("builtin exists");
                let id = self.sources.add(Origin::Builtin(name), text.as_bytes().to_vec());
                self.frames.push(Frame {
                    lexer: Lexer::new(id, self.sources.file(id).bytes.clone()),
                    conds: Vec::new(),
                    canonical: None,
                });
                true
            }
            _ => false,
        };
        let target = if opened || matches!(target, IncludeTarget::Mdl) { target } else { IncludeTarget::Missing };
        self.includes.push(IncludeRecord { path: written, angle, target, span });
        if !opened {
            // Nothing to read: the end marker follows at once.
            self.pending = Some(Token { tok: Tok::IncludeEnd, span });
        }
        Token { tok: Tok::IncludeBegin(index), span }
    }

    fn resolve(&mut self, written: &str, angle: bool, span: Span) -> IncludeTarget {
        let expanded = self.expand(written);
        if expanded.ends_with(".mdl") || expanded.starts_with("::") {
            return IncludeTarget::Mdl;
        }
        let path = Path::new(&expanded);
        let mut searched = Vec::new();
        if path.is_absolute() {
            searched.push(path.to_path_buf());
        } else {
            if !angle {
                let dir = self.sources.file(span.file).dir().map(Path::to_path_buf);
                searched.push(dir.unwrap_or_default().join(path));
            }
            searched.extend(self.options.include_paths.iter().map(|d| d.join(path)));
            // mental ray's own include path, when a registry entry sets it.
            if let Some(dirs) = self.registry.get("_MI_REG_INCLUDE") {
                let dirs = self.expand(dirs);
                searched.extend(dirs.split([';', ':']).filter(|d| !d.is_empty()).map(|d| Path::new(d).join(path)));
            }
        }
        if expanded.contains('\\') {
            // Windows paths written by Windows exporters.
            let unix: Vec<PathBuf> =
                searched.iter().map(|p| PathBuf::from(p.to_string_lossy().replace('\\', "/"))).collect();
            searched.extend(unix);
        }
        if let Some(found) = searched.iter().find(|p| p.is_file()) {
            return IncludeTarget::File(found.clone());
        }
        if self.options.builtin_declarations {
            let base = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if let Some(name) = stdlib::builtin_name(base) {
                return IncludeTarget::Builtin(name);
            }
        }
        // Something is there, but it cannot be read as a file (a directory, a device, a pipe).
        if let Some(other) = searched.iter().find(|p| p.exists()) {
            let what = if other.is_dir() { "a directory" } else { "not a regular file" };
            let message =
                format!("include file '{}' is {what} ({})", clip(&expanded), clip(&other.display().to_string()));
            self.diags.push(Diagnostic::error(span, message));
            return IncludeTarget::Missing;
        }
        let mut d = Diagnostic::error(span, format!("cannot find include file '{}'", clip(&expanded)));
        if searched.is_empty() {
            d = d.with_note(None, "no include directories are set: pass -I DIR or set MI_INCLUDE_PATH");
        } else {
            let list: Vec<String> = searched.iter().map(|p| clip(&p.display().to_string())).collect();
            d = d.with_note(None, format!("looked for: {}", list.join(", ")));
        }
        self.diags.push(d);
        IncludeTarget::Missing
    }

    fn open_file(&mut self, path: &Path, span: Span) -> bool {
        if self.frames.len() > MAX_INCLUDE_DEPTH {
            self.diags.push(Diagnostic::error(span, format!("includes nest deeper than {MAX_INCLUDE_DEPTH} files")));
            return false;
        }
        let canonical = path.canonicalize().ok();
        if let Some(c) = &canonical {
            if let Some(pos) = self.frames.iter().position(|f| f.canonical.as_ref() == Some(c)) {
                let chain: Vec<String> = self.frames[pos..]
                    .iter()
                    .map(|f| self.sources.file(f.lexer.file).name())
                    .chain(std::iter::once(path.display().to_string()))
                    .collect();
                self.diags.push(Diagnostic::error(span, format!("include loop: {}", chain.join(" -> "))));
                return false;
            }
        }
        match read_source(path) {
            Ok(bytes) => {
                let id = self.sources.add(Origin::Disk(path.to_path_buf()), bytes);
                let lexer = Lexer::new(id, self.sources.file(id).bytes.clone());
                self.frames.push(Frame { lexer, conds: Vec::new(), canonical });
                true
            }
            Err(msg) => {
                self.diags
                    .push(Diagnostic::error(span, format!("cannot read include file '{}': {msg}", path.display())));
                false
            }
        }
    }
}

/// Splits directive arguments into words: quoted strings or runs of non-blanks.
fn split_args(text: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut chars = text.chars().peekable();
    while let Some(&c) = chars.peek() {
        if c.is_whitespace() {
            chars.next();
        } else if c == '"' {
            chars.next();
            let mut w = String::new();
            while let Some(c) = chars.next() {
                match c {
                    '"' => break,
                    '\\' => w.extend(chars.next()),
                    c => w.push(c),
                }
            }
            words.push(w);
        } else {
            let mut w = String::new();
            while let Some(&c) = chars.peek() {
                if c.is_whitespace() {
                    break;
                }
                w.push(c);
                chars.next();
            }
            words.push(w);
        }
    }
    words
}

/// A name shortened for a message (a registry expansion can be long).
fn clip(text: &str) -> String {
    const MAX: usize = 160;
    if text.len() <= MAX {
        return text.to_string();
    }
    let mut end = MAX;
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}… ({} bytes)", &text[..end], text.len())
}
