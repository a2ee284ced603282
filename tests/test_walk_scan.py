"""The walk's equilibria as a sweep's warm starts (session 36): under the thermal law at a
constant force the limit search hands on the equilibria its walk met below each limit
(`LimitSearch.scan_torque`, `scan_creep`), and a sweep's points start between them without
the predictor stage, where they started between the creeps at zero torque and at the
limit with it."""

from __future__ import annotations

import math

import numpy as np

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.limit import limit_search

THERMAL = Variator(traction_law="thermal")
RATIOS = np.array([0.6, 1.0, 1.4, 1.9])
OP = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}


def _search():
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture, RATIOS,
                       np.zeros(RATIOS.size), 2000.0, 2000.0 * math.pi / 30)  # fmt: skip
    return limit_search(pb, THERMAL.design.creep_limit, THERMAL.options)


def test_the_scan_is_the_branch_below_the_limit():
    """Each row: zero torque first, torques increasing up to the limit, its last (``+inf``
    after), the disc creeps growing with them up to the limit's (none past the fold: a
    walk's step can land there and still rise, Table I at ratios 1.90-2.0)."""
    s = _search()
    assert s.scan_torque is not None
    for t, x, lim, x_lim in zip(s.scan_torque, s.scan_creep, s.torque, s.creep, strict=True):
        got = np.isfinite(t)
        assert got.sum() >= 3 and t[0] == 0.0 and t[got][-1] == lim
        assert np.all(np.diff(t[got]) > 0) and np.all(np.isnan(x[~got]))
        disc = np.abs(x[got][:, [0, -1]])
        assert np.all(np.diff(disc, axis=0) > 0)
        np.testing.assert_array_equal(x[got][-1], x_lim)


def test_starts_between_the_walks_equilibria_lie_near_the_solutions():
    """At 20 %, 50 %, 80 % and 95 % of each limit the start's disc creeps lie within 25 %
    of `solve`'s and mostly within 5 % (measured: at most 19 %, at ratio 1.4 where the
    walk's points are 28 N m apart, median 0.7 %); the line from zero torque to the limit,
    the start before, was off by up to 78 %."""
    s = _search()
    errors = []
    for j, ratio in enumerate(RATIOS):
        torques = s.torque[j] * np.array([0.2, 0.5, 0.8, 0.95])
        starts = s.start_between(np.full(4, j), torques)
        for t, x0 in zip(torques, starts, strict=True):
            c = THERMAL.solve(float(ratio), float(t), **OP).contacts
            sol = np.array([c["input"].creep, c["output"].creep])
            errors.append(np.abs(x0[[0, -1]] / sol - 1.0))
    errors = np.array(errors)
    assert errors.max() < 0.25 and np.median(errors) < 0.05, errors
