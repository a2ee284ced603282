"""Parasitic losses (docs/model.md §12): off by default, analytic limits of each model,
and the Eq. 38 = Eq. 39 balance with them on."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ballcvt import TractionLimitError, Variator, load_builtin
from ballcvt.errors import NoEquilibriumError
from ballcvt.model.losses import moment_coefficient, parasitic_torques, seal_torque, thrust_bearing_torque, windage_torque
from drives import fixed_oil_hub


@pytest.fixture(scope="module")
def hub():
    return Variator(*fixed_oil_hub())


def test_off_by_default_and_bitwise_unchanged():
    design, fluid = load_builtin()
    assert design.parasitic is None
    ball, drag0, drag2 = parasitic_torques(design, fluid, 200.0, 100.0, 600.0, 1e4)
    assert ball == 0.0 and not drag0.any() and not drag2.any()
    r = Variator().solve(1.0, 40.0, clamp_force=2000.0, input_speed_rpm=2000)
    assert r.losses["parasitic"] == 0.0
    # the same three terms (parasitic is exactly 0), summed per contact first in the total
    # (Eq. 40's P_CR + P_SP per contact): equal up to the association's round-off
    paper = r.losses["creep"] + r.losses["spin"] + r.losses["bearing"]
    assert r.losses["total"] == pytest.approx(paper, rel=4 * np.finfo(float).eps, abs=0)


def test_moment_coefficient_limits():
    # creeping flow: Stokes' torque 8 pi mu r^3 omega exactly (Lamb 1932, Art. 334)
    mu, rho, r, w = 0.5, 900.0, 1e-3, 1.0
    nu = mu / rho
    assert windage_torque(w, r, rho, nu) == pytest.approx(8 * math.pi * mu * r**3 * w,
                                                          rel=1e-12)
    # laminar disc (von Karman / Cochran) and turbulent disc branches
    assert moment_coefficient(1e4) == pytest.approx(3.87 / 100.0)
    assert moment_coefficient(1e7) == pytest.approx(0.146 / 1e7**0.2)
    assert windage_torque(0.0, 0.1, 900.0, 1e-5) == 0.0


def test_seal_and_thrust_bearing_by_hand():
    # SKF form, d_s in mm, N mm -> N m
    assert seal_torque(0.03, 0.028, 2.25, 2.0) == pytest.approx(
        1e-3 * (0.028 * 30.0**2.25 + 2.0))
    assert thrust_bearing_torque(1e4, 0.06, 0.0013) == pytest.approx(0.0013 * 1e4 * 0.03)


def test_thrust_bearing_loss_is_zero_at_equal_disc_speeds(hub):
    # between the discs: no relative speed at tau_ID ~ 1 without creep
    design, fluid = hub.design, hub.fluid
    _, d0, d2 = parasitic_torques(design, fluid, 200.0, 200.0, 600.0, 1e4)
    assert d0[..., 2] == 0.0 and d2[..., 2] == 0.0
    _, d0, d2 = parasitic_torques(design, fluid, 200.0, 100.0, 600.0, 1e4)
    assert d0[..., 2] == pytest.approx(-d2[..., 2]) and d0[..., 2] > 0


@settings(max_examples=10, deadline=None)
@given(ratio=st.floats(0.5, 2.0), torque=st.floats(2.0, 60.0), rpm=st.floats(50.0, 4000.0))
def test_eq38_equals_eq39_with_parasitic_losses(ratio, torque, rpm):
    v = Variator(*fixed_oil_hub())
    try:
        r = v.solve(ratio, torque, clamp_law="cam", input_speed_rpm=rpm)
    except (TractionLimitError, NoEquilibriumError):
        # honest refusals: beyond capacity, or the cam's preload cannot carry the
        # drive's own drag at this speed (e.g. ratio 2, 2 N m, 2,799 rpm)
        return
    assert r.losses["parasitic"] > 0
    assert r.eta == pytest.approx(r.eta_loss, abs=1e-9)
    ls = r.losses
    assert ls["parasitic"] == pytest.approx(ls["churning"] + ls["seals"] + ls["disc_bearings"]
                                            + ls["hub_bearings"])  # the hub's own (issue 27)
    assert ls["total"] == pytest.approx(ls["creep"] + ls["spin"] + ls["bearing"]
                                        + ls["parasitic"])


def test_parasitic_losses_lower_the_efficiency(hub):
    bare = Variator(hub.design.replace(parasitic=None), hub.fluid)
    a = hub.solve(0.5, 40.0, clamp_force=2000.0, input_speed_rpm=2000)
    b = bare.solve(0.5, 40.0, clamp_force=2000.0, input_speed_rpm=2000)
    assert a.eta < b.eta
    # the input shaft carries the parasitic drag on top of the disc torque
    assert a.input_torque > b.input_torque


def test_sweep_reports_parasitic_kinds(hub):
    ds = hub.sweep(ratio=[0.5, 1.0], output_torque=[20.0], clamp_force=2000.0,
                   input_speed_rpm=2000)
    losses = ds.losses.squeeze()
    for kind in ("churning", "seals", "disc_bearings", "user_terms", "total"):
        assert kind in ds.loss.values
    assert "parasitic" not in ds.loss.values  # a subtotal: in loss_subtotals (issue 25)
    assert np.all(ds.loss_subtotals.sel(subtotal="parasitic") > 0)
    r = hub.solve(0.5, 20.0, clamp_force=2000.0, input_speed_rpm=2000)
    for kind, value in r.losses.items():
        assert float(losses.sel(loss=kind, ratio=0.5)) == pytest.approx(value, rel=1e-9,
                                                                         abs=1e-12)
