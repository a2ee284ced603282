"""Issue 24: every JSON file ballcvt writes parses under a strict parser (no NaN, no
Infinity), and a saved result whose numbers were edited by hand warns when it is loaded
(a checksum of what ballcvt computed). Each failed before: a cycle's summary.json held
``Infinity``, and an edited result loaded silently."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pandas as pd
import pytest

from ballcvt import OperatingResult
from ballcvt.analysis.cycles import CycleResult
from ballcvt.errors import ResultChecksumWarning
from ballcvt.files import write_json
from ballcvt.model.modes import OperatingMode
from ballcvt.results.planetary import PlanetaryResult


def strict(text: str):
    """``json.loads`` that refuses NaN and the infinities (RFC 8259)."""

    def refuse(constant):
        raise ValueError(f"{constant} is not JSON")

    return json.loads(text, parse_constant=refuse)


def test_write_json_is_strict_and_says_where(tmp_path):
    data = {"a": math.inf, "b": {"c": np.float64("nan"), "d": [1.0, -math.inf]},
            "e": np.array([1.5, np.inf]), "f": np.int64(3), "ok": 2.0}
    back = strict(write_json(tmp_path / "x.json", data).read_text())
    assert back["a"] is None and back["b"] == {"c": None, "d": [1.0, None]}
    assert back["e"] == [1.5, None] and back["f"] == 3 and back["ok"] == 2.0
    assert back["non_finite"] == ["a", "b.c", "b.d[1]", "e[1]"]
    assert "non_finite" not in strict(write_json(tmp_path / "y.json", {"x": 1.0}).read_text())


def test_a_cycle_summary_with_an_infinity_is_strict_json(tmp_path):
    # e.g. a cycle from time -1e308 to 1e308: the duration overflows
    steps = pd.DataFrame({"time": [0.0, 1.0], "duration": [0.5, 0.5]})
    summary = {"duration_s": math.inf, "efficiency": None, "energy_in_J": math.nan,
               "losses_J": {"creep": math.inf}}
    CycleResult(steps=steps, summary=summary).save(tmp_path)
    back = strict((tmp_path / "summary.json").read_text())
    assert back["duration_s"] is None and back["losses_J"]["creep"] is None
    assert back["non_finite"] == ["duration_s", "energy_in_J", "losses_J.creep"]


def test_fit_json_is_strict(tmp_path):
    from test_cli_support import TINY_CURVES

    from ballcvt.api import fit_fluid, read_curves
    from ballcvt.params import load_builtin

    curves = read_curves(TINY_CURVES)
    fit = fit_fluid(curves, load_builtin("table1")[1], None, reduced_modulus=2.2e11)
    bad = type(fit)(**{**fit.__dict__,
                       "standard_errors": {k: math.inf for k in fit.standard_errors}})
    bad.save(tmp_path, curves)
    back = strict((tmp_path / "fit.json").read_text())
    assert all(v is None for v in back["standard_errors"].values())
    assert back["non_finite"] == [f"standard_errors.{k}" for k in fit.standard_errors]


@pytest.fixture(scope="module")
def saved(double, tmp_path_factory):
    r = double.solve(ratio=1.2, output_torque=30.0, clamp_force=2000.0, input_speed_rpm=2000)
    path = tmp_path_factory.mktemp("saved") / "r.json"
    r.save(path)
    return r, path


def test_a_saved_result_is_strict_json_with_a_checksum(saved):
    r, path = saved
    data = strict(path.read_text())
    assert data["checksum"].startswith("sha256:") and len(data["checksum"]) == 71
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an unmodified file loads silently
        assert OperatingResult.load(path) == r


@pytest.mark.parametrize("edit", [
    lambda d: d.update(clamp_force=d["clamp_force"] * 1.01),
    lambda d: d["contacts"]["input"].update(p_max=1.0e9),
    lambda d: d["design"].update(name="someone else's drive"),
    lambda d: d.update(warnings=[*d["warnings"], "added by hand"]),
])
def test_an_edited_result_warns_that_it_is_not_what_ballcvt_computed(saved, tmp_path, edit):
    _, path = saved
    data = json.loads(path.read_text())
    edit(data)
    edited = tmp_path / "edited.json"
    edited.write_text(json.dumps(data, indent=2))
    with pytest.warns(ResultChecksumWarning, match="no longer matches") as rec:
        OperatingResult.load(edited)
    assert rec[0].message.modified and str(edited) in str(rec[0].message)


def test_reformatting_a_saved_result_is_not_an_edit(saved, tmp_path):
    _, path = saved
    same = tmp_path / "same.json"
    same.write_text(json.dumps(dict(reversed(json.loads(path.read_text()).items()))))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        OperatingResult.load(same)


def test_an_old_result_without_a_checksum_loads_with_a_note(saved, tmp_path):
    r, path = saved
    data = json.loads(path.read_text())
    del data["checksum"]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(data))
    with pytest.warns(ResultChecksumWarning, match="no checksum") as rec:
        assert OperatingResult.load(old) == r
    assert not rec[0].message.modified


def test_a_planetary_result_carries_a_checksum(double, tmp_path):
    r = double.solve(1.4, 15.0, clamp_force=2000.0, input_speed=80.0,
                     mode=OperatingMode("disc2", "carrier"))
    path = tmp_path / "p.json"
    r.save(path)
    assert strict(path.read_text())["checksum"].startswith("sha256:")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        PlanetaryResult.load(path)
    data = json.loads(path.read_text())
    data["load_torque"] = 16.0
    path.write_text(json.dumps(data))
    with pytest.warns(ResultChecksumWarning, match="no longer matches"):
        PlanetaryResult.load(path)
