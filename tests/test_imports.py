"""The house's import rules, read from the source with ``ast``: every import of every module of
``plans/`` (at the top, inside functions, under ``TYPE_CHECKING``), no import circle anywhere,
and the layers in one order — a module imports only from its own layer or the layers before it:

    scene → model → structure → kinematics → kinetostatics → constructions → drawing
          → checking/layout/export/output → pipeline → handout/bench → cli

(``plans.errors`` is the foundation every layer may import.) A new module belongs to a layer
by its dotted name; one that belongs to none fails here until it is placed."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "plans"

#: The layers, first to last: a module's layer is the first prefix its dotted name matches.
LAYERS: tuple[tuple[str, ...], ...] = (
    ("plans.errors", "plans.examples", "plans.linalg", "plans.spatial"),
    ("plans.scene",),
    ("plans.model",),
    ("plans.structure",),
    ("plans.kinematics", "plans.gears"),
    ("plans.kinetostatics",),
    ("plans.dynamics",),
    ("plans.constructions",),
    ("plans.drawing",),
    ("plans.checking", "plans.checking_read", "plans.checking_gears", "plans.checking_groups", "plans.checking_areas", "plans.checking_report", "plans.checking_geometry", "plans.layout",
     "plans.export", "plans.output"),
    ("plans.pipeline",),
    ("plans.handout", "plans.bench"),
    ("plans.cli", "plans.__main__", "plans"),
)


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def imports_of(module: str, path: Path) -> set[str]:
    """Every module of plans that ``module`` imports, anywhere in its source (a name imported
    from a package counts as its submodule when there is one, else as the package)."""
    package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package[:len(package) - node.level + 1] + ([base] if base else []))
            names = [f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base for a in node.names]
        else:
            continue
        for name in names:
            while name and name not in MODULES:      # `import plans.kinematics.solve as s`, a name in a module
                name = name.rpartition(".")[0]
            if name and name != module:
                out.add(name)
    return out


GRAPH = {m: imports_of(m, p) for m, p in MODULES.items()}


def layer(module: str) -> int:
    """The index of ``module``'s layer in :data:`LAYERS` (``plans`` itself, the API, is the top)."""
    for k, prefixes in enumerate(LAYERS):
        if any(module == p or (p != "plans" and module.startswith(p + ".")) for p in prefixes):
            return k
    raise LookupError(module)


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module, and modules importing themselves
    (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            else:
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
                    if len(comp) > 1:
                        out.append(sorted(comp))
    return out


def test_no_import_circle_in_plans():
    assert cycles(GRAPH) == []


def test_every_module_has_a_layer():
    unplaced = []
    for m in MODULES:
        try:
            layer(m)
        except LookupError:
            unplaced.append(m)
    assert unplaced == []


def test_layers_import_only_downwards():
    upward = sorted(f"{m} (layer {layer(m)}) imports {d} (layer {layer(d)})"
                    for m, deps in GRAPH.items() for d in deps if layer(d) > layer(m))
    assert upward == []


# -- the test's own reader and cycle finder, on made-up sources ----------------------------------

def test_cycle_finder_finds_circles_and_only_them():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set(), "c": {"b"}}) == []
    assert sorted(cycles({"a": {"b"}, "b": {"a"}, "c": {"d"}, "d": {"c"}})) == [["a", "b"], ["c", "d"]]


@pytest.mark.parametrize("source", [
    "from .solve import analyse",
    "def f():\n    from .solve import analyse\n",
    "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .solve import analyse\n",
    "import plans.kinematics.solve as s",
])
def test_reader_sees_every_kind_of_import(tmp_path, source):
    path = tmp_path / "state.py"
    path.write_text(source)
    assert "plans.kinematics.solve" in imports_of("plans.kinematics.state", path)


def test_layers_are_ordered_as_the_architecture_says():
    order = ["plans.scene", "plans.model", "plans.structure", "plans.kinematics.solve", "plans.kinetostatics",
             "plans.constructions", "plans.drawing", "plans.checking", "plans.pipeline", "plans.handout", "plans.cli"]
    assert [layer(m) for m in order] == sorted(layer(m) for m in order)
    assert layer("plans.errors") == 0 and layer("plans") == len(LAYERS) - 1
