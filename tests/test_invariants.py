"""Invariants over random designs and operating points (hypothesis), and convergence."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ballcvt import Variator, load_builtin
from ballcvt.params.feasibility import max_rollers

BASE_DESIGN, BASE_FLUID = load_builtin()


@st.composite
def cases(draw):
    k, rs = draw(st.floats(1.0, 2.5)), draw(st.floats(0.015, 0.05))
    n_max = min(12, max_rollers(k, rs, BASE_DESIGN.min_roller_gap))     # feasible designs only
    design = BASE_DESIGN.replace(
        aspect_ratio=k,
        roller_radius=rs,
        theta0_deg=(th := draw(st.floats(30.0, 60.0))),
        theta2_deg=th + draw(st.floats(-5.0, 5.0)),
        alpha_deg=draw(st.floats(5.0, 20.0)),
        n_rollers=draw(st.integers(min(4, n_max), n_max)),
        disc_groove_ratio=draw(st.floats(1.5, 6.0)),
        idler_groove_ratio=draw(st.floats(1.5, 6.0)),
    )
    arch = draw(st.sampled_from(["double", "single"]))
    v = Variator(design, BASE_FLUID, arch)
    lo, hi = v.ratio_range
    ratio = draw(st.floats(max(lo, 0.5), min(hi, 2.0)))
    clamp = draw(st.floats(500.0, 4000.0))
    rpm = draw(st.floats(300.0, 6000.0))
    frac = draw(st.floats(0.02, 0.9))
    return v, ratio, clamp, rpm, frac


@given(cases())
def test_power_balance_and_signs(case):
    v, ratio, clamp, rpm, frac = case
    limit = v.limit_torque(ratio=ratio, clamp_force=clamp, input_speed_rpm=rpm)
    r = v.solve(ratio=ratio, output_torque=frac * limit, clamp_force=clamp, input_speed_rpm=rpm)
    assert r.converged and r.residual_norm <= v.options.tol
    # Eq. 38 = Eq. 39 exactly at the exact equilibrium. At a residual eps (torques over
    # F_N0 r_S) the power balance is off by at most n F_N0 r_S eps (|omega_S| + sum |Omega|);
    # the factor 2 is a margin for round-off in the loss sums.
    speeds = abs(r.roller_speed) + sum(abs(c.body_speed) for c in r.contacts.values())
    slack = v.design.n_rollers * clamp * v.design.roller_radius * r.residual_norm * speeds
    assert r.eta == pytest.approx(r.eta_loss, abs=1e-12 + 2.0 * slack / r.input_power)
    assert 0.0 < r.eta < 1.0
    for c in r.contacts.values():
        assert c.creep_loss >= 0.0 and c.spin_loss >= 0.0
        assert c.creep * c.mu >= 0.0                              # creep and traction agree
        assert c.spin * c.chi >= 0.0                              # spin moment opposes spin
    assert min(r.losses.values()) >= 0.0
    assert r.losses["total"] == pytest.approx(r.input_power - r.output_power, rel=1e-8)


@pytest.mark.parametrize("arch", ["double", "single"])
def test_grid_converges(arch):
    """Every point of a 20 x 20 grid, ratio 0.5-2, T_2 5 N m to 90 % of the limit."""
    v = Variator(architecture=arch)
    op = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}
    for ratio in np.linspace(0.5, 2.0, 20):
        limit = v.limit_torque(ratio=ratio, **op)
        for torque in np.linspace(5.0, 0.9 * limit, 20):
            r = v.solve(ratio=ratio, output_torque=torque, **op)
            assert r.converged and r.residual_norm <= v.options.tol, (ratio, torque)
            assert np.isfinite(r.eta) and 0 < r.eta < 1


def test_zero_torque_gives_zero_efficiency(double):
    r = double.solve(ratio=1.3, output_torque=0.0, clamp_force=2000.0, input_speed_rpm=2000)
    assert r.eta == 0.0
    assert r.eta_loss == pytest.approx(0.0, abs=1e-9)
    assert r.input_torque > 0.0


def test_limit_torque_grows_with_clamp(double):
    op = {"ratio": 1.0, "input_speed_rpm": 2000.0}
    limits = [double.limit_torque(clamp_force=f, **op) for f in (1000.0, 2000.0, 3000.0)]
    assert limits[0] < limits[1] < limits[2]
