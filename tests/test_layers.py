"""The layers of the package (docs/architecture.md): one direction only, no import cycle.

Every import is followed, relative or absolute, at module level or inside a function:
a lower layer never imports a higher one, a leaf imports only leaves, no two modules
import each other (directly or round a longer circle), physics never imports plotting.
The checker is tested on a planted tree (`test_the_checker_catches_*`), so that it cannot
pass by seeing nothing.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import ballcvt

ROOT = Path(ballcvt.__file__).parent
#: Lowest first: each layer may import the layers to its left and the leaves.
LAYERS = ["params", "model", "equilibrium", "performance", "solvers", "results", "analysis",
          "api", "reports", "interfaces"]
#: Import no layer (only other leaves); any layer may import them.
LEAVES = ["errors", "units", "registry", "files", "_version", "_compat", "_display",
          "plotting"]


def module_names(root: Path) -> dict[str, tuple[Path, bool]]:
    """Dotted module name -> (file, is a package) for every module under ``root``."""
    out = {}
    for path in root.rglob("*.py"):
        parts = list(path.relative_to(root.parent).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        out[".".join(parts[:-1] if is_pkg else parts)] = (path, is_pkg)
    return out


def import_graph(root: Path) -> dict[str, set[str]]:
    """Module -> the package's modules it imports (absolute and relative imports alike)."""
    mods = module_names(root)
    top = root.name
    graph: dict[str, set[str]] = {}
    for name, (path, is_pkg) in mods.items():
        targets: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                targets.update(a.name for a in node.names if a.name.split(".")[0] == top)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = name.split(".") if is_pkg else name.split(".")[:-1]
                    base = base[: len(base) - node.level + 1] + ([node.module] if node.module else [])
                    module = ".".join(base)
                elif (node.module or "").split(".")[0] == top:
                    module = node.module
                else:
                    continue
                for alias in node.names:
                    sub = f"{module}.{alias.name}"
                    targets.add(sub if sub in mods else module)
        graph[name] = {t for t in targets if t != name}
    return graph


def _room(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def upward_imports(graph) -> list[str]:
    """Imports of a higher layer, and leaves importing a layer."""
    offences = []
    for src, targets in graph.items():
        a = _room(src)
        for dst in sorted(targets):
            b = _room(dst)
            if a in LEAVES and b not in LEAVES and b:
                offences.append(f"leaf {src} imports {dst}")
            elif a in LAYERS and b in LAYERS and LAYERS.index(b) > LAYERS.index(a):
                offences.append(f"{src} ({a}) imports {dst} ({b})")
            elif a and b == "" and dst != src:
                offences.append(f"{src} imports the package root {dst}")
            elif a and a not in LAYERS + LEAVES:
                offences.append(f"{src} is in no layer: add {a!r} to LAYERS or LEAVES")
    return offences


def import_cycles(graph) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles = []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))

    for v in graph:
        if v not in index:
            visit(v)
    return cycles


def test_no_upward_imports():
    assert upward_imports(import_graph(ROOT)) == []


def test_no_import_cycles():
    assert import_cycles(import_graph(ROOT)) == []


def test_physics_never_imports_plotting():
    graph = import_graph(ROOT)
    physics = LAYERS[: LAYERS.index("results") + 1]
    for src, targets in graph.items():
        if _room(src) in physics:
            assert not any(_room(t) == "plotting" for t in targets), src
            assert "matplotlib" not in module_names(ROOT)[src][0].read_text(), src


def test_every_top_level_module_is_in_a_layer():
    rooms = {_room(m) for m in import_graph(ROOT)} - {""}
    assert rooms <= set(LAYERS) | set(LEAVES), rooms - set(LAYERS) - set(LEAVES)


@pytest.fixture
def planted(tmp_path):
    """A small package tree in the same shape, to plant offences in."""
    pkg = tmp_path / "pkg"
    for sub in ("params", "model", "solvers", "model/traction"):
        (pkg / sub).mkdir(parents=True, exist_ok=True)
        (pkg / sub / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("")
    (pkg / "errors.py").write_text("")
    (pkg / "params" / "models.py").write_text("from ..errors import x\n")
    (pkg / "model" / "traction" / "laws.py").write_text("from ...params.models import Design\n")
    (pkg / "solvers" / "point.py").write_text("from ..model.traction import laws\n")
    return pkg


def _rename(graph, top):
    return {k.replace(top, "ballcvt", 1): {t.replace(top, "ballcvt", 1) for t in v}
            for k, v in graph.items()}


def test_the_checker_passes_a_clean_tree(planted):
    graph = _rename(import_graph(planted), "pkg")
    assert upward_imports(graph) == [] and import_cycles(graph) == []
    assert "ballcvt.model.traction.laws" in graph["ballcvt.solvers.point"]


@pytest.mark.parametrize("line", [
    "from ...solvers.point import solve\n",            # relative, module level
    "import pkg.solvers.point\n",                       # absolute
    "from pkg.solvers import point\n",                  # absolute, a submodule
    "def f():\n    from ...solvers import point\n",     # inside a function
])
def test_the_checker_catches_an_upward_import(planted, line):
    target = planted / "model" / "traction" / "laws.py"
    target.write_text(target.read_text() + line)
    offences = upward_imports(_rename(import_graph(planted), "pkg"))
    assert offences == ["ballcvt.model.traction.laws (model) imports ballcvt.solvers.point "
                        "(solvers)"] or offences == ["ballcvt.model.traction.laws (model) "
                                                     "imports ballcvt.solvers (solvers)"]


def test_the_checker_catches_a_cycle_and_a_leaf_import(planted):
    (planted / "params" / "io.py").write_text("from .models import Design\n")
    models = planted / "params" / "models.py"
    models.write_text(models.read_text() + "from . import io\n")
    (planted / "errors.py").write_text("from .model import traction\n")
    graph = _rename(import_graph(planted), "pkg")
    assert import_cycles(graph) == [["ballcvt.params.io", "ballcvt.params.models"]]
    assert "leaf ballcvt.errors imports ballcvt.model.traction" in upward_imports(graph)
