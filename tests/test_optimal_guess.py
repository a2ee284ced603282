"""The optimal clamp's first guess (`GUESS_FIT`, session 25): where the batched search
starts, never what it certifies."""

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.optimal_batch import GUESS_TORQUES, WIDTH, _guess, optimal_forces


def _problem(drive, ratio, torque, rpm):
    v = Variator(*load_builtin(drive))
    ratio, torque = np.broadcast_arrays(np.asarray(ratio, float), np.asarray(torque, float))
    return build_problem(v.design, v.fluid, v.architecture, ratio, torque, 1000.0,
                         rpm * np.pi / 30.0)


def test_finite_and_inside_the_bounds_far_outside_the_fit():
    torque = np.array([1e-6, 0.5, 1.0, 5.0, 200.0, 1e3, 1e5])
    pb = _problem("table1", 1.0, torque, 2000.0)
    lo, hi = np.full(torque.size, np.log(10.0)), np.full(torque.size, np.log(1e6))
    u = _guess(pb, lo, hi)
    assert np.all(np.isfinite(u))
    assert np.all((u >= lo + WIDTH - 1e-12) & (u <= hi - WIDTH + 1e-12))
    assert np.all(np.diff(u[2:]) > 0)  # from the fit's range up, it grows with the torque


def test_continuous_at_the_ends_of_the_fitted_torques():
    lo, hi = np.full(2, np.log(10.0)), np.full(2, np.log(1e6))
    for t in GUESS_TORQUES:
        pb = _problem("hub", 1.2, np.array([t * (1 - 1e-9), t * (1 + 1e-9)]), 300.0)
        u = _guess(pb, lo, hi)
        assert u[1] - u[0] == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("drive", ["table1", "hub"])
def test_near_the_optimum_on_a_duty_cycles_points(drive):
    """180 rpm, 5-20 N m (the example commute's steps): the guess that replaced
    ``F = 200 + 14 T`` was 0.31 below the optimum there (session 25)."""
    torque = np.array([5.0, 7.0, 12.0, 18.0])
    pb = _problem(drive, 1.05, torque, 180.0)
    got = optimal_forces(pb)
    assert got.fast.all()
    lo, hi = np.full(torque.size, np.log(1.0)), np.full(torque.size, np.log(1e6))
    err = np.abs(_guess(pb, lo, hi) - np.log(got.force))
    old = np.abs(np.log(200.0 + 14.0 * torque * 1.05) - np.log(got.force))
    assert np.all(err < 0.15) and np.all(err < old)
