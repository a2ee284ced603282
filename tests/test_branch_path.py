"""The walk along the branch from zero torque (`ballcvt.solvers.branch_path`) on Table I's
drive under the thermal law: where it stops, and the limits it leads to against the
torque continuation it replaced."""

import math

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers import branch_path, peak
from ballcvt.solvers.branch_path import CORRECTOR_SHARE, Walk, follow_branch
from ballcvt.solvers.newton import PATIENCE, branch_pinned, branch_solver
from ballcvt.solvers.options import SolverOptions, at_residual_floor
from ballcvt.solvers.peak import FOLD_MARGIN, peak_limits

THERMAL = Variator(traction_law="thermal")
OPTIONS = at_residual_floor(SolverOptions(), THERMAL.fluid)
RATIOS = np.array([0.5, 0.8, 1.0, 1.4, 2.0])


def _problem(speed_rpm=2000.0, force=2000.0):
    return build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture, RATIOS,
                         np.zeros(RATIOS.size), force, speed_rpm * math.pi / 30).flat()  # fmt: skip


def _walk(pb):
    pin = THERMAL.design.creep_limit * (1.0 - 1e-7)
    ok, x0, _ = branch_solver(OPTIONS)(pb, None, True)
    t0 = np.where(ok, 0.0, np.nan)
    walk = follow_branch(pb, branch_pinned(OPTIONS, PATIENCE), OPTIONS.quadrature, (pin, pin),
                         (t0, np.asarray(x0)))  # fmt: skip
    return walk, pin


def test_the_walk_stops_just_past_the_fold_on_the_rising_branch():
    """Every walk stops at a step whose torque fell, with its last two points rising and
    admissible: the fold (the limit over `FOLD_MARGIN`) lies beyond the point before the
    last, and the last point is not above it (to the solver's noise)."""
    pb = _problem()
    walk, pin = _walk(pb)
    fold = peak_limits(pb, THERMAL.design.creep_limit, OPTIONS)[0] / (1.0 - FOLD_MARGIN)
    assert walk.stopped.all()
    assert np.all(walk.after[0] < walk.torque)
    assert np.all(walk.before[0] < walk.torque) and np.all(walk.before[0] < fold)
    assert np.all(walk.torque <= fold * (1.0 + 1e-9))
    assert np.all(np.abs(walk.creep) <= pin) and np.all(np.abs(walk.before[1]) <= pin)


@pytest.mark.parametrize("speed_rpm, force", [(2000.0, 2000.0), (5000.0, 800.0), (500.0, 5000.0)])
def test_limits_from_the_walk_are_those_from_the_torque_continuation(monkeypatch, speed_rpm,
                                                                     force):  # fmt: skip
    """The limits with the walk against those with the torque continuation (the walk made
    to stop nowhere, as where its solves fail), each the climb's fold less the margin:
    the same to 1e-6, or the walk's higher, at the scanned fold, where the climb from the
    continuation stopped short of it (measured: within 8e-7 over Table I's sweeps at 2000
    and 5000 rpm, 800 to 5000 N, but 1.6e-5 higher at 5000 rpm and 800 N, ratio 0.5, and
    1.2e-4 at 500 rpm and 5 kN, ratios 0.5 and 0.8: tests/test_fold_climb.py)."""
    pb = _problem(speed_rpm, force)
    walked, _ = peak_limits(pb, THERMAL.design.creep_limit, OPTIONS)

    def nowhere(flat, *args):
        got = follow_branch(flat, *args)
        none = np.zeros(flat.size, dtype=bool)
        return Walk(got.torque, got.creep, got.before, got.after, got.direction, none, none)

    monkeypatch.setattr(peak, "follow_branch", nowhere)
    followed, _ = peak_limits(pb, THERMAL.design.creep_limit, OPTIONS)
    assert np.all(walked >= followed * (1.0 - 1e-6))
    assert np.all(walked <= followed * (1.0 + FOLD_MARGIN))
    assert np.sum(np.abs(walked / followed - 1.0) <= 1e-6) >= RATIOS.size - 2


def test_a_corrector_far_from_its_prediction_is_refused():
    """`_close`: a corrected point more than `CORRECTOR_SHARE` of the step from its
    prediction, or turned more than `BEND` from the predictor, is refused (another branch
    of the held creep's equations, found on Table I at ratio 1.0 from a long step)."""
    x = np.array([[0.01, 0.0, 0.0, 0.01]])
    d = np.array([[1.0, 0.0, 0.0, 1.0]]) / math.sqrt(2.0)
    step = np.array([0.01])
    near = x + step[:, None] * d + 0.1 * CORRECTOR_SHARE * 0.01
    far = x + step[:, None] * d + np.array([[0.0, 0.0, 0.0, 0.8 * CORRECTOR_SHARE * 0.01]]) * 2
    turned = x + 0.01 * np.array([[1.0, 0.0, 0.0, -0.2]])
    assert branch_path._close(near, x, d, step).all()
    assert not branch_path._close(far, x, d, step).any()
    assert not branch_path._close(turned, x, d, step).any()
