"""Issue 23: the parasitic drags' directions follow the solved speeds (docs/model.md §12).

The disc thrust bearing opposes the discs' solved relative speed as Coulomb friction
regularised by tanh (Andersson, Soderberg and Bjorklund, Tribology International 40 (2007)
580-587): through the creep band just above tau_ID = 1, the stick band included, its loss
is >= 0, Eq. 38 = Eq. 39 holds, and the Newton Jacobian carries the tanh slope.
"""

from dataclasses import replace

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium.problem import build_problem
from ballcvt.equilibrium.residual import balancing_output_torque, evaluate, evaluate_with_jacobian
from ballcvt.model.losses import STICK_SPEED, coulomb_direction, drag_magnitudes, drag_power, shaft_drags
from ballcvt.solvers.newton import solve_batch
from drives import fixed_oil_hub

HUB = fixed_oil_hub()
W0 = 2000.0 * np.pi / 30.0
#: At 20 N m, 2000 N, 2000 rpm the discs' solved relative speed crosses zero (the bearing
#: sticks) between tau_ID 1.00555 and 1.00575; the sign flips of issue 23 lie below.
STICK_RATIO = 1.00565


def test_coulomb_direction():
    x = np.array([-1.0, -19.5, -1e-3, 0.0, 1e-9, 1e-3, 0.3, 19.5, 1e3]) * STICK_SPEED
    d = coulomb_direction(x)
    assert np.all(d * x >= 0.0) and np.all(np.abs(d) <= 1.0)
    assert np.array_equal(d, -coulomb_direction(-x))
    assert coulomb_direction(0.0) == 0.0
    assert coulomb_direction(19.5 * STICK_SPEED) == 1.0  # Coulomb's sign beyond the band


def test_drag_power_is_exactly_non_negative_at_nearly_equal_speeds():
    design, fluid = HUB
    w2 = W0 * (1.0 + np.linspace(-1e-9, 1e-9, 2001))
    mag = drag_magnitudes(design, fluid, W0, w2, 600.0, 1e4)
    power = drag_power(mag, W0, w2)
    assert np.all(power >= 0.0)
    # the torques times the speeds give the same power to round-off
    m0, m2 = shaft_drags(mag, W0, w2)
    assert np.allclose(m0 * W0 + m2 * w2[:, None], power, rtol=0.0, atol=1e-9)


@pytest.mark.parametrize("ratio", [1.001, 1.003, 1.0055, STICK_RATIO, 1.0058, 1.02])
def test_eq38_equals_eq39_through_the_creep_band(ratio):
    r = Variator(*HUB).solve(ratio, 20.0, clamp_force=2000.0, input_speed_rpm=2000)
    assert r.losses["disc_bearings"] >= 0.0
    assert r.eta == pytest.approx(r.eta_loss, abs=1e-9)


def _solved(ratio):
    design, fluid = HUB
    pb = build_problem(design, fluid, "double", ratio, 20.0, 2000.0, W0)
    sol = solve_batch(pb)
    assert bool(np.all(sol.converged))
    return pb, sol.state


def test_the_bearing_sticks_and_its_torque_balances():
    """In the stick band the relative speed is within a few omega_s and the bearing carries
    less than its Coulomb torque; the output balance uses the drag at the solved speeds."""
    pb, state = _solved(STICK_RATIO)
    dw = state.omega[..., 0] - state.omega[..., -1]
    assert abs(float(dw)) < 3.0 * STICK_SPEED
    coulomb = float(pb.disc_drag[..., 2])
    m0, m2 = shaft_drags(drag_magnitudes(*HUB, 0.0, 0.0, 0.0, 0.0), 0.0, 0.0)
    assert not m0.any() and not m2.any()
    shaft_only = float(np.sum(pb.output_drag))
    carried = shaft_only - float(state.output_drag)  # the bearing's share, |.| < Coulomb's
    assert 0.0 < abs(carried) < coulomb
    assert float(balancing_output_torque(pb, state)) == pytest.approx(20.0, abs=1e-8)


def test_jacobian_carries_the_bearing_slope_in_the_stick_band():
    pb, state = _solved(STICK_RATIO)
    x = state.creep
    _, jac = evaluate_with_jacobian(pb, x)
    nc = x.shape[-1]
    fd = np.empty_like(jac)
    for j in range(nc):
        h = np.zeros(nc)
        h[j] = 1e-9
        fd[:, j] = (evaluate(pb, x + h).residual - evaluate(pb, x - h).residual) / 2e-9
    # the node motion with the pole is not differentiated: a Newton Jacobian, ~1 % off
    tol = 0.02 * np.max(np.abs(fd))
    assert np.allclose(jac, fd, rtol=0.02, atol=tol)
    # and the bearing's slope is there: without it the Jacobian differs beyond that
    _, bare = evaluate_with_jacobian(replace(pb, disc_drag=np.zeros_like(pb.disc_drag)), x)
    assert np.max(np.abs(bare - jac)) > 10.0 * tol
