"""Issue 25: the capacity names the constraint that sets it (limit, capacity, API)."""

import json

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.api import capacity_curve, load_builtin
from ballcvt.interfaces.cli.main import main


def test_hub_ratio_one_cam_is_pressure_bound(capsys):
    assert main(["limit", "--design", "hub", "--oil-temperature", "fixed", "--ratio", "1", "--clamp-law", "cam",
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["active_constraint"] == "pressure (max_pressure 3 GPa)"
    assert data["interval_constraints"][0] == ["zero torque", "pressure (max_pressure 3 GPa)"]
    assert main(["limit", "--design", "hub", "--oil-temperature", "fixed", "--ratio", "1", "--clamp-law", "cam"]) == 0
    assert "set by: pressure (max_pressure 3 GPa)" in capsys.readouterr().out


@pytest.mark.parametrize("ratio, contact", [(2.0, "input"), (0.5, "output")])
def test_constant_force_is_creep_bound_at_a_named_contact(ratio, contact):
    cap = Variator(architecture="single").capacity(ratio, clamp_force=2000.0,
                                                   input_speed_rpm=2000)
    assert cap.active_constraint == f"creep ({contact} contact)"
    assert cap.constraints[0][0] == "zero torque"


def test_empty_capacity_says_no_equilibrium():
    cap = Variator().capacity(1.0, clamp_force=5.0, input_speed_rpm=2000)
    assert cap.intervals == () and cap.active_constraint == "no equilibrium"


def test_capacity_command_writes_curve_and_figure(tmp_path, capsys):
    out = tmp_path / "cap"
    assert main(["capacity", "--design", "hub", "--oil-temperature", "fixed", "--clamp-law", "cam", "--ratio-range",
                 "0.8", "1.2", "--points", "2", "--out", str(out)]) == 0
    text = (out / "capacity.csv").read_text().splitlines()
    assert text[0].startswith("ratio,limit_torque,lowest_torque,active_constraint")
    assert len(text) == 3 and "pressure (max_pressure 3 GPa)" in text[1]
    assert (out / "capacity.png").exists() and (out / "capacity.svg").exists()
    assert "set by pressure" in capsys.readouterr().out


def test_capacity_curve_api():
    d, f = load_builtin("table1")
    c = capacity_curve(Variator(d, f, "single"), [0.5, 2.0], clamp_force=2000.0,
                       input_speed_rpm=2000)
    frame = c.to_frame()
    assert list(frame["active_constraint"]) == ["creep (output contact)",
                                                "creep (input contact)"]
    assert np.all(c.limit_torque > 0)


def test_small_preload_names_the_lower_end(capsys):
    argv = ["limit", "--design", "hub", "--oil-temperature", "fixed", "--clamp-law", "cam", "--cam-preload", "20",
            "--ratio", "1", "--speed", "2000"]  # not the hub's [operating] 150 rpm
    assert main([*argv, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["capacity_intervals"][0][0] > 0.0
    assert data["interval_constraints"][0] == ["creep (input contact)",
                                               "pressure (max_pressure 3 GPa)"]
    assert main(argv) == 0
    assert "N m set by creep (input contact)" in capsys.readouterr().out
