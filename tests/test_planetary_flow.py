"""Efficiency of a planetary point by the way its power flows (issue 23): in [0, 1], the
same in Python, JSON and text, with the member the power enters through."""

import json
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ballcvt import Variator
from ballcvt.errors import BallCVTError
from ballcvt.interfaces.cli.main import main
from ballcvt.model.modes import MEMBERS, OperatingMode
from ballcvt.results.planetary import PlanetaryResult

F = 2000.0
PLANETARY = [OperatingMode(h, d) for h in MEMBERS for d in MEMBERS
             if h != d and not OperatingMode(h, d).is_default]


@pytest.fixture(scope="module")
def v():
    return Variator()


def _unit(x):
    return x is None or 0.0 <= x <= 1.0


@settings(max_examples=30, deadline=None)
@given(mode=st.sampled_from(PLANETARY), ratio=st.floats(0.5, 1.9),
       torque=st.floats(-25.0, 25.0), speed=st.floats(20.0, 120.0),
       held=st.sampled_from([0.0, -15.0, 15.0]))
def test_efficiencies_are_in_the_unit_interval(mode, ratio, torque, speed, held):
    mode = OperatingMode(mode.held, mode.driver, held_speed=held)
    try:
        r = Variator().solve(ratio, torque, clamp_force=F, input_speed=speed, mode=mode)
    except BallCVTError:
        return
    d = json.loads(r.to_json())
    for key in ("eta", "eta_loss", "eta_speed", "eta_torque", "variator_eta", "overall_eta"):
        assert _unit(d[key]), (key, d[key])
    assert d["eta"] == r.eta == d["overall_eta"]
    assert d["input_member"] == r.input_member != "none"
    first = r.input_member.split("+")[0]
    assert r.powers[first] > 0.0
    assert PlanetaryResult.from_dict(d) == r


@pytest.mark.parametrize("held, driver, ratio, torque, carrier_frame", [
    ("disc0", "carrier", 0.6, 5.0, -3.02),    # JSON eta was -3.02, overall 0.333
    ("disc0", "disc2", 1.7, 5.0, -2.31),
    ("disc0", "carrier", 0.6, 10.0, 2.99),    # reversed flow: 1 / eta
])
def test_reproducers(v, held, driver, ratio, torque, carrier_frame):
    r = v.solve(ratio, torque, clamp_force=F, input_speed_rpm=600,
                mode=OperatingMode(held, driver))
    assert r.relative.eta == pytest.approx(carrier_frame, abs=0.01)   # disc 0 as input
    assert 0.0 <= r.eta <= 1.0 and 0.0 <= r.variator_efficiency["eta"] <= 1.0
    assert json.loads(r.to_json())["eta"] == r.eta


def test_text_shows_only_efficiencies_in_the_unit_interval(capsys):
    assert main(["point", "--held", "disc0", "--driver", "carrier", "--ratio", "0.6",
                     "--torque", "5", "--speed", "600"]) == 0
    out = capsys.readouterr().out
    assert "in through carrier, out through disc2" in out
    for line in out.splitlines():
        if line.startswith("efficiency"):
            for value in re.findall(r"[-+]?\d+\.\d+", line):
                assert 0.0 <= float(value) <= 1.0, line


def test_reversed_variator_efficiency_inverts_the_carrier_frame(v):
    r = v.solve(0.6, 10.0, clamp_force=F, input_speed_rpm=600,
                mode=OperatingMode("disc0", "carrier"))
    assert r.power_flow.startswith("disc2 -> disc0")
    var = r.variator_efficiency
    assert var["eta"] == pytest.approx(1.0 / r.relative.eta, rel=1e-12)
    assert var["speed"] * var["torque"] == pytest.approx(var["eta"], rel=1e-9)
