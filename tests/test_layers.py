"""The layers of the package: a lower layer never imports a higher one."""

import ast
from pathlib import Path

import ballcvt

ROOT = Path(ballcvt.__file__).parent
#: Lowest first. Modules at the top level that are not listed are base (errors, _version).
LAYERS = ["params", "geometry", "modes", "clamping", "contact", "bearings", "equilibrium",
          "solver", "performance", "optimize", "fitting", "results", "sweeps", "cycles",
          "variator", "studies", "plotting", "reports", "ui", "cli"]


def _layer(module: str) -> int | None:
    head = module.split(".")[0]
    return LAYERS.index(head) if head in LAYERS else None


def test_no_upward_imports():
    offences = []
    for path in ROOT.rglob("*.py"):
        rel = path.relative_to(ROOT).with_suffix("")
        here = _layer(".".join(rel.parts))
        if here is None:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level > 0 and node.module:
                parts = list(rel.parts[: len(rel.parts) - node.level]) + node.module.split(".")
                target = _layer(".".join(parts))
                if target is not None and target > here:
                    offences.append(f"{rel} imports {node.module}")
    assert not offences, offences


def test_physics_never_imports_plotting():
    for path in ROOT.rglob("*.py"):
        text = path.read_text()
        if path.relative_to(ROOT).parts[0] in LAYERS[:LAYERS.index("plotting")]:
            assert "matplotlib" not in text, path
