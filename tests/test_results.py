"""Result objects: immutable, carry inputs, version and convergence, save and load."""

import dataclasses

import pytest
from conftest import PAPER

from ballcvt import OperatingResult, __version__


def test_result_round_trip(double, tmp_path):
    r = double.solve(ratio=1.2, output_torque=30.0, **PAPER)
    path = tmp_path / "r.json"
    r.save(path)
    back = OperatingResult.load(path)
    assert back == r
    assert back.version == __version__ and back.converged
    assert back.design == double.design and back.fluid == double.fluid


def test_result_is_immutable(double):
    r = double.solve(ratio=1.0, output_torque=20.0, **PAPER)
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.eta = 1.0
    with pytest.raises(TypeError):
        r.contacts["input"] = None


def test_result_contents(single):
    r = single.solve(ratio=1.0, output_torque=40.0, **PAPER)
    assert list(r.contacts) == ["input", "idler", "output"]
    assert r.tilt_deg == pytest.approx(0.0, abs=1e-12)
    assert r.actual_ratio == pytest.approx(r.eta_speed, rel=1e-12)  # tau_ID = 1
    assert abs(r.contacts["idler"].creep) < 1e-12                    # zero spin, Fig. 12
    assert r.input_power - r.output_power == pytest.approx(r.losses["total"], rel=1e-9)
    assert r.residual_norm <= 1e-11 and r.iterations > 0
