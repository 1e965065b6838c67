#!/usr/bin/env python3
"""List module import cycles among the files of a Rust crate.

Usage: scripts/import_cycles.py [SRC_DIR] [--pairs] [--edges FILE]

Reads every `.rs` file under SRC_DIR (default `src`), resolves each `use crate::…`,
`use super::…`, `use self::…` and each inline `crate::…`/`super::…` path to the file that
defines it (following `pub use` re-exports), and prints the strongly connected components of
the file import graph that hold more than two files, largest first, one component a paragraph.
`--pairs` also prints the two-file cycles (a file and the file it imports importing it back);
`--edges FILE` prints the files FILE imports and the files importing it.
Comments and string literals are ignored; `mod` declarations are not imports. The exit status
is 1 when a component of more than two files exists, else 0.
"""

import os
import re
import sys

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def strip(text):
    """Text with comments, strings and char literals blanked (offsets kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:]) and (i == 0 or not re.match(r"\w", text[i - 1])):
            m = re.match(r'r(#*)"', text[i:])
            close = '"' + m.group(1)
            j = text.find(close, i + len(m.group(0)))
            j = n if j < 0 else j + len(close)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j = min(n, j + 1)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "'":
            m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:])
            if m:
                out.append(" " * len(m.group(0)))
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def module_files(src):
    """Map module path (tuple of names, crate root = ()) to its file, relative to src."""
    mods = {}
    for root, _, files in os.walk(src):
        for f in files:
            if not f.endswith(".rs"):
                continue
            rel = os.path.relpath(os.path.join(root, f), src)
            parts = rel[:-3].split(os.sep)
            if parts == ["lib"]:
                mods[()] = rel
            elif parts == ["main"]:
                continue
            elif parts[-1] == "mod":
                mods[tuple(parts[:-1])] = rel
            else:
                mods[tuple(parts)] = rel
    return mods


def expand_use(tree):
    """Flatten a use tree `a::{b, c::{d, e as f}}` into (path, alias) pairs."""
    tree = re.sub(r"\s+", "", tree)
    results = []

    def walk(prefix, t):
        items, depth, cur = [], 0, ""
        for ch in t:
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            if ch == "," and depth == 0:
                items.append(cur)
                cur = ""
            else:
                cur += ch
        if cur:
            items.append(cur)
        for item in items:
            b = item.find("{")
            if b >= 0:
                head = item[:b].rstrip(":")
                inner = item[b + 1 : item.rfind("}")]
                walk(prefix + ([s for s in head.split("::") if s]), inner)
            else:
                alias = None
                if "as" in item and re.search(r"as" + IDENT + "$", item):
                    m = re.match(r"(.*?)as(" + IDENT + ")$", item)
                    # `as` joins without spaces after whitespace removal: split on the last `as`
                    item, alias = m.group(1), m.group(2)
                segs = [s for s in item.split("::") if s]
                if segs and segs[-1] == "self":
                    segs = segs[:-1]
                results.append((prefix + segs, alias))

    walk([], tree)
    return results


def inline_modules(text):
    """Spans (start, end, name) of inline `mod name { … }` blocks in stripped text."""
    spans = []
    for m in re.finditer(r"\bmod\s+(" + IDENT + r")\s*\{", text):
        depth, j = 1, m.end()
        while j < len(text) and depth:
            if text[j] == "{":
                depth += 1
            elif text[j] == "}":
                depth -= 1
            j += 1
        spans.append((m.start(), j, m.group(1)))
    return spans


def scope_at(spans, pos):
    """Names of the inline modules enclosing offset pos, outermost first."""
    return [name for (s, e, name) in sorted(spans) if s <= pos < e]


def absolute(segs, module):
    """Absolute path (list) of a `crate::`/`super::`/`self::` path seen in module, or None."""
    if not segs:
        return None
    if segs[0] == "crate":
        return segs[1:]
    if segs[0] in ("super", "self"):
        base = list(module)
        i = 0
        while i < len(segs) and segs[i] in ("super", "self"):
            if segs[i] == "super":
                if not base:
                    return None
                base.pop()
            i += 1
        return base + segs[i:]
    return None


class Crate:
    def __init__(self, src):
        self.src = src
        self.mods = module_files(src)
        self.file_mod = {f: m for m, f in self.mods.items()}
        self.text = {}
        self.reexports = {}  # file -> {name: absolute path}
        for mod, f in self.mods.items():
            raw = open(os.path.join(src, f), encoding="utf-8").read()
            self.text[f] = strip(raw)
        for mod, f in self.mods.items():
            self.reexports[f] = {}
            t = self.text[f]
            spans = inline_modules(t)
            for m in re.finditer(r"\bpub(\([^)]*\))?\s+use\s+([^;]+);", t):
                if scope_at(spans, m.start()):
                    continue
                for segs, alias in expand_use(m.group(2)):
                    if not segs or segs[-1] == "*":
                        continue
                    ab = absolute(segs, mod)
                    if ab is None:
                        # a path relative to the module (`pub use child::Item`)
                        ab = list(mod) + segs
                    self.reexports[f][alias or segs[-1]] = ab

    def resolve(self, path, depth=0):
        """The file defining the item at absolute path (list of names), or None."""
        best = None
        for k in range(len(path), -1, -1):
            if tuple(path[:k]) in self.mods:
                best = k
                break
        if best is None:
            return None
        f = self.mods[tuple(path[:best])]
        rest = path[best:]
        if rest and depth < 8 and rest[0] in self.reexports.get(f, {}):
            target = self.reexports[f][rest[0]] + rest[1:]
            g = self.resolve(target, depth + 1)
            if g is not None:
                return g
        return f

    def edges(self):
        graph = {f: set() for f in self.text}
        for f, t in self.text.items():
            mod = self.file_mod[f]
            spans = inline_modules(t)
            used = []
            for m in re.finditer(r"\buse\s+([^;]+);", t):
                scope = list(mod) + scope_at(spans, m.start())
                for segs, _ in expand_use(m.group(1)):
                    ab = absolute(segs, scope)
                    if ab is None and segs and segs[0] != "*" and tuple(list(mod) + segs[:1]) in self.mods:
                        ab = list(mod) + segs  # 2015-style relative `use child::…`
                    if ab is not None:
                        used.append([s for s in ab if s != "*"])
                t = t[: m.start()] + " " * (m.end() - m.start()) + t[m.end() :]
            for m in re.finditer(r"\b(crate|super|self)((?:\s*::\s*" + IDENT + r")+)", t):
                scope = list(mod) + scope_at(spans, m.start())
                segs = [m.group(1)] + [s.strip() for s in m.group(2).split("::") if s.strip()]
                ab = absolute(segs, scope)
                if ab is not None:
                    used.append(ab)
            for ab in used:
                g = self.resolve(ab)
                if g is not None and g != f:
                    graph[f].add(g)
        return graph


def components(graph):
    """Strongly connected components (Tarjan, iterative)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                    advanced = True
                    break
                elif w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                out.append(sorted(comp))
    return out


def main(argv):
    src, pairs, edges_of = "src", False, None
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--pairs":
            pairs = True
        elif a == "--edges":
            edges_of = args.pop(0)
        elif a in ("-h", "--help"):
            print(__doc__)
            return 0
        else:
            src = a
    graph = Crate(src).edges()
    if edges_of:
        print("imports:", " ".join(sorted(graph.get(edges_of, []))))
        print("imported by:", " ".join(sorted(f for f in graph if edges_of in graph[f])))
        return 0
    big = sorted((c for c in components(graph) if len(c) > 2), key=lambda c: (-len(c), c))
    for c in big:
        print(f"cycle of {len(c)} files:")
        for f in c:
            inside = sorted(g for g in graph[f] if g in c)
            print(f"  {f} -> {' '.join(inside)}")
    two = sorted({tuple(sorted((a, b))) for a in graph for b in graph[a] if a in graph.get(b, ())})
    if pairs:
        for a, b in two:
            print(f"two-file cycle: {a} <-> {b}")
    print(f"{len(big)} cycles of more than two files; {len(two)} two-file cycles")
    return 1 if big else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
