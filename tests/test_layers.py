"""The layers of the package (docs/architecture.md): one direction only, no import cycle.

Every import is followed, relative or absolute, at module level or inside a function:
a lower layer never imports a higher one, a leaf imports only leaves, no two modules
import each other (directly or round a longer circle), physics never imports plotting.
The checker is tested on a planted tree (`test_the_checker_catches_*`), so that it cannot
pass by seeing nothing.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from codemap import (  # tools/codemap.py: the same code draws docs/architecture.md's diagram
    LAYERS,
    LEAVES,
    _room,
    import_cycles,
    import_graph,
    module_names,
    upward_imports,
)

import ballcvt

ROOT = Path(ballcvt.__file__).parent


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


def test_old_paths_and_names_still_work_with_one_warning():
    """A restructure keeps users working: old module paths, dissolved packages' names and
    renamed names answer with a BallCVTDeprecationWarning naming the new one."""
    import importlib
    import sys
    import warnings

    from ballcvt import _compat
    from ballcvt.errors import BallCVTDeprecationWarning

    cases = [
        ("ballcvt.contact.traction", None, "ballcvt.model.traction.isothermal"),
        ("ballcvt.solver", "SolverOptions", "ballcvt.solvers"),
        ("ballcvt.geometry", "ideal_ratio", "ballcvt.model.kinematics.ideal_ratio"),
        ("ballcvt.cli.main", "main", "ballcvt.interfaces.cli.main"),
        ("ballcvt.params.feasibility", "max_balls", "max_rollers"),
        ("ballcvt.equilibrium.problem", "ball_mass", "roller_mass"),
    ]
    for module, name, new in cases:
        _compat._warned.clear()
        if module in _compat.MOVED_MODULES or module in _compat.MOVED_PACKAGES:
            sys.modules.pop(module, None)  # answered afresh, as on first import
        with warnings.catch_warnings(record=True) as got:
            warnings.simplefilter("always")
            obj = importlib.import_module(module)
            if name is not None:
                obj = getattr(obj, name)
        assert obj is not None
        messages = [str(w.message) for w in got if w.category is BallCVTDeprecationWarning]
        assert len(messages) >= 1 and any(new in m for m in messages), (module, messages)
