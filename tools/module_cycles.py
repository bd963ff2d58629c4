#!/usr/bin/env python3
"""Finds circles among each crate's top-level modules.

A crate's top-level modules are the files and folders directly under its src/ (besides
lib.rs/main.rs). Module A uses module B when a file of A names `crate::B` or, from A's own
top-level file, `super::B` or a `use` of `B::` through the crate root. The architecture
asks that these uses point one way (docs/ARCHITECTURE.md); this prints every strongly
connected group of two or more modules and exits 1 if there is one.

    python3 tools/module_cycles.py            # every crate under crates/
    python3 tools/module_cycles.py crates/render
"""

import os
import re
import sys


def modules(src):
    """Top-level module name -> list of its source files."""
    found = {}
    for entry in sorted(os.listdir(src)):
        path = os.path.join(src, entry)
        if entry.endswith(".rs") and entry not in ("lib.rs", "main.rs"):
            found[entry[:-3]] = [path]
        elif os.path.isdir(path) and entry != "bin":
            files = []
            for root, _, names in os.walk(path):
                files += [os.path.join(root, n) for n in names if n.endswith(".rs")]
            found[entry] = files
    return found


def strip_comments(text):
    text = re.sub(r"//[^\n]*", "", text)
    return re.sub(r"/\*.*?\*/", "", text, flags=re.S)


def reexports(src):
    """Names the crate root re-exports from its modules (`pub use m::{A, B}`) -> module."""
    found = {}
    for lib in ("lib.rs", "main.rs"):
        path = os.path.join(src, lib)
        if not os.path.exists(path):
            continue
        text = strip_comments(open(path, encoding="utf-8").read())
        for m in re.finditer(r"pub use ([a-z_][a-z0-9_]*)::(\{[^}]*\}|[A-Za-z_][A-Za-z0-9_]*)\s*;", text):
            module, names = m.group(1), m.group(2).strip("{}")
            for part in names.split(","):
                part = part.strip().split(" as ")[-1].split("::")[-1].strip()
                if part:
                    found[part] = module
    return found


def uses(name, files, names, exported):
    """The other top-level modules that module `name` refers to."""
    out = set()
    for path in files:
        text = strip_comments(open(path, encoding="utf-8").read())
        # Test modules may reach anywhere.
        text = re.split(r"#\[cfg\(test\)\]\s*mod tests", text)[0]
        top_level = os.path.dirname(path).endswith("src") or os.path.basename(path) == "mod.rs" and os.path.dirname(
            os.path.dirname(path)
        ).endswith("src")
        for m in re.finditer(r"\bcrate::([A-Za-z_][A-Za-z0-9_]*)", text):
            out.add(m.group(1))
        for m in re.finditer(r"\bcrate::\{([^}]*)\}", text):
            for part in m.group(1).split(","):
                out.add(part.strip().split("::")[0])
        if top_level:
            for m in re.finditer(r"\bsuper::([A-Za-z_][A-Za-z0-9_]*)", text):
                out.add(m.group(1))
            # `use super::{a, b::c}` groups.
            for m in re.finditer(r"\b(?:super|crate)::\{([^}]*)\}", text):
                for part in m.group(1).split(","):
                    out.add(part.strip().split("::")[0])
    out = {exported.get(m, m) for m in out}
    return {m for m in out if m in names and m != name}


def cycles(graph):
    """Strongly connected components of two or more nodes (Tarjan)."""
    index, low, stack, on, result = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                result.append(sorted(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return result


def main(argv):
    roots = argv[1:] or [os.path.join("crates", c) for c in sorted(os.listdir("crates"))]
    bad = 0
    for root in roots:
        src = os.path.join(root, "src")
        if not os.path.isdir(src):
            continue
        mods = modules(src)
        exported = reexports(src)
        graph = {name: uses(name, files, mods, exported) for name, files in mods.items()}
        for group in cycles(graph):
            bad += 1
            edges = [f"{a}->{b}" for a in group for b in sorted(graph[a]) if b in group]
            print(f"{root}: modules in a circle: {', '.join(group)} ({'; '.join(edges)})")
    if bad:
        return 1
    print(f"module_cycles: no circles among the top-level modules of {len(roots)} crates")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
