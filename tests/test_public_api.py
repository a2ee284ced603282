"""The front ends use only the public API; the API reaches everything the CLI does.

`public_imports_offences` parses every module of a package with `ast` and lists each import
that is not a public name of ``ballcvt`` or ``ballcvt.api``, a leaf, or the package itself
(relative imports resolved, function-level imports included). Adding ``interfaces/ui`` or
``reports`` to the check is one line in `PACKAGES`.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import numpy as np
import pytest

import ballcvt
from ballcvt.api import (CycleSettings, LimitCurve, MapGrid, OperatingMode, SweepSettings,
                         TableGrid, Variator)
from ballcvt.errors import InputError
from drives import fixed_oil_hub

ROOT = Path(ballcvt.__file__).parent
LEAVES = ["ballcvt.errors", "ballcvt.files", "ballcvt.units", "ballcvt.registry",
          "ballcvt.plotting", "ballcvt._display", "ballcvt._version"]
#: Modules whose public names (``__all__``) a front end may import.
PUBLIC = ["ballcvt", "ballcvt.api"]
#: package -> the other public modules it may use (the layers above the API it calls).
PACKAGES = {
    "interfaces/cli": ["ballcvt.reports", "ballcvt.reports.study", "ballcvt.interfaces.ui"],
}


def _imports(path: Path, module: str, is_pkg: bool):
    """(line, imported module, names or None) of every import in a file."""
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield node.lineno, a.name, None
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = module.split(".") if is_pkg else module.split(".")[:-1]
                base = base[: len(base) - node.level + 1] + ([node.module] if node.module else [])
                target = ".".join(base)
            else:
                target = node.module or ""
            yield node.lineno, target, [a.name for a in node.names]


def public_imports_offences(package: str, public_modules=()) -> list[str]:
    """Imports in ``ballcvt/<package>`` of anything but public names and leaves."""
    own = "ballcvt." + package.replace("/", ".")
    allowed = PUBLIC + list(public_modules)
    offences = []
    for path in sorted((ROOT / package).rglob("*.py")):
        rel = path.relative_to(ROOT.parent).with_suffix("").parts
        is_pkg = rel[-1] == "__init__"
        module = ".".join(rel[:-1] if is_pkg else rel)
        for line, target, names in _imports(path, module, is_pkg):
            if target.split(".")[0] != "ballcvt":
                continue
            if target == own or target.startswith(own + "."):
                continue
            if any(target == leaf or target.startswith(leaf + ".") for leaf in LEAVES):
                continue
            if target in allowed:
                public = set(getattr(importlib.import_module(target), "__all__", ()))
                sub = {n for n in names or () if f"{target}.{n}" in allowed}
                bad = [n for n in names or () if n not in public and n not in sub]
                if not bad:
                    continue
                target += " (" + ", ".join(bad) + ")"
            offences.append(f"{path.relative_to(ROOT)}:{line} imports {target}")
    return offences


@pytest.mark.parametrize("package", sorted(PACKAGES))
def test_front_ends_import_only_the_public_api(package):
    assert public_imports_offences(package, PACKAGES[package]) == []


def test_the_check_catches_an_internal_import(tmp_path, monkeypatch):
    import ballcvt.interfaces.cli.point as point
    source = Path(point.__file__).read_text()
    fake = tmp_path / "ballcvt" / "interfaces" / "cli"
    fake.mkdir(parents=True)
    (fake / "point.py").write_text(source + "\nfrom ...solvers.limit import limit_torque\n"
                                   "from ...api import build_problem\n")
    monkeypatch.setattr(f"{__name__}.ROOT", tmp_path / "ballcvt")
    got = public_imports_offences("interfaces/cli")
    assert any("imports ballcvt.solvers.limit" in g for g in got)
    assert any("ballcvt.api (build_problem)" in g for g in got)


def test_every_public_name_exists():
    for module in (ballcvt, ballcvt.api):
        for name in module.__all__:
            assert getattr(module, name) is not None, (module.__name__, name)


def test_cli_modules_are_thin():
    import ballcvt.interfaces.cli as cli
    for path in Path(cli.__file__).parent.glob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef):
                body = node.body[1:] if ast.get_docstring(node) else node.body
                assert body[-1].end_lineno - body[0].lineno + 1 <= 80, (path.name, node.name)


def test_choices_come_from_the_registries():
    from ballcvt.interfaces.cli.main import build_parser, main
    from ballcvt.registry import TRACTION_LAWS

    class MyLaw:
        name = "my_law"

    TRACTION_LAWS.register(MyLaw())
    try:
        sub = next(a for a in build_parser()._actions if a.dest == "command")
        point = sub.choices["point"]
        law = next(a for a in point._actions if a.dest == "traction_law")
        assert "my_law" in law.choices
    finally:
        TRACTION_LAWS.unregister("my_law")
    with pytest.raises(SystemExit) as exc:                     # no longer offered
        main(["point", "--traction-law", "my_law"])
    assert exc.value.code == 2


def test_settings_and_old_keywords_agree():
    v = Variator()
    kw = dict(clamp_force=2000.0, input_speed_rpm=2000)
    a = v.solve(1.0, 40.0, **kw, check_capacity=False)
    b = v.solve(1.0, 40.0, **kw, settings=ballcvt.SolveSettings(check_capacity=False))
    assert a.eta == b.eta
    with pytest.raises(TypeError, match="unexpected keyword argument 'workerz'"):
        v.sweep(ratio=1.0, output_torque=10.0, **kw, workerz=2)
    s = ballcvt.api.settings.merge_settings(SweepSettings, SweepSettings(workers=3),
                                            {"label": "x"}, "sweep")
    assert (s.workers, s.label) == (3, "x")
    assert CycleSettings(target_input_speed_rpm=30.0).target() == pytest.approx(np.pi)


def test_limit_curve_matches_the_point_limit():
    v = Variator()
    curve = v.limit_curve([0.8, 1.2], input_speed_rpm=2000, clamp_force=2000.0, progress=False)
    assert isinstance(curve, LimitCurve) and curve.torque.shape == (2,)
    for r, t in zip((0.8, 1.2), curve.torque):
        one = v.limit_torque(r, clamp_force=2000.0, input_speed_rpm=2000)
        assert t == pytest.approx(one, rel=2e-3)


def test_map_and_table_defaults_come_from_the_limit_curve():
    v = Variator()
    ds = v.efficiency_map(MapGrid((0.8, 1.2), 2, None, 3), clamp_force=2000.0, progress=False)
    top = 1.02 * float(np.nanmax(ds.limit_torque.values))
    assert float(ds.output_torque.max()) == pytest.approx(top)
    with pytest.raises(InputError, match="ratio_range"):
        MapGrid((2.0, 1.0))
    with pytest.raises(InputError, match="speed_range"):
        TableGrid(speed_range_rpm=(0.0, 10.0))


def test_planetary_map_and_capacity():
    v = Variator()
    mode = OperatingMode("disc0", "carrier")
    batch = v.planetary_map(mode, [0.8, 1.2], 5.0, driver_speed_rpm=600, clamp_force=2000.0)
    assert batch.status.shape == (2,)
    cap = v.planetary_capacity(mode, [0.8], driver_speed_rpm=600, clamp_force=2000.0)
    assert cap.shape == (1,)
    with pytest.raises(InputError, match="clamp_law"):
        v.planetary_map(mode, 1.0, 5.0, driver_speed=60.0, clamp_force=None)


def test_with_cam_names_the_missing_keys():
    design, fluid = ballcvt.load_builtin()
    v = Variator(design.replace(cam=None), fluid)
    with pytest.raises(InputError, match="missing: --p"):
        v.with_cam({"disc": "input"}, {"preload": "--p"})
    assert v.with_cam(dict(Variator(*fixed_oil_hub()).design.cam)).design.cam
