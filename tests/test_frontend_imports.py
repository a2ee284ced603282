"""The front ends (the reports and the Bokeh explorer) use the public API only.

Every import in ``ballcvt/reports/**`` and ``ballcvt/interfaces/ui/**`` (absolute or
relative, at module level or inside a function) must name one of:

- a module of the front end's own package;
- ``ballcvt.api`` (its public names);
- a leaf (``errors``, ``files``, ``units``, ``registry``, ``plotting``, ``_display``; their
  public names);
- the public names of the analysis layer's packages, as exported by their ``__init__``
  (``ballcvt.analysis``, ``ballcvt.analysis.sweeps``, ``ballcvt.analysis.studies``, ...);
- a top-level public name of ``ballcvt`` (``ballcvt.__all__``), from wherever it is
  defined (the package root itself cannot be imported from a layer: tests/test_layers.py).

The checker is tried on planted imports, so that it cannot pass by seeing nothing.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

import ballcvt

ROOT = Path(ballcvt.__file__).parent
#: Front-end package -> its directory.
FRONT_ENDS = {"ballcvt.reports": ROOT / "reports", "ballcvt.interfaces.ui": ROOT / "interfaces" / "ui"}
LEAVES = ("errors", "files", "units", "registry", "plotting", "_display")


def _is_package(module: str) -> bool:
    return (ROOT.parent / module.replace(".", "/") / "__init__.py").is_file()


def _is_module(module: str) -> bool:
    return _is_package(module) or (ROOT.parent / (module.replace(".", "/") + ".py")).is_file()


def _top_level(module: str, name: str) -> bool:
    """``name`` imported from ``module`` is one of ``ballcvt``'s top-level public names."""
    if name not in ballcvt.__all__:
        return False
    return getattr(importlib.import_module(module), name, None) is getattr(ballcvt, name)


def _allowed(module: str, name: str | None, own: str) -> bool:
    """May a front end of package ``own`` import ``name`` from ``module`` (None: the
    module itself, ``import module``)?"""
    if module == own or module.startswith(own + "."):
        return True
    if name is not None and _is_module(f"{module}.{name}"):  # from pkg import submodule
        return _allowed(f"{module}.{name}", None, own)
    public = name is None or not name.startswith("_")
    if module == "ballcvt.api" or module in {f"ballcvt.{leaf}" for leaf in LEAVES}:
        return public
    if module.startswith("ballcvt.analysis") and _is_package(module):
        exported = getattr(importlib.import_module(module), "__all__", [])
        return name is None or name in exported
    return name is not None and _top_level(module, name)


def offences(source: str, module: str, is_pkg: bool, own: str) -> list[str]:
    """The imports of ``source`` (module ``module``) that a front end may not make."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            pairs = [(a.name, None) for a in node.names if a.name.split(".")[0] == "ballcvt"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = module.split(".") if is_pkg else module.split(".")[:-1]
                base = base[: len(base) - node.level + 1] + ([node.module] if node.module else [])
                target = ".".join(base)
            elif (node.module or "").split(".")[0] == "ballcvt":
                target = node.module
            else:
                continue
            pairs = [(target, a.name) for a in node.names]
        else:
            continue
        for target, name in pairs:
            if not _allowed(target, name, own):
                what = target if name is None else f"{target}.{name}"
                out.append(f"{module}:{node.lineno} imports {what}")
    return out


def _modules():
    for own, folder in FRONT_ENDS.items():
        for path in sorted(folder.rglob("*.py")):
            parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
            is_pkg = parts[-1] == "__init__"
            yield own, ".".join(parts[:-1] if is_pkg else parts), path, is_pkg


def test_the_front_ends_import_only_public_names():
    found = list(_modules())
    assert len(found) >= 8  # reports (7 modules) and the explorer (2)
    bad = []
    for own, module, path, is_pkg in found:
        bad += offences(path.read_text(), module, is_pkg, own)
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize(
    "line",
    [
        "from ..solvers.limit import saturated_traction",
        "from ..equilibrium.problem import build_problem",
        "from ..analysis.sweeps.curves import limit_search_curves",
        "from ..analysis.sweeps.export import write_table",
        "from ..analysis.studies import _not_exported",
        "from ..model.modes import relative_ratio_coefficients",
        "import ballcvt.solvers.limit",
        "from ballcvt.model import kinematics",
        "from ..api import _speed",
        "def f():\n    from ..equilibrium import problem",
    ],
)
def test_the_checker_catches_a_private_import(line):
    assert offences(line, "ballcvt.reports.x", False, "ballcvt.reports")


@pytest.mark.parametrize(
    "line",
    [
        "from ..analysis import write_table",
        "from ..analysis.sweeps import to_netcdf",
        "from ..analysis import traction_ceiling",
        "from ..api import Variator",
        "from ..params import Design",
        "from .._version import __version__",
        "from ..plotting import save",
        "from .figures import FIGURES",
        "from . import figures",
        "import numpy as np",
    ],
)
def test_the_checker_lets_public_names_through(line):
    assert not offences(line, "ballcvt.reports.x", False, "ballcvt.reports")


def test_the_checker_resolves_the_explorer_relative_imports():
    src = "from ...errors import BallCVTError\nfrom ...solvers.point import solve_point"
    got = offences(src, "ballcvt.interfaces.ui.app", False, "ballcvt.interfaces.ui")
    assert got == ["ballcvt.interfaces.ui.app:2 imports ballcvt.solvers.point.solve_point"]
