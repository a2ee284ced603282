"""A map of the ballcvt package drawn from its own source: imports, layers, size.

Used by the tests (tests/test_layers.py, tests/test_hygiene.py), by the documentation
(docs/architecture.md: the layer diagram is drawn from these imports at build time) and by
hand::

    python tools/codemap.py              # the hygiene figures as a Markdown table
    python tools/codemap.py --diagram docs/_generated/layers.svg

Every import is followed, relative or absolute, at module level or inside a function.
"""

from __future__ import annotations

import argparse
import ast
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1] / "src" / "ballcvt"

#: Lowest first: each layer may import the layers to its left and the leaves.
LAYERS = [
    "params",
    "model",
    "equilibrium",
    "performance",
    "solvers",
    "results",
    "analysis",
    "api",
    "reports",
    "interfaces",
]
#: Import no layer (only other leaves); any layer may import them.
LEAVES = [
    "errors", "units", "status", "registry", "files", "_version", "_compat", "_lazy", "_display",
    "plotting",
]


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
                    base = base[: len(base) - node.level + 1] + (
                        [node.module] if node.module else []
                    )
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


# --- size and shape -------------------------------------------------------------------

#: A function over this many parameters takes a parameter object, unless the comment block
#: right above its ``def`` has a line starting ``# many parameters:`` that says why.
MAX_PARAMETERS = 7
#: Longest function body, docstring aside [lines].
MAX_BODY = 80
#: Longest module [lines].
MAX_MODULE = 500
JUSTIFICATION = "# many parameters:"


def _parameters(node) -> list[str]:
    a = node.args
    names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs if x.arg not in ("self", "cls")]
    return (
        names
        + (["*" + a.vararg.arg] if a.vararg else [])
        + (["**" + a.kwarg.arg] if a.kwarg else [])
    )


def _body_lines(node) -> int:
    body = node.body
    first = body[0]
    if isinstance(first, ast.Expr) and isinstance(getattr(first, "value", None), ast.Constant):
        if isinstance(first.value.value, str):
            body = body[1:]
    return 0 if not body else body[-1].end_lineno - body[0].lineno + 1


def functions(root: Path = ROOT):
    """``(where, name, parameters, body lines, justification or None)`` of every function."""
    out = []
    for path in sorted(root.rglob("*.py")):
        lines = path.read_text().splitlines()
        for node in ast.walk(ast.parse("\n".join(lines))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                first = min([node.lineno] + [d.lineno for d in node.decorator_list])
                why, row = None, first - 2  # the comment block right above the def
                while row >= 0 and lines[row].strip().startswith("#"):
                    if lines[row].strip().startswith(JUSTIFICATION):
                        why = lines[row].strip()
                    row -= 1
                where = f"{path.relative_to(root.parent)}:{node.lineno}"
                out.append((where, node.name, len(_parameters(node)), _body_lines(node), why))
    return out


def module_lines(root: Path = ROOT) -> dict[str, int]:
    return {
        str(p.relative_to(root.parent)): len(p.read_text().splitlines())
        for p in sorted(root.rglob("*.py"))
    }


def figures(root: Path = ROOT) -> dict[str, object]:
    """The hygiene figures of the package (README and docs/architecture.md)."""
    funcs = functions(root)
    sizes = module_lines(root)
    graph = import_graph(root)
    many = [f for f in funcs if f[2] > MAX_PARAMETERS]
    return {
        "modules": len(sizes),
        "lines": sum(sizes.values()),
        "largest module": max(sizes.items(), key=lambda kv: kv[1]),
        f"modules over {MAX_MODULE} lines": [k for k, v in sizes.items() if v > MAX_MODULE],
        f"function bodies over {MAX_BODY} lines": [
            f"{w} {n}" for w, n, _, b, _ in funcs if b > MAX_BODY
        ],
        f"functions over {MAX_PARAMETERS} parameters": len(many),
        "  of which justified": [f"{w} {n} ({p})" for w, n, p, _, why in many if why],
        "  unjustified": [f"{w} {n} ({p})" for w, n, p, _, why in many if not why],
        "import cycles": import_cycles(graph),
        "upward imports": upward_imports(graph),
    }


def figures_markdown(root: Path = ROOT) -> str:
    """`figures` as a Markdown list (docs/architecture.md)."""
    out = []
    for key, value in figures(root).items():
        if isinstance(value, list):
            value = "none" if not value else "; ".join(f"`{v}`" for v in value)
        elif isinstance(value, tuple):
            value = f"`{value[0]}` ({value[1]} lines)"
        out.append(f"- {key.strip()}: {value}")
    return "\n".join(out)


# --- the layer diagram ----------------------------------------------------------------


def room_edges(graph) -> Counter:
    """(importing room, imported room) -> number of module imports, rooms being the
    top-level packages and modules (``model``, ``solvers``, ``errors``, ...)."""
    edges: Counter = Counter()
    for src, targets in graph.items():
        for dst in targets:
            a, b = _room(src), _room(dst)
            if a and b and a != b:
                edges[(a, b)] += 1
    return edges


def subrooms(graph) -> dict[str, list[str]]:
    """Each layer's second-level modules and packages (``model`` -> traction, clamping...)."""
    out: dict[str, set[str]] = {}
    for m in graph:
        parts = m.split(".")
        if len(parts) > 2 and parts[1] in LAYERS:
            out.setdefault(parts[1], set()).add(parts[2])
    return {k: sorted(v - {"__init__"}) for k, v in out.items()}


def draw_layers(graph, path: Path) -> Path:
    """Draw the layers (lowest at the bottom) and who imports whom, from ``graph``.

    Left: the stack of layers with the modules each holds. Right: the number of module
    imports from each layer (row) to each layer or leaf (column); a cell above the
    diagonal would be an upward import, drawn in red.
    """
    import textwrap

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.patches import FancyBboxPatch

    edges = room_edges(graph)
    subs = subrooms(graph)
    cols = LAYERS + [leaf for leaf in LEAVES if any(b == leaf for (_, b) in edges)]
    fig, (left, right) = plt.subplots(
        1, 2, figsize=(14, 0.62 * len(LAYERS) + 1.6), gridspec_kw={"width_ratios": [1.05, 1]}
    )
    height = 0.8
    for i, name in enumerate(LAYERS):
        left.add_patch(
            FancyBboxPatch(
                (0, i), 10, height, boxstyle="round,pad=0.02", fc="#e8f0fb", ec="#2a5599"
            )
        )
        left.text(0.2, i + height / 2, name, va="center", weight="bold", fontsize=10)
        inside = textwrap.fill(", ".join(subs.get(name, [])) or "(one module)", 62)
        left.text(2.6, i + height / 2, inside, va="center", fontsize=7.5)
        if i:
            left.annotate(
                "",
                (5, i - 0.2 + 0.05),
                (5, i - 0.05),
                arrowprops={"arrowstyle": "-|>", "color": "#2a5599"},
            )
    left.set_xlim(-0.2, 10.2)
    left.set_ylim(-0.3, len(LAYERS))
    left.axis("off")
    left.set_title("layers, lowest first (a layer imports only those below it)", fontsize=10)
    counts = np.zeros((len(LAYERS), len(cols)))
    for (a, b), n in edges.items():
        if a in LAYERS and b in cols:
            counts[LAYERS.index(a), cols.index(b)] = n
    right.imshow(
        np.where(counts > 0, np.log1p(counts), np.nan),
        origin="lower",
        cmap="Blues",
        aspect="auto",
        vmin=0,
        vmax=np.log1p(counts.max()) * 1.3,
    )
    for r in range(len(LAYERS)):
        for c in range(len(cols)):
            if counts[r, c]:
                upward = c < len(LAYERS) and c > r
                right.text(
                    c,
                    r,
                    f"{counts[r, c]:.0f}",
                    ha="center",
                    va="center",
                    fontsize=8,
                    color="red" if upward else "black",
                    weight="bold" if upward else "normal",
                )
    right.axvline(len(LAYERS) - 0.5, color="#888", lw=0.8)
    right.plot([-0.5, len(LAYERS) - 0.5], [-0.5, len(LAYERS) - 0.5], color="#bbb", lw=0.6)
    right.set_xticks(range(len(cols)), cols, rotation=60, ha="right", fontsize=8)
    right.set_yticks(range(len(LAYERS)), LAYERS, fontsize=8)
    right.set_xlabel("imported layer | leaves")
    right.set_ylabel("importing layer")
    right.set_title("module imports between layers (above the diagonal: none)", fontsize=10)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, bbox_inches="tight")
    plt.close(fig)
    return path


def layer_table(graph) -> str:
    """Markdown: for each layer, the lower layers and leaves it imports, with counts."""
    edges = room_edges(graph)
    rows = ["| layer | holds | imports (number of module imports) |", "|---|---|---|"]
    subs = subrooms(graph)
    for name in reversed(LAYERS):
        deps = sorted(
            ((b, n) for (a, b), n in edges.items() if a == name),
            key=lambda bn: (
                bn[0] not in LAYERS,
                -LAYERS.index(bn[0]) if bn[0] in LAYERS else 0,
                bn[0],
            ),
        )
        rows.append(
            f"| `{name}` | {', '.join(subs.get(name, [])) or '-'} | "
            + ", ".join(f"{b} ({n})" for b, n in deps)
            + " |"
        )
    return "\n".join(rows)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    parser.add_argument("--diagram", type=Path, help="write the layer diagram (SVG or PNG)")
    parser.add_argument("--table", action="store_true", help="print the layer table")
    args = parser.parse_args(argv)
    graph = import_graph(ROOT)
    if args.diagram:
        print(draw_layers(graph, args.diagram))
    if args.table:
        print(layer_table(graph))
    if not (args.diagram or args.table):
        for key, value in figures().items():
            print(f"- {key}: {value}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
