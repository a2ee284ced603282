"""Under the thermal law a torque-following clamp's capacity scan, its bisections and its
sweep points start from nearby solutions, kept on the branch from zero torque (session 33):
the same answers as following each point from zero torque."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ballcvt.solvers.capacity as capacity
from ballcvt import Variator
from ballcvt.errors import TractionLimitError
from ballcvt.equilibrium.problem import build_problem
from ballcvt.model.clamping import clamp_law
from ballcvt.solvers.limit import limit_search
from ballcvt.solvers.newton import solve_batch, solve_from
from ballcvt.solvers.options import at_residual_floor

THERMAL = Variator(traction_law="thermal")
OPTIONS = at_residual_floor(THERMAL.options, THERMAL.fluid)
W = 2000.0 * math.pi / 30.0
CAM = {"clamp_law": "cam", "input_speed_rpm": 2000.0}


def test_the_march_decides_every_scan_point_as_followed_from_zero_torque(monkeypatch):
    """Table I's drive at three ratios, two of whose scans end past the fold: every scan
    torque is admissible or not as when it is followed from zero torque, with the same
    creeps where it is."""
    seen = {}
    real = capacity._march

    def spy(points, admissible, shape):
        seen["march"] = real(points, admissible, shape)
        seen["zero"] = admissible(points, None)
        return seen["march"]

    monkeypatch.setattr(capacity, "_march", spy)
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture,
                       np.array([1.0, 1.7, 2.0]), np.zeros(3), 1000.0, W)  # fmt: skip
    law = clamp_law("cam", THERMAL.design, None)
    limit_search(pb, THERMAL.design.creep_limit, OPTIONS, law=law)
    ok, converged, creep = seen["march"]
    zero = seen["zero"]
    assert 0 < ok.sum() < ok.size  # some scan torques past the fold
    np.testing.assert_array_equal(ok, zero.ok)
    np.testing.assert_allclose(creep[ok], zero.creep[ok], rtol=1e-6, atol=1e-12)


def test_a_near_start_is_kept_only_on_the_branch():
    """`solve_from` without the predictor stage: from creeps 5 % off the branch's the
    direct solve is kept; from a start past the fold (the input creep 0.06) Newton lands
    on the other equilibrium, which is refused and followed from zero torque: both the
    branch's, as `solve_batch` from no start."""
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture,
                       np.array([1.0, 1.0]), np.array([100.0, 100.0]), 2000.0, W).flat()
    ref = solve_batch(pb, OPTIONS)
    start = np.array(ref.state.creep) * 1.05
    start[1] = [0.06, 0.0, 0.0, 0.06]
    got = solve_from(pb, OPTIONS, start, predict=False)
    assert ref.converged.all() and got.converged.all()
    np.testing.assert_allclose(got.state.creep, ref.state.creep, rtol=0, atol=1e-8)


@pytest.mark.parametrize("ratio", [1.0, 1.8333333333333333])
def test_a_thermal_cam_sweep_is_solve_up_to_its_capacity(ratio):
    """A sweep's points (started from its capacity scan's creeps) are `solve`'s (followed
    from zero torque), up to 0.999 of the capacity (at ratio 1.83 the capacity is the
    fold of the branch)."""
    limit = THERMAL.limit_torque(ratio, **CAM)
    torque = limit * np.array([0.1, 0.5, 0.9, 0.999])
    ds = THERMAL.sweep(ratio=[ratio], output_torque=torque, progress=False, **CAM)
    swept = np.asarray(ds.eta).ravel()
    solved = [THERMAL.solve(ratio, float(t), **CAM).eta for t in torque]
    np.testing.assert_allclose(swept, solved, rtol=0, atol=1e-7)


def test_the_capacity_is_the_torque_solve_reaches():
    """Table I's single-idler drive at 5000 rpm, ratio 1.56, under the cam: the capacity's
    bisection ends are followed from zero torque, as `solve` does. Started from their
    admissible end (Newton and the fold test) its trials carried the capacity to 10.785
    N m, where `solve` found no equilibrium on the branch above 10.783 and raised a
    ConvergenceError inside the reported capacity (session 33); since session 39 the
    trials are so started and the two final ends confirmed."""
    single = Variator(THERMAL.design, THERMAL.fluid, "single", traction_law="thermal")
    ratio, kw = float(np.linspace(0.6, 1.8, 6)[4]), {"clamp_law": "cam", "input_speed_rpm": 5000.0}
    limit = single.limit_torque(ratio, **kw)
    assert single.solve(ratio, limit * (1 - 2e-5), **kw).converged
    with pytest.raises(TractionLimitError):
        single.solve(ratio, limit * (1 + 1e-4), **kw)


def test_the_bisection_ends_are_those_of_trials_followed_from_zero_torque(monkeypatch):
    """Table I at 2000 rpm, ratios whose capacity is the fold of the branch: the
    bisection by Newton from the admissible end, its ends confirmed from zero torque
    (stepped down by `FOLD_MARGIN` where the continuation stops short of the fold), gives
    the capacity of the bisection whose every trial is followed from zero torque, within
    that margin and the bisection's tolerance, and `solve` reaches it."""
    from ballcvt.solvers.limit import LIMIT_RTOL
    from ballcvt.solvers.peak import FOLD_MARGIN

    ratios = np.array([1.55, 1.8, 2.0])
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture, ratios,
                       np.zeros(ratios.size), 1000.0, W)  # fmt: skip
    law = clamp_law("cam", THERMAL.design, None)
    fast = limit_search(pb, THERMAL.design.creep_limit, OPTIONS, law=law).torque

    def followed(flat, admissible, rows, ends, rtol):
        trial = lambda p, x0: admissible(p, None, False)  # noqa: E731
        return capacity._bisect(flat, trial, rows, ends, rtol)

    monkeypatch.setattr(capacity, "_confirmed_bisection", followed)
    slow = limit_search(pb, THERMAL.design.creep_limit, OPTIONS, law=law).torque
    share = fast / slow - 1.0
    assert np.all(share >= -(FOLD_MARGIN + 2 * LIMIT_RTOL)) and np.all(share <= LIMIT_RTOL)
    for ratio, limit in zip(ratios, fast, strict=True):
        assert THERMAL.solve(float(ratio), float(limit), **CAM).converged
