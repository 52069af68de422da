"""The package's import graph, read from the code: cycles, private names used across modules,
imports against the layers, and module sizes.

Run it from the checkout (``python tests/architecture.py``); it prints what it finds and exits
non-zero when anything breaks the rules of ``docs/architecture.md``. ``tests/test_architecture.py``
runs the same checks in the suite. It reads the source with :mod:`ast` and imports nothing from
the package, so it works on a broken tree too.

Every import counts, also one inside a function (a lazy import is still a dependency).
"""

from __future__ import annotations

import ast
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = "hapticproof"

#: The layers, lowest first: a module may import from its own layer and the layers before it.
LAYERS = ("core", "exact", "systems", "analysis", "audit", "report", "bench", "cli", "derivations")
#: Modules over this many lines are two concepts (the handbook: cut by concept, "past ~2000 lines it is two").
MAX_LINES = 2000


@dataclass
class Graph:
    modules: dict[str, Path]
    imports: dict[str, set[str]] = field(default_factory=dict)
    private: list[tuple[str, str, str]] = field(default_factory=list)   # (importer, module, name)


def _module_files() -> dict[str, Path]:
    out = {}
    roots = [(ROOT / "src" / PACKAGE, PACKAGE), (ROOT / "derivations", f"{PACKAGE}.derivations")]
    for base, prefix in roots:
        for path in sorted(base.rglob("*.py")):
            rel = path.relative_to(base).with_suffix("")
            parts = [p for p in rel.parts if p != "__init__"]
            out[".".join([prefix, *parts])] = path
    return out


def _resolve(importer: str, is_package: bool, node: ast.ImportFrom) -> str:
    if not node.level:
        return node.module or ""
    base = importer.split(".") if is_package else importer.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def read_graph() -> Graph:
    graph = Graph(_module_files())
    modules = graph.modules
    for name, path in modules.items():
        deps: set[str] = set()
        aliases: dict[str, str] = {}            # local name -> module, for module._name access
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                target = _resolve(name, path.name == "__init__.py", node)
                if not target.startswith(PACKAGE):
                    continue
                for alias in node.names:
                    full = f"{target}.{alias.name}"
                    if full in modules:
                        deps.add(full)
                        aliases[alias.asname or alias.name] = full
                        continue
                    if target in modules:
                        deps.add(target)
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        graph.private.append((name, target, alias.name))
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name in modules:
                        deps.add(alias.name)
                        if alias.asname:
                            aliases[alias.asname] = alias.name
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases
                    and node.attr.startswith("_") and not node.attr.startswith("__")):
                graph.private.append((name, aliases[node.value.id], node.attr))
        deps.discard(name)
        graph.imports[name] = deps
    return graph


def cycles(graph: Graph) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in graph.imports.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    sys.setrecursionlimit(max(10_000, sys.getrecursionlimit()))
    for v in graph.modules:
        if v not in index:
            visit(v)
    return out


def layer_of(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in LAYERS else None


def upward_imports(graph: Graph) -> list[tuple[str, str]]:
    """Imports of a layer above the importer's (the top-level ``hapticproof`` package, the public
    facade, may import from every layer)."""
    out = []
    for importer, deps in graph.imports.items():
        own = layer_of(importer)
        if own is None:
            continue
        for dep in deps:
            theirs = layer_of(dep)
            if theirs is None:
                if dep == PACKAGE:
                    out.append((importer, dep))
                continue
            if LAYERS.index(theirs) > LAYERS.index(own):
                out.append((importer, dep))
    return sorted(out)


#: The independent checker: the certificate checks, their exact arithmetic and the
#: definition-level judge. They import only ``core`` and each other -- nothing of the kernel.
CHECKER = tuple(f"{PACKAGE}.exact.{name}" for name in ("checker", "checkarith", "judge", "judgedisplay", "judgepoints", "scenebinding", "shownmatrix", "shownnetwork",
                                                              "acceptance"))


def checker_imports(graph: Graph) -> list[str]:
    """The independent checker imports nothing of the kernel's layer (nor above it)."""
    return sorted(f"{m} -> {d}" for m in CHECKER for d in graph.imports.get(m, ())
                  if layer_of(d) != "core" and d not in CHECKER)


def long_modules(graph: Graph, limit: int = MAX_LINES) -> list[tuple[str, int]]:
    sizes = ((name, len(path.read_text(encoding="utf-8").splitlines())) for name, path in graph.modules.items())
    return sorted(((n, k) for n, k in sizes if k > limit), key=lambda x: -x[1])


def main() -> int:
    graph = read_graph()
    found = {
        "import cycles": [" <-> ".join(c) for c in cycles(graph)],
        "private names imported across modules": [f"{a} uses {m}.{n}" for a, m, n in graph.private],
        "imports from a higher layer": [f"{a} -> {b}" for a, b in upward_imports(graph)],
        "checker imports (must be none outside core and the checker's own modules)": checker_imports(graph),
        f"modules over {MAX_LINES} lines": [f"{n}: {k} lines" for n, k in long_modules(graph)],
    }
    print(f"{len(graph.modules)} modules, {sum(len(v) for v in graph.imports.values())} imports between them")
    for title, items in found.items():
        print(f"{title}: {len(items)}")
        for item in items:
            print(f"  {item}")
    return 1 if any(found.values()) else 0


if __name__ == "__main__":
    raise SystemExit(main())
