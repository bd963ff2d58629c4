//! The graph of named shaders: which named shader's parameters connect to which
//! (`"p" = "other"`, `= "other.member"`, shader lists `= "other"`), checked before anything
//! evaluates it.
//!
//! Two things no renderer can evaluate are errors here, so that `mira check --scene`
//! reports them and `mira render` stops before rendering: a cycle of connections (a shader
//! that depends on its own result), and a chain of connections deeper than
//! [`MAX_SHADER_DEPTH`] (shader evaluation recurses once per connection). The walk itself
//! is iterative, so a file cannot overflow the stack here whatever its size.

use std::collections::HashMap;

use mi::ast::{Param, ShaderItem, ShaderList, Value};
use mi::{Diagnostic, Span};

use crate::names::{Def, Table};

/// Longest chain of connected named shaders mira evaluates (a shader connected to a
/// shader … `MAX_SHADER_DEPTH` shaders in all).
pub const MAX_SHADER_DEPTH: usize = 256;

/// One connection: the named shader it reaches and where it is written.
#[derive(Clone, Debug)]
struct Edge {
    to: usize,
    span: Span,
}

/// Named shaders and their connections.
struct Graph {
    names: Vec<String>,
    spans: Vec<Span>,
    edges: Vec<Vec<Edge>>,
}

/// Reports connection cycles and too-deep chains among the named shaders of `table`.
pub fn check(table: &Table, diags: &mut Vec<Diagnostic>) {
    let graph = Graph::of(table);
    let depths = walk(&graph, diags);
    // The deepest chain, reported once at the shader that starts it.
    if let Some((start, depth)) = depths.iter().enumerate().max_by_key(|(i, d)| (**d, std::cmp::Reverse(*i))) {
        if *depth > MAX_SHADER_DEPTH {
            diags.push(Diagnostic::error(
                graph.spans[start],
                format!(
                    "shader '{}' starts a chain of {depth} connected shaders; mira evaluates chains of at most \
                     {MAX_SHADER_DEPTH}",
                    graph.names[start]
                ),
            ));
        }
    }
}

impl Graph {
    fn of(table: &Table) -> Graph {
        let mut named: Vec<(&String, &crate::names::Element)> =
            table.elements.iter().filter(|(_, e)| matches!(e.def, Def::Shader(_))).collect();
        // Sorted by position in the file, so that messages come in a stable order.
        named.sort_by_key(|(n, e)| (e.span.file, e.span.lo, n.as_str()));
        let index: HashMap<&str, usize> = named.iter().enumerate().map(|(i, (n, _))| (n.as_str(), i)).collect();
        let mut graph = Graph {
            names: named.iter().map(|(n, _)| (*n).clone()).collect(),
            spans: named.iter().map(|(_, e)| e.span).collect(),
            edges: Vec::with_capacity(named.len()),
        };
        for (_, e) in &named {
            let mut out = Vec::new();
            if let Def::Shader(defs) = &e.def {
                if let Some(d) = defs.last() {
                    let mut collect = Collect { table, scope: &e.scope, index: &index, out: &mut out };
                    collect.list(&d.list);
                }
            }
            graph.edges.push(out);
        }
        graph
    }
}

/// Gathers the connections written in one shader's definition.
struct Collect<'c, 't, 'a> {
    table: &'t Table<'a>,
    scope: &'c str,
    index: &'c HashMap<&'c str, usize>,
    out: &'c mut Vec<Edge>,
}

impl Collect<'_, '_, '_> {
    fn list(&mut self, list: &ShaderList) {
        for item in &list.0 {
            match item {
                ShaderItem::Ref(name) => self.target(&name.text, name.span, false),
                ShaderItem::Call { params, .. } => self.params(params),
                ShaderItem::Define { list, .. } => self.list(list),
            }
        }
    }

    fn params(&mut self, params: &[Param]) {
        for p in params {
            self.value(&p.value);
        }
    }

    // Recursion here follows the nesting of one value, which the parser bounds.
    fn value(&mut self, v: &Value) {
        match v {
            Value::Connect(name) => self.target(&name.text, name.span, true),
            Value::Define(item) => self.list(&ShaderList(vec![(**item).clone()])),
            Value::Struct(fields) => self.params(fields),
            Value::Array(vs) | Value::Seq(vs) => vs.iter().for_each(|v| self.value(v)),
            _ => {}
        }
    }

    /// The named shader `name` (or `shader.member`) reached from here, if it exists
    /// (unknown names are reported by [`crate::references`]).
    fn target(&mut self, name: &str, span: Span, member: bool) {
        let shader = |n: &str| {
            let full = self.table.resolve_name(n, self.scope)?;
            self.index.get(full.as_str()).copied()
        };
        let to = shader(name).or_else(|| if member { shader(name.rsplit_once('.')?.0) } else { None });
        if let Some(to) = to {
            self.out.push(Edge { to, span });
        }
    }
}

/// Depth-first walk with an explicit stack: reports each cycle once (at the connection
/// that closes it) and returns, for every shader, the length of the longest chain of
/// connections that starts there (1 for a shader connected to nothing; shaders on or
/// behind a cycle count only their acyclic part).
fn walk(graph: &Graph, diags: &mut Vec<Diagnostic>) -> Vec<usize> {
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        New,
        Open,
        Done,
    }
    let n = graph.names.len();
    let mut state = vec![State::New; n];
    let mut depth = vec![1usize; n];
    for root in 0..n {
        if state[root] != State::New {
            continue;
        }
        // (node, next edge to follow)
        let mut stack: Vec<(usize, usize)> = vec![(root, 0)];
        state[root] = State::Open;
        while let Some(top) = stack.last_mut() {
            let node = top.0;
            if let Some(edge) = graph.edges[node].get(top.1) {
                top.1 += 1;
                match state[edge.to] {
                    State::New => {
                        state[edge.to] = State::Open;
                        stack.push((edge.to, 0));
                    }
                    State::Open => {
                        let from = stack.iter().position(|(s, _)| *s == edge.to).unwrap_or(0);
                        let mut names: Vec<&str> =
                            stack[from..].iter().map(|(s, _)| graph.names[*s].as_str()).collect();
                        names.push(&graph.names[edge.to]);
                        diags.push(Diagnostic::error(
                            edge.span,
                            format!("shader connections form a cycle: {}", cycle_text(&names)),
                        ));
                    }
                    State::Done => {}
                }
            } else {
                stack.pop();
                state[node] = State::Done;
                let below = graph.edges[node]
                    .iter()
                    .filter(|e| state[e.to] == State::Done)
                    .map(|e| depth[e.to])
                    .max()
                    .unwrap_or(0);
                depth[node] = below + 1;
            }
        }
    }
    depth
}

/// A cycle for a message: all of it when short, else its two ends.
fn cycle_text(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
    if quoted.len() <= 8 {
        return quoted.join(" -> ");
    }
    format!(
        "{} -> … {} more … -> {}",
        quoted[..3].join(" -> "),
        quoted.len() - 6,
        quoted[quoted.len() - 3..].join(" -> ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn diagnostics(text: &str) -> Vec<String> {
        let parsed = mi::parse_source(mi::Origin::Memory("g.mi".into()), text.as_bytes().to_vec(), &Default::default());
        assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
        let mut diags = Vec::new();
        let (table, _) = Table::collect(&parsed.items, 0, &mut diags);
        check(&table, &mut diags);
        diags.iter().map(|d| d.render(&parsed.sources).lines().next().unwrap_or_default().to_string()).collect()
    }

    fn chain(n: usize) -> String {
        let mut s = String::from("shader \"s0\" \"mib_color_mix\" ()\n");
        for i in 1..n {
            s += &format!("shader \"s{i}\" \"mib_color_mix\" (\"color_0\" = \"s{}\")\n", i - 1);
        }
        s
    }

    #[test]
    fn a_cycle_is_reported_once_at_the_connection_that_closes_it() {
        let d = diagnostics(
            "shader \"a\" \"mib_color_mix\" (\"color_0\" = \"b\")\nshader \"b\" \"mib_color_mix\" (\"color_0\" = \"a\")\n",
        );
        assert_eq!(d, ["g.mi:2:41: error: shader connections form a cycle: 'a' -> 'b' -> 'a'"]);
        let d = diagnostics("shader \"a\" \"mib_color_mix\" (\"color_0\" = \"a.result\")\n");
        assert_eq!(d, ["g.mi:1:41: error: shader connections form a cycle: 'a' -> 'a'"]);
    }

    #[test]
    fn shared_inputs_are_not_cycles() {
        // A diamond: d uses b and c, both use a.
        let d = diagnostics(
            "shader \"a\" \"mib_color_mix\" ()\nshader \"b\" \"mib_color_mix\" (\"color_0\" = \"a\")\n\
             shader \"c\" \"mib_color_mix\" (\"color_0\" = \"a\")\n\
             shader \"d\" \"mib_color_mix\" (\"color_0\" = \"b\", \"color_1\" = \"c\")\n",
        );
        assert!(d.is_empty(), "{d:?}");
    }

    #[test]
    fn chains_up_to_the_limit_pass_and_longer_ones_are_an_error() {
        assert!(diagnostics(&chain(MAX_SHADER_DEPTH)).is_empty());
        let n = MAX_SHADER_DEPTH + 1;
        let d = diagnostics(&chain(n));
        assert_eq!(
            d,
            [format!(
                "g.mi:{n}:1: error: shader 's{}' starts a chain of {n} connected shaders; mira evaluates chains of \
                 at most {MAX_SHADER_DEPTH}",
                n - 1
            )]
        );
    }

    /// 50 000 connected shaders (issue 15 found the stack overflow with this many): one
    /// error, no recursion.
    #[test]
    fn a_very_long_chain_is_one_error() {
        let d = diagnostics(&chain(50_000));
        assert_eq!(d.len(), 1, "{d:?}");
        assert!(d[0].contains("starts a chain of 50000 connected shaders"), "{d:?}");
    }
}
