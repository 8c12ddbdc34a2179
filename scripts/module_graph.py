#!/usr/bin/env python3
"""The library's import graph, checked against the order of the data flow.

Reads every `src/**/*.rs`, collects the `crate::…`, `super::…` and `self::…`
paths each file names (in `use` items and inline), and prints two graphs:

* modules: the top-level modules of the crate (`solver`, `contact`, ...),
  one edge per pair of modules where a file of the first names the second;
* files: one edge per pair of files, where a path is resolved to the
  deepest file that exists for it.

It fails (exit 1) on a cycle in either graph and on a module edge that runs
against the layer order below (a lower layer naming a higher one).

A module's `mod.rs` (or `lib.rs`) declaring its children (`mod x;`) and
re-exporting their items (`pub use x::Y;`) is its facade, not a dependency:
those lines add no edge. Everything else in it does.

Usage: python3 scripts/module_graph.py [--quiet] [--src DIR]

`--src` reads another source tree (tests/architecture.rs runs a fixture
with a known cycle, to see that the check can fail).
"""

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "src"

# The data flow, lowest first: a module may name modules of its own layer
# or lower ones, never a higher one. Within a layer, edges must not cycle.
LAYERS = [
    # the iteration record is plain data that an error carries
    ["error", "history"],
    # sparse linear algebra knows nothing of the mechanics: the problem
    # factorises with it and the solver condenses with it, so it sits below
    # both (the order lists it after `problem` by where it is used)
    ["sparse", "linsolve", "condense"],
    ["nurbs", "geometry", "quadrature", "material"],
    ["space", "dofs", "interface", "pressure"],
    ["assembly"],
    ["contact"],
    ["problem", "wellposed"],
    ["solver"],
    ["post"],
    ["report", "timing", "resources"],
    ["scene"],
    # The binary. (The book's machinery and the chapter programs' allocator
    # are not the library's: they live in book/companion, outside src/.)
    ["main"],
]
RANK = {m: i for i, layer in enumerate(LAYERS) for m in layer}

PATH = re.compile(r"\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP = re.compile(r"\buse\s+(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{", re.S)
FACADE = re.compile(r"^\s*(pub(\([^)]*\))?\s+)?(mod\s+\w+\s*;|use\s+(self::)?(?!crate\b|super\b)\w+(::[\w{}, *]+)*\s*;)", re.M)


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def module_of(path):
    """The module path of a source file: src/solver/kernel.rs → [solver, kernel]."""
    rel = path.relative_to(SRC).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] in ("mod", "lib"):
        parts = parts[:-1]
    return parts


def file_of(parts):
    """The deepest existing file for a module path (items resolve to their module)."""
    for n in range(len(parts), 0, -1):
        base = SRC.joinpath(*parts[:n])
        for cand in (base.with_suffix(".rs"), base / "mod.rs"):
            if cand.exists():
                return cand
    return SRC / "lib.rs"


def is_root(path):
    return path.name in ("mod.rs", "lib.rs")


def group_paths(text):
    """`use crate::a::{b, c::d}` → crate::a::b, crate::a::c::d (one level deep)."""
    out = []
    for m in USE_GROUP.finditer(text):
        depth, i = 1, m.end()
        start = i
        while i < len(text) and depth:
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        for item in re.split(r",(?![^{]*\})", text[start : i - 1]):
            item = item.strip().split("{")[0].rstrip(":").strip()
            if item and item != "self":
                out.append((m.group(1), m.group(2) + "::" + item.split(" as ")[0].strip()))
    return out


def resolve(path, head, tail):
    here = module_of(path)
    own = here if is_root(path) else here
    segs = [s for s in tail.split("::") if s]
    if head == "crate":
        parts = segs
    elif head == "self":
        parts = own + segs
    else:  # super: the parent of this file's module
        parts = own[:-1] + segs
        while parts and parts[0] == "super":
            parts = parts[1:]
    return parts


def edges_of(path):
    text = strip_comments(path.read_text())
    if is_root(path):
        text = FACADE.sub("", text)
    found = [(m.group(1), m.group(2)) for m in PATH.finditer(text)] + group_paths(text)
    files, modules = set(), set()
    for head, tail in found:
        parts = resolve(path, head, tail)
        if not parts:
            continue
        target = file_of(parts)
        if target != path:
            files.add(target)
        modules.add(parts[0])
    return files, modules


def top(path):
    parts = module_of(path)
    return parts[0] if parts else ("main" if path.name == "main.rs" else "lib")


def cycles(graph):
    """Strongly connected components with more than one node (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main():
    global SRC, ROOT
    quiet = "--quiet" in sys.argv
    if "--src" in sys.argv:
        SRC = Path(sys.argv[sys.argv.index("--src") + 1]).resolve()
        ROOT = SRC.parent
    files = sorted(p for p in SRC.rglob("*.rs"))
    file_graph, module_graph = {}, {}
    for f in files:
        fe, me = edges_of(f)
        file_graph[f] = fe
        src = top(f)
        if src == "lib":
            continue
        for m in me:
            if m != src and m in RANK or m not in RANK and m != src:
                module_graph.setdefault(src, set()).add(m)
    rel = lambda p: str(p.relative_to(ROOT))
    problems = []
    unknown = sorted({m for es in module_graph.values() for m in es} | set(module_graph)) 
    for m in unknown:
        if m not in RANK:
            problems.append(f"module `{m}` has no layer in scripts/module_graph.py")
    against = []
    for a in sorted(module_graph):
        for b in sorted(module_graph[a]):
            if a in RANK and b in RANK and RANK[b] > RANK[a]:
                against.append((a, b))
    mod_cycles = cycles(module_graph)
    file_cycles = cycles({rel(k): {rel(x) for x in v} for k, v in file_graph.items()})
    if not quiet:
        print("module graph (layer order, lowest first):")
        for layer in LAYERS:
            for m in layer:
                if m in module_graph or any(m in v for v in module_graph.values()):
                    deps = ", ".join(sorted(module_graph.get(m, ())))
                    print(f"  {m} [{RANK[m]}] -> {deps or '-'}")
        n_file_edges = sum(len(v) for v in file_graph.values())
        print(f"files: {len(files)}, file edges: {n_file_edges}")
    for a, b in against:
        problems.append(f"edge against the order: {a} [{RANK[a]}] -> {b} [{RANK[b]}]")
    for c in mod_cycles:
        problems.append("module cycle: " + " <-> ".join(c))
    for c in file_cycles:
        problems.append("file cycle: " + " <-> ".join(c))
    print(f"{len(mod_cycles)} module cycles, {len(file_cycles)} file cycles, {len(against)} edges against the order")
    for p in problems:
        print("  " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
