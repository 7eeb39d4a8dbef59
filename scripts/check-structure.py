#!/usr/bin/env python3
"""Structure checks of the Rust sources in src/ (one concept per file, short functions, layers):

  1. no file over 600 lines of non-test code (every line outside `#[cfg(test)]` items;
     a file declared as `#[cfg(test)] mod NAME;` is test code as a whole);
  2. no function over 120 lines (a `fn` item, from its `fn` line to its closing brace,
     found by brace counting with comments, strings and character literals blanked out), except
     those in the exceptions file, each with its reason;
  3. no import cycle between modules: the `use` declarations and the `crate::`, `super::`,
     `self::` (and child-module) paths of non-test code, resolved to the module that defines
     the item (re-exports followed), give a graph at every level of the module tree: the
     top-level modules of the crate, then the files and sub-modules within each module. A cycle
     at any level fails and is printed with the line of each edge. A module's `pub use` of its
     own descendants (a facade) is not an edge.

    python3 scripts/check-structure.py [--src DIR] [--exceptions FILE] [--graph]
                                       [--max-file-lines N] [--max-fn-lines N]

--src defaults to src/ of this repository, --exceptions to scripts/structure-exceptions.txt
(lines `PATH::FN  reason`, or `PATH  reason` for a file over the limit; `#` starts a comment).
--graph prints the module graph of every level. Exits 1 when a check fails, 2 on a usage error.
Python 3 standard library only.
"""

import argparse
import re
import sys
from collections import defaultdict
from pathlib import Path

MAX_FILE_LINES = 600
MAX_FN_LINES = 120
ROOT = Path(__file__).resolve().parent.parent
# The name by which the checked crate's own binaries refer to it (`muscle_actuator::…` in
# src/main.rs); `--crate-name` for another crate (python/src, the extension, is `_core`).
CRATE_NAME = ["muscle_actuator"]

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
CFG_TEST = re.compile(r"#\s*\[\s*cfg\s*\(\s*(?:all\s*\(\s*)?test\b[^\]]*\]")
FN_ITEM = re.compile(r"\bfn\s+(" + IDENT + r")")
USE_DECL = re.compile(r"(\bpub\s*(?:\([^)]*\))?\s*)?\buse\s+([^;]*);")
INLINE_PATH = re.compile(r"(?<![A-Za-z0-9_:])(crate|super|self|muscle_actuator)((?:\s*::\s*" + IDENT + r")+)")
MOD_DECL = re.compile(r"\bmod\s+(" + IDENT + r")\s*([;{])")
ITEM_DEF = re.compile(r"\b(?:struct|enum|union|trait|type|const|static|fn|mod|macro_rules!)\s+(" + IDENT + r")")
KEYWORDS = {"crate", "super", "self", "Self"}


# --- lexing --------------------------------------------------------------------------------


def blank(text):
    """`text` with comments and the contents of string and character literals replaced by
    spaces (newlines kept, so offsets and line numbers stay those of the source)."""
    out = list(text)
    n = len(text)
    i = 0

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            wipe(i, j)
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
            wipe(i, j)
            i = j
        elif (m := re.match(r'b?r(#*)"', text[i:i + 260])) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            close = '"' + m.group(1)
            start = i + m.end()
            j = text.find(close, start)
            j = n if j < 0 else j
            wipe(start, j)
            i = j + len(close)
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            wipe(i + 1, min(j, n))
            i = j + 1
        elif c == "'":
            # A character literal ('x', '\n', '\u{1F600}', '\''), or a lifetime ('a).
            if i + 1 < n and text[i + 1] == "\\":
                j = text.find("'", i + 3)
                j = n if j < 0 else j
                wipe(i + 1, j)
                i = j + 1
            elif i + 2 < n and text[i + 2] == "'":
                wipe(i + 1, i + 2)
                i += 3
            else:
                i += 1
        else:
            i += 1
    return "".join(out)


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def matching_brace(text, open_at):
    """The offset of the `}` closing the `{` at `open_at` (in blanked text)."""
    depth = 0
    for j in range(open_at, len(text)):
        if text[j] == "{":
            depth += 1
        elif text[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(text) - 1


def item_end(text, start):
    """The end of the item starting at `start`: its `;` or its body's closing `}`, whichever
    comes first outside parentheses, brackets and generics; for a field or a variant (an item
    of a list), the `,` or `}` that ends it. Returns (end offset, whether it has a body)."""
    depth = angles = 0
    for j in range(start, len(text)):
        c = text[j]
        if c in "([":
            depth += 1
        elif c in ")]":
            depth -= 1
        elif c == "<":
            angles += 1
        elif c == ">" and text[j - 1] not in "-=" and angles:
            angles -= 1
        elif depth == 0 and c == ";":
            return j, False
        elif depth == 0 and c == "{":
            return matching_brace(text, j), True
        elif depth == 0 and c == "}" or depth == 0 and angles == 0 and c == ",":
            return j - 1, False
    return len(text) - 1, False


# --- one source file -------------------------------------------------------------------------


class Source:
    def __init__(self, path, rel):
        self.path = path
        self.rel = rel  # e.g. "src/sim/part.rs"
        self.text = blank(path.read_text(encoding="utf-8", errors="replace"))
        self.lines = self.text.count("\n") + (0 if self.text.endswith("\n") else 1)
        self.test_only = False  # declared `#[cfg(test)] mod x;`
        self.test_lines = set()
        self.test_mods = set()  # child modules declared under #[cfg(test)]
        for m in CFG_TEST.finditer(self.text):
            j = m.end()
            # Further attributes of the same item.
            while (a := re.match(r"\s*#\s*\[", self.text[j:])) is not None:
                j = self.text.index("]", j + a.end()) + 1
                # (an attribute with nested brackets is rare in this position; good enough)
            end, _ = item_end(self.text, j)
            decl = MOD_DECL.match(re.sub(r"^\s*(?:pub\s*(?:\([^)]*\))?\s*)?", "", self.text[j:end + 1]))
            if decl:
                self.test_mods.add(decl.group(1))
            self.test_lines.update(range(line_of(self.text, m.start()), line_of(self.text, end) + 1))
        # Non-test code only, test items blanked out (line structure kept).
        keep = []
        for k, line in enumerate(self.text.split("\n"), start=1):
            keep.append("" if k in self.test_lines else line)
        self.code = "\n".join(keep)
        # Inline modules of non-test code (`mod name { ... }`): (body start, body end, name).
        self.inline = []
        for m in MOD_DECL.finditer(self.code):
            if m.group(2) == "{":
                self.inline.append((m.end() - 1, matching_brace(self.code, m.end() - 1), m.group(1)))

    def scope_at(self, offset):
        """The inline modules around `offset`, outermost first."""
        return tuple(n for a, b, n in self.inline if a < offset < b)

    def code_lines(self):
        return 0 if self.test_only else self.lines - len(self.test_lines)

    def functions(self):
        """(name, first line, number of lines) of every `fn` item with a body in non-test code."""
        if self.test_only:
            return []
        found = []
        for m in FN_ITEM.finditer(self.code):
            end, body = item_end(self.code, m.end())
            if not body:
                continue
            a, b = line_of(self.code, m.start()), line_of(self.code, end)
            found.append((m.group(1), a, b - a + 1))
        return found


# --- the module tree ---------------------------------------------------------------------------


def module_of(rel_in_src):
    """The module path of a file under src/ (a tuple; () is the crate root), or None for a
    binary crate root other than lib.rs."""
    parts = list(Path(rel_in_src).with_suffix("").parts)
    if parts == ["lib"]:
        return ()
    if parts == ["main"]:
        return ("main",)  # the binary: a top-level node of its own
    if parts[-1] == "mod":
        parts = parts[:-1]
    return tuple(parts)


def parse_use_tree(s):
    """The paths of a use tree (`a::{b, c::{d as e, self}, f::*}`), each as (segments, alias)."""
    tokens = re.findall(IDENT + r"|::|\{|\}|,|\*", s)
    pos = 0

    def tree(prefix):
        nonlocal pos
        out = []
        segs = list(prefix)
        while pos < len(tokens):
            t = tokens[pos]
            if t == "{":
                pos += 1
                while pos < len(tokens) and tokens[pos] != "}":
                    out += tree(segs)
                    if pos < len(tokens) and tokens[pos] == ",":
                        pos += 1
                pos += 1  # }
                return out
            if t in (",", "}"):
                break
            if t == "::":
                pos += 1
                continue
            if t == "*":
                out.append((segs + ["*"], None))
                pos += 1
                return out
            if t == "as":
                alias = tokens[pos + 1] if pos + 1 < len(tokens) else None
                pos += 2
                out.append((segs, alias))
                return out
            segs.append(t)
            pos += 1
        if segs != list(prefix):
            if segs[-1] == "self":
                segs = segs[:-1]
            out.append((segs, None))
        return out

    return tree([])


class Crate:
    def __init__(self, src):
        self.src = src
        self.files = {}  # module path -> Source
        for p in sorted(src.rglob("*.rs")):
            rel = p.relative_to(src)
            mod = module_of(rel)
            self.files[mod] = Source(p, str(Path(src.name) / rel))
        # Files declared as test-only modules by their parent.
        for mod, s in self.files.items():
            for name in s.test_mods:
                child = self.files.get((mod + (name,)) if mod != ("main",) else None)
                if child is not None:
                    child.test_only = True
        self.defined = {}  # module -> names of the items it defines
        self.reexports = {}  # module -> {name: absolute path}
        self.globs = {}  # module -> [absolute module paths re-exported with *]
        for mod, s in self.files.items():
            self.defined[mod] = set(ITEM_DEF.findall(s.code))
            self.reexports[mod], self.globs[mod] = {}, []
            for m in USE_DECL.finditer(s.code):
                if not m.group(1) or s.scope_at(m.start()):
                    continue
                for segs, alias in parse_use_tree(m.group(2)):
                    absolute = self.absolute(mod, segs)
                    if absolute is None:
                        continue
                    if absolute[-1] == "*":
                        self.globs[mod].append(tuple(absolute[:-1]))
                    elif absolute:
                        self.reexports[mod][alias or absolute[-1]] = tuple(absolute)

    def is_module(self, path):
        return tuple(path) in self.files

    def absolute(self, mod, segs):
        """`segs` (a path written in module `mod`) as a path from the crate root, or None when it
        names another crate."""
        if not segs:
            return None
        head, rest = segs[0], list(segs[1:])
        if head == "crate" or head == CRATE_NAME[0]:
            return rest
        if head == "self":
            return list(mod) + rest
        if head == "super":
            base = list(mod)
            while segs and segs[0] == "super":
                base = base[:-1]
                segs = segs[1:]
            return base + list(segs)
        if mod == ("main",):
            return None
        if self.is_module(tuple(mod) + (head,)):
            return list(mod) + list(segs)  # a child module, named relative to `mod`
        return None

    def resolve(self, path, depth=0):
        """The module that defines what `path` (from the crate root) names."""
        mod = ()
        path = list(path)
        for k, seg in enumerate(path):
            if seg == "*":
                return mod
            if self.is_module(mod + (seg,)):
                mod = mod + (seg,)
                continue
            if depth < 8 and seg not in self.defined.get(mod, ()):
                if seg in self.reexports.get(mod, {}):
                    return self.resolve(list(self.reexports[mod][seg]) + path[k + 1:], depth + 1)
                for g in self.globs.get(mod, []):
                    if seg in self.defined.get(g, ()) or seg in self.reexports.get(g, {}):
                        return self.resolve(list(g) + path[k:], depth + 1)
            return mod
        return mod

    def edges(self):
        """{(from module, to module): (file, line, path as written)} for non-test code."""
        out = {}
        for mod, s in self.files.items():
            if s.test_only:
                continue
            code = s.code

            def add(segs, offset, written):
                absolute = self.absolute(mod + s.scope_at(offset), segs)
                if absolute is None:
                    return
                target = self.resolve(absolute)
                if target != mod and (mod, target) not in out:
                    out[(mod, target)] = (s.rel, line_of(code, offset), written)

            spans = []
            for m in USE_DECL.finditer(code):
                spans.append((m.start(), m.end()))
                public = bool(m.group(1))
                for segs, _ in parse_use_tree(m.group(2)):
                    absolute = self.absolute(mod + s.scope_at(m.start()), segs)
                    facade = public and absolute is not None and tuple(absolute[: len(mod)]) == mod
                    if not facade:
                        add(segs, m.start(), "use " + "::".join(segs))
            in_use = lambda o: any(a <= o < b for a, b in spans)  # noqa: E731
            for m in INLINE_PATH.finditer(code):
                if in_use(m.start()):
                    continue
                segs = [m.group(1)] + re.findall(IDENT, m.group(2))
                add(segs, m.start(), "::".join(segs))
            # Child modules named directly (`part::Part::new()`), in the module's own file.
            children = {c[-1] for c in self.files if len(c) == len(mod) + 1 and c[: len(mod)] == mod}
            if children and mod != ("main",):
                pat = re.compile(r"(?<![A-Za-z0-9_:])(" + "|".join(map(re.escape, sorted(children))) + r")\s*::\s*(" + IDENT + ")")
                for m in pat.finditer(code):
                    if in_use(m.start()):
                        continue
                    add([m.group(1), m.group(2)], m.start(), m.group(1) + "::" + m.group(2))
        return out


def name(mod):
    return "crate" if mod == () else "::".join(mod)


def levels(crate, edges):
    """{parent module: {(from node, to node): evidence}}: at the level of `parent`, a node is the
    parent itself (its own file) or one of its direct children (with all its descendants)."""
    parents = {m[:-1] for m in crate.files if m} | {()}
    out = {}
    for p in sorted(parents):
        lv = {}
        for (a, b), ev in edges.items():
            if a[: len(p)] != p or b[: len(p)] != p:
                continue
            na = p if a == p else a[: len(p) + 1]
            nb = p if b == p else b[: len(p) + 1]
            if na != nb and (na, nb) not in lv:
                lv[(na, nb)] = ev
        out[p] = lv
    return out


def cycles(edges):
    """The strongly connected components of more than one node, each as one cycle through it
    (a list of nodes, first repeated at the end)."""
    graph = defaultdict(set)
    nodes = set()
    for a, b in edges:
        graph[a].add(b)
        nodes |= {a, b}
    index, low, stack, on, comps = {}, {}, [], set(), []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                strong(w)
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
                comps.append(set(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            strong(v)
    found = []
    for comp in comps:
        start = min(comp)
        # Shortest way back to `start` within the component (breadth first).
        prev, frontier, seen = {}, [start], {start}
        back = None
        while frontier and back is None:
            nxt = []
            for v in frontier:
                for w in sorted(graph[v] & comp):
                    if w == start:
                        back = v
                        break
                    if w not in seen:
                        seen.add(w)
                        prev[w] = v
                        nxt.append(w)
                if back is not None:
                    break
            frontier = nxt
        path = [back]
        while path[-1] != start:
            path.append(prev[path[-1]])
        path.reverse()
        found.append(path + [start])
    return found


def load_exceptions(path):
    fns, files, problems = {}, {}, []
    if path is None or not path.exists():
        return fns, files, problems
    for k, raw in enumerate(path.read_text().splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        parts = line.split(None, 1)
        if len(parts) < 2:
            problems.append(f"{path.name}:{k}: an exception needs a reason: {raw.strip()}")
            continue
        key, reason = parts
        (fns if "::" in key else files)[key] = reason.strip()
    return fns, files, problems


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--src", type=Path, default=ROOT / "src")
    ap.add_argument("--exceptions", type=Path, default=None)
    ap.add_argument("--crate-name", default="muscle_actuator", help="the crate's own name in paths")
    ap.add_argument("--graph", action="store_true", help="print the module graph of every level")
    ap.add_argument("--max-file-lines", type=int, default=MAX_FILE_LINES, metavar="N")
    ap.add_argument("--max-fn-lines", type=int, default=MAX_FN_LINES, metavar="N")
    a = ap.parse_args(argv)
    CRATE_NAME[0] = a.crate_name
    if not a.src.is_dir():
        print(f"check-structure: no directory {a.src}", file=sys.stderr)
        return 2
    exceptions = a.exceptions
    if exceptions is None and a.src.resolve() == (ROOT / "src").resolve():
        exceptions = ROOT / "scripts" / "structure-exceptions.txt"
    fn_exc, file_exc, failures = load_exceptions(exceptions)
    used = set()
    crate = Crate(a.src)

    for mod, s in sorted(crate.files.items(), key=lambda kv: kv[1].rel):
        n = s.code_lines()
        if n > a.max_file_lines:
            if s.rel in file_exc:
                used.add(s.rel)
                print(f"excepted: {s.rel}: {n} lines of non-test code ({file_exc[s.rel]})")
            else:
                failures.append(f"{s.rel}: {n} lines of non-test code (limit {a.max_file_lines})")
        for fname, line, length in s.functions():
            if length > a.max_fn_lines:
                key = f"{s.rel}::{fname}"
                if key in fn_exc:
                    used.add(key)
                    print(f"excepted: {s.rel}:{line}: fn {fname}, {length} lines ({fn_exc[key]})")
                else:
                    failures.append(f"{s.rel}:{line}: fn {fname} is {length} lines (limit {a.max_fn_lines})")
    for key in sorted(set(fn_exc) | set(file_exc)):
        if key not in used:
            print(f"note: exception {key} is not needed any more (remove it from {exceptions.name})")

    edges = crate.edges()
    by_level = levels(crate, edges)
    if a.graph:
        for p, lv in by_level.items():
            if not lv:
                continue
            print(f"module graph within {name(p)}:")
            out = defaultdict(list)
            for na, nb in lv:
                out[na].append(nb)
            for na in sorted(out):
                print(f"  {name(na)} -> {', '.join(name(nb) for nb in sorted(out[na]))}")
    for p, lv in by_level.items():
        for cyc in cycles(lv):
            lines = [f"import cycle within {name(p)}: " + " -> ".join(name(v) for v in cyc)]
            for u, v in zip(cyc, cyc[1:]):
                f, ln, written = lv[(u, v)]
                lines.append(f"    {name(u)} -> {name(v)}: {f}:{ln}: {written}")
            failures.append("\n".join(lines))

    for f in failures:
        print(f"FAIL {f}")
    files = sum(1 for s in crate.files.values() if not s.test_only)
    if failures:
        print(f"check-structure: {len(failures)} problem(s) in {files} files of {a.src}")
        return 1
    print(f"check-structure: {files} files of {a.src}: sizes, function lengths and imports are fine")
    return 0


if __name__ == "__main__":
    sys.exit(main())
