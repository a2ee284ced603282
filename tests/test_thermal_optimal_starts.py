"""Under the thermal law the optimal clamp's solves start from nearby equilibria, kept on
the branch from zero torque (session 37): the wide start's neighbours from its centres,
and the solve at the optimum from the search's creeps, in a sweep as in `solve`."""

from __future__ import annotations

import numpy as np

import ballcvt.solvers.newton as newton
from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.optimal_batch import WIDTH
from ballcvt.solvers.optimal_stencil import _first_round, _Scorer
from ballcvt.solvers.options import coarse_options
from ballcvt.units import rpm_to_rad_s

THERMAL = Variator(traction_law="thermal")
KW = {"clamp_law": "optimal", "input_speed_rpm": 2000.0}


def _followed(monkeypatch):
    """A list that gains the number of points of every torque continuation from zero."""
    seen: list[int] = []
    real = newton.continue_in_torque

    def spy(sub, *args, **kwargs):
        seen.append(sub.size)
        return real(sub, *args, **kwargs)

    monkeypatch.setattr(newton, "continue_in_torque", spy)
    return seen


def test_the_wide_start_follows_its_centres_alone(monkeypatch):
    """The wide start's round (on the search rule, no predictor stage): each centre is
    followed from zero torque, its neighbours solved from its creeps and, where Newton
    does not keep them, scored -inf rather than followed (they only pick where the climb
    starts). Before session 37 all three forces of every point were followed."""
    ratios, torques = np.array([0.7, 1.2, 1.8]), np.array([20.0, 40.0, 30.0])
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture, ratios, torques,
                       1000.0, rpm_to_rad_s(2000.0)).flat()  # fmt: skip
    score = _Scorer(pb, THERMAL.design.creep_limit, coarse_options(THERMAL.options, search=True))
    index = np.arange(3)
    best = [THERMAL.solve(r, t, **KW).clamp_force for r, t in zip(ratios, torques)]
    u = np.log(best)[:, None] + WIDTH * np.array([-1.0, 0.0, 1.0])  # about each optimum
    seen = _followed(monkeypatch)
    e, x = _first_round(score, index, u, guess=True)
    assert sum(seen) <= index.size  # the centres alone
    e = e.reshape(-1, 3)
    assert np.isfinite(e[:, 1]).all()  # every centre admissible here
    for j in np.flatnonzero(np.isfinite(e[:, 2])):  # a kept neighbour is the followed one
        followed, _ = score(np.array([j]), u[j, 2:3])
        assert abs(followed[0] - e[j, 2]) < 1e-7  # (both to the search rule's tolerance)


def test_the_solve_at_the_optimum_starts_from_the_search(monkeypatch):
    """A thermal sweep under the optimal clamp solves its points from the creeps its search
    found at each optimum (Newton, kept unless past a fold), with no point followed from
    zero torque after the search; `solve` does the same and gives the same efficiency to
    round-off, and a solve followed from zero torque at that force agrees to the solver's
    tolerance."""
    ratio, torque = np.array([0.8, 1.5]), np.array([20.0, 45.0])
    import ballcvt.analysis.sweeps.curves as curves

    real = curves.optimal_start
    at_search: list[int] = []

    def spy(*args, **kwargs):
        got = real(*args, **kwargs)
        at_search.append(len(seen))  # the continuations made up to the search's end
        return got

    seen = _followed(monkeypatch)
    monkeypatch.setattr(curves, "optimal_start", spy)
    ds = THERMAL.sweep(ratio=ratio, output_torque=torque, progress=False, **KW)
    monkeypatch.setattr(curves, "optimal_start", real)
    assert at_search and at_search[-1] == len(seen)  # none after it
    eta = np.asarray(ds.eta)[0, 0]
    force = np.asarray(ds.clamp_force)[0, 0]
    assert np.isfinite(eta).all()
    for i, r in enumerate(ratio):
        for k, t in enumerate(torque):
            got = THERMAL.solve(float(r), float(t), **KW)
            assert abs(got.eta - eta[i, k]) < 1e-12
            assert got.clamp_force == force[i, k]
            followed = THERMAL.solve(float(r), float(t), clamp_force=float(force[i, k]),
                                     input_speed_rpm=2000.0)  # fmt: skip
            assert abs(followed.eta - eta[i, k]) < 1e-8

